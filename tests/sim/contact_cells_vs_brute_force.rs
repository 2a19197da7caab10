//! The per-cell food and aversive lists of the contacts phase (`MoverCells::with_contacts` in
//! `sim::world`) change no result: worlds with walls, many food and aversive objects of mixed
//! radii (0 included) and creatures of mixed sizes run side by side with the plain loops over
//! every object (`World::set_brute_force`) and must agree to the bit after every tick, food
//! included. Creatures are dropped right at objects' edges (where a contact is decided by the
//! last bit), anywhere, and outside the arena and the cells.

use crate::sim_common;

use crate::sim_common::Mix;
use berry_evolve::geometry::Vec2;
use berry_evolve::sim::controller::{Controller, MotorCommand};
use berry_evolve::sim::motion::Pose;
use berry_evolve::sim::World;
use std::fmt::Write;

/// Random signals, often at full speed, eating half the time.
struct Forager(Mix);

impl Controller for Forager {
    fn act(&mut self, _: &[f64]) -> MotorCommand {
        let r = &mut self.0;
        let mut signal = || match r.below(4) {
            0 => 1.0,
            1 => -1.0,
            _ => r.uniform(-1.2, 1.2),
        };
        let (left, right) = (signal(), signal());
        MotorCommand {
            left,
            right,
            eat: r.uniform(0.0, 1.0),
        }
    }
}

fn random_world(seed: u64) -> String {
    let r = &mut Mix(seed);
    let (w, h) = (r.uniform(60.0, 700.0), r.uniform(60.0, 700.0));
    let mut t = String::new();
    writeln!(t, "[world]\narena = [{w:.3}, {h:.3}]").unwrap();
    writeln!(t, "boundary_walls = {}", r.chance(0.8)).unwrap();
    for _ in 0..r.below(12) {
        if let Some([x0, y0, x1, y1]) = sim_common::random_wall(r, (w, h), 0.1, (2.0, 40.0)) {
            writeln!(
                t,
                "[[world.walls]]\nfrom = [{x0:.3}, {y0:.3}]\nto = [{x1:.3}, {y1:.3}]"
            )
            .unwrap();
        }
    }
    let radius = |r: &mut Mix| match r.below(4) {
        0 => 0.0,
        1 => r.uniform(0.1, 1.0),
        2 => r.uniform(1.0, 6.0),
        _ => r.uniform(6.0, 40.0),
    };
    for k in 0..1 + r.below(3) {
        writeln!(
            t,
            "[world.kinds.food_{k}]\nclass = \"food\"\nradius = {:.4}\nsubstance = [{:.3}, 1.0, 0.0, 0.5]\nbite = [0.3, 0.2, 0.0, 0.1]\nregen = [0.01, 0.0, 0.0, 0.02]\n[[world.place]]\nkind = \"food_{k}\"\ncount = {}",
            radius(r),
            r.uniform(0.5, 5.0),
            1 + r.below(30)
        )
        .unwrap();
    }
    if r.chance(0.7) {
        writeln!(
            t,
            "[world.kinds.nettle]\nclass = \"aversive\"\nradius = {:.4}\n[[world.place]]\nkind = \"nettle\"\ncount = {}",
            radius(r),
            1 + r.below(12)
        )
        .unwrap();
    }
    writeln!(
        t,
        "[creature]\neating = \"{}\"\ndiameter = {:.4}",
        if r.chance(0.5) { "contact" } else { "action" },
        r.uniform(0.5, 14.0)
    )
    .unwrap();
    t
}

fn state(w: &World) -> String {
    format!("{:?}\n{:?}\n", w.creatures(), w.food())
}

#[test]
fn contact_cells_and_brute_force_agree_to_the_bit() {
    let mut checked = 0;
    let mut contacts = 0;
    for seed in 0..50u64 {
        let text = random_world(seed);
        let creatures = 1 + (seed % 4) as usize;
        let Some((mut cells, mut brute)) = sim_common::twin_worlds(&text, creatures, seed) else {
            continue;
        };
        checked += 1;
        brute.set_brute_force(true);
        let mut jumps = Mix(seed ^ 0xc0ffee);
        let [w, h] = cells.arena();
        let reach = cells.creature_radius();
        let jump = |tick: u64, _: usize, cells: &World| {
            if tick % 10 != 9 {
                return None;
            }
            let objects: Vec<(Vec2, f64)> = cells
                .food()
                .iter()
                .map(|f| (f.position, f.radius))
                .chain(cells.aversives().iter().map(|a| (a.position, a.radius)))
                .collect();
            let position = match jumps.below(4) {
                0 => Vec2::new(
                    jumps.uniform(-2.0 * w, 3.0 * w),
                    jumps.uniform(-2.0 * h, 3.0 * h),
                ),
                1 => Vec2::new(jumps.uniform(0.0, w), jumps.uniform(0.0, h)),
                _ => {
                    // On an object's edge, a hair inside or outside.
                    let (c, r) = objects[jumps.below(objects.len() as u64) as usize];
                    let d = (reach + r) * (1.0 + jumps.uniform(-1e-15, 1e-15));
                    c + sim_common::heading(jumps.uniform(0.0, 360.0)) * d
                }
            };
            Some(Pose {
                position,
                heading: sim_common::heading(jumps.uniform(0.0, 360.0)),
            })
        };
        let check = |tick: u64, cells: &World, brute: &World| {
            contacts += cells
                .creatures()
                .iter()
                .filter(|c| c.shocked || c.food_detectors.contains(&true))
                .count();
            let (a, b) = (state(cells), state(brute));
            assert!(
                a == b,
                "seed {seed}, tick {tick}: the cells and the plain loops differ\n{text}"
            );
        };
        let forager = |i: u64| Forager(Mix(seed * 100 + i));
        sim_common::side_by_side((&mut cells, &mut brute), forager, 200, jump, check);
    }
    assert!(checked > 30, "{checked}");
    assert!(contacts > 1000, "{contacts}");
}
