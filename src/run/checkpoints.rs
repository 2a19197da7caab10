//! A run's checkpoints as the run reads them: what one holds ([`CheckpointPayload`]), finding
//! and reading the one to resume from with its checks (the envelope's hash, the payload's
//! shape), and rewriting older ones when a run's planned length changes. The envelope, the
//! atomic writes and the pruning are `record::checkpoint`'s.

use super::error::RunError;
use super::extension::EndOfRunValidation;
use super::names::CHECKPOINT_DIR;
use crate::evo::search::{self, SearchState};
use crate::evo::state::{Champion, EvaluatedGeneration};
use crate::evo::validation::ValidatedChampion;
use crate::experiment::{Experiment, ExperimentConfig};
use crate::record::checkpoint::{self, CheckpointError, CheckpointErrorKind, ContentError};
use crate::record::fitness_csv::FitnessRow;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

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
