//! Evaluation: a genome's fitness, measured by living `trials` lives in trial worlds.
//!
//! One trial is a pure function of (experiment, the genomes of one group, generation, group
//! index, trial index): its world comes from its own seed stream and it shares nothing with
//! other trials. (With common random numbers that stream does not depend on the group, so
//! [`evaluate_population`] builds each trial world once and hands every group a clone: the
//! same world, built once instead of once per group.) [`evaluate_population`] runs all (group, trial) pairs in parallel with rayon
//! (with stateless brains, several trials of a group at once in lockstep, see
//! [`crate::evo::lockstep`]), collects them in index order and reduces them serially, so the
//! result is the same bits for any number of threads, and the same as evaluating one group at
//! a time with [`evaluate_group`] (which a later distributed runner can call on another
//! machine).

use crate::brain::genome::Genome;
use crate::brain::spec::Topology;
use crate::brain::{Brain, BrainController};
use crate::evo::fitness::{LifePlan, LifeScore, MEASURE_COUNT};
use crate::evo::lockstep;
use crate::experiment::{Aggregate, Experiment};
use crate::seed::{stream, Generation, IndividualId, Purpose, Rng, TrialIndex};
use crate::sim::controller::{Controller, MotorCommand};
use crate::sim::world::{ValidSpecs, World};
use crate::sim::PlacementError;

/// Jobs per leaf of rayon's split of a generation's job list: 1, so that a thread that runs
/// out of work can take any job not yet started. With rayon's default split a leaf holds
/// several jobs that one thread runs in turn, and at the end of a generation the other
/// thread idles while that leaf finishes. The results are collected in job order either way.
pub const JOBS_APART: usize = 1;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
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
}

/// One individual's life in one trial world.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrialOutcome {
    /// The trial's score under `[fitness]`.
    pub score: f64,
    /// The metabolic vector at the end of life.
    pub metabolism: [f64; 4],
    /// Ticks on which the shock sensor was on.
    pub shocked_ticks: u64,
    /// True when the brain produced a NaN or infinite output: the life was stopped.
    pub non_finite: bool,
    /// The behaviour measures, one per [`crate::experiment::MEASURES`] entry (0 for those
    /// the experiment's `[behaviour]` does not name).
    pub measures: [f64; MEASURE_COUNT],
}

/// An individual's evaluation over all its trials.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Evaluation {
    /// The aggregated fitness; `None` when the brain produced a non-finite output in any
    /// trial (such an individual ranks below every other and is left out of statistics).
    pub fitness: Option<f64>,
    /// Mean over trials of the metabolic vector at the end of life (the per-food components
    /// kept alongside the score).
    pub metabolism: [f64; 4],
    /// Mean over trials of each behaviour measure the experiment's `[behaviour]` names, in
    /// its order (empty when it names none, and then left out of checkpoints).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub measures: Vec<f64>,
}

impl Evaluation {
    /// The fitness used for selection: non-finite brains rank below everything.
    pub fn selection_fitness(&self) -> f64 {
        self.fitness.unwrap_or(f64::MIN)
    }
}

/// The random stream that builds trial `trial` of generation `generation` for `group`.
/// With common random numbers every group of a generation gets the same stream.
pub fn trial_stream(
    experiment: &Experiment,
    generation: Generation,
    group: u64,
    trial: TrialIndex,
) -> Rng {
    let who = if experiment.evaluation.common_random_numbers {
        IndividualId(0)
    } else {
        IndividualId(group)
    };
    stream(
        experiment.seed(),
        Purpose::TrialWorld,
        generation,
        who,
        trial,
    )
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
    experiment: &Experiment,
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
                experiment.creature.max_rpt,
                experiment.creature.eats_by_action(),
            ))
        })
        .collect()
}

/// Builds trial `trial`'s world for `creatures` creatures of group `group`.
pub(crate) fn trial_world(
    experiment: &Experiment,
    creatures: usize,
    generation: Generation,
    group: u64,
    trial: TrialIndex,
) -> Result<World, EvaluationError> {
    let specs = valid_specs(experiment, generation, trial)?;
    build_trial_world(specs, experiment, creatures, generation, group, trial)
}

/// The experiment's world and creature specifications, validated (the error names `trial`).
pub(crate) fn valid_specs(
    experiment: &Experiment,
    generation: Generation,
    trial: TrialIndex,
) -> Result<ValidSpecs<'_>, EvaluationError> {
    ValidSpecs::new(&experiment.world, &experiment.creature)
        .map_err(|error| world_error(generation, trial, error))
}

/// [`trial_world`] from specifications validated once for several trials.
pub(crate) fn build_trial_world(
    specs: ValidSpecs<'_>,
    experiment: &Experiment,
    creatures: usize,
    generation: Generation,
    group: u64,
    trial: TrialIndex,
) -> Result<World, EvaluationError> {
    let rng = trial_stream(experiment, generation, group, trial);
    World::build(specs, creatures, rng).map_err(|error| world_error(generation, trial, error))
}

fn world_error(
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
/// paths set up before the first tick (bite tracking turned on in `world` when needed).
pub(crate) fn start_scores(
    experiment: &Experiment,
    world: &mut World,
) -> (LifePlan, Vec<LifeScore>) {
    let plan = LifePlan::new(experiment, world);
    plan.prepare(world);
    let scores = (0..world.creatures().len())
        .map(|i| LifeScore::start(&plan, world, i))
        .collect();
    (plan, scores)
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
            }
        })
        .collect()
}

/// Lives one trial for a group of genomes sharing one world; returns one outcome per genome.
/// Builds one brain per genome for this trial alone and steps the world tick by tick (the
/// path for brains with state; [`crate::evo::lockstep`] gives the same bits for stateless
/// ones).
pub fn run_trial(
    experiment: &Experiment,
    topology: &Topology,
    genomes: &[Genome],
    generation: Generation,
    group: u64,
    trial: TrialIndex,
) -> Result<Vec<TrialOutcome>, EvaluationError> {
    // The brains first, then the world, so that a bad genome is reported before a world
    // that cannot be built, as everywhere.
    let mut controllers = checked_controllers(experiment, topology, genomes, group)?;
    let world = trial_world(experiment, genomes.len(), generation, group, trial)?;
    Ok(live_trial(experiment, world, &mut controllers))
}

/// [`run_trial`] in a given world: a clone of the trial's world from [`shared_worlds`].
fn run_trial_in(
    experiment: &Experiment,
    topology: &Topology,
    genomes: &[Genome],
    group: u64,
    world: World,
) -> Result<Vec<TrialOutcome>, EvaluationError> {
    let mut controllers = checked_controllers(experiment, topology, genomes, group)?;
    Ok(live_trial(experiment, world, &mut controllers))
}

/// One [`CheckedController`] per genome of group `group`.
fn checked_controllers(
    experiment: &Experiment,
    topology: &Topology,
    genomes: &[Genome],
    group: u64,
) -> Result<Vec<CheckedController<BrainController>>, EvaluationError> {
    Ok(controllers(experiment, topology, genomes, group)?
        .into_iter()
        .map(|inner| CheckedController {
            inner,
            non_finite: false,
        })
        .collect())
}

/// The trial worlds of generation `generation`, built once, when every group lives the same
/// ones (common random numbers: the world of trial t comes from a stream that does not
/// depend on the group), for groups of `creatures`; `None` otherwise. A job then clones its
/// trial's world, which is the very world it would have built (random stream state
/// included), instead of building it: building costs as much as a few hundred ticks (the
/// placement draws and the index, its smell grid above all), and a population of 64 would
/// build every trial world 64 times. Built in trial order, so a world that cannot be built
/// is reported for the first such trial.
pub(crate) fn shared_worlds(
    experiment: &Experiment,
    creatures: usize,
    generation: Generation,
) -> Result<Option<Vec<World>>, EvaluationError> {
    if !experiment.evaluation.common_random_numbers {
        return Ok(None);
    }
    let trials = experiment.evaluation.trials;
    if trials == 0 {
        return Ok(Some(Vec::new()));
    }
    let specs = valid_specs(experiment, generation, TrialIndex(0))?;
    (0..trials)
        .map(|t| build_trial_world(specs, experiment, creatures, generation, 0, TrialIndex(t)))
        .collect::<Result<Vec<_>, _>>()
        .map(Some)
}

/// Steps `world` for at most `ticks` ticks with `controllers` (one per creature), stopping
/// after the first tick in which no creature recorded a score.
pub(crate) fn live_trial<C: Controller>(
    experiment: &Experiment,
    mut world: World,
    controllers: &mut [CheckedController<C>],
) -> Vec<TrialOutcome> {
    let (plan, mut scores) = start_scores(experiment, &mut world);
    let mut invalid = vec![false; controllers.len()];
    for _ in 0..experiment.evaluation.ticks {
        world.step(controllers);
        for (flag, controller) in invalid.iter_mut().zip(controllers.iter()) {
            *flag = controller.non_finite;
        }
        if !record_tick(&world, &invalid, &mut scores, &plan) {
            break;
        }
    }
    outcomes(&world, &scores, &invalid, &plan)
}

/// Combines an individual's trials (in trial order) into its evaluation.
pub fn aggregate(experiment: &Experiment, trials: &[TrialOutcome]) -> Evaluation {
    let n = trials.len() as f64;
    let mut metabolism = [0.0; 4];
    for t in trials {
        for (m, x) in metabolism.iter_mut().zip(t.metabolism) {
            *m += x;
        }
    }
    for m in &mut metabolism {
        *m /= n;
    }
    let fitness = if trials.iter().any(|t| t.non_finite || !t.score.is_finite()) {
        None
    } else {
        Some(match experiment.evaluation.aggregate {
            Aggregate::Mean => trials.iter().map(|t| t.score).sum::<f64>() / n,
            Aggregate::Min => trials.iter().map(|t| t.score).fold(f64::INFINITY, f64::min),
        })
    };
    let measures = experiment
        .behaviour
        .measures
        .iter()
        .map(|m| trials.iter().map(|t| t.measures[m.index()]).sum::<f64>() / n)
        .collect();
    Evaluation {
        fitness,
        metabolism,
        measures,
    }
}

/// Evaluates one group (individuals `group*k .. group*k + k`) serially, trial by trial.
pub fn evaluate_group(
    experiment: &Experiment,
    topology: &Topology,
    genomes: &[Genome],
    generation: Generation,
    group: u64,
) -> Result<Vec<Evaluation>, EvaluationError> {
    let mut per_individual: Vec<Vec<TrialOutcome>> = vec![Vec::new(); genomes.len()];
    for t in 0..experiment.evaluation.trials {
        let outcomes = run_trial(
            experiment,
            topology,
            genomes,
            generation,
            group,
            TrialIndex(t),
        )?;
        for (list, outcome) in per_individual.iter_mut().zip(outcomes) {
            list.push(outcome);
        }
    }
    Ok(per_individual
        .iter()
        .map(|trials| aggregate(experiment, trials))
        .collect())
}

/// Evaluates a whole population in parallel on the current rayon pool. With a stateless
/// brain (an MLP), each job is one group and a chunk of up to
/// [`lockstep::CHUNK_TRIALS`] of its trials run in lockstep ([`lockstep::run_trials`]: one
/// brain per genome, batched over the chunk's worlds); otherwise each (group, trial) pair is
/// one job ([`run_trial`]). Either way, results are collected in index order and aggregated
/// serially, so they are the same bits on any number of threads and on either path.
pub fn evaluate_population(
    experiment: &Experiment,
    topology: &Topology,
    population: &[Genome],
    generation: Generation,
) -> Result<Vec<Evaluation>, EvaluationError> {
    let k = experiment.evaluation.group_size as usize;
    let trials = experiment.evaluation.trials;
    let groups = population.len() / k;
    let shared = shared_worlds(experiment, k, generation)?;
    let shared = shared.as_deref();
    // outcomes[g * trials + t][i] is individual g*k + i's life in trial t.
    let outcomes: Vec<Vec<TrialOutcome>> = if lockstep::stateless(topology) {
        let chunks = lockstep::chunks(trials);
        let jobs: Vec<(usize, std::ops::Range<u64>)> = (0..groups)
            .flat_map(|g| chunks.iter().map(move |c| (g, c.clone())))
            .collect();
        // One job per leaf of rayon's split (see JOBS_APART).
        let per_job: Vec<Vec<Vec<TrialOutcome>>> = jobs
            .par_iter()
            .with_max_len(JOBS_APART)
            .map(|(g, chunk)| {
                lockstep::run_trials_in(
                    experiment,
                    topology,
                    &population[g * k..(g + 1) * k],
                    generation,
                    *g as u64,
                    chunk.clone(),
                    shared,
                )
            })
            .collect::<Result<_, _>>()?;
        per_job.into_iter().flatten().collect()
    } else {
        let jobs: Vec<(usize, u64)> = (0..groups)
            .flat_map(|g| (0..trials).map(move |t| (g, t)))
            .collect();
        jobs.par_iter()
            .with_max_len(JOBS_APART)
            .map(|&(g, t)| {
                let genomes = &population[g * k..(g + 1) * k];
                match shared {
                    Some(worlds) => {
                        let world = worlds[t as usize].clone();
                        run_trial_in(experiment, topology, genomes, g as u64, world)
                    }
                    None => run_trial(
                        experiment,
                        topology,
                        genomes,
                        generation,
                        g as u64,
                        TrialIndex(t),
                    ),
                }
            })
            .collect::<Result<_, _>>()?
    };
    // Serial reduction in index order.
    let mut evaluations = Vec::with_capacity(population.len());
    let mut trial_list = Vec::with_capacity(trials as usize);
    for group_trials in outcomes.chunks(trials as usize) {
        for i in 0..k {
            trial_list.clear();
            trial_list.extend(group_trials.iter().map(|outcome| outcome[i]));
            evaluations.push(aggregate(experiment, &trial_list));
        }
    }
    Ok(evaluations)
}

/// Builds `trials` worlds for one creature each from `rng_of(t)`, in trial order (e.g. the
/// validation worlds, or `compare`'s held-out worlds), validating the specifications once.
pub fn worlds_from(
    experiment: &Experiment,
    trials: u64,
    generation: Generation,
    rng_of: impl Fn(TrialIndex) -> Rng,
) -> Result<Vec<World>, EvaluationError> {
    if trials == 0 {
        return Ok(Vec::new());
    }
    let specs = valid_specs(experiment, generation, TrialIndex(0))?;
    (0..trials)
        .map(|t| {
            World::build(specs, 1, rng_of(TrialIndex(t)))
                .map_err(|error| world_error(generation, TrialIndex(t), error))
        })
        .collect()
}

/// Evaluates each of `genomes` alone in every one of `worlds` (built for one creature, e.g.
/// by [`worlds_from`]), in parallel on the current rayon pool, with the same trial path as
/// evolution (lockstep for stateless brains). Results in genome order, each aggregated
/// serially over the worlds in order: the same bits for any number of threads.
pub fn evaluate_in_worlds(
    experiment: &Experiment,
    topology: &Topology,
    genomes: &[Genome],
    worlds: &[World],
) -> Result<Vec<Evaluation>, EvaluationError> {
    let trials = worlds.len() as u64;
    let per_genome: Vec<Vec<TrialOutcome>> = if lockstep::stateless(topology) {
        let chunks = lockstep::chunks(trials);
        let jobs: Vec<(usize, std::ops::Range<u64>)> = (0..genomes.len())
            .flat_map(|g| chunks.iter().map(move |c| (g, c.clone())))
            .collect();
        let per_job: Vec<Vec<Vec<TrialOutcome>>> = jobs
            .par_iter()
            .with_max_len(JOBS_APART)
            .map(|(g, chunk)| {
                lockstep::run_trials_in(
                    experiment,
                    topology,
                    std::slice::from_ref(&genomes[*g]),
                    Generation(0),
                    *g as u64,
                    chunk.clone(),
                    Some(worlds),
                )
            })
            .collect::<Result<_, _>>()?;
        let mut lives: Vec<Vec<TrialOutcome>> = vec![Vec::new(); genomes.len()];
        for ((g, _), job) in jobs.iter().zip(per_job) {
            lives[*g].extend(job.into_iter().map(|o| o[0]));
        }
        lives
    } else {
        let jobs: Vec<(usize, usize)> = (0..genomes.len())
            .flat_map(|g| (0..worlds.len()).map(move |t| (g, t)))
            .collect();
        let outcomes: Vec<TrialOutcome> = jobs
            .par_iter()
            .with_max_len(JOBS_APART)
            .map(|&(g, t)| {
                run_trial_in(
                    experiment,
                    topology,
                    std::slice::from_ref(&genomes[g]),
                    g as u64,
                    worlds[t].clone(),
                )
                .map(|o| o[0])
            })
            .collect::<Result<_, _>>()?;
        outcomes
            .chunks(worlds.len().max(1))
            .map(<[TrialOutcome]>::to_vec)
            .collect()
    };
    Ok(per_genome
        .iter()
        .map(|lives| aggregate(experiment, lives))
        .collect())
}
