//! The search seam (`evo::search`): ask/tell through the trait gives the genomes the GA and
//! PGPE gave before the trait (pinned from the binary before it), the state round-trips
//! through checkpoint JSON and a restored search continues with the same genomes, champion
//! candidates (PGPE's centre, none for the GA), strict checks of a checkpoint's state, and
//! `bench` timing the file's own algorithm.

use crate::cli_common::{fixture, run_ok};

use berry_evolve::brain::genome::Genome;
use berry_evolve::evo::evaluate::Evaluation;
use berry_evolve::evo::search::map_elites::MapElitesState;
use berry_evolve::evo::search::novelty::NoveltyState;
use berry_evolve::evo::search::pgpe::PgpeState;
use berry_evolve::evo::search::{self, Search, SearchState};
use berry_evolve::evo::state::{evaluate, EvaluatedGeneration, Individual};
use berry_evolve::experiment::Experiment;

fn load(name: &str) -> Experiment {
    Experiment::load(&fixture(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// FNV-1a over the little-endian bytes of every parameter (and step size) of `genomes`:
/// the same function as the script that pinned the values below from checkpoints.
fn hash(genomes: impl IntoIterator<Item = Genome>) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    let mut add = |x: f64| {
        for b in x.to_le_bytes() {
            h ^= u64::from(b);
            h = h.wrapping_mul(0x0100_0000_01b3);
        }
    };
    for g in genomes {
        g.parameters.iter().for_each(|&x| add(x));
        if let Some(s) = g.step_size {
            add(s);
        }
    }
    h
}

fn hash_values(values: &[f64]) -> u64 {
    hash([Genome {
        parameters: values.to_vec(),
        step_size: None,
    }])
}

/// Drives `search` as the run loop does, evaluating generations `0..=last` of `experiment`;
/// returns the last evaluated generation (its lineage recorded) and the search having asked
/// for it.
fn drive(experiment: &Experiment, search: &mut dyn Search, last: u64) -> EvaluatedGeneration {
    let topology = experiment.topology();
    let mut asked = search.ask();
    let mut g = search.generation();
    loop {
        assert_eq!(asked.genomes.len(), search.evaluated_per_generation());
        let evaluated = evaluate(experiment, &topology, g, asked.genomes)
            .unwrap()
            .with_lineage(asked.lineage);
        if g == last {
            return evaluated;
        }
        search.tell(&evaluated);
        g += 1;
        assert_eq!(search.generation(), g);
        asked = search.ask();
    }
}

fn births(generation: &EvaluatedGeneration) -> Vec<(String, Vec<u64>)> {
    generation
        .individuals
        .iter()
        .map(|i| {
            let l = i.lineage.as_ref().unwrap();
            (l.birth.name().to_string(), l.parents.clone())
        })
        .collect()
}

/// The values were computed by a few lines of Python (FNV-1a over the numbers, read back exactly)
/// from `checkpoints/gen-000003.json` of `berry-evolve run tests/fixtures/<file> --generations
/// 4`, run by the binary of commit f15e41a, before the search trait existed.
#[test]
fn ask_and_tell_give_the_genomes_the_ga_and_pgpe_gave_before_the_trait() {
    let ga = load("tiny.toml");
    let mut search = search::factory::of(&ga, &ga.topology());
    assert_eq!(search.name(), "ga");
    let third = drive(&ga, search.as_mut(), 3);
    assert_eq!(
        hash(third.individuals.iter().map(|i| i.genome.clone())),
        0x3ead_d172_0e90_1dbe,
        "the GA's generation 3 of tiny.toml"
    );
    let lineage = births(&third);
    assert_eq!(lineage[0], ("elite".to_string(), vec![1]));
    assert_eq!(lineage[1], ("crossover".to_string(), vec![2, 1]));
    assert_eq!(lineage[11], ("mutated".to_string(), vec![0]));
    assert_eq!(search.state(), None, "the GA keeps no state of its own");

    let pgpe = load("tiny-pgpe.toml");
    let mut search = search::factory::of(&pgpe, &pgpe.topology());
    assert_eq!(search.name(), "pgpe");
    let third = drive(&pgpe, search.as_mut(), 3);
    assert_eq!(
        hash(third.individuals.iter().map(|i| i.genome.clone())),
        0x7ada_74d5_0dd8_e893,
        "PGPE's generation 3 of tiny-pgpe.toml"
    );
    let lineage = births(&third);
    assert_eq!(lineage[0], ("pgpe_sample".to_string(), vec![]));
    assert_eq!(lineage[12], ("pgpe_centre".to_string(), vec![12]));
    let Some(Ok(state)) = search.state().and_then(|s| s.read::<PgpeState>("pgpe")) else {
        panic!("PGPE saves its distribution");
    };
    let all: Vec<f64> = [state.centre, state.stdev, state.velocity].concat();
    assert_eq!(
        hash_values(&all),
        0x6162_5ec1_a605_e04c,
        "θ_3 of tiny-pgpe.toml"
    );
}

/// Novelty search's generation 3 of tiny-novelty.toml and its archive then, pinned (values
/// from this test's first run, on the commit that added novelty search), so that a change to
/// the draws, the scores or the archive shows.
#[test]
fn novelty_search_gives_its_pinned_genomes_and_archive() {
    let e = load("tiny-novelty.toml");
    let mut search = search::factory::of(&e, &e.topology());
    let third = drive(&e, search.as_mut(), 3);
    let Some(Ok(state)) = search
        .state()
        .and_then(|s| s.read::<NoveltyState>("novelty"))
    else {
        panic!("novelty saves its archive");
    };
    let behaviours: Vec<f64> = state
        .archive
        .iter()
        .flat_map(|a| a.behaviour.clone())
        .collect();
    let got = (
        hash(third.individuals.iter().map(|i| i.genome.clone())),
        state.archive.len(),
        hash_values(&behaviours),
    );
    assert_eq!(
        got,
        (0x762e_5a7b_6a59_8e19, 10, 0xcbac_e1f1_5d63_212e),
        "{got:x?}"
    );
    assert_eq!(births(&third)[0].0, "elite");
}

/// MAP-Elites' generation 3 of tiny-map-elites.toml and its archive then, pinned (values
/// from this test's first run, on the commit that added MAP-Elites), so that a change to the
/// emitter's draws, the cells or the insertion rule shows.
#[test]
fn map_elites_gives_its_pinned_genomes_and_archive() {
    let e = load("tiny-map-elites.toml");
    let mut search = search::factory::of(&e, &e.topology());
    let third = drive(&e, search.as_mut(), 3);
    let Some(Ok(state)) = search
        .state()
        .and_then(|s| s.read::<MapElitesState>("map_elites"))
    else {
        panic!("map-elites saves its archive");
    };
    let fitness: Vec<f64> = state.elites.iter().map(|e| e.fitness).collect();
    let got = (
        hash(third.individuals.iter().map(|i| i.genome.clone())),
        state.elites.len(),
        hash(state.elites.iter().map(|e| e.genome.clone())),
        hash_values(&fitness),
    );
    assert_eq!(
        got,
        (
            0xe278_6ec6_f088_b725,
            3,
            0xadd1_6a4d_7c9a_a976,
            0x5c30_f73c_26cb_0875
        ),
        "{got:x?}"
    );
    assert_eq!(births(&third)[0].0, "iso_line");
}

/// A checkpoint holds the state that sampled the last generation; restoring it into a new
/// search and telling it that generation gives the next one, as a run never stopped.
#[test]
fn the_state_round_trips_through_checkpoint_json_and_resumes_exactly() {
    for name in [
        "tiny.toml",
        "tiny-pgpe.toml",
        "tiny-sep-cma-es.toml",
        "tiny-novelty.toml",
        "tiny-map-elites.toml",
    ] {
        let experiment = load(name);
        let topology = experiment.topology();
        let mut whole = search::factory::of(&experiment, &topology);
        let second = drive(&experiment, whole.as_mut(), 2);
        // As the run loop writes it, then reads it back.
        let json = serde_json::to_string(&whole.state()).unwrap();
        let read: Option<SearchState> = serde_json::from_str(&json).unwrap();
        assert_eq!(read, whole.state(), "{name}: {json:.80}");
        match &read {
            None => assert_eq!(json, "null", "{name}: the GA writes no state"),
            Some(state) => {
                let key = state.algorithm().replace('-', "_");
                assert!(json.starts_with(&format!("{{\"{key}\":{{")), "{json:.80}");
                assert_eq!(
                    state.algorithm(),
                    search::factory::of(&experiment, &topology).name()
                );
            }
        }
        whole.tell(&second);
        let expected = whole.ask();

        let mut resumed = search::factory::of(&experiment, &topology);
        assert_eq!(resumed.state_problem(read.as_ref()), None, "{name}");
        resumed.restore(read.as_ref(), 2);
        assert_eq!(resumed.state(), read, "{name}: restored as saved");
        resumed.tell(&second);
        assert_eq!(resumed.generation(), 3);
        assert_eq!(
            resumed.ask(),
            expected,
            "{name}: generation 3 after a resume"
        );
        assert_eq!(resumed.state(), whole.state(), "{name}");
    }
}

fn individual(genome: &Genome, fitness: f64) -> Individual {
    Individual {
        genome: genome.clone(),
        evaluation: Evaluation {
            fitness: Some(fitness),
            metabolism: [fitness, 0.0, 0.0, 0.0],
            measures: Vec::new(),
            area_ticks: Vec::new(),
        },
        lineage: None,
    }
}

/// PGPE's champion is its centre (the last individual) even when a sample scores higher, and
/// validation always considers the centre; the GA's is its best individual, with no extra
/// candidate.
#[test]
fn pgpe_names_its_centre_as_champion_candidate_and_the_ga_none() {
    for (name, centre_only) in [
        ("tiny-pgpe.toml", true),
        ("tiny-sep-cma-es.toml", true),
        ("tiny.toml", false),
        ("tiny-novelty.toml", false),
        ("tiny-map-elites.toml", false),
    ] {
        let experiment = load(name);
        let search = search::factory::of(&experiment, &experiment.topology());
        let asked = search.ask();
        let n = asked.genomes.len();
        // The first individual scores best; the last (PGPE's centre) second best.
        let generation = EvaluatedGeneration {
            generation: 0,
            individuals: asked
                .genomes
                .iter()
                .enumerate()
                .map(|(i, g)| {
                    let f = if i == 0 {
                        10.0
                    } else if i == n - 1 {
                        5.0
                    } else {
                        i as f64 / 100.0
                    };
                    individual(g, f)
                })
                .collect(),
        };
        let summary = generation.summary();
        let champion = search
            .improved_champion(None, &generation, &summary)
            .unwrap();
        let candidates = search.champion_candidates(&generation);
        if centre_only {
            assert_eq!(champion.individual, (n - 1) as u64, "{name}: the centre");
            assert_eq!(champion.fitness, 5.0);
            assert_eq!(candidates.len(), 1, "{name}");
            assert_eq!(candidates[0].individual, Some((n - 1) as u64));
            assert_eq!(candidates[0].genome, asked.genomes[n - 1]);
            assert_eq!(candidates[0].training_fitness, Some(5.0));
            assert_eq!(search.champion_candidates_per_generation(), 1);
        } else {
            assert_eq!(champion.individual, 0, "{name}: the best individual");
            assert!(candidates.is_empty(), "{name}");
            assert_eq!(search.champion_candidates_per_generation(), 0);
        }
        // An equal fitness keeps the older champion.
        assert!(search
            .improved_champion(Some(&champion), &generation, &summary)
            .is_none());
    }
}

/// The search's count, wording and first genomes agree with the experiment and with `ask`.
#[test]
fn each_search_describes_itself_and_its_first_genomes_are_its_first_ask() {
    for (name, words) in [
        ("tiny.toml", "genetic algorithm"),
        ("tiny-pgpe.toml", "PGPE"),
        ("tiny-sep-cma-es.toml", "sep-CMA-ES"),
        ("tiny-novelty.toml", "novelty search"),
        ("tiny-map-elites.toml", "MAP-Elites"),
    ] {
        let experiment = load(name);
        let search = search::factory::of(&experiment, &experiment.topology());
        assert_eq!(search.describe(), words);
        assert_eq!(
            search.evaluated_per_generation(),
            experiment.evolution.evaluated_per_generation(),
            "{name}"
        );
        let all = search.ask().genomes;
        for n in [1, 2, 5, all.len()] {
            assert_eq!(search.first_genomes(n), all[..n], "{name}, n = {n}");
        }
        assert_eq!(
            search.ask().genomes,
            all,
            "{name}: asking twice gives the same"
        );
    }
}

/// A checkpoint's state must be the experiment's algorithm's, with the brain's lengths.
#[test]
fn a_checkpoint_state_of_another_algorithm_or_shape_is_named() {
    let ga = load("tiny.toml");
    let pgpe = load("tiny-pgpe.toml");
    let pgpe_search = search::factory::of(&pgpe, &pgpe.topology());
    let state = pgpe_search.state();
    let ga_search = search::factory::of(&ga, &ga.topology());
    assert_eq!(
        ga_search.state_problem(state.as_ref()).as_deref(),
        Some("it holds a pgpe state, but its experiment uses the ga")
    );
    assert_eq!(
        pgpe_search.state_problem(None).as_deref(),
        Some("its experiment uses pgpe, but it holds no pgpe state")
    );
    let Some(Ok(mut short)) = state.and_then(|s| s.read::<PgpeState>("pgpe")) else {
        unreachable!()
    };
    short.centre.pop();
    let problem = pgpe_search
        .state_problem(Some(&SearchState::of("pgpe", &short)))
        .unwrap();
    assert!(problem.contains("the pgpe centre has"), "{problem}");
}

/// `bench --evolution` on a PGPE file times PGPE (its centre evaluated too), not a GA.
#[test]
fn bench_on_the_pgpe_file_times_pgpe() {
    let file = fixture("tiny-pgpe.toml");
    let out = run_ok(&[
        "bench",
        "--worlds",
        "2",
        "--ticks",
        "10",
        "--scaling",
        "0",
        "--generations",
        "2",
        "--evolution",
        file.to_str().unwrap(),
        "--json",
    ]);
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let evolution = &report["evolution"];
    assert_eq!(evolution["algorithm"], "pgpe");
    // 12 samples and the centre, 2 trials of 120 ticks.
    assert_eq!(
        evolution["creature_ticks_per_generation"],
        13.0 * 2.0 * 120.0
    );
    assert_eq!(evolution["identical_bests"], true);
    let stderr = String::from_utf8_lossy(&out.stderr);
    for t in evolution["threads"].as_array().unwrap() {
        let share = t["search_share_percent"].as_f64().unwrap();
        assert!((0.0..100.0).contains(&share), "{share}");
        assert!(
            stderr.contains(&format!(
                "(algorithm pgpe) on {} thread(s)",
                t["threads"].as_u64().unwrap()
            )),
            "{stderr}"
        );
        assert!(
            stderr.contains(&format!("search share {share:.2}%")),
            "{stderr}"
        );
    }
}
