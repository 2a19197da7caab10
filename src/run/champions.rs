//! The run folder's `champions.jsonl` (see [`crate::record::champions`]): which genome of a
//! generation is its champion.

use super::error::RunError;
use super::generation_loop::Loop;
use crate::evo::state::{EvaluatedGeneration, GenerationSummary};
use crate::record::genome_file::{GenomeFile, Origin};

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
