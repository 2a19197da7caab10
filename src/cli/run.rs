//! `berry-evolve run`: start a new run of an experiment.

use crate::cli::console::errln;

use super::progress::reporter;
use anyhow::Context;
use berry_evolve::experiment::Experiment;
use berry_evolve::run::{start, RunOptions};
use clap::Args;
use std::path::PathBuf;
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
    #[arg(long)]
    pub seed: Option<u64>,
    /// Override the number of generations.
    #[arg(long)]
    pub generations: Option<u64>,
    // Not `#[command(flatten)] ExecutionArgs`: clap leaves the top-level `Option<RunArgs>`
    // (the bare `berry-evolve FILE` form) as None when it holds a nested flatten.
    /// Worker threads (default: one per core). Results do not depend on it.
    #[arg(long)]
    pub jobs: Option<usize>,
    /// Print nothing but errors.
    #[arg(long, short)]
    pub quiet: bool,
    /// Replace a run already in the run folder.
    #[arg(long)]
    pub force: bool,
}

/// How a resumed run executes; none of it changes the results.
#[derive(Debug, Args)]
pub struct ExecutionArgs {
    /// Worker threads (default: one per core). Results do not depend on it.
    #[arg(long)]
    pub jobs: Option<usize>,
    /// Print nothing but errors.
    #[arg(long, short)]
    pub quiet: bool,
}

/// Installs a Ctrl-C / SIGTERM handler: the first signal asks the run to stop after the
/// current generation (with a checkpoint); the second stops at once.
pub fn stop_flag() -> anyhow::Result<Arc<AtomicBool>> {
    let flag = Arc::new(AtomicBool::new(false));
    let handler_flag = flag.clone();
    ctrlc::set_handler(move || {
        if handler_flag.swap(true, Ordering::SeqCst) {
            errln!("\nstopping now; the last checkpoint is intact");
            std::process::exit(130);
        }
        errln!("\nstopping after this generation (press Ctrl-C again to stop at once)");
    })
    .context("cannot install the Ctrl-C handler")?;
    Ok(flag)
}

/// Runs the subcommand.
pub fn run(args: RunArgs) -> anyhow::Result<()> {
    let mut experiment = Experiment::load(&args.experiment)?;
    if let Some(seed) = args.seed {
        experiment.seed = seed;
    }
    if let Some(g) = args.generations {
        experiment.evolution.generations = g;
    }
    experiment.validate().with_context(|| {
        format!(
            "{} with the command-line overrides",
            args.experiment.display()
        )
    })?;
    let dir = args.out.unwrap_or_else(|| experiment.default_run_dir());
    let stop = stop_flag()?;
    let mut progress = reporter(args.quiet);
    let summary = start(
        experiment,
        &dir,
        args.force,
        RunOptions {
            jobs: args.jobs.unwrap_or(0),
            stop: Some(&stop),
        },
        progress.as_mut(),
    )?;
    if !args.quiet {
        report(&summary);
    }
    Ok(())
}

/// Prints where a finished run's results are.
pub fn report(summary: &berry_evolve::run::RunSummary) {
    if let Some(best) = &summary.best_ever {
        errln!(
            "done: {} generations; best ever {:.4} (generation {}, individual {}), metabolism {:?}",
            summary.generations,
            best.fitness,
            best.generation,
            best.individual,
            best.metabolism
        );
    }
    errln!(
        "results in {}: fitness.csv, best.json, checkpoints/",
        summary.dir.display()
    );
}
