//! Variation in draw order 2 (`[evolution] draw_order = 2`): every offspring drawn from its
//! own stream, two genes' chances a draw and one word a normal, so that making a generation
//! of brains with thousands of parameters costs little and runs on every thread.
//!
//! # Draw order 2 (part of the reproducibility contract)
//!
//! The elites are copied first, as in draw order 1 ([`crate::evo::vary`]). Then, from the
//! generation's variation stream, offspring after offspring: parent x (one pick), and unless
//! crossover is `none` parent y (a second pick) and one `chance(probability)` to recombine.
//! Only the picks come from that stream. Offspring k of the population (counting the elites)
//! then draws everything else from its own stream: the generation stream's key with ChaCha
//! stream number k + 1, from its first word (the generation's own draws are stream 0):
//!
//! 1. Recombination, when chosen: uniform takes one 64-bit draw per 64 genes, gene i taking
//!    y's gene when bit i mod 64 (from the least significant) of draw ⌊i / 64⌋ is set;
//!    one-point and arithmetic draw as in draw order 1. With self-adaptation the step size
//!    is the geometric mean √σx · √σy, no draw.
//! 2. Mutation: with self-adaptation first one normal g0 and σ' = σ · exp(τ g0), kept within
//!    [min_sigma, 10^6]. Then one 64-bit draw per two genes, in gene order: gene 2i mutates
//!    when the draw's low 32 bits are below ⌊p · 2^32⌋ (every gene when p ≥ 1), gene 2i + 1
//!    when its high 32 bits are; then, for each mutated gene in gene order, one normal g and
//!    gene += σ' · g. The chances are drawn whatever p is, so the stream's use depends on p
//!    only through the number of normals.
//!
//! Normals are [`gaussian_ziggurat`]. Each offspring is a function of its picks
//! and its own stream, so offspring are made in parallel with the same bits on any number of
//! threads.

use crate::brain::genome::Genome;
use crate::evo::lineage::{Birth, Lineage};
use crate::evo::operators::{draw_step_size, mean_step_size, recombine};
use crate::evo::search::draws::own_stream;
use crate::evo::select::Selector;
use crate::experiment::evolution::{CrossoverSpec, EvolutionSpec, MutationSpec};
use crate::seed::{chance, gaussian_ziggurat, Normals, Rng};
use rand_chacha::rand_core::RngCore;
use rayon::prelude::*;

/// One offspring's parents, as drawn from the generation's stream: y only when it is
/// recombined.
struct Parents {
    x: usize,
    y: Option<usize>,
}

/// Appends the offspring to `next` (which holds the elites) until the population is full,
/// and their lineage to `lineage`, drawing as the module documentation says.
pub(crate) fn offspring(
    spec: &EvolutionSpec,
    parents: &[Genome],
    selector: &mut Selector,
    rng: &mut Rng,
    next: &mut Vec<Genome>,
    lineage: &mut Vec<Lineage>,
) {
    let first = next.len();
    let mut chosen = Vec::with_capacity(spec.population - first);
    while first + chosen.len() < spec.population {
        let x = selector.pick(rng);
        let y = match spec.crossover {
            CrossoverSpec::None => None,
            crossover => {
                let y = selector.pick(rng);
                chance(rng, crossover.probability()).then_some(y)
            }
        };
        lineage.push(match y {
            Some(y) => Lineage::of(Birth::Crossover, &[x, y]),
            None => Lineage::of(Birth::Mutated, &[x]),
        });
        chosen.push(Parents { x, y });
    }
    let key: &Rng = rng;
    let made: Vec<Genome> = chosen
        .par_iter()
        .enumerate()
        .map(|(k, p)| {
            let mut own = own_stream(key, first + k);
            make(spec, &parents[p.x], p.y.map(|y| &parents[y]), &mut own)
        })
        .collect();
    next.extend(made);
}

/// One offspring of `x` (and `y` when recombined) drawn from its own stream `own`.
fn make(spec: &EvolutionSpec, x: &Genome, y: Option<&Genome>, own: &mut Rng) -> Genome {
    let mut child = match y {
        Some(y) => {
            let mut child = match spec.crossover {
                CrossoverSpec::Uniform { .. } => uniform_by_bits(x, y, own),
                crossover => recombine(&crossover, x, y, own),
            };
            if spec.mutation.self_adaptive.is_some() {
                child.step_size = Some(mean_step_size(&spec.mutation, x, y));
            }
            child
        }
        None => x.clone(),
    };
    mutate_by_chances(&mut child, &spec.mutation, own);
    child
}

/// Uniform crossover with one 64-bit draw per 64 genes (step 1).
fn uniform_by_bits(x: &Genome, y: &Genome, own: &mut Rng) -> Genome {
    assert_eq!(
        x.parameters.len(),
        y.parameters.len(),
        "crossover parents must have the same number of parameters"
    );
    let mut parameters = Vec::with_capacity(x.parameters.len());
    for (mine, theirs) in x.parameters.chunks(64).zip(y.parameters.chunks(64)) {
        let bits = own.next_u64();
        // A mask per gene rather than a branch: the bits are random, so a branch would be
        // mispredicted half the time, which cost more than drawing them.
        parameters.extend(mine.iter().zip(theirs).enumerate().map(|(j, (&a, &b))| {
            let take = 0u64.wrapping_sub(bits >> j & 1);
            f64::from_bits(a.to_bits() & !take | b.to_bits() & take)
        }));
    }
    Genome {
        parameters,
        step_size: x.step_size,
    }
}

/// Mutation by chances drawn two genes a draw, then the normals (step 2).
fn mutate_by_chances(genome: &mut Genome, mutation: &MutationSpec, own: &mut Rng) {
    let sigma = draw_step_size(genome, mutation, Normals::Ziggurat, own);
    let threshold = chance_threshold(mutation.probability);
    let genes = &mut genome.parameters;
    // Every gene's index is written, and the count moves on only for those that mutate: no
    // branch on a random bit, which would be mispredicted at every probability but the ends.
    let mut mutated = vec![0u32; genes.len() + 1];
    let mut count = 0;
    for pair in (0..genes.len()).step_by(2) {
        let draw = own.next_u64();
        mutated[count] = pair as u32;
        count += usize::from(draw & 0xFFFF_FFFF < threshold);
        if pair + 1 < genes.len() {
            mutated[count] = pair as u32 + 1;
            count += usize::from(draw >> 32 < threshold);
        }
    }
    for &i in &mutated[..count] {
        genes[i as usize] += sigma * gaussian_ziggurat(own);
    }
}

/// A gene mutates when its 32-bit chance is below this: ⌊p · 2^32⌋, all of them from p = 1.
fn chance_threshold(p: f64) -> u64 {
    if p >= 1.0 {
        1 << 32
    } else if p > 0.0 {
        (p * 4_294_967_296.0) as u64
    } else {
        0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::seed::{stream, Generation, IndividualId, Purpose, Seed, TrialIndex};

    fn own() -> Rng {
        stream(
            Seed(4),
            Purpose::Variation,
            Generation(1),
            IndividualId(0),
            TrialIndex(0),
        )
    }

    #[test]
    fn uniform_crossover_takes_each_gene_by_its_bit() {
        let n = 150;
        let x = Genome::new(vec![0.0; n]);
        let y = Genome::new(vec![1.0; n]);
        let child = uniform_by_bits(&x, &y, &mut own());
        let mut words = own();
        let bits: Vec<u64> = (0..3).map(|_| words.next_u64()).collect();
        for (i, &gene) in child.parameters.iter().enumerate() {
            let expected = (bits[i / 64] >> (i % 64)) & 1;
            assert_eq!(gene, expected as f64, "gene {i}");
        }
    }

    #[test]
    fn mutation_reads_two_chances_a_draw_then_the_normals() {
        // p = 0.5: a gene mutates when its half of the draw is below 2^31, i.e. when that
        // half's top bit is clear; worked out here from the same words.
        let mutation = MutationSpec {
            probability: 0.5,
            sigma: 2.0,
            ..MutationSpec::default()
        };
        let n = 41;
        let mut genome = Genome::new(vec![0.0; n]);
        mutate_by_chances(&mut genome, &mutation, &mut own());
        let mut words = own();
        let draws: Vec<u64> = (0..21).map(|_| words.next_u64()).collect();
        let mut expected = vec![0.0; n];
        for i in 0..n {
            let half = if i % 2 == 0 {
                draws[i / 2] as u32
            } else {
                (draws[i / 2] >> 32) as u32
            };
            if half >> 31 == 0 {
                expected[i] = 2.0 * gaussian_ziggurat(&mut words);
            }
        }
        let changed = expected.iter().filter(|&&g| g != 0.0).count();
        assert!((10..=31).contains(&changed), "{changed} of {n} mutated");
        assert_eq!(genome.parameters, expected);
    }

    #[test]
    fn each_gene_mutates_with_the_probability() {
        for p in [0.01, 0.1, 0.3, 0.9] {
            let mutation = MutationSpec {
                probability: p,
                sigma: 1.0,
                ..MutationSpec::default()
            };
            let n = 20_000;
            let mut rng = own();
            let mut hits = vec![0u32; 4];
            for _ in 0..25 {
                let mut genome = Genome::new(vec![0.0; n]);
                mutate_by_chances(&mut genome, &mutation, &mut rng);
                // Four stretches of the genome: each gene alike, the last ones too.
                for (q, part) in genome.parameters.chunks(n / 4).enumerate() {
                    hits[q] += part.iter().filter(|&&g| g != 0.0).count() as u32;
                }
            }
            for h in hits {
                let share = f64::from(h) / (25.0 * (n / 4) as f64);
                let sd = (p * (1.0 - p) / (25.0 * (n / 4) as f64)).sqrt();
                assert!((share - p).abs() < 5.0 * sd, "p {p}: share {share}");
            }
        }
        // The ends: every gene, and none; the chances drawn either way.
        for (p, changed) in [(1.0, 30), (0.0, 0)] {
            let mutation = MutationSpec {
                probability: p,
                ..MutationSpec::default()
            };
            let mut genome = Genome::new(vec![0.0; 30]);
            let mut rng = own();
            mutate_by_chances(&mut genome, &mutation, &mut rng);
            assert_eq!(
                genome.parameters.iter().filter(|&&g| g != 0.0).count(),
                changed
            );
            // 15 draws of chances, then a normal per mutated gene (one draw, rarely more).
            let words = rng.get_word_pos();
            assert!(
                words >= 2 * (15 + changed) as u128 && words < 2 * (15 + 2 * changed + 1) as u128
            );
        }
    }
}
