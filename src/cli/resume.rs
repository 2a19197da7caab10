//! `berry-evolve resume`: continue a run from its newest good checkpoint (or a given one).

use super::cluster::{evaluator, Ranks};
use super::console::errln;
use super::progress::reporter;
use super::run::Interrupting;
use super::run::{announcing, stop_flag, ExecutionArgs};
use super::run_report::{self, CheckRequest};
use berry_evolve::record::checkpoint::list_checkpoints;
use berry_evolve::run::{resume_target, resume_with, ResumeRequest, RunOptions, CHECKPOINT_DIR};
use clap::Args;
use std::path::{Path, PathBuf};

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
    let opening = opening_line(&args.target);
    let stop = stop_flag(at)?;
    let mut progress = announcing(
        reporter(args.execution.quiet),
        args.execution.quiet,
        opening,
    );
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
    let check = CheckRequest {
        enabled: !args.execution.no_check,
        jobs,
        baseline: None,
    };
    let outcome = run_report::finish(result, args.json, args.execution.quiet, check);
    if !args.execution.quiet {
        if let Some(note) = remote.as_deref().and_then(|e| e.report()) {
            errln!("{note}");
        }
    }
    outcome
}

/// The line `resume` opens with (printed once the resume is accepted, before its first
/// note or generation): the run folder and the checkpoint it continues from, the one named
/// or the folder's newest (the one resume reads: a damaged newest one is refused, not
/// skipped). None when the target is no run folder (resume then says why).
fn opening_line(target: &Path) -> Option<String> {
    let (dir, file) = resume_target(target).ok()?;
    let (generation, checkpoint) = match file {
        Some(f) => {
            let generation = f
                .file_name()
                .and_then(|n| n.to_str())
                .and_then(berry_evolve::record::checkpoint::parse_checkpoint_file_name);
            (generation, f)
        }
        None => {
            let (g, p) = list_checkpoints(&dir.join(CHECKPOINT_DIR)).ok()?.pop()?;
            (Some(g), p)
        }
    };
    let done = generation.map_or(String::new(), |g| format!(" (generations 0 to {g} done)"));
    Some(format!(
        "resuming the run in {} from checkpoint {}{done}",
        dir.display(),
        checkpoint.display()
    ))
}
