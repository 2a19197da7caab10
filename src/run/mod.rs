//! A run: one experiment evolving in a run folder. Owns the folder's files (effective
//! `experiment.toml`, `fitness.csv` written row by row, `best.json`, `champions.jsonl`,
//! `checkpoints/`) and the generation loop that connects evolution to them, including
//! resuming from a checkpoint so that a stopped run finishes with the same bytes as one never
//! stopped.
//!
//! By concern, lowest first (each file uses only those above it):
//! - [`names`]: the folder's file names; [`lock`]: one writer per folder.
//! - `progress`: what a run reports ([`Progress`], [`RunSummary`]) and how it is executed
//!   ([`RunOptions`]); `error`: [`RunError`].
//! - `extension`: what extending a finished run sets aside (pure); `checkpoints`: what a
//!   checkpoint holds ([`CheckpointPayload`]) and reading one back.
//! - `folder`: the lock taken, a run's own files, the change log, a failed run's advice.
//! - `generation_loop`: evaluate, record, checkpoint, vary (with `champions` and
//!   `validated`, its `champions.jsonl` and `best.json` under `[validation]`).
//! - `start`: a new run; `resume`: a pure [`ResumePlan`], then its apply step.
//! - [`estimate`]: how long a run will take.

pub mod estimate;
pub mod lock;
pub mod names;

mod champions;
mod checkpoints;
mod error;
mod extension;
mod folder;
mod generation_loop;
mod progress;
mod resume;
mod start;
mod validated;

pub use checkpoints::{load_checkpoint, replan_older_checkpoints, CheckpointPayload};
pub use error::RunError;
pub use extension::EndOfRunValidation;
pub use names::{
    BASELINE_FILE, BEST_FILE, CHAMPIONS_FILE, CHANGES_FILE, CHECKPOINT_DIR, DISCARDED_DIR,
    EXPERIMENT_FILE, FITNESS_FILE,
};
pub use progress::{JobHook, Progress, RunOptions, RunSummary, Silent};
pub use resume::{resume, resume_target, resume_with, ResumePlan, ResumeRequest};
pub use start::{check_worlds, start};
