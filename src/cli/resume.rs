//! `berry-evolve resume`: continue a run from its newest good checkpoint (or a given one).

use super::progress::reporter;
use super::run::{report, stop_flag};
use berry_evolve::run::{resume, RunOptions};
use clap::Args;
use std::path::PathBuf;

/// Arguments of `resume`.
#[derive(Debug, Args)]
pub struct ResumeArgs {
    /// A run folder (uses its newest good checkpoint) or a checkpoint file.
    pub target: PathBuf,
    /// Run until this many generations in total (extends a finished run).
    #[arg(long)]
    pub generations: Option<u64>,
    /// Worker threads (default: one per core). Results do not depend on it.
    #[arg(long)]
    pub jobs: Option<usize>,
    /// Continue even though experiment.toml differs from the checkpoint's experiment; the
    /// change is recorded in config-changes.log.
    #[arg(long)]
    pub allow_config_change: bool,
    /// Print nothing but errors.
    #[arg(long, short)]
    pub quiet: bool,
}

/// Runs the subcommand.
pub fn run(args: ResumeArgs) -> anyhow::Result<()> {
    let stop = stop_flag()?;
    let mut progress = reporter(args.quiet);
    let summary = resume(
        &args.target,
        args.generations,
        args.allow_config_change,
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
