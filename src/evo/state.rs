//! The state of an evolution between generations: the last evaluated generation, the best
//! individual ever seen, the search distribution (PGPE only, [`SearchState`]), and how to make
//! the next generation from them. Pure: no files, no clocks; the run module saves and restores
//! this state.

use crate::brain::genome::Genome;
use crate::brain::spec::Topology;
use crate::evo::evaluate::{evaluate_population_on, Evaluation, Evaluator, JobDone, ThisProcess};
use crate::evo::init::initial_population;
use crate::evo::life::EvaluationError;
use crate::evo::lineage::{Birth, Lineage};
use crate::evo::pgpe::{self, PgpeState};
use crate::evo::stats::FitnessStats;
use crate::evo::vary::next_generation_with_lineage;
use crate::experiment::Experiment;
use crate::seed::{stream, Generation, IndividualId, Purpose, TrialIndex};
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

/// What an algorithm carries from one generation to the next besides the evaluated
/// generation itself: nothing for the GA (its state is its population), the search
/// distribution that sampled the generation for PGPE. Saved in checkpoints.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SearchState {
    /// PGPE's centre, standard deviations and ClipUp velocity.
    Pgpe(PgpeState),
}

/// A generation before its evaluation: its genomes in population order, where each came
/// from, and the search state that sampled it (PGPE).
#[derive(Debug, Clone, PartialEq)]
pub struct Unevaluated {
    /// The genomes.
    pub genomes: Vec<Genome>,
    /// One lineage per genome, in the same order.
    pub lineage: Vec<Lineage>,
    /// The search distribution that sampled it (PGPE only).
    pub search: Option<SearchState>,
}

/// The lineage of a PGPE generation of `population` samples and the centre: the samples
/// have no parent index (see [`Birth::PgpeSample`]); the centre's parent is `centre_parent`.
fn pgpe_lineage(population: usize, centre_parent: Option<usize>) -> Vec<Lineage> {
    let mut lineage = vec![Lineage::orphan(Birth::PgpeSample); population];
    lineage.push(match centre_parent {
        Some(p) => Lineage::of(Birth::PgpeCentre, &[p]),
        None => Lineage::orphan(Birth::PgpeCentre),
    });
    lineage
}

/// Generation 0 of the experiment's algorithm and the search state that sampled it: the
/// GA's random population ([`first_population`]), or PGPE's samples around its initial
/// centre followed by the centre.
pub fn first_generation(experiment: &Experiment, topology: &Topology) -> Unevaluated {
    match experiment.evolution.pgpe_settings() {
        None => {
            let genomes = first_population(experiment, topology);
            Unevaluated {
                lineage: vec![Lineage::orphan(Birth::Random); genomes.len()],
                genomes,
                search: None,
            }
        }
        Some(spec) => {
            let state = PgpeState::initial(&spec, topology.parameter_count());
            let population = experiment.evolution.population;
            let genomes = pgpe::sample(experiment.seed(), Generation(0), &state, population);
            Unevaluated {
                lineage: pgpe_lineage(population, None),
                genomes,
                search: Some(SearchState::Pgpe(state)),
            }
        }
    }
}

/// Generation g + 1 of the experiment's algorithm from evaluated generation g and the search
/// state that sampled it: the GA's [`offspring`], or PGPE's update (on the samples' fitness,
/// the centre's left out) and new samples. A PGPE experiment without a state (a run switched
/// from the GA with `--allow-config-change`) starts its centre at generation g's best
/// individual.
pub fn next_generation_of(
    experiment: &Experiment,
    parents: &EvaluatedGeneration,
    search: Option<&SearchState>,
) -> Unevaluated {
    let Some(spec) = experiment.evolution.pgpe_settings() else {
        let (genomes, lineage) = offspring_with_lineage(experiment, parents);
        return Unevaluated {
            genomes,
            lineage,
            search: None,
        };
    };
    let population = experiment.evolution.population;
    let fitness = parents.selection_fitness();
    let (next, centre_parent) = match search {
        Some(SearchState::Pgpe(state)) if fitness.len() == population + 1 => (
            pgpe::step(
                experiment.seed(),
                &spec,
                state,
                Generation(parents.generation),
                &fitness[..population],
            ),
            population,
        ),
        _ => {
            let best = parents.summary().best_individual.unwrap_or(0);
            (
                PgpeState::centred_on(&spec, &parents.individuals[best].genome.parameters),
                best,
            )
        }
    };
    let genomes = pgpe::sample(
        experiment.seed(),
        Generation(parents.generation + 1),
        &next,
        population,
    );
    Unevaluated {
        genomes,
        lineage: pgpe_lineage(population, Some(centre_parent)),
        search: Some(SearchState::Pgpe(next)),
    }
}

/// The first `n` genomes of generation 0 (at most the generation's size), drawn as
/// [`first_generation`] draws them but without the rest: what a timing calibration lives
/// with, so that it meets the brains a run starts from at the cost of a few.
pub fn first_genomes(experiment: &Experiment, topology: &Topology, n: usize) -> Vec<Genome> {
    let n = n.min(experiment.evolution.evaluated_per_generation());
    let mut genomes = match experiment.evolution.pgpe_settings() {
        // The GA draws individual after individual from one stream, so a smaller population
        // is the first individuals of the full one.
        None => {
            let mut spec = experiment.evolution.clone();
            spec.population = n;
            initial_population(
                &spec,
                topology.parameter_count(),
                &mut initialisation(experiment),
            )
        }
        // The whole generation (PGPE's ends with its centre).
        Some(_) if n == experiment.evolution.evaluated_per_generation() => {
            first_generation(experiment, topology).genomes
        }
        // PGPE's samples come in mirrored pairs from one noise stream, then the centre: the
        // pairs of a smaller sample are the first pairs of the full one.
        Some(spec) => {
            let state = PgpeState::initial(&spec, topology.parameter_count());
            pgpe::sample(experiment.seed(), Generation(0), &state, n + 1)
        }
    };
    genomes.truncate(n);
    genomes
}

/// The seed's initialisation stream, which generation 0 is drawn from.
fn initialisation(experiment: &Experiment) -> crate::seed::Rng {
    stream(
        experiment.seed(),
        Purpose::Initialisation,
        Generation(0),
        IndividualId(0),
        TrialIndex(0),
    )
}

/// Generation 0: drawn from the seed's initialisation stream.
pub fn first_population(experiment: &Experiment, topology: &Topology) -> Vec<Genome> {
    initial_population(
        &experiment.evolution,
        topology.parameter_count(),
        &mut initialisation(experiment),
    )
}

/// Generation g + 1 from evaluated generation g, drawn from the variation stream of g.
pub fn offspring(experiment: &Experiment, parents: &EvaluatedGeneration) -> Vec<Genome> {
    offspring_with_lineage(experiment, parents).0
}

/// [`offspring`] with each one's lineage.
pub fn offspring_with_lineage(
    experiment: &Experiment,
    parents: &EvaluatedGeneration,
) -> (Vec<Genome>, Vec<Lineage>) {
    let mut rng = stream(
        experiment.seed(),
        Purpose::Variation,
        Generation(parents.generation),
        IndividualId(0),
        TrialIndex(0),
    );
    let genomes: Vec<Genome> = parents
        .individuals
        .iter()
        .map(|i| i.genome.clone())
        .collect();
    next_generation_with_lineage(
        &experiment.evolution,
        &genomes,
        &parents.selection_fitness(),
        &mut rng,
    )
}

/// Evaluates `population` as generation `generation` (in parallel on the current rayon pool).
/// The individuals carry no lineage; [`EvaluatedGeneration::with_lineage`] adds it.
pub fn evaluate(
    experiment: &Experiment,
    topology: &Topology,
    generation: u64,
    population: Vec<Genome>,
) -> Result<EvaluatedGeneration, EvaluationError> {
    evaluate_on(
        &ThisProcess,
        experiment,
        topology,
        generation,
        population,
        None,
    )
}

/// [`evaluate`], telling `on_job` of each evaluation job as it finishes (see [`JobDone`]).
pub fn evaluate_watched(
    experiment: &Experiment,
    topology: &Topology,
    generation: u64,
    population: Vec<Genome>,
    on_job: JobDone<'_>,
) -> Result<EvaluatedGeneration, EvaluationError> {
    evaluate_on(
        &ThisProcess,
        experiment,
        topology,
        generation,
        population,
        on_job,
    )
}

/// [`evaluate_watched`] with the evaluation jobs run by `evaluator` (e.g. MPI ranks): the
/// same bits.
pub fn evaluate_on(
    evaluator: &dyn Evaluator,
    experiment: &Experiment,
    topology: &Topology,
    generation: u64,
    population: Vec<Genome>,
    on_job: JobDone<'_>,
) -> Result<EvaluatedGeneration, EvaluationError> {
    let evaluations = evaluate_population_on(
        evaluator,
        experiment,
        topology,
        &population,
        Generation(generation),
        on_job,
    )?;
    Ok(EvaluatedGeneration {
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
    })
}

impl EvaluatedGeneration {
    /// The generation with `lineage[i]` recorded for individual i (in population order; an
    /// individual beyond the list keeps none).
    pub fn with_lineage(mut self, lineage: Vec<Lineage>) -> EvaluatedGeneration {
        for (individual, born) in self.individuals.iter_mut().zip(lineage) {
            individual.lineage = Some(born);
        }
        self
    }
}

/// The new champion under the experiment's algorithm: for the GA any individual
/// ([`improved_champion`]); for PGPE only the centre, the last individual, since the centre is
/// the solution the search converges to and a sample is the centre plus noise.
pub fn improved_champion_for(
    experiment: &Experiment,
    previous: Option<&Champion>,
    generation: &EvaluatedGeneration,
    summary: &GenerationSummary,
) -> Option<Champion> {
    if experiment.evolution.pgpe_settings().is_none() {
        return improved_champion(previous, generation, summary);
    }
    let c = generation.individuals.len().checked_sub(1)?;
    let centre = &generation.individuals[c];
    let fitness = centre.evaluation.fitness?;
    if previous.is_some_and(|p| fitness <= p.fitness) {
        return None;
    }
    Some(Champion {
        genome: centre.genome.clone(),
        fitness,
        metabolism: centre.evaluation.metabolism,
        generation: generation.generation,
        individual: c as u64,
    })
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
