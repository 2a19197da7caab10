//! `[evolution] algorithm = "novelty"`: novelty, scores and archive additions on a case worked
//! by hand (through the search trait, with made-up evaluations), the refusals of
//! `[evolution.novelty]` naming their key, fitness_weight = 1 making the GA's run, and the run
//! guarantees (any thread count, same bytes; resumed or not, same bytes; the archive in the
//! checkpoint).

use crate::cli_common::{fixture, read};
use crate::run_guarantees::{last_checkpoint, run, same_bytes_on_any_thread_count_and_resumed};

use berry_evolve::brain::genome::Genome;
use berry_evolve::evo::evaluate::Evaluation;
use berry_evolve::evo::search::novelty::{
    archive_additions, novelty, scaled_ranks, scores, Addition, ArchiveEntry, NoveltyState,
};
use berry_evolve::evo::search::{self, SearchState};
use berry_evolve::evo::state::{EvaluatedGeneration, Individual};
use berry_evolve::experiment::Experiment;
use berry_evolve::seed::{stream, unit, Generation, IndividualId, Purpose, Seed, TrialIndex};
use std::path::Path;

fn close(a: &[f64], b: &[f64]) {
    assert_eq!(a.len(), b.len(), "{a:?} vs {b:?}");
    for (x, y) in a.iter().zip(b) {
        assert!((x - y).abs() < 1e-12, "{a:?} vs {b:?}");
    }
}

/// Behaviours in the unit square, k = 2: the population A = (0, 0), B = (0.3, 0.4),
/// C = (1, 0) and the archive D = (0, 1). Distances: AB 0.5, AC 1, AD 1, BC √0.65 = 0.80623,
/// BD √0.45 = 0.67082, CD √2. The two nearest: A {B, C or D} → (0.5 + 1)/2 = 0.75;
/// B {A, D} → (0.5 + 0.67082)/2 = 0.58541; C {B, A} → (0.80623 + 1)/2 = 0.90311.
#[test]
fn novelty_of_a_hand_computed_case() {
    let population = vec![vec![0.0, 0.0], vec![0.3, 0.4], vec![1.0, 0.0]];
    let archive = vec![vec![0.0, 1.0]];
    let n = novelty(&population, &archive, 2);
    close(
        &n,
        &[
            0.75,
            (0.5 + 0.45f64.sqrt()) / 2.0,
            (0.65f64.sqrt() + 1.0) / 2.0,
        ],
    );
    // Fewer neighbours than k: all of them (A's only neighbour is B).
    close(&novelty(&population[..2], &[], 2), &[0.5, 0.5]);
    close(&novelty(&population[..1], &[], 2), &[0.0]);
    // Threshold 0.7: A (0.75) and C (0.90) enter, B (0.59) does not; a broken brain never.
    let mut rng = stream(
        Seed(1),
        Purpose::Novelty,
        Generation(0),
        IndividualId(0),
        TrialIndex(0),
    );
    let fit = [Some(3.0), Some(1.0), Some(2.0)];
    assert_eq!(
        archive_additions(&n, &fit, Addition::Threshold(0.7), &mut rng),
        vec![0, 2]
    );
    assert_eq!(
        archive_additions(
            &n,
            &[Some(3.0), Some(1.0), None],
            Addition::Threshold(0.7),
            &mut rng
        ),
        vec![0]
    );
    // Ranks scaled to [0, 1], ties sharing their mean rank.
    close(&scaled_ranks(&[2.0, 1.0, 2.0]), &[0.75, 0.0, 0.75]);
    close(&scaled_ranks(&[5.0]), &[0.5]);
    // w = 0: novelty's ranks B < A < C. w = 0.5 with fitness 3, 1, 2: A 0.5·0.5 + 0.5·1,
    // B 0, C 0.5·1 + 0.5·0.5.
    close(&scores(&n, &fit, 0.0), &[0.5, 0.0, 1.0]);
    close(&scores(&n, &fit, 0.5), &[0.75, 0.0, 0.75]);
    assert_eq!(scores(&n, &[Some(3.0), None, Some(2.0)], 0.0)[1], f64::MIN);
}

/// tiny-novelty.toml with the `[evolution.novelty]` table replaced by `table` and the
/// population by `population`.
fn with_table(population: usize, table: &str) -> String {
    let text = std::fs::read_to_string(fixture("tiny-novelty.toml")).unwrap();
    let start = text.find("[evolution.novelty]").unwrap();
    let end = text.find("[behaviour]").unwrap();
    format!(
        "{}[evolution.novelty]\n{table}\n\n{}",
        &text[..start],
        &text[end..]
    )
    .replace("population = 12", &format!("population = {population}"))
}

fn load(text: &str) -> Experiment {
    Experiment::from_toml(text, &fixture("tiny-novelty.toml")).unwrap_or_else(|e| panic!("{e}"))
}

/// An individual with `[behaviour] measures = ["food_types", "distinct_food"]` values.
fn individual(fitness: Option<f64>, food_types: f64, distinct_food: f64) -> Individual {
    Individual {
        genome: Genome {
            parameters: vec![fitness.unwrap_or(-1.0); 3],
            step_size: None,
        },
        evaluation: Evaluation {
            fitness,
            metabolism: [0.0; 4],
            measures: vec![food_types, distinct_food],
            area_ticks: Vec::new(),
        },
        lineage: None,
    }
}

/// The same case through the search: descriptors distinct_food in [0, 10] and food_types in
/// [0, 2] scale the measures to A, B, C; the archive (capacity 2) holds D; telling the
/// generation adds A and C and pushes D out; the elites are C and A, by novelty.
#[test]
fn the_search_scales_descriptors_scores_by_novelty_and_keeps_a_bounded_archive() {
    let e = load(&with_table(
        3,
        "descriptors = [{ measure = \"distinct_food\", min = 0, max = 10 }, \
         { measure = \"food_types\", min = 0, max = 2 }]\n\
         k = 2\narchive_threshold = 0.7\narchive_size = 2",
    ));
    let mut s = search::factory::of(&e, &e.topology());
    assert_eq!(s.name(), "novelty");
    let d = |generation, individual, behaviour: Vec<f64>| ArchiveEntry {
        generation,
        individual,
        behaviour,
    };
    let before = SearchState::of(
        "novelty",
        &NoveltyState {
            archive: vec![d(3, 1, vec![0.0, 1.0])],
        },
    );
    assert_eq!(s.state_problem(Some(&before)), None);
    s.restore(Some(&before), 4);
    // Scaled: A (0/10, 0/2), B (3/10, 0.8/2), C (10/10, 0/2); a value beyond max clamps.
    let generation = EvaluatedGeneration {
        generation: 4,
        individuals: vec![
            individual(Some(3.0), 0.0, 0.0),
            individual(Some(1.0), 0.8, 3.0),
            individual(Some(2.0), 0.0, 12.0),
        ],
    };
    s.tell(&generation);
    assert_eq!(
        s.state(),
        Some(SearchState::of(
            "novelty",
            &NoveltyState {
                archive: vec![d(4, 0, vec![0.0, 0.0]), d(4, 2, vec![1.0, 0.0])],
            },
        ))
    );
    let next = s.ask();
    assert_eq!(
        next.genomes[0], generation.individuals[2].genome,
        "C is the most novel"
    );
    assert_eq!(next.genomes[1], generation.individuals[0].genome, "then A");
    assert_eq!(next.lineage[0].parents, vec![2]);

    // Probabilistic addition: one draw per individual from the generation's novelty stream.
    let e = load(&with_table(
        3,
        "descriptors = [{ measure = \"distinct_food\", min = 0, max = 10 }]\n\
         k = 2\narchive_probability = 0.5\narchive_size = 10",
    ));
    let mut s = search::factory::of(&e, &e.topology());
    s.tell(&generation);
    let mut rng = stream(
        e.seed(),
        Purpose::Novelty,
        Generation(4),
        IndividualId(0),
        TrialIndex(0),
    );
    let expected: Vec<u64> = (0..3).filter(|_| unit(&mut rng) < 0.5).collect();
    let Some(Ok(state)) = s.state().and_then(|s| s.read::<NoveltyState>("novelty")) else {
        panic!("novelty saves its archive")
    };
    let got: Vec<u64> = state.archive.iter().map(|e| e.individual).collect();
    assert_eq!(got, expected);
    let wrong = SearchState::of(
        "novelty",
        &NoveltyState {
            archive: vec![d(0, 0, vec![0.5, 0.5])],
        },
    );
    let problem = s.state_problem(Some(&wrong)).unwrap();
    assert!(
        problem.contains("has 2 descriptors") && problem.contains("has 1"),
        "{problem}"
    );
    assert!(s
        .state_problem(None)
        .unwrap()
        .contains("no novelty archive"));
}

#[test]
fn the_novelty_table_is_checked_and_names_its_key() {
    let error = |text: &str| {
        Experiment::from_toml(text, &fixture("tiny-novelty.toml"))
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default()
    };
    let one = "descriptors = [{ measure = \"distinct_food\", min = 0, max = 6 }]";
    let missing = error(&with_table(
        12,
        "descriptors = [{ measure = \"ticks_alive\", min = 0, max = 6 }]",
    ));
    assert!(
        missing.contains("evolution.novelty.descriptors")
            && missing.contains("ticks_alive")
            && missing.contains("food_types, distinct_food"),
        "{missing}"
    );
    let range = error(&with_table(
        12,
        "descriptors = [{ measure = \"distinct_food\", min = 6, max = 6 }]",
    ));
    assert!(
        range.contains("evolution.novelty.descriptors") && range.contains("min < max"),
        "{range}"
    );
    let none = error(&with_table(12, ""));
    assert!(
        none.contains("evolution.novelty.descriptors") && none.contains("at least one"),
        "{none}"
    );
    // The pool: 12 − 1 others + 10 archived = 21 neighbours at most.
    let k = error(&with_table(
        12,
        &format!("{one}\nk = 22\narchive_size = 10"),
    ));
    assert!(k.contains("evolution.novelty.k") && k.contains("21"), "{k}");
    assert_eq!(
        error(&with_table(
            12,
            &format!("{one}\nk = 21\narchive_size = 10")
        )),
        ""
    );
    let both = error(&with_table(
        12,
        &format!("{one}\narchive_threshold = 0.1\narchive_probability = 0.1"),
    ));
    assert!(
        both.contains("evolution.novelty.archive_probability"),
        "{both}"
    );
    let weight = error(&with_table(12, &format!("{one}\nfitness_weight = 1.5")));
    assert!(
        weight.contains("evolution.novelty.fitness_weight"),
        "{weight}"
    );
    let ga = error(&with_table(12, one).replace("algorithm = \"novelty\"", "algorithm = \"ga\""));
    assert!(
        ga.contains("evolution.novelty") && ga.contains("only used with"),
        "{ga}"
    );
}

/// 1 and 2 threads give the same bytes; a run stopped after 3 generations and resumed to 6
/// gives the bytes of one never stopped; the checkpoint holds the archive, full by then
/// (capacity 10, about 3.6 entries a generation), its oldest entries gone.
#[test]
fn novelty_runs_are_the_same_bytes_on_any_thread_count_and_resumed() {
    let (_dir, one) = same_bytes_on_any_thread_count_and_resumed("tiny-novelty.toml", &[]);
    let checkpoint = last_checkpoint(&one);
    let archive = checkpoint["payload"]["search"]["novelty"]["archive"]
        .as_array()
        .unwrap()
        .clone();
    assert_eq!(archive.len(), 10, "full");
    assert!(
        archive[0]["generation"].as_u64().unwrap() > 0,
        "the oldest left"
    );
    assert!(
        archive
            .iter()
            .all(|e| e["generation"].as_u64().unwrap() < 5),
        "the archive before generation 5 was told"
    );
    assert_eq!(archive[0]["behaviour"].as_array().unwrap().len(), 2);
}

/// With fitness_weight = 1 the score is fitness's rank, which orders (and ties) as the
/// fitness does, so the run is the GA's: the same fitness.csv and best.json (but its config hash).
#[test]
fn fitness_weight_one_is_the_ga() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(fixture("tiny-novelty.toml"))
        .unwrap()
        .replace("fitness_weight = 0.25", "fitness_weight = 1.0");
    let start = text.find("algorithm = \"novelty\"").unwrap();
    let end = text.find("[behaviour]").unwrap();
    let ga = format!("{}{}", &text[..start], &text[end..]);
    let (nf, gf) = (dir.path().join("novelty.toml"), dir.path().join("ga.toml"));
    std::fs::write(&nf, &text).unwrap();
    std::fs::write(&gf, ga).unwrap();
    let (n, g) = (dir.path().join("n"), dir.path().join("g"));
    run(&nf, &n, "6", "2");
    run(&gf, &g, "6", "2");
    assert!(
        read(&n.join("fitness.csv")) == read(&g.join("fitness.csv")),
        "fitness.csv differs"
    );
    // best.json names its experiment's config hash, which differs; the genome may not.
    let best = |dir: &Path| -> serde_json::Value {
        let mut v: serde_json::Value =
            serde_json::from_slice(&read(&dir.join("best.json"))).unwrap();
        v["origin"]["config_hash"] = serde_json::Value::Null;
        v
    };
    assert_eq!(best(&n), best(&g));
}
