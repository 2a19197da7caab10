//! The parts of a life in a trial that every trial path shares: the trial's world and its
//! seed stream, the brains as checked controllers, the score bookkeeping after each tick, the
//! outcome of a life, and why a trial could not run. The one-world path
//! ([`crate::evo::trial`]), the lockstep path ([`crate::evo::lockstep`]) and evaluation's
//! shared worlds ([`crate::evo::evaluate`]) are built from these, so they agree to the bit;
//! none of them imports another for them. Each reads the experiment through the trial's
//! [`TrialPlan`] only.

use crate::brain::genome::Genome;
use crate::brain::spec::Topology;
use crate::brain::{Brain, BrainController, LifeKey};
use crate::evo::fitness::{LifePlan, LifeScore, MEASURE_COUNT};
use crate::evo::trial_plan::TrialPlan;
use crate::experiment::evolution::MAX_DESCRIBED_AREAS;
use crate::seed::{stream, Generation, IndividualId, Purpose, Rng, TrialIndex};
use crate::sim::controller::{Controller, MotorCommand};
use crate::sim::metabolism::Metabolism;
use crate::sim::world::{ValidSpecs, World};
use crate::sim::PlacementError;
use thiserror::Error;

/// Why an evaluation could not run at all (as opposed to a creature doing badly).
#[derive(Debug, Error)]
pub enum EvaluationError {
    /// The genome does not fit the experiment's brain topology.
    #[error("individual {individual}: {error}")]
    Brain {
        /// Index in the population.
        individual: u64,
        /// What the brain said.
        error: crate::brain::BrainError,
    },
    /// The trial world could not be built (e.g. placement impossible at this density).
    #[error("generation {generation}, trial {trial}: cannot build the world: {error}")]
    World {
        /// Generation of the trial.
        generation: u64,
        /// Trial index.
        trial: u64,
        /// The placement failure.
        error: crate::sim::PlacementError,
    },
    /// A trial path that lives one episode per life was asked for lives of several.
    #[error(
        "evaluation.episodes_per_life = {episodes}: {path} lives one episode per life; set \
         episodes_per_life = 1 for it"
    )]
    Episodes {
        /// The experiment's episodes per life.
        episodes: u64,
        /// The path that cannot (e.g. "the step-by-step episode of the Python package").
        path: &'static str,
    },
    /// Another process (an MPI rank) could not evaluate its share, or could not take part.
    #[error("rank {rank} {what}")]
    Rank {
        /// The rank, from 1 (rank 0 is the process that owns the run folder).
        rank: usize,
        /// What went wrong, as a clause: "could not evaluate ...: ...".
        what: String,
    },
}

/// One individual's life in one trial world.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrialOutcome {
    /// The trial's score under `[fitness]`.
    pub score: f64,
    /// The metabolic vector at the end of life.
    pub metabolism: Metabolism,
    /// Ticks on which the shock sensor was on.
    pub shocked_ticks: u64,
    /// True when the brain produced a NaN or infinite output: the life was stopped.
    pub non_finite: bool,
    /// The behaviour measures, one per [`crate::experiment::MEASURES`] entry (0 for those
    /// the experiment's `[behaviour]` does not name).
    pub measures: [f64; MEASURE_COUNT],
    /// The ticks alive in each area the search's descriptors name, in descriptor order (0
    /// past them; all 0 for a search that names none).
    pub area_ticks: [f64; MAX_DESCRIBED_AREAS],
}

/// The random stream that builds trial `trial` of generation `generation` for `group`.
/// With common random numbers every group of a generation gets the same stream.
pub fn trial_stream(
    plan: &TrialPlan,
    generation: Generation,
    group: u64,
    trial: TrialIndex,
) -> Rng {
    let who = if plan.common_random_numbers {
        IndividualId(0)
    } else {
        IndividualId(group)
    };
    stream(plan.seed, Purpose::TrialWorld, generation, who, trial)
}

/// The command a creature gets from `command`: itself when every field is finite, else None
/// (the creature stands still for that tick and its life is marked invalid). The one check
/// both evaluation paths apply, so that they agree to the bit.
#[inline]
#[allow(clippy::eq_op)] // x − x is the finiteness test, on purpose
pub(crate) fn finite_command(command: MotorCommand) -> Option<MotorCommand> {
    // x − x is 0 for a finite x and NaN for ±∞ and NaN, and a NaN term makes the sum NaN:
    // the three tests in one comparison, without a branch each.
    let (l, r, e) = (command.left, command.right, command.eat);
    ((l - l) + (r - r) + (e - e) == 0.0).then_some(command)
}

/// A controller that notices non-finite outputs instead of letting NaN reach the world: the
/// creature stands still for that tick and the life is marked invalid.
pub(crate) struct CheckedController<C> {
    pub(crate) inner: C,
    pub(crate) non_finite: bool,
}

impl<C: Controller> Controller for CheckedController<C> {
    fn act(&mut self, observation: &[f64]) -> MotorCommand {
        finite_command(self.inner.act(observation)).unwrap_or_else(|| {
            self.non_finite = true;
            MotorCommand::default()
        })
    }
}

/// Builds the controller of every genome of group `group` (errors name the individual).
pub(crate) fn controllers(
    plan: &TrialPlan,
    topology: &Topology,
    genomes: &[Genome],
    group: u64,
) -> Result<Vec<BrainController>, EvaluationError> {
    genomes
        .iter()
        .enumerate()
        .map(|(k, genome)| {
            let brain = Brain::new(topology, &genome.parameters).map_err(|error| {
                EvaluationError::Brain {
                    individual: group * genomes.len() as u64 + k as u64,
                    error,
                }
            })?;
            Ok(BrainController::new(
                brain,
                plan.creature.max_rpt,
                plan.creature.eats_by_action(),
            ))
        })
        .collect()
}

/// Builds trial `trial`'s world for `creatures` creatures of group `group`.
pub(crate) fn trial_world(
    plan: &TrialPlan,
    creatures: usize,
    generation: Generation,
    group: u64,
    trial: TrialIndex,
) -> Result<World, EvaluationError> {
    let specs = valid_specs(plan, generation, trial)?;
    build_trial_world(specs, plan, creatures, generation, group, trial)
}

/// The experiment's world and creature specifications, validated (the error names `trial`).
pub(crate) fn valid_specs<'a>(
    plan: &TrialPlan<'a>,
    generation: Generation,
    trial: TrialIndex,
) -> Result<ValidSpecs<'a>, EvaluationError> {
    ValidSpecs::new(plan.world, plan.creature)
        .map_err(|error| world_error(generation, trial, error))
}

/// [`trial_world`] from specifications validated once for several trials.
pub(crate) fn build_trial_world(
    specs: ValidSpecs<'_>,
    plan: &TrialPlan,
    creatures: usize,
    generation: Generation,
    group: u64,
    trial: TrialIndex,
) -> Result<World, EvaluationError> {
    let rng = trial_stream(plan, generation, group, trial);
    World::build(specs, creatures, rng).map_err(|error| world_error(generation, trial, error))
}

/// The error of a trial world that could not be placed.
pub(crate) fn world_error(
    generation: Generation,
    trial: TrialIndex,
    error: PlacementError,
) -> EvaluationError {
    EvaluationError::World {
        generation: generation.0,
        trial: trial.0,
        error,
    }
}

/// The score bookkeeping after one tick: every living creature whose life is still valid
/// (`invalid[i]` false) records the tick. Returns whether any did; when none did, the trial
/// is over (nothing it could still record).
/// What `plan` watches beyond the metabolism and the shock flag is recorded too, only when
/// it watches something.
#[inline]
pub(crate) fn record_tick(
    world: &World,
    invalid: &[bool],
    scores: &mut [LifeScore],
    plan: &LifePlan,
) -> bool {
    let mut anyone_alive = false;
    let watch = plan.needs_world_every_tick();
    for (i, ((creature, score), &invalid)) in world
        .creatures()
        .iter()
        .zip(scores)
        .zip(invalid)
        .enumerate()
    {
        if !invalid && creature.alive {
            score.record_tick(&creature.metabolism, creature.shocked);
            if watch {
                score.record_world(plan, world, i);
            }
            anyone_alive = true;
        }
    }
    anyone_alive
}

/// The plan of a trial in `world` and one fresh score per creature: what both evaluation
/// paths set up before the first tick (bite tracking and the event log turned on in `world`
/// when the plan needs them, [`LifePlan::prepare`]; the log only ever on, so a watcher's
/// switch made before stands).
pub(crate) fn start_scores(plan: &TrialPlan, world: &mut World) -> (LifePlan, Vec<LifeScore>) {
    let life_plan = LifePlan::new(plan, world);
    life_plan.prepare(world);
    let scores = (0..world.creatures().len())
        .map(|i| LifeScore::start(&life_plan, world, i))
        .collect();
    (life_plan, scores)
}

/// Every creature's outcome at the end of a trial.
pub(crate) fn outcomes(
    world: &World,
    scores: &[LifeScore],
    invalid: &[bool],
    plan: &LifePlan,
) -> Vec<TrialOutcome> {
    world
        .creatures()
        .iter()
        .zip(scores)
        .zip(invalid)
        .enumerate()
        .map(|(i, ((creature, score), &non_finite))| {
            let (score_value, measures) = score.finish_in(plan, world, i);
            TrialOutcome {
                score: score_value,
                metabolism: creature.metabolism,
                shocked_ticks: score.shocked_ticks(),
                non_finite,
                measures,
                area_ticks: score.described_area_ticks(),
            }
        })
        .collect()
}

/// One [`CheckedController`] per genome of group `group`, each told which life it lives
/// (trial `trial` of generation `generation`): a plastic brain with random initial weights
/// draws them from that life's stream ([`crate::brain::LifeKey`]); other brains ignore it.
pub(crate) fn checked_controllers(
    plan: &TrialPlan,
    topology: &Topology,
    genomes: &[Genome],
    group: u64,
    (generation, trial): (Generation, TrialIndex),
) -> Result<Vec<CheckedController<BrainController>>, EvaluationError> {
    let first = group * genomes.len() as u64;
    Ok(controllers(plan, topology, genomes, group)?
        .into_iter()
        .enumerate()
        .map(|(k, mut inner)| {
            inner.brain_mut().start_life(LifeKey {
                seed: plan.seed,
                generation,
                individual: IndividualId(first + k as u64),
                trial,
            });
            CheckedController {
                inner,
                non_finite: false,
            }
        })
        .collect())
}
