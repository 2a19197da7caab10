//! sep-CMA-ES: `[evolution] algorithm = "sep-cma-es"`, CMA-ES with a diagonal covariance
//! matrix, linear in time and memory in the number of parameters.
//!
//! R. Ros, N. Hansen, "A simple modification in CMA-ES achieving linear time and space
//! complexity", PPSN X, 2008: the covariance matrix C is kept diagonal and its learning rates
//! are multiplied by (n + 2) / 3, since n variances are learnt instead of n(n + 1)/2 entries.
//! Every other constant is the default of N. Hansen, "The CMA evolution strategy: a
//! tutorial", arXiv:1604.00772 (Table 1, positive weights only):
//!
//! - λ = `population` (the tutorial's default is 4 + ⌊3 ln n⌋), μ = ⌊λ/2⌋;
//! - w_i ∝ ln((λ + 1)/2) − ln i for i = 1..μ, summing to 1; μ_eff = 1 / Σ w_i²;
//! - c_σ = (μ_eff + 2)/(n + μ_eff + 5), d_σ = 1 + 2 max(0, √((μ_eff − 1)/(n + 1)) − 1) + c_σ;
//! - c_c = (4 + μ_eff/n)/(n + 4 + 2 μ_eff/n);
//! - c_1 = 2/((n + 1.3)² + μ_eff), c_μ = min(1 − c_1, 2 (μ_eff − 2 + 1/μ_eff)/((n + 2)² + μ_eff)),
//!   then both × (n + 2)/3 for the diagonal, c_1 at most 1 and c_μ at most 1 − c_1;
//! - E‖N(0, I)‖ ≈ √n (1 − 1/(4n) + 1/(21n²)).
//!
//! # One generation
//!
//! The state θ_g = (mean m, step size σ, variances c (the diagonal of C), paths p_σ and p_c,
//! updates so far t) samples generation g: x_k = m + σ √c ⊙ z_k for k = 0..λ − 1, z_k standard
//! normal, then individual λ = m itself (evaluated so that the mean can be the champion, as
//! PGPE's centre; its fitness does not enter the update). After the evaluation, with the
//! samples ranked best first (`select::ranking`: ties to the lower index, NaN last):
//!
//! 1. z_w = Σ_{i<μ} w_i z_{i:λ}, y_w = √c ⊙ z_w, m ← m + σ y_w;
//! 2. p_σ ← (1 − c_σ) p_σ + √(c_σ (2 − c_σ) μ_eff) z_w (C^−½ y_w is z_w for a diagonal C);
//! 3. t ← t + 1; h_σ = 1 if ‖p_σ‖ / √(1 − (1 − c_σ)^{2t}) < (1.4 + 2/(n + 1)) E‖N(0, I)‖, else 0;
//! 4. p_c ← (1 − c_c) p_c + h_σ √(c_c (2 − c_c) μ_eff) y_w;
//! 5. c_j ← (1 − c_1 − c_μ) c_j + c_1 (p_c,j² + (1 − h_σ) c_c (2 − c_c) c_j)
//!    + c_μ Σ_{i<μ} w_i c_j z_{i:λ,j}²;
//! 6. σ ← σ exp((c_σ/d_σ)(‖p_σ‖ / E‖N(0, I)‖ − 1)).
//!
//! σ is kept within [10^-12, 10^6] and every c_j within [10^-12, 10^12], so that the state
//! stays positive and finite for any run length. Sums run in index order; `exp`, `ln` and
//! powers are `libm`'s, so the bits are the same on every platform.
//!
//! # Draw order (part of the reproducibility contract)
//!
//! Generation g's noise comes from `stream(seed, Purpose::Search, g, 0, 0)`: for k = 0..λ − 1
//! and each parameter j in order, one `gaussian()` z_kj (draw order 2: `gaussian_ziggurat()`,
//! vector k from its own stream, `draws::own_stream`). The update regenerates z from the same
//! stream, so a checkpoint needs only θ_g (`"search": {"sep_cma_es": {...}}`) and the evaluated
//! generation, and a resumed run continues with the same bits. The mean starts at 0, σ at
//! `[evolution.cma_es] sigma_init`, c at 1, the paths at 0.
//!
//! Full CMA-ES (a covariance matrix and its eigendecomposition) is `super::cma_es`.

use super::cma_family::{CmaSearch, Distribution};
use crate::brain::genome::Genome;
use crate::evo::select::ranking;
use crate::experiment::evolution::{CmaEsSpec, MAX_MAGNITUDE};
use serde::{Deserialize, Serialize};

/// The smallest step size: far below any useful step, it keeps σ positive.
pub const MIN_SIGMA: f64 = 1.0e-12;

/// The variances c_j are kept within [1 / MAX_VARIANCE, MAX_VARIANCE].
pub const MAX_VARIANCE: f64 = 1.0e12;

/// The constants of one (n, λ): the module documentation's list.
#[derive(Debug, Clone, PartialEq)]
pub struct Constants {
    /// λ, samples per generation.
    pub lambda: usize,
    /// The μ = ⌊λ/2⌋ recombination weights, best first, summing to 1.
    pub weights: Vec<f64>,
    /// μ_eff = 1 / Σ w².
    pub mu_eff: f64,
    /// c_σ, the step-size path's learning rate.
    pub c_sigma: f64,
    /// d_σ, the step size's damping.
    pub d_sigma: f64,
    /// c_c, the covariance path's learning rate.
    pub c_c: f64,
    /// c_1, the rank-one learning rate (× (n + 2)/3).
    pub c_1: f64,
    /// c_μ, the rank-μ learning rate (× (n + 2)/3).
    pub c_mu: f64,
    /// E‖N(0, I)‖.
    pub chi_n: f64,
}

impl Constants {
    /// The constants for `n` parameters and `lambda` samples (both at least 1).
    pub fn new(n: usize, lambda: usize) -> Constants {
        let nf = n.max(1) as f64;
        let lambda = lambda.max(1);
        let mu = (lambda / 2).max(1);
        let top = libm::log((lambda as f64 + 1.0) / 2.0);
        let raw: Vec<f64> = (1..=mu).map(|i| top - libm::log(i as f64)).collect();
        let mut sum = 0.0;
        for w in &raw {
            sum += w;
        }
        let weights: Vec<f64> = raw.iter().map(|w| w / sum).collect();
        let mut squares = 0.0;
        for w in &weights {
            squares += w * w;
        }
        let mu_eff = 1.0 / squares;
        let c_sigma = (mu_eff + 2.0) / (nf + mu_eff + 5.0);
        let d_sigma = 1.0 + 2.0 * (((mu_eff - 1.0) / (nf + 1.0)).sqrt() - 1.0).max(0.0) + c_sigma;
        let c_c = (4.0 + mu_eff / nf) / (nf + 4.0 + 2.0 * mu_eff / nf);
        let c_1 = 2.0 / ((nf + 1.3) * (nf + 1.3) + mu_eff);
        let c_mu = (1.0 - c_1)
            .min(2.0 * (mu_eff - 2.0 + 1.0 / mu_eff) / ((nf + 2.0) * (nf + 2.0) + mu_eff));
        // Ros & Hansen: n variances learn (n + 2)/3 times faster than a full matrix.
        let faster = (nf + 2.0) / 3.0;
        let c_1 = (c_1 * faster).min(1.0);
        let c_mu = (c_mu * faster).min(1.0 - c_1).max(0.0);
        let chi_n = nf.sqrt() * (1.0 - 1.0 / (4.0 * nf) + 1.0 / (21.0 * nf * nf));
        Constants {
            lambda,
            weights,
            mu_eff,
            c_sigma,
            d_sigma,
            c_c,
            c_1,
            c_mu,
            chi_n,
        }
    }
}

/// The search distribution that samples one generation: θ_g of the module documentation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SepCmaState {
    /// The mean m, one value per parameter: the current solution (the champion candidate).
    pub mean: Vec<f64>,
    /// The step size σ.
    pub sigma: f64,
    /// The variances c, the diagonal of C, one per parameter, all positive.
    pub variances: Vec<f64>,
    /// The step-size evolution path p_σ.
    pub path_sigma: Vec<f64>,
    /// The covariance evolution path p_c.
    pub path_c: Vec<f64>,
    /// Updates so far, t (for h_σ's correction of a young path).
    pub updates: u64,
}

impl SepCmaState {
    /// A state centred on `mean`, with σ = `sigma`, c = 1 and zero paths.
    pub fn centred_on(mean: &[f64], sigma: f64) -> SepCmaState {
        SepCmaState {
            mean: mean.to_vec(),
            sigma,
            variances: vec![1.0; mean.len()],
            path_sigma: vec![0.0; mean.len()],
            path_c: vec![0.0; mean.len()],
            updates: 0,
        }
    }

    /// The initial state for `parameters` parameters: m = 0.
    pub fn initial(spec: &CmaEsSpec, parameters: usize) -> SepCmaState {
        SepCmaState::centred_on(&vec![0.0; parameters], spec.sigma_init)
    }

    /// Why this state cannot sample genomes of `parameters` parameters (wrong lengths, a
    /// non-finite value, a step size or variance that is not positive), or `None` if it can.
    pub fn problem(&self, parameters: usize) -> Option<String> {
        for (name, values) in [
            ("mean", &self.mean),
            ("variances", &self.variances),
            ("path_sigma", &self.path_sigma),
            ("path_c", &self.path_c),
        ] {
            if values.len() != parameters {
                return Some(format!(
                    "the sep-cma-es {name} has {} values, the experiment's brain has {parameters} parameters",
                    values.len()
                ));
            }
            if values.iter().any(|x| !x.is_finite()) {
                return Some(format!("the sep-cma-es {name} holds a non-finite value"));
            }
        }
        if !(self.sigma.is_finite() && self.sigma > 0.0) {
            return Some(format!(
                "the sep-cma-es sigma is {}, not a positive number",
                self.sigma
            ));
        }
        if self.variances.iter().any(|&c| c <= 0.0) {
            return Some("the sep-cma-es variances hold a value that is not positive".to_string());
        }
        None
    }
}

/// The samples x_k = m + σ √c ⊙ z_k for each of `noises` in order, then the mean itself.
pub fn individuals(state: &SepCmaState, noises: &[Vec<f64>]) -> Vec<Genome> {
    let scale: Vec<f64> = state
        .variances
        .iter()
        .map(|&c| state.sigma * c.sqrt())
        .collect();
    let genome = |parameters: Vec<f64>| Genome {
        parameters,
        step_size: None,
    };
    let mut out: Vec<Genome> = noises
        .iter()
        .map(|z| {
            genome(
                state
                    .mean
                    .iter()
                    .zip(&scale)
                    .zip(z)
                    .map(|((m, s), z)| m + s * z)
                    .collect(),
            )
        })
        .collect();
    out.push(genome(state.mean.clone()));
    out
}

/// The L2 norm, summed in index order.
fn norm(v: &[f64]) -> f64 {
    let mut sum = 0.0;
    for x in v {
        sum += x * x;
    }
    sum.sqrt()
}

/// θ_{g+1} from θ_g, the noises that sampled generation g and the samples' fitness (higher is
/// better; `fitness[k]` for sample k, the mean's left out), steps 1–6.
///
/// # Panics
/// If `fitness` does not hold one value per noise.
pub fn update(
    constants: &Constants,
    state: &SepCmaState,
    noises: &[Vec<f64>],
    fitness: &[f64],
) -> SepCmaState {
    assert_eq!(fitness.len(), noises.len(), "one fitness value per sample");
    let n = state.mean.len();
    let nf = n.max(1) as f64;
    let k = constants;
    let order = ranking(fitness);
    let parents: Vec<&Vec<f64>> = order
        .iter()
        .take(k.weights.len())
        .map(|&i| &noises[i])
        .collect();
    let root: Vec<f64> = state.variances.iter().map(|c| c.sqrt()).collect();
    let mut z_w = vec![0.0; n];
    let mut rank_mu = vec![0.0; n];
    for (w, z) in k.weights.iter().zip(&parents) {
        for j in 0..n {
            z_w[j] += w * z[j];
            let y = root[j] * z[j];
            rank_mu[j] += w * y * y;
        }
    }
    let y_w: Vec<f64> = root.iter().zip(&z_w).map(|(r, z)| r * z).collect();
    let mean = state
        .mean
        .iter()
        .zip(&y_w)
        .map(|(m, y)| m + state.sigma * y)
        .collect();
    let sigma_rate = (k.c_sigma * (2.0 - k.c_sigma) * k.mu_eff).sqrt();
    let path_sigma: Vec<f64> = state
        .path_sigma
        .iter()
        .zip(&z_w)
        .map(|(p, z)| (1.0 - k.c_sigma) * p + sigma_rate * z)
        .collect();
    let length = norm(&path_sigma);
    let updates = state.updates + 1;
    let young = 1.0 - libm::pow(1.0 - k.c_sigma, 2.0 * updates as f64);
    let h_sigma = length / young.sqrt() < (1.4 + 2.0 / (nf + 1.0)) * k.chi_n;
    let c_rate = (k.c_c * (2.0 - k.c_c) * k.mu_eff).sqrt();
    let path_c: Vec<f64> = state
        .path_c
        .iter()
        .zip(&y_w)
        .map(|(p, y)| (1.0 - k.c_c) * p + if h_sigma { c_rate * y } else { 0.0 })
        .collect();
    let stall = if h_sigma { 0.0 } else { k.c_c * (2.0 - k.c_c) };
    let variances = (0..n)
        .map(|j| {
            let c = state.variances[j];
            ((1.0 - k.c_1 - k.c_mu) * c
                + k.c_1 * (path_c[j] * path_c[j] + stall * c)
                + k.c_mu * rank_mu[j])
                .clamp(1.0 / MAX_VARIANCE, MAX_VARIANCE)
        })
        .collect();
    let sigma = (state.sigma * libm::exp((k.c_sigma / k.d_sigma) * (length / k.chi_n - 1.0)))
        .clamp(MIN_SIGMA, MAX_MAGNITUDE);
    SepCmaState {
        mean,
        sigma,
        variances,
        path_sigma,
        path_c,
        updates,
    }
}

/// CMA-ES with a diagonal covariance, as a [`Distribution`] of [`CmaSearch`].
#[derive(Debug, Clone)]
pub struct Diagonal;

impl Distribution for Diagonal {
    type State = SepCmaState;
    type Constants = Constants;
    const NAME: &'static str = "sep-cma-es";
    const TAG: &'static str = "sep_cma_es";
    const DESCRIBE: &'static str = "sep-CMA-ES";

    fn constants(parameters: usize, population: usize) -> Constants {
        Constants::new(parameters, population)
    }

    fn lambda(constants: &Constants) -> usize {
        constants.lambda
    }

    fn initial(spec: &CmaEsSpec, parameters: usize) -> SepCmaState {
        SepCmaState::initial(spec, parameters)
    }

    fn centred_on(mean: &[f64], sigma: f64) -> SepCmaState {
        SepCmaState::centred_on(mean, sigma)
    }

    fn individuals(state: &SepCmaState, noises: &[Vec<f64>]) -> Vec<Genome> {
        individuals(state, noises)
    }

    fn update(
        constants: &Constants,
        state: &SepCmaState,
        noises: &[Vec<f64>],
        fitness: &[f64],
    ) -> SepCmaState {
        update(constants, state, noises, fitness)
    }

    fn problem(state: &SepCmaState, parameters: usize) -> Option<String> {
        state.problem(parameters)
    }
}

/// sep-CMA-ES as a [`super::Search`] (`algorithm = "sep-cma-es"`).
pub type SepCmaEs = CmaSearch<Diagonal>;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn constants_follow_the_tutorial_for_ten_parameters() {
        // n = 10, λ = 10: μ = 5, w ∝ ln 5.5 − ln i.
        let k = Constants::new(10, 10);
        assert_eq!(k.weights.len(), 5);
        let sum: f64 = k.weights.iter().sum();
        assert!((sum - 1.0).abs() < 1e-15);
        assert!(
            (k.mu_eff - 3.167_299_281_410_701_7).abs() < 1e-12,
            "{}",
            k.mu_eff
        );
        assert!((k.c_sigma - 0.284_428_587_946_367_44).abs() < 1e-12);
        // Ros & Hansen's factor (n + 2)/3 = 4 on the tutorial's c_1 and c_μ.
        let c_1 = 2.0 / (11.3 * 11.3 + k.mu_eff);
        assert!((k.c_1 - 4.0 * c_1).abs() < 1e-15);
        assert!(k.c_1 + k.c_mu <= 1.0);
    }
}
