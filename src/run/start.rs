//! Starting a new run: refuse what cannot work before touching the folder (a dangling
//! `--out`, a world that cannot be built, a folder another process writes or that holds a
//! run without `--force`), write the effective experiment and the empty outputs, then hand
//! generation 0 to the generation loop.

use super::error::{io_err, RunError};
use super::folder::{clean_temp_files, holds_run, lock_folder, output_failed, remove_own_files};
use super::generation_loop::{drive, Loop};
use super::names::{CHAMPIONS_FILE, CHECKPOINT_DIR, EXPERIMENT_FILE, FITNESS_FILE};
use super::progress::{Progress, RunOptions, RunSummary};
use crate::evo::life::EvaluationError;
use crate::evo::search;
use crate::evo::TrialPlan;
use crate::experiment::Experiment;
use crate::record::atomic::write_atomic;
use crate::record::champions::ChampionsLog;
use crate::record::fitness_csv::{extra_columns, FitnessCsv};
use std::path::Path;

/// Builds generation 0's trial worlds as the run will (group 0), so that a world that cannot
/// be built (a placement rule with no room) is found before anything is written: `run`
/// refuses it touching no folder, and `inspect` reports it.
pub fn check_worlds(experiment: &Experiment) -> Result<(), EvaluationError> {
    let plan = TrialPlan::new(experiment);
    let creatures = plan.group_size as usize;
    for t in 0..plan.trials {
        crate::evo::life::trial_world(
            &plan,
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
