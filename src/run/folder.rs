//! The run folder and the files a run owns in it: taking its lock, cleaning what a killed
//! write left, telling a run's own files from a user's (`--force` removes only those),
//! appending to the change log, and the advice a failed run gives about its last good
//! checkpoint. The names are in [`super::names`], the lock itself in [`super::lock`].

use super::checkpoints::CheckpointPayload;
use super::error::{io_err, RunError};
use super::lock::{self, LockError, RunLock};
use super::names::{
    BASELINE_FILE, BEST_FILE, CHAMPIONS_FILE, CHANGES_FILE, CHECKPOINT_DIR, DISCARDED_DIR,
    EXPERIMENT_FILE, FITNESS_FILE,
};
use crate::evo::life::EvaluationError;
use crate::experiment::diff::changed_keys;
use crate::experiment::Experiment;
use crate::input::{read_regular, read_regular_text, MAX_CSV_BYTES, MAX_EXPERIMENT_BYTES};
use crate::record::atomic::{remove_stale_temp_files, write_atomic};
use crate::record::checkpoint;
use std::path::{Path, PathBuf};

/// Does `dir` already hold (part of) a run?
pub(super) fn holds_run(dir: &Path) -> bool {
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
pub(super) fn lock_folder(dir: &Path) -> Result<RunLock, RunError> {
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
pub(super) fn clean_temp_files(dir: &Path) -> Result<(), RunError> {
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
pub(super) fn remove_own_files(dir: &Path) -> Result<Vec<String>, RunError> {
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

/// Appends a note to `config-changes.log` in the run folder.
pub(super) fn record_config_change(
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
pub(super) fn record_change(dir: &Path, line: &str) -> Result<(), RunError> {
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

/// Removes `path`; a file already gone is fine.
pub(super) fn remove_if_present(path: &Path) -> Result<(), RunError> {
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
pub(super) fn evaluation_failed(dir: &Path, source: EvaluationError) -> RunError {
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
pub(super) fn output_failed(dir: &Path, source: RunError) -> RunError {
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
