//! The searches' draws made in parallel (issue 30's speed work) are bit for bit those of
//! drawing one after another: each hot loop is checked against a plain sequential
//! reference written here from the documented draw order, with genomes long enough to span
//! several parallel chunks and the GA's buffered-word batches, on 1 and 3 threads.

use berry_evolve::brain::genome::Genome;
use berry_evolve::evo::search::{cma_family, map_elites, pgpe};
use berry_evolve::evo::select::Selector;
use berry_evolve::evo::vary::{mutate, next_generation, recombine};
use berry_evolve::experiment::evolution::{
    CrossoverSpec, EvolutionSpec, MutationSpec, PgpeSpec, SelectionSpec, SelfAdaptation,
};
use berry_evolve::seed::{
    chance, gaussian, gaussian_from, stream, unit, Generation, IndividualId, Normals, Purpose, Rng,
    Seed, TrialIndex,
};

fn rng(seed: u64) -> Rng {
    stream(
        Seed(seed),
        Purpose::Variation,
        Generation(1),
        IndividualId(0),
        TrialIndex(0),
    )
}

fn bits(values: &[f64]) -> Vec<u64> {
    values.iter().map(|x| x.to_bits()).collect()
}

/// Runs `f` on a pool of `threads` threads.
pub fn on<T: Send>(threads: usize, f: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
        .install(f)
}

/// The GA's next generation drawn one value after another from the stream, as
/// `src/evo/vary.rs` documents it (recombine and mutate on their own draw from the stream
/// directly).
fn sequential_generation(
    spec: &EvolutionSpec,
    parents: &[Genome],
    fitness: &[f64],
    rng: &mut Rng,
) -> Vec<Genome> {
    let mut selector = Selector::new(&spec.selection, fitness);
    let elites = spec.elitism.min(parents.len()).min(spec.population);
    let mut next: Vec<Genome> = selector.ranking()[..elites]
        .iter()
        .map(|&i| parents[i].clone())
        .collect();
    while next.len() < spec.population {
        let x = &parents[selector.pick(rng)];
        let mut child = match spec.crossover {
            CrossoverSpec::None => x.clone(),
            crossover => {
                let y = &parents[selector.pick(rng)];
                if chance(rng, crossover.probability()) {
                    let mut child = recombine(&crossover, x, y, rng);
                    if spec.mutation.self_adaptive.is_some() {
                        let sx = x.step_size.unwrap_or(spec.mutation.sigma);
                        let sy = y.step_size.unwrap_or(spec.mutation.sigma);
                        child.step_size = Some(sx.sqrt() * sy.sqrt());
                    }
                    child
                } else {
                    x.clone()
                }
            }
        };
        mutate(&mut child, &spec.mutation, rng);
        next.push(child);
    }
    next
}

#[test]
fn mutate_is_a_chance_then_a_gaussian_per_gene() {
    let spec = MutationSpec {
        probability: 0.3,
        sigma: 0.2,
        self_adaptive: None,
    };
    let start: Vec<f64> = (0..5000).map(|i| i as f64 * 0.001).collect();
    let mut genome = Genome::new(start.clone());
    let mut r = rng(3);
    mutate(&mut genome, &spec, &mut r);
    let mut reference = rng(3);
    let mut expected = start;
    for gene in &mut expected {
        if chance(&mut reference, spec.probability) {
            *gene += spec.sigma * gaussian(&mut reference);
        }
    }
    assert_eq!(bits(&genome.parameters), bits(&expected));
    assert_eq!(unit(&mut r).to_bits(), unit(&mut reference).to_bits());
}

#[test]
fn gaussian_from_is_gaussian() {
    let mut a = rng(4);
    let mut b = rng(4);
    for _ in 0..1000 {
        let (u1, u2) = (unit(&mut b), unit(&mut b));
        assert_eq!(gaussian(&mut a).to_bits(), gaussian_from(u1, u2).to_bits());
    }
}

/// Every crossover kind, with and without self-adaptation, 3,000 genes and 24 offspring
/// (about 150,000 words: several of the buffer's batches).
#[test]
fn the_ga_generation_is_the_sequential_one_on_any_thread_count() {
    let genes = 3000;
    let mut r = rng(9);
    let parents: Vec<Genome> = (0..10)
        .map(|_| {
            let mut g = Genome::new((0..genes).map(|_| unit(&mut r) - 0.5).collect());
            g.step_size = Some(0.1 + unit(&mut r));
            g
        })
        .collect();
    let fitness: Vec<f64> = (0..10).map(|i| ((i * 7) % 10) as f64).collect();
    let crossovers = [
        CrossoverSpec::None,
        CrossoverSpec::Uniform { probability: 0.5 },
        CrossoverSpec::OnePoint { probability: 0.7 },
        CrossoverSpec::Arithmetic { probability: 0.6 },
    ];
    for crossover in crossovers {
        for self_adaptive in [
            None,
            Some(SelfAdaptation {
                tau: None,
                min_sigma: 1e-6,
            }),
        ] {
            let spec = EvolutionSpec {
                population: 26,
                elitism: 2,
                selection: SelectionSpec::Tournament { size: 3 },
                crossover,
                mutation: MutationSpec {
                    probability: 0.3,
                    sigma: 0.3,
                    self_adaptive,
                },
                ..EvolutionSpec::default()
            };
            let mut reference = rng(11);
            let expected = sequential_generation(&spec, &parents, &fitness, &mut reference);
            let after = unit(&mut reference).to_bits();
            for threads in [1, 3] {
                let mut r = rng(11);
                let got = on(threads, || {
                    next_generation(&spec, &parents, &fitness, &mut r)
                });
                assert_eq!(got.len(), expected.len());
                for (k, (g, e)) in got.iter().zip(&expected).enumerate() {
                    assert_eq!(
                        bits(&g.parameters),
                        bits(&e.parameters),
                        "{crossover:?}, self-adaptive {}, {threads} threads: offspring {k}",
                        self_adaptive.is_some()
                    );
                    assert_eq!(g.step_size.map(f64::to_bits), e.step_size.map(f64::to_bits));
                }
                assert_eq!(unit(&mut r).to_bits(), after, "the stream ends in place");
            }
        }
    }
}

#[test]
fn pgpe_and_cma_noises_are_the_sequential_ones() {
    let parameters = 2500;
    let state = pgpe::PgpeState::initial(&PgpeSpec::default(), parameters);
    for threads in [1, 3] {
        let got = on(threads, || {
            pgpe::noises(Normals::BoxMuller, Seed(5), Generation(2), &state, 7 * 2)
        });
        let mut r = pgpe::noise_stream(Seed(5), Generation(2));
        let expected: Vec<Vec<u64>> = (0..7)
            .map(|_| {
                state
                    .stdev
                    .iter()
                    .map(|&s| (s * gaussian(&mut r)).to_bits())
                    .collect()
            })
            .collect();
        let got: Vec<Vec<u64>> = got.iter().map(|v| bits(v)).collect();
        assert_eq!(got, expected, "pgpe, {threads} threads");

        let got = on(threads, || {
            cma_family::noises(Normals::BoxMuller, Seed(5), Generation(2), parameters, 5)
        });
        let mut r = stream(
            Seed(5),
            Purpose::Search,
            Generation(2),
            IndividualId(0),
            TrialIndex(0),
        );
        let expected: Vec<Vec<u64>> = (0..5)
            .map(|_| {
                (0..parameters)
                    .map(|_| gaussian(&mut r).to_bits())
                    .collect()
            })
            .collect();
        let got: Vec<Vec<u64>> = got.iter().map(|v| bits(v)).collect();
        assert_eq!(got, expected, "cma, {threads} threads");
    }
}

#[test]
fn map_elites_offspring_are_the_sequential_ones() {
    let genes = 2500;
    let xi: Vec<f64> = (0..genes).map(|i| libm::sin(i as f64)).collect();
    let xj: Vec<f64> = (0..genes).map(|i| libm::cos(i as f64)).collect();
    for threads in [1, 3] {
        let mut r = rng(21);
        let (iso, gauss) = on(threads, || {
            let iso = map_elites::iso_line(&xi, &xj, 0.01, 0.2, &mut r);
            let gauss = map_elites::gaussian_offspring(&xi, 0.1, &mut r);
            (iso, gauss)
        });
        let mut reference = rng(21);
        let line = gaussian(&mut reference);
        let isotropic: Vec<f64> = (0..genes).map(|_| gaussian(&mut reference)).collect();
        let expected_iso = map_elites::iso_line_with(&xi, &xj, 0.01, 0.2, line, &isotropic);
        let expected_gauss: Vec<f64> = xi
            .iter()
            .map(|&a| a + 0.1 * gaussian(&mut reference))
            .collect();
        assert_eq!(
            bits(&iso),
            bits(&expected_iso),
            "iso-line, {threads} threads"
        );
        assert_eq!(
            bits(&gauss),
            bits(&expected_gauss),
            "gaussian, {threads} threads"
        );
        assert_eq!(unit(&mut r).to_bits(), unit(&mut reference).to_bits());
    }
}
