//! `[evolution] draw_order = 2` (offspring from their own streams, two chances a draw, one word
//! per normal): each search that draws keeps the run guarantees under it (1 and 2 threads,
//! resumed), the key changes the run (a file without it keeps draw order 1), and the GA's
//! offspring do not depend on the number of threads.
use crate::cli_common::{fixture, read};
use crate::parallel_draws::on;
use crate::run_guarantees::{last_checkpoint, run, same_bytes_for};
use berry_evolve::brain::genome::Genome;
use berry_evolve::evo::lineage::Birth;
use berry_evolve::evo::next_generation;
use berry_evolve::evo::vary::next_generation_with_lineage;
use berry_evolve::experiment::evolution::{CrossoverSpec, EvolutionSpec, MutationSpec};
use berry_evolve::seed::{stream, unit, Generation, IndividualId, Purpose, Rng, Seed, TrialIndex};
use std::path::{Path, PathBuf};

/// `tests/fixtures/<name>` with `draw_order = 2` added to its `[evolution]` table, written into
/// `dir`.
fn with_draw_order_2(name: &str, dir: &Path) -> PathBuf {
    let text = String::from_utf8(read(&fixture(name))).unwrap();
    assert!(
        text.contains("\n[evolution]\n"),
        "{name} has an [evolution] table"
    );
    let changed = text.replacen("\n[evolution]\n", "\n[evolution]\ndraw_order = 2\n", 1);
    let file = dir.join(name);
    std::fs::write(&file, changed).unwrap();
    file
}

/// The genomes of the population in a run's generation-5 checkpoint.
fn last_genomes(run: &Path) -> serde_json::Value {
    let checkpoint = last_checkpoint(run);
    let individuals = checkpoint["payload"]["last"]["individuals"]
        .as_array()
        .unwrap()
        .clone();
    individuals.iter().map(|i| i["genome"].clone()).collect()
}

#[test]
fn every_search_keeps_its_guarantees_in_draw_order_2_and_the_key_changes_the_run() {
    let files = tempfile::tempdir().unwrap();
    for (name, also) in [
        ("tiny.toml", &[][..]),
        ("tiny-novelty.toml", &[][..]),
        ("tiny-map-elites.toml", &["archive.csv"][..]),
        ("tiny-pgpe.toml", &[][..]),
        ("tiny-sep-cma-es.toml", &[][..]),
    ] {
        let file = with_draw_order_2(name, files.path());
        let (_runs, two) = same_bytes_for(&file, &format!("{name} in draw order 2"), also);
        let first_order = files.path().join(format!("{name}-order-1"));
        run(&fixture(name), &first_order, "6", "2");
        assert_ne!(
            last_genomes(&two),
            last_genomes(&first_order),
            "{name}: draw order 2 made the same generation as draw order 1"
        );
    }
}

fn bits(genomes: &[Genome]) -> Vec<Vec<u64>> {
    genomes
        .iter()
        .map(|g| g.parameters.iter().map(|x| x.to_bits()).collect())
        .collect()
}

fn rng() -> Rng {
    stream(
        Seed(8),
        Purpose::Variation,
        Generation(3),
        IndividualId(0),
        TrialIndex(0),
    )
}

#[test]
fn ga_offspring_in_draw_order_2_are_the_same_on_any_thread_count() {
    let mut r = rng();
    let parents: Vec<Genome> = (0..16)
        .map(|_| Genome::new((0..3000).map(|_| unit(&mut r) - 0.5).collect()))
        .collect();
    let fitness: Vec<f64> = (0..16).map(|i| ((i * 5) % 7) as f64).collect();
    for crossover in [
        CrossoverSpec::Uniform { probability: 0.7 },
        CrossoverSpec::OnePoint { probability: 0.5 },
        CrossoverSpec::None,
    ] {
        let spec = EvolutionSpec {
            population: 40,
            elitism: 2,
            crossover,
            mutation: MutationSpec {
                probability: 0.05,
                sigma: 0.2,
                ..MutationSpec::default()
            },
            draw_order: 2,
            ..EvolutionSpec::default()
        };
        let (one, lineage) = on(1, || {
            next_generation_with_lineage(&spec, &parents, &fitness, &mut rng())
        });
        let (three, lineage_three) = on(3, || {
            next_generation_with_lineage(&spec, &parents, &fitness, &mut rng())
        });
        assert_eq!(bits(&one), bits(&three), "{crossover:?}");
        assert_eq!(lineage, lineage_three);
        assert_eq!(one.len(), 40);
        // An offspring that was not recombined differs from its parent in about 5% of its
        // genes (3000 × 0.05 = 150, standard deviation 12).
        for (child, born) in one.iter().zip(&lineage).skip(2) {
            if born.birth == Birth::Mutated {
                let parent = &parents[born.parents[0] as usize];
                let moved = child
                    .parameters
                    .iter()
                    .zip(&parent.parameters)
                    .filter(|(a, b)| a != b)
                    .count();
                assert!(
                    (90..=210).contains(&moved),
                    "{crossover:?}: {moved} genes moved"
                );
            }
        }
        let first_order = next_generation(
            &EvolutionSpec {
                draw_order: 1,
                ..spec.clone()
            },
            &parents,
            &fitness,
            &mut rng(),
        );
        assert_eq!(bits(&one[..2]), bits(&first_order[..2]), "elites");
        assert_ne!(bits(&one[2..]), bits(&first_order[2..]), "{crossover:?}");
    }
}
