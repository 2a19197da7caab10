//! The resume's apply step: carries out a [`ResumePlan`] that no refusal stopped. Records
//! the changes in config-changes.log, moves newer checkpoints aside, writes the effective
//! experiment, rewrites older checkpoints with a new plan, sets aside an end-of-run
//! validation the run is extended past, repairs `fitness.csv` and `champions.jsonl` from the
//! checkpoint, and hands the next generation to the generation loop.

use super::plan::{file_names, ResumePlan};
use crate::evo::search;
use crate::evo::state::EvaluatedGeneration;
use crate::experiment::Experiment;
use crate::input::{read_regular, MAX_CSV_BYTES};
use crate::record::atomic::write_atomic;
use crate::record::champions::ChampionsLog;
use crate::record::fitness_csv::{extra_columns, FitnessCsv, FitnessRow};
use crate::run::checkpoints::{replan_older_checkpoints, CheckpointPayload};
use crate::run::error::{io_err, RunError};
use crate::run::extension;
use crate::run::folder::{record_change, record_config_change, remove_if_present};
use crate::run::generation_loop::{drive, Loop};
use crate::run::lock::RunLock;
use crate::run::names::{
    BEST_FILE, CHAMPIONS_FILE, CHECKPOINT_DIR, DISCARDED_DIR, EXPERIMENT_FILE, FITNESS_FILE,
};
use crate::run::progress::{Progress, RunOptions, RunSummary};
use std::path::Path;

/// The checkpoint a resume continues from.
pub struct Resumed<'a> {
    /// The run folder.
    pub dir: &'a Path,
    /// The checkpoint file read.
    pub checkpoint: &'a Path,
    /// What it holds.
    pub payload: CheckpointPayload,
    /// Its experiment, validated.
    pub experiment: &'a Experiment,
}

/// Carries out `plan` on the run folder of `from`, whose `lock` the caller holds, and
/// continues the run (or, with nothing left to evaluate, makes its final files match the
/// finished run).
pub fn apply(
    plan: ResumePlan,
    from: Resumed<'_>,
    lock: RunLock,
    options: RunOptions<'_>,
    progress: &mut dyn Progress,
) -> Result<RunSummary, RunError> {
    change_folder(&plan, &from, progress)?;
    let replanned = plan.replanned;
    let (mut state, last, rewound) = reopen(plan, from, lock, progress)?;
    if state.next_generation >= state.experiment.evolution.generations {
        // Nothing left to evaluate: make sure the final files match the finished run.
        let checkpoint = state.finish(&last)?;
        progress.end();
        return Ok(state.summary(state.next_generation, checkpoint));
    }
    if rewound {
        // best.json as a run planned this long has it now.
        if state.validated_best.is_none() {
            remove_if_present(&state.dir.join(BEST_FILE))?;
        }
        state.write_best()?;
    }
    if rewound || replanned {
        // The checkpoint continued from, with the new plan; it goes when the next one is
        // written if the schedule would not have it.
        state.write_checkpoint(&last)?;
    }
    state.search.tell(&last);
    let population = state.search.ask();
    drive(state, population, options, progress)
}

/// The plan's changes to the folder before the run reopens its files: the change log's
/// lines, the newer checkpoints moved aside, the effective experiment.toml, and the older
/// checkpoints rewritten with a new planned length.
fn change_folder(
    plan: &ResumePlan,
    from: &Resumed<'_>,
    progress: &mut dyn Progress,
) -> Result<(), RunError> {
    let dir = from.dir;
    if plan.config_changed {
        record_config_change(dir, from.experiment, &plan.experiment, from.checkpoint)?;
    }
    if !plan.discard.is_empty() {
        let names = file_names(&plan.discard).join(", ");
        let aside = dir.join(DISCARDED_DIR);
        std::fs::create_dir_all(&aside).map_err(io_err(&aside))?;
        for p in &plan.discard {
            let to = aside.join(p.file_name().unwrap_or_default());
            std::fs::rename(p, &to).map_err(io_err(p))?;
        }
        record_change(
            dir,
            &format!(
                "resumed from {} with --discard-newer: moved {names} to {DISCARDED_DIR}/",
                from.checkpoint.display(),
            ),
        )?;
        progress.note(&format!(
            "moved the newer checkpoints {names} to {}",
            aside.display()
        ));
    }
    if let Some((requested, planned)) = plan.shortened {
        record_change(
            dir,
            &format!(
                "resumed from {} with --shorten: generations {planned} -> {requested}",
                from.checkpoint.display()
            ),
        )?;
    }
    let experiment_path = dir.join(EXPERIMENT_FILE);
    write_atomic(&experiment_path, plan.experiment.to_toml().as_bytes())
        .map_err(io_err(&experiment_path))?;
    if plan.replanned {
        replan_older_checkpoints(
            &dir.join(CHECKPOINT_DIR),
            from.payload.last.generation,
            &plan.experiment,
        )?;
    }
    Ok(())
}

/// The generation loop's state as the checkpoint left it, with the end-of-run validation set
/// aside when the run is extended past it, and `fitness.csv` and `champions.jsonl` reopened
/// to match the checkpoint. Returns it, the checkpoint's last generation and whether the
/// validation was set aside.
fn reopen(
    plan: ResumePlan,
    from: Resumed<'_>,
    lock: RunLock,
    progress: &mut dyn Progress,
) -> Result<(Loop, EvaluatedGeneration, bool), RunError> {
    let Resumed {
        dir,
        checkpoint,
        mut payload,
        experiment: written_with,
    } = from;
    let experiment = plan.experiment;
    let last_generation = payload.last.generation;
    let rewound = plan.extending && payload.end_of_run_validation.is_some();
    if let Some(end) = payload.end_of_run_validation.take_if(|_| plan.extending) {
        let last_extra = payload.history_extra.last().cloned().unwrap_or_default();
        let r = extension::rewind(
            written_with,
            &end,
            payload.validated_best.take(),
            &last_extra,
        );
        payload.validated_best = r.validated_best;
        if let Some(row) = payload.history_extra.last_mut() {
            *row = r.last_extra;
        }
        progress.note(&format!(
            "generation {last_generation} was validated only because it was the run's last; \
             that validation is set aside so that the run continues as one planned for {} \
             generations from the start",
            experiment.evolution.generations
        ));
    }
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
    if payload.history.len() as u64 == last_generation + 1 {
        repair_csv(
            &csv_path,
            &payload.history,
            &payload.history_extra,
            &columns,
            checkpoint,
            progress,
        )?;
    }
    let csv = FitnessCsv::reopen_for_resume_with(&csv_path, last_generation, &columns)?.csv;
    let champions = reopen_champions(
        &dir.join(CHAMPIONS_FILE),
        last_generation,
        checkpoint,
        progress,
    )?;
    let topology = experiment.topology();
    let mut search = search::factory::of(&experiment, &topology);
    search.restore(payload.search.as_ref(), last_generation);
    let state = Loop {
        topology,
        dir: dir.to_path_buf(),
        csv,
        champions,
        history: payload.history,
        best_ever: payload.best_ever,
        next_generation: last_generation + 1,
        history_extra: payload.history_extra,
        validated_best: payload.validated_best,
        validation_worlds: None,
        end_of_run_validation: payload.end_of_run_validation,
        experiment,
        _lock: lock,
        search,
    };
    Ok((state, payload.last, rewound))
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
