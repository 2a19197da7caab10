//! The named world sets and evaluating genomes on them: which trial worlds "training
//! generation g", "validation" and "held-out" mean, and the one way genomes meet them. The
//! command line (`compare`, `replay`, `render`, `summary`) and the Python package both come
//! here, so `berry-evolve compare --json` and `Experiment.evaluate` in Python give the same
//! bits by construction.
//!
//! Two ways to meet a set, both here:
//! - [`lives`] / [`evaluate_alone`]: each genome alone (group 0) in the same worlds, common
//!   random numbers forced on ([`alone`]): what `compare` reports, for any set.
//! - [`evaluate`] with a training set: the population as the run evaluates generation g
//!   (its groups, its `common_random_numbers`), through
//!   [`crate::evo::evaluate::evaluate_population`]. For an experiment with common random
//!   numbers and groups of one (the shipped foraging experiments) both give the same bits.

use crate::brain::genome::Genome;
use crate::brain::spec::Topology;
use crate::evo::episodes::{Life, LifeOrigin};
use crate::evo::evaluate::{aggregate, evaluate_population, run_trial, Evaluation, JOBS_APART};
use crate::evo::init::initial_population;
use crate::evo::life::{EvaluationError, TrialOutcome};
use crate::evo::trial::{run_life, run_trial_in_world, NoObserver, TrialId};
use crate::evo::validation::validation_worlds;
use crate::experiment::Experiment;
use crate::seed::{stream, Generation, IndividualId, Purpose, TrialIndex};
use crate::sim::world::World;
use crate::validate::InvalidValue;
use rayon::prelude::*;
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
    /// trial from their generation's streams.
    pub fn built_worlds(
        self,
        experiment: &Experiment,
    ) -> Result<Option<Vec<World>>, EvaluationError> {
        match self {
            WorldSet::Validation => Ok(Some(validation_worlds(experiment)?)),
            _ => Ok(None),
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

/// `genome`'s life, alone (group 0), in trial `t` of `set`: in the `built` world t (the
/// validation worlds) when given, else in the world its generation's stream builds.
fn life(
    experiment: &Experiment,
    topology: &Topology,
    genome: &Genome,
    set: WorldSet,
    built: Option<&[World]>,
    t: u64,
) -> Result<TrialOutcome, EvaluationError> {
    let genomes = std::slice::from_ref(genome);
    let generation = set.generation();
    let trial = TrialIndex(t);
    let lives = match built {
        Some(worlds) => {
            let id = TrialId {
                generation,
                group: 0,
                trial,
            };
            let world = worlds[t as usize].clone();
            // Built worlds are the validation worlds (see `WorldSet::built_worlds`).
            let origin = LifeOrigin::validation(trial);
            run_trial_in_world(experiment, topology, genomes, id, origin, world, NoObserver)?
        }
        None => run_trial(experiment, topology, genomes, generation, 0, trial)?,
    };
    Ok(lives[0])
}

/// One life's episodes as `compare --json` reports them (lives of several episodes).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LifeChoices {
    /// The episodes (numbered from 1) a switch came before.
    pub switches: Vec<u64>,
    /// Per episode: were the switch kinds' payoffs exchanged (relative to `[world.kinds]`)?
    pub exchanged: Vec<bool>,
    /// Per episode: was the first bite of a switch kind of the paying one? (false when it bit
    /// neither, or the life had ended)
    pub correct_first_choice: Vec<bool>,
}

/// [`lives`], also returning each life's episodes (one list per trial, in trial order).
pub fn lives_by_episode(
    experiment: &Experiment,
    topology: &Topology,
    genome: &Genome,
    set: WorldSet,
    built: Option<&[World]>,
) -> Result<Vec<(TrialOutcome, LifeChoices)>, EvaluationError> {
    (0..trial_count(experiment, built))
        .into_par_iter()
        .map(|t| {
            let trial = TrialIndex(t);
            let generation = set.generation();
            let id = TrialId {
                generation,
                group: 0,
                trial,
            };
            let (origin, first) = match built {
                Some(worlds) => (
                    LifeOrigin::validation(trial),
                    Some(worlds[t as usize].clone()),
                ),
                None => (LifeOrigin::trial(experiment, generation, 0, trial), None),
            };
            let genomes = std::slice::from_ref(genome);
            let (outcomes, episodes) =
                run_life(experiment, topology, genomes, id, origin, first, NoObserver)?;
            let life = Life::new(experiment, origin);
            let choices = LifeChoices {
                switches: life.schedule().switches(),
                exchanged: life.schedule().exchanged.clone(),
                correct_first_choice: life.correct_choices(&episodes[0]),
            };
            Ok((outcomes[0], choices))
        })
        .collect()
}

/// How many trials `genome` lives in `set`: the `built` worlds when given, else the
/// experiment's `[evaluation] trials`.
fn trial_count(experiment: &Experiment, built: Option<&[World]>) -> u64 {
    built.map_or(experiment.evaluation.trials, |w| w.len() as u64)
}

/// Lives every trial of `genome` alone in `set`'s worlds (group 0): the `built` worlds (from
/// [`WorldSet::built_worlds`]) when given, else those its generation's streams build; the
/// trials in parallel, collected in trial order, so the same bits on any number of threads.
/// `experiment` should come from [`alone`], so that the worlds do not depend on the group.
pub fn lives(
    experiment: &Experiment,
    topology: &Topology,
    genome: &Genome,
    set: WorldSet,
    built: Option<&[World]>,
) -> Result<Vec<TrialOutcome>, EvaluationError> {
    (0..trial_count(experiment, built))
        .into_par_iter()
        .map(|t| life(experiment, topology, genome, set, built, t))
        .collect()
}

/// [`lives`] for each of `genomes` (every (genome, trial) pair in parallel, collected in
/// order), each aggregated over its trials as `compare` does.
pub fn evaluate_alone(
    experiment: &Experiment,
    topology: &Topology,
    genomes: &[Genome],
    set: WorldSet,
    built: Option<&[World]>,
) -> Result<Vec<Evaluation>, EvaluationError> {
    let trials = trial_count(experiment, built);
    let jobs = genomes.len() * trials as usize;
    let outcomes: Vec<TrialOutcome> = (0..jobs as u64)
        .collect::<Vec<_>>()
        .into_par_iter()
        .with_max_len(JOBS_APART)
        .map(|j| {
            let genome = &genomes[(j / trials) as usize];
            life(experiment, topology, genome, set, built, j % trials)
        })
        .collect::<Result<_, _>>()?;
    Ok(outcomes
        .chunks(trials.max(1) as usize)
        .take(genomes.len())
        .map(|lives| aggregate(experiment, lives))
        .collect())
}

/// Evaluates `genomes` on `set`: the training worlds of generation g exactly as the run
/// evaluates that generation (its groups and common random numbers), the held-out and
/// validation worlds each genome alone as `compare` does ([`evaluate_alone`] in [`alone`]'s
/// experiment). Results in genome order; the same bits on any number of threads.
pub fn evaluate(
    experiment: &Experiment,
    topology: &Topology,
    genomes: &[Genome],
    set: WorldSet,
) -> Result<Vec<Evaluation>, WorldsError> {
    set.check(experiment)?;
    match set {
        WorldSet::Training(g) => {
            let k = experiment.evaluation.group_size.max(1);
            if genomes.len() as u64 % k != 0 {
                return Err(WorldsError::PartialGroup {
                    genomes: genomes.len(),
                    group_size: k,
                });
            }
            Ok(evaluate_population(
                experiment,
                topology,
                genomes,
                Generation(g),
            )?)
        }
        WorldSet::HeldOut | WorldSet::Validation | WorldSet::Design => {
            let experiment = alone(experiment)?;
            let built = set.built_worlds(&experiment)?;
            Ok(evaluate_alone(
                &experiment,
                topology,
                genomes,
                set,
                built.as_deref(),
            )?)
        }
    }
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
