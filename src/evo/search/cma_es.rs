//! CMA-ES: `[evolution] algorithm = "cma-es"`, the evolution strategy with a full covariance
//! matrix, quadratic in memory and (between decompositions) in time in the number of
//! parameters, cubic for each eigendecomposition; refused beyond [`MAX_PARAMETERS`].
//!
//! N. Hansen, "The CMA evolution strategy: a tutorial", arXiv:1604.00772: every constant is
//! the tutorial's default (Table 1, positive weights only), and one generation is the
//! tutorial's `purecmaes.m`:
//!
//! - λ = `population` (the tutorial's default is 4 + ⌊3 ln n⌋), μ = ⌊λ/2⌋;
//! - w_i ∝ ln((λ + 1)/2) − ln i for i = 1..μ, summing to 1; μ_eff = 1 / Σ w_i²;
//! - c_σ = (μ_eff + 2)/(n + μ_eff + 5), d_σ = 1 + 2 max(0, √((μ_eff − 1)/(n + 1)) − 1) + c_σ;
//! - c_c = (4 + μ_eff/n)/(n + 4 + 2 μ_eff/n);
//! - c_1 = 2/((n + 1.3)² + μ_eff), c_μ = min(1 − c_1, 2 (μ_eff − 2 + 1/μ_eff)/((n + 2)² + μ_eff));
//! - E‖N(0, I)‖ ≈ √n (1 − 1/(4n) + 1/(21n²)).
//!
//! (sep-CMA-ES, `super::sep_cma_es`, is the same with a diagonal C and c_1, c_μ × (n + 2)/3.)
//!
//! # One generation
//!
//! The state θ_g = (mean m, step size σ, covariance C, paths p_σ and p_c, the eigenvectors
//! b_j and axis lengths d_j (√ of the eigenvalues) of C at its last decomposition, updates so
//! far t, and t_e, the update count at that decomposition) samples generation g:
//! y_k = Σ_j d_j z_kj b_j, x_k = m + σ y_k for k = 0..λ − 1, z_k standard normal, then
//! individual λ = m itself (evaluated so that the mean can be the champion, as sep-CMA-ES's
//! mean and PGPE's centre; its fitness does not enter the update). After the evaluation, with
//! the samples ranked best first (`select::ranking`: ties to the lower index, NaN last):
//!
//! 1. y_w = Σ_{i<μ} w_i y_{i:λ}, z_w = Σ_{i<μ} w_i z_{i:λ}, m ← m + σ y_w;
//! 2. p_σ ← (1 − c_σ) p_σ + √(c_σ (2 − c_σ) μ_eff) Σ_j z_w,j b_j (that is C^−½ y_w with the
//!    decomposition that sampled, as the tutorial's `invsqrtC`);
//! 3. t ← t + 1; h_σ = 1 if ‖p_σ‖ / √(1 − (1 − c_σ)^{2t}) < (1.4 + 2/(n + 1)) E‖N(0, I)‖, else 0;
//! 4. p_c ← (1 − c_c) p_c + h_σ √(c_c (2 − c_c) μ_eff) y_w;
//! 5. C ← (1 − c_1 − c_μ) C + c_1 (p_c p_cᵀ + (1 − h_σ) c_c (2 − c_c) C)
//!    + c_μ Σ_{i<μ} w_i y_{i:λ} y_{i:λ}ᵀ (the upper triangle, mirrored: C stays symmetric);
//! 6. σ ← σ exp((c_σ/d_σ)(‖p_σ‖ / E‖N(0, I)‖ − 1));
//! 7. the lazy eigendecomposition of the tutorial: if λ (t − t_e) > λ / ((c_1 + c_μ) n 10)
//!    (evaluations since the last decomposition, as `counteval − eigeneval`), C is decomposed
//!    again and t_e ← t. Otherwise the old b_j, d_j keep sampling: the decomposition costs
//!    O(n³), the rest of a generation O(λ n²).
//!
//! σ is kept within [10^-12, 10^6] and every d_j² within [10^-12, 10^12], so that the state
//! stays positive and finite for any run length. Sums run in index order; `exp`, `ln`, powers
//! and square roots are `libm`'s.
//!
//! # The eigendecomposition (determinism)
//!
//! nalgebra's `SymmetricEigen` (Householder tridiagonalisation, then implicit QR with
//! Wilkinson shifts), a maintained and tested solver rather than a hand-written Jacobi
//! sweep; it runs serially in `tell`, never on the thread pool, so the same C gives the same
//! bits on every run and thread count. Its output is then made independent of the solver's
//! internals: the eigenpairs are sorted by eigenvalue (ascending, ties by the solver's index)
//! and each eigenvector's sign is fixed so that its largest-magnitude component (the first
//! such) is positive. A C with a non-finite entry, or a solver that does not converge within
//! its iteration budget, keeps the previous decomposition (t_e is still set, so it is not
//! retried every generation).
//!
//! # Draw order (part of the reproducibility contract)
//!
//! Generation g's noise comes from `stream(seed, Purpose::Search, g, 0, 0)`: for k = 0..λ − 1
//! and each parameter j in order, one `gaussian()` z_kj, as sep-CMA-ES draws it (draw order 2:
//! `gaussian_ziggurat()`, vector k from its own stream). The update
//! regenerates z from the same stream, so a checkpoint needs only θ_g
//! (`"search": {"cma_es": {...}}`) and the evaluated generation, and a resumed run continues
//! with the same bits. The mean starts at 0, σ at `[evolution.cma_es] sigma_init`, C, b_j
//! and d_j at the identity, the paths at 0.

use super::cma_family::{CmaSearch, Distribution};
use super::sep_cma_es::{MAX_VARIANCE, MIN_SIGMA};
use crate::brain::genome::Genome;
use crate::evo::select::ranking;
use crate::experiment::evolution::{CmaEsSpec, MAX_MAGNITUDE};
use serde::{Deserialize, Serialize};

pub use crate::experiment::evolution::MAX_CMA_ES_PARAMETERS as MAX_PARAMETERS;

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
    /// c_1, the rank-one learning rate.
    pub c_1: f64,
    /// c_μ, the rank-μ learning rate.
    pub c_mu: f64,
    /// E‖N(0, I)‖.
    pub chi_n: f64,
}

impl Constants {
    /// The tutorial's constants for `n` parameters and `lambda` samples (both at least 1).
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
        let d_sigma =
            1.0 + 2.0 * (libm::sqrt((mu_eff - 1.0) / (nf + 1.0)) - 1.0).max(0.0) + c_sigma;
        let c_c = (4.0 + mu_eff / nf) / (nf + 4.0 + 2.0 * mu_eff / nf);
        let c_1 = 2.0 / ((nf + 1.3) * (nf + 1.3) + mu_eff);
        let c_mu = (1.0 - c_1)
            .min(2.0 * (mu_eff - 2.0 + 1.0 / mu_eff) / ((nf + 2.0) * (nf + 2.0) + mu_eff))
            .max(0.0);
        let chi_n = libm::sqrt(nf) * (1.0 - 1.0 / (4.0 * nf) + 1.0 / (21.0 * nf * nf));
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

    /// Whether C is decomposed again after `since` updates without a decomposition for `n`
    /// parameters: the tutorial's `counteval − eigeneval > λ/(c1 + cmu)/N/10`.
    pub fn decompose_after(&self, since: u64, n: usize) -> bool {
        let lambda = self.lambda as f64;
        since as f64 * lambda > lambda / (self.c_1 + self.c_mu) / n.max(1) as f64 / 10.0
    }
}

/// The search distribution that samples one generation: θ_g of the module documentation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CmaState {
    /// The mean m, one value per parameter: the current solution (the champion candidate).
    pub mean: Vec<f64>,
    /// The step size σ.
    pub sigma: f64,
    /// The covariance matrix C, row by row (n rows of n values, symmetric).
    pub covariance: Vec<Vec<f64>>,
    /// The step-size evolution path p_σ.
    pub path_sigma: Vec<f64>,
    /// The covariance evolution path p_c.
    pub path_c: Vec<f64>,
    /// The eigenvectors b_j of C at its last decomposition, one per row, in ascending order
    /// of their eigenvalues, each with its largest-magnitude component positive.
    pub eigenvectors: Vec<Vec<f64>>,
    /// The axis lengths d_j, the square roots of the eigenvalues, in the same order.
    pub axes: Vec<f64>,
    /// Updates so far, t (for h_σ's correction of a young path).
    pub updates: u64,
    /// t at the last decomposition, t_e.
    pub decomposed_at: u64,
}

/// The n × n identity, row by row.
fn identity(n: usize) -> Vec<Vec<f64>> {
    (0..n)
        .map(|i| (0..n).map(|j| if i == j { 1.0 } else { 0.0 }).collect())
        .collect()
}

impl CmaState {
    /// A state centred on `mean`, with σ = `sigma`, C = I and zero paths.
    pub fn centred_on(mean: &[f64], sigma: f64) -> CmaState {
        let n = mean.len();
        CmaState {
            mean: mean.to_vec(),
            sigma,
            covariance: identity(n),
            path_sigma: vec![0.0; n],
            path_c: vec![0.0; n],
            eigenvectors: identity(n),
            axes: vec![1.0; n],
            updates: 0,
            decomposed_at: 0,
        }
    }

    /// The initial state for `parameters` parameters: m = 0.
    pub fn initial(spec: &CmaEsSpec, parameters: usize) -> CmaState {
        CmaState::centred_on(&vec![0.0; parameters], spec.sigma_init)
    }

    /// Why this state cannot sample genomes of `parameters` parameters (wrong lengths, a
    /// non-finite value, a step size or axis that is not positive, t_e after t), or `None`
    /// if it can.
    pub fn problem(&self, parameters: usize) -> Option<String> {
        let vectors = [
            ("mean", &self.mean),
            ("path_sigma", &self.path_sigma),
            ("path_c", &self.path_c),
            ("axes", &self.axes),
        ];
        for (name, values) in vectors {
            if values.len() != parameters {
                return Some(format!(
                    "the cma-es {name} has {} values, the experiment's brain has {parameters} parameters",
                    values.len()
                ));
            }
            if values.iter().any(|x| !x.is_finite()) {
                return Some(format!("the cma-es {name} holds a non-finite value"));
            }
        }
        for (name, rows) in [
            ("covariance", &self.covariance),
            ("eigenvectors", &self.eigenvectors),
        ] {
            if rows.len() != parameters || rows.iter().any(|r| r.len() != parameters) {
                return Some(format!(
                    "the cma-es {name} is not {parameters} rows of {parameters} values (the \
                     experiment's brain has {parameters} parameters)"
                ));
            }
            if rows.iter().flatten().any(|x| !x.is_finite()) {
                return Some(format!("the cma-es {name} holds a non-finite value"));
            }
        }
        if !(self.sigma.is_finite() && self.sigma > 0.0) {
            return Some(format!(
                "the cma-es sigma is {}, not a positive number",
                self.sigma
            ));
        }
        if self.axes.iter().any(|&d| d <= 0.0) {
            return Some("the cma-es axes hold a value that is not positive".to_string());
        }
        if self.decomposed_at > self.updates {
            return Some(format!(
                "the cma-es decomposed_at ({}) is after its updates ({})",
                self.decomposed_at, self.updates
            ));
        }
        None
    }
}

/// Σ_j scale_j z_j b_j for the eigenvectors b_j (rows of `vectors`), summed in order of j.
fn combine(vectors: &[Vec<f64>], scale: impl Fn(usize) -> f64, z: &[f64]) -> Vec<f64> {
    let n = z.len();
    let mut out = vec![0.0; n];
    for (j, b) in vectors.iter().enumerate() {
        let a = scale(j) * z[j];
        for i in 0..n {
            out[i] += a * b[i];
        }
    }
    out
}

/// The steps y_k = Σ_j d_j z_kj b_j for each of `noises` in order.
pub fn steps(state: &CmaState, noises: &[Vec<f64>]) -> Vec<Vec<f64>> {
    noises
        .iter()
        .map(|z| combine(&state.eigenvectors, |j| state.axes[j], z))
        .collect()
}

/// The samples x_k = m + σ y_k for each of `noises` in order, then the mean itself.
pub fn individuals(state: &CmaState, noises: &[Vec<f64>]) -> Vec<Genome> {
    let genome = |parameters: Vec<f64>| Genome {
        parameters,
        step_size: None,
    };
    let mut out: Vec<Genome> = steps(state, noises)
        .into_iter()
        .map(|y| {
            genome(
                state
                    .mean
                    .iter()
                    .zip(&y)
                    .map(|(m, y)| m + state.sigma * y)
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
    libm::sqrt(sum)
}

/// The eigendecomposition of the symmetric `covariance`: the eigenvectors (one per row) and
/// the eigenvalues, sorted ascending (ties by the solver's index), each eigenvector with its
/// first largest-magnitude component positive. `None` if C holds a non-finite value or the
/// solver does not converge.
pub fn decompose(covariance: &[Vec<f64>]) -> Option<(Vec<Vec<f64>>, Vec<f64>)> {
    let n = covariance.len();
    if covariance.iter().flatten().any(|x| !x.is_finite()) {
        return None;
    }
    let matrix = nalgebra::DMatrix::from_fn(n, n, |i, j| covariance[i][j]);
    // The implicit QR needs about 2 sweeps per eigenvalue; 0 would mean no limit.
    let eigen = nalgebra::SymmetricEigen::try_new(matrix, f64::EPSILON, 100 * n + 100)?;
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| {
        eigen.eigenvalues[a]
            .total_cmp(&eigen.eigenvalues[b])
            .then(a.cmp(&b))
    });
    let mut vectors = Vec::with_capacity(n);
    let mut values = Vec::with_capacity(n);
    for &k in &order {
        let column = eigen.eigenvectors.column(k);
        let mut largest = 0;
        for i in 1..n {
            if column[i].abs() > column[largest].abs() {
                largest = i;
            }
        }
        let sign = if column[largest] < 0.0 { -1.0 } else { 1.0 };
        vectors.push(column.iter().map(|x| sign * x).collect());
        values.push(eigen.eigenvalues[k]);
    }
    if vectors
        .iter()
        .flatten()
        .chain(&values)
        .any(|x: &f64| !x.is_finite())
    {
        return None;
    }
    Some((vectors, values))
}

/// θ_{g+1} from θ_g, the noises that sampled generation g and the samples' fitness (higher is
/// better; `fitness[k]` for sample k, the mean's left out), steps 1–7.
///
/// # Panics
/// If `fitness` does not hold one value per noise.
pub fn update(
    constants: &Constants,
    state: &CmaState,
    noises: &[Vec<f64>],
    fitness: &[f64],
) -> CmaState {
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
    let ys: Vec<Vec<f64>> = parents
        .iter()
        .map(|z| combine(&state.eigenvectors, |j| state.axes[j], z))
        .collect();
    let mut z_w = vec![0.0; n];
    let mut y_w = vec![0.0; n];
    for ((w, z), y) in k.weights.iter().zip(&parents).zip(&ys) {
        for j in 0..n {
            z_w[j] += w * z[j];
            y_w[j] += w * y[j];
        }
    }
    let mean = state
        .mean
        .iter()
        .zip(&y_w)
        .map(|(m, y)| m + state.sigma * y)
        .collect();
    let whitened = combine(&state.eigenvectors, |_| 1.0, &z_w);
    let sigma_rate = libm::sqrt(k.c_sigma * (2.0 - k.c_sigma) * k.mu_eff);
    let path_sigma: Vec<f64> = state
        .path_sigma
        .iter()
        .zip(&whitened)
        .map(|(p, z)| (1.0 - k.c_sigma) * p + sigma_rate * z)
        .collect();
    let length = norm(&path_sigma);
    let updates = state.updates + 1;
    let young = 1.0 - libm::pow(1.0 - k.c_sigma, 2.0 * updates as f64);
    let h_sigma = length / libm::sqrt(young) < (1.4 + 2.0 / (nf + 1.0)) * k.chi_n;
    let c_rate = libm::sqrt(k.c_c * (2.0 - k.c_c) * k.mu_eff);
    let path_c: Vec<f64> = state
        .path_c
        .iter()
        .zip(&y_w)
        .map(|(p, y)| (1.0 - k.c_c) * p + if h_sigma { c_rate * y } else { 0.0 })
        .collect();
    let stall = if h_sigma { 0.0 } else { k.c_c * (2.0 - k.c_c) };
    let keep = 1.0 - k.c_1 - k.c_mu;
    let mut covariance = state.covariance.clone();
    for a in 0..n {
        for b in a..n {
            let c = state.covariance[a][b];
            let mut rank_mu = 0.0;
            for (w, y) in k.weights.iter().zip(&ys) {
                rank_mu += w * y[a] * y[b];
            }
            let value = keep * c + k.c_1 * (path_c[a] * path_c[b] + stall * c) + k.c_mu * rank_mu;
            covariance[a][b] = value;
            covariance[b][a] = value;
        }
    }
    let sigma = (state.sigma * libm::exp((k.c_sigma / k.d_sigma) * (length / k.chi_n - 1.0)))
        .clamp(MIN_SIGMA, MAX_MAGNITUDE);
    let mut next = CmaState {
        mean,
        sigma,
        covariance,
        path_sigma,
        path_c,
        eigenvectors: state.eigenvectors.clone(),
        axes: state.axes.clone(),
        updates,
        decomposed_at: state.decomposed_at,
    };
    if k.decompose_after(updates - state.decomposed_at, n) {
        next.decomposed_at = updates;
        if let Some((vectors, values)) = decompose(&next.covariance) {
            next.eigenvectors = vectors;
            next.axes = values
                .iter()
                .map(|&v| libm::sqrt(v.clamp(1.0 / MAX_VARIANCE, MAX_VARIANCE)))
                .collect();
        }
    }
    next
}

/// CMA-ES with a full covariance matrix, as a [`Distribution`] of [`CmaSearch`].
#[derive(Debug, Clone)]
pub struct Full;

impl Distribution for Full {
    type State = CmaState;
    type Constants = Constants;
    const NAME: &'static str = "cma-es";
    const TAG: &'static str = "cma_es";
    const DESCRIBE: &'static str = "CMA-ES";

    fn constants(parameters: usize, population: usize) -> Constants {
        Constants::new(parameters, population)
    }

    fn lambda(constants: &Constants) -> usize {
        constants.lambda
    }

    fn initial(spec: &CmaEsSpec, parameters: usize) -> CmaState {
        CmaState::initial(spec, parameters)
    }

    fn centred_on(mean: &[f64], sigma: f64) -> CmaState {
        CmaState::centred_on(mean, sigma)
    }

    fn individuals(state: &CmaState, noises: &[Vec<f64>]) -> Vec<Genome> {
        individuals(state, noises)
    }

    fn update(
        constants: &Constants,
        state: &CmaState,
        noises: &[Vec<f64>],
        fitness: &[f64],
    ) -> CmaState {
        update(constants, state, noises, fitness)
    }

    fn problem(state: &CmaState, parameters: usize) -> Option<String> {
        state.problem(parameters)
    }
}

/// CMA-ES as a [`super::Search`] (`algorithm = "cma-es"`).
pub type CmaEs = CmaSearch<Full>;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_decomposition_is_sorted_and_signed() {
        // C = [[2, 1], [1, 2]]: eigenvalues 1 and 3, eigenvectors (1, −1)/√2 and (1, 1)/√2.
        let (vectors, values) = decompose(&[vec![2.0, 1.0], vec![1.0, 2.0]]).unwrap();
        assert!((values[0] - 1.0).abs() < 1e-14 && (values[1] - 3.0).abs() < 1e-14);
        let r = std::f64::consts::FRAC_1_SQRT_2;
        // Ties in magnitude: the first component is the one made positive.
        assert!((vectors[0][0] - r).abs() < 1e-14 && (vectors[0][1] + r).abs() < 1e-14);
        assert!((vectors[1][0] - r).abs() < 1e-14 && (vectors[1][1] - r).abs() < 1e-14);
        // A diagonal C with a negative-looking start: the sorted identity's columns, positive.
        let (vectors, values) = decompose(&[
            vec![3.0, 0.0, 0.0],
            vec![0.0, 1.0, 0.0],
            vec![0.0, 0.0, 2.0],
        ])
        .unwrap();
        let near = |a: &[f64], b: &[f64]| a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-14);
        assert!(near(&values, &[1.0, 2.0, 3.0]), "{values:?}");
        assert!(near(&vectors[0], &[0.0, 1.0, 0.0]), "{vectors:?}");
        assert!(near(&vectors[2], &[1.0, 0.0, 0.0]), "{vectors:?}");
        assert!(decompose(&[vec![f64::NAN]]).is_none());
    }

    #[test]
    fn the_constants_are_the_tutorials_without_the_diagonal_factor() {
        let k = Constants::new(10, 10);
        assert!((k.mu_eff - 3.167_299_281_410_701_7).abs() < 1e-12);
        assert!((k.c_1 - 2.0 / (11.3 * 11.3 + k.mu_eff)).abs() < 1e-18);
        // n = 10: 1/((c_1 + c_μ) n 10) < 1, so C is decomposed every generation.
        assert!(k.decompose_after(1, 10));
        let big = Constants::new(2000, 26);
        assert!(!big.decompose_after(1, 2000) && big.decompose_after(1000, 2000));
    }
}
