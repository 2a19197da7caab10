//! The named world sets: which trial worlds "training generation g", "validation",
//! "held-out" and "design" mean, how they are built ([`WorldSet::build`]), and the random
//! genomes every science table sets champions against ([`random_genomes`]). Genomes meet
//! them through the one evaluation door, [`crate::evo::door`]; the command line (`compare`,
//! `replay`, `render`, `summary`) and the Python package both name sets here, so
//! `berry-evolve compare --json` and `Experiment.evaluate` in Python give the same bits by
//! construction.

use crate::brain::genome::Genome;
use crate::evo::episodes::LifeOrigin;
use crate::evo::init::initial_population;
use crate::evo::life::{trial_stream, valid_specs, world_error, EvaluationError};
use crate::evo::trial_plan::TrialPlan;
use crate::experiment::Experiment;
use crate::seed::{stream, Generation, IndividualId, Purpose, Rng, TrialIndex};
use crate::sim::world::World;
use crate::validate::InvalidValue;
use thiserror::Error;

/// Generation number whose trial worlds serve as the held-out test set: far beyond any run's
/// length, so no individual was ever selected on them. `--generation 1099511627776` (its
/// value, 2^40) still names them.
pub const HELD_OUT_GENERATION: u64 = 1 << 40;

/// Generation number whose trial worlds are the design set: where hand-designed controllers
/// and an experiment's settings are tuned, so that the held-out worlds stay unseen by the
/// tuning as well as by evolution (SCIENCE.md). `--generation 1099511627777` still names it.
pub const DESIGN_GENERATION: u64 = HELD_OUT_GENERATION + 1;

/// The names a world set is given by (`--worlds`, Python's `worlds=`).
pub const SET_NAMES: [&str; 4] = ["held-out", "validation", "training", "design"];

/// Whose trial worlds, resolved.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WorldSet {
    /// Generation G's training worlds ([`crate::seed::Purpose::TrialWorld`] streams).
    Training(u64),
    /// The held-out worlds: the training streams of [`HELD_OUT_GENERATION`], group 0.
    HeldOut,
    /// The experiment's validation worlds
    /// ([`crate::seed::Purpose::ValidationWorld`] streams).
    Validation,
    /// The design worlds: the training streams of [`DESIGN_GENERATION`], group 0.
    Design,
}

/// Why genomes could not be evaluated on a world set.
#[derive(Debug, Error)]
pub enum WorldsError {
    /// A set name that is none of [`SET_NAMES`].
    #[error("unknown world set `{name}`: possible values: held-out, validation, training, design")]
    UnknownSet {
        /// The name given.
        name: String,
    },
    /// The validation worlds of an experiment that has none.
    #[error(
        "world set `validation`: experiment `{experiment}` has no [validation] table (or its \
         `every` is 0), so it has no validation worlds; add one (e.g. `[validation]` with \
         every = 10, top = 3, trials = 10) or choose the held-out worlds"
    )]
    NoValidation {
        /// The experiment's name.
        experiment: String,
    },
    /// Training worlds for a population that does not fill its groups.
    #[error(
        "{genomes} genomes do not fill groups of {group_size} ([evaluation] group_size): give \
         a multiple of {group_size}"
    )]
    PartialGroup {
        /// Genomes given.
        genomes: usize,
        /// The experiment's group size.
        group_size: u64,
    },
    /// The experiment with common random numbers forced on did not validate.
    #[error(transparent)]
    Experiment(#[from] InvalidValue),
    /// A trial could not run (a genome that does not fit, a world that cannot be built).
    #[error(transparent)]
    Evaluation(#[from] EvaluationError),
}

impl WorldSet {
    /// Generation `g`'s worlds: the held-out set for [`HELD_OUT_GENERATION`] (so the old
    /// `--generation 1099511627776` form is named like `--worlds held-out`).
    pub fn of_generation(g: u64) -> WorldSet {
        match g {
            HELD_OUT_GENERATION => WorldSet::HeldOut,
            DESIGN_GENERATION => WorldSet::Design,
            _ => WorldSet::Training(g),
        }
    }

    /// The set called `name` (one of [`SET_NAMES`]); `generation` chooses the training worlds'
    /// generation and is ignored by the other sets.
    pub fn parse(name: &str, generation: u64) -> Result<WorldSet, WorldsError> {
        match name {
            "held-out" => Ok(WorldSet::HeldOut),
            "validation" => Ok(WorldSet::Validation),
            "design" => Ok(WorldSet::Design),
            "training" => Ok(WorldSet::of_generation(generation)),
            _ => Err(WorldsError::UnknownSet {
                name: name.to_string(),
            }),
        }
    }

    /// The generation whose streams build the worlds (0 for the validation worlds, whose
    /// streams are of their own purpose).
    pub fn generation(self) -> Generation {
        Generation(match self {
            WorldSet::Training(g) => g,
            WorldSet::HeldOut => HELD_OUT_GENERATION,
            WorldSet::Design => DESIGN_GENERATION,
            WorldSet::Validation => 0,
        })
    }

    /// `training`, `held-out` or `validation` (as `--worlds` spells it).
    pub fn name(self) -> &'static str {
        match self {
            WorldSet::Training(_) => "training",
            WorldSet::HeldOut => "held-out",
            WorldSet::Validation => "validation",
            WorldSet::Design => "design",
        }
    }

    /// The title of trial `t`: `held-out world 2`, `validation world 2`, `trial 2 of
    /// generation 5`.
    pub fn trial_title(self, t: u64) -> String {
        match self {
            WorldSet::Training(g) => format!("trial {t} of generation {g}"),
            WorldSet::HeldOut | WorldSet::Validation | WorldSet::Design => {
                format!("{} world {t}", self.name())
            }
        }
    }

    /// A trial's line label: `trial 2` for training worlds (as replay always printed),
    /// `held-out world 2` and `validation world 2` for the named sets.
    pub fn trial_label(self, t: u64) -> String {
        match self {
            WorldSet::Training(_) => format!("trial {t}"),
            _ => self.trial_title(t),
        }
    }

    /// `n` trials of this set: `3 trial(s) of generation 5`, `3 held-out world(s)`.
    pub fn count_text(self, n: usize) -> String {
        match self {
            WorldSet::Training(g) => format!("{n} trial(s) of generation {g}"),
            _ => format!("{n} {} world(s)", self.name()),
        }
    }

    /// `the held-out worlds (...)`, `the validation worlds (...)` or `generation G's training
    /// worlds`, as compare's first line says it.
    pub fn description(self) -> String {
        match self {
            WorldSet::HeldOut => {
                "the held-out worlds (never used in training or validation)".to_string()
            }
            WorldSet::Validation => {
                "the validation worlds (the [validation] table's, on which best.json is chosen)"
                    .to_string()
            }
            WorldSet::Design => "the design worlds (for tuning hand-designed controllers and \
                                 settings; never used in training, validation or held-out)"
                .to_string(),
            WorldSet::Training(g) => format!("generation {g}'s training worlds"),
        }
    }

    /// How many worlds the set has in `experiment`: `[validation] trials` for the validation
    /// worlds, `[evaluation] trials` for the others.
    pub fn trials(self, experiment: &Experiment) -> u64 {
        match self {
            WorldSet::Validation => experiment.validation.trials,
            _ => experiment.evaluation.trials,
        }
    }

    /// Refuses the validation worlds of an experiment without validation: it has none.
    pub fn check(self, experiment: &Experiment) -> Result<(), WorldsError> {
        if self == WorldSet::Validation && !experiment.validation.enabled() {
            return Err(WorldsError::NoValidation {
                experiment: experiment.name.clone(),
            });
        }
        Ok(())
    }

    /// The validation worlds (for one creature each) of `experiment`, exactly those a run's
    /// validation evaluates on; None for the other sets, whose trial worlds are built trial by
    /// trial from their generation's streams (`replay`, which lives one trial at a time).
    pub fn built_worlds(
        self,
        experiment: &Experiment,
    ) -> Result<Option<Vec<World>>, EvaluationError> {
        match self {
            WorldSet::Validation => Ok(Some(validation_worlds(experiment)?)),
            _ => Ok(None),
        }
    }

    /// The set's worlds in `experiment` for one creature each, built once: the validation
    /// worlds (exactly those a run's validation evaluates on), else group 0's trial worlds of
    /// the set's generation (the worlds a genome alone meets there: with group 0 the stream
    /// is the same with or without common random numbers).
    pub fn build(self, experiment: &Experiment) -> Result<BuiltWorlds, EvaluationError> {
        match self {
            WorldSet::Validation => Ok(BuiltWorlds {
                worlds: validation_worlds(experiment)?,
                origin: LifeOrigin::validation(TrialIndex(0)),
            }),
            WorldSet::Training(_) | WorldSet::HeldOut | WorldSet::Design => {
                let generation = self.generation();
                let plan = TrialPlan::new(experiment);
                Ok(BuiltWorlds {
                    worlds: worlds_from(&plan, plan.trials, generation, |t| {
                        trial_stream(&plan, generation, 0, t)
                    })?,
                    origin: LifeOrigin::trial(&plan, generation, 0, TrialIndex(0)),
                })
            }
        }
    }
}

/// `count` random genomes, the baseline every science table sets champions against: drawn
/// as an initial population is, from the [`Purpose::Baseline`] stream of `generation` (a
/// set's [`WorldSet::generation`]), so that `compare` and `summary` on one set draw the very
/// same genomes.
pub fn random_genomes(
    experiment: &Experiment,
    generation: Generation,
    count: usize,
) -> Vec<Genome> {
    let mut rng = stream(
        experiment.seed(),
        Purpose::Baseline,
        generation,
        IndividualId(0),
        TrialIndex(0),
    );
    let mut spec = experiment.evolution.clone();
    spec.population = count;
    initial_population(&spec, experiment.topology().parameter_count(), &mut rng)
}

/// `experiment` with common random numbers forced on: every genome evaluated alone meets the
/// same worlds (what `compare` evaluates in).
pub fn alone(experiment: &Experiment) -> Result<Experiment, InvalidValue> {
    experiment
        .with_overrides()
        .common_random_numbers(true)
        .build()
}

/// A set's worlds, built once for one creature each, and where the first came from (world
/// t's life is at `origin.with_trial(t)`, whence the later episodes of lives of several).
#[derive(Debug, Clone)]
pub struct BuiltWorlds {
    /// The worlds, in trial order.
    pub worlds: Vec<World>,
    /// The seed-stream coordinates of the first world.
    pub origin: LifeOrigin,
}

/// The fixed validation worlds of `experiment` (one creature each): world t is built from
/// the [`Purpose::ValidationWorld`] stream of (seed, generation 0, individual 0, trial t).
pub fn validation_worlds(experiment: &Experiment) -> Result<Vec<World>, EvaluationError> {
    worlds_from(
        &TrialPlan::new(experiment),
        experiment.validation.trials,
        Generation(0),
        |trial| {
            stream(
                experiment.seed(),
                Purpose::ValidationWorld,
                Generation(0),
                IndividualId(0),
                trial,
            )
        },
    )
}

/// Builds `trials` worlds for one creature each from `rng_of(t)`, in trial order,
/// validating the specifications once.
fn worlds_from(
    plan: &TrialPlan,
    trials: u64,
    generation: Generation,
    rng_of: impl Fn(TrialIndex) -> Rng,
) -> Result<Vec<World>, EvaluationError> {
    if trials == 0 {
        return Ok(Vec::new());
    }
    let specs = valid_specs(plan, generation, TrialIndex(0))?;
    (0..trials)
        .map(|t| {
            World::build(specs, 1, rng_of(TrialIndex(t)))
                .map_err(|error| world_error(generation, TrialIndex(t), error))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn set_names_parse_and_an_unknown_one_is_refused() {
        assert_eq!(WorldSet::parse("held-out", 3).unwrap(), WorldSet::HeldOut);
        assert_eq!(
            WorldSet::parse("validation", 3).unwrap(),
            WorldSet::Validation
        );
        assert_eq!(
            WorldSet::parse("training", 3).unwrap(),
            WorldSet::Training(3)
        );
        assert_eq!(
            WorldSet::parse("training", HELD_OUT_GENERATION).unwrap(),
            WorldSet::HeldOut
        );
        let e = WorldSet::parse("test", 0).unwrap_err().to_string();
        assert!(e.contains("`test`") && e.contains("held-out"), "{e}");
        for name in SET_NAMES {
            assert_eq!(WorldSet::parse(name, 1).unwrap().name(), name);
        }
    }
}
