//! The metabolic state m = ⟨fA, fB, fC, fD⟩ (§5.3): what eating adds and what time and
//! movement take away.

use crate::seed::{uniform, Rng};

/// The metabolic vector m = ⟨fA, fB, fC, fD⟩ (§5.3): the amount of each food type's substance
/// a creature holds, indexed by food type (A = 0 … D = 3), never below 0. The name it carries
/// across layers (a creature's state, a trial's outcome, an evaluation, checkpoints, genome
/// files, traces). An alias rather than a newtype: it serializes as the same array of four
/// numbers and the tick's arithmetic indexes it as it always has, so no file byte and no
/// instruction changes.
pub type Metabolism = [f64; 4];

/// A creature's m at birth: `initial` plus, per component, a uniform draw from
/// [0, `spread`) (components in order A … D; no draw at all when every spread is 0, so that
/// worlds without one keep their bytes).
pub fn at_birth(initial: Metabolism, spread: [f64; 4], rng: &mut Rng) -> Metabolism {
    if spread.iter().all(|&s| s == 0.0) {
        return initial;
    }
    let mut m = initial;
    for t in 0..4 {
        m[t] += uniform(rng, 0.0, spread[t]);
    }
    m
}

/// How m decays: per tick and per LU travelled, per food type.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Decay {
    /// Subtracted every tick.
    pub per_tick: [f64; 4],
    /// Subtracted per LU travelled this tick.
    pub per_lu: [f64; 4],
}

impl Decay {
    /// One tick of metabolism, in the order of SPEC-NOTES: first what was eaten this tick is
    /// added, then the decay for the tick and for the `travelled` LU is subtracted. m never
    /// drops below 0 (§5.3 speaks of amounts of consumed substance).
    #[inline]
    pub fn apply(&self, m: &mut Metabolism, received: &[f64; 4], travelled: f64) {
        for t in 0..4 {
            let next = m[t] + received[t] - (self.per_tick[t] + self.per_lu[t] * travelled);
            m[t] = next.max(0.0);
        }
    }
}

/// `weights · m`: a metabolic vector (or an amount per type A–D) weighted by `[fitness]
/// weights`, summed left to right (the fitness's gain and the switch measures' paying kind use
/// these very bits).
#[inline]
pub fn weighted(weights: &[f64; 4], m: &[f64; 4]) -> f64 {
    weights[0] * m[0] + weights[1] * m[1] + weights[2] * m[2] + weights[3] * m[3]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eat_then_decay_never_below_zero() {
        let decay = Decay {
            per_tick: [0.5, 0.0, 1.0, 0.0],
            per_lu: [0.25, 0.0, 0.0, 2.0],
        };
        let mut m = [1.0, 2.0, 0.25, 1.0];
        decay.apply(&mut m, &[1.0, 0.0, 0.0, 0.0], 2.0);
        // A: 1 + 1 - (0.5 + 0.25 * 2) = 1; B unchanged; C: 0.25 - 1 < 0 -> 0; D: 1 - 4 -> 0.
        assert_eq!(m, [1.0, 2.0, 0.0, 0.0]);
    }
}
