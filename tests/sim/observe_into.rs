//! `World::observe_into` (what lockstep evaluation uses: each world writes its observation
//! straight into the batch) gives the bits of `World::observe` and `World::step`: the same
//! observations, sensor noise draws and creature states, tick after tick, on every shipped
//! experiment's world (smell, whiskers, food detectors, landmarks, areas, noise, the eye,
//! doors, teleporters, wanderers and predators), several creatures, dead ones included; the
//! brute-force senses agree too; and `observe_into` leaves `World::observation` alone.

use crate::sim_common;

use berry_evolve::experiment::Experiment;
use berry_evolve::sim::controller::{Controller, MotorCommand};
use berry_evolve::sim::World;
use std::path::Path;

/// A stateless controller whose command is a fixed function of the observation's bits, so
/// that any difference in an observation soon shows in the poses too.
#[derive(Clone, Copy)]
struct Wobbly;

impl Controller for Wobbly {
    fn act(&mut self, observation: &[f64]) -> MotorCommand {
        let sum: f64 = observation
            .iter()
            .enumerate()
            .map(|(k, &x)| x * (1.0 + k as f64 * 0.37))
            .sum();
        MotorCommand {
            left: 0.3 * libm::sin(sum),
            right: 0.3 * libm::cos(1.3 * sum) + 0.05,
            eat: 1.0,
        }
    }
}

fn experiments() -> Vec<(String, Experiment)> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("experiments");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.push(dir.join("bench/foraging-world.toml"));
    files.sort();
    files
        .into_iter()
        .map(|p| {
            let e = Experiment::load(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
            (p.display().to_string(), e)
        })
        .collect()
}

fn bits(values: &[f64]) -> Vec<u64> {
    values.iter().map(|x| x.to_bits()).collect()
}

/// Steps `plain` with `World::step` and `fast` phase by phase with `observe_into`, for
/// `ticks` ticks, comparing every observation and creature as it goes; creature `kill.1` of
/// both dies at tick `kill.0`. Returns how many observations were compared.
fn compare(name: &str, plain: &mut World, fast: &mut World, ticks: u64, kill: (u64, usize)) -> u64 {
    let n = plain.creatures().len();
    let width = plain.layout().len();
    let mut controllers = vec![Wobbly; n];
    let mut out = vec![f64::NAN; width];
    let mut compared = 0;
    for tick in 0..ticks {
        if tick == kill.0 && kill.1 < n {
            plain.kill(kill.1);
            fast.kill(kill.1);
        }
        plain.step(&mut controllers);
        fast.begin_tick();
        for (i, controller) in controllers.iter_mut().enumerate() {
            let before = bits(fast.observation(i));
            out.fill(f64::NAN);
            if !fast.observe_into(i, &mut out) {
                assert!(
                    !plain.creatures()[i].alive,
                    "{name}: tick {tick} creature {i}"
                );
                assert!(
                    out.iter().all(|x| x.is_nan()),
                    "a dead creature writes nothing"
                );
                continue;
            }
            assert_eq!(
                bits(&out),
                bits(plain.observation(i)),
                "{name}: tick {tick} creature {i}"
            );
            assert_eq!(
                bits(fast.observation(i)),
                before,
                "observe_into leaves observation() alone"
            );
            compared += 1;
            fast.apply(i, controller.act(&out));
        }
        fast.end_tick();
        assert_eq!(fast.tick(), plain.tick());
        assert_eq!(fast.creatures(), plain.creatures(), "{name}: tick {tick}");
        assert_eq!(fast.food(), plain.food(), "{name}: tick {tick}");
    }
    compared
}

#[test]
fn observe_into_gives_the_bits_of_step_on_every_experiment_world() {
    let mut compared = 0;
    for (name, experiment) in experiments() {
        for (creatures, seed) in [(1, 3), (3, 4)] {
            let build = || {
                World::new(
                    &experiment.world,
                    &experiment.creature,
                    creatures,
                    sim_common::rng(seed),
                )
            };
            let (Ok(mut plain), Ok(mut fast)) = (build(), build()) else {
                continue;
            };
            compared += compare(&name, &mut plain, &mut fast, 300, (150, 1));
        }
    }
    assert!(compared > 10_000, "{compared} observations compared");
}

#[test]
fn brute_force_senses_give_the_same_observations() {
    for (name, experiment) in experiments() {
        let build = || {
            World::new(
                &experiment.world,
                &experiment.creature,
                2,
                sim_common::rng(7),
            )
        };
        let (Ok(mut plain), Ok(mut fast)) = (build(), build()) else {
            continue;
        };
        plain.set_brute_force(true);
        compare(&name, &mut plain, &mut fast, 200, (100, 0));
    }
}

#[test]
#[should_panic(expected = "one observation's width")]
fn observe_into_rejects_a_buffer_of_another_width() {
    let (_, experiment) = experiments().swap_remove(0);
    let mut world = World::new(
        &experiment.world,
        &experiment.creature,
        1,
        sim_common::rng(1),
    )
    .unwrap();
    let mut out = vec![0.0; world.layout().len() + 1];
    world.begin_tick();
    world.observe_into(0, &mut out);
}
