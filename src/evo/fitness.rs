//! Fitness of one life: the `[fitness]` table applied to a creature's metabolic history
//! (report §5.3 leaves the function open; SPEC-NOTES lists the choices offered here).

use crate::experiment::{FitnessMode, FitnessSpec};

/// Accumulates what a life's score needs, tick by tick.
#[derive(Debug, Clone)]
pub struct LifeScore {
    weights: [f64; 4],
    mode: FitnessMode,
    shock_penalty: f64,
    integral: f64,
    shocked_ticks: u64,
}

/// `weights · m`.
#[inline]
pub fn weighted(weights: &[f64; 4], m: &[f64; 4]) -> f64 {
    weights[0] * m[0] + weights[1] * m[1] + weights[2] * m[2] + weights[3] * m[3]
}

impl LifeScore {
    /// A score for a life that has not started yet.
    pub fn new(spec: &FitnessSpec) -> Self {
        LifeScore {
            weights: spec.weights,
            mode: spec.mode,
            shock_penalty: spec.shock_penalty,
            integral: 0.0,
            shocked_ticks: 0,
        }
    }

    /// Records one lived tick: the metabolic vector after it and whether the creature was
    /// shocked on it.
    #[inline]
    pub fn record_tick(&mut self, metabolism: &[f64; 4], shocked: bool) {
        if self.mode == FitnessMode::Integrated {
            self.integral += weighted(&self.weights, metabolism);
        }
        self.shocked_ticks += u64::from(shocked);
    }

    /// Ticks on which the creature was shocked.
    pub fn shocked_ticks(&self) -> u64 {
        self.shocked_ticks
    }

    /// The life's score, given the metabolic vector at its end.
    pub fn finish(&self, final_metabolism: &[f64; 4]) -> f64 {
        let gain = match self.mode {
            FitnessMode::Final => weighted(&self.weights, final_metabolism),
            FitnessMode::Integrated => self.integral,
        };
        gain - self.shock_penalty * self.shocked_ticks as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn final_mode_is_weights_dot_final_m_minus_shocks() {
        let spec = FitnessSpec {
            weights: [1.0, 2.0, 0.0, -1.0],
            mode: FitnessMode::Final,
            shock_penalty: 0.5,
        };
        let mut s = LifeScore::new(&spec);
        s.record_tick(&[9.0, 9.0, 9.0, 9.0], true);
        s.record_tick(&[1.0, 1.0, 1.0, 1.0], false);
        s.record_tick(&[0.0, 0.0, 0.0, 0.0], true);
        // 1*3 + 2*4 + 0*5 - 1*1 = 10, minus 2 shocked ticks * 0.5.
        assert_eq!(s.finish(&[3.0, 4.0, 5.0, 1.0]), 9.0);
        assert_eq!(s.shocked_ticks(), 2);
    }

    #[test]
    fn integrated_mode_sums_every_tick() {
        let spec = FitnessSpec {
            weights: [1.0, 1.0, 1.0, 1.0],
            mode: FitnessMode::Integrated,
            shock_penalty: 1.0,
        };
        let mut s = LifeScore::new(&spec);
        s.record_tick(&[1.0, 0.0, 0.0, 0.0], false);
        s.record_tick(&[1.0, 1.0, 0.0, 0.0], false);
        s.record_tick(&[1.0, 1.0, 1.0, 0.0], true);
        // 1 + 2 + 3 - 1.
        assert_eq!(s.finish(&[100.0; 4]), 5.0);
    }
}
