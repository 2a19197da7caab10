//! The one evaluation door: a request ([`Evaluate`]: these genomes, in these worlds) answered
//! with their evaluations, their lives trial by trial, or, for lives of several episodes,
//! each life's per-episode choices. The generation loop, validation, `compare`, `summary`,
//! `bench`, the run's time estimate and the Python package all evaluate here, so one set of
//! worlds means the same lives wherever it is named.
//!
//! The worlds ([`Worlds`]) are a generation's training worlds met as the run meets them (in
//! groups, with the experiment's common random numbers; the only request whose jobs an
//! [`Evaluator`] may send to other processes), a named set's worlds met by each genome alone
//! ([`crate::evo::worlds::WorldSet`]: held-out, validation, design, or a generation's
//! training worlds), or worlds built beforehand. Every answer is collected in genome and
//! trial order and reduced serially: the same bits on any number of threads.

use crate::brain::genome::Genome;
use crate::brain::spec::Topology;
use crate::evo::episodes::{Life, LifeOrigin};
use crate::evo::evaluate::{
    aggregate, run_trial_in, Evaluation, Evaluator, JobDone, PopulationJobs, ThisProcess,
    JOBS_APART,
};
use crate::evo::life::{EvaluationError, TrialOutcome};
use crate::evo::lockstep;
use crate::evo::trial::{run_life, NoObserver, TrialId};
use crate::evo::trial_plan::TrialPlan;
use crate::evo::worlds::{BuiltWorlds, WorldSet, WorldsError};
use crate::experiment::Experiment;
use crate::seed::{Generation, TrialIndex};
use rayon::prelude::*;
use std::borrow::Cow;

/// Whose worlds the genomes of a request meet, and how.
#[derive(Debug, Clone, Copy)]
pub enum Worlds<'a> {
    /// Generation g's training worlds as the run evaluates that generation: genomes
    /// `i*k .. i*k + k` share group i's worlds (`[evaluation] group_size` k, its
    /// `common_random_numbers`). The genomes must fill their groups ([`Evaluate::check`]).
    Training(Generation),
    /// A set's worlds, each genome alone in every one of them (group 0, and numbered
    /// individual 0 as if it were the only genome: what `compare` and Python's
    /// `Experiment.evaluate` report for any set but the run's own training).
    Alone(WorldSet),
    /// Worlds built beforehand ([`WorldSet::build`]), genome i alone in every one of them
    /// and numbered individual i (validation's candidates, `summary`'s random genomes).
    Built(&'a BuiltWorlds),
}

impl Worlds<'static> {
    /// What a set name means when genomes are evaluated "on a set" (Python's `worlds=`): a
    /// generation's training worlds as the run meets them, any other set alone.
    pub fn of(set: WorldSet) -> Worlds<'static> {
        match set {
            WorldSet::Training(g) => Worlds::Training(Generation(g)),
            other => Worlds::Alone(other),
        }
    }
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

/// A request: `genomes` (brains of `topology`) evaluated under `experiment` in `worlds`,
/// optionally watched job by job. Its trials see only the experiment's [`TrialPlan`]; the
/// experiment itself names the world sets (validation's trials, held-out) and a
/// generation's jobs.
#[derive(Clone, Copy)]
pub struct Evaluate<'a> {
    experiment: &'a Experiment,
    plan: TrialPlan<'a>,
    topology: &'a Topology,
    genomes: &'a [Genome],
    worlds: Worlds<'a>,
    on_job: JobDone<'a>,
}

impl<'a> Evaluate<'a> {
    /// The request to evaluate `genomes` in `worlds` (resolves the experiment's
    /// [`TrialPlan`] once for all its trials).
    pub fn new(
        experiment: &'a Experiment,
        topology: &'a Topology,
        genomes: &'a [Genome],
        worlds: Worlds<'a>,
    ) -> Evaluate<'a> {
        Evaluate {
            experiment,
            plan: TrialPlan::new(experiment),
            topology,
            genomes,
            worlds,
            on_job: None,
        }
    }

    /// The same request, calling `on_job` as each job finishes (a progress bar within a
    /// generation; see [`JobDone`]). It only counts, so it cannot change a result.
    pub fn watched(self, on_job: JobDone<'a>) -> Evaluate<'a> {
        Evaluate { on_job, ..self }
    }

    /// Refuses what cannot be evaluated as asked: the validation worlds of an experiment
    /// without validation, training worlds for genomes that do not fill their groups.
    pub fn check(&self) -> Result<(), WorldsError> {
        match self.worlds {
            Worlds::Alone(set) => set.check(self.experiment),
            Worlds::Training(_) => {
                let k = self.plan.group_size.max(1);
                if self.genomes.len() as u64 % k != 0 {
                    return Err(WorldsError::PartialGroup {
                        genomes: self.genomes.len(),
                        group_size: k,
                    });
                }
                Ok(())
            }
            Worlds::Built(_) => Ok(()),
        }
    }

    /// Every genome's evaluation, in genome order, on this process's current rayon pool.
    pub fn run(&self) -> Result<Vec<Evaluation>, EvaluationError> {
        self.run_on(&ThisProcess)
    }

    /// Every genome's evaluation, in genome order, a generation's training jobs run by
    /// `evaluator` (e.g. MPI ranks; the same bits wherever they run). Other requests run on
    /// this process's current rayon pool: their worlds are no generation's jobs, which is
    /// all another process knows how to rebuild.
    pub fn run_on(&self, evaluator: &dyn Evaluator) -> Result<Vec<Evaluation>, EvaluationError> {
        if let Worlds::Training(generation) = self.worlds {
            let jobs = self.jobs(generation)?;
            let lives = evaluator.run_jobs(&jobs)?;
            return Ok(jobs.reduce(lives));
        }
        Ok(self
            .lives()?
            .iter()
            .map(|trials| aggregate(&self.plan, trials))
            .collect())
    }

    /// Every genome's lives: per genome, in genome order, its trial outcomes in trial order
    /// (on this process's current rayon pool).
    pub fn lives(&self) -> Result<Vec<Vec<TrialOutcome>>, EvaluationError> {
        match self.worlds {
            Worlds::Training(generation) => {
                let jobs = self.jobs(generation)?;
                let lives = ThisProcess.run_jobs(&jobs)?;
                Ok(jobs.lives(lives))
            }
            Worlds::Alone(_) | Worlds::Built(_) => {
                let built = self.built()?;
                self.alone_lives(&built)
            }
        }
    }

    /// [`Evaluate::lives`], each life with its episodes' choices (what `compare --json`
    /// reports for lives of several episodes).
    pub fn lives_by_episode(
        &self,
    ) -> Result<Vec<Vec<(TrialOutcome, LifeChoices)>>, EvaluationError> {
        let (k, trials, built) = match self.worlds {
            Worlds::Training(_) => {
                let k = self.plan.group_size.max(1) as usize;
                (k, self.plan.trials, None)
            }
            Worlds::Alone(_) | Worlds::Built(_) => {
                let built = self.built()?;
                (1, built.worlds.len() as u64, Some(built))
            }
        };
        let groups = self.genomes.len() / k;
        let pairs: Vec<(usize, u64)> = (0..groups)
            .flat_map(|g| (0..trials).map(move |t| (g, t)))
            .collect();
        let per_pair: Vec<Vec<(TrialOutcome, LifeChoices)>> = pairs
            .par_iter()
            .with_max_len(JOBS_APART)
            .map(|&(g, t)| {
                let trial = TrialIndex(t);
                let group = self.group_number(g);
                let (origin, first) = match &built {
                    Some(b) => (
                        b.origin.with_trial(trial),
                        Some(b.worlds[t as usize].clone()),
                    ),
                    None => {
                        let Worlds::Training(generation) = self.worlds else {
                            unreachable!("only training worlds are built trial by trial")
                        };
                        let origin = LifeOrigin::trial(&self.plan, generation, group, trial);
                        (origin, None)
                    }
                };
                let id = TrialId {
                    generation: origin.generation,
                    group,
                    trial,
                };
                let genomes = &self.genomes[g * k..(g + 1) * k];
                let (outcomes, episodes) = run_life(
                    &self.plan,
                    self.topology,
                    genomes,
                    id,
                    origin,
                    first,
                    NoObserver,
                )?;
                self.job_done();
                let life = Life::new(&self.plan, origin);
                Ok(outcomes
                    .into_iter()
                    .zip(&episodes)
                    .map(|(o, e)| {
                        let choices = LifeChoices {
                            switches: life.schedule().switches(),
                            exchanged: life.schedule().exchanged.clone(),
                            correct_first_choice: life.correct_choices(e),
                        };
                        (o, choices)
                    })
                    .collect())
            })
            .collect::<Result<_, EvaluationError>>()?;
        // per_pair[g * trials + t][i] is genome g*k + i's life t.
        let mut lives = vec![Vec::with_capacity(trials as usize); self.genomes.len()];
        for (pair, (g, _)) in per_pair.into_iter().zip(&pairs) {
            for (i, life) in pair.into_iter().enumerate() {
                lives[g * k + i].push(life);
            }
        }
        Ok(lives)
    }

    /// The jobs of evaluating the genomes as generation `generation`.
    fn jobs(&self, generation: Generation) -> Result<PopulationJobs<'a>, EvaluationError> {
        Ok(
            PopulationJobs::new(self.experiment, self.topology, self.genomes, generation)?
                .watched(self.on_job),
        )
    }

    /// The worlds of a request whose genomes meet them alone: built here for a set, or the
    /// ones given.
    fn built(&self) -> Result<Cow<'a, BuiltWorlds>, EvaluationError> {
        match self.worlds {
            Worlds::Alone(set) => Ok(Cow::Owned(set.build(self.experiment)?)),
            Worlds::Built(built) => Ok(Cow::Borrowed(built)),
            Worlds::Training(_) => unreachable!("training worlds are met in groups"),
        }
    }

    /// The group number of genome (or group) `g`: it numbers the individuals (their brains'
    /// per-life draws, the errors) and, for training worlds without common random numbers,
    /// chooses the worlds.
    fn group_number(&self, g: usize) -> u64 {
        match self.worlds {
            Worlds::Alone(_) => 0,
            Worlds::Training(_) | Worlds::Built(_) => g as u64,
        }
    }

    /// Tells the watcher (if any) that a job finished.
    fn job_done(&self) {
        if let Some(f) = self.on_job {
            f();
        }
    }

    /// Each genome alone in every one of `built`'s worlds, with the same trial path as
    /// evolution (lockstep for MLPs, stateless or plastic), every (genome, job) pair in parallel and
    /// collected in order.
    fn alone_lives(&self, built: &BuiltWorlds) -> Result<Vec<Vec<TrialOutcome>>, EvaluationError> {
        let (plan, topology, genomes) = (&self.plan, self.topology, self.genomes);
        let worlds = &built.worlds[..];
        let origin = built.origin;
        let trials = worlds.len() as u64;
        if let Some(lanes) = lockstep::lanes(topology) {
            let chunks = lockstep::chunks_for(lanes, trials);
            let jobs: Vec<(usize, std::ops::Range<u64>)> = (0..genomes.len())
                .flat_map(|g| chunks.iter().map(move |c| (g, c.clone())))
                .collect();
            let per_job: Vec<Vec<Vec<TrialOutcome>>> = jobs
                .par_iter()
                .with_max_len(JOBS_APART)
                .map(|(g, chunk)| {
                    let lives = lockstep::run_trials_in(
                        plan,
                        topology,
                        std::slice::from_ref(&genomes[*g]),
                        Generation(0),
                        self.group_number(*g),
                        chunk.clone(),
                        Some(worlds),
                        origin,
                    );
                    self.job_done();
                    lives
                })
                .collect::<Result<_, _>>()?;
            let mut lives: Vec<Vec<TrialOutcome>> = vec![Vec::new(); genomes.len()];
            for ((g, _), job) in jobs.iter().zip(per_job) {
                lives[*g].extend(job.into_iter().map(|o| o[0]));
            }
            return Ok(lives);
        }
        let jobs: Vec<(usize, usize)> = (0..genomes.len())
            .flat_map(|g| (0..worlds.len()).map(move |t| (g, t)))
            .collect();
        let outcomes: Vec<TrialOutcome> = jobs
            .par_iter()
            .with_max_len(JOBS_APART)
            .map(|&(g, t)| {
                let life = run_trial_in(
                    plan,
                    topology,
                    std::slice::from_ref(&genomes[g]),
                    self.group_number(g),
                    origin.with_trial(TrialIndex(t as u64)),
                    worlds[t].clone(),
                )
                .map(|o| o[0]);
                self.job_done();
                life
            })
            .collect::<Result<_, _>>()?;
        Ok(outcomes
            .chunks(worlds.len().max(1))
            .take(genomes.len())
            .map(<[TrialOutcome]>::to_vec)
            .collect())
    }
}
