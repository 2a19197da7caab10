//! Lockstep evaluation (several trials of a group at once, one batched brain per genome)
//! gives the same bits as living every (group, trial) alone with `run_trial`, on 1 and 2
//! threads: foraging, groups of several creatures, deaths and early stops, and brains whose
//! sums overflow. `evaluate_population` (which, with common random numbers, builds each trial
//! world once and clones it for every group) is compared with `evaluate_group` (which builds
//! every world itself), with common random numbers on and off.

use crate::door::{evaluate_group, evaluate_population, run_trial};
use berry_evolve::brain::genome::Genome;
use berry_evolve::evo::evaluate::Evaluation;
use berry_evolve::evo::lockstep::{self, CHUNK_TRIALS};
use berry_evolve::evo::search::ga::first_population;
use berry_evolve::evo::TrialPlan;
use berry_evolve::experiment::Experiment;
use berry_evolve::seed::{Generation, TrialIndex};
use std::path::Path;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn load(path: &str) -> Experiment {
    Experiment::load(&root().join(path)).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// `tests/fixtures/tiny.toml` with `world` appended to its `[world]` tables and `replace`
/// applied to the text.
fn tiny(world: &str, replace: (&str, &str)) -> Experiment {
    let path = root().join("tests/fixtures/tiny.toml");
    let text = std::fs::read_to_string(&path)
        .unwrap()
        .replace(replace.0, replace.1);
    let (head, rest) = text.split_at(text.find("[brain]").unwrap());
    let text = format!(
        "{head}{world}\n[creature]\ninitial_metabolism = [5, 5, 0, 0]\ndecay_per_tick = [0.01, 0, 0, 0]\n\n{rest}"
    );
    Experiment::from_toml(&text, &path).unwrap_or_else(|e| panic!("{e}"))
}

/// An evaluation as bits, so that -0.0, NaN payloads and the like count as differences.
fn bits(evaluations: &[Evaluation]) -> Vec<(Option<u64>, [u64; 4])> {
    evaluations
        .iter()
        .map(|e| (e.fitness.map(f64::to_bits), e.metabolism.map(f64::to_bits)))
        .collect()
}

fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
}

/// Checks, for generation `generation` of `population`:
/// - every lockstep chunk's outcomes are `run_trial`'s for each of its trials, to the bit;
/// - `evaluate_population` on 1 and on 2 threads equals evaluating group by group, trial by
///   trial, with `evaluate_group` (the per-trial path).
fn check(experiment: &Experiment, population: &[Genome], generation: u64) {
    let topology = experiment.topology();
    let k = experiment.evaluation.group_size as usize;
    let generation = Generation(generation);
    let mut serial = Vec::new();
    for (g, genomes) in population.chunks(k).enumerate() {
        let g = g as u64;
        for chunk in lockstep::chunks(experiment.evaluation.trials) {
            let together = lockstep::run_trials(
                &TrialPlan::new(experiment),
                &topology,
                genomes,
                generation,
                g,
                chunk.clone(),
            )
            .unwrap();
            assert_eq!(together.len() as u64, chunk.end - chunk.start);
            for (t, outcomes) in chunk.zip(&together) {
                let alone = run_trial(experiment, &topology, genomes, generation, g, TrialIndex(t))
                    .unwrap();
                assert_eq!(alone.len(), outcomes.len());
                for (a, b) in alone.iter().zip(outcomes) {
                    assert_eq!(a.score.to_bits(), b.score.to_bits(), "group {g} trial {t}");
                    assert_eq!(
                        a.metabolism.map(f64::to_bits),
                        b.metabolism.map(f64::to_bits),
                        "group {g} trial {t}"
                    );
                    assert_eq!(a.shocked_ticks, b.shocked_ticks);
                    assert_eq!(a.non_finite, b.non_finite);
                }
            }
        }
        serial.extend(evaluate_group(experiment, &topology, genomes, generation, g).unwrap());
    }
    let serial = bits(&serial);
    for threads in [1, 2] {
        let parallel = pool(threads)
            .install(|| evaluate_population(experiment, &topology, population, generation))
            .unwrap();
        assert_eq!(bits(&parallel), serial, "{threads} thread(s)");
    }
}

#[test]
fn foraging_matches_the_per_trial_path() {
    let experiment = load("experiments/foraging.toml");
    assert!(lockstep::stateless(&experiment.topology()));
    let experiment = experiment
        .with_overrides()
        .edit(|c| c.evolution.population = 6)
        // More trials than one chunk holds, so that a partial chunk follows a full one.
        .trials(CHUNK_TRIALS + 3)
        .ticks(150)
        .build()
        .unwrap();
    let population = first_population(&experiment, &experiment.topology());
    check(&experiment, &population, 0);
    // Without common random numbers every group has its own worlds.
    let experiment = experiment
        .with_overrides()
        .common_random_numbers(false)
        .build()
        .unwrap();
    check(&experiment, &population, 4);
}

#[test]
fn groups_sharing_a_world_match_the_per_trial_path() {
    // No shipped experiment has group_size > 1: tiny with groups of 3 and 4.
    for group_size in [3, 4] {
        let experiment = tiny("", ("", ""))
            .with_overrides()
            .edit(|c| c.evaluation.group_size = group_size)
            .trials(5)
            .build()
            .unwrap();
        let population = first_population(&experiment, &experiment.topology());
        assert_eq!(population.len() % group_size as usize, 0);
        check(&experiment, &population, 1);
    }
}

#[test]
fn deaths_and_early_stops_match_the_per_trial_path() {
    // Lethal ground predators kill some creatures part-way through their lives.
    let experiment = load("experiments/predator-arena.toml")
        .with_overrides()
        .trials(CHUNK_TRIALS + 1)
        .ticks(300)
        .edit(|c| c.evaluation.group_size = 2)
        .build()
        .unwrap();
    let population = first_population(&experiment, &experiment.topology());
    check(&experiment, &population, 0);
    // An air predator that strikes everyone in the first tick: every world stops at once,
    // each creature keeping its initial metabolism.
    let experiment = tiny(
        include_str!("../fixtures/worlds/lethal-air-predator.toml"),
        ("", ""),
    )
    .with_overrides()
    .edit(|c| c.evaluation.group_size = 3)
    .build()
    .unwrap();
    let topology = experiment.topology();
    let population = first_population(&experiment, &topology);
    check(&experiment, &population, 0);
    let outcomes = lockstep::run_trials(
        &TrialPlan::new(&experiment),
        &topology,
        &population[..3],
        Generation(0),
        0,
        0..2,
    )
    .unwrap();
    for outcome in outcomes.iter().flatten() {
        assert_eq!(outcome.metabolism, [5.0, 5.0, 0.0, 0.0]);
    }
    // A slower, smaller strike: creatures die at different ticks, some never.
    let experiment = tiny(
        "[[world.air_predators]]\nspeed = 2\nstrike_radius = 25\neffect = \"lethal\"\n",
        ("", ""),
    )
    .with_overrides()
    .edit(|c| c.evaluation.group_size = 2)
    .trials(CHUNK_TRIALS + 2)
    .build()
    .unwrap();
    let population = first_population(&experiment, &experiment.topology());
    check(&experiment, &population, 3);
}

/// Parameters at ±f64::MAX and ±1e308: products overflow to ±∞, sums to ∞ − ∞ = NaN inside
/// the network (see tests/evo/overflowing_brains.rs).
fn huge(n: usize, variant: usize) -> Vec<f64> {
    (0..n)
        .map(|i| match (i + variant) % 4 {
            0 => f64::MAX,
            1 => -f64::MAX,
            2 => 1e308,
            _ => -1e308,
        })
        .collect()
}

#[test]
fn overflowing_brains_match_the_per_trial_path() {
    // The brain turns NaN into 0, so these commands stay finite; the lockstep's own handling
    // of non-finite commands is tested in src/evo/lockstep.rs with a controller that does
    // produce NaN.
    let experiment = tiny("", ("hidden = [4]", "hidden = [4]\nactivation = \"relu\""));
    let topology = experiment.topology();
    let mut population = first_population(&experiment, &topology);
    let n = topology.parameter_count();
    for (k, genome) in population.iter_mut().enumerate().take(6) {
        genome.parameters = huge(n, k);
    }
    check(&experiment, &population, 0);
}

#[test]
fn stateful_brains_keep_the_per_trial_path() {
    for kind in ["recurrent", "ctrnn"] {
        let experiment = tiny(
            "",
            (
                "kind = \"mlp\"\nhidden = [4]",
                &format!("kind = \"{kind}\""),
            ),
        );
        let topology = experiment.topology();
        assert!(!lockstep::stateless(&topology), "{kind}");
        let population = first_population(&experiment, &topology);
        let serial: Vec<Evaluation> = population
            .chunks(1)
            .enumerate()
            .flat_map(|(g, genomes)| {
                evaluate_group(&experiment, &topology, genomes, Generation(0), g as u64).unwrap()
            })
            .collect();
        for threads in [1, 2] {
            let parallel = pool(threads)
                .install(|| evaluate_population(&experiment, &topology, &population, Generation(0)))
                .unwrap();
            assert_eq!(
                bits(&parallel),
                bits(&serial),
                "{kind}, {threads} thread(s)"
            );
        }
    }
}
