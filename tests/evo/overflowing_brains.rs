//! A brain whose sums overflow (parameters near f64::MAX, ReLU hidden units) does not poison a
//! run: what a researcher gets is finite fitness values and a fitness.csv without NaN.
//!
//! Found behaviour: ReLU maps NaN to 0 and every output unit ends in tanh followed by
//! `nan_to_zero`, so motor commands stay finite even when ∞ − ∞ arises inside the network;
//! the `non_finite` column counts only individuals whose life or score was not finite (here 0).
//! Crossover clamps to the parents' range and mutation cannot overflow f64::MAX, so the huge
//! genomes also breed without producing an infinite parameter.

use berry_evolve::brain::Brain;
use berry_evolve::evo::search::ga::first_population;
use berry_evolve::evo::state::evaluate;
use berry_evolve::experiment::Experiment;
use berry_evolve::record::checkpoint;
use berry_evolve::run::{self, CheckpointPayload, RunOptions, Silent};
use std::path::Path;

fn relu_tiny() -> Experiment {
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/tiny.toml"),
    )
    .unwrap()
    .replace("hidden = [4]", "hidden = [4]\nactivation = \"relu\"");
    Experiment::from_toml(&text, Path::new("tiny-relu.toml")).unwrap()
}

/// Parameters at ±f64::MAX and ±1e308: products overflow to ±∞, sums to ∞ − ∞ = NaN.
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

/// Hidden layer all +f64::MAX (sums overflow to +∞, ReLU keeps ∞), output weights alternating
/// ±f64::MAX: each output sum is ∞ − ∞ = NaN, which the brain turns into 0.
fn nan_inside(experiment: &Experiment) -> Vec<f64> {
    let topology = experiment.topology();
    let n = topology.parameter_count();
    let inputs = Brain::new(&topology, &vec![0.0; n]).unwrap().inputs();
    let first = (inputs + 1) * 4; // the hidden layer: (inputs + 1) × 4 units
    (0..n)
        .map(|i| {
            if i < first || i % 2 == 0 {
                f64::MAX
            } else {
                -f64::MAX
            }
        })
        .collect()
}

#[test]
fn a_brain_whose_sums_become_nan_outputs_zero() {
    let experiment = relu_tiny();
    let topology = experiment.topology();
    let mut brain = Brain::new(&topology, &nan_inside(&experiment)).unwrap();
    // Layout assumed by nan_inside: hidden layer, then (4 + 1) × outputs.
    assert_eq!(
        (brain.inputs() + 1) * 4 + 5 * brain.outputs(),
        topology.parameter_count()
    );
    let inputs = vec![1.0; brain.inputs()];
    let mut outputs = vec![f64::NAN; brain.outputs()];
    brain.activate(&inputs, &mut outputs);
    assert_eq!(outputs, vec![0.0; brain.outputs()]);
}

#[test]
fn overflowing_brains_get_a_finite_fitness_or_are_counted_as_non_finite() {
    let experiment = relu_tiny();
    let topology = experiment.topology();
    let mut population = first_population(&experiment, &topology);
    let n = topology.parameter_count();
    for (k, genome) in population.iter_mut().enumerate().take(6) {
        genome.parameters = huge(n, k);
    }
    population[6].parameters = nan_inside(&experiment);
    let evaluated = evaluate(&experiment, &topology, 0, population).expect("evaluation runs");
    let summary = evaluated.summary();
    let mut non_finite = 0;
    for individual in &evaluated.individuals {
        match individual.evaluation.fitness {
            Some(f) => assert!(f.is_finite(), "fitness {f}"),
            None => non_finite += 1,
        }
        assert!(individual
            .evaluation
            .metabolism
            .iter()
            .all(|m| m.is_finite()));
    }
    assert_eq!(summary.non_finite, non_finite);
    for x in [
        summary.stats.best,
        summary.stats.mean,
        summary.stats.median,
        summary.stats.worst,
        summary.stats.std,
    ] {
        assert!(x.is_finite(), "{summary:?}");
    }
    // The NaN→0 rule of the brain keeps every motor command finite: nobody is excluded.
    assert_eq!(summary.non_finite, 0, "{summary:?}");
}

#[test]
fn a_run_whose_population_overflows_continues_with_a_clean_fitness_csv() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("run");
    let experiment = relu_tiny().with_overrides().generations(2).build().unwrap();
    let summary = run::start(
        experiment,
        &dir,
        false,
        RunOptions {
            jobs: 1,
            stop: None,
            evaluator: None,
        },
        &mut Silent,
    )
    .unwrap();
    // Replace the whole last generation by overflowing genomes, as if evolution had found them.
    let path = summary.checkpoint.unwrap();
    let mut loaded = checkpoint::load::<CheckpointPayload>(&path, None).unwrap();
    let n = loaded.payload.experiment.topology().parameter_count();
    for (k, individual) in loaded.payload.last.individuals.iter_mut().enumerate() {
        individual.genome.parameters = huge(n, k);
    }
    let hash = loaded.config_hash.clone();
    checkpoint::write_checkpoint(
        &dir.join(run::CHECKPOINT_DIR),
        &hash,
        loaded.generation,
        &loaded.payload,
        3,
    )
    .unwrap();
    let summary = run::resume(
        &dir,
        Some(6),
        false,
        RunOptions {
            jobs: 2,
            stop: None,
            evaluator: None,
        },
        &mut Silent,
    )
    .expect("the run continues");
    assert_eq!(summary.generations, 6);
    let csv = std::fs::read_to_string(dir.join(run::FITNESS_FILE)).unwrap();
    let lower = csv.to_ascii_lowercase();
    assert!(!lower.contains("nan") && !lower.contains("inf"), "{csv}");
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let non_finite_column = header.iter().position(|h| *h == "non_finite").unwrap();
    let mut rows = 0;
    for line in lines {
        rows += 1;
        for field in line.split(',') {
            let x: f64 = field.parse().unwrap_or_else(|_| panic!("{line}"));
            assert!(x.is_finite(), "{line}");
        }
        let counted: u64 = line
            .split(',')
            .nth(non_finite_column)
            .unwrap()
            .parse()
            .unwrap();
        assert_eq!(counted, 0, "{line}");
    }
    assert_eq!(rows, 6);
    // The offspring of the overflowing generation are still finite genomes.
    let last =
        checkpoint::load_latest_good::<CheckpointPayload>(&dir.join(run::CHECKPOINT_DIR), None)
            .unwrap();
    assert!(last
        .checkpoint
        .payload
        .last
        .individuals
        .iter()
        .all(|i| i.genome.is_finite()));
}
