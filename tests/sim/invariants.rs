//! Seeded randomized invariants of the whole world (parry style: a fixed seed, many random
//! cases, informative messages): bodies never end a tick in a wall, outside the arena or in
//! each other, headings stay unit length, metabolism stays finite and non-negative, and food
//! substance is conserved.

use crate::sim_common::world;
use berry_evolve::geometry::{circle_touches_segment, circles_touch};
use berry_evolve::seed::{chance, uniform, Rng};
use berry_evolve::sim::controller::{Controller, MotorCommand};
use berry_evolve::sim::World;
use rand::SeedableRng;

/// Random motor signals, sometimes beyond `max_rpt` (to exercise the clamp), sometimes held
/// at full speed ahead for a while (to push into walls and other creatures).
struct Random {
    rng: Rng,
    charge: u32,
}

impl Controller for Random {
    fn act(&mut self, _: &[f64]) -> MotorCommand {
        if self.charge > 0 {
            self.charge -= 1;
            return MotorCommand {
                left: 1.0,
                right: 0.9,
                eat: 1.0,
            };
        }
        if chance(&mut self.rng, 0.02) {
            self.charge = 30;
        }
        MotorCommand {
            left: uniform(&mut self.rng, -0.3, 0.3),
            right: uniform(&mut self.rng, -0.3, 0.3),
            eat: 1.0,
        }
    }
}

const WORLD: &str = r#"
[world]
search_steps = 20

# A corridor, a diagonal, a small box with a gap and a thin spike.
[[world.walls]]
from = [60, 0]
to = [60, 200]

[[world.walls]]
from = [120, 300]
to = [120, 90]

[[world.walls]]
from = [150, 150]
to = [250, 250]

[[world.walls]]
from = [200, 40]
to = [260, 40]

[[world.walls]]
from = [260, 40]
to = [260, 100]

[[world.walls]]
from = [260, 100]
to = [200, 100]

[[world.walls]]
from = [200, 100]
to = [200, 75]

[[world.walls]]
from = [30, 250]
to = [31, 251]

[world.kinds.apple]
class = "food"
radius = 1.5
substance = [1, 0.5, 0, 0]
capacity = [2, 0.5, 0, 0]
bite = [0.3, 0.2, 0, 0]
regen = [0.01, 0.001, 0, 0]

[world.kinds.nettle]
class = "aversive"
radius = 2

[[world.place]]
kind = "apple"
count = 60
min_spacing = 6

[[world.place]]
kind = "nettle"
count = 10

[creature]
decay_per_tick = [0.001, 0, 0, 0]
decay_per_lu = [0.002, 0, 0, 0]
"#;

fn check(w: &World, tick: u64) {
    let r = w.creature_radius();
    let [width, height] = w.arena();
    let creatures = w.creatures();
    for (i, c) in creatures.iter().enumerate() {
        let p = c.pose.position;
        assert!(
            p.x > r && p.x < width - r && p.y > r && p.y < height - r,
            "tick {tick}: creature {i} at {p} is outside the arena"
        );
        for (k, wall) in w.wall_segments().iter().enumerate() {
            assert!(
                !circle_touches_segment(p, r, wall),
                "tick {tick}: creature {i} at {p} touches wall {k} {wall:?}"
            );
        }
        for (j, other) in creatures.iter().enumerate().skip(i + 1) {
            assert!(
                !circles_touch(p, r, other.pose.position, r),
                "tick {tick}: creatures {i} at {p} and {j} at {} overlap",
                other.pose.position
            );
        }
        let h = c.pose.heading.length();
        assert!(
            (h - 1.0).abs() < 1e-12,
            "tick {tick}: creature {i} heading length {h}"
        );
        for m in c.metabolism {
            assert!(
                m.is_finite() && m >= 0.0,
                "tick {tick}: creature {i} m = {m}"
            );
        }
    }
}

/// Substance taken from food (initial + regenerated − left) against substance received by
/// creatures, per type.
fn check_conservation(w: &World, initial: &[[f64; 4]], tick: u64) {
    for t in 0..4 {
        let taken: f64 = w
            .food()
            .iter()
            .zip(initial)
            .map(|(f, a0)| a0[t] + f.regenerated[t] - f.amount[t])
            .sum();
        let given: f64 = w.food().iter().map(|f| f.given[t]).sum();
        let received: f64 = w.creatures().iter().map(|c| c.eaten[t]).sum();
        let tol = 1e-9 * (1.0 + received.abs());
        assert!(
            (taken - received).abs() <= tol && (given - received).abs() <= tol,
            "tick {tick}, substance {t}: taken {taken}, given {given}, received {received}"
        );
    }
}

#[test]
fn ten_thousand_random_ticks_keep_bodies_clear_and_substance_conserved() {
    for seed in [2024, 7, 99] {
        run(seed);
    }
}

fn run(seed: u64) {
    let creatures = 6;
    let mut w = world(WORLD, creatures, seed);
    let initial: Vec<[f64; 4]> = w.food().iter().map(|f| f.amount).collect();
    let mut controllers: Vec<Random> = (0..creatures as u64)
        .map(|i| Random {
            rng: Rng::seed_from_u64(1000 * seed + i),
            charge: 0,
        })
        .collect();
    check(&w, 0);
    let mut blocked = 0;
    for _ in 0..10_000 {
        w.step(&mut controllers);
        check(&w, w.tick());
        blocked += w.creatures().iter().filter(|c| c.blocked).count();
        if w.tick() % 100 == 0 {
            check_conservation(&w, &initial, w.tick());
        }
    }
    check_conservation(&w, &initial, w.tick());
    // The test is only worth something if creatures did run into things and did eat.
    assert!(blocked > 100, "seed {seed}: only {blocked} blocked moves");
    let eaten: f64 = w.creatures().iter().map(|c| c.eaten[0]).sum();
    assert!(eaten > 1.0, "seed {seed}: only {eaten} A eaten");
    for c in w.creatures() {
        assert!(c.command.left.abs() <= 0.25 && c.command.right.abs() <= 0.25);
    }
}
