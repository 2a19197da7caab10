//! Resuming a run: find what to continue from (a run folder or one of its checkpoints),
//! decide from the checkpoint, the experiment file in the folder and the request what the
//! run continues as ([`plan`]: pure, every refusal happens there, so a refused resume
//! touches nothing), then carry it out and continue ([`apply`]).

mod apply;
mod plan;

pub use plan::{ResumePlan, ResumeRequest};

use crate::experiment::{Experiment, ExperimentError};
use crate::record::checkpoint;
use crate::run::checkpoints::load_checkpoint;
use crate::run::error::{io_err, RunError};
use crate::run::folder::{clean_temp_files, holds_run, lock_folder};
use crate::run::names::{CHECKPOINT_DIR, EXPERIMENT_FILE};
use crate::run::progress::{Progress, RunOptions, RunSummary};
use apply::Resumed;
use plan::Found;
use std::path::{Path, PathBuf};

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
        plan::check_something_to_resume(
            &dir,
            &listed,
            holds_run(&dir),
            dir.join(EXPERIMENT_FILE).is_file(),
        )?;
    }
    let (_, loaded_path, payload, program) = load_checkpoint(file.as_deref().unwrap_or(&dir))?;
    let cdir = dir.join(CHECKPOINT_DIR);
    let listed = checkpoint::list_checkpoints(&cdir).map_err(io_err(&cdir))?;
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
    // Validated already when the checkpoint was loaded (`check_payload_shape`).
    let checkpointed = Experiment::try_from(payload.experiment.clone()).map_err(|error| {
        ExperimentError::Invalid {
            path: experiment_path.clone(),
            error,
        }
    })?;
    let on_disk = if experiment_path.exists() {
        Some(Experiment::load(&experiment_path)?)
    } else {
        None
    };
    if plan::output_edited(&checkpointed, on_disk.as_ref()) {
        progress.note(&format!(
            "{} has an edited [output] table; it is used from now on",
            experiment_path.display()
        ));
    }
    let found = Found {
        target,
        dir: &dir,
        checkpoint: &loaded_path,
        experiment: &checkpointed,
        last_generation: payload.last.generation,
        checkpoints: &listed,
        experiment_path: &experiment_path,
    };
    let plan = ResumePlan::decide(&found, on_disk.as_ref(), request)?;
    let from = Resumed {
        dir: &dir,
        checkpoint: &loaded_path,
        payload,
        experiment: &checkpointed,
    };
    apply::apply(plan, from, lock, options, progress)
}
