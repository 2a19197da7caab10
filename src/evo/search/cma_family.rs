//! The CMA-ES family behind the ask/tell seam: one [`Search`] over a search distribution whose
//! covariance is either full ([`super::cma_es`]) or diagonal ([`super::sep_cma_es`]).
//!
//! Both sample λ genomes and then the mean, learn from the samples' ranks, centre a new
//! distribution on the best individual when a checkpoint holds none of their state, and offer
//! only the mean as champion; what differs is the distribution itself ([`Distribution`]).

use super::draws;
use super::{centre_candidate, improved_centre, own_state, Search, SearchState, Unevaluated};
use crate::brain::genome::Genome;
use crate::evo::lineage::{Birth, Lineage};
use crate::evo::state::{Champion, EvaluatedGeneration, GenerationSummary};
use crate::evo::validation::Candidate;
use crate::experiment::evolution::CmaEsSpec;
use crate::experiment::Experiment;
use crate::seed::{stream, Generation, IndividualId, Normals, Purpose, Seed, TrialIndex};
use serde::de::DeserializeOwned;
use serde::Serialize;
use std::fmt::Debug;

/// A CMA-ES search distribution: its constants, its state θ and how θ samples and learns.
pub trait Distribution: Debug + Clone + Send + Sync + 'static {
    /// θ, as a checkpoint holds it.
    type State: Debug + Clone + Serialize + DeserializeOwned + Send + Sync;
    /// What depends only on the number of parameters and λ.
    type Constants: Debug + Clone + Send + Sync;

    /// `[evolution] algorithm` (`cma-es`).
    const NAME: &'static str;
    /// The state's tag in checkpoints (`cma_es`).
    const TAG: &'static str;
    /// The algorithm in words (`CMA-ES`).
    const DESCRIBE: &'static str;

    /// The constants for `parameters` parameters and a population of `population`.
    fn constants(parameters: usize, population: usize) -> Self::Constants;
    /// λ, the samples per generation (the mean comes on top).
    fn lambda(constants: &Self::Constants) -> usize;
    /// θ_0: mean 0, step size `spec.sigma_init`.
    fn initial(spec: &CmaEsSpec, parameters: usize) -> Self::State;
    /// A new distribution centred on `mean` with step size `sigma`.
    fn centred_on(mean: &[f64], sigma: f64) -> Self::State;
    /// The samples for each of `noises` in order, then the mean.
    fn individuals(state: &Self::State, noises: &[Vec<f64>]) -> Vec<Genome>;
    /// θ_{g+1} from θ_g, the noises that sampled generation g and the samples' fitness.
    fn update(
        constants: &Self::Constants,
        state: &Self::State,
        noises: &[Vec<f64>],
        fitness: &[f64],
    ) -> Self::State;
    /// Why `state` cannot continue a search over `parameters` parameters, or `None`.
    fn problem(state: &Self::State, parameters: usize) -> Option<String>;
}

/// The λ standard normal vectors z_k of generation `generation`: one stream
/// (`Purpose::Search`, the generation, individual 0, trial 0), vector after vector, parameter
/// after parameter, so a smaller sample is the first of a larger one (both CMA-ES variants).
pub fn noises(
    normals: Normals,
    seed: Seed,
    generation: Generation,
    parameters: usize,
    lambda: usize,
) -> Vec<Vec<f64>> {
    let mut rng = stream(
        seed,
        Purpose::Search,
        generation,
        IndividualId(0),
        TrialIndex(0),
    );
    draws::gaussian_rows(normals, &mut rng, lambda, parameters)
}

/// A CMA-ES search as a [`Search`]: θ_g, the generation it samples, where its mean came from.
#[derive(Debug, Clone)]
pub struct CmaSearch<D: Distribution> {
    seed: Seed,
    spec: CmaEsSpec,
    constants: D::Constants,
    parameters: usize,
    /// The generation `state` samples.
    generation: u64,
    /// θ_g; `None` after a restore without this algorithm's state (a run that switched
    /// algorithm), until [`Search::tell`] centres a new distribution on the best individual.
    state: Option<D::State>,
    /// The individual of generation g − 1 the mean came from (`None` for generation 0).
    mean_parent: Option<usize>,
    /// The noises the last `ask` drew, for `tell`.
    noises: draws::NoiseCache,
    /// How the noises are drawn (`[evolution] draw_order`).
    normals: Normals,
}

impl<D: Distribution> CmaSearch<D> {
    /// A new search for `experiment` (`[evolution.cma_es]`, or every default) with genomes of
    /// `parameters` parameters: θ_0 is [`Distribution::initial`], λ the population.
    pub fn new(experiment: &Experiment, parameters: usize) -> CmaSearch<D> {
        let spec = experiment.evolution.cma_es.unwrap_or_default();
        CmaSearch {
            seed: experiment.seed(),
            spec,
            constants: D::constants(parameters, experiment.evolution.population),
            parameters,
            generation: 0,
            state: Some(D::initial(&spec, parameters)),
            mean_parent: None,
            noises: draws::NoiseCache::default(),
            normals: experiment.evolution.normals(),
        }
    }

    fn lambda(&self) -> usize {
        D::lambda(&self.constants)
    }

    /// The first `count` samples of generation `self.generation` (then the mean).
    fn sample(&self, count: usize) -> Vec<Genome> {
        let initial;
        let state = match &self.state {
            Some(state) => state,
            None => {
                initial = D::initial(&self.spec, self.parameters);
                &initial
            }
        };
        let z = noises(
            self.normals,
            self.seed,
            Generation(self.generation),
            self.parameters,
            count,
        );
        D::individuals(state, &z)
    }
}

impl<D: Distribution> Search for CmaSearch<D> {
    fn name(&self) -> &'static str {
        D::NAME
    }

    fn describe(&self) -> &'static str {
        D::DESCRIBE
    }

    fn evaluated_per_generation(&self) -> usize {
        self.lambda() + 1
    }

    fn generation(&self) -> u64 {
        self.generation
    }

    fn ask(&self) -> Unevaluated {
        let mut lineage = vec![Lineage::orphan(Birth::CmaSample); self.lambda()];
        lineage.push(match self.mean_parent {
            Some(p) => Lineage::of(Birth::CmaMean, &[p]),
            None => Lineage::orphan(Birth::CmaMean),
        });
        let lambda = self.lambda();
        let initial;
        let state = match &self.state {
            Some(state) => state,
            None => {
                initial = D::initial(&self.spec, self.parameters);
                &initial
            }
        };
        // Kept for `tell`, which updates θ with the same noises.
        let z = self
            .noises
            .get_or_draw((self.generation, lambda, Vec::new()), || {
                noises(
                    self.normals,
                    self.seed,
                    Generation(self.generation),
                    self.parameters,
                    lambda,
                )
            });
        Unevaluated {
            genomes: D::individuals(state, &z),
            lineage,
        }
    }

    /// θ_{g+1} from the samples' fitness (the mean's left out). Without θ_g, or when the
    /// generation does not hold λ samples and the mean (a run that changed its algorithm or
    /// population), the new distribution is centred on the generation's best individual.
    fn tell(&mut self, evaluated: &EvaluatedGeneration) {
        let fitness = evaluated.selection_fitness();
        let lambda = self.lambda();
        let (next, parent) = match &self.state {
            Some(state) if fitness.len() == lambda + 1 => {
                // The noises `ask` drew for this generation, or drawn again (after a resume).
                let key = (evaluated.generation, lambda, Vec::new());
                let z = self.noises.take_or_draw(key, || {
                    noises(
                        self.normals,
                        self.seed,
                        Generation(evaluated.generation),
                        self.parameters,
                        lambda,
                    )
                });
                (
                    D::update(&self.constants, state, &z, &fitness[..lambda]),
                    lambda,
                )
            }
            _ => {
                let best = evaluated.summary().best_individual.unwrap_or(0);
                (
                    D::centred_on(
                        &evaluated.individuals[best].genome.parameters,
                        self.spec.sigma_init,
                    ),
                    best,
                )
            }
        };
        self.state = Some(next);
        self.generation = evaluated.generation + 1;
        self.mean_parent = Some(parent);
    }

    fn state(&self) -> Option<SearchState> {
        self.state.as_ref().map(|s| SearchState::of(D::TAG, s))
    }

    fn restore(&mut self, state: Option<&SearchState>, generation: u64) {
        self.generation = generation;
        // Another algorithm's state, or none: `tell` centres on the best individual.
        self.state = own_state::<D::State>(state, D::TAG, D::NAME).ok();
        self.mean_parent = None;
    }

    fn state_problem(&self, state: Option<&SearchState>) -> Option<String> {
        match own_state::<D::State>(state, D::TAG, D::NAME) {
            Ok(state) => D::problem(&state, self.parameters),
            Err(why) => Some(why),
        }
    }

    fn first_genomes(&self, n: usize) -> Vec<Genome> {
        let n = n.min(self.evaluated_per_generation());
        if n == self.evaluated_per_generation() {
            return self.ask().genomes;
        }
        // Sample after sample from one stream: a smaller sample is the first of the full one.
        let mut genomes = self.sample(n);
        genomes.truncate(n);
        genomes
    }

    /// Only the mean, the last individual, can become the champion (a sample is the mean plus
    /// noise).
    fn improved_champion(
        &self,
        previous: Option<&Champion>,
        generation: &EvaluatedGeneration,
        _summary: &GenerationSummary,
    ) -> Option<Champion> {
        improved_centre(previous, generation)
    }

    /// The mean, which validation always considers.
    fn champion_candidates(&self, evaluated: &EvaluatedGeneration) -> Vec<Candidate> {
        centre_candidate(evaluated)
    }

    fn champion_candidates_per_generation(&self) -> usize {
        1
    }
}
