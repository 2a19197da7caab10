//! `berry-evolve resume`: continue a run from its newest good checkpoint (or a given one).

use super::cluster::{evaluator, Ranks};
use super::console::errln;
use super::progress::reporter;
use super::run::Interrupting;
use super::run::{stop_flag, ExecutionArgs};
use super::run_report;
use berry_evolve::run::{resume_target, resume_with, ResumeRequest, RunOptions};
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
    /// Resume the checkpoint given although the run folder holds newer ones: they are moved
    /// to discarded-checkpoints/ and the move recorded in config-changes.log.
    #[arg(long)]
    pub discard_newer: bool,
    /// Accept a --generations below what the run plans (recorded in config-changes.log).
    #[arg(long)]
    pub shorten: bool,
    /// At the end, print one JSON document on stdout instead of the text summary (schema
    /// `berry-evolve/run/1`, as `run --json`). Progress stays on stderr.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub execution: ExecutionArgs,
}

/// Runs the subcommand.
pub fn run(args: ResumeArgs, ranks: Option<&Ranks>) -> anyhow::Result<()> {
    let at = resume_target(&args.target)
        .ok()
        .map(|(dir, _)| Interrupting {
            start_over: format!(
                "{} run {}/experiment.toml --out {} --force",
                berry_evolve::invocation::program(),
                dir.display(),
                dir.display()
            ),
            dir,
        });
    let stop = stop_flag(at)?;
    let mut progress = reporter(args.execution.quiet);
    let jobs = args.execution.jobs.unwrap_or(0);
    let remote = evaluator(ranks, jobs, &stop)?;
    let result = resume_with(
        &args.target,
        ResumeRequest {
            generations: args.generations,
            allow_config_change: args.allow_config_change,
            discard_newer: args.discard_newer,
            shorten: args.shorten,
        },
        RunOptions {
            jobs,
            stop: Some(&stop),
            evaluator: remote.as_deref(),
        },
        progress.as_mut(),
    );
    let outcome = run_report::finish(result, args.json, args.execution.quiet);
    if !args.execution.quiet {
        if let Some(note) = remote.as_deref().and_then(|e| e.report()) {
            errln!("{note}");
        }
    }
    outcome
}
