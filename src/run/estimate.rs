//! How long a run will take: its workload, counted from the experiment ([`Workload`]), and a
//! wall time on this machine from a short calibration ([`calibrate`]) that evaluates the
//! first few individuals of generation 0 exactly as the run will, on a thread pool of the
//! run's size, and times it.
//!
//! The calibration is deterministic work that changes nothing: it writes no file and draws
//! from no stream a run draws from afterwards (each trial's world comes from its own stream,
//! see `seed::stream`), so a run's files are the same bytes with or without it. Only the
//! printed estimate depends on the clock. It lives with the brains a run starts from;
//! evolved brains can live longer lives (creatures that die early end their trial early) or
//! shorter ones, which the estimate cannot know.

use crate::evo::door::{Evaluate, Worlds};
use crate::evo::evaluate::shared_worlds;
use crate::evo::life::EvaluationError;
use crate::evo::lockstep;
use crate::evo::search;
use crate::evo::TrialPlan;
use crate::experiment::Experiment;
use crate::seed::Generation;
use serde::Serialize;
use std::ops::Range;
use std::time::{Duration, Instant};
use thiserror::Error;

/// What a run (or the rest of one) evaluates, in creature-ticks: one creature living one
/// tick of one trial. Counts are nominal: a trial in which every creature has died ends
/// early and costs less.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Workload {
    /// Generations to evaluate.
    pub generations: u64,
    /// Individuals evaluated per generation (the search's; PGPE also evaluates its centre).
    pub individuals: u64,
    /// Trials per individual.
    pub trials: u64,
    /// Ticks per trial (per episode, when a life has several).
    pub ticks: u64,
    /// Episodes per life (`evaluation.episodes_per_life`; 1: a trial is one world).
    pub episodes: u64,
    /// Creatures sharing one trial world (`evaluation.group_size`).
    pub creatures_per_world: u64,
    /// individuals × trials × episodes × ticks.
    pub creature_ticks_per_generation: u64,
    /// Validation rounds among the generations (`[validation]`; 0 when off).
    pub validations: u64,
    /// Candidates evaluated per validation round, at most (the top individuals, and the
    /// search's own candidates, e.g. PGPE's centre).
    pub validation_candidates: u64,
    /// Validation worlds per candidate.
    pub validation_trials: u64,
    /// validations × candidates × validation trials × ticks.
    pub validation_creature_ticks: u64,
    /// generations × creature-ticks per generation + validation creature-ticks.
    pub total_creature_ticks: u64,
}

impl Workload {
    /// The workload of evaluating generations `generations` (e.g. `0..total` for a new run,
    /// `next..total` for a resumed one) of `experiment`.
    pub fn of(experiment: &Experiment, generations: Range<u64>) -> Workload {
        let total = experiment.evolution.generations;
        let count = generations.end.saturating_sub(generations.start);
        let e = &experiment.evaluation;
        let search = search::factory::of(experiment, &experiment.topology());
        let individuals = search.evaluated_per_generation() as u64;
        // A life of several episodes lives `ticks` in each of them.
        let life_ticks = e.ticks.saturating_mul(e.episodes_per_life);
        let per_generation = individuals
            .saturating_mul(e.trials)
            .saturating_mul(life_ticks);
        let v = &experiment.validation;
        let validations = if v.enabled() && count > 0 {
            // Rounds after every `every`-th generation, and after the run's last one.
            let multiples = generations.end / v.every - generations.start / v.every;
            let last = generations.end >= total && total % v.every != 0;
            multiples + u64::from(last)
        } else {
            0
        };
        let candidates = if v.enabled() {
            v.top + search.champion_candidates_per_generation() as u64
        } else {
            0
        };
        let validation_ticks = validations
            .saturating_mul(candidates)
            .saturating_mul(v.trials)
            .saturating_mul(life_ticks);
        Workload {
            generations: count,
            individuals,
            trials: e.trials,
            ticks: e.ticks,
            episodes: e.episodes_per_life,
            creatures_per_world: e.group_size,
            creature_ticks_per_generation: per_generation,
            validations,
            validation_candidates: candidates,
            validation_trials: if v.enabled() { v.trials } else { 0 },
            validation_creature_ticks: validation_ticks,
            total_creature_ticks: count
                .saturating_mul(per_generation)
                .saturating_add(validation_ticks),
        }
    }
}

/// What a calibration measured.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Calibration {
    /// Worker threads of the pool it ran on (the run's `--jobs`).
    pub threads: usize,
    /// Individuals of generation 0 it evaluated (the first ones).
    pub individuals: u64,
    /// Trials each lived.
    pub trials: u64,
    /// Ticks per trial (the experiment's, or fewer when one life is too long to time).
    pub ticks: u64,
    /// individuals × trials × ticks.
    pub creature_ticks: u64,
    /// Wall time of that evaluation, building its trial worlds left out when a generation
    /// builds them once for everybody (common random numbers), in seconds.
    pub seconds: f64,
    /// Wall time of building one generation's shared trial worlds (0 when every group
    /// builds its own, which `seconds` then includes), in seconds.
    pub world_seconds: f64,
    /// Wall time of the whole calibration, in seconds.
    pub elapsed_seconds: f64,
}

impl Calibration {
    /// Measured creature-ticks per second of wall time.
    pub fn rate(&self) -> f64 {
        self.creature_ticks as f64 / self.seconds
    }
}

/// A workload's estimated wall time.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Estimate {
    /// What is evaluated.
    pub workload: Workload,
    /// What the time is based on.
    pub calibration: Calibration,
    /// One generation's evaluation, in seconds.
    pub seconds_per_generation: f64,
    /// The validation rounds together, in seconds.
    pub validation_seconds: f64,
    /// The whole workload, in seconds (file writing, selection and variation left out:
    /// they are small next to evaluation).
    pub total_seconds: f64,
}

impl Estimate {
    /// Scales `calibration` to `workload`.
    pub fn new(workload: Workload, calibration: Calibration) -> Estimate {
        let per_tick = calibration.seconds / calibration.creature_ticks.max(1) as f64;
        let per_generation =
            calibration.world_seconds + per_tick * workload.creature_ticks_per_generation as f64;
        let validation = per_tick * workload.validation_creature_ticks as f64;
        Estimate {
            workload,
            calibration,
            seconds_per_generation: per_generation,
            validation_seconds: validation,
            total_seconds: per_generation * workload.generations as f64 + validation,
        }
    }
}

/// A calibration that could not run.
#[derive(Debug, Error)]
pub enum CalibrationError {
    /// The thread pool could not be built.
    #[error("cannot start {jobs} worker threads: {message}")]
    Threads {
        /// Threads asked for.
        jobs: usize,
        /// rayon's reason.
        message: String,
    },
    /// Evaluation failed (the run would fail the same way).
    #[error(transparent)]
    Evaluation(#[from] EvaluationError),
}

/// How long the calibration's last, measured evaluation should take for `inspect`: long
/// enough that the clock's and the scheduler's noise is small, short enough that the whole
/// calibration (a short probe, then growing evaluations whose sum is below twice the last)
/// stays well under a second.
pub const CALIBRATION_TARGET: Duration = Duration::from_millis(250);

/// The same for the note a run prints before it starts: it only has to tell minutes from
/// hours, and every run pays for it.
pub const RUN_CALIBRATION_TARGET: Duration = Duration::from_millis(100);

/// The calibration stops growing when its next evaluation would end later than this after
/// it started (it then uses the last one, even if shorter than the target): a busy machine
/// must not make it cost a second.
const CALIBRATION_BUDGET: f64 = 0.8;

/// Ticks of the probe that sizes the calibration.
const PROBE_TICKS: u64 = 40;

/// Times the evaluation of generation 0's first individuals on a pool of `jobs` threads (0:
/// one per core, as a run) and returns what it measured. Grows the number of individuals,
/// one group at first, until an evaluation lasts `target` (e.g. [`CALIBRATION_TARGET`]) or
/// the whole generation is timed; lives are shortened only when a single group's trials
/// would last longer than the target.
pub fn calibrate(
    experiment: &Experiment,
    jobs: usize,
    target: Duration,
) -> Result<Calibration, CalibrationError> {
    let started = Instant::now();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(jobs)
        .build()
        .map_err(|e| CalibrationError::Threads {
            jobs,
            message: e.to_string(),
        })?;
    pool.install(|| measure(experiment, target.as_secs_f64(), started))
        .map(|c| Calibration {
            threads: pool.current_num_threads(),
            ..c
        })
}

/// [`calibrate`]'s work, on the current pool.
fn measure(
    experiment: &Experiment,
    target: f64,
    started: Instant,
) -> Result<Calibration, CalibrationError> {
    let topology = experiment.topology();
    let k = experiment.evaluation.group_size.max(1) as usize;
    let search = search::factory::of(experiment, &topology);
    let all = search.evaluated_per_generation();
    let groups = (all / k).max(1);
    let genomes = search.first_genomes(groups * k);
    let (trials, ticks) = (experiment.evaluation.trials, experiment.evaluation.ticks);
    // The probe: one group, one trial, a few ticks, to see whether one group's full lives
    // fit in the target.
    let probe_ticks = ticks.min(PROBE_TICKS);
    let mut timed = None;
    if let Some(probe) = shortened(experiment, 1, probe_ticks) {
        let probe_seconds = time(|| {
            Evaluate::new(
                &probe,
                &topology,
                &genomes[..k],
                Worlds::Training(Generation(0)),
            )
            .run()
            .map(drop)
        })?;
        let per_tick = probe_seconds / (k as u64 * probe_ticks) as f64;
        if per_tick * (k as u64 * trials * ticks) as f64 > target && ticks > probe_ticks {
            // One group's lives alone last longer than the target: time shorter lives, in
            // at most one lockstep chunk of trials.
            let trials = trials.min(lockstep::CHUNK_TRIALS);
            let fit = (target / (per_tick * (k as u64 * trials) as f64)) as u64;
            timed = shortened(experiment, trials, fit.clamp(probe_ticks, ticks));
        }
    }
    let timed = timed.unwrap_or_else(|| experiment.clone());
    let (trials, ticks) = (timed.evaluation.trials, timed.evaluation.ticks);
    let world_seconds = if timed.evaluation.common_random_numbers {
        time(|| shared_worlds(&TrialPlan::new(&timed), k, Generation(0)).map(drop))?
    } else {
        0.0
    };
    let mut n = 1;
    loop {
        let seconds = time(|| {
            Evaluate::new(
                &timed,
                &topology,
                &genomes[..n * k],
                Worlds::Training(Generation(0)),
            )
            .run()
            .map(drop)
        })?;
        let lives = seconds - world_seconds;
        // Aim the next evaluation at the target (at most 8× as many), within the generation.
        let grow = (target / seconds.max(1e-6)).clamp(2.0, 8.0);
        let late = started.elapsed().as_secs_f64() + seconds * grow > CALIBRATION_BUDGET;
        if seconds >= target || n == groups || late {
            let episodes = timed.evaluation.episodes_per_life;
            let creature_ticks = (n * k) as u64 * trials * episodes * ticks;
            return Ok(Calibration {
                threads: 0,
                individuals: (n * k) as u64,
                trials,
                ticks,
                creature_ticks,
                // A clock step or a busy machine can make the lives look free: never below
                // a nanosecond per creature-tick.
                seconds: lives.max(creature_ticks as f64 * 1e-9),
                world_seconds,
                elapsed_seconds: started.elapsed().as_secs_f64(),
            });
        }
        n = ((n as f64 * grow).ceil() as usize).min(groups);
    }
}

/// `experiment` with `trials` trials of `ticks` ticks, validated again (`None` if that is
/// refused: the calibration then times the experiment's own lives).
fn shortened(experiment: &Experiment, trials: u64, ticks: u64) -> Option<Experiment> {
    experiment
        .with_overrides()
        .trials(trials)
        .ticks(ticks)
        .build()
        .ok()
}

/// Wall time of `work`, in seconds.
fn time(work: impl FnOnce() -> Result<(), EvaluationError>) -> Result<f64, EvaluationError> {
    let start = Instant::now();
    work()?;
    Ok(start.elapsed().as_secs_f64())
}

#[cfg(test)]
mod tests {
    use super::{calibrate, Estimate, Workload, RUN_CALIBRATION_TARGET};
    use crate::experiment::Experiment;
    use std::path::Path;

    fn experiment(extra: &str) -> Experiment {
        let text = format!(
            "name = \"w\"\nseed = 3\n[evolution]\npopulation = 8\ngenerations = 25\nelitism = 1\n\
             [evaluation]\ntrials = 3\nticks = 50\n{extra}"
        );
        Experiment::from_toml(&text, Path::new("w.toml")).unwrap()
    }

    #[test]
    fn workload_counts_generations_individuals_trials_ticks_and_validation() {
        let plain = Workload::of(&experiment(""), 0..25);
        assert_eq!(plain.creature_ticks_per_generation, 8 * 3 * 50);
        assert_eq!(plain.validations, 0);
        assert_eq!(plain.total_creature_ticks, 25 * 8 * 3 * 50);

        // Validation after generations 9, 19 and the last, 24 (0-based).
        let validated = experiment("[validation]\nevery = 10\ntop = 2\ntrials = 4\n");
        let w = Workload::of(&validated, 0..25);
        assert_eq!(w.validations, 3);
        assert_eq!(w.validation_creature_ticks, 3 * 2 * 4 * 50);
        assert_eq!(w.total_creature_ticks, 25 * 8 * 3 * 50 + 3 * 2 * 4 * 50);
        // Resumed at generation 15: rounds after 19 and 24 are left.
        assert_eq!(Workload::of(&validated, 15..25).validations, 2);
        assert_eq!(Workload::of(&validated, 15..25).generations, 10);
        // A run that ends on a multiple validates once after its last generation.
        let even = experiment("[validation]\nevery = 5\ntop = 1\ntrials = 1\n");
        assert_eq!(Workload::of(&even, 0..25).validations, 5);
        // Checked against the rule the run applies, generation by generation.
        for (first, every) in [(0, 10), (3, 7), (24, 4), (25, 10)] {
            let e = experiment(&format!("[validation]\nevery = {every}\n"));
            let due = (first..25)
                .filter(|&g| crate::evo::validation::is_due(&e.validation, g, 25))
                .count() as u64;
            assert_eq!(
                Workload::of(&e, first..25).validations,
                due,
                "{first} {every}"
            );
        }
    }

    #[test]
    fn pgpe_also_evaluates_its_centre() {
        let text = "name = \"p\"\nseed = 3\n[evolution]\nalgorithm = \"pgpe\"\npopulation = 8\n\
                    generations = 25\n[evaluation]\ntrials = 3\nticks = 50\n";
        let pgpe = Experiment::from_toml(text, Path::new("p.toml")).unwrap();
        let w = Workload::of(&pgpe, 0..25);
        assert_eq!(w.individuals, 9);
        assert_eq!(w.creature_ticks_per_generation, 9 * 3 * 50);
    }

    #[test]
    fn a_calibration_times_real_lives_and_scales_to_the_workload() {
        let e = experiment("");
        let c = calibrate(&e, 1, RUN_CALIBRATION_TARGET).unwrap();
        assert_eq!(c.threads, 1);
        assert!(c.individuals >= 1 && c.individuals <= 8, "{c:?}");
        assert_eq!((c.trials, c.ticks), (3, 50), "{c:?}");
        assert_eq!(c.creature_ticks, c.individuals * 3 * 50);
        assert!(c.seconds > 0.0 && c.elapsed_seconds < 1.0, "{c:?}");
        let estimate = Estimate::new(Workload::of(&e, 0..25), c);
        let per_tick = c.seconds / c.creature_ticks as f64;
        assert_eq!(
            estimate.seconds_per_generation,
            c.world_seconds + per_tick * (8 * 3 * 50) as f64
        );
        assert_eq!(
            estimate.total_seconds,
            25.0 * estimate.seconds_per_generation
        );
    }
}
