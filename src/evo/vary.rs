//! Variation: crossover and mutation, and [`next_generation`], which makes generation g + 1
//! from evaluated generation g (elitism, selection, crossover, mutation), and
//! [`next_generation_with_lineage`], which also says who each offspring's parents were.
//!
//! # Draw order (part of the reproducibility contract)
//!
//! [`next_generation`] copies the `elitism` best parents first (no draws), then makes each
//! offspring in turn, drawing from the one variation stream in this order:
//!
//! 1. Parent x: one pick of the selection method (see [`crate::evo::select`]).
//! 2. Unless crossover is `none`: parent y, a second pick; then one `chance(probability)`
//!    (one `unit()`) deciding whether to recombine. If not, the offspring copies x.
//! 3. Recombination, when chosen:
//!    - uniform: one `chance(0.5)` per gene, in gene order; true takes y's gene;
//!    - one-point: one `below(n − 1)`, cut = 1 + that, genes `0..cut` from x, the rest from
//!      y (with fewer than 2 genes: no draw, the offspring copies x);
//!    - arithmetic: one `unit()` a; each gene is a·x + (1 − a)·y, kept within [min, max] of
//!      the two parents' genes so rounding cannot step outside.
//!
//!    With self-adaptation the recombined step size is the geometric mean √σx · √σy
//!    (a parent without one counts as having `sigma`); no draw.
//! 4. Mutation: with self-adaptation first one `gaussian()` g0 and σ' = σ · exp(τ g0)
//!    kept within [min_sigma, 10^6]; then for each gene in order one `chance(probability)`
//!    and, when it is true, one `gaussian()` g with gene += σ' · g (σ' = `sigma` without
//!    self-adaptation). The chance is drawn for every gene, so the stream's use does not
//!    depend on the probability.
//!
//! `chance` and `unit` consume one 64-bit output, `gaussian` two, and `below` one or
//! (rarely, on rejection) more.
//!
//! This is draw order 1, every file's unless it sets `[evolution] draw_order = 2`, whose
//! offspring come from their own streams ([`crate::evo::vary_streams`]).
//!
//! # Drawing, then transforming
//!
//! The draws above are made one after another from the one stream, in that order; but a
//! mutated gene's normal draw is only recorded then (its two `unit()` values), and turned
//! into the number ([`gaussian_from`], the `log`, `sqrt` and `cos` that cost most of a
//! variation) once every offspring is drawn, offspring by offspring in parallel. Each gene
//! is mutated at most once and each value is a pure function of its own two draws, so the
//! bits are those of drawing and mutating gene after gene, on any number of threads.
//! Crossover's and mutation's words themselves are read from a buffer of the same stream's
//! words filled ahead in parallel ([`Words`]), uniform crossover's and mutation's read in
//! place ([`Words::window`]) rather than by a call per word; selection draws from the stream
//! moved to where the buffer stands, and the buffer continues after its words.

use crate::brain::genome::Genome;
use crate::evo::lineage::{Birth, Lineage};
pub use crate::evo::operators::recombine;
use crate::evo::operators::{draw_step_size, mean_step_size, recombine_from};
use crate::evo::search::draws::Words;
use crate::evo::select::{ranking, truncation_count, Selector};
use crate::evo::vary_streams;
use crate::experiment::evolution::{CrossoverSpec, EvolutionSpec, MutationSpec, SelectionSpec};
use crate::seed::{chance, gaussian_from, unit, Normals, Rng};
use rand_chacha::rand_core::RngCore;
use rayon::prelude::*;

/// Makes the next generation: exactly `spec.population` genomes, the `spec.elitism` best
/// parents first (best first, ties broken by lower index; copied unchanged, step size
/// included), then offspring made as the module documentation says.
///
/// `fitness[i]` is the fitness of `parents[i]`; higher is better and every value should be
/// finite (a NaN ranks with −∞). If there are fewer parents than `spec.elitism`, all of them
/// are elites. Offspring carry a step size exactly when mutation is self-adaptive.
///
/// # Panics
/// If `parents` and `fitness` differ in length, if there are no parents while offspring are
/// needed, or if the parents' genomes differ in length (all are decoded by one topology).
pub fn next_generation(
    spec: &EvolutionSpec,
    parents: &[Genome],
    fitness: &[f64],
    rng: &mut Rng,
) -> Vec<Genome> {
    next_generation_with_lineage(spec, parents, fitness, rng).0
}

/// [`next_generation`], also saying where each offspring came from (the same genomes and
/// draws: recording the parents' indices draws nothing).
///
/// # Panics
/// As [`next_generation`].
pub fn next_generation_with_lineage(
    spec: &EvolutionSpec,
    parents: &[Genome],
    fitness: &[f64],
    rng: &mut Rng,
) -> (Vec<Genome>, Vec<Lineage>) {
    if let Some(first) = parents.first() {
        assert!(
            parents
                .iter()
                .all(|p| p.parameters.len() == first.parameters.len()),
            "all parents must have the same number of parameters"
        );
    }
    vary(spec, parents, fitness, rng)
}

/// [`next_generation_with_lineage`] without its checks, for a caller that left out (as empty
/// genomes) the parents that neither elitism nor selection can choose: the GA with
/// truncation selection keeps only those it can (see [`choosable`]).
pub(crate) fn vary(
    spec: &EvolutionSpec,
    parents: &[Genome],
    fitness: &[f64],
    rng: &mut Rng,
) -> (Vec<Genome>, Vec<Lineage>) {
    assert_eq!(
        parents.len(),
        fitness.len(),
        "one fitness value per parent is needed"
    );
    let mut next = Vec::with_capacity(spec.population);
    let mut lineage = Vec::with_capacity(spec.population);
    if spec.population == 0 {
        return (next, lineage);
    }
    let mut selector = Selector::new(&spec.selection, fitness);
    let elites = spec.elitism.min(parents.len()).min(spec.population);
    for &i in &selector.ranking()[..elites] {
        next.push(parents[i].clone());
        lineage.push(Lineage::of(Birth::Elite, &[i]));
    }
    if spec.offspring_streams() {
        vary_streams::offspring(spec, parents, &mut selector, rng, &mut next, &mut lineage);
        return (next, lineage);
    }
    // Each offspring's mutation, drawn in turn and applied to all of them at the end.
    let mut mutations = Vec::with_capacity(spec.population - elites);
    let mut words = Words::expecting(rng, expected_words(spec, parents, elites));
    while next.len() < spec.population {
        // Selection draws from the stream itself, the rest from the words after its draws.
        rng.set_word_pos(words.position());
        let xi = selector.pick(rng);
        let x = &parents[xi];
        let (mut child, born) = match spec.crossover {
            CrossoverSpec::None => {
                words.seek(rng.get_word_pos());
                (x.clone(), Lineage::of(Birth::Mutated, &[xi]))
            }
            crossover => {
                let yi = selector.pick(rng);
                let y = &parents[yi];
                words.seek(rng.get_word_pos());
                if chance(&mut words, crossover.probability()) {
                    let mut child = match crossover {
                        CrossoverSpec::Uniform { .. } => uniform_from_words(x, y, &mut words),
                        _ => recombine_from(&crossover, x, y, &mut words),
                    };
                    if spec.mutation.self_adaptive.is_some() {
                        child.step_size = Some(mean_step_size(&spec.mutation, x, y));
                    }
                    (child, Lineage::of(Birth::Crossover, &[xi, yi]))
                } else {
                    (x.clone(), Lineage::of(Birth::Mutated, &[xi]))
                }
            }
        };
        mutations.push(draw_mutation_from_words(
            &mut child,
            &spec.mutation,
            &mut words,
        ));
        next.push(child);
        lineage.push(born);
    }
    if !mutations.is_empty() {
        // Where drawing everything from the stream would have left it.
        rng.set_word_pos(words.position());
    }
    next[elites..]
        .par_iter_mut()
        .zip(mutations.par_iter())
        .for_each(|(child, mutation)| mutation.apply(child));
    (next, lineage)
}

/// About how many 32-bit words of the stream the offspring will use (a little more), so that
/// [`Words`] draws them in one or a few batches.
fn expected_words(spec: &EvolutionSpec, parents: &[Genome], elites: usize) -> usize {
    // The longest: parents left out are empty.
    let genes = parents
        .iter()
        .map(|p| p.parameters.len())
        .max()
        .unwrap_or(0) as f64;
    let crossover = match spec.crossover {
        CrossoverSpec::None => 0.0,
        CrossoverSpec::Uniform { probability } => 1.0 + probability.clamp(0.0, 1.0) * genes,
        _ => 2.0,
    };
    let mutation = 2.0 + genes * (1.0 + 2.0 * spec.mutation.probability.clamp(0.0, 1.0));
    let offspring = spec.population.saturating_sub(elites) as f64;
    // 64-bit draws are two words; 2% and a little more for the picks and the spread.
    (offspring * (crossover + mutation) * 2.0 * 1.02) as usize + 4096
}

/// The parents that elitism or selection can choose, by index: with truncation selection
/// the elites and the truncated best (ranked as [`crate::evo::select::Selector`] ranks them),
/// otherwise all of them. A caller keeping parents for [`vary`] need copy only these.
pub(crate) fn choosable(spec: &EvolutionSpec, fitness: &[f64]) -> Vec<bool> {
    match spec.selection {
        SelectionSpec::Truncation { fraction } if !fitness.is_empty() => {
            let kept = truncation_count(fraction, fitness.len())
                .max(spec.elitism)
                .min(fitness.len());
            let mut choosable = vec![false; fitness.len()];
            for &i in &ranking(fitness)[..kept] {
                choosable[i] = true;
            }
            choosable
        }
        _ => vec![true; fitness.len()],
    }
}

/// `unit()` of the 64-bit draw made of the words `lo` then `hi` (as ChaCha's `next_u64`).
#[inline(always)]
fn unit_of(lo: u32, hi: u32) -> f64 {
    ((u64::from(hi) << 32 | u64::from(lo)) >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

/// Uniform crossover of `x` and `y` exactly as [`recombine_from`] draws it (one
/// `chance(0.5)` per gene, in gene order, true taking y's gene), reading the words in place
/// rather than one call per gene.
fn uniform_from_words(x: &Genome, y: &Genome, words: &mut Words) -> Genome {
    assert_eq!(
        x.parameters.len(),
        y.parameters.len(),
        "crossover parents must have the same number of parameters"
    );
    let n = x.parameters.len();
    let mut parameters = Vec::with_capacity(n);
    while parameters.len() < n {
        let done = parameters.len();
        let window = words.window(2);
        let take = (window.len() / 2).min(n - done);
        parameters.extend(
            window[..2 * take]
                .chunks_exact(2)
                .zip(&x.parameters[done..done + take])
                .zip(&y.parameters[done..done + take])
                .map(|((w, &a), &b)| if unit_of(w[0], w[1]) < 0.5 { b } else { a }),
        );
        words.advance(2 * take);
    }
    Genome {
        parameters,
        step_size: x.step_size,
    }
}

/// [`draw_mutation`] reading the words in place: the same draws (the step size's
/// `gaussian`, then per gene one `chance` and, when true, two `unit()`), the same record.
fn draw_mutation_from_words(
    genome: &mut Genome,
    mutation: &MutationSpec,
    words: &mut Words,
) -> DrawnMutation {
    let sigma = draw_step_size(genome, mutation, Normals::BoxMuller, words);
    let p = mutation.probability;
    let n = genome.parameters.len();
    let expected = (p.clamp(0.0, 1.0) * n as f64) as usize;
    let mut genes = Vec::with_capacity(expected + expected / 8 + 16);
    // A gene uses at most 6 words; each is recorded into `staged` whether it mutates or not
    // and counted only when it does, so the loop has no branch on the draw.
    const STAGED: usize = 64;
    let mut staged = [(0usize, 0.0f64, 0.0f64); STAGED];
    let mut i = 0;
    while i < n {
        let window = words.window(6);
        let mut k = 0;
        let mut count = 0;
        while i < n && k + 6 <= window.len() {
            let w = &window[k..k + 6];
            let hit = unit_of(w[0], w[1]) < p;
            // `count` is below STAGED here; the mask only spares the bounds check.
            staged[count % STAGED] = (i, unit_of(w[2], w[3]), unit_of(w[4], w[5]));
            count += usize::from(hit);
            k += 2 + 4 * usize::from(hit);
            i += 1;
            if count == STAGED {
                genes.extend_from_slice(&staged);
                count = 0;
            }
        }
        genes.extend_from_slice(&staged[..count]);
        words.advance(k);
    }
    DrawnMutation { sigma, genes }
}

/// Mutates `genome` in place as step 4 of the module documentation says. Without
/// self-adaptation the genome's step size is cleared; with it, a genome without a step size
/// starts from `mutation.sigma`.
pub fn mutate(genome: &mut Genome, mutation: &MutationSpec, rng: &mut Rng) {
    draw_mutation(genome, mutation, rng).apply(genome);
}

/// A genome's mutation as drawn: the step size and, for each gene that mutates, its index
/// and the two `unit()` draws its normal draw is made of.
struct DrawnMutation {
    sigma: f64,
    genes: Vec<(usize, f64, f64)>,
}

impl DrawnMutation {
    /// Adds σ' · g to each drawn gene, g = [`gaussian_from`] its two draws: what
    /// `gene += sigma * gaussian(rng)` would have added.
    fn apply(&self, genome: &mut Genome) {
        for &(i, a, b) in &self.genes {
            genome.parameters[i] += self.sigma * gaussian_from(a, b);
        }
    }
}

/// Draws `genome`'s mutation as step 4 of the module documentation says and sets its step
/// size; the genes change when the result is applied.
fn draw_mutation(
    genome: &mut Genome,
    mutation: &MutationSpec,
    rng: &mut impl RngCore,
) -> DrawnMutation {
    let sigma = draw_step_size(genome, mutation, Normals::BoxMuller, rng);
    // About probability × genes entries: reserved once rather than grown.
    let expected = (mutation.probability.clamp(0.0, 1.0) * genome.parameters.len() as f64) as usize;
    let mut genes = Vec::with_capacity(expected + expected / 8 + 16);
    for i in 0..genome.parameters.len() {
        if chance(rng, mutation.probability) {
            let a = unit(rng);
            let b = unit(rng);
            genes.push((i, a, b));
        }
    }
    DrawnMutation { sigma, genes }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::seed::{stream, Generation, IndividualId, Purpose, Seed, TrialIndex};

    fn rng() -> Rng {
        stream(
            Seed(3),
            Purpose::Variation,
            Generation(2),
            IndividualId(0),
            TrialIndex(0),
        )
    }

    #[test]
    fn leaving_out_the_parents_truncation_cannot_choose_changes_nothing() {
        let mut r = rng();
        let parents: Vec<Genome> = (0..20)
            .map(|_| Genome::new((0..500).map(|_| unit(&mut r)).collect()))
            .collect();
        // Ties, so that the ranking's order by index matters.
        let fitness: Vec<f64> = (0..20).map(|i| ((i * 7) % 6) as f64).collect();
        for (fraction, elitism) in [(0.2, 2), (0.1, 5), (1.0, 0)] {
            let spec = EvolutionSpec {
                population: 30,
                elitism,
                selection: SelectionSpec::Truncation { fraction },
                crossover: CrossoverSpec::Uniform { probability: 0.5 },
                ..EvolutionSpec::default()
            };
            let choosable = choosable(&spec, &fitness);
            let kept = truncation_count(fraction, 20).max(elitism);
            assert_eq!(choosable.iter().filter(|&&c| c).count(), kept);
            let trimmed: Vec<Genome> = parents
                .iter()
                .zip(&choosable)
                .map(|(g, &c)| {
                    if c {
                        g.clone()
                    } else {
                        Genome::new(Vec::new())
                    }
                })
                .collect();
            let (all, all_lineage) =
                next_generation_with_lineage(&spec, &parents, &fitness, &mut rng());
            let (some, some_lineage) = vary(&spec, &trimmed, &fitness, &mut rng());
            assert_eq!(all, some, "fraction {fraction}, elitism {elitism}");
            assert_eq!(all_lineage, some_lineage);
        }
    }
}
