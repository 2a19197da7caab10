//! [`TrialPlan`]: what a trial needs of the experiment (the world, the creature, the length of
//! a life, the streams, the scoring), resolved once from a validated
//! [`crate::experiment::Experiment`] and handed to the trial code instead of the whole
//! experiment, so that building worlds, living ticks and scoring cannot read the search's
//! settings, the validation's or the output's.
//!
//! It holds only copies of scalars and references into the experiment, so it is resolved
//! where a request starts (the door's [`crate::evo::door::Evaluate::new`], a generation's
//! [`crate::evo::evaluate::PopulationJobs::new`], replay, the named world sets, Python's
//! episodes) and passed by reference from there; it changes no bit of any trial.

use crate::experiment::evolution::DescribedAreas;
use crate::experiment::{Aggregate, BehaviourSpec, Experiment, FitnessSpec, SwitchSpec};
use crate::seed::Seed;
use crate::sim::spec::{CreatureSpec, WorldSpec};

/// What a trial needs of an experiment, read from it once ([`TrialPlan::new`]).
#[derive(Debug, Clone, Copy)]
pub struct TrialPlan<'a> {
    /// The master seed every trial stream derives from.
    pub seed: Seed,
    /// The world of every trial (`[world]`).
    pub world: &'a WorldSpec,
    /// The creatures' body and senses (`[creature]`).
    pub creature: &'a CreatureSpec,
    /// Ticks per trial (per episode in a life of several; `[evaluation] ticks`).
    pub ticks: u64,
    /// Trial worlds per individual (`[evaluation] trials`).
    pub trials: u64,
    /// Episodes per life (`[evaluation] episodes_per_life`).
    pub episodes_per_life: u64,
    /// What changes between the episodes of a life (`[evaluation.switch]`), if anything.
    pub switch: Option<&'a SwitchSpec>,
    /// Every group of a generation lives the same trial worlds
    /// (`[evaluation] common_random_numbers`).
    pub common_random_numbers: bool,
    /// Individuals that share one world (`[evaluation] group_size`).
    pub group_size: u64,
    /// How an individual's trial scores are combined (`[evaluation] aggregate`).
    pub aggregate: Aggregate,
    /// How a life is scored (`[fitness]`).
    pub fitness: &'a FitnessSpec,
    /// The behaviour measures reported next to fitness (`[behaviour]`).
    pub behaviour: &'a BehaviourSpec,
    /// The areas whose ticks a search's descriptors count (`area = "..."`; usually none).
    pub described_areas: DescribedAreas,
}

impl<'a> TrialPlan<'a> {
    /// The plan of `experiment`'s trials.
    pub fn new(experiment: &'a Experiment) -> TrialPlan<'a> {
        let evaluation = &experiment.evaluation;
        TrialPlan {
            seed: experiment.seed(),
            world: &experiment.world,
            creature: &experiment.creature,
            ticks: evaluation.ticks,
            trials: evaluation.trials,
            episodes_per_life: evaluation.episodes_per_life,
            switch: evaluation.switch.as_ref(),
            common_random_numbers: evaluation.common_random_numbers,
            group_size: evaluation.group_size,
            aggregate: evaluation.aggregate,
            fitness: &experiment.fitness,
            behaviour: &experiment.behaviour,
            described_areas: experiment.evolution.described_areas(&experiment.world),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    /// Each field is the experiment's own value (trials and ticks, both counts, not swapped),
    /// overrides included, and the tables are the experiment's, not copies.
    #[test]
    fn a_plan_reads_the_experiments_own_values() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        let experiment = Experiment::load(&root.join("tests/fixtures/tiny.toml"))
            .unwrap()
            .with_overrides()
            .seed(11)
            .trials(5)
            .ticks(7)
            .common_random_numbers(false)
            .build()
            .unwrap();
        let plan = TrialPlan::new(&experiment);
        assert_eq!(plan.seed, Seed(11));
        assert_eq!((plan.trials, plan.ticks), (5, 7));
        assert!(!plan.common_random_numbers);
        let e = &experiment.evaluation;
        assert_eq!(plan.group_size, e.group_size);
        assert_eq!(plan.episodes_per_life, e.episodes_per_life);
        assert_eq!(plan.aggregate, e.aggregate);
        assert_eq!(plan.switch, e.switch.as_ref());
        assert!(std::ptr::eq(plan.world, &experiment.world));
        assert!(std::ptr::eq(plan.creature, &experiment.creature));
        assert!(std::ptr::eq(plan.fitness, &experiment.fitness));
        assert!(std::ptr::eq(plan.behaviour, &experiment.behaviour));
    }
}
