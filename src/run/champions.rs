//! The run folder's `champions.jsonl` (see [`crate::record::champions`]): which genome of a
//! generation is its champion, and how the log is reopened when a run resumes.

use super::{Loop, Progress, RunError};
use crate::evo::state::{EvaluatedGeneration, GenerationSummary};
use crate::record::champions::ChampionsLog;
use crate::record::genome_file::{GenomeFile, Origin};
use std::path::Path;

impl Loop {
    /// Appends generation `evaluated`'s best individual (the highest fitness, ties to the
    /// lower index: the one behind fitness.csv's `best` column, for PGPE too, whose centre
    /// is only the best when it scores best) to `champions.jsonl`. A generation without a
    /// finite fitness has no best and gets no line.
    pub(super) fn append_champion(
        &mut self,
        evaluated: &EvaluatedGeneration,
        summary: &GenerationSummary,
    ) -> Result<(), RunError> {
        let Some(b) = summary.best_individual else {
            return Ok(());
        };
        let best = &evaluated.individuals[b];
        let file = GenomeFile::new(
            &self.experiment,
            &best.genome,
            Origin::evolved(
                &self.experiment,
                evaluated.generation,
                Some(b as u64),
                best.evaluation.fitness,
                Some(best.evaluation.metabolism),
            ),
        );
        Ok(self.champions.append(&file)?)
    }
}

/// Reopens `champions.jsonl` for a run resuming after generation `last_generation` from
/// `checkpoint`, telling the user what was dropped or why the file starts later.
pub(super) fn reopen_champions(
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
