//! Why a run could not start, continue or finish: the one typed error of `run`, each variant
//! naming the file or folder, what is wrong and the command that works (the CLI prints it).

use super::names::{CHANGES_FILE, DISCARDED_DIR};
use super::progress::RunSummary;
use crate::evo::life::EvaluationError;
use crate::experiment::ExperimentError;
use crate::record::champions::ChampionsError;
use crate::record::checkpoint::CheckpointError;
use crate::record::genome_file::GenomeFileError;
use std::path::{Path, PathBuf};
use thiserror::Error;

/// Why a run could not start, continue or finish.
#[derive(Debug, Error)]
pub enum RunError {
    /// The run folder already holds a run.
    #[error("{dir} already holds a run; continue it with `{program} resume {dir}` or start over with --force", program = crate::invocation::program())]
    FolderInUse {
        /// The folder.
        dir: PathBuf,
    },
    /// Another process writes this run folder.
    #[error("{dir} is in use by {}: another berry-evolve writes this run folder. Wait for it to finish (or stop it), then try again", match pid { Some(p) => format!("process {p}"), None => "another process".to_string() })]
    InUse {
        /// The folder.
        dir: PathBuf,
        /// The holder's process id.
        pid: Option<u32>,
    },
    /// The run folder's lock file could not be opened or locked.
    #[error("cannot lock the run folder {dir} ({path}): {error}; a run folder must be a writable folder on a local file system")]
    Lock {
        /// The folder.
        dir: PathBuf,
        /// The lock file.
        path: PathBuf,
        /// The I/O error.
        error: std::io::Error,
    },
    /// The run folder holds a run's files but no checkpoint: nothing to resume.
    #[error("{dir} holds the files of a run that stopped before its first checkpoint, so there is nothing to resume; start it over with: {program} run {experiment} --out {dir} --force", program = crate::invocation::program())]
    NothingToResume {
        /// The folder.
        dir: PathBuf,
        /// The experiment file to start over with.
        experiment: String,
    },
    /// `--force` found an experiment.toml that this program did not write.
    #[error("{path} is not the file a run writes (it differs from the run's own form, e.g. it has comments), so --force does not delete it; move it out of the run folder (or choose another --out) and run again")]
    NotOwnExperiment {
        /// The file.
        path: PathBuf,
    },
    /// `--out` is a symbolic link to nothing.
    #[error("--out {dir} is a symbolic link to {target}, which does not exist; create that folder first (mkdir -p {target}) or choose another --out")]
    DanglingOut {
        /// The link.
        dir: PathBuf,
        /// Where it points.
        target: PathBuf,
    },
    /// What `resume` was given is neither a run folder nor a checkpoint in one.
    #[error("cannot resume {target}: {reason}")]
    ResumeTarget {
        /// The argument.
        target: PathBuf,
        /// Why, and what to do.
        reason: String,
    },
    /// Resuming an older checkpoint would leave newer ones behind.
    #[error("{dir} holds checkpoints newer than {checkpoint} ({newer}); resuming from it would discard them. To do that, moving them to {dir}/{DISCARDED_DIR}/ and recording it in {CHANGES_FILE}, run: {command}")]
    NewerCheckpoints {
        /// The run folder.
        dir: PathBuf,
        /// The checkpoint asked for.
        checkpoint: PathBuf,
        /// The newer checkpoints' names.
        newer: String,
        /// The command that does it.
        command: String,
    },
    /// `resume --generations N` asked for fewer generations than the run plans.
    #[error("--generations {requested} is fewer than the {planned} generations this run plans; to shorten the run (recorded in {CHANGES_FILE}), run: {command}")]
    FewerGenerations {
        /// What was asked for.
        requested: u64,
        /// What the run plans.
        planned: u64,
        /// The command that does it.
        command: String,
    },
    /// The run folder could not be created (e.g. a parent is a regular file).
    #[error("cannot create the run folder {dir}: {error}; choose another --out, or make sure every parent of it is a writable folder with free space")]
    CreateFolder {
        /// The run folder.
        dir: PathBuf,
        /// The I/O error.
        error: std::io::Error,
    },
    /// A file of the run folder could not be read or written.
    #[error("{path}: {error}")]
    Io {
        /// The file or folder.
        path: PathBuf,
        /// The I/O error.
        error: std::io::Error,
    },
    /// The experiment is not usable.
    #[error(transparent)]
    Experiment(#[from] ExperimentError),
    /// A checkpoint could not be read or written.
    #[error(transparent)]
    Checkpoint(#[from] CheckpointError),
    /// The fitness CSV could not be written.
    #[error(transparent)]
    Csv(#[from] crate::record::fitness_csv::FitnessCsvError),
    /// best.json could not be written.
    #[error(transparent)]
    Genome(#[from] GenomeFileError),
    /// champions.jsonl could not be read or written.
    #[error(transparent)]
    Champions(#[from] ChampionsError),
    /// Evaluation failed.
    #[error(transparent)]
    Evaluation(#[from] EvaluationError),
    /// The thread pool could not be built.
    #[error("cannot start {jobs} worker threads: {message}")]
    Threads {
        /// Requested threads.
        jobs: usize,
        /// rayon's message.
        message: String,
    },
    /// The experiment file in the folder differs from the checkpoint's experiment.
    #[error("{path} differs from the experiment in checkpoint {checkpoint} (config hash {hashes}; {changes}); the run would no longer be the one its seed describes. Restore the file, or continue anyway (the change is recorded in the run folder): {command}")]
    ConfigChanged {
        /// The experiment file.
        path: PathBuf,
        /// The checkpoint.
        checkpoint: PathBuf,
        /// The file's experiment's hash vs the checkpoint's (short), `found vs expected`.
        hashes: String,
        /// The changed keys, `key: checkpoint's -> file's`, separated by "; ".
        changes: String,
        /// The command that continues anyway.
        command: String,
    },
    /// `resume --generations N` asked for fewer generations than the checkpoint holds.
    #[error("--generations {requested}: checkpoint {checkpoint} already holds {completed} completed generations; ask for at least that many{older}")]
    TooFewGenerations {
        /// What was asked for.
        requested: u64,
        /// Generations the checkpoint holds.
        completed: u64,
        /// The checkpoint.
        checkpoint: PathBuf,
        /// A command resuming an older checkpoint instead, when one exists.
        older: String,
    },
    /// A file of the run could not be written during the run (full disk, permissions, the
    /// folder removed); the run stopped.
    #[error("the run in {dir} stopped: an output file could not be written. {advice}")]
    OutputFailed {
        /// The run folder.
        dir: PathBuf,
        /// What the user can do, naming the last good checkpoint if there is one.
        advice: String,
        /// The write that failed.
        source: Box<RunError>,
    },
    /// Another MPI rank could not evaluate its share (or stopped answering); the run stopped.
    #[error("the run in {dir} stopped: an MPI rank failed. {advice}")]
    RankFailed {
        /// The run folder.
        dir: PathBuf,
        /// What the user can do, naming the last good checkpoint if there is one.
        advice: String,
        /// What the rank did.
        source: Box<EvaluationError>,
    },
    /// Stopped by the user (Ctrl-C / SIGTERM) after writing a checkpoint.
    #[error("interrupted after generation {generation}; the checkpoint {checkpoint} holds it. Continue with: {program} resume {dir}", program = crate::invocation::program())]
    Interrupted {
        /// Last completed generation.
        generation: u64,
        /// The checkpoint written.
        checkpoint: PathBuf,
        /// The run folder.
        dir: PathBuf,
        /// Where the run stands (for `run --json`).
        summary: Box<RunSummary>,
    },
}

/// Wraps an I/O error on `path` (a file or folder of the run) as a [`RunError::Io`].
pub(super) fn io_err(path: &Path) -> impl FnOnce(std::io::Error) -> RunError + '_ {
    move |error| RunError::Io {
        path: path.to_path_buf(),
        error,
    }
}
