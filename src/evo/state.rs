//! The state of an evolution between generations: the last evaluated generation, the best
//! individual ever seen, and how a generation is evaluated and summarised. How the next
//! generation is made is the search's ([`crate::evo::search`], whose state, [`crate::evo::search::SearchState`], a
//! checkpoint also holds). Pure: no files, no clocks; the run module saves and restores this
//! state.

use crate::brain::genome::Genome;
use crate::brain::spec::Topology;
use crate::evo::door::{Evaluate, Worlds};
use crate::evo::evaluate::Evaluation;
use crate::evo::life::EvaluationError;
use crate::evo::lineage::Lineage;
use crate::evo::stats::FitnessStats;
use crate::experiment::Experiment;
use crate::seed::Generation;
use crate::sim::metabolism::Metabolism;
use serde::{Deserialize, Serialize};

/// A genome and how it did.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Individual {
    /// The genome.
    pub genome: Genome,
    /// Its evaluation in its generation's trial worlds.
    pub evaluation: Evaluation,
    /// How it was born and from which individuals of the previous generation; absent in
    /// checkpoints written before lineage was recorded (berry-evolve 0.3.5 and earlier).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lineage: Option<Lineage>,
}

/// The best individual seen so far, with where it came from.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Champion {
    /// The genome.
    pub genome: Genome,
    /// Its fitness in the generation it was evaluated in.
    pub fitness: f64,
    /// Its mean final metabolic vector over that generation's trials.
    pub metabolism: Metabolism,
    /// The generation it belongs to.
    pub generation: u64,
    /// Its index in that generation.
    pub individual: u64,
}

/// One evaluated generation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EvaluatedGeneration {
    /// Its number, from 0.
    pub generation: u64,
    /// Its individuals in population order.
    pub individuals: Vec<Individual>,
}

/// What a generation's evaluation says, reduced serially in index order.
#[derive(Debug, Clone, PartialEq)]
pub struct GenerationSummary {
    /// Fitness statistics over the individuals with a finite fitness.
    pub stats: FitnessStats,
    /// Index of the best individual (highest fitness, ties to the lower index).
    pub best_individual: Option<usize>,
    /// Population mean of each metabolic component.
    pub mean_metabolism: Metabolism,
    /// The best individual's metabolic components.
    pub best_metabolism: Metabolism,
    /// Individuals whose brain produced a non-finite output.
    pub non_finite: u64,
}

impl EvaluatedGeneration {
    /// Summarises the generation serially, in index order.
    pub fn summary(&self) -> GenerationSummary {
        let finite: Vec<f64> = self
            .individuals
            .iter()
            .filter_map(|i| i.evaluation.fitness)
            .collect();
        let mut best_individual: Option<usize> = None;
        for (index, individual) in self.individuals.iter().enumerate() {
            if let Some(f) = individual.evaluation.fitness {
                let better = match best_individual {
                    None => true,
                    Some(b) => f > self.individuals[b].evaluation.selection_fitness(),
                };
                if better {
                    best_individual = Some(index);
                }
            }
        }
        let n = self.individuals.len().max(1) as f64;
        let mut mean_metabolism = [0.0; 4];
        for individual in &self.individuals {
            for (m, x) in mean_metabolism
                .iter_mut()
                .zip(individual.evaluation.metabolism)
            {
                *m += x;
            }
        }
        for m in &mut mean_metabolism {
            *m /= n;
        }
        GenerationSummary {
            stats: FitnessStats::of(&finite),
            best_individual,
            mean_metabolism,
            best_metabolism: best_individual
                .map(|b| self.individuals[b].evaluation.metabolism)
                .unwrap_or([0.0; 4]),
            non_finite: (self.individuals.len() - finite.len()) as u64,
        }
    }

    /// The fitness values used for selection, in population order.
    pub fn selection_fitness(&self) -> Vec<f64> {
        self.individuals
            .iter()
            .map(|i| i.evaluation.selection_fitness())
            .collect()
    }
}

/// Evaluates `population` as generation `generation` (in parallel on the current rayon pool;
/// [`crate::evo::door::Evaluate`] on its training worlds). The individuals carry no lineage;
/// [`EvaluatedGeneration::with_lineage`] adds it.
pub fn evaluate(
    experiment: &Experiment,
    topology: &Topology,
    generation: u64,
    population: Vec<Genome>,
) -> Result<EvaluatedGeneration, EvaluationError> {
    let worlds = Worlds::Training(Generation(generation));
    let evaluations = Evaluate::new(experiment, topology, &population, worlds).run()?;
    Ok(EvaluatedGeneration::new(
        generation,
        population,
        evaluations,
    ))
}

impl EvaluatedGeneration {
    /// Generation `generation`: `population` with its `evaluations` (in the same order), no
    /// lineage yet.
    pub fn new(
        generation: u64,
        population: Vec<Genome>,
        evaluations: Vec<Evaluation>,
    ) -> EvaluatedGeneration {
        EvaluatedGeneration {
            generation,
            individuals: population
                .into_iter()
                .zip(evaluations)
                .map(|(genome, evaluation)| Individual {
                    genome,
                    evaluation,
                    lineage: None,
                })
                .collect(),
        }
    }

    /// The generation with `lineage[i]` recorded for individual i (in population order; an
    /// individual beyond the list keeps none).
    pub fn with_lineage(mut self, lineage: Vec<Lineage>) -> EvaluatedGeneration {
        for (individual, born) in self.individuals.iter_mut().zip(lineage) {
            individual.lineage = Some(born);
        }
        self
    }
}

/// The new best-ever individual if `generation` beats `previous` (strictly; an equal
/// fitness keeps the older champion).
pub fn improved_champion(
    previous: Option<&Champion>,
    generation: &EvaluatedGeneration,
    summary: &GenerationSummary,
) -> Option<Champion> {
    let b = summary.best_individual?;
    let best = &generation.individuals[b];
    let fitness = best.evaluation.fitness?;
    if previous.is_some_and(|p| fitness <= p.fitness) {
        return None;
    }
    Some(Champion {
        genome: best.genome.clone(),
        fitness,
        metabolism: best.evaluation.metabolism,
        generation: generation.generation,
        individual: b as u64,
    })
}
