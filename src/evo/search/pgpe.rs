//! PGPE with ClipUp: `[evolution] algorithm = "pgpe"`, a distribution-based alternative to the
//! genetic algorithm.
//!
//! PGPE, policy gradients with parameter-based exploration: F. Sehnke, C. Osendorfer,
//! T. Rückstieß, A. Graves, J. Peters, J. Schmidhuber, "Parameter-exploring policy gradients",
//! Neural Networks 23(4), 551–559, 2010 (symmetric sampling, §4.1; the standard-deviation
//! update, eq. 9). ClipUp: N. E. Toklu, P. Liskowski, R. K. Srivastava, "ClipUp: a simple and
//! powerful optimizer for distribution-based policy evolution", PPSN XVI, 2020. The arithmetic
//! follows EvoJAX's `PGPE` with `optimizer = "clipup"` (`evojax/algo/pgpe.py`), and the defaults
//! are EvoJAX's (see [`PgpeSpec`]).
//!
//! Why this algorithm here: the GA's failure in the vehicle space (docs/search.md) is noisy
//! ranking and small undirected steps. PGPE estimates an ascent direction from every
//! evaluation of a generation, not only from the tournament winners; a mirrored pair c ± ε
//! meets the same trial worlds (common random numbers), so the difference of its two scores
//! cancels most of the world's luck; centred ranks make the step independent of the fitness
//! scale and of outliers; ClipUp bounds the centre's move in parameter units and its momentum
//! averages the noisy directions over generations; and every parameter's standard deviation
//! adapts. It is EvoJAX's and evotorch's PGPE, so results can be compared with theirs.
//!
//! # One generation
//!
//! The state θ_g = (centre c, standard deviations σ, velocity v) samples generation g: with
//! population N (even) and K = N/2 pairs, scaled noises ε_k = σ ⊙ z_k (z_k standard normal),
//! individuals 2k = c + ε_k and 2k + 1 = c − ε_k, and individual N = c itself (evaluated only
//! so that the centre can be the champion; its fitness does not enter the update). After the
//! evaluation, with fitness f_0 .. f_{N−1} of the samples:
//!
//! 1. centred ranks u_i = r_i / (N − 1) − 0.5, r_i the rank of f_i from 0 (worst) to N − 1
//!    (best); tied values get the mean of their ranks (so a generation that scores the same
//!    everywhere moves nothing), and a non-finite brain ranks with −∞;
//! 2. for each pair d_k = u_{2k} − u_{2k+1}, a_k = (u_{2k} + u_{2k+1}) / 2, and the baseline
//!    b = mean of all u;
//! 3. g_c = (1/K) Σ_k ε_k · d_k · 0.5, g_σ = (1/K) Σ_k (a_k − b) · (ε_k² − σ²) / σ
//!    (per parameter, summed over k in increasing order);
//! 4. ClipUp: ĝ = g_c / ‖g_c‖ (0 when ‖g_c‖ is 0), v ← μ v + α ĝ, and if ‖v‖ > v_max then
//!    v ← v · v_max / ‖v‖; c ← c + v (EvoJAX stores −v and subtracts it: the same bits);
//! 5. σ ← clamp(σ + η_σ g_σ, σ − κσ, σ + κσ), then kept within [10^-12, 10^6] so that it stays
//!    positive and finite for any run length.
//!
//! The initial state is EvoJAX's: c = 0, σ = `stdev_init` everywhere, v = 0.
//!
//! # Draw order (part of the reproducibility contract)
//!
//! Generation g's noise comes from `stream(seed, Purpose::Search, g, 0, 0)`: for k = 0 .. K − 1
//! and each parameter j in order, one `gaussian()` z (draw order 2: `gaussian_ziggurat()`, pair k's
//! from its own stream, `draws::own_stream`) and ε_kj = σ_j · z. The update of step 4
//! draws nothing: it regenerates ε from the same stream, so a checkpoint needs only θ_g and the
//! evaluated generation, and a resumed run continues with the same bits.
//!
//! # Behind the search trait
//!
//! [`Pgpe`] is this algorithm as a [`Search`]: `ask` samples generation g from θ_g (N
//! samples, then the centre; individual N), `tell` steps θ_g to θ_{g+1} on the samples'
//! fitness, the checkpoint holds θ_g as `"search": {"pgpe": {...}}`, the champion is always
//! the centre, and validation always considers the centre too.

use super::draws;
use super::{centre_candidate, improved_centre, own_state, Search, SearchState, Unevaluated};
use crate::brain::genome::Genome;
use crate::evo::lineage::{Birth, Lineage};
use crate::evo::state::{Champion, EvaluatedGeneration, GenerationSummary};
use crate::evo::validation::Candidate;
use crate::experiment::evolution::{PgpeSpec, MAX_MAGNITUDE};
use crate::experiment::Experiment;
use crate::seed::{stream, Generation, IndividualId, Normals, Purpose, Rng, Seed, TrialIndex};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// The smallest standard deviation: far below any useful step, it only keeps σ positive (the
/// update divides by it) in runs long enough to shrink it geometrically towards 0.
pub const MIN_STDEV: f64 = 1.0e-12;

/// The search distribution that samples one generation: θ_g of the module documentation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PgpeState {
    /// The centre c, one value per parameter: the current solution (the champion candidate).
    pub centre: Vec<f64>,
    /// The standard deviations σ, one per parameter, all positive.
    pub stdev: Vec<f64>,
    /// ClipUp's velocity v: the last move of the centre.
    pub velocity: Vec<f64>,
}

impl PgpeState {
    /// The initial state for `parameters` parameters: c = 0, σ = `stdev_init`, v = 0.
    pub fn initial(spec: &PgpeSpec, parameters: usize) -> PgpeState {
        PgpeState {
            centre: vec![0.0; parameters],
            stdev: vec![spec.stdev_init; parameters],
            velocity: vec![0.0; parameters],
        }
    }

    /// A state centred on `centre` (e.g. when a run switches from the GA to PGPE: its best
    /// individual), with σ = `stdev_init` and v = 0.
    pub fn centred_on(spec: &PgpeSpec, centre: &[f64]) -> PgpeState {
        PgpeState {
            centre: centre.to_vec(),
            stdev: vec![spec.stdev_init; centre.len()],
            velocity: vec![0.0; centre.len()],
        }
    }

    /// Why this state cannot sample genomes of `parameters` parameters (wrong lengths, a
    /// non-finite value, a non-positive standard deviation), or `None` if it can.
    pub fn problem(&self, parameters: usize) -> Option<String> {
        for (name, values) in [
            ("centre", &self.centre),
            ("stdev", &self.stdev),
            ("velocity", &self.velocity),
        ] {
            if values.len() != parameters {
                return Some(format!(
                    "the pgpe {name} has {} values, the experiment's brain has {parameters} parameters",
                    values.len()
                ));
            }
            if values.iter().any(|x| !x.is_finite()) {
                return Some(format!("the pgpe {name} holds a non-finite value"));
            }
        }
        if self.stdev.iter().any(|&s| s <= 0.0) {
            return Some("the pgpe stdev holds a value that is not positive".to_string());
        }
        None
    }
}

/// The stream of generation `generation`'s noise.
pub fn noise_stream(seed: Seed, generation: Generation) -> Rng {
    stream(
        seed,
        Purpose::Search,
        generation,
        IndividualId(0),
        TrialIndex(0),
    )
}

/// The K = `population / 2` scaled noises ε_k = σ ⊙ z_k of generation `generation`, drawn as
/// the module documentation says.
pub fn noises(
    normals: Normals,
    seed: Seed,
    generation: Generation,
    state: &PgpeState,
    population: usize,
) -> Vec<Vec<f64>> {
    let mut rng = noise_stream(seed, generation);
    // The draws in parallel, then ε = σ ⊙ z as `s * gaussian()` would make it.
    let mut noises = draws::gaussian_rows(normals, &mut rng, population / 2, state.stdev.len());
    noises.par_iter_mut().for_each(|z| {
        for (x, &s) in z.iter_mut().zip(&state.stdev) {
            // x · s is s · x to the bit (IEEE multiplication commutes).
            *x *= s;
        }
    });
    noises
}

/// The individuals of a generation sampled with `noises`: c + ε_k and c − ε_k for each k in
/// order, then the centre itself (N + 1 genomes, no step sizes).
pub fn individuals(state: &PgpeState, noises: &[Vec<f64>]) -> Vec<Genome> {
    let genome = |parameters: Vec<f64>| Genome {
        parameters,
        step_size: None,
    };
    let mut out = Vec::with_capacity(2 * noises.len() + 1);
    for e in noises {
        out.push(genome(
            state.centre.iter().zip(e).map(|(c, e)| c + e).collect(),
        ));
        out.push(genome(
            state.centre.iter().zip(e).map(|(c, e)| c - e).collect(),
        ));
    }
    out.push(genome(state.centre.clone()));
    out
}

/// Generation `generation` sampled from `state`: `population` samples, then the centre.
pub fn sample(
    normals: Normals,
    seed: Seed,
    generation: Generation,
    state: &PgpeState,
    population: usize,
) -> Vec<Genome> {
    individuals(state, &noises(normals, seed, generation, state, population))
}

/// The value a fitness is ranked by: NaN with −∞, −0.0 equal to +0.0.
fn key(fitness: f64) -> f64 {
    if fitness.is_nan() {
        f64::NEG_INFINITY
    } else {
        fitness + 0.0
    }
}

/// Centred ranks u_i = r_i / (n − 1) − 0.5 (step 1 of the module documentation): r_i from 0
/// (worst) to n − 1 (best), tied values sharing the mean of their ranks. A single value gets 0.
pub fn centred_ranks(fitness: &[f64]) -> Vec<f64> {
    let n = fitness.len();
    let keys: Vec<f64> = fitness.iter().map(|&f| key(f)).collect();
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_unstable_by(|&a, &b| keys[a].total_cmp(&keys[b]).then(a.cmp(&b)));
    let mut ranks = vec![0.0; n];
    let mut start = 0;
    while start < n {
        let mut end = start + 1;
        while end < n && keys[order[end]] == keys[order[start]] {
            end += 1;
        }
        // Positions start .. end − 1 tie: each gets their mean.
        let rank = (start + end - 1) as f64 / 2.0;
        for &i in &order[start..end] {
            ranks[i] = rank;
        }
        start = end;
    }
    if n < 2 {
        return vec![0.0; n];
    }
    let top = (n - 1) as f64;
    ranks.iter().map(|r| r / top - 0.5).collect()
}

/// The centre's and the standard deviations' gradient estimates g_c and g_σ (step 3) from
/// the samples' centred ranks `u` (2K values, pair k at 2k and 2k + 1) and the noises.
pub fn gradients(u: &[f64], noises: &[Vec<f64>], stdev: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let pairs = noises.len();
    let n = stdev.len();
    let mut grad_centre = vec![0.0; n];
    let mut grad_stdev = vec![0.0; n];
    if pairs == 0 {
        return (grad_centre, grad_stdev);
    }
    let mut sum = 0.0;
    for &x in &u[..2 * pairs] {
        sum += x;
    }
    let baseline = sum / (2 * pairs) as f64;
    let k = pairs as f64;
    // Blocks of parameters in parallel: each parameter's sums still run over the pairs in
    // order, so the bits do not depend on the blocks or the threads.
    const BLOCK: usize = 1024;
    grad_centre
        .par_chunks_mut(BLOCK)
        .zip(grad_stdev.par_chunks_mut(BLOCK))
        .enumerate()
        .for_each(|(block, (centre, spread))| {
            let lo = block * BLOCK;
            let stdev = &stdev[lo..lo + centre.len()];
            for (pair, e) in noises.iter().enumerate() {
                let (plus, minus) = (u[2 * pair], u[2 * pair + 1]);
                let difference = plus - minus;
                let average = (plus + minus) / 2.0;
                let e = &e[lo..lo + centre.len()];
                for j in 0..centre.len() {
                    centre[j] += e[j] * difference * 0.5;
                    spread[j] +=
                        (average - baseline) * (e[j] * e[j] - stdev[j] * stdev[j]) / stdev[j];
                }
            }
            for j in 0..centre.len() {
                centre[j] /= k;
                spread[j] /= k;
            }
        });
    (grad_centre, grad_stdev)
}

/// The L2 norm, summed in index order.
fn norm(v: &[f64]) -> f64 {
    let mut sum = 0.0;
    for x in v {
        sum += x * x;
    }
    sum.sqrt()
}

/// θ_{g+1} from θ_g, the noises that sampled generation g and the samples' fitness
/// (`fitness[i]` for individual i < N; the centre's is not passed), steps 1–5.
///
/// # Panics
/// If `fitness` does not hold two values per noise.
pub fn update(
    spec: &PgpeSpec,
    state: &PgpeState,
    noises: &[Vec<f64>],
    fitness: &[f64],
) -> PgpeState {
    assert_eq!(
        fitness.len(),
        2 * noises.len(),
        "pgpe needs the fitness of both samples of every pair"
    );
    let u = centred_ranks(fitness);
    let (grad_centre, grad_stdev) = gradients(&u, noises, &state.stdev);
    let length = norm(&grad_centre);
    let mut velocity: Vec<f64> = state
        .velocity
        .iter()
        .zip(&grad_centre)
        .map(|(&v, &g)| {
            let direction = if length > 0.0 { g / length } else { 0.0 };
            spec.momentum * v + direction * spec.center_learning_rate
        })
        .collect();
    let speed = norm(&velocity);
    if speed > spec.max_speed {
        for v in &mut velocity {
            *v = *v * spec.max_speed / speed;
        }
    }
    let centre = state
        .centre
        .iter()
        .zip(&velocity)
        .map(|(c, v)| c + v)
        .collect();
    let stdev = state
        .stdev
        .iter()
        .zip(&grad_stdev)
        .map(|(&s, &g)| {
            let allowed = s.abs() * spec.stdev_max_change;
            // s is positive and finite, so both ranges are ordered.
            (s + spec.stdev_learning_rate * g)
                .clamp(s - allowed, s + allowed)
                .clamp(MIN_STDEV, MAX_MAGNITUDE)
        })
        .collect();
    PgpeState {
        centre,
        stdev,
        velocity,
    }
}

/// θ_{g+1}: [`update`] with generation `generation`'s noises regenerated from the seed.
pub fn step(
    normals: Normals,
    seed: Seed,
    spec: &PgpeSpec,
    state: &PgpeState,
    generation: Generation,
    fitness: &[f64],
) -> PgpeState {
    let noises = noises(normals, seed, generation, state, fitness.len());
    update(spec, state, &noises, fitness)
}

/// PGPE as a [`Search`]: θ_g, the generation it samples, and where its centre came from.
#[derive(Debug, Clone)]
pub struct Pgpe {
    seed: Seed,
    spec: PgpeSpec,
    /// N, the samples per generation (the centre comes on top).
    population: usize,
    parameters: usize,
    /// The generation `state` samples.
    generation: u64,
    /// θ_g; `None` after a restore without a PGPE state (a run switched from the GA), until
    /// [`Search::tell`] centres a new distribution on the best individual it is told of.
    state: Option<PgpeState>,
    /// The individual of generation g − 1 the centre came from: that generation's centre
    /// (index N), or its best individual when the search was (re)started there; `None` for
    /// generation 0.
    centre_parent: Option<usize>,
    /// The noises the last `ask` drew, for `tell`.
    noises: draws::NoiseCache,
    /// How the noises are drawn (`[evolution] draw_order`).
    normals: Normals,
}

/// What generation `generation`'s `pairs` noises drawn for `state` are looked up by.
fn noise_key(generation: u64, pairs: usize, state: &PgpeState) -> draws::NoiseKey {
    (
        generation,
        pairs,
        state.stdev.iter().map(|s| s.to_bits()).collect(),
    )
}

impl Pgpe {
    /// A new search for `experiment` (`[evolution.pgpe]`'s settings, or every default) with
    /// genomes of `parameters` parameters: θ_0 is [`PgpeState::initial`].
    pub fn new(experiment: &Experiment, parameters: usize) -> Pgpe {
        let spec = experiment.evolution.pgpe.unwrap_or_default();
        Pgpe {
            seed: experiment.seed(),
            spec,
            population: experiment.evolution.population,
            parameters,
            generation: 0,
            state: Some(PgpeState::initial(&spec, parameters)),
            centre_parent: None,
            noises: draws::NoiseCache::default(),
            normals: experiment.evolution.normals(),
        }
    }

    /// θ_g, or θ_0 when a restore left none (never asked for in a run: it tells first).
    fn current(&self) -> PgpeState {
        self.state
            .clone()
            .unwrap_or_else(|| PgpeState::initial(&self.spec, self.parameters))
    }
}

/// The lineage of a PGPE generation of `population` samples and the centre: the samples
/// have no parent index (see [`Birth::PgpeSample`]); the centre's parent is `centre_parent`.
fn lineage(population: usize, centre_parent: Option<usize>) -> Vec<Lineage> {
    let mut lineage = vec![Lineage::orphan(Birth::PgpeSample); population];
    lineage.push(match centre_parent {
        Some(p) => Lineage::of(Birth::PgpeCentre, &[p]),
        None => Lineage::orphan(Birth::PgpeCentre),
    });
    lineage
}

impl Search for Pgpe {
    fn name(&self) -> &'static str {
        "pgpe"
    }

    fn describe(&self) -> &'static str {
        "PGPE"
    }

    fn evaluated_per_generation(&self) -> usize {
        self.population + 1
    }

    fn generation(&self) -> u64 {
        self.generation
    }

    fn ask(&self) -> Unevaluated {
        let genomes = match &self.state {
            Some(state) => {
                // Kept for `tell`, which updates θ with the same noises.
                let key = noise_key(self.generation, self.population / 2, state);
                let noises = self.noises.get_or_draw(key, || {
                    noises(
                        self.normals,
                        self.seed,
                        Generation(self.generation),
                        state,
                        self.population,
                    )
                });
                individuals(state, &noises)
            }
            None => sample(
                self.normals,
                self.seed,
                Generation(self.generation),
                &self.current(),
                self.population,
            ),
        };
        Unevaluated {
            genomes,
            lineage: lineage(self.population, self.centre_parent),
        }
    }

    /// θ_{g+1} from the samples' fitness (the centre's left out). Without θ_g, or when the
    /// generation does not hold N samples and the centre (a run that changed its algorithm or
    /// population), the new distribution is centred on the generation's best individual.
    fn tell(&mut self, evaluated: &EvaluatedGeneration) {
        let fitness = evaluated.selection_fitness();
        let population = self.population;
        let (next, centre_parent) = match &self.state {
            Some(state) if fitness.len() == population + 1 => {
                // The noises `ask` drew for this generation, or drawn again (after a resume):
                // [`step`]'s.
                let generation = Generation(evaluated.generation);
                let key = noise_key(generation.0, population / 2, state);
                let noises = self.noises.take_or_draw(key, || {
                    noises(self.normals, self.seed, generation, state, population)
                });
                (
                    update(&self.spec, state, &noises, &fitness[..population]),
                    population,
                )
            }
            _ => {
                let best = evaluated.summary().best_individual.unwrap_or(0);
                (
                    PgpeState::centred_on(
                        &self.spec,
                        &evaluated.individuals[best].genome.parameters,
                    ),
                    best,
                )
            }
        };
        self.state = Some(next);
        self.generation = evaluated.generation + 1;
        self.centre_parent = Some(centre_parent);
    }

    fn state(&self) -> Option<SearchState> {
        self.state.as_ref().map(|s| SearchState::of("pgpe", s))
    }

    fn restore(&mut self, state: Option<&SearchState>, generation: u64) {
        self.generation = generation;
        // Another algorithm's state, or none: `tell` centres on the best individual.
        self.state = own_state::<PgpeState>(state, "pgpe", "pgpe").ok();
        // Only the centre's lineage depends on it, and it is set by the next `tell`.
        self.centre_parent = None;
    }

    fn state_problem(&self, state: Option<&SearchState>) -> Option<String> {
        match own_state::<PgpeState>(state, "pgpe", "pgpe") {
            Ok(state) => state.problem(self.parameters),
            Err(why) => Some(why),
        }
    }

    fn first_genomes(&self, n: usize) -> Vec<Genome> {
        let n = n.min(self.evaluated_per_generation());
        let mut genomes = if n == self.evaluated_per_generation() {
            // The whole generation (it ends with the centre).
            self.ask().genomes
        } else {
            // The samples come in mirrored pairs from one noise stream, then the centre: the
            // pairs of a smaller sample are the first pairs of the full one.
            sample(
                self.normals,
                self.seed,
                Generation(0),
                &self.current(),
                n + 1,
            )
        };
        genomes.truncate(n);
        genomes
    }

    /// Only the centre, the last individual, can become the champion: it is the solution
    /// the search converges to, and a sample is the centre plus noise.
    fn improved_champion(
        &self,
        previous: Option<&Champion>,
        generation: &EvaluatedGeneration,
        _summary: &GenerationSummary,
    ) -> Option<Champion> {
        improved_centre(previous, generation)
    }

    /// The centre, evaluated as the generation's last individual: validation always
    /// considers it (after the top individuals), also when its training score does not rank
    /// it among them.
    fn champion_candidates(&self, evaluated: &EvaluatedGeneration) -> Vec<Candidate> {
        centre_candidate(evaluated)
    }

    fn champion_candidates_per_generation(&self) -> usize {
        1
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn centred_ranks_share_ties_and_span_minus_half_to_half() {
        assert_eq!(
            centred_ranks(&[3.0, 1.0, 2.0, 0.0, 5.0]),
            [0.25, -0.25, 0.0, -0.5, 0.5]
        );
        // Ties share the mean rank; all equal means no preference at all.
        assert_eq!(centred_ranks(&[1.0, 1.0, 0.0, 2.0]), [0.0, 0.0, -0.5, 0.5]);
        assert_eq!(centred_ranks(&[4.0; 6]), [0.0; 6]);
        assert_eq!(
            centred_ranks(&[f64::NAN, -0.0, 0.0, 1.0]),
            [-0.5, 0.0, 0.0, 0.5]
        );
        assert_eq!(centred_ranks(&[7.0]), [0.0]);
    }
}
