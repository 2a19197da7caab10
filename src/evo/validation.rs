//! Champions chosen on validation worlds (`[validation]`), and the behaviour-measure and
//! validation columns of a generation's `fitness.csv` row.
//!
//! Every `every` generations (and after the last) the generation's `top` best individuals by
//! training fitness, plus any further candidates the search passes in (e.g. an evolution
//! strategy's distribution centre), are evaluated alone on `trials` fixed validation worlds:
//! [`crate::seed::Purpose::ValidationWorld`] streams, the same worlds at every validation and never
//! trained on (training uses [`crate::seed::Purpose::TrialWorld`] at generations below 2^40, `compare` the
//! same purpose at generation 2^40). The best candidate on validation so far is the champion
//! written to `best.json`. The validation fitness is aggregated over the validation worlds as
//! `[evaluation] aggregate` says.

use crate::brain::genome::Genome;
use crate::brain::spec::Topology;
use crate::evo::door::{Evaluate, Worlds};
use crate::evo::evaluate::Evaluation;
use crate::evo::life::EvaluationError;
use crate::evo::state::{EvaluatedGeneration, GenerationSummary};
use crate::evo::worlds::{BuiltWorlds, WorldSet};
use crate::experiment::{Experiment, ValidationSpec};
use crate::sim::metabolism::Metabolism;
use serde::{Deserialize, Serialize};

/// A genome to validate, with where it came from.
#[derive(Debug, Clone, PartialEq)]
pub struct Candidate {
    /// The genome.
    pub genome: Genome,
    /// The generation it belongs to.
    pub generation: u64,
    /// Its index in that generation's population (`None`: not a member, e.g. a search
    /// distribution's centre).
    pub individual: Option<u64>,
    /// Its training fitness, when it has one.
    pub training_fitness: Option<f64>,
    /// Its mean final metabolic vector in training, when it has one.
    pub training_metabolism: Option<Metabolism>,
}

/// The best candidate on validation, with its validation evaluation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ValidatedChampion {
    /// The genome.
    pub genome: Genome,
    /// Its evaluation on the validation worlds (fitness, metabolism, measures).
    pub validation: Evaluation,
    /// The generation it was validated after (and belongs to).
    pub generation: u64,
    /// Its index in that generation (`None`: not a population member).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub individual: Option<u64>,
    /// Its training fitness in that generation, when it has one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub training_fitness: Option<f64>,
    /// Its mean final metabolic vector in training, when it has one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub training_metabolism: Option<Metabolism>,
}

impl ValidatedChampion {
    /// Its validation fitness (`f64::MIN` when non-finite, which never wins).
    pub fn fitness(&self) -> f64 {
        self.validation.selection_fitness()
    }
}

/// Is generation `generation` (of `total`) one after which to validate?
pub fn is_due(spec: &ValidationSpec, generation: u64, total: u64) -> bool {
    spec.enabled() && (is_scheduled(spec, generation) || generation + 1 >= total)
}

/// Is generation `generation` validated by `every`'s schedule, whatever the run's length? A
/// run also validates its last generation ([`is_due`]); that end-of-run validation is the one
/// a longer run would not make, so extending a run sets it aside (see `run::extension`).
pub fn is_scheduled(spec: &ValidationSpec, generation: u64) -> bool {
    spec.enabled() && (generation + 1) % spec.every == 0
}

/// The indices of `generation`'s best `k` individuals with a finite fitness, best first
/// (ties to the lower index).
pub fn top_individuals(generation: &EvaluatedGeneration, k: usize) -> Vec<usize> {
    let mut ranked: Vec<(usize, f64)> = generation
        .individuals
        .iter()
        .enumerate()
        .filter_map(|(i, ind)| ind.evaluation.fitness.map(|f| (i, f)))
        .collect();
    // Stable sort by descending fitness: equal fitness keeps index order.
    ranked.sort_by(|a, b| b.1.total_cmp(&a.1));
    ranked.into_iter().take(k).map(|(i, _)| i).collect()
}

/// The generation's top `[validation] top` individuals as candidates, best first.
pub fn top_candidates(experiment: &Experiment, generation: &EvaluatedGeneration) -> Vec<Candidate> {
    top_individuals(generation, experiment.validation.top as usize)
        .into_iter()
        .map(|i| {
            let ind = &generation.individuals[i];
            Candidate {
                genome: ind.genome.clone(),
                generation: generation.generation,
                individual: Some(i as u64),
                training_fitness: ind.evaluation.fitness,
                training_metabolism: Some(ind.evaluation.metabolism),
            }
        })
        .collect()
}

/// Evaluates `candidates` on `worlds` (the validation worlds, [`WorldSet::build`]'s) and
/// returns the best of them
/// (highest finite validation fitness; ties to the earlier candidate), or `None` when no
/// candidate has a finite one. In parallel on the current rayon pool; the same bits for any
/// number of threads.
pub fn validate(
    experiment: &Experiment,
    topology: &Topology,
    candidates: &[Candidate],
    worlds: &BuiltWorlds,
) -> Result<Option<ValidatedChampion>, EvaluationError> {
    let genomes: Vec<Genome> = candidates.iter().map(|c| c.genome.clone()).collect();
    let evaluations = Evaluate::new(experiment, topology, &genomes, Worlds::Built(worlds)).run()?;
    let mut best: Option<usize> = None;
    for (k, e) in evaluations.iter().enumerate() {
        if let Some(f) = e.fitness {
            if best.is_none_or(|b| f > evaluations[b].selection_fitness()) {
                best = Some(k);
            }
        }
    }
    Ok(best.map(|b| {
        let c = &candidates[b];
        ValidatedChampion {
            genome: c.genome.clone(),
            validation: evaluations[b].clone(),
            generation: c.generation,
            individual: c.individual,
            training_fitness: c.training_fitness,
            training_metabolism: c.training_metabolism,
        }
    }))
}

/// `candidate` if it beats `previous` on validation (strictly: an equal fitness keeps the
/// older champion).
pub fn improved(
    previous: Option<&ValidatedChampion>,
    candidate: Option<&ValidatedChampion>,
) -> Option<ValidatedChampion> {
    let c = candidate?;
    c.validation.fitness?;
    if previous.is_some_and(|p| c.fitness() <= p.fitness()) {
        return None;
    }
    Some(c.clone())
}

/// The behaviour-measure columns of a generation's row, in
/// [`crate::record::fitness_csv::extra_columns`]' order: per measure, the best individual's
/// value (empty when no individual has a finite fitness) and the population mean (over every
/// individual, summed in index order).
pub fn measure_columns(
    experiment: &Experiment,
    generation: &EvaluatedGeneration,
    summary: &GenerationSummary,
) -> Vec<Option<f64>> {
    let n = generation.individuals.len().max(1) as f64;
    let mut values = Vec::with_capacity(2 * experiment.behaviour.measures.len());
    for k in 0..experiment.behaviour.measures.len() {
        let best = summary.best_individual.and_then(|b| {
            generation.individuals[b]
                .evaluation
                .measures
                .get(k)
                .copied()
        });
        let mean = generation
            .individuals
            .iter()
            .map(|i| i.evaluation.measures.get(k).copied().unwrap_or(0.0))
            .sum::<f64>()
            / n;
        values.push(best);
        values.push(Some(mean));
    }
    values
}

/// The validation columns of a generation's row (`validation_best`, then
/// `validation_<measure>` per measure): `best`, this generation's best candidate on
/// validation, or empty fields when the generation was not validated (or no candidate had a
/// finite fitness). Nothing when validation is off.
pub fn validation_columns(
    experiment: &Experiment,
    best: Option<&ValidatedChampion>,
) -> Vec<Option<f64>> {
    if !experiment.validation.enabled() {
        return Vec::new();
    }
    let mut values = vec![best.and_then(|b| b.validation.fitness)];
    for k in 0..experiment.behaviour.measures.len() {
        values.push(best.and_then(|b| b.validation.measures.get(k).copied()));
    }
    values
}

/// What a run records after evaluating a generation, beyond the plain row: the extra columns
/// of its `fitness.csv` row ([`measure_columns`] then [`validation_columns`]) and, when the
/// generation is due for validation ([`is_due`] of `total` generations), its best candidate
/// on validation. `worlds` caches the validation worlds between calls (built at the first
/// validation). `extra` candidates (e.g. a search distribution's centre) are validated after
/// the generation's top individuals.
pub fn after_generation(
    experiment: &Experiment,
    topology: &Topology,
    generation: &EvaluatedGeneration,
    summary: &GenerationSummary,
    total: u64,
    extra: Vec<Candidate>,
    worlds: &mut Option<BuiltWorlds>,
) -> Result<(Vec<Option<f64>>, Option<ValidatedChampion>), EvaluationError> {
    let mut columns = measure_columns(experiment, generation, summary);
    let mut best = None;
    if is_due(&experiment.validation, generation.generation, total) {
        let worlds = match worlds {
            Some(worlds) => worlds,
            None => worlds.insert(WorldSet::Validation.build(experiment)?),
        };
        let mut candidates = top_candidates(experiment, generation);
        candidates.extend(extra);
        best = validate(experiment, topology, &candidates, worlds)?;
    }
    columns.extend(validation_columns(experiment, best.as_ref()));
    Ok((columns, best))
}
