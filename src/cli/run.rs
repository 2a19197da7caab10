//! `berry-evolve run`: start a new run of an experiment.

use crate::cli::console::errln;

use super::check;
use super::cluster::{evaluator, Ranks};
use super::estimate;
use super::progress::reporter;
use super::run_report::{self, CheckRequest};
use anyhow::Context;
use berry_evolve::experiment::{Experiment, ExperimentError};
use berry_evolve::record::fitness_csv::FitnessRow;
use berry_evolve::run::{start, JobHook, Progress, RunOptions};
use berry_evolve::validate::InvalidValue;
use clap::Args;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// Arguments of `run` (also accepted without the word `run`).
#[derive(Debug, Args)]
pub struct RunArgs {
    /// The experiment file (TOML).
    pub experiment: PathBuf,
    /// Run folder (default: results/<name>/seed-<seed>/).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Override the experiment's seed.
    #[arg(long, conflicts_with = "seeds")]
    pub seed: Option<u64>,
    /// Replicates: run these seeds one after another, each in its own run folder
    /// `<out>/seed-<s>/` (default out: results/<name>/), each byte-identical to a `--seed s`
    /// run. `1..10` is 1 to 10 inclusive; `1,3,5` a list. A seed whose folder already holds
    /// a run is continued from its checkpoint (unless --force), so the same command finishes
    /// an interrupted batch. Summarise with `berry-evolve summary <out>`.
    #[arg(long)]
    pub seeds: Option<String>,
    /// Override the number of generations.
    #[arg(long)]
    pub generations: Option<u64>,
    // Not `#[command(flatten)] ExecutionArgs`: clap leaves the top-level `Option<RunArgs>`
    // (the bare `berry-evolve FILE` form) as None when it holds a nested flatten.
    /// Worker threads, 1 to 1024 (default: one per core). Results do not depend on it. Under
    /// `mpirun -np N` (a build with the `mpi` feature): threads per rank, and the generation's
    /// evaluation is split across the N ranks, with the same results (docs/scale-out.md).
    #[arg(long, value_parser = parse_jobs)]
    pub jobs: Option<usize>,
    /// Print nothing but errors.
    #[arg(long, short)]
    pub quiet: bool,
    /// Replace a run already in the run folder: removes only the run's own files (its
    /// experiment.toml, fitness.csv, best.json, checkpoints, config-changes.log) and says which.
    #[arg(long)]
    pub force: bool,
    /// At the end, print one JSON document on stdout instead of the text summary (schema
    /// `berry-evolve/run/1`: status done or interrupted, run folder, generations done, best
    /// and validation fitness, best.json, resume command, the held-out check `check` and the
    /// commands to look at the champion `look`; with --seeds
    /// `berry-evolve/run-seeds/1`, one such entry per seed). Progress stays on stderr; --quiet
    /// silences it but not the document.
    #[arg(long)]
    pub json: bool,
    /// Before the first generation, a run times a few of its own evaluations (under a
    /// second; results do not depend on it) and prints its estimated wall time; above an hour
    /// it warns on stderr (also with --quiet) and starts anyway. This flag skips both.
    #[arg(long)]
    pub no_estimate: bool,
    /// Skip the held-out check at the end: the champion (best.json) against 5 random genomes
    /// and the experiment's baseline (`[output] baseline`) on up to 10 worlds evolution never
    /// saw, costing at most 3% of the run (`compare` gives the full comparison). Not made
    /// with --quiet unless --json; with --json it is the document's `check` field.
    #[arg(long)]
    pub no_check: bool,
}

/// How a resumed run executes; none of it changes the results.
#[derive(Debug, Args)]
pub struct ExecutionArgs {
    /// Worker threads, 1 to 1024 (default: one per core). Results do not depend on it. Under
    /// `mpirun -np N` (a build with the `mpi` feature): threads per rank, any N.
    #[arg(long, value_parser = parse_jobs)]
    pub jobs: Option<usize>,
    /// Print nothing but errors.
    #[arg(long, short)]
    pub quiet: bool,
    /// Skip the held-out check at the end (see `run --help`).
    #[arg(long)]
    pub no_check: bool,
}

/// The most worker threads `--jobs` accepts (a thread per core is the useful most; far more
/// only costs start-up time and memory).
pub const MAX_JOBS: usize = 1024;

/// `--jobs`: 1 to [`MAX_JOBS`].
pub(crate) fn parse_jobs(text: &str) -> Result<usize, String> {
    let jobs: usize = text
        .parse()
        .map_err(|_| format!("`{text}` is not a whole number of threads"))?;
    if !(1..=MAX_JOBS).contains(&jobs) {
        return Err(format!(
            "must be between 1 and {MAX_JOBS} worker threads (leave it out for one per core)"
        ));
    }
    Ok(jobs)
}

/// What the handler of a second signal tells the user about the run folder.
pub struct Interrupting {
    /// The run folder.
    pub dir: PathBuf,
    /// How to start the run over when it has no checkpoint yet.
    pub start_over: String,
}

/// What stopping at once leaves: the newest checkpoint to resume, or nothing.
fn stopping_now(at: Option<&Interrupting>) -> String {
    let Some(at) = at else {
        return "stopping now".to_string();
    };
    let newest = berry_evolve::record::checkpoint::list_checkpoints(
        &at.dir.join(berry_evolve::run::CHECKPOINT_DIR),
    )
    .ok()
    .and_then(|mut v| v.pop());
    match newest {
        Some((_, path)) => format!(
            "stopping now; the last checkpoint, {}, is intact. Continue with: {} resume {}",
            path.display(),
            berry_evolve::invocation::program(),
            at.dir.display()
        ),
        None => format!(
            "stopping now, before the first checkpoint: there is nothing to resume. Start again with: {}",
            at.start_over
        ),
    }
}

/// Installs a Ctrl-C / SIGTERM handler: the first signal asks the run to stop after the
/// current generation (with a checkpoint); the second stops at once.
pub fn stop_flag(at: Option<Interrupting>) -> anyhow::Result<Arc<AtomicBool>> {
    let flag = Arc::new(AtomicBool::new(false));
    let handler_flag = flag.clone();
    ctrlc::set_handler(move || {
        if handler_flag.swap(true, Ordering::SeqCst) {
            errln!("\n{}", stopping_now(at.as_ref()));
            std::process::exit(130);
        }
        errln!("\nstopping after this generation (press Ctrl-C again to stop at once)");
    })
    .context("cannot install the Ctrl-C handler")?;
    Ok(flag)
}

/// Runs the subcommand.
pub fn run(args: RunArgs, ranks: Option<&Ranks>) -> anyhow::Result<()> {
    if let Some(spec) = &args.seeds {
        let seeds = parse_seeds(spec)?;
        return run_seeds(&args, &seeds, ranks);
    }
    let mut overrides = Experiment::load(&args.experiment)?.with_overrides();
    if let Some(seed) = args.seed {
        overrides = overrides.seed(seed);
    }
    if let Some(g) = args.generations {
        overrides = overrides.generations(g);
    }
    let experiment = overrides.build().with_context(|| {
        format!(
            "{} with the command-line overrides",
            args.experiment.display()
        )
    })?;
    let dir = args
        .out
        .clone()
        .unwrap_or_else(|| experiment.default_run_dir());
    refuse_replicates(&dir, &args.experiment, experiment.seed)?;
    buildable(&experiment, &args.experiment)?;
    let (baseline, baseline_note) = check::resolve_baseline(&experiment, &args.experiment);
    warn_before_start(&experiment, &args, baseline_note);
    let stop = stop_flag(Some(Interrupting {
        dir: dir.clone(),
        start_over: format!(
            "{} run {} --out {} --force",
            berry_evolve::invocation::program(),
            args.experiment.display(),
            dir.display()
        ),
    }))?;
    let line = announce(&experiment.name, &format!("seed {}", experiment.seed), &dir);
    let estimated = announced(reporter(args.quiet), &experiment, &args);
    let mut progress = announcing(estimated, args.quiet, Some(line));
    let jobs = args.jobs.unwrap_or(0);
    let remote = evaluator(ranks, jobs, &stop)?;
    let result = start(
        experiment,
        &dir,
        args.force,
        RunOptions {
            jobs,
            stop: Some(&stop),
            evaluator: remote.as_deref(),
        },
        progress.as_mut(),
    );
    let check = CheckRequest {
        enabled: !args.no_check,
        jobs,
        baseline,
    };
    let outcome = run_report::finish(result, args.json, args.quiet, check);
    if !args.quiet {
        if let Some(note) = remote.as_deref().and_then(|e| e.report()) {
            errln!("{note}");
        }
    }
    outcome
}

/// Refuses, as the experiment file's problem, a world that cannot be built (a placement
/// rule with no room), before anything is written: the fixed file then starts again with
/// the same command. `start` refuses it too (so does every caller of the library), but
/// without naming the file.
fn buildable(experiment: &Experiment, file: &Path) -> anyhow::Result<()> {
    berry_evolve::run::check_worlds(experiment).map_err(|error| {
        ExperimentError::Invalid {
            path: file.to_path_buf(),
            error: InvalidValue::new(
                "world",
                format!("{error}; nothing was written, so the fixed file starts as it is"),
            ),
        }
        .into()
    })
}

/// Before a run starts, what would make it a dead end, on stderr (also with --quiet, as the
/// long-run warning): a world in which nothing can change the fitness, and a baseline file
/// that is not there (a note, unless --quiet).
fn warn_before_start(experiment: &Experiment, args: &RunArgs, baseline_note: Option<String>) {
    if let Some(w) = constant_fitness_warning(experiment) {
        errln!("{w}");
    }
    if let (Some(note), false) = (baseline_note, args.quiet) {
        errln!("{note}");
    }
}

/// The warning for an experiment in which every creature scores the same whatever it does
/// (e.g. the empty world of `config --defaults`); `inspect` prints it too.
pub fn constant_fitness_warning(experiment: &Experiment) -> Option<String> {
    if experiment
        .fitness
        .can_vary(&experiment.world, &experiment.creature)
    {
        return None;
    }
    Some(format!(
        "warning: nothing in this world can change the fitness: it holds no food or other \
         objects (no [[world.place]] with a count, no [[world.objects]], no predators) and no \
         [fitness] term pays for moving, so every creature scores the same and evolution has \
         nothing to select. Add food, as experiments/foraging.toml does with \
         [world.kinds.<name>] and [[world.place]], or start from a built-in experiment: {} \
         new NAME --from foraging",
        berry_evolve::invocation::program()
    ))
}

/// `run --out DIR` where DIR holds the seed folders of a `run --seeds` batch: a single run
/// there would mix its files with the batch's (and `summary DIR` would read them as one).
/// `seed`: the seed this run would use.
fn refuse_replicates(dir: &Path, experiment: &Path, seed: u64) -> anyhow::Result<()> {
    let seeds = replicate_seeds(dir);
    if seeds.is_empty() {
        return Ok(());
    }
    let names: Vec<String> = seeds.iter().map(|s| format!("seed-{s}/")).collect();
    let how = if seeds.contains(&seed) {
        format!(
            "Seed {seed} is already in it: continue it with {} resume {}",
            berry_evolve::invocation::program(),
            dir.join(format!("seed-{seed}")).display()
        )
    } else {
        format!(
            "To add seed {seed} to the batch: {} run {} --seeds {seed} --out {}",
            berry_evolve::invocation::program(),
            experiment.display(),
            dir.display()
        )
    };
    anyhow::bail!(
        "{} holds the seed replicates of a `run --seeds` batch ({}): a single run there would \
         mix its files with theirs. {how}; for a run of its own, choose another --out (or \
         leave it out: results/<name>/seed-<seed>/)",
        dir.display(),
        names.join(", ")
    )
}

/// The seeds whose `seed-<s>/` folder in `dir` holds a run (its experiment.toml), in order.
fn replicate_seeds(dir: &Path) -> Vec<u64> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Vec::new();
    };
    let mut seeds: Vec<u64> = entries
        .filter_map(Result::ok)
        .filter_map(|e| {
            let seed = e
                .file_name()
                .to_str()?
                .strip_prefix("seed-")?
                .parse()
                .ok()?;
            e.path()
                .join(berry_evolve::run::EXPERIMENT_FILE)
                .is_file()
                .then_some(seed)
        })
        .collect();
    seeds.sort_unstable();
    seeds
}

/// `progress`, preceded by the estimate and the long-run warning unless --no-estimate.
fn announced(
    progress: Box<dyn Progress>,
    experiment: &Experiment,
    args: &RunArgs,
) -> Box<dyn Progress> {
    if args.no_estimate {
        return progress;
    }
    Box::new(estimate::Announced {
        inner: progress,
        experiment: experiment.clone(),
        jobs: args.jobs.unwrap_or(0),
        quiet: args.quiet,
    })
}

/// `run --seeds`: the batch's estimate (timed with the first seed) and warning, before the
/// first seed starts.
fn announce_batch(experiment: &Experiment, args: &RunArgs, seeds: usize) {
    if args.no_estimate {
        return;
    }
    let generations = 0..experiment.evolution.generations;
    let target = berry_evolve::run::estimate::RUN_CALIBRATION_TARGET;
    let Some(mut e) = estimate::estimate(experiment, args.jobs.unwrap_or(0), generations, target)
    else {
        return;
    };
    if !args.quiet {
        errln!("{} per seed", estimate::run_line(&e));
    }
    e.total_seconds *= seeds as f64;
    if let Some(w) = estimate::long_run_warning(&e, &format!("this batch of {seeds} seeds")) {
        errln!("{w}");
    }
}

/// The progress reporter for this terminal and flags, which first prints `line` (unless
/// quiet) when the run reports for the first time: a run refused before it starts prints only
/// its error.
pub(crate) fn announcing(
    inner: Box<dyn Progress>,
    quiet: bool,
    line: Option<String>,
) -> Box<dyn Progress> {
    match line {
        Some(line) if !quiet => Box::new(Announcing {
            line: Some(line),
            inner,
        }),
        _ => inner,
    }
}

/// See [`announcing`].
struct Announcing {
    line: Option<String>,
    inner: Box<dyn Progress>,
}

impl Announcing {
    fn say(&mut self) {
        if let Some(line) = self.line.take() {
            errln!("{line}");
        }
    }
}

impl Progress for Announcing {
    fn begin(&mut self, first: u64, total: u64) {
        self.say();
        self.inner.begin(first, total);
    }
    fn generation(&mut self, row: &FitnessRow) {
        self.inner.generation(row);
    }
    fn checkpoint(&mut self, path: &std::path::Path) {
        self.inner.checkpoint(path);
    }
    fn end(&mut self) {
        // A resumed run that was already finished ends without beginning.
        self.say();
        self.inner.end();
    }
    fn note(&mut self, message: &str) {
        self.say();
        self.inner.note(message);
    }
    fn within_generation(&mut self, jobs_per_generation: u64) -> Option<JobHook> {
        self.inner.within_generation(jobs_per_generation)
    }
}

/// The first line of a run: what runs and where its results go, with the folder a relative
/// `--out` (or the default results/...) is relative to, since it is the current one.
fn announce(name: &str, what: &str, dir: &std::path::Path) -> String {
    let relative_to = match std::env::current_dir() {
        Ok(cwd) if dir.is_relative() => {
            format!(" (in {}; --out chooses another folder)", cwd.display())
        }
        _ => String::new(),
    };
    format!(
        "running `{name}` {what}: results go to {}{relative_to}",
        dir.display()
    )
}

/// The seeds of `--seeds`: `a..b` (a to b inclusive) or a comma-separated list, in the order
/// given, without repeats.
pub fn parse_seeds(spec: &str) -> anyhow::Result<Vec<u64>> {
    let number = |t: &str| -> anyhow::Result<u64> {
        t.trim().parse::<u64>().map_err(|_| {
            anyhow::anyhow!(
                "--seeds {spec}: `{}` is not a seed (a whole number from 0); write a range \
                 such as 1..10 or a list such as 1,3,5",
                t.trim()
            )
        })
    };
    let seeds: Vec<u64> = if let Some((a, b)) = spec.split_once("..") {
        let (a, b) = (number(a)?, number(b.trim_start_matches('='))?);
        anyhow::ensure!(
            a <= b,
            "--seeds {spec}: the range is empty (the first seed is above the last)"
        );
        anyhow::ensure!(
            b - a < 10_000,
            "--seeds {spec}: more than 10000 seeds; is this a typo?"
        );
        (a..=b).collect()
    } else {
        spec.split(',').map(number).collect::<anyhow::Result<_>>()?
    };
    for (i, s) in seeds.iter().enumerate() {
        anyhow::ensure!(
            !seeds[..i].contains(s),
            "--seeds {spec}: seed {s} is named twice"
        );
    }
    anyhow::ensure!(!seeds.is_empty(), "--seeds {spec}: no seed given");
    Ok(seeds)
}

/// `run --seeds`: each seed in turn in `<out>/seed-<s>/`, one line per seed on stdout.
fn run_seeds(args: &RunArgs, seeds: &[u64], ranks: Option<&Ranks>) -> anyhow::Result<()> {
    let experiment = Experiment::load(&args.experiment)?;
    let (_, baseline_note) = check::resolve_baseline(&experiment, &args.experiment);
    warn_before_start(&experiment, args, baseline_note);
    let base = match &args.out {
        Some(out) => out.clone(),
        None => PathBuf::from("results").join(&experiment.name),
    };
    let mut line = {
        let consecutive = seeds.windows(2).all(|w| w[1] == w[0] + 1);
        let what = match seeds {
            [one] => format!("seed {one}"),
            [first, .., last] if consecutive => format!("seeds {first} to {last}"),
            _ => format!(
                "seeds {}",
                seeds
                    .iter()
                    .map(u64::to_string)
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        };
        Some(announce(&experiment.name, &what, &base.join("seed-<s>")))
    };
    let stop = stop_flag(None)?;
    if let Some(&first) = seeds.first() {
        let mut overrides = experiment.with_overrides().seed(first);
        if let Some(g) = args.generations {
            overrides = overrides.generations(g);
        }
        if let Ok(e) = overrides.build() {
            // What runs and where comes before the batch's estimate.
            if !args.no_estimate && !args.quiet {
                if let Some(line) = line.take() {
                    errln!("{line}");
                }
            }
            announce_batch(&e, args, seeds.len());
        }
    }
    let mut report = run_report::SeedsReport::new(args.json);
    let jobs = args.jobs.unwrap_or(0);
    let remote = evaluator(ranks, jobs, &stop)?;
    for &seed in seeds {
        let mut overrides = experiment.with_overrides().seed(seed);
        if let Some(g) = args.generations {
            overrides = overrides.generations(g);
        }
        let e = overrides.build().with_context(|| {
            format!(
                "{} with seed {seed} and the command-line overrides",
                args.experiment.display()
            )
        })?;
        let dir = base.join(format!("seed-{seed}"));
        let options = RunOptions {
            jobs,
            stop: Some(&stop),
            evaluator: remote.as_deref(),
        };
        let mut progress = announcing(reporter(args.quiet), args.quiet, line.take());
        let continued = !args.force && dir.join(berry_evolve::run::EXPERIMENT_FILE).exists();
        let result = if continued {
            berry_evolve::run::resume(&dir, args.generations, false, options, progress.as_mut())
        } else {
            buildable(&e, &args.experiment)?;
            start(e, &dir, args.force, options, progress.as_mut())
        };
        report
            .add(seed, continued, result)
            .with_context(|| format!("seed {seed} ({})", dir.display()))?;
    }
    report.print()
}

#[cfg(test)]
mod tests {
    use super::parse_seeds;

    #[test]
    fn seeds_as_ranges_and_lists() {
        assert_eq!(parse_seeds("1..5").unwrap(), vec![1, 2, 3, 4, 5]);
        assert_eq!(parse_seeds("1..=3").unwrap(), vec![1, 2, 3]);
        assert_eq!(parse_seeds("7").unwrap(), vec![7]);
        assert_eq!(parse_seeds("1,3, 5").unwrap(), vec![1, 3, 5]);
        assert!(parse_seeds("5..1").is_err());
        assert!(parse_seeds("1,1").is_err());
        assert!(parse_seeds("a..3").is_err());
        assert!(parse_seeds("").is_err());
    }
}
