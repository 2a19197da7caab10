//! The per-cell wall lists of the creatures' moves (`MoverCells` in `sim::world`) change no
//! result: worlds of few walls and no doors (where every move takes its walls from a cell's
//! list) run side by side with the plain loops over every wall (`World::set_brute_force`) and
//! must agree to the bit after every tick. The controllers often drive at full ±max_rpt (the
//! largest move the lists cover), creatures are dropped anywhere (outside the arena and the
//! grid too) and against walls, where they push tick after tick.

use crate::sim_common;

use crate::sim_common::Mix;
use berry_evolve::geometry::Vec2;
use berry_evolve::sim::controller::{Controller, MotorCommand};
use berry_evolve::sim::motion::Pose;
use berry_evolve::sim::World;
use std::fmt::Write;

/// Full speed forwards or backwards most of the time, else random signals, some beyond
/// ±max_rpt (clamped by the world).
struct Pusher(Mix);

impl Controller for Pusher {
    fn act(&mut self, _: &[f64]) -> MotorCommand {
        let r = &mut self.0;
        let mut signal = || match r.below(6) {
            0 => 5.0,
            1 => -5.0,
            2 => r.uniform(-2.0, 2.0),
            _ => 1.0,
        };
        let (left, right) = (signal(), signal());
        MotorCommand {
            left,
            right,
            eat: 0.0,
        }
    }
}

/// Few walls (at most 64 fixed ones with the boundary), some long or diagonal, no doors.
fn random_world(seed: u64) -> String {
    let r = &mut Mix(seed);
    let (w, h) = (r.uniform(40.0, 900.0), r.uniform(40.0, 900.0));
    let mut t = String::new();
    writeln!(t, "[world]\narena = [{w:.3}, {h:.3}]").unwrap();
    writeln!(t, "slippery_walls = {}", r.chance(0.3)).unwrap();
    writeln!(t, "boundary_walls = {}", r.chance(0.8)).unwrap();
    let walls = 1 + r.below(56);
    for _ in 0..walls {
        let Some([x0, y0, x1, y1]) = sim_common::random_wall(r, (w, h), 0.15, (2.0, 50.0)) else {
            continue;
        };
        writeln!(
            t,
            "[[world.walls]]\nfrom = [{x0:.3}, {y0:.3}]\nto = [{x1:.3}, {y1:.3}]"
        )
        .unwrap();
    }
    if r.chance(0.4) {
        writeln!(t, "[world.wanderers]\ncount = {}", 1 + r.below(3)).unwrap();
    }
    if r.chance(0.4) {
        writeln!(
            t,
            "[[world.predators]]\nstrategy = \"wander\"\neffect = \"shock\""
        )
        .unwrap();
    }
    writeln!(
        t,
        "[creature]\neating = \"contact\"\nmax_rpt = {:.3}",
        if r.chance(0.3) {
            r.uniform(0.05, 3.0)
        } else {
            1.0
        }
    )
    .unwrap();
    t
}

fn state(w: &World) -> String {
    let mut s = format!("{:?}\n", w.creatures());
    writeln!(s, "{:?}\n{:?}", w.actors(), w.things()).unwrap();
    s
}

#[test]
fn mover_cells_and_brute_force_agree_to_the_bit() {
    let mut checked = 0;
    for seed in 0..60u64 {
        let text = random_world(seed);
        let creatures = 8;
        let Some((mut cells, mut brute)) = sim_common::twin_worlds(&text, creatures, seed) else {
            continue;
        };
        checked += 1;
        brute.set_brute_force(true);
        let mut jumps = Mix(seed ^ 0x5eed);
        let [w, h] = cells.arena();
        let jump = |tick: u64, _: usize, _: &World| {
            if tick % 40 != 39 {
                return None;
            }
            let position = if jumps.chance(0.3) {
                // Far outside, beyond the cells.
                Vec2::new(
                    jumps.uniform(-2.0 * w, 3.0 * w),
                    jumps.uniform(-2.0 * h, 3.0 * h),
                )
            } else {
                Vec2::new(
                    jumps.uniform(-0.1 * w, 1.1 * w),
                    jumps.uniform(-0.1 * h, 1.1 * h),
                )
            };
            Some(Pose {
                position,
                heading: sim_common::heading(jumps.uniform(0.0, 360.0)),
            })
        };
        let check = |tick: u64, cells: &World, brute: &World| {
            let (a, b) = (state(cells), state(brute));
            assert!(
                a == b,
                "seed {seed}, tick {tick}: the cells and the plain loops differ\n{text}"
            );
        };
        let pusher = |i: u64| Pusher(Mix(seed * 100 + i));
        sim_common::side_by_side((&mut cells, &mut brute), pusher, 250, jump, check);
    }
    assert!(checked > 30, "{checked}");
}
