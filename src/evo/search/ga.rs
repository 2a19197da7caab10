//! The generational genetic algorithm behind the [`Search`] trait (`[evolution] algorithm =
//! "ga"`, the default): generation 0 drawn from the seed's initialisation stream
//! ([`crate::evo::init`]), each next generation made from the last evaluated one by elitism,
//! selection, crossover and mutation ([`crate::evo::vary`]) drawing from the variation stream
//! of that generation. Its state is the last evaluated generation (of which it copies only
//! the genomes the next generation can choose), which a checkpoint holds anyway, so it saves
//! no [`SearchState`].

use super::{Search, SearchState, Unevaluated};
use crate::brain::genome::Genome;
use crate::brain::spec::Topology;
use crate::evo::init::initial_population;
use crate::evo::lineage::{Birth, Lineage};
use crate::evo::state::EvaluatedGeneration;
use crate::evo::vary::{choosable, next_generation_with_lineage, vary};
use crate::experiment::evolution::EvolutionSpec;
use crate::experiment::Experiment;
use crate::seed::{stream, Generation, IndividualId, Purpose, Rng, Seed, TrialIndex};

/// The genetic algorithm's search.
#[derive(Debug, Clone)]
pub struct Ga {
    seed: Seed,
    spec: EvolutionSpec,
    parameters: usize,
    /// The last evaluated generation, told: its number, genomes and selection fitness.
    parents: Option<(u64, Vec<Genome>, Vec<f64>)>,
}

impl Ga {
    /// A new search for `experiment` with genomes of `parameters` parameters.
    pub fn new(experiment: &Experiment, parameters: usize) -> Ga {
        Ga {
            seed: experiment.seed(),
            spec: experiment.evolution.clone(),
            parameters,
            parents: None,
        }
    }
}

impl Ga {
    /// Tells the GA the evaluated generation with `scores` (one per individual, higher is
    /// better) in place of its fitness: what selection and elitism then rank by. Novelty
    /// search tells its novelty scores this way.
    pub(super) fn tell_scores(&mut self, evaluated: &EvaluatedGeneration, scores: Vec<f64>) {
        self.parents = Some((
            evaluated.generation,
            choosable_genomes(&self.spec, evaluated, &scores),
            scores,
        ));
    }
}

/// The evaluated generation's genomes, in order, copied only where the next generation can
/// choose them ([`choosable`]; the others are left empty): with truncation selection most
/// individuals cannot be parents, and copying every genome was much of a `tell`.
fn choosable_genomes(
    spec: &EvolutionSpec,
    evaluated: &EvaluatedGeneration,
    scores: &[f64],
) -> Vec<Genome> {
    let choosable = choosable(spec, scores);
    evaluated
        .individuals
        .iter()
        .zip(choosable)
        .map(|(i, chosen)| {
            if chosen {
                i.genome.clone()
            } else {
                Genome {
                    parameters: Vec::new(),
                    step_size: None,
                }
            }
        })
        .collect()
}

impl Search for Ga {
    fn name(&self) -> &'static str {
        "ga"
    }

    fn describe(&self) -> &'static str {
        "genetic algorithm"
    }

    fn evaluated_per_generation(&self) -> usize {
        self.spec.population
    }

    fn generation(&self) -> u64 {
        self.parents.as_ref().map_or(0, |(g, _, _)| g + 1)
    }

    fn ask(&self) -> Unevaluated {
        match &self.parents {
            None => {
                let genomes =
                    initial_population(&self.spec, self.parameters, &mut initialisation(self.seed));
                Unevaluated {
                    lineage: vec![Lineage::orphan(Birth::Random); genomes.len()],
                    genomes,
                }
            }
            Some((generation, genomes, fitness)) => {
                let (genomes, lineage) = vary(
                    &self.spec,
                    genomes,
                    fitness,
                    &mut variation(self.seed, *generation),
                );
                Unevaluated { genomes, lineage }
            }
        }
    }

    fn tell(&mut self, evaluated: &EvaluatedGeneration) {
        self.tell_scores(evaluated, evaluated.selection_fitness());
    }

    fn state(&self) -> Option<SearchState> {
        None
    }

    fn restore(&mut self, _state: Option<&SearchState>, _generation: u64) {
        // Nothing to restore: the evaluated generation told next is the whole state.
    }

    fn state_problem(&self, state: Option<&SearchState>) -> Option<String> {
        state.map(|s| {
            format!(
                "it holds a {} state, but its experiment uses the ga",
                s.algorithm()
            )
        })
    }

    fn first_genomes(&self, n: usize) -> Vec<Genome> {
        // The GA draws individual after individual from one stream, so a smaller population
        // is the first individuals of the full one.
        let mut spec = self.spec.clone();
        spec.population = n.min(self.spec.population);
        initial_population(&spec, self.parameters, &mut initialisation(self.seed))
    }
}

/// The seed's initialisation stream, which generation 0 is drawn from.
fn initialisation(seed: Seed) -> Rng {
    stream(
        seed,
        Purpose::Initialisation,
        Generation(0),
        IndividualId(0),
        TrialIndex(0),
    )
}

/// The variation stream of generation `generation`, which generation + 1 is made with.
fn variation(seed: Seed, generation: u64) -> Rng {
    stream(
        seed,
        Purpose::Variation,
        Generation(generation),
        IndividualId(0),
        TrialIndex(0),
    )
}

/// Generation 0 of the GA: drawn from the seed's initialisation stream (also a handy source
/// of random genomes for tests and tools, whatever the experiment's algorithm).
pub fn first_population(experiment: &Experiment, topology: &Topology) -> Vec<Genome> {
    initial_population(
        &experiment.evolution,
        topology.parameter_count(),
        &mut initialisation(experiment.seed()),
    )
}

/// The GA's generation g + 1 from evaluated generation g, drawn from the variation stream of g.
pub fn offspring(experiment: &Experiment, parents: &EvaluatedGeneration) -> Vec<Genome> {
    offspring_with_lineage(experiment, parents).0
}

/// [`offspring`] with each one's lineage.
pub fn offspring_with_lineage(
    experiment: &Experiment,
    parents: &EvaluatedGeneration,
) -> (Vec<Genome>, Vec<Lineage>) {
    let genomes: Vec<Genome> = parents
        .individuals
        .iter()
        .map(|i| i.genome.clone())
        .collect();
    next_generation_with_lineage(
        &experiment.evolution,
        &genomes,
        &parents.selection_fitness(),
        &mut variation(experiment.seed(), parents.generation),
    )
}
