//! Helpers shared by the simulator's integration tests: worlds from TOML text, exact poses,
//! and trivial controllers.
#![allow(dead_code)]

use berry_evolve::geometry::Vec2;
use berry_evolve::seed::{stream, Generation, IndividualId, Purpose, Rng, Seed, TrialIndex};
use berry_evolve::sim::controller::{Controller, MotorCommand};
use berry_evolve::sim::motion::Pose;
use berry_evolve::sim::{CreatureSpec, World, WorldSpec};
use serde::Deserialize;

/// A `[world]` and a `[creature]` table, as in an experiment file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Setup {
    #[serde(default)]
    pub world: WorldSpec,
    #[serde(default)]
    pub creature: CreatureSpec,
}

pub fn rng(seed: u64) -> Rng {
    stream(
        Seed(seed),
        Purpose::TrialWorld,
        Generation(0),
        IndividualId(0),
        TrialIndex(0),
    )
}

pub fn setup(text: &str) -> Setup {
    toml::from_str(text).unwrap_or_else(|e| panic!("bad test TOML: {e}"))
}

/// A world from TOML text with `creatures` creatures.
pub fn world(text: &str, creatures: usize, seed: u64) -> World {
    let s = setup(text);
    World::new(&s.world, &s.creature, creatures, rng(seed))
        .unwrap_or_else(|e| panic!("cannot build test world: {e}"))
}

/// A unit heading at `degrees` (0 = +x, 90 = +y, down the screen).
pub fn heading(degrees: f64) -> Vec2 {
    let a = degrees.to_radians();
    Vec2::new(libm::cos(a), libm::sin(a))
}

/// Puts creature `i` at (x, y) facing `degrees`.
pub fn put(world: &mut World, i: usize, x: f64, y: f64, degrees: f64) {
    world.set_pose(
        i,
        Pose {
            position: Vec2::new(x, y),
            heading: heading(degrees),
        },
    );
}

/// A controller that never moves (and never asks to eat).
#[derive(Debug, Clone, Copy)]
pub struct Still;

impl Controller for Still {
    fn act(&mut self, _: &[f64]) -> MotorCommand {
        MotorCommand::default()
    }
}

/// A controller with a fixed command.
#[derive(Debug, Clone, Copy)]
pub struct Fixed(pub MotorCommand);

impl Controller for Fixed {
    fn act(&mut self, _: &[f64]) -> MotorCommand {
        self.0
    }
}

pub fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * (1.0 + a.abs().max(b.abs()))
}

#[track_caller]
pub fn assert_close(got: f64, want: f64, what: &str) {
    assert!(close(got, want), "{what}: got {got}, want {want}");
}

/// splitmix64: a test's own seeded generator, so that worlds compared side by side get the
/// same draws without touching the simulator's streams.
pub struct Mix(pub u64);

impl Mix {
    pub fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [a, b).
    pub fn uniform(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * ((self.next() >> 11) as f64 / (1u64 << 53) as f64)
    }

    pub fn chance(&mut self, p: f64) -> bool {
        self.uniform(0.0, 1.0) < p
    }

    pub fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
}

/// Two identical worlds from the `[world]`/`[creature]` text `text`, with `creatures`
/// creatures placed from `seed`'s stream, to run side by side (one of them switched to another
/// code path); `None` when a random world leaves no room for its creatures.
pub fn twin_worlds(text: &str, creatures: usize, seed: u64) -> Option<(World, World)> {
    let setup = setup(text);
    let build = || World::new(&setup.world, &setup.creature, creatures, rng(seed));
    match (build(), build()) {
        (Ok(a), Ok(b)) => Some((a, b)),
        _ => None,
    }
}

/// Steps twin worlds `fast` and `plain` (see [`twin_worlds`]) side by side for `ticks` ticks,
/// creature i of each driven by its own `controller(i)`. Before every tick, `jump(tick,
/// fast)` may give creature i a new pose in both worlds; after it, `check(tick, fast,
/// plain)` compares them (and counts what the test wants counted).
pub fn side_by_side<C: Controller>(
    (fast, plain): (&mut World, &mut World),
    controller: impl Fn(u64) -> C,
    ticks: u64,
    mut jump: impl FnMut(u64, usize, &World) -> Option<Pose>,
    mut check: impl FnMut(u64, &World, &World),
) {
    let n = fast.creatures().len() as u64;
    let mut cf: Vec<C> = (0..n).map(&controller).collect();
    let mut cp: Vec<C> = (0..n).map(&controller).collect();
    for tick in 0..ticks {
        for i in 0..n as usize {
            if let Some(pose) = jump(tick, i, fast) {
                fast.set_pose(i, pose);
                plain.set_pose(i, pose);
            }
        }
        fast.step(&mut cf);
        plain.step(&mut cp);
        check(tick, fast, plain);
    }
}

/// A random wall `[x0, y0, x1, y1]` inside a `w` × `h` arena: long (30–100% of the larger
/// side) with probability `long`, else `short.0`–`short.1` LU; horizontal, vertical or at any
/// angle, clipped to the arena. `None` when clipping left it under 1 LU.
pub fn random_wall(
    r: &mut Mix,
    (w, h): (f64, f64),
    long: f64,
    short: (f64, f64),
) -> Option<[f64; 4]> {
    let (x0, y0) = (r.uniform(0.0, w), r.uniform(0.0, h));
    let len = if r.chance(long) {
        r.uniform(0.3, 1.0) * w.max(h)
    } else {
        r.uniform(short.0, short.1)
    };
    let (dx, dy) = match r.below(3) {
        0 => (len, 0.0),
        1 => (0.0, len),
        _ => {
            let a = r.uniform(0.0, std::f64::consts::TAU);
            (len * libm::cos(a), len * libm::sin(a))
        }
    };
    let (x1, y1) = ((x0 + dx).clamp(0.0, w), (y0 + dy).clamp(0.0, h));
    ((x1 - x0).abs() + (y1 - y0).abs() >= 1.0).then_some([x0, y0, x1, y1])
}
