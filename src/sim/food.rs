//! Food (§4.3) and aversive objects (§4.4) as a running world holds them: substance amounts,
//! bites, depletion and regeneration, and the bookkeeping that lets tests check that every
//! unit of substance a creature receives was taken from a food object.

use crate::geometry::Vec2;
use crate::sim::smell::Smell;
use crate::sim::spec::{
    AversiveKind, FoodKind, DEFAULT_AVERSIVE_COLOUR, DEFAULT_FOOD_COLOUR, DEFAULT_OBJECT_HEIGHT,
};
use serde::{Deserialize, Serialize};

/// One food object.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Food {
    /// Index of its kind in [`crate::sim::world::World::kinds`].
    pub kind: usize,
    /// Centre in LU.
    pub position: Vec2,
    /// Radius in LU (0 = a point).
    pub radius: f64,
    /// Substance ⟨A, B, C, D⟩ it holds now.
    pub amount: [f64; 4],
    /// Most substance it can hold (regeneration stops there).
    pub capacity: [f64; 4],
    /// Substance moved to a creature per eating tick (at most what is left).
    pub bite: [f64; 4],
    /// Substance added per tick, up to `capacity`.
    pub regen: [f64; 4],
    /// Eating removes substance from the object.
    pub depletes: bool,
    /// The smell intensity scales with total amount / total capacity.
    pub smell_follows_amount: bool,
    /// What it gives off at full strength.
    pub smell: Smell,
    /// Substance given to creatures over the trial (with `depletes` off the amount stays
    /// unchanged but this still counts what was given).
    pub given: [f64; 4],
    /// Substance added by regeneration over the trial.
    pub regenerated: [f64; 4],
    /// Colour `[r, g, b]` the eye sees.
    pub colour: [f64; 3],
    /// Height in LU of the cylinder the eye sees.
    pub height: f64,
}

impl Food {
    /// A new, full food object of kind `spec` (index `kind`) at `position`.
    pub fn new(kind: usize, spec: &FoodKind, position: Vec2) -> Food {
        Food {
            kind,
            position,
            radius: spec.radius,
            amount: spec.substance,
            capacity: spec.capacity(),
            bite: spec.bite,
            regen: spec.regen,
            depletes: spec.depletes,
            smell_follows_amount: spec.smell_follows_amount,
            smell: Smell::new(&spec.odour, spec.intensity, spec.range),
            given: [0.0; 4],
            regenerated: [0.0; 4],
            colour: spec.colour.unwrap_or(DEFAULT_FOOD_COLOUR),
            height: spec.height.unwrap_or(DEFAULT_OBJECT_HEIGHT),
        }
    }

    /// Regeneration (§4.3): add r per type, never beyond capacity.
    #[inline]
    pub fn regenerate(&mut self) {
        for t in 0..4 {
            if self.regen[t] > 0.0 && self.amount[t] < self.capacity[t] {
                let next = (self.amount[t] + self.regen[t]).min(self.capacity[t]);
                self.regenerated[t] += next - self.amount[t];
                self.amount[t] = next;
            }
        }
    }

    /// Would [`Food::regenerate`] change it now? Only when some substance with r > 0 is
    /// below capacity; otherwise regeneration leaves every field as it is.
    #[inline]
    pub fn regrows_now(&self) -> bool {
        (0..4).any(|t| self.regen[t] > 0.0 && self.amount[t] < self.capacity[t])
    }

    /// One bite (§4.3, SPEC-NOTES): min(bite, what is left) per type, taken from the object
    /// when it depletes. Returns what the creature receives.
    #[inline]
    pub fn take_bite(&mut self) -> [f64; 4] {
        let mut got = [0.0; 4];
        for (t, g) in got.iter_mut().enumerate() {
            let x = self.bite[t].min(self.amount[t]);
            if x > 0.0 {
                *g = x;
                self.given[t] += x;
                if self.depletes {
                    self.amount[t] -= x;
                }
            }
        }
        got
    }

    /// Does it hold any substance of type `t` (0 = A)? What the food detector of §5.2 asks.
    #[inline]
    pub fn holds(&self, t: usize) -> bool {
        self.amount[t] > 0.0
    }

    /// The factor on the smell intensity: amount / capacity (totals over the four types)
    /// when the smell follows the amount, else 1. Validation guarantees a positive capacity
    /// total whenever the smell follows the amount.
    #[inline]
    pub fn smell_scale(&self) -> f64 {
        if self.smell_follows_amount {
            let capacity: f64 = self.capacity.iter().sum();
            if capacity > 0.0 {
                self.amount.iter().sum::<f64>() / capacity
            } else {
                0.0
            }
        } else {
            1.0
        }
    }
}

/// One aversive object: shocks a creature whose body touches it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Aversive {
    /// Index of its kind in [`crate::sim::world::World::kinds`].
    pub kind: usize,
    /// Centre in LU.
    pub position: Vec2,
    /// Radius in LU (0 = a point).
    pub radius: f64,
    /// What it gives off.
    pub smell: Smell,
    /// Colour `[r, g, b]` the eye sees.
    pub colour: [f64; 3],
    /// Height in LU of the cylinder the eye sees.
    pub height: f64,
}

impl Aversive {
    /// A new aversive object of kind `spec` (index `kind`) at `position`.
    pub fn new(kind: usize, spec: &AversiveKind, position: Vec2) -> Aversive {
        Aversive {
            kind,
            position,
            radius: spec.radius,
            smell: Smell::new(&spec.odour, spec.intensity, spec.range),
            colour: spec.colour.unwrap_or(DEFAULT_AVERSIVE_COLOUR),
            height: spec.height.unwrap_or(DEFAULT_OBJECT_HEIGHT),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn apple(depletes: bool) -> Food {
        let spec = FoodKind {
            substance: [3.0, 0.5, 0.0, 0.0],
            capacity: Some([4.0, 0.5, 0.0, 0.0]),
            bite: [2.0, 1.0, 1.0, 0.0],
            regen: [0.75, 0.0, 0.0, 0.0],
            depletes,
            ..FoodKind::default()
        };
        Food::new(0, &spec, Vec2::ZERO)
    }

    #[test]
    fn bite_takes_at_most_what_is_left() {
        let mut f = apple(true);
        assert_eq!(f.take_bite(), [2.0, 0.5, 0.0, 0.0]);
        assert_eq!(f.amount, [1.0, 0.0, 0.0, 0.0]);
        assert_eq!(f.take_bite(), [1.0, 0.0, 0.0, 0.0]);
        assert_eq!(f.take_bite(), [0.0; 4]);
        assert_eq!(f.given, [3.0, 0.5, 0.0, 0.0]);
        assert!(!f.holds(0));
    }

    #[test]
    fn without_depletion_the_amount_stays() {
        let mut f = apple(false);
        for _ in 0..5 {
            assert_eq!(f.take_bite(), [2.0, 0.5, 0.0, 0.0]);
        }
        assert_eq!(f.amount, [3.0, 0.5, 0.0, 0.0]);
        assert_eq!(f.given, [10.0, 2.5, 0.0, 0.0]);
    }

    #[test]
    fn regeneration_stops_at_capacity() {
        let mut f = apple(true);
        f.regenerate(); // 3.75
        f.regenerate(); // 4.5 -> capped at 4
        assert_eq!(f.amount[0], 4.0);
        assert_eq!(f.regenerated[0], 1.0);
        f.regenerate();
        assert_eq!(f.amount[0], 4.0);
    }
}
