//! A run: one experiment evolving in a run folder. Owns the folder's files (effective
//! `experiment.toml`, `fitness.csv` written row by row, `best.json`, `champions.jsonl`,
//! `checkpoints/`) and the generation loop that connects evolution to them, including
//! resuming from a checkpoint so that a stopped run finishes with the same bytes as one never
//! stopped.

pub mod estimate;
pub mod lock;

mod champions;

use crate::brain::spec::Topology;
use crate::evo::evaluate::{evaluation_jobs, Evaluator};
use crate::evo::life::EvaluationError;
use crate::evo::search::{self, Search, SearchState, Unevaluated};
use crate::evo::state::{
    evaluate_on, evaluate_watched, Champion, EvaluatedGeneration, GenerationSummary,
};
use crate::evo::validation::{self, ValidatedChampion};
use crate::experiment::diff::changed_keys;
use crate::experiment::{Experiment, ExperimentConfig, ExperimentError};
use crate::input::{read_regular, read_regular_text, MAX_CSV_BYTES, MAX_EXPERIMENT_BYTES};
use crate::record::archive::ARCHIVE_FILE;
use crate::record::atomic::{remove_stale_temp_files, write_atomic};
use crate::record::champions::{ChampionsError, ChampionsLog};
use crate::record::checkpoint::{self, CheckpointError, CheckpointErrorKind, ContentError};
use crate::record::fitness_csv::{extra_columns, FitnessCsv, FitnessRow};
use crate::record::genome_file::{GenomeFile, GenomeFileError, Origin};
use lock::{LockError, RunLock};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use thiserror::Error;

mod extension;
mod validated;

pub use extension::EndOfRunValidation;

/// File names inside a run folder.
pub const EXPERIMENT_FILE: &str = "experiment.toml";
/// The fitness curve.
pub const FITNESS_FILE: &str = "fitness.csv";
/// The best genome so far.
pub const BEST_FILE: &str = "best.json";
/// Each generation's best genome, one genome file per line.
pub const CHAMPIONS_FILE: &str = "champions.jsonl";
/// The checkpoint folder.
pub const CHECKPOINT_DIR: &str = "checkpoints";
/// Where `resume --discard-newer` moves the checkpoints newer than the one resumed.
pub const DISCARDED_DIR: &str = "discarded-checkpoints";
/// The log of explicit changes to a run (config changes, shortening, discarded checkpoints).
pub const CHANGES_FILE: &str = "config-changes.log";
/// A copy of the experiment's baseline genome (`[output] baseline`), kept for the held-out
/// check of a later `resume`, which cannot resolve the key from the run folder.
pub const BASELINE_FILE: &str = "baseline.json";

/// What a checkpoint holds besides its envelope (format, program version, config hash,
/// generation, checksum). No random generator state is needed: every stream is derived from
/// the seed and the generation (see `seed::stream`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CheckpointPayload {
    /// The effective experiment, seed included, as read back (validated when the checkpoint
    /// is loaded, see `check_payload_shape`).
    pub experiment: ExperimentConfig,
    /// The last completed generation: genomes and evaluations.
    pub last: EvaluatedGeneration,
    /// The best individual ever seen.
    pub best_ever: Option<Champion>,
    /// One fitness row per completed generation.
    pub history: Vec<FitnessRow>,
    /// The search distribution that sampled `last` (PGPE only; absent for the GA, so GA
    /// checkpoints keep their bytes).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub search: Option<SearchState>,
    /// Per completed generation, the values of the fitness CSV's extra columns (behaviour
    /// measures, validation); empty when the experiment has none.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub history_extra: Vec<Vec<Option<f64>>>,
    /// The best individual on validation so far (`[validation]` on).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub validated_best: Option<ValidatedChampion>,
    /// Present in a finished run's last checkpoint when its last generation was validated
    /// only because it was the last: what that validation changed, so that extending the run
    /// can set it aside.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub end_of_run_validation: Option<EndOfRunValidation>,
}

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

fn io_err(path: &Path) -> impl FnOnce(std::io::Error) -> RunError + '_ {
    move |error| RunError::Io {
        path: path.to_path_buf(),
        error,
    }
}

/// Does `dir` already hold (part of) a run?
fn holds_run(dir: &Path) -> bool {
    [
        EXPERIMENT_FILE,
        FITNESS_FILE,
        BEST_FILE,
        CHAMPIONS_FILE,
        CHECKPOINT_DIR,
    ]
    .iter()
    .any(|f| dir.join(f).exists())
}

/// Takes the run folder's lock (see [`lock`]): the first thing every writer does.
fn lock_folder(dir: &Path) -> Result<RunLock, RunError> {
    RunLock::acquire(dir).map_err(|e| match e {
        LockError::InUse { pid } => RunError::InUse {
            dir: dir.to_path_buf(),
            pid,
        },
        LockError::Io(error) => RunError::Lock {
            dir: dir.to_path_buf(),
            path: dir.join(lock::LOCK_FILE),
            error,
        },
    })
}

/// Removes the temporary files of killed writes in the run folder (only a lock holder may).
fn clean_temp_files(dir: &Path) -> Result<(), RunError> {
    remove_stale_temp_files(dir).map_err(io_err(dir))?;
    let cdir = dir.join(CHECKPOINT_DIR);
    if cdir.is_dir() {
        remove_stale_temp_files(&cdir).map_err(io_err(&cdir))?;
    }
    Ok(())
}

/// Is `path` an experiment.toml this program wrote: exactly the run's own serialization of
/// the experiment it holds? A user's file (comments, another key order) is not.
fn is_own_experiment(path: &Path) -> bool {
    read_regular_text(path, MAX_EXPERIMENT_BYTES)
        .ok()
        .and_then(|text| {
            Experiment::from_toml(&text, path)
                .ok()
                .map(|e| e.to_toml() == text)
        })
        .unwrap_or(false)
}

/// `--force`: removes the earlier run's own files (and nothing else) and returns their
/// names relative to `dir`. Refuses, before removing anything, an experiment.toml that this
/// program did not write.
fn remove_own_files(dir: &Path) -> Result<Vec<String>, RunError> {
    let experiment = dir.join(EXPERIMENT_FILE);
    if experiment.exists() && !is_own_experiment(&experiment) {
        return Err(RunError::NotOwnExperiment { path: experiment });
    }
    let mut files: Vec<(PathBuf, String)> = Vec::new();
    for f in [
        EXPERIMENT_FILE,
        FITNESS_FILE,
        BEST_FILE,
        CHAMPIONS_FILE,
        CHANGES_FILE,
        BASELINE_FILE,
    ] {
        let p = dir.join(f);
        if p.symlink_metadata().is_ok_and(|m| m.is_file()) {
            files.push((p, f.to_string()));
        }
    }
    for sub in [CHECKPOINT_DIR, DISCARDED_DIR] {
        let d = dir.join(sub);
        if d.is_dir() {
            for (_, p) in checkpoint::list_checkpoints(&d).map_err(io_err(&d))? {
                let name = format!(
                    "{sub}/{}",
                    p.file_name().unwrap_or_default().to_string_lossy()
                );
                files.push((p, name));
            }
        }
    }
    let mut removed = Vec::new();
    for (p, name) in files {
        std::fs::remove_file(&p).map_err(io_err(&p))?;
        removed.push(name);
    }
    // An emptied folder of discarded checkpoints goes too; one with the user's files stays.
    let _ = std::fs::remove_dir(dir.join(DISCARDED_DIR));
    Ok(removed)
}

/// Builds generation 0's trial worlds as the run will (group 0), so that a world that cannot
/// be built (a placement rule with no room) is found before anything is written: `run`
/// refuses it touching no folder, and `inspect` reports it.
pub fn check_worlds(experiment: &Experiment) -> Result<(), EvaluationError> {
    let creatures = experiment.evaluation.group_size as usize;
    for t in 0..experiment.evaluation.trials {
        crate::evo::life::trial_world(
            experiment,
            creatures,
            crate::seed::Generation(0),
            0,
            crate::seed::TrialIndex(t),
        )?;
    }
    Ok(())
}

/// Starts a new run of `experiment` in `dir`. Refuses a folder that already holds a run
/// unless `force`, in which case the old run's own files (and only those) are removed first.
/// Refuses at once, touching nothing, a folder another process writes.
pub fn start(
    experiment: Experiment,
    dir: &Path,
    force: bool,
    options: RunOptions<'_>,
    progress: &mut dyn Progress,
) -> Result<RunSummary, RunError> {
    if dir
        .symlink_metadata()
        .is_ok_and(|m| m.file_type().is_symlink())
        && !dir.exists()
    {
        return Err(RunError::DanglingOut {
            dir: dir.to_path_buf(),
            target: std::fs::read_link(dir).unwrap_or_default(),
        });
    }
    // Before the folder exists: the fixed file then starts without --force.
    check_worlds(&experiment)?;
    std::fs::create_dir_all(dir).map_err(|error| RunError::CreateFolder {
        dir: dir.to_path_buf(),
        error,
    })?;
    let lock = lock_folder(dir)?;
    // A run killed while writing (e.g. before --force) leaves `.<name>.tmp-*` files.
    clean_temp_files(dir)?;
    if holds_run(dir) {
        if !force {
            return Err(RunError::FolderInUse {
                dir: dir.to_path_buf(),
            });
        }
        let removed = remove_own_files(dir)?;
        if !removed.is_empty() {
            progress.note(&format!(
                "--force removed the earlier run's {} file(s) from {}: {}",
                removed.len(),
                dir.display(),
                removed.join(", ")
            ));
        }
    }
    let checkpoints = dir.join(CHECKPOINT_DIR);
    std::fs::create_dir_all(&checkpoints).map_err(|error| RunError::CreateFolder {
        dir: dir.to_path_buf(),
        error,
    })?;
    let experiment_path = dir.join(EXPERIMENT_FILE);
    write_atomic(&experiment_path, experiment.to_toml().as_bytes())
        .map_err(io_err(&experiment_path))
        .map_err(|e| output_failed(dir, e))?;
    let csv = FitnessCsv::create_with(&dir.join(FITNESS_FILE), &extra_columns(&experiment))
        .map_err(|e| output_failed(dir, e.into()))?;
    let champions = ChampionsLog::create(&dir.join(CHAMPIONS_FILE))
        .map_err(|e| output_failed(dir, e.into()))?;
    let topology = experiment.topology();
    let search = search::factory::of(&experiment, &topology);
    let population = search.ask();
    drive(
        Loop {
            experiment,
            topology,
            dir: dir.to_path_buf(),
            csv,
            champions,
            history: Vec::new(),
            best_ever: None,
            next_generation: 0,
            _lock: lock,
            search,
            history_extra: Vec::new(),
            validated_best: None,
            validation_worlds: None,
            end_of_run_validation: None,
        },
        population,
        options,
        progress,
    )
}

/// What `resume` is asked to do beyond continuing.
#[derive(Debug, Clone, Copy, Default)]
pub struct ResumeRequest {
    /// Run until this many generations in total.
    pub generations: Option<u64>,
    /// Continue although experiment.toml differs from the checkpoint's experiment.
    pub allow_config_change: bool,
    /// Resume an older checkpoint although newer ones exist, moving those aside.
    pub discard_newer: bool,
    /// Accept `generations` below what the run plans.
    pub shorten: bool,
}

/// The flags a resume needs, to name the whole command that works in a refusal.
#[derive(Debug, Clone, Copy)]
struct ResumeFlags {
    discard_newer: bool,
    allow_config_change: bool,
    shorten: bool,
}

impl ResumeFlags {
    /// `berry-evolve resume TARGET [--generations G]` with these flags.
    fn command(&self, target: &Path, generations: Option<u64>) -> String {
        let mut command = format!(
            "{} resume {}",
            crate::invocation::program(),
            target.display()
        );
        if let Some(g) = generations {
            command.push_str(&format!(" --generations {g}"));
        }
        for (on, flag) in [
            (self.discard_newer, " --discard-newer"),
            (self.shorten, " --shorten"),
            (self.allow_config_change, " --allow-config-change"),
        ] {
            if on {
                command.push_str(flag);
            }
        }
        command
    }
}

/// Where to resume from: a run folder (its newest good checkpoint) or a checkpoint file.
pub fn resume(
    target: &Path,
    generations: Option<u64>,
    allow_config_change: bool,
    options: RunOptions<'_>,
    progress: &mut dyn Progress,
) -> Result<RunSummary, RunError> {
    resume_with(
        target,
        ResumeRequest {
            generations,
            allow_config_change,
            ..ResumeRequest::default()
        },
        options,
        progress,
    )
}

/// The run folder of a `resume` target and the checkpoint file named, if one was: a folder
/// is itself; a checkpoint file (a symbolic link, a bare name typed inside `checkpoints/`)
/// belongs to the folder holding the `checkpoints/` it really lies in. A checkpoint that
/// lies in no run folder is refused before anything is read or written.
pub fn resume_target(target: &Path) -> Result<(PathBuf, Option<PathBuf>), RunError> {
    let refuse = |reason: String| RunError::ResumeTarget {
        target: target.to_path_buf(),
        reason,
    };
    let meta = match std::fs::metadata(target) {
        Ok(m) => m,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            return Err(refuse(
                "no such run folder or checkpoint file; give the run folder (e.g. results/<name>/seed-<seed>) or one of its checkpoints/gen-NNNNNN.json".to_string(),
            ))
        }
        Err(e) => return Err(refuse(e.to_string())),
    };
    if meta.is_dir() {
        return Ok((target.to_path_buf(), None));
    }
    if !meta.is_file() {
        return Err(refuse(
            "not a regular file or folder (only a run folder or a checkpoint file can be resumed)"
                .to_string(),
        ));
    }
    let in_checkpoints = |p: &Path| {
        p.parent()
            .filter(|d| d.file_name().is_some_and(|n| n == CHECKPOINT_DIR))
            .map(|d| match d.parent() {
                Some(r) if !r.as_os_str().is_empty() => r.to_path_buf(),
                _ => PathBuf::from("."),
            })
    };
    let is_link = target
        .symlink_metadata()
        .is_ok_and(|m| m.file_type().is_symlink());
    if !is_link {
        if let Some(dir) = in_checkpoints(target) {
            return Ok((dir, Some(target.to_path_buf())));
        }
    }
    let real = std::fs::canonicalize(target).map_err(|e| refuse(e.to_string()))?;
    match in_checkpoints(&real) {
        Some(dir) => Ok((dir, Some(real))),
        None => Err(refuse(format!(
            "{} is not inside a run folder's {CHECKPOINT_DIR}/ folder, so there is no run to continue; put it in one and resume that folder: mkdir -p RUN/{CHECKPOINT_DIR} && cp {} RUN/{CHECKPOINT_DIR}/ && {} resume RUN",
            real.display(),
            target.display(),
            crate::invocation::program()
        ))),
    }
}

/// [`resume`] with every choice explicit (see [`ResumeRequest`]).
pub fn resume_with(
    target: &Path,
    request: ResumeRequest,
    options: RunOptions<'_>,
    progress: &mut dyn Progress,
) -> Result<RunSummary, RunError> {
    let (dir, file) = resume_target(target)?;
    let lock = lock_folder(&dir)?;
    clean_temp_files(&dir)?;
    if file.is_none() {
        let listed = checkpoint::list_checkpoints(&dir.join(CHECKPOINT_DIR)).unwrap_or_default();
        if listed.is_empty() && holds_run(&dir) {
            let experiment = dir.join(EXPERIMENT_FILE);
            return Err(RunError::NothingToResume {
                dir: dir.clone(),
                experiment: if experiment.is_file() {
                    experiment.display().to_string()
                } else {
                    "EXPERIMENT.toml".to_string()
                },
            });
        }
    }
    let (loaded_path, payload, program) = match &file {
        Some(f) => {
            let (_, p, payload, program) = load_checkpoint(f)?;
            (p, payload, program)
        }
        None => {
            let (_, p, payload, program) = load_checkpoint(&dir)?;
            (p, payload, program)
        }
    };
    let generations = request.generations;
    let last_generation = payload.last.generation;
    // An older checkpoint than the newest: the newer ones would be left behind.
    let cdir = dir.join(CHECKPOINT_DIR);
    let newer: Vec<PathBuf> = checkpoint::list_checkpoints(&cdir)
        .map_err(io_err(&cdir))?
        .into_iter()
        .filter(|(g, _)| *g > last_generation)
        .map(|(_, p)| p)
        .collect();
    let newer_names = newer
        .iter()
        .map(|p| {
            p.file_name()
                .unwrap_or_default()
                .to_string_lossy()
                .into_owned()
        })
        .collect::<Vec<_>>();
    if program != checkpoint::PROGRAM {
        // Reproducibility is promised per version: another version may compute differently
        // (0.2.0 changed the brains' arithmetic), so say so rather than stay silent.
        progress.note(&format!(
            "{} was written by {program}; this is {}. The run continues, but its later \
             generations may differ from a run made entirely with {program}",
            loaded_path.display(),
            checkpoint::PROGRAM
        ));
    }
    let experiment_path = dir.join(EXPERIMENT_FILE);
    let invalid = |error| ExperimentError::Invalid {
        path: experiment_path.clone(),
        error,
    };
    // First every decision, then (only when none refuses) every change: a refused resume
    // touches nothing, and its message gives the whole command that works, with every flag
    // this resume needs.
    let mut needs = ResumeFlags {
        discard_newer: request.discard_newer || !newer.is_empty(),
        allow_config_change: request.allow_config_change,
        shorten: request.shorten,
    };
    // Validated already when the checkpoint was loaded (`check_payload_shape`).
    let checkpointed = Experiment::try_from(payload.experiment.clone()).map_err(invalid)?;
    let mut experiment = checkpointed.clone();
    let mut config_changed = None;
    if experiment_path.exists() {
        let on_disk = Experiment::load(&experiment_path)?;
        if on_disk.config_hash() != experiment.config_hash() {
            needs.allow_config_change = true;
            config_changed = Some(on_disk.clone());
            experiment = on_disk;
        } else {
            if on_disk.evolution.generations != experiment.evolution.generations
                && generations.is_none()
            {
                // Only the length differs: the file was edited to extend the run.
                experiment = experiment
                    .with_overrides()
                    .generations(on_disk.evolution.generations)
                    .build()
                    .map_err(invalid)?;
            }
            if on_disk.output != experiment.output {
                // [output] decides only where and how often results are saved: honoured.
                progress.note(&format!(
                    "{} has an edited [output] table; it is used from now on",
                    experiment_path.display()
                ));
                experiment = experiment
                    .with_overrides()
                    .output(on_disk.output.clone())
                    .build()
                    .map_err(invalid)?;
            }
        }
    }
    let mut shortened = None;
    let mut fewer = None;
    if let Some(g) = generations {
        if g < last_generation + 1 {
            let older = checkpoint::list_checkpoints(&cdir)
                .unwrap_or_default()
                .into_iter()
                .rev()
                .find(|(og, _)| *og < g)
                .map_or(String::new(), |(_, p)| {
                    let flags = ResumeFlags {
                        discard_newer: true,
                        shorten: needs.shorten || g < experiment.evolution.generations,
                        ..needs
                    };
                    format!(
                        ", or continue from an older checkpoint: {}",
                        flags.command(&p, Some(g))
                    )
                });
            return Err(RunError::TooFewGenerations {
                requested: g,
                completed: last_generation + 1,
                checkpoint: loaded_path,
                older,
            });
        }
        let planned = experiment.evolution.generations;
        if g < planned {
            needs.shorten = true;
            fewer = Some((g, planned));
            shortened = Some(format!(
                "resumed from {} with --shorten: generations {planned} -> {g}",
                loaded_path.display()
            ));
        }
        experiment = experiment
            .with_overrides()
            .generations(g)
            .build()
            .map_err(invalid)?;
    }
    let command = needs.command(target, generations);
    if let Some(on_disk) = &config_changed {
        if !request.allow_config_change {
            return Err(RunError::ConfigChanged {
                path: experiment_path,
                checkpoint: loaded_path,
                hashes: format!(
                    "{} vs {}",
                    &on_disk.config_hash()[..12],
                    &checkpointed.config_hash()[..12]
                ),
                changes: changed_keys(&checkpointed, on_disk).join("; "),
                command,
            });
        }
    }
    if !newer.is_empty() && !request.discard_newer {
        return Err(RunError::NewerCheckpoints {
            dir: dir.clone(),
            checkpoint: loaded_path,
            newer: newer_names.join(", "),
            command,
        });
    }
    if let Some((requested, planned)) = fewer.filter(|_| !request.shorten) {
        return Err(RunError::FewerGenerations {
            requested,
            planned,
            command,
        });
    }
    // Every check passed: now the changes.
    if config_changed.is_some() {
        record_config_change(&dir, &checkpointed, &experiment, &loaded_path)?;
    }
    if !newer.is_empty() {
        let aside = dir.join(DISCARDED_DIR);
        std::fs::create_dir_all(&aside).map_err(io_err(&aside))?;
        for p in &newer {
            let to = aside.join(p.file_name().unwrap_or_default());
            std::fs::rename(p, &to).map_err(io_err(p))?;
        }
        record_change(
            &dir,
            &format!(
                "resumed from {} with --discard-newer: moved {} to {DISCARDED_DIR}/",
                loaded_path.display(),
                newer_names.join(", ")
            ),
        )?;
        progress.note(&format!(
            "moved the newer checkpoints {} to {}",
            newer_names.join(", "),
            aside.display()
        ));
    }
    if let Some(line) = shortened {
        record_change(&dir, &line)?;
    }
    write_atomic(&experiment_path, experiment.to_toml().as_bytes())
        .map_err(io_err(&experiment_path))?;
    let mut payload = payload;
    let extending = experiment.evolution.generations > last_generation + 1;
    let replanned = payload.experiment.evolution.generations != experiment.evolution.generations;
    if replanned {
        replan_older_checkpoints(&cdir, last_generation, &experiment)?;
    }
    let rewound = match &payload.end_of_run_validation {
        Some(end) if extending => {
            let written_with = Experiment::try_from(payload.experiment.clone()).map_err(invalid)?;
            let last_extra = payload.history_extra.last().cloned().unwrap_or_default();
            let r = extension::rewind(
                &written_with,
                end,
                payload.validated_best.take(),
                &last_extra,
            );
            payload.validated_best = r.validated_best;
            if let Some(row) = payload.history_extra.last_mut() {
                *row = r.last_extra;
            }
            payload.end_of_run_validation = None;
            progress.note(&format!(
                "generation {last_generation} was validated only because it was the run's last; \
                 that validation is set aside so that the run continues as one planned for {} \
                 generations from the start",
                experiment.evolution.generations
            ));
            true
        }
        _ => false,
    };
    let csv_path = dir.join(FITNESS_FILE);
    let columns = extra_columns(&experiment);
    if rewound {
        // The rewound row replaces the validated one without a "repaired" note.
        let bytes = crate::record::fitness_csv::to_bytes_with(
            &columns,
            &payload.history,
            &payload.history_extra,
        )
        .map_err(io_err(&csv_path))?;
        write_atomic(&csv_path, &bytes).map_err(io_err(&csv_path))?;
    }
    let csv = if payload.history.len() as u64 == last_generation + 1 {
        repair_csv(
            &csv_path,
            &payload.history,
            &payload.history_extra,
            &columns,
            &loaded_path,
            progress,
        )?;
        FitnessCsv::reopen_for_resume_with(&csv_path, last_generation, &columns)?.csv
    } else {
        FitnessCsv::reopen_for_resume_with(&csv_path, last_generation, &columns)?.csv
    };
    let champions = reopen_champions(
        &dir.join(CHAMPIONS_FILE),
        last_generation,
        &loaded_path,
        progress,
    )?;
    let topology = experiment.topology();
    let mut search = search::factory::of(&experiment, &topology);
    search.restore(payload.search.as_ref(), payload.last.generation);
    let mut state = Loop {
        topology,
        dir: dir.clone(),
        csv,
        champions,
        history: payload.history,
        best_ever: payload.best_ever,
        next_generation: last_generation + 1,
        history_extra: payload.history_extra,
        validated_best: payload.validated_best,
        validation_worlds: None,
        end_of_run_validation: payload.end_of_run_validation.clone(),
        experiment,
        _lock: lock,
        search,
    };
    if state.next_generation >= state.experiment.evolution.generations {
        // Nothing left to evaluate: make sure the final files match the finished run.
        let checkpoint = state.finish(&payload.last)?;
        progress.end();
        return Ok(RunSummary {
            dir,
            generations: state.next_generation,
            best_ever: state.best_ever,
            checkpoint: Some(checkpoint),
            validated_best: state.validated_best,
        });
    }
    if rewound {
        // best.json as a run planned this long has it now.
        if state.validated_best.is_none() {
            remove_if_present(&dir.join(BEST_FILE))?;
        }
        state.write_best()?;
    }
    if rewound || replanned {
        // The checkpoint continued from, with the new plan; it goes when the next one is
        // written if the schedule would not have it.
        state.write_checkpoint(&payload.last)?;
    }
    state.search.tell(&payload.last);
    let population = state.search.ask();
    drive(state, population, options, progress)
}

/// Reopens `champions.jsonl` for a run resuming after generation `last_generation` from
/// `checkpoint`, telling the user what was dropped or why the file starts later.
fn reopen_champions(
    path: &Path,
    last_generation: u64,
    checkpoint: &Path,
    progress: &mut dyn Progress,
) -> Result<ChampionsLog, RunError> {
    let reopened = ChampionsLog::reopen_for_resume(path, last_generation)?;
    if reopened.created {
        progress.note(&format!(
            "{} was missing (deleted, or the run was started by a version that did not write \
             it): it starts with generation {}; the champions of generations 0..={last_generation} \
             are not in it (extract any individual of {} with berry-evolve extract)",
            path.display(),
            last_generation + 1,
            checkpoint.display()
        ));
    }
    Ok(reopened.log)
}

/// Makes `fitness.csv` begin with exactly the rows the checkpoint carries (the true ones):
/// a missing file is rebuilt, a damaged or edited row rewritten, and the user told which.
/// Rows after the checkpoint are left for [`FitnessCsv::reopen_for_resume`] to drop.
fn repair_csv(
    path: &Path,
    history: &[FitnessRow],
    history_extra: &[Vec<Option<f64>>],
    columns: &[String],
    checkpoint: &Path,
    progress: &mut dyn Progress,
) -> Result<(), RunError> {
    let expected = crate::record::fitness_csv::to_bytes_with(columns, history, history_extra)
        .map_err(io_err(path))?;
    let existing = match read_regular(path, MAX_CSV_BYTES) {
        Ok(bytes) => Some(bytes),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => None,
        Err(e) => {
            return Err(RunError::Io {
                path: path.to_path_buf(),
                error: e,
            })
        }
    };
    let what = match &existing {
        Some(bytes) if bytes.starts_with(&expected) => return Ok(()),
        None => "it was missing".to_string(),
        Some(bytes) => {
            let line = bytes
                .split(|&b| b == b'\n')
                .zip(expected.split(|&b| b == b'\n'))
                .position(|(a, b)| a != b)
                .unwrap_or(0);
            if line == 0 {
                "its header was damaged".to_string()
            } else if line > history.len() {
                "rows were missing".to_string()
            } else {
                format!(
                    "the row of generation {} differed from the checkpoint",
                    history[line - 1].generation
                )
            }
        }
    };
    write_atomic(path, &expected).map_err(io_err(path))?;
    progress.note(&format!(
        "repaired {}: {what}; rows 0..={} rewritten from {}",
        path.display(),
        history.len().saturating_sub(1),
        checkpoint.display()
    ));
    Ok(())
}

/// Finds and reads the checkpoint to resume from. Returns (run folder, checkpoint, payload,
/// the program that wrote it). Reads only: removes and renames nothing, takes no lock, so
/// `export-csv` can watch a live run. A checkpoint pruned by the live run between listing
/// and reading is skipped for the next newest one (see `checkpoint::load_latest_good`).
pub fn load_checkpoint(
    target: &Path,
) -> Result<(PathBuf, PathBuf, CheckpointPayload, String), RunError> {
    if !target.is_dir() {
        // A file, or something that is neither (refused by the reader, a FIFO included).
        let loaded = checkpoint::load::<CheckpointPayload>(target, None)?;
        check_payload_hash(target, &loaded.config_hash, &loaded.payload)?;
        check_payload_shape(target, &loaded.payload)?;
        let dir = run_dir_of_checkpoint(target);
        return Ok((dir, target.to_path_buf(), loaded.payload, loaded.program));
    }
    let cdir = target.join(CHECKPOINT_DIR);
    let loaded = checkpoint::load_latest_good::<CheckpointPayload>(&cdir, None)?
        .refuse_if_newest_unusable()?;
    check_payload_hash(
        &loaded.path,
        &loaded.checkpoint.config_hash,
        &loaded.checkpoint.payload,
    )?;
    check_payload_shape(&loaded.path, &loaded.checkpoint.payload)?;
    Ok((
        target.to_path_buf(),
        loaded.path.clone(),
        loaded.checkpoint.payload,
        loaded.checkpoint.program,
    ))
}

/// The envelope's config hash must be the hash of the experiment inside it.
fn check_payload_hash(
    path: &Path,
    envelope_hash: &str,
    payload: &CheckpointPayload,
) -> Result<(), RunError> {
    let inner = payload.experiment.config_hash();
    if inner != envelope_hash {
        return Err(RunError::Checkpoint(CheckpointError {
            path: path.to_path_buf(),
            kind: CheckpointErrorKind::ConfigMismatch {
                found: envelope_hash[..envelope_hash.len().min(12)].to_string(),
                expected: inner[..12].to_string(),
            },
            previous_good: None,
        }));
    }
    Ok(())
}

/// The payload must fit its experiment before evolution touches it: a checkpoint edited by
/// hand (and re-signed) could otherwise make variation or selection panic.
fn check_payload_shape(path: &Path, payload: &CheckpointPayload) -> Result<(), RunError> {
    let refuse = |message: String| {
        Err(RunError::Checkpoint(CheckpointError {
            path: path.to_path_buf(),
            kind: CheckpointErrorKind::Content(ContentError::PayloadShape(message)),
            previous_good: None,
        }))
    };
    let experiment = match Experiment::try_from(payload.experiment.clone()) {
        Ok(experiment) => experiment,
        Err(e) => return refuse(format!("its experiment is not valid: {e}")),
    };
    let population = experiment.evolution.evaluated_per_generation();
    let individuals = payload.last.individuals.len();
    if individuals != population {
        return refuse(format!(
            "the last generation holds {individuals} individuals, its experiment evaluates {population} per generation"
        ));
    }
    let parameters = experiment.topology().parameter_count();
    if let Some(problem) = search::factory::of(&experiment, &experiment.topology())
        .state_problem(payload.search.as_ref())
    {
        return refuse(problem);
    }
    let genomes = payload
        .last
        .individuals
        .iter()
        .map(|i| &i.genome)
        .chain(payload.best_ever.as_ref().map(|c| &c.genome));
    for (k, genome) in genomes.enumerate() {
        if genome.parameters.len() != parameters {
            let which = if k < individuals {
                format!("individual {k}")
            } else {
                "the best individual".to_string()
            };
            return refuse(format!(
                "{which} has {} parameters, the experiment's brain has {parameters}",
                genome.parameters.len()
            ));
        }
    }
    Ok(())
}

/// `run/checkpoints/gen-000010.json` → `run`.
fn run_dir_of_checkpoint(path: &Path) -> PathBuf {
    let parent = path.parent().unwrap_or(Path::new("."));
    if parent.file_name().is_some_and(|n| n == CHECKPOINT_DIR) {
        parent.parent().unwrap_or(Path::new(".")).to_path_buf()
    } else {
        parent.to_path_buf()
    }
}

/// Appends a note to `config-changes.log` in the run folder.
fn record_config_change(
    dir: &Path,
    old: &Experiment,
    new: &Experiment,
    checkpoint: &Path,
) -> Result<(), RunError> {
    let mut line = format!(
        "resumed from {} with a changed experiment: config hash {} -> {}",
        checkpoint.display(),
        old.config_hash(),
        new.config_hash()
    );
    for change in changed_keys(old, new) {
        line.push_str("\n  ");
        line.push_str(&change);
    }
    record_change(dir, &line)
}

/// Appends `line` to `config-changes.log`, replacing the file atomically (the log is small).
fn record_change(dir: &Path, line: &str) -> Result<(), RunError> {
    let path = dir.join(CHANGES_FILE);
    let mut text = match read_regular(&path, MAX_CSV_BYTES) {
        Ok(bytes) => bytes,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Vec::new(),
        Err(error) => return Err(RunError::Io { path, error }),
    };
    text.extend_from_slice(line.as_bytes());
    text.push(b'\n');
    write_atomic(&path, &text).map_err(io_err(&path))
}

/// The state the generation loop carries.
struct Loop {
    experiment: Experiment,
    topology: Topology,
    dir: PathBuf,
    csv: FitnessCsv,
    /// `champions.jsonl`, appended with the CSV row.
    champions: ChampionsLog,
    history: Vec<FitnessRow>,
    best_ever: Option<Champion>,
    next_generation: u64,
    /// Held for the whole run: no other process writes this folder meanwhile.
    _lock: RunLock,
    /// The search, as it was when it asked for the generation being evaluated.
    search: Box<dyn Search>,
    history_extra: Vec<Vec<Option<f64>>>,
    validated_best: Option<ValidatedChampion>,
    /// The validation worlds, built at the first validation of this process.
    validation_worlds: Option<Vec<crate::sim::world::World>>,
    /// Set after the last generation when its validation was only for being the last.
    end_of_run_validation: Option<EndOfRunValidation>,
}

impl Loop {
    fn row(&self, generation: &EvaluatedGeneration, summary: &GenerationSummary) -> FitnessRow {
        let population = self.experiment.evolution.evaluated_per_generation() as u64;
        FitnessRow {
            generation: generation.generation,
            evaluations: population * (generation.generation + 1),
            best: summary.stats.best,
            mean: summary.stats.mean,
            median: summary.stats.median,
            worst: summary.stats.worst,
            std: summary.stats.std,
            // 0 until some individual has a finite fitness (as FitnessStats reports an empty set).
            best_ever: self.best_ever.as_ref().map_or(0.0, |c| c.fitness),
            mean_food_a: summary.mean_metabolism[0],
            mean_food_b: summary.mean_metabolism[1],
            mean_food_c: summary.mean_metabolism[2],
            mean_food_d: summary.mean_metabolism[3],
            best_food_a: summary.best_metabolism[0],
            best_food_b: summary.best_metabolism[1],
            best_food_c: summary.best_metabolism[2],
            best_food_d: summary.best_metabolism[3],
            non_finite: summary.non_finite,
        }
    }

    fn write_best(&self) -> Result<(), RunError> {
        if self.experiment.validation.enabled() {
            return self.write_validated_best();
        }
        if let Some(c) = &self.best_ever {
            let file = GenomeFile::new(
                &self.experiment,
                &c.genome,
                Origin::evolved(
                    &self.experiment,
                    c.generation,
                    Some(c.individual),
                    Some(c.fitness),
                    Some(c.metabolism),
                ),
            );
            file.save(&self.dir.join(BEST_FILE))?;
        }
        Ok(())
    }

    fn write_checkpoint(&mut self, last: &EvaluatedGeneration) -> Result<PathBuf, RunError> {
        // The checkpoint must never be ahead of the CSV or the champions on disk (power loss).
        self.csv.sync()?;
        self.champions.sync()?;
        let payload = CheckpointPayload {
            experiment: self.experiment.config().clone(),
            last: last.clone(),
            best_ever: self.best_ever.clone(),
            history: self.history.clone(),
            search: self.search.state(),
            history_extra: self.history_extra.clone(),
            validated_best: self.validated_best.clone(),
            end_of_run_validation: self.end_of_run_validation.clone(),
        };
        let every = self.experiment.output.checkpoint_every;
        Ok(checkpoint::write_checkpoint_superseding(
            &self.dir.join(CHECKPOINT_DIR),
            &self.experiment.config_hash(),
            last.generation,
            &payload,
            self.experiment.output.keep_checkpoints as usize,
            |older| extension::superseded_checkpoint(every, last.generation, older),
        )?)
    }

    /// Final files of a finished run: best.json and the last checkpoint.
    fn finish(&mut self, last: &EvaluatedGeneration) -> Result<PathBuf, RunError> {
        self.write_best()?;
        self.write_checkpoint(last)
    }
}

/// Rewrites the checkpoints in `dir` older than generation `last` that were written for the
/// same experiment with another planned length, with `experiment`'s length: a checkpoint
/// records the run's plan, and a run planned this long from the start wrote them with it.
/// A checkpoint that does not read back, or belongs to another configuration (before a
/// `--allow-config-change`), is left as it is.
pub fn replan_older_checkpoints(
    dir: &Path,
    last: u64,
    experiment: &Experiment,
) -> Result<(), RunError> {
    let generations = experiment.evolution.generations;
    let hash = experiment.config_hash();
    let listed = checkpoint::list_checkpoints(dir).map_err(|error| RunError::Io {
        path: dir.to_path_buf(),
        error,
    })?;
    for (g, path) in listed.into_iter().filter(|(g, _)| *g < last) {
        let Ok(mut old) = checkpoint::load::<CheckpointPayload>(&path, Some(&hash)) else {
            continue;
        };
        if old.payload.experiment.evolution.generations == generations {
            continue;
        }
        old.payload.experiment.evolution.generations = generations;
        // `keep` as large as can be: this rewrite prunes nothing.
        checkpoint::write_checkpoint(dir, &hash, g, &old.payload, usize::MAX)?;
    }
    Ok(())
}

/// Removes `path`; a file already gone is fine.
fn remove_if_present(path: &Path) -> Result<(), RunError> {
    match std::fs::remove_file(path) {
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => Err(RunError::Io {
            path: path.to_path_buf(),
            error: e,
        }),
        _ => Ok(()),
    }
}

/// The newest checkpoint of `dir` that loads.
fn newest_good_checkpoint(dir: &Path) -> Option<PathBuf> {
    checkpoint::load_latest_good::<CheckpointPayload>(&dir.join(CHECKPOINT_DIR), None)
        .ok()
        .map(|loaded| loaded.path)
}

/// Wraps a failed evaluation of the generation loop: a failed rank with what the user can do
/// about it (the other errors are the experiment's and say so themselves).
fn evaluation_failed(dir: &Path, source: EvaluationError) -> RunError {
    if !matches!(source, EvaluationError::Rank { .. }) {
        return source.into();
    }
    let advice = match newest_good_checkpoint(dir) {
        Some(path) => format!(
            "The last good checkpoint, {}, is kept; continue with: {} resume {} \
             (under mpirun with any number of ranks, or without: the results are the same)",
            path.display(),
            crate::invocation::program(),
            dir.display()
        ),
        None => "No checkpoint was written yet; start the run again with --force".to_string(),
    };
    RunError::RankFailed {
        dir: dir.to_path_buf(),
        advice,
        source: Box::new(source),
    }
}

/// Wraps a failed write of the generation loop with what the user can do about it.
fn output_failed(dir: &Path, source: RunError) -> RunError {
    let advice = match newest_good_checkpoint(dir) {
        Some(path) => format!(
            "The last good checkpoint, {}, is kept. Fix the cause below (disk space, permissions, \
             the folder) and continue with: {} resume {}",
            path.display(),
            crate::invocation::program(),
            dir.display()
        ),
        None => "No checkpoint was written yet. Fix the cause below (disk space, permissions, \
                 the folder) and start the run again with --force"
            .to_string(),
    };
    RunError::OutputFailed {
        dir: dir.to_path_buf(),
        advice,
        source: Box::new(source),
    }
}

/// The generation loop: evaluate, record, checkpoint, vary, until done or stopped.
fn drive(
    mut state: Loop,
    mut population: Unevaluated,
    options: RunOptions<'_>,
    progress: &mut dyn Progress,
) -> Result<RunSummary, RunError> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(options.jobs)
        .build()
        .map_err(|e| RunError::Threads {
            jobs: options.jobs,
            message: e.to_string(),
        })?;
    let total = state.experiment.evolution.generations;
    let every = state.experiment.output.checkpoint_every;
    let on_job = progress.within_generation(evaluation_jobs(
        &state.experiment,
        &state.topology,
        state.experiment.evolution.evaluated_per_generation(),
    ));
    progress.begin(state.next_generation, total);
    let mut generation = state.next_generation;
    loop {
        let on_job = on_job.as_deref().map(|f| f as &(dyn Fn() + Sync));
        let evaluated = match options.evaluator {
            Some(evaluator) => evaluate_on(
                evaluator,
                &state.experiment,
                &state.topology,
                generation,
                population.genomes,
                on_job,
            )
            .map_err(|e| evaluation_failed(&state.dir, e))?,
            None => pool.install(|| {
                evaluate_watched(
                    &state.experiment,
                    &state.topology,
                    generation,
                    population.genomes,
                    on_job,
                )
            })?,
        }
        .with_lineage(population.lineage);
        let summary = evaluated.summary();
        let improved =
            state
                .search
                .improved_champion(state.best_ever.as_ref(), &evaluated, &summary);
        if let Some(champion) = improved {
            state.best_ever = Some(champion);
            state
                .write_best()
                .map_err(|e| output_failed(&state.dir, e))?;
        }
        let candidates = state.search.champion_candidates(&evaluated);
        let (mut extras, validated) = pool.install(|| {
            validation::after_generation(
                &state.experiment,
                &state.topology,
                &evaluated,
                &summary,
                total,
                candidates,
                &mut state.validation_worlds,
            )
        })?;
        if let Some(archive) = state.search.archive(&evaluated) {
            // An archive search (MAP-Elites): its metrics end the row; archive.csv is replaced.
            extras.extend(archive.metrics().columns());
            crate::record::archive::write(&state.dir, &archive)
                .map_err(|e| output_failed(&state.dir, io_err(&state.dir.join(ARCHIVE_FILE))(e)))?;
        }
        let replaced = validation::improved(state.validated_best.as_ref(), validated.as_ref());
        if validated.is_some()
            && generation + 1 >= total
            && !validation::is_scheduled(&state.experiment.validation, generation)
        {
            state.end_of_run_validation = Some(EndOfRunValidation {
                replaced_champion: replaced.is_some(),
                previous: replaced.as_ref().and_then(|_| state.validated_best.clone()),
            });
        }
        if let Some(v) = replaced {
            state.validated_best = Some(v);
            state
                .write_best()
                .map_err(|e| output_failed(&state.dir, e))?;
        }
        let row = state.row(&evaluated, &summary);
        state
            .csv
            .append_with(&row, &extras)
            .map_err(|e| output_failed(&state.dir, e.into()))?;
        state
            .append_champion(&evaluated, &summary)
            .map_err(|e| output_failed(&state.dir, e))?;
        state.history.push(row);
        if !extras.is_empty() {
            state.history_extra.push(extras);
        }
        progress.generation(&row);
        let is_last = generation + 1 >= total;
        let stop_requested = options.stop.is_some_and(|s| s.load(Ordering::SeqCst));
        if is_last {
            let path = state
                .finish(&evaluated)
                .map_err(|e| output_failed(&state.dir, e))?;
            progress.checkpoint(&path);
            progress.end();
            return Ok(RunSummary {
                dir: state.dir.clone(),
                generations: total,
                best_ever: state.best_ever.clone(),
                checkpoint: Some(path),
                validated_best: state.validated_best.clone(),
            });
        }
        if (generation + 1) % every == 0 || stop_requested {
            let path = state
                .write_checkpoint(&evaluated)
                .map_err(|e| output_failed(&state.dir, e))?;
            progress.checkpoint(&path);
            if stop_requested {
                return Err(RunError::Interrupted {
                    generation,
                    checkpoint: path.clone(),
                    dir: state.dir.clone(),
                    summary: Box::new(RunSummary {
                        dir: state.dir.clone(),
                        generations: generation + 1,
                        best_ever: state.best_ever.clone(),
                        checkpoint: Some(path),
                        validated_best: state.validated_best.clone(),
                    }),
                });
            }
        }
        population = pool.install(|| {
            state.search.tell(&evaluated);
            state.search.ask()
        });
        generation += 1;
    }
}
