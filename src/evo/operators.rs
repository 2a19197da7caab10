//! The variation operators both draw orders share ([`crate::evo::vary`] and
//! [`crate::evo::vary_streams`]): recombination of two parents, and the self-adaptive step
//! size's draw.

use crate::brain::genome::Genome;
use crate::experiment::evolution::{CrossoverSpec, MutationSpec, MAX_MAGNITUDE};
use crate::seed::{below, chance, unit, Normals, Rng};
use rand_chacha::rand_core::RngCore;

/// Recombines `x` and `y` by `crossover` (always: the crossover probability is the caller's
/// decision), drawing as step 3 of [`crate::evo::vary`]'s documentation says. The offspring keeps
/// `x`'s step size; [`crate::evo::vary::next_generation`] replaces it by the geometric mean when
/// self-adaptive. `CrossoverSpec::None` copies `x` without a draw.
///
/// # Panics
/// If the parents differ in length.
pub fn recombine(crossover: &CrossoverSpec, x: &Genome, y: &Genome, rng: &mut Rng) -> Genome {
    recombine_from(crossover, x, y, rng)
}

/// [`recombine`] drawing from any generator (the buffered words of the stream).
pub(crate) fn recombine_from(
    crossover: &CrossoverSpec,
    x: &Genome,
    y: &Genome,
    rng: &mut impl RngCore,
) -> Genome {
    assert_eq!(
        x.parameters.len(),
        y.parameters.len(),
        "crossover parents must have the same number of parameters"
    );
    let n = x.parameters.len();
    let parameters = match crossover {
        CrossoverSpec::None => x.parameters.clone(),
        CrossoverSpec::Uniform { .. } => x
            .parameters
            .iter()
            .zip(&y.parameters)
            .map(|(&a, &b)| if chance(rng, 0.5) { b } else { a })
            .collect(),
        CrossoverSpec::OnePoint { .. } => {
            if n < 2 {
                x.parameters.clone()
            } else {
                let cut = 1 + below(rng, n as u64 - 1) as usize;
                let mut p = Vec::with_capacity(n);
                p.extend_from_slice(&x.parameters[..cut]);
                p.extend_from_slice(&y.parameters[cut..]);
                p
            }
        }
        CrossoverSpec::Arithmetic { .. } => {
            let a = unit(rng);
            x.parameters
                .iter()
                .zip(&y.parameters)
                .map(|(&p, &q)| (a * p + (1.0 - a) * q).max(p.min(q)).min(p.max(q)))
                .collect()
        }
    };
    Genome {
        parameters,
        step_size: x.step_size,
    }
}

/// Draws and sets `genome`'s step size ([`crate::evo::vary`]'s step 4, first draw, with self-adaptation; its normal
/// as `normals` says) and says the σ' its genes mutate with.
pub(crate) fn draw_step_size(
    genome: &mut Genome,
    mutation: &MutationSpec,
    normals: Normals,
    rng: &mut impl RngCore,
) -> f64 {
    match &mutation.self_adaptive {
        Some(adaptation) => {
            let tau = adaptation.tau_for(genome.parameters.len());
            let old = genome.step_size.unwrap_or(mutation.sigma);
            // The floor is applied last so that it wins over the ceiling.
            let new = (old * libm::exp(tau * normals.draw(rng)))
                .min(MAX_MAGNITUDE)
                .max(adaptation.min_sigma);
            genome.step_size = Some(new);
            new
        }
        None => {
            genome.step_size = None;
            mutation.sigma
        }
    }
}

/// A recombined offspring's step size with self-adaptation: the geometric mean √σx · √σy of
/// its parents' (a parent without one counts as having `sigma`); no draw.
pub(crate) fn mean_step_size(mutation: &MutationSpec, x: &Genome, y: &Genome) -> f64 {
    let sx = x.step_size.unwrap_or(mutation.sigma);
    let sy = y.step_size.unwrap_or(mutation.sigma);
    sx.sqrt() * sy.sqrt()
}
