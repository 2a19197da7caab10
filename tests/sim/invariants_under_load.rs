//! Simulator invariants under load (reliability): many seeded worlds with every element on
//! (doors, teleporters, wanderers, ground and air predators, safe areas, landmarks, the eye,
//! sensor noise), fast motors and a crowded arena. After every tick: no living creature is
//! outside the arena or touches a static wall, living creatures and wanderers never overlap,
//! headings stay unit length, the metabolic vector stays finite and non-negative, and food
//! substance is conserved. And nothing panics.
//!
//! Short version in CI; the long version is `bash scripts/invariants-long.sh`
//! (BERRY_LOAD_WORLDS and BERRY_LOAD_TICKS raise the numbers).

use crate::sim_common::world;
use berry_evolve::geometry::{circle_touches_segment, circles_touch, Segment, Vec2};
use berry_evolve::seed::{chance, uniform, Rng};
use berry_evolve::sim::controller::{Controller, MotorCommand};
use berry_evolve::sim::gadgets::Role;
use berry_evolve::sim::World;
use rand::SeedableRng;

/// Random, often saturated motor signals (the clamp is max_rpt = 1: 12.6 LU per tick).
struct Reckless {
    rng: Rng,
}

impl Controller for Reckless {
    fn act(&mut self, observation: &[f64]) -> MotorCommand {
        assert!(
            observation.iter().all(|x| x.is_finite()),
            "non-finite observation"
        );
        let full = chance(&mut self.rng, 0.3);
        let (l, r) = if full {
            (2.0, uniform(&mut self.rng, 1.0, 2.0))
        } else {
            (
                uniform(&mut self.rng, -1.2, 1.2),
                uniform(&mut self.rng, -1.2, 1.2),
            )
        };
        MotorCommand {
            left: l,
            right: r,
            eat: uniform(&mut self.rng, 0.0, 1.0),
        }
    }
}

const WORLD: &str = r#"
[world]
arena = [240, 240]
slippery_walls = true
wall_shock = true

[[world.walls]]
from = [80, 0]
to = [80, 150]
[[world.walls]]
from = [160, 240]
to = [160, 90]
[[world.walls]]
from = [100, 60]
to = [140, 100]
opaque = false

[[world.doors]]
from = [80, 150]
to = [80, 200]
trigger = [40, 220]
trigger_radius = 6
open_ticks = 40

[[world.teleporters]]
entry = [200, 30]
radius = 5
exit = [30, 30]
odour = [0, 0, 0, 0, 0, 0, 0, 1]
intensity = 0.5
range = 60

[world.kinds.apple]
class = "food"
radius = 1.5
substance = [2, 1, 0, 0]
bite = [0.3, 0.2, 0, 0]
regen = [0.01, 0.005, 0, 0]
smell_follows_amount = true
odour = [1, 0, 0, 0, 0, 0, 0, 0]
intensity = 1
range = 50

[world.kinds.nettle]
class = "aversive"
radius = 2
odour = [0, 1, 0, 0, 0, 0, 0, 0]
intensity = 0.5
range = 30

[[world.place]]
kind = "apple"
count = 40
min_spacing = 6
[[world.place]]
kind = "nettle"
count = 8

[[world.landmarks]]
position = [500, -100]

[[world.areas]]
region = [170, 170, 230, 230]
kind = "safe"
odour = [0, 0, 0, 0, 0, 1, 0, 0]
intensity = 0.5

[world.wanderers]
count = 8
max_rpt = 0.8

[[world.predators]]
strategy = "chase"
effect = "shock"
max_rpt = 0.5
[[world.predators]]
strategy = "patrol"
waypoints = [[20, 20], [220, 20], [220, 220]]
effect = "lethal"
max_rpt = 0.3
[[world.predators]]
strategy = "wander"
effect = "shock"

[[world.air_predators]]
speed = 4
strike_radius = 8
effect = "shock"
[[world.air_predators]]
speed = 1.5
strike_radius = 5
effect = "lethal"

[creature]
max_rpt = 1.0
eating = "action"
decay_per_tick = [0.001, 0, 0, 0]
decay_per_lu = [0.001, 0.0005, 0, 0]

[creature.inputs]
metabolism = true
landmarks = true
areas = true
eye = true

[creature.eye]
width = 8
height = 2

[creature.noise.smell]
n = 0.1
n_sigma = 0.05
m = 0.2
m_sigma = 0.1

[creature.noise.eye]
n = 0.05
n_sigma = 0.02
"#;

/// The walls that never move: the arena's four and the three interior ones (doors excluded:
/// a door may close on a creature standing in its doorway, which may then only move away).
fn static_walls() -> Vec<Segment> {
    let p = |x: f64, y: f64| Vec2::new(x, y);
    vec![
        Segment::new(p(0.0, 0.0), p(240.0, 0.0)),
        Segment::new(p(240.0, 0.0), p(240.0, 240.0)),
        Segment::new(p(240.0, 240.0), p(0.0, 240.0)),
        Segment::new(p(0.0, 240.0), p(0.0, 0.0)),
        Segment::new(p(80.0, 0.0), p(80.0, 150.0)),
        Segment::new(p(160.0, 240.0), p(160.0, 90.0)),
        Segment::new(p(100.0, 60.0), p(140.0, 100.0)),
    ]
}

fn env(name: &str, default: u64) -> u64 {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

fn check(w: &World, walls: &[Segment], seed: u64) {
    let t = w.tick();
    let r = w.creature_radius();
    let [width, height] = w.arena();
    let creatures = w.creatures();
    for (i, c) in creatures.iter().enumerate() {
        let p = c.pose.position;
        let h = c.pose.heading.length();
        assert!(
            (h - 1.0).abs() < 1e-9,
            "seed {seed} tick {t}: creature {i} heading length {h}"
        );
        for m in c.metabolism {
            assert!(
                m.is_finite() && m >= 0.0,
                "seed {seed} tick {t}: creature {i} m = {m}"
            );
        }
        if !c.alive {
            continue;
        }
        assert!(
            p.x >= r && p.x <= width - r && p.y >= r && p.y <= height - r,
            "seed {seed} tick {t}: creature {i} at {p} is outside the arena"
        );
        for (k, wall) in walls.iter().enumerate() {
            assert!(
                !circle_touches_segment(p, r, wall),
                "seed {seed} tick {t}: creature {i} at {p} touches wall {k}"
            );
        }
        for (j, other) in creatures.iter().enumerate().skip(i + 1) {
            assert!(
                !other.alive || !circles_touch(p, r, other.pose.position, r),
                "seed {seed} tick {t}: creatures {i} and {j} overlap"
            );
        }
        for (k, actor) in w.actors().iter().enumerate() {
            if actor.role == Role::Wanderer {
                assert!(
                    !circles_touch(p, r, actor.pose.position, r),
                    "seed {seed} tick {t}: creature {i} overlaps wanderer {k}"
                );
            }
        }
    }
    for (k, actor) in w.actors().iter().enumerate() {
        let p = actor.pose.position;
        assert!(
            p.is_finite() && p.x >= r && p.x <= width - r && p.y >= r && p.y <= height - r,
            "seed {seed} tick {t}: actor {k} at {p} is outside the arena"
        );
    }
}

fn check_conservation(w: &World, initial: &[[f64; 4]], seed: u64) {
    for s in 0..4 {
        let taken: f64 = w
            .food()
            .iter()
            .zip(initial)
            .map(|(f, a0)| a0[s] + f.regenerated[s] - f.amount[s])
            .sum();
        let received: f64 = w.creatures().iter().map(|c| c.eaten[s]).sum();
        assert!(
            (taken - received).abs() <= 1e-9 * (1.0 + received.abs()),
            "seed {seed} tick {}: substance {s} taken {taken} but received {received}",
            w.tick()
        );
    }
}

#[test]
fn every_element_on_fast_and_crowded_keeps_the_invariants() {
    let worlds = env("BERRY_LOAD_WORLDS", 8);
    let ticks = env("BERRY_LOAD_TICKS", 3000);
    let walls = static_walls();
    let creatures = 10;
    let (mut deaths, mut shocked, mut eaten) = (0, 0u64, 0.0);
    for seed in 0..worlds {
        let mut w = world(WORLD, creatures, 5000 + seed);
        let initial: Vec<[f64; 4]> = w.food().iter().map(|f| f.amount).collect();
        let mut controllers: Vec<Reckless> = (0..creatures as u64)
            .map(|i| Reckless {
                rng: Rng::seed_from_u64(seed * 100 + i),
            })
            .collect();
        check(&w, &walls, seed);
        for _ in 0..ticks {
            w.step(&mut controllers);
            check(&w, &walls, seed);
            shocked += w.creatures().iter().filter(|c| c.shocked).count() as u64;
            if w.tick() % 50 == 0 {
                check_conservation(&w, &initial, seed);
            }
        }
        check_conservation(&w, &initial, seed);
        deaths += w.creatures().iter().filter(|c| !c.alive).count();
        eaten += w.creatures().iter().map(|c| c.eaten[0]).sum::<f64>();
    }
    // The load is only a test if things happened.
    assert!(shocked > 100, "only {shocked} shocked creature-ticks");
    assert!(deaths > 0, "no creature was ever killed");
    assert!(eaten > 1.0, "only {eaten} A eaten");
}
