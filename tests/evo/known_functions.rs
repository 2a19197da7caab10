//! Known test functions for the evolution strategies, through the search trait with a
//! test-function evaluator instead of the simulator: how many evaluations a search needs to
//! reach a target (used by the CMA-ES and sep-CMA-ES tests).

use crate::cli_common::fixture;
use berry_evolve::evo::evaluate::Evaluation;
use berry_evolve::evo::search::Search;
use berry_evolve::evo::state::{EvaluatedGeneration, Individual};
use berry_evolve::experiment::Experiment;

/// The fixture `file` (an evolution strategy's tiny experiment, population 12, sigma_init
/// 0.5, seed 5) with `population` (λ), `sigma_init` and `seed` replaced.
pub fn experiment(file: &str, lambda: usize, sigma: f64, seed: u64) -> Experiment {
    let path = fixture(file);
    let text = std::fs::read_to_string(&path)
        .unwrap()
        .replace("population = 12", &format!("population = {lambda}"))
        .replace("sigma_init = 0.5", &format!("sigma_init = {sigma:?}"))
        .replace("seed = 5", &format!("seed = {seed}"));
    Experiment::from_toml(&text, &path).unwrap_or_else(|e| panic!("{e}"))
}

/// Evaluations (λ = 4 + ⌊3 ln n⌋ per generation; the mean, which these searches evaluate
/// too, is not counted, as the published figures count none) until a sample of `n`
/// parameters scores `target` or less on `f` (minimised), from the mean 0 with step size
/// `sigma`; `None` beyond `budget` evaluations. `new` makes the search (of `file`'s
/// algorithm) for an experiment and a number of parameters.
#[allow(clippy::too_many_arguments)]
pub fn evaluations_to_reach<S: Search>(
    new: impl Fn(&Experiment, usize) -> S,
    file: &str,
    f: &dyn Fn(&[f64]) -> f64,
    n: usize,
    sigma: f64,
    target: f64,
    seed: u64,
    budget: usize,
) -> Option<usize> {
    let lambda = 4 + (3.0 * libm::log(n as f64)).floor() as usize;
    let e = experiment(file, lambda, sigma, seed);
    let mut search = new(&e, n);
    assert_eq!(search.evaluated_per_generation(), lambda + 1);
    let mut evaluations = 0;
    while evaluations < budget {
        let asked = search.ask();
        let values: Vec<f64> = asked.genomes.iter().map(|g| f(&g.parameters)).collect();
        evaluations += lambda;
        if values[..lambda].iter().any(|&v| v <= target) {
            return Some(evaluations);
        }
        let individuals = asked
            .genomes
            .into_iter()
            .zip(&values)
            .map(|(genome, &v)| Individual {
                genome,
                evaluation: Evaluation {
                    fitness: Some(-v),
                    metabolism: [0.0; 4],
                    measures: Vec::new(),
                    area_ticks: Vec::new(),
                },
                lineage: None,
            })
            .collect();
        search.tell(&EvaluatedGeneration {
            generation: search.generation(),
            individuals,
        });
    }
    None
}
