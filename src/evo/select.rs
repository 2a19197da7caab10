//! Selection: the ranking of an evaluated generation (for elitism) and the three ways of
//! picking a parent from it (tournament, truncation, linear rank), each drawing from the
//! variation stream in a fixed, documented order.
//!
//! # Comparing fitness
//!
//! Higher fitness is better. Every comparison uses one total order: by fitness, then by
//! index, the lower index winning ties, so the result never depends on a sort algorithm's
//! stability or on anything but the values. `-0.0` and `+0.0` are equal. Fitness is meant to
//! be finite; a NaN still gets a deterministic place, tied with −∞ (the worst).
//!
//! # Draws per pick
//!
//! - tournament of size k (taken as at most n): k distinct entrants by Floyd's sampling,
//!   one `below(j + 1)` for each j in n − k .. n, in increasing j (an already drawn index
//!   is replaced by j). The best entrant wins.
//! - truncation: one `below(m)` with m = ⌈fraction · n⌉ (at least 1); the pick is the
//!   individual of that position in the ranking (0 = best).
//! - rank: one `unit()`, scaled by the total weight and located in the cumulative weights of
//!   ranks 0 (worst) .. n − 1 (best), summed serially.

use crate::experiment::evolution::SelectionSpec;
use crate::seed::{below, unit, Rng};
use std::cmp::Ordering;

/// The value a fitness is compared by: NaN ranks with −∞ and −0.0 equals +0.0.
fn key(fitness: f64) -> f64 {
    if fitness.is_nan() {
        f64::NEG_INFINITY
    } else {
        // Adding +0.0 turns -0.0 into +0.0, so `total_cmp` sees them as equal.
        fitness + 0.0
    }
}

/// Compares individuals `a` and `b`: `Less` when `a` ranks before (is better than) `b`.
fn rank_order(keys: &[f64], a: usize, b: usize) -> Ordering {
    keys[b].total_cmp(&keys[a]).then(a.cmp(&b))
}

/// The indices of `fitness`, best first; equal fitness keeps the lower index first.
pub fn ranking(fitness: &[f64]) -> Vec<usize> {
    let keys: Vec<f64> = fitness.iter().map(|&f| key(f)).collect();
    ranking_of_keys(&keys)
}

fn ranking_of_keys(keys: &[f64]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..keys.len()).collect();
    order.sort_unstable_by(|&a, &b| rank_order(keys, a, b));
    order
}

/// How many of `n` individuals truncation selection with `fraction` may pick from:
/// ⌈fraction · n⌉, at least 1 and at most n. A product within 10^-9 (relative) of an integer
/// counts as that integer, so 0.07 × 100 gives 7 even though it is 7.000000000000001 in
/// floating point.
pub fn truncation_count(fraction: f64, n: usize) -> usize {
    let x = fraction * n as f64;
    let nearest = x.round();
    let m = if (x - nearest).abs() <= 1e-9 * x.abs().max(1.0) {
        nearest
    } else {
        x.ceil()
    };
    // `as` saturates, and NaN becomes 0: both end inside 1..=n after the clamp.
    (m as usize).clamp(1, n.max(1))
}

/// The probability that linear rank selection with pressure `pressure` picks the
/// individual of rank `rank` (0 = worst) among `n` (Baker's formula).
pub fn rank_probability(pressure: f64, rank: usize, n: usize) -> f64 {
    rank_weight(pressure, rank, n) / n as f64
}

/// Baker's linear ranking weight: (2 − s) + 2(s − 1) · rank / (n − 1); the weights of
/// all ranks sum to n. A population of one has weight 1.
fn rank_weight(pressure: f64, rank: usize, n: usize) -> f64 {
    if n <= 1 {
        return 1.0;
    }
    (2.0 - pressure) + 2.0 * (pressure - 1.0) * rank as f64 / (n - 1) as f64
}

/// Picks parents from one evaluated generation. Built once per generation; every pick
/// draws from the given stream as the module documentation says.
#[derive(Debug, Clone)]
pub struct Selector {
    spec: SelectionSpec,
    keys: Vec<f64>,
    /// Individuals best first.
    order: Vec<usize>,
    /// Rank selection: cumulative weights of ranks 0 (worst) ..= r.
    cumulative: Vec<f64>,
    /// Tournament: who has entered the current tournament (cleared after each).
    entered: Vec<bool>,
    entrants: Vec<usize>,
}

impl Selector {
    /// A selector over `fitness` (one value per individual, higher is better).
    ///
    /// # Panics
    /// If `fitness` is empty: there is nobody to select.
    pub fn new(spec: &SelectionSpec, fitness: &[f64]) -> Selector {
        assert!(
            !fitness.is_empty(),
            "selection needs at least one evaluated individual"
        );
        let keys: Vec<f64> = fitness.iter().map(|&f| key(f)).collect();
        let order = ranking_of_keys(&keys);
        let n = keys.len();
        let mut cumulative = Vec::new();
        let mut entered = Vec::new();
        match *spec {
            SelectionSpec::Rank { pressure } => {
                let mut total = 0.0;
                cumulative.reserve_exact(n);
                for rank in 0..n {
                    total += rank_weight(pressure, rank, n);
                    cumulative.push(total);
                }
            }
            SelectionSpec::Tournament { .. } => entered = vec![false; n],
            SelectionSpec::Truncation { .. } => {}
        }
        Selector {
            spec: *spec,
            keys,
            order,
            cumulative,
            entered,
            entrants: Vec::new(),
        }
    }

    /// The individuals, best first (ties: lower index first).
    pub fn ranking(&self) -> &[usize] {
        &self.order
    }

    /// The index of one selected parent.
    pub fn pick(&mut self, rng: &mut Rng) -> usize {
        let n = self.keys.len();
        match self.spec {
            SelectionSpec::Tournament { size } => self.tournament(size.clamp(1, n), rng),
            SelectionSpec::Truncation { fraction } => {
                let m = truncation_count(fraction, n);
                self.order[below(rng, m as u64) as usize]
            }
            SelectionSpec::Rank { .. } => {
                let total = self.cumulative[n - 1];
                let u = unit(rng) * total;
                // The first rank whose cumulative weight exceeds u; rounding of u·total up to
                // the total is clamped to the best rank.
                let rank = self.cumulative.partition_point(|&c| c <= u).min(n - 1);
                self.order[n - 1 - rank]
            }
        }
    }

    /// The best of `k` distinct individuals drawn by Floyd's algorithm.
    fn tournament(&mut self, k: usize, rng: &mut Rng) -> usize {
        let n = self.keys.len();
        let mut winner: Option<usize> = None;
        for j in (n - k)..n {
            let t = below(rng, j as u64 + 1) as usize;
            let entrant = if self.entered[t] { j } else { t };
            self.entered[entrant] = true;
            self.entrants.push(entrant);
            winner = Some(match winner {
                Some(w) if rank_order(&self.keys, w, entrant) == Ordering::Less => w,
                _ => entrant,
            });
        }
        for e in self.entrants.drain(..) {
            self.entered[e] = false;
        }
        // k >= 1, so the loop ran at least once.
        winner.unwrap_or(self.order[0])
    }
}
