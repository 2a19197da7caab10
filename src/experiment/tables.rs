//! The experiment tables that belong to evaluation rather than to the world, the brain or
//! the genetic algorithm: `[evaluation]`, `[fitness]` and `[output]`.

use crate::validate::{all_finite, count_within, finite, non_negative, InvalidValue, Valid};
use serde::{Deserialize, Serialize};

/// Most trials per individual: beyond this a generation would take days.
pub const MAX_TRIALS: u64 = 10_000;
/// Most ticks per trial (a life of 10^7 ticks is about an hour of one core).
pub const MAX_TICKS: u64 = 10_000_000;
/// Most creature-ticks one generation may ask for (population × trials × ticks): about
/// a day of one core at the simulator's speed; anything above is almost surely a typo.
pub const MAX_CREATURE_TICKS_PER_GENERATION: u64 = 200_000_000_000;

/// How the trials of an individual are combined into one fitness.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Aggregate {
    /// The mean over trials.
    Mean,
    /// The worst trial: rewards controllers that never fail.
    Min,
}

/// `[evaluation]`: how an individual's fitness is measured.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct EvaluationSpec {
    /// Trial worlds per individual (default: 3).
    pub trials: u64,
    /// Ticks per trial, i.e. the length of a life (default: 500).
    pub ticks: u64,
    /// How trial scores are combined: `"mean"` or `"min"` (default: mean).
    pub aggregate: Aggregate,
    /// Common random numbers: every individual of a generation faces the same trial worlds,
    /// new worlds each generation (default: true). When false each individual gets its own.
    pub common_random_numbers: bool,
    /// Individuals that share one world (default: 1). With k > 1 the population is cut into
    /// groups of k consecutive individuals that live together; it must divide the population.
    pub group_size: u64,
}

impl Default for EvaluationSpec {
    fn default() -> Self {
        EvaluationSpec {
            trials: 3,
            ticks: 500,
            aggregate: Aggregate::Mean,
            common_random_numbers: true,
            group_size: 1,
        }
    }
}

impl EvaluationSpec {
    /// Checks the table on its own.
    pub fn validate(&self) -> Valid {
        count_within(
            "evaluation.trials",
            self.trials,
            1,
            MAX_TRIALS,
            "trials per individual",
        )?;
        count_within(
            "evaluation.ticks",
            self.ticks,
            1,
            MAX_TICKS,
            "ticks per trial",
        )?;
        count_within(
            "evaluation.group_size",
            self.group_size,
            1,
            1_000,
            "creatures per world",
        )?;
        Ok(())
    }

    /// Checks the constraints that involve the population size.
    pub fn validate_against_population(&self, population: usize) -> Valid {
        let population = population as u64;
        if population % self.group_size != 0 {
            return Err(InvalidValue::new(
                "evaluation.group_size",
                format!(
                    "must divide the population ({population}) so that every group is full, got {}",
                    self.group_size
                ),
            ));
        }
        let work = population
            .saturating_mul(self.trials)
            .saturating_mul(self.ticks);
        if work > MAX_CREATURE_TICKS_PER_GENERATION {
            return Err(InvalidValue::new(
                "evaluation.ticks",
                format!(
                    "population × trials × ticks = {work} creature-ticks per generation exceeds \
                     the limit of {MAX_CREATURE_TICKS_PER_GENERATION} (about a day of one core)"
                ),
            ));
        }
        Ok(())
    }
}

/// How a life's metabolic history becomes a score.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FitnessMode {
    /// `weights · m` at the end of life.
    Final,
    /// `weights · m` summed over every tick of life (rewards eating early and keeping it).
    Integrated,
}

/// `[fitness]`: the score of one trial (report §5.3 leaves it open; SPEC-NOTES).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct FitnessSpec {
    /// Weight of each metabolic component fA, fB, fC, fD (default: [1, 1, 1, 1]). Negative
    /// weights make a food type poisonous.
    pub weights: [f64; 4],
    /// `"final"` or `"integrated"` (default: final).
    pub mode: FitnessMode,
    /// Subtracted once per tick on which the shock sensor is on (default: 0).
    pub shock_penalty: f64,
}

impl Default for FitnessSpec {
    fn default() -> Self {
        FitnessSpec {
            weights: [1.0; 4],
            mode: FitnessMode::Final,
            shock_penalty: 0.0,
        }
    }
}

impl FitnessSpec {
    /// Checks the table.
    pub fn validate(&self) -> Valid {
        all_finite("fitness.weights", &self.weights)?;
        non_negative("fitness.shock_penalty", self.shock_penalty)?;
        finite("fitness.shock_penalty", self.shock_penalty)
    }
}

/// `[output]`: how often a run saves itself. Not part of the config hash: it changes where
/// results go, never what they are.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct OutputSpec {
    /// Write a checkpoint every this many generations, and always at the end (default: 10).
    pub checkpoint_every: u64,
    /// How many checkpoints to keep; older ones are deleted (default: 3, at least 1).
    pub keep_checkpoints: u64,
}

impl Default for OutputSpec {
    fn default() -> Self {
        OutputSpec {
            checkpoint_every: 10,
            keep_checkpoints: 3,
        }
    }
}

impl OutputSpec {
    /// Checks the table.
    pub fn validate(&self) -> Valid {
        count_within(
            "output.checkpoint_every",
            self.checkpoint_every,
            1,
            u32::MAX as u64,
            "generations",
        )?;
        count_within(
            "output.keep_checkpoints",
            self.keep_checkpoints,
            1,
            1_000,
            "files",
        )
    }
}
