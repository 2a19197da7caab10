//! The generation loop: evaluate a generation, write what it produced (best.json, the
//! fitness row, the champion, a checkpoint when due), then let the search vary, until the
//! run is done or asked to stop. [`Loop`] is the state it carries, started by
//! [`super::start()`] or by the resume's apply step.

use super::checkpoints::CheckpointPayload;
use super::error::{io_err, RunError};
use super::extension::{self, EndOfRunValidation};
use super::folder::{evaluation_failed, output_failed};
use super::lock::RunLock;
use super::names::{BEST_FILE, CHECKPOINT_DIR};
use super::progress::{Progress, RunOptions, RunSummary};
use crate::brain::spec::Topology;
use crate::evo::door::{Evaluate, Worlds};
use crate::evo::evaluate::evaluation_jobs;
use crate::evo::search::{Search, Unevaluated};
use crate::evo::state::{Champion, EvaluatedGeneration, GenerationSummary};
use crate::evo::validation::{self, ValidatedChampion};
use crate::evo::worlds::BuiltWorlds;
use crate::experiment::Experiment;
use crate::record::archive::{self, ARCHIVE_FILE};
use crate::record::champions::ChampionsLog;
use crate::record::checkpoint;
use crate::record::fitness_csv::{FitnessCsv, FitnessRow};
use crate::record::genome_file::{GenomeFile, Origin};
use crate::seed::Generation;
use std::path::PathBuf;
use std::sync::atomic::Ordering;

/// The state the generation loop carries.
pub(super) struct Loop {
    pub(super) experiment: Experiment,
    pub(super) topology: Topology,
    pub(super) dir: PathBuf,
    pub(super) csv: FitnessCsv,
    /// `champions.jsonl`, appended with the CSV row.
    pub(super) champions: ChampionsLog,
    pub(super) history: Vec<FitnessRow>,
    pub(super) best_ever: Option<Champion>,
    pub(super) next_generation: u64,
    /// Held for the whole run: no other process writes this folder meanwhile.
    pub(super) _lock: RunLock,
    /// The search, as it was when it asked for the generation being evaluated.
    pub(super) search: Box<dyn Search>,
    pub(super) history_extra: Vec<Vec<Option<f64>>>,
    pub(super) validated_best: Option<ValidatedChampion>,
    /// The validation worlds, built at the first validation of this process.
    pub(super) validation_worlds: Option<BuiltWorlds>,
    /// Set after the last generation when its validation was only for being the last.
    pub(super) end_of_run_validation: Option<EndOfRunValidation>,
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

    pub(super) fn write_best(&self) -> Result<(), RunError> {
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

    pub(super) fn write_checkpoint(
        &mut self,
        last: &EvaluatedGeneration,
    ) -> Result<PathBuf, RunError> {
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
    pub(super) fn finish(&mut self, last: &EvaluatedGeneration) -> Result<PathBuf, RunError> {
        self.write_best()?;
        self.write_checkpoint(last)
    }
}

/// The generation loop: evaluate, record, checkpoint, vary, until done or stopped.
pub(super) fn drive(
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
        let genomes = &population.genomes;
        let request = Evaluate::new(
            &state.experiment,
            &state.topology,
            genomes,
            Worlds::Training(Generation(generation)),
        )
        .watched(on_job);
        let evaluations = match options.evaluator {
            Some(evaluator) => request
                .run_on(evaluator)
                .map_err(|e| evaluation_failed(&state.dir, e))?,
            None => pool.install(|| request.run())?,
        };
        let evaluated = EvaluatedGeneration::new(generation, population.genomes, evaluations)
            .with_lineage(population.lineage);
        let row = state.record_generation(&evaluated, &pool, total)?;
        progress.generation(&row);
        let is_last = generation + 1 >= total;
        let stop_requested = options.stop.is_some_and(|s| s.load(Ordering::SeqCst));
        if is_last {
            let path = state
                .finish(&evaluated)
                .map_err(|e| output_failed(&state.dir, e))?;
            progress.checkpoint(&path);
            progress.end();
            return Ok(state.summary(total, path));
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
                    summary: Box::new(state.summary(generation + 1, path)),
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

impl Loop {
    /// Writes what generation `evaluated` (of a run of `total` generations) produced, in
    /// this order: `best.json` when the champion improved, the validation of its candidates
    /// (and `best.json` again when the champion on validation changed), its `fitness.csv`
    /// row and its line of `champions.jsonl`; returns the row. A failed write names the last
    /// good checkpoint ([`output_failed`]).
    fn record_generation(
        &mut self,
        evaluated: &EvaluatedGeneration,
        pool: &rayon::ThreadPool,
        total: u64,
    ) -> Result<FitnessRow, RunError> {
        let generation = evaluated.generation;
        let summary = evaluated.summary();
        let improved = self
            .search
            .improved_champion(self.best_ever.as_ref(), evaluated, &summary);
        if let Some(champion) = improved {
            self.best_ever = Some(champion);
            self.write_best().map_err(|e| output_failed(&self.dir, e))?;
        }
        let candidates = self.search.champion_candidates(evaluated);
        let (mut extras, validated) = pool.install(|| {
            validation::after_generation(
                &self.experiment,
                &self.topology,
                evaluated,
                &summary,
                total,
                candidates,
                &mut self.validation_worlds,
            )
        })?;
        if let Some(archive) = self.search.archive(evaluated) {
            // An archive search (MAP-Elites): its metrics end the row; archive.csv is replaced.
            extras.extend(archive.metrics().columns());
            archive::write(&self.dir, &archive)
                .map_err(|e| output_failed(&self.dir, io_err(&self.dir.join(ARCHIVE_FILE))(e)))?;
        }
        let replaced = validation::improved(self.validated_best.as_ref(), validated.as_ref());
        if validated.is_some()
            && generation + 1 >= total
            && !validation::is_scheduled(&self.experiment.validation, generation)
        {
            self.end_of_run_validation = Some(EndOfRunValidation {
                replaced_champion: replaced.is_some(),
                previous: replaced.as_ref().and_then(|_| self.validated_best.clone()),
            });
        }
        if let Some(v) = replaced {
            self.validated_best = Some(v);
            self.write_best().map_err(|e| output_failed(&self.dir, e))?;
        }
        let row = self.row(evaluated, &summary);
        self.csv
            .append_with(&row, &extras)
            .map_err(|e| output_failed(&self.dir, e.into()))?;
        self.append_champion(evaluated, &summary)
            .map_err(|e| output_failed(&self.dir, e))?;
        self.history.push(row);
        if !extras.is_empty() {
            self.history_extra.push(extras);
        }
        Ok(row)
    }

    /// Where the run stands after `generations` generations, `checkpoint` the last written.
    pub(super) fn summary(&self, generations: u64, checkpoint: PathBuf) -> RunSummary {
        RunSummary {
            dir: self.dir.clone(),
            generations,
            best_ever: self.best_ever.clone(),
            checkpoint: Some(checkpoint),
            validated_best: self.validated_best.clone(),
        }
    }
}
