//! A run: one experiment evolving in a run folder. Owns the folder's files (effective
//! `experiment.toml`, `fitness.csv` written row by row, `best.json`, `checkpoints/`) and the
//! generation loop that connects evolution to them, including resuming from a checkpoint so
//! that a stopped run finishes with the same bytes as one never stopped.

use crate::brain::spec::Topology;
use crate::evo::evaluate::EvaluationError;
use crate::evo::state::{
    evaluate, first_generation, improved_champion_for, next_generation_of, Champion,
    EvaluatedGeneration, GenerationSummary, SearchState,
};
use crate::experiment::{Experiment, ExperimentError};
use crate::record::atomic::{remove_stale_temp_files, write_atomic};
use crate::record::checkpoint::{self, CheckpointError, CheckpointErrorKind, ContentError};
use crate::record::fitness_csv::{FitnessCsv, FitnessRow};
use crate::record::genome_file::{GenomeFile, GenomeFileError, Origin};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use thiserror::Error;

/// File names inside a run folder.
pub const EXPERIMENT_FILE: &str = "experiment.toml";
/// The fitness curve.
pub const FITNESS_FILE: &str = "fitness.csv";
/// The best genome so far.
pub const BEST_FILE: &str = "best.json";
/// The checkpoint folder.
pub const CHECKPOINT_DIR: &str = "checkpoints";

/// What a checkpoint holds besides its envelope (format, program version, config hash,
/// generation, checksum). No random generator state is needed: every stream is derived from
/// the seed and the generation (see `seed::stream`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CheckpointPayload {
    /// The effective experiment, seed included.
    pub experiment: Experiment,
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
}

/// Why a run could not start, continue or finish.
#[derive(Debug, Error)]
pub enum RunError {
    /// The run folder already holds a run.
    #[error("{dir} already holds a run; continue it with `berry-evolve resume {dir}` or start over with --force")]
    FolderInUse {
        /// The folder.
        dir: PathBuf,
    },
    /// The run folder could not be created (e.g. a parent is a regular file).
    #[error("cannot create the run folder {dir}: {error}; choose another --out, or make sure every parent of it is a writable folder")]
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
    #[error("{path} differs from the experiment in checkpoint {checkpoint} (config hash {found} vs {expected}); the run would no longer be the one its seed describes. Restore the file, or pass --allow-config-change to continue anyway (the change is recorded in the run folder)")]
    ConfigChanged {
        /// The experiment file.
        path: PathBuf,
        /// The checkpoint.
        checkpoint: PathBuf,
        /// Hash of the file's experiment (short).
        found: String,
        /// Hash in the checkpoint (short).
        expected: String,
    },
    /// `resume --generations N` asked for fewer generations than the checkpoint holds.
    #[error("--generations {requested}: checkpoint {checkpoint} already holds {completed} completed generations; ask for at least that many")]
    TooFewGenerations {
        /// What was asked for.
        requested: u64,
        /// Generations the checkpoint holds.
        completed: u64,
        /// The checkpoint.
        checkpoint: PathBuf,
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
    /// Stopped by the user (Ctrl-C / SIGTERM) after writing a checkpoint.
    #[error("interrupted after generation {generation}; the checkpoint {checkpoint} holds it. Continue with: berry-evolve resume {dir}")]
    Interrupted {
        /// Last completed generation.
        generation: u64,
        /// The checkpoint written.
        checkpoint: PathBuf,
        /// The run folder.
        dir: PathBuf,
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
}

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
}

fn io_err(path: &Path) -> impl FnOnce(std::io::Error) -> RunError + '_ {
    move |error| RunError::Io {
        path: path.to_path_buf(),
        error,
    }
}

/// Does `dir` already hold (part of) a run?
fn holds_run(dir: &Path) -> bool {
    [EXPERIMENT_FILE, FITNESS_FILE, BEST_FILE, CHECKPOINT_DIR]
        .iter()
        .any(|f| dir.join(f).exists())
}

/// Starts a new run of `experiment` in `dir`. Refuses a folder that already holds a run
/// unless `force`, in which case the old run's files are removed first.
pub fn start(
    experiment: Experiment,
    dir: &Path,
    force: bool,
    options: RunOptions<'_>,
    progress: &mut dyn Progress,
) -> Result<RunSummary, RunError> {
    if dir.is_dir() {
        // A run killed while writing (e.g. before --force) leaves `.<name>.tmp-*` files.
        remove_stale_temp_files(dir).map_err(io_err(dir))?;
    }
    if holds_run(dir) {
        if !force {
            return Err(RunError::FolderInUse {
                dir: dir.to_path_buf(),
            });
        }
        for f in [EXPERIMENT_FILE, FITNESS_FILE, BEST_FILE] {
            let p = dir.join(f);
            if p.exists() {
                std::fs::remove_file(&p).map_err(io_err(&p))?;
            }
        }
        let c = dir.join(CHECKPOINT_DIR);
        if c.exists() {
            std::fs::remove_dir_all(&c).map_err(io_err(&c))?;
        }
    }
    let checkpoints = dir.join(CHECKPOINT_DIR);
    std::fs::create_dir_all(&checkpoints).map_err(|error| RunError::CreateFolder {
        dir: dir.to_path_buf(),
        error,
    })?;
    let experiment_path = dir.join(EXPERIMENT_FILE);
    write_atomic(&experiment_path, experiment.to_toml().as_bytes())
        .map_err(io_err(&experiment_path))?;
    let csv = FitnessCsv::create(&dir.join(FITNESS_FILE))?;
    let topology = experiment.topology();
    let (population, search) = first_generation(&experiment, &topology);
    drive(
        Loop {
            experiment,
            topology,
            dir: dir.to_path_buf(),
            csv,
            history: Vec::new(),
            best_ever: None,
            next_generation: 0,
            search,
        },
        population,
        options,
        progress,
    )
}

/// Where to resume from: a run folder (its newest good checkpoint) or a checkpoint file.
pub fn resume(
    target: &Path,
    generations: Option<u64>,
    allow_config_change: bool,
    options: RunOptions<'_>,
    progress: &mut dyn Progress,
) -> Result<RunSummary, RunError> {
    let (dir, loaded_path, payload, program) = load_checkpoint(target)?;
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
    let mut experiment = payload.experiment.clone();
    let experiment_path = dir.join(EXPERIMENT_FILE);
    if experiment_path.exists() {
        let on_disk = Experiment::load(&experiment_path)?;
        if on_disk.config_hash() != experiment.config_hash() {
            if !allow_config_change {
                return Err(RunError::ConfigChanged {
                    path: experiment_path,
                    checkpoint: loaded_path,
                    found: on_disk.config_hash()[..12].to_string(),
                    expected: experiment.config_hash()[..12].to_string(),
                });
            }
            record_config_change(&dir, &experiment, &on_disk, &loaded_path)?;
            experiment = on_disk;
        } else if on_disk.evolution.generations != experiment.evolution.generations
            && generations.is_none()
        {
            // Only the length differs: the file was edited to extend the run.
            experiment.evolution.generations = on_disk.evolution.generations;
        }
    }
    if let Some(g) = generations {
        if g < payload.last.generation + 1 {
            return Err(RunError::TooFewGenerations {
                requested: g,
                completed: payload.last.generation + 1,
                checkpoint: loaded_path,
            });
        }
        experiment.evolution.generations = g;
    }
    experiment
        .validate()
        .map_err(|error| ExperimentError::Invalid {
            path: experiment_path.clone(),
            error,
        })?;
    write_atomic(&experiment_path, experiment.to_toml().as_bytes())
        .map_err(io_err(&experiment_path))?;
    let last_generation = payload.last.generation;
    let csv_path = dir.join(FITNESS_FILE);
    let csv = if csv_path.exists() || payload.history.len() as u64 != last_generation + 1 {
        FitnessCsv::reopen_for_resume(&csv_path, last_generation)?.csv
    } else {
        // A deleted fitness.csv is rebuilt from the rows the checkpoint carries (the same
        // bytes: the same rows through the same writer).
        let mut csv = FitnessCsv::create(&csv_path)?;
        for row in &payload.history {
            csv.append(row)?;
        }
        csv
    };
    let topology = experiment.topology();
    let mut state = Loop {
        topology,
        dir: dir.clone(),
        csv,
        history: payload.history,
        best_ever: payload.best_ever,
        next_generation: last_generation + 1,
        experiment,
        search: payload.search.clone(),
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
        });
    }
    let (population, search) =
        next_generation_of(&state.experiment, &payload.last, payload.search.as_ref());
    state.search = search;
    drive(state, population, options, progress)
}

/// Finds and reads the checkpoint to resume from. Returns (run folder, checkpoint, payload,
/// the program that wrote it).
pub fn load_checkpoint(
    target: &Path,
) -> Result<(PathBuf, PathBuf, CheckpointPayload, String), RunError> {
    if target.is_file() {
        let loaded = checkpoint::load::<CheckpointPayload>(target, None)?;
        check_payload_hash(target, &loaded.config_hash, &loaded.payload)?;
        check_payload_shape(target, &loaded.payload)?;
        let dir = run_dir_of_checkpoint(target);
        return Ok((dir, target.to_path_buf(), loaded.payload, loaded.program));
    }
    let cdir = target.join(CHECKPOINT_DIR);
    remove_stale_temp_files(target).map_err(io_err(target))?;
    if cdir.is_dir() {
        remove_stale_temp_files(&cdir).map_err(io_err(&cdir))?;
    }
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
    if let Err(e) = payload.experiment.validate() {
        return refuse(format!("its experiment is not valid: {e}"));
    }
    let population = payload.experiment.evolution.evaluated_per_generation();
    let individuals = payload.last.individuals.len();
    if individuals != population {
        return refuse(format!(
            "the last generation holds {individuals} individuals, its experiment evaluates {population} per generation"
        ));
    }
    let parameters = payload.experiment.topology().parameter_count();
    match (
        &payload.search,
        payload.experiment.evolution.pgpe_settings(),
    ) {
        (None, None) => {}
        (Some(SearchState::Pgpe(state)), Some(_)) => {
            if let Some(problem) = state.problem(parameters) {
                return refuse(problem);
            }
        }
        (Some(_), None) => {
            return refuse("it holds a pgpe state, but its experiment uses the ga".into())
        }
        (None, Some(_)) => {
            return refuse("its experiment uses pgpe, but it holds no pgpe state".into())
        }
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
    use std::io::Write;
    let path = dir.join("config-changes.log");
    let mut f = std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(&path)
        .map_err(io_err(&path))?;
    writeln!(
        f,
        "resumed from {} with a changed experiment: config hash {} -> {}",
        checkpoint.display(),
        old.config_hash(),
        new.config_hash()
    )
    .and_then(|_| f.sync_all())
    .map_err(io_err(&path))
}

/// The state the generation loop carries.
struct Loop {
    experiment: Experiment,
    topology: Topology,
    dir: PathBuf,
    csv: FitnessCsv,
    history: Vec<FitnessRow>,
    best_ever: Option<Champion>,
    next_generation: u64,
    /// The search distribution that sampled the generation being evaluated (PGPE).
    search: Option<SearchState>,
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
        if let Some(c) = &self.best_ever {
            let file = GenomeFile::new(
                &self.experiment,
                &c.genome,
                Origin {
                    description: None,
                    experiment: Some(self.experiment.name.clone()),
                    config_hash: Some(self.experiment.config_hash()),
                    generation: Some(c.generation),
                    individual: Some(c.individual),
                    fitness: Some(c.fitness),
                    metabolism: Some(c.metabolism),
                },
            );
            file.save(&self.dir.join(BEST_FILE))?;
        }
        Ok(())
    }

    fn write_checkpoint(&mut self, last: &EvaluatedGeneration) -> Result<PathBuf, RunError> {
        // The checkpoint must never be ahead of the CSV on disk (power loss).
        self.csv.sync()?;
        let payload = CheckpointPayload {
            experiment: self.experiment.clone(),
            last: last.clone(),
            best_ever: self.best_ever.clone(),
            history: self.history.clone(),
            search: self.search.clone(),
        };
        Ok(checkpoint::write_checkpoint(
            &self.dir.join(CHECKPOINT_DIR),
            &self.experiment.config_hash(),
            last.generation,
            &payload,
            self.experiment.output.keep_checkpoints as usize,
        )?)
    }

    /// Final files of a finished run: best.json and the last checkpoint.
    fn finish(&mut self, last: &EvaluatedGeneration) -> Result<PathBuf, RunError> {
        self.write_best()?;
        self.write_checkpoint(last)
    }
}

/// Wraps a failed write of the generation loop with what the user can do about it.
fn output_failed(dir: &Path, source: RunError) -> RunError {
    let newest = checkpoint::load_latest_good::<CheckpointPayload>(&dir.join(CHECKPOINT_DIR), None)
        .ok()
        .map(|loaded| loaded.path);
    let advice = match newest {
        Some(path) => format!(
            "The last good checkpoint, {}, is kept. Fix the cause below (disk space, permissions, \
             the folder) and continue with: berry-evolve resume {}",
            path.display(),
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
    mut population: Vec<crate::brain::genome::Genome>,
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
    progress.begin(state.next_generation, total);
    let mut generation = state.next_generation;
    loop {
        let evaluated =
            pool.install(|| evaluate(&state.experiment, &state.topology, generation, population))?;
        let summary = evaluated.summary();
        let improved = improved_champion_for(
            &state.experiment,
            state.best_ever.as_ref(),
            &evaluated,
            &summary,
        );
        if let Some(champion) = improved {
            state.best_ever = Some(champion);
            state
                .write_best()
                .map_err(|e| output_failed(&state.dir, e))?;
        }
        let row = state.row(&evaluated, &summary);
        state
            .csv
            .append(&row)
            .map_err(|e| output_failed(&state.dir, e.into()))?;
        state.history.push(row);
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
                    checkpoint: path,
                    dir: state.dir.clone(),
                });
            }
        }
        let (next, search) = pool
            .install(|| next_generation_of(&state.experiment, &evaluated, state.search.as_ref()));
        population = next;
        state.search = search;
        generation += 1;
    }
}
