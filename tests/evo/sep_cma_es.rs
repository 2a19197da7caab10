//! `[evolution] algorithm = "sep-cma-es"`: evaluations to reach a target on known functions
//! (through the search trait, with a test-function evaluator instead of the simulator)
//! against Ros & Hansen's published figures, the table's validation, and the run guarantees
//! (any thread count, same bytes; resumed or not, same bytes; the state in the checkpoint).

use crate::cli_common::fixture;
use crate::known_functions;
use crate::run_guarantees::{last_checkpoint, same_bytes_on_any_thread_count_and_resumed};

use berry_evolve::evo::search::sep_cma_es::SepCmaEs;
use berry_evolve::experiment::Experiment;

/// [`known_functions::evaluations_to_reach`] for sep-CMA-ES.
fn evaluations_to_reach(
    f: &dyn Fn(&[f64]) -> f64,
    n: usize,
    sigma: f64,
    target: f64,
    seed: u64,
    budget: usize,
) -> Option<usize> {
    let file = "tiny-sep-cma-es.toml";
    known_functions::evaluations_to_reach(SepCmaEs::new, file, f, n, sigma, target, seed, budget)
}

/// The median over seeds 1..=5 of [`evaluations_to_reach`].
fn median_evaluations(f: &dyn Fn(&[f64]) -> f64, n: usize, target: f64) -> usize {
    let mut runs: Vec<usize> = (1..=5)
        .map(|seed| {
            evaluations_to_reach(f, n, 1.0, target, seed, 200_000)
                .unwrap_or_else(|| panic!("seed {seed}: {target} not reached"))
        })
        .collect();
    runs.sort_unstable();
    runs[2]
}

/// The published setting starts at x0 = (1, ..., 1) with σ0 = 1; the search's mean starts at
/// 0, so the functions are shifted by 1 (translation changes nothing for CMA-ES).
fn shifted(x: &[f64], i: usize) -> f64 {
    x[i] + 1.0
}

/// Ros & Hansen (2008), Table 3: the ellipsoid f(x) = Σ 10^(6(i−1)/(n−1)) x_i² in 20-D, from
/// x0 = 1, σ0 = 1, to 10^-9: 5.4e3 evaluations (median). Table 2: the separable
/// "hyper-ellipsoid" Σ (i x_i)² in 30-D to 10^-10: 5.9e3. Within a factor of 2 of both. The
/// sphere has no figure in those tables; on it sep-CMA-ES is CMA-ES with an isotropic C, and
/// it must need fewer evaluations than the ellipsoid of the same dimension (and at least a
/// fifth of them: the covariance learning is what the ellipsoid costs extra).
#[test]
fn sep_cma_es_reaches_published_evaluation_counts_on_sphere_and_ellipsoids() {
    let ellipsoid = |x: &[f64]| {
        let n = x.len();
        let mut sum = 0.0;
        for i in 0..n {
            let a = libm::pow(10.0, 6.0 * i as f64 / (n - 1) as f64);
            sum += a * shifted(x, i) * shifted(x, i);
        }
        sum
    };
    let hyper = |x: &[f64]| {
        let mut sum = 0.0;
        for i in 0..x.len() {
            let y = (i + 1) as f64 * shifted(x, i);
            sum += y * y;
        }
        sum
    };
    let sphere = |x: &[f64]| {
        let mut sum = 0.0;
        for i in 0..x.len() {
            sum += shifted(x, i) * shifted(x, i);
        }
        sum
    };
    let e = median_evaluations(&ellipsoid, 20, 1e-9);
    assert!(
        (2_700..=10_800).contains(&e),
        "ellipsoid 20-D: {e} evaluations, published 5.4e3"
    );
    let h = median_evaluations(&hyper, 30, 1e-10);
    assert!(
        (2_950..=11_800).contains(&h),
        "hyper-ellipsoid 30-D: {h}, published 5.9e3"
    );
    let s = median_evaluations(&sphere, 20, 1e-9);
    assert!(s < e && 5 * s > e, "sphere 20-D: {s}, ellipsoid {e}");
    eprintln!("evaluations: ellipsoid 20-D {e}, hyper-ellipsoid 30-D {h}, sphere 20-D {s}");
}

#[test]
fn the_cma_es_table_is_checked_and_names_its_key() {
    let path = fixture("tiny-sep-cma-es.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let error = |text: &str| {
        Experiment::from_toml(text, &path)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default()
    };
    let zero = error(&text.replace("sigma_init = 0.5", "sigma_init = 0.0"));
    assert!(zero.contains("evolution.cma_es.sigma_init"), "{zero}");
    let ga = error(&text.replace("algorithm = \"sep-cma-es\"", "algorithm = \"ga\""));
    assert!(
        ga.contains("evolution.cma_es") && ga.contains("sep-cma-es"),
        "{ga}"
    );
    let elitism = error(&text.replace("generations = 8", "generations = 8\nelitism = 3"));
    assert!(elitism.contains("evolution.elitism"), "{elitism}");
    let e = Experiment::from_toml(&text, &path).unwrap();
    assert_eq!(
        e.evolution.evaluated_per_generation(),
        13,
        "λ samples and the mean"
    );
}

/// 1 and 2 threads give the same bytes; a run stopped after 3 generations and resumed to 6
/// gives the bytes of one never stopped; the checkpoint holds the distribution.
#[test]
fn sep_cma_es_runs_are_the_same_bytes_on_any_thread_count_and_resumed() {
    let (_dir, one) = same_bytes_on_any_thread_count_and_resumed("tiny-sep-cma-es.toml", &[]);
    let checkpoint = last_checkpoint(&one);
    let state = &checkpoint["payload"]["search"]["sep_cma_es"];
    assert!(state["sigma"].as_f64().unwrap() > 0.0, "{state}");
    assert_eq!(state["updates"], 5);
    let last = &checkpoint["payload"]["last"]["individuals"];
    assert_eq!(last.as_array().unwrap().len(), 13);
    assert_eq!(last[12]["lineage"]["birth"], "cma_mean");
    assert_eq!(
        last[12]["genome"]["parameters"], state["mean"],
        "θ_5 sampled generation 5"
    );
}
