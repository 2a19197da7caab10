//! `best.json` of a run with `[validation]` on: the best individual on the validation worlds
//! so far, its origin saying so.

use super::error::RunError;
use super::generation_loop::Loop;
use super::names::BEST_FILE;
use crate::record::genome_file::{GenomeFile, Origin};

impl Loop {
    /// Writes the validation champion to `best.json` (nothing before the first validation).
    /// Its origin's generation, individual, fitness and metabolism are those of its training
    /// evaluation (so that `replay` reproduces them); the description gives the validation
    /// fitness.
    pub(super) fn write_validated_best(&self) -> Result<(), RunError> {
        let Some(v) = &self.validated_best else {
            return Ok(());
        };
        let spec = &self.experiment.validation;
        let fitness = v
            .validation
            .fitness
            .map_or("non-finite".to_string(), |f| f.to_string());
        let description = format!(
            "chosen on validation: validation fitness {fitness} ({:?} over {} validation \
             worlds), the best of generation {}'s top {} by training fitness",
            self.experiment.evaluation.aggregate, spec.trials, v.generation, spec.top
        );
        let file = GenomeFile::new(
            &self.experiment,
            &v.genome,
            Origin {
                description: Some(description),
                ..Origin::evolved(
                    &self.experiment,
                    v.generation,
                    v.individual,
                    v.training_fitness,
                    v.training_metabolism,
                )
            },
        );
        file.save(&self.dir.join(BEST_FILE))?;
        Ok(())
    }
}
