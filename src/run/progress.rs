//! What a run tells its caller and how it is executed: progress as it goes ([`Progress`]),
//! the threads or ranks it evaluates on ([`RunOptions`]) and where it ends ([`RunSummary`]).
//! None of this changes a run's results.

use crate::evo::evaluate::Evaluator;
use crate::evo::state::Champion;
use crate::evo::validation::ValidatedChampion;
use crate::record::fitness_csv::FitnessRow;
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;

/// Receives progress reports; the CLI draws a bar or prints lines.
pub trait Progress {
    /// The run will evaluate generations `first..total`.
    fn begin(&mut self, first: u64, total: u64);
    /// Generation `row.generation` is done.
    fn generation(&mut self, row: &FitnessRow);
    /// A checkpoint was written.
    fn checkpoint(&mut self, path: &Path);
    /// The run ended normally.
    fn end(&mut self);
    /// Something the user should know that is not an error (default: ignored).
    fn note(&mut self, _message: &str) {}
    /// Asked once, before [`Progress::begin`], with the number of evaluation jobs in each
    /// generation: a reporter that shows progress within a generation returns what to call
    /// as each job finishes (from the worker threads, in any order). Default: nothing, and
    /// nothing is counted.
    fn within_generation(&mut self, _jobs_per_generation: u64) -> Option<JobHook> {
        None
    }
}

/// What [`Progress::within_generation`] returns: called once per finished evaluation job.
pub type JobHook = std::sync::Arc<dyn Fn() + Send + Sync>;

/// A [`Progress`] that reports nothing.
pub struct Silent;

impl Progress for Silent {
    fn begin(&mut self, _: u64, _: u64) {}
    fn generation(&mut self, _: &FitnessRow) {}
    fn checkpoint(&mut self, _: &Path) {}
    fn end(&mut self) {}
}

/// How a run is executed (none of this changes its results).
pub struct RunOptions<'a> {
    /// Worker threads; 0 means one per core.
    pub jobs: usize,
    /// Set to true (e.g. by a signal handler) to stop after the current generation.
    pub stop: Option<&'a AtomicBool>,
    /// Where each generation's evaluation jobs run, when not on this process's `jobs`
    /// threads (e.g. MPI ranks, `crate::evo::ranks`); `None`: here.
    pub evaluator: Option<&'a dyn Evaluator>,
}

/// What a finished run reports.
#[derive(Debug, Clone)]
pub struct RunSummary {
    /// The run folder.
    pub dir: PathBuf,
    /// Generations completed in total.
    pub generations: u64,
    /// The best individual ever seen.
    pub best_ever: Option<Champion>,
    /// The last checkpoint written.
    pub checkpoint: Option<PathBuf>,
    /// The best individual on validation (`[validation]` on), the one best.json holds.
    pub validated_best: Option<ValidatedChampion>,
}
