//! Evaluation: a genome's fitness, measured by living `trials` lives in trial worlds, and the
//! jobs a generation's evaluation splits into. Callers come through the one door,
//! [`crate::evo::door::Evaluate`]; this file holds what it is made of.
//!
//! One trial is a pure function of (the [`TrialPlan`], the genomes of one group, generation, group
//! index, trial index): its world comes from its own seed stream and it shares nothing with
//! other trials. (With common random numbers that stream does not depend on the group, so
//! [`PopulationJobs`] builds each trial world once and hands every group a clone: the same
//! world, built once instead of once per group.) The jobs run in parallel with rayon (with
//! MLPs, stateless or plastic, several trials of a group at once in lockstep, see
//! [`crate::evo::lockstep`]), are collected in index order and reduced serially, so the
//! result is the same bits for any number of threads, and the same as living one trial at a
//! time with [`crate::evo::trial::run_trial`]. The generation's jobs can run on this
//! process's threads ([`ThisProcess`]) or on other processes ([`Evaluator`]; the `mpi`
//! feature's ranks), with the same bits.

use crate::brain::genome::Genome;
use crate::brain::spec::Topology;
use crate::evo::episodes::LifeOrigin;
use crate::evo::life::{
    build_trial_world, checked_controllers, valid_specs, EvaluationError, TrialOutcome,
};
use crate::evo::lockstep;
use crate::evo::trial;
use crate::evo::trial_plan::TrialPlan;
use crate::experiment::{Aggregate, Experiment};
use crate::seed::{Generation, TrialIndex};
use crate::sim::metabolism::Metabolism;
use crate::sim::world::World;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// Jobs per leaf of rayon's split of a generation's job list: 1, so that a thread that runs
/// out of work can take any job not yet started. With rayon's default split a leaf holds
/// several jobs that one thread runs in turn, and at the end of a generation the other
/// thread idles while that leaf finishes. The results are collected in job order either way.
pub const JOBS_APART: usize = 1;

/// An individual's evaluation over all its trials.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Evaluation {
    /// The aggregated fitness; `None` when the brain produced a non-finite output in any
    /// trial (such an individual ranks below every other and is left out of statistics).
    pub fitness: Option<f64>,
    /// Mean over trials of the metabolic vector at the end of life (the per-food components
    /// kept alongside the score).
    pub metabolism: Metabolism,
    /// Mean over trials of each behaviour measure the experiment's `[behaviour]` names, in
    /// its order (empty when it names none, and then left out of checkpoints).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub measures: Vec<f64>,
    /// Mean over trials of the ticks alive in each area the search's descriptors name
    /// (`area = "..."`), in descriptor order (empty when they name none, and then left out
    /// of checkpoints).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub area_ticks: Vec<f64>,
}

impl Evaluation {
    /// The fitness used for selection: non-finite brains rank below everything.
    pub fn selection_fitness(&self) -> f64 {
        self.fitness.unwrap_or(f64::MIN)
    }
}

/// One trial for `genomes` (group `group`) in a given world: a clone of the trial's world
/// from [`shared_worlds`], or a world built beforehand from the stream at `origin` (the first
/// of the life's worlds).
pub(crate) fn run_trial_in(
    plan: &TrialPlan,
    topology: &Topology,
    genomes: &[Genome],
    group: u64,
    origin: LifeOrigin,
    world: World,
) -> Result<Vec<TrialOutcome>, EvaluationError> {
    let mut controllers = checked_controllers(
        plan,
        topology,
        genomes,
        group,
        (origin.generation, origin.trial),
    )?;
    if plan.episodes_per_life > 1 {
        let id = trial::TrialId {
            generation: origin.generation,
            group,
            trial: origin.trial,
        };
        let observer = trial::NoObserver;
        return Ok(trial::live_life(plan, Some(world), origin, id, &mut controllers, observer)?.0);
    }
    Ok(trial::live(
        plan,
        world,
        &mut controllers,
        trial::NoObserver,
    ))
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
    plan: &TrialPlan,
    creatures: usize,
    generation: Generation,
) -> Result<Option<Vec<World>>, EvaluationError> {
    if !plan.common_random_numbers {
        return Ok(None);
    }
    let trials = plan.trials;
    if trials == 0 {
        return Ok(Some(Vec::new()));
    }
    let specs = valid_specs(plan, generation, TrialIndex(0))?;
    (0..trials)
        .map(|t| build_trial_world(specs, plan, creatures, generation, 0, TrialIndex(t)))
        .collect::<Result<Vec<_>, _>>()
        .map(Some)
}

/// Combines an individual's trials (in trial order) into its evaluation.
pub fn aggregate(plan: &TrialPlan, trials: &[TrialOutcome]) -> Evaluation {
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
        Some(match plan.aggregate {
            Aggregate::Mean => trials.iter().map(|t| t.score).sum::<f64>() / n,
            Aggregate::Min => trials.iter().map(|t| t.score).fold(f64::INFINITY, f64::min),
        })
    };
    let measures = plan
        .behaviour
        .measures
        .iter()
        .map(|m| trials.iter().map(|t| t.measures[m.index()]).sum::<f64>() / n)
        .collect();
    let area_ticks = (0..plan.described_areas.len())
        .map(|k| trials.iter().map(|t| t.area_ticks[k]).sum::<f64>() / n)
        .collect();
    Evaluation {
        fitness,
        metabolism,
        measures,
        area_ticks,
    }
}

/// One evaluation job of a generation: a group's chunk of trials lived in lockstep
/// (stateless and plastic MLPs), or one (group, trial) pair.
#[derive(Debug, Clone, PartialEq)]
enum Job {
    /// Group `group`'s trials `trials`, in lockstep ([`lockstep::run_trials_in`]).
    Chunk {
        group: usize,
        trials: std::ops::Range<u64>,
    },
    /// Group `group`'s trial `trial` alone ([`trial::run_trial`]).
    Trial { group: usize, trial: u64 },
}

/// What one job returns: per trial of the job, in trial order, one outcome per genome of its
/// group.
pub type JobLives = Vec<Vec<TrialOutcome>>;

/// The evaluation jobs of one generation, numbered `0..len()`. Any job can run anywhere
/// ([`PopulationJobs::run`] is a pure function of the job's number, the experiment, the
/// population and the generation); [`PopulationJobs::reduce`] combines their results in job
/// order, so where and in which order they ran changes no bit. This is the seam between the
/// generation and where its work runs: this process's threads ([`ThisProcess`]) or, with the
/// `mpi` feature, other processes (`crate::evo::ranks`). The jobs live their trials by the
/// generation's [`TrialPlan`]; the experiment itself is kept only to be sent to other
/// processes, which resolve the same plan from it.
pub struct PopulationJobs<'a> {
    experiment: &'a Experiment,
    plan: TrialPlan<'a>,
    topology: &'a Topology,
    population: &'a [Genome],
    generation: Generation,
    shared: Option<Vec<World>>,
    jobs: Vec<Job>,
    on_job: JobDone<'a>,
}

impl<'a> PopulationJobs<'a> {
    /// The jobs of evaluating `population` as generation `generation`: with an MLP (stateless
    /// or plastic, [`lockstep::lanes`]) one per group and chunk of up to
    /// [`lockstep::CHUNK_TRIALS`] trials, otherwise one per (group, trial) pair; group-major.
    /// Resolves the generation's [`TrialPlan`] and builds the shared trial worlds once (see
    /// `shared_worlds`).
    pub fn new(
        experiment: &'a Experiment,
        topology: &'a Topology,
        population: &'a [Genome],
        generation: Generation,
    ) -> Result<Self, EvaluationError> {
        let plan = TrialPlan::new(experiment);
        let k = plan.group_size as usize;
        let trials = plan.trials;
        let groups = population.len() / k;
        let shared = shared_worlds(&plan, k, generation)?;
        let jobs = if let Some(lanes) = lockstep::lanes(topology) {
            let chunks = lockstep::chunks_for(lanes, trials);
            (0..groups)
                .flat_map(|group| {
                    chunks.iter().map(move |c| Job::Chunk {
                        group,
                        trials: c.clone(),
                    })
                })
                .collect()
        } else {
            (0..groups)
                .flat_map(|group| (0..trials).map(move |trial| Job::Trial { group, trial }))
                .collect()
        };
        Ok(PopulationJobs {
            experiment,
            plan,
            topology,
            population,
            generation,
            shared,
            jobs,
            on_job: None,
        })
    }

    /// The same jobs, calling `on_job` as each finishes (see [`JobDone`]).
    pub fn watched(self, on_job: JobDone<'a>) -> Self {
        PopulationJobs { on_job, ..self }
    }

    /// Tells the [`JobDone`] hook (if any) that `count` jobs finished, e.g. jobs another
    /// process ran.
    pub fn jobs_done(&self, count: usize) {
        if let Some(f) = self.on_job {
            (0..count).for_each(|_| f());
        }
    }

    /// The number of jobs.
    pub fn len(&self) -> usize {
        self.jobs.len()
    }

    /// True when there is no job (an empty population).
    pub fn is_empty(&self) -> bool {
        self.jobs.is_empty()
    }

    /// The experiment evaluated (what other processes rebuild the jobs from).
    pub fn experiment(&self) -> &'a Experiment {
        self.experiment
    }

    /// The population evaluated.
    pub fn population(&self) -> &'a [Genome] {
        self.population
    }

    /// The generation evaluated.
    pub fn generation(&self) -> Generation {
        self.generation
    }

    /// The shape of job `index`'s result: (trials, genomes per trial).
    pub fn shape(&self, index: usize) -> (usize, usize) {
        let k = self.plan.group_size as usize;
        match &self.jobs[index] {
            Job::Chunk { trials, .. } => ((trials.end - trials.start) as usize, k),
            Job::Trial { .. } => (1, k),
        }
    }

    /// Runs job `index` on the calling thread.
    pub fn run(&self, index: usize) -> Result<JobLives, EvaluationError> {
        let k = self.plan.group_size as usize;
        let shared = self.shared.as_deref();
        match &self.jobs[index] {
            Job::Chunk { group, trials } => lockstep::run_trials_in(
                &self.plan,
                self.topology,
                &self.population[group * k..(group + 1) * k],
                self.generation,
                *group as u64,
                trials.clone(),
                shared,
                LifeOrigin::trial(&self.plan, self.generation, *group as u64, TrialIndex(0)),
            ),
            Job::Trial { group, trial } => {
                let genomes = &self.population[group * k..(group + 1) * k];
                let lives = match shared {
                    Some(worlds) => {
                        let world = worlds[*trial as usize].clone();
                        let (generation, trial) = (self.generation, TrialIndex(*trial));
                        let origin =
                            LifeOrigin::trial(&self.plan, generation, *group as u64, trial);
                        run_trial_in(
                            &self.plan,
                            self.topology,
                            genomes,
                            *group as u64,
                            origin,
                            world,
                        )
                    }
                    None => trial::run_trial(
                        &self.plan,
                        self.topology,
                        genomes,
                        self.generation,
                        *group as u64,
                        TrialIndex(*trial),
                        trial::NoObserver,
                    ),
                }?;
                Ok(vec![lives])
            }
        }
    }

    /// Runs jobs `range` in parallel on the current rayon pool, one job per leaf of its split
    /// (see [`JOBS_APART`]); results in job order.
    pub fn run_range(
        &self,
        range: std::ops::Range<usize>,
    ) -> Result<Vec<JobLives>, EvaluationError> {
        range
            .into_par_iter()
            .with_max_len(JOBS_APART)
            .map(|index| {
                let lives = self.run(index);
                self.jobs_done(1);
                lives
            })
            .collect()
    }

    /// Every individual's lives from every job's result (`per_job[j]` is job j's): per
    /// individual, in population order, its trial outcomes in trial order.
    pub fn lives(&self, per_job: Vec<JobLives>) -> Vec<Vec<TrialOutcome>> {
        let k = self.plan.group_size as usize;
        let trials = self.plan.trials as usize;
        // outcomes[g * trials + t][i] is individual g*k + i's life in trial t.
        let outcomes: Vec<Vec<TrialOutcome>> = per_job.into_iter().flatten().collect();
        let mut lives = Vec::with_capacity(self.population.len());
        for group_trials in outcomes.chunks(trials) {
            for i in 0..k {
                lives.push(group_trials.iter().map(|outcome| outcome[i]).collect());
            }
        }
        lives
    }

    /// The population's evaluations from every job's result (`per_job[j]` is job j's), reduced
    /// serially in index order.
    pub fn reduce(&self, per_job: Vec<JobLives>) -> Vec<Evaluation> {
        self.lives(per_job)
            .iter()
            .map(|trials| aggregate(&self.plan, trials))
            .collect()
    }
}

/// Where a generation's jobs run. Every implementation returns each job's
/// [`PopulationJobs::run`] result, in job order; none may change a bit.
pub trait Evaluator {
    /// Runs all of `jobs` and returns their results in job order.
    fn run_jobs(&self, jobs: &PopulationJobs<'_>) -> Result<Vec<JobLives>, EvaluationError>;

    /// What it did so far, for the user (e.g. jobs per rank); `None`: nothing to say.
    fn report(&self) -> Option<String> {
        None
    }
}

/// Runs every job on this process's current rayon pool.
pub struct ThisProcess;

impl Evaluator for ThisProcess {
    fn run_jobs(&self, jobs: &PopulationJobs<'_>) -> Result<Vec<JobLives>, EvaluationError> {
        jobs.run_range(0..jobs.len())
    }
}

/// Told of each evaluation job as it finishes, from whichever worker thread ran it and in
/// any order (e.g. a progress bar within a generation). It only counts: results are still
/// collected in index order, so it cannot change them.
pub type JobDone<'a> = Option<&'a (dyn Fn() + Sync)>;

/// How many jobs a generation of `individuals` individuals splits into (what a
/// [`JobDone`] is called that many times for): per group, one per lockstep chunk of trials
/// with an MLP, one per trial otherwise (the jobs of [`PopulationJobs`]).
pub fn evaluation_jobs(experiment: &Experiment, topology: &Topology, individuals: usize) -> u64 {
    let groups = (individuals as u64) / experiment.evaluation.group_size.max(1);
    let trials = experiment.evaluation.trials;
    let per_group = if let Some(lanes) = lockstep::lanes(topology) {
        lockstep::chunks_for(lanes, trials).len() as u64
    } else {
        trials
    };
    groups.saturating_mul(per_group)
}
