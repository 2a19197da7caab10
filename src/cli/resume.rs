//! `berry-evolve resume`: continue a run from its newest good checkpoint (or a given one).

use super::progress::reporter;
use super::run::{report, stop_flag, ExecutionArgs};
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
    /// Continue even though experiment.toml differs from the checkpoint's experiment; the
    /// change is recorded in config-changes.log.
    #[arg(long)]
    pub allow_config_change: bool,
    #[command(flatten)]
    pub execution: ExecutionArgs,
}

/// Runs the subcommand.
pub fn run(args: ResumeArgs) -> anyhow::Result<()> {
    let stop = stop_flag()?;
    let mut progress = reporter(args.execution.quiet);
    let summary = resume(
        &args.target,
        args.generations,
        args.allow_config_change,
        RunOptions {
            jobs: args.execution.jobs.unwrap_or(0),
            stop: Some(&stop),
        },
        progress.as_mut(),
    )?;
    if !args.execution.quiet {
        report(&summary);
    }
    Ok(())
}
