//! Initialisation: the random generation 0.

use crate::brain::genome::Genome;
use crate::experiment::evolution::EvolutionSpec;
use crate::seed::{uniform, Rng};

/// Draws `spec.population` genomes of `parameter_count` parameters each, every parameter
/// uniform in [−init_range, init_range).
///
/// Draw order: individual 0's parameters in order, then individual 1's, and so on, one
/// `uniform()` (one 64-bit output) per parameter. With self-adaptive mutation every genome
/// starts with step size `sigma` (no draw); otherwise it has none.
pub fn initial_population(
    spec: &EvolutionSpec,
    parameter_count: usize,
    rng: &mut Rng,
) -> Vec<Genome> {
    let r = spec.init_range;
    let step_size = spec.mutation.self_adaptive.map(|_| spec.mutation.sigma);
    (0..spec.population)
        .map(|_| Genome {
            parameters: (0..parameter_count).map(|_| uniform(rng, -r, r)).collect(),
            step_size,
        })
        .collect()
}
