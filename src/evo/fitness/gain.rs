//! The pure pieces of a life's score: the metabolic gain `B(m)` with its balance options, and
//! the goal-shaping term with the distances it is measured by. No world, no state.

use crate::experiment::Balance;
use crate::geometry::Vec2;
use crate::sim::area::Area;

pub use crate::sim::metabolism::weighted;

/// The metabolic gain `B(m)` of one metabolic vector (see
/// [`crate::experiment::FitnessSpec`]): `Σ wᵢ·mᵢ` or `min wᵢ·mᵢ` over the components with
/// wᵢ ≠ 0, minus `imbalance_penalty × (max − min)` of those components. With `Balance::Sum`
/// and no penalty this is [`weighted`], bit for bit.
pub fn balanced_gain(weights: &[f64; 4], m: &[f64; 4], balance: Balance, penalty: f64) -> f64 {
    let base = match balance {
        Balance::Sum => weighted(weights, m),
        Balance::Min => weighted_extremes(weights, m).map_or(0.0, |(lo, _)| lo),
    };
    if penalty == 0.0 {
        return base;
    }
    let spread = weighted_extremes(weights, m).map_or(0.0, |(lo, hi)| hi - lo);
    base - penalty * spread
}

/// The smallest and largest `wᵢ·mᵢ` over the components with wᵢ ≠ 0 (None when every
/// weight is 0).
fn weighted_extremes(weights: &[f64; 4], m: &[f64; 4]) -> Option<(f64, f64)> {
    let mut extremes: Option<(f64, f64)> = None;
    for (w, x) in weights.iter().zip(m) {
        if *w != 0.0 {
            let v = w * x;
            extremes = Some(extremes.map_or((v, v), |(lo, hi)| (lo.min(v), hi.max(v))));
        }
    }
    extremes
}

/// The goal-shaping term: `bonus × max(0, 1 − distance / range)`.
pub fn goal_term(bonus: f64, distance: f64, range: f64) -> f64 {
    bonus * goal_nearness(distance, range)
}

/// What the goal term counts: `max(0, 1 − distance / range)`.
pub fn goal_nearness(distance: f64, range: f64) -> f64 {
    (1.0 - distance / range).max(0.0)
}

/// The distance from `p` to the nearest point of `area` (0 inside or on its border).
pub fn distance_to_area(area: &Area, p: Vec2) -> f64 {
    let dx = (area.lo.x - p.x).max(0.0).max(p.x - area.hi.x);
    let dy = (area.lo.y - p.y).max(0.0).max(p.y - area.hi.y);
    (dx * dx + dy * dy).sqrt()
}

/// What `[fitness] goal` points at.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Goal {
    /// A named area: the distance is to its nearest point.
    Area(Area),
    /// A point.
    Point(Vec2),
}

impl Goal {
    /// The distance from `p` to the goal.
    pub fn distance(&self, p: Vec2) -> f64 {
        match self {
            Goal::Area(a) => distance_to_area(a, p),
            Goal::Point(g) => g.distance(p),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn balance_min_scores_the_scarcest_weighted_component() {
        // Weighted components 2*1, 1*5, (weight 0 ignored), 0.5*8 = 2, 5, -, 4: min 2.
        let w = [2.0, 1.0, 0.0, 0.5];
        let m = [1.0, 5.0, -7.0, 8.0];
        assert_eq!(balanced_gain(&w, &m, Balance::Min, 0.0), 2.0);
        // Sum with an imbalance penalty 0.25: 11 - 0.25 * (5 - 2) = 10.25.
        assert_eq!(balanced_gain(&w, &m, Balance::Sum, 0.25), 10.25);
        // Min with the penalty: 2 - 0.5 * 3 = 0.5.
        assert_eq!(balanced_gain(&w, &m, Balance::Min, 0.5), 0.5);
        // No weight: nothing to take the minimum of.
        assert_eq!(balanced_gain(&[0.0; 4], &m, Balance::Min, 1.0), 0.0);
        // Sum without a penalty is the plain dot product.
        assert_eq!(balanced_gain(&w, &m, Balance::Sum, 0.0), weighted(&w, &m));
    }

    #[test]
    fn goal_term_falls_linearly_to_zero_at_the_range() {
        assert_eq!(goal_term(10.0, 0.0, 100.0), 10.0);
        assert_eq!(goal_term(10.0, 25.0, 100.0), 7.5);
        assert_eq!(goal_term(10.0, 100.0, 100.0), 0.0);
        assert_eq!(goal_term(10.0, 250.0, 100.0), 0.0);
    }

    #[test]
    fn distance_to_an_area_is_to_its_nearest_point() {
        let a = Area {
            lo: Vec2::new(10.0, 20.0),
            hi: Vec2::new(30.0, 40.0),
            kind: crate::sim::spec::AreaKind::Plain,
            smell: crate::sim::smell::Smell::new(&[0.0; 8], 0.0, None),
        };
        assert_eq!(distance_to_area(&a, Vec2::new(20.0, 30.0)), 0.0);
        assert_eq!(distance_to_area(&a, Vec2::new(30.0, 40.0)), 0.0);
        assert_eq!(distance_to_area(&a, Vec2::new(0.0, 30.0)), 10.0);
        assert_eq!(distance_to_area(&a, Vec2::new(33.0, 44.0)), 5.0);
        assert_eq!(Goal::Point(Vec2::new(3.0, 4.0)).distance(Vec2::ZERO), 5.0);
    }
}
