//! A lethal predator ends a creature's life for evaluation: its score stops being recorded and
//! its final metabolism is the value at its death.

use crate::door::run_trial;
use berry_evolve::brain::genome::Genome;
use berry_evolve::experiment::Experiment;
use berry_evolve::seed::{Generation, TrialIndex};
use std::path::Path;

fn experiment(extra: &str) -> Experiment {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let path = root.join("tests/fixtures/tiny.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    // The tables go before [brain] so that they belong to [world] and [creature].
    let (world, rest) = text.split_at(text.find("[brain]").unwrap());
    let text = format!(
        "{world}{extra}\n[creature]\ninitial_metabolism = [5, 5, 0, 0]\ndecay_per_tick = [0.01, 0, 0, 0]\n\n{rest}"
    );
    Experiment::from_toml(&text, &path).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn a_creature_killed_at_once_keeps_its_initial_metabolism() {
    let air = include_str!("../fixtures/worlds/lethal-air-predator.toml");
    let killed = experiment(air);
    let free = experiment("");
    let genome = |e: &Experiment| Genome::new(vec![0.0; e.topology().parameter_count()]);
    let run = |e: &Experiment| {
        run_trial(
            e,
            &e.topology(),
            &[genome(e)],
            Generation(0),
            0,
            TrialIndex(0),
        )
        .unwrap()[0]
    };
    let dead = run(&killed);
    let alive = run(&free);
    // The air predator strikes in its first tick, before the creature's metabolism decays.
    assert_eq!(dead.metabolism, [5.0, 5.0, 0.0, 0.0]);
    // Without it the creature lives all 120 ticks and decays 0.01 per tick.
    assert!(
        (alive.metabolism[0] - (5.0 - 1.2)).abs() < 1e-9,
        "{alive:?}"
    );
    assert_ne!(dead.score, alive.score);
}
