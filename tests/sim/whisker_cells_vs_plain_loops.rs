//! The per-cell shortlists of the whiskers and food detectors ([`WhiskerCells`]): the pass
//! that reads them (`Surroundings::whiskers_and_food`) must give exactly the answers of the
//! plain loops over every wall and food object (`whisker_touches_all`, `food_detectors_all`),
//! on random worlds, at poses chosen to graze walls, wall ends and food, on cell edges, off
//! the grid, and with whiskers longer than the lists were built for; and each list must hold
//! every wall and food object the module docs say it holds.

use crate::sim_common;
use std::fmt::Write;

use crate::sim_common::Mix;
use berry_evolve::geometry::BoxedSegment;
use berry_evolve::geometry::{segments_intersect, Segment, Vec2};
use berry_evolve::sim::index::whisker_cells::WhiskerCells;
use berry_evolve::sim::index::StaticIndex;
use berry_evolve::sim::sensors::{Body, Surroundings};
use berry_evolve::sim::smell::Smell;
use berry_evolve::sim::wall::Walls;
use berry_evolve::sim::World;

/// A random world: walls of every slope, doors, food of several radii (points included),
/// aversive objects, and a few creatures.
fn random_world(seed: u64) -> String {
    let r = &mut Mix(seed);
    let (w, h) = (r.uniform(40.0, 600.0), r.uniform(40.0, 600.0));
    let mut t = String::new();
    writeln!(t, "[world]\narena = [{w:.3}, {h:.3}]").unwrap();
    writeln!(t, "boundary_walls = {}", r.chance(0.7)).unwrap();
    let most = if r.chance(0.3) { 80 } else { 20 };
    for _ in 0..r.below(most) {
        let Some([x0, y0, x1, y1]) = sim_common::random_wall(r, (w, h), 0.2, (1.0, 40.0)) else {
            continue;
        };
        writeln!(
            t,
            "[[world.walls]]\nfrom = [{x0:.3}, {y0:.3}]\nto = [{x1:.3}, {y1:.3}]\nopaque = {}",
            r.chance(0.5)
        )
        .unwrap();
    }
    for _ in 0..r.below(3) {
        let (x0, y0) = (r.uniform(0.0, w), r.uniform(0.0, h));
        let (x1, y1) = ((x0 + r.uniform(3.0, 30.0)).min(w), y0);
        let (tx, ty) = (r.uniform(0.0, w), r.uniform(0.0, h));
        writeln!(
            t,
            "[[world.doors]]\nfrom = [{x0:.3}, {y0:.3}]\nto = [{x1:.3}, {y1:.3}]\n\
             trigger = [{tx:.3}, {ty:.3}]\ntrigger_radius = 5"
        )
        .unwrap();
    }
    let food_kinds = 1 + r.below(4);
    for k in 0..food_kinds {
        let radius = if r.chance(0.25) {
            0.0
        } else {
            r.uniform(0.3, 8.0)
        };
        let substance: Vec<String> = (0..4)
            .map(|_| {
                if r.chance(0.5) {
                    format!("{:.3}", r.uniform(0.1, 5.0))
                } else {
                    "0".into()
                }
            })
            .collect();
        writeln!(
            t,
            "[world.kinds.food{k}]\nclass = \"food\"\nradius = {radius:.3}\nsubstance = [{}]\n\
             bite = [0.5, 0.5, 0.5, 0.5]",
            substance.join(", ")
        )
        .unwrap();
        writeln!(
            t,
            "[[world.place]]\nkind = \"food{k}\"\ncount = {}",
            r.below(80)
        )
        .unwrap();
    }
    if r.chance(0.5) {
        writeln!(
            t,
            "[world.kinds.nettle]\nclass = \"aversive\"\nradius = {:.3}\n\
             [[world.place]]\nkind = \"nettle\"\ncount = {}",
            r.uniform(0.0, 5.0),
            r.below(20)
        )
        .unwrap();
    }
    writeln!(
        t,
        "[creature]\nwhisker_length = {:.3}\n[world.start]\nregion = [0, 0, {w:.3}, {h:.3}]",
        r.uniform(0.0, 25.0)
    )
    .unwrap();
    t
}

/// What the senses of a creature in `w` see, with `walls` and `index` built from it.
fn surroundings<'a>(w: &'a World, walls: &'a Walls, index: &'a StaticIndex) -> Surroundings<'a> {
    Surroundings {
        walls: walls.felt(),
        opaque: walls.opaque(),
        food: w.food(),
        aversives: w.aversives(),
        areas: w.areas(),
        creatures: w.creatures(),
        things: w.things(),
        skip_thing: usize::MAX,
        smell_c: 0.01,
        index,
    }
}

/// The whiskers' and food detectors' answers of the plain loops over every wall and object.
fn plain_loops(
    s: &Surroundings,
    me: usize,
    body: &Body,
    p: Vec2,
    tips: [Vec2; 2],
) -> ([bool; 2], [bool; 4]) {
    (
        [
            s.whisker_touches_all(me, body, p, tips[0]),
            s.whisker_touches_all(me, body, p, tips[1]),
        ],
        s.food_detectors_all(p, body.radius),
    )
}

/// A point near something worth grazing: a wall's end or a point on it, a food object's rim,
/// a cell's edge, or anywhere (beyond the arena too).
fn near_point(r: &mut Mix, w: &World, felt: &[BoxedSegment], cell: f64) -> Vec2 {
    let [aw, ah] = w.arena();
    let jitter = |r: &mut Mix, s: f64| Vec2::new(r.uniform(-s, s), r.uniform(-s, s));
    match r.below(6) {
        0 if !felt.is_empty() => {
            let s = felt[r.below(felt.len() as u64) as usize].segment;
            let t = r.uniform(0.0, 1.0);
            s.a + (s.b - s.a) * t + jitter(r, 8.0)
        }
        1 if !felt.is_empty() => {
            let s = felt[r.below(felt.len() as u64) as usize].segment;
            (if r.chance(0.5) { s.a } else { s.b }) + jitter(r, 6.0)
        }
        2 if !w.food().is_empty() => {
            let f = &w.food()[r.below(w.food().len() as u64) as usize];
            f.position + jitter(r, f.radius + 6.0)
        }
        3 => {
            // On a cell's edge or corner, exactly.
            let x = (r.below(40) as f64) * cell;
            let y = (r.below(40) as f64) * cell;
            match r.below(3) {
                0 => Vec2::new(x, y),
                1 => Vec2::new(x, r.uniform(0.0, ah)),
                _ => Vec2::new(r.uniform(0.0, aw), y),
            }
        }
        4 => Vec2::new(
            r.uniform(-0.2 * aw, 1.2 * aw),
            r.uniform(-0.2 * ah, 1.2 * ah),
        ),
        _ => Vec2::new(r.uniform(0.0, aw), r.uniform(0.0, ah)),
    }
}

/// The whisker tips a pose gives, or (rarely) tips pointing at a wall's end exactly, tips of
/// a heading that is not a unit vector (whiskers longer or shorter than the lists assume), or
/// tips on top of the centre.
fn tips(r: &mut Mix, body: &Body, p: Vec2, felt: &[BoxedSegment]) -> [Vec2; 2] {
    let a = r.uniform(0.0, std::f64::consts::TAU);
    let heading = Vec2::new(libm::cos(a), libm::sin(a));
    match r.below(10) {
        0 if !felt.is_empty() => {
            let s = felt[r.below(felt.len() as u64) as usize].segment;
            [s.a, body.whisker_tips(p, heading)[1]]
        }
        1 => body.whisker_tips(p, heading * r.uniform(0.5, 3.0)),
        2 => [p, p],
        _ => body.whisker_tips(p, heading),
    }
}

#[test]
fn shortlists_give_the_plain_loops_answers_on_random_worlds() {
    let (mut listed, mut fallback, mut touching, mut detecting) = (0, 0, 0, 0);
    for seed in 0..60u64 {
        let text = random_world(seed);
        let setup = sim_common::setup(&text);
        let Ok(w) = World::new(&setup.world, &setup.creature, 3, sim_common::rng(seed)) else {
            continue;
        };
        let walls = Walls::build(&setup.world);
        let r = &mut Mix(seed ^ 0x5EED);
        // The body's radius and whisker length vary around the world's own.
        let radius = if r.chance(0.2) {
            0.0
        } else {
            r.uniform(0.1, 8.0)
        };
        let whisker_length = setup.creature.whisker_length;
        let phi = r.uniform(0.0, std::f64::consts::PI);
        let body = Body {
            radius,
            whisker_length,
            whisker_cos: libm::cos(phi),
            whisker_sin: libm::sin(phi),
            smell: Smell::new(&[0.0; 8], 0.0, None),
        };
        let reach = whisker_length.max(radius);
        let index = StaticIndex::build(w.arena(), reach, w.food(), w.aversives(), &walls);
        let cells = index
            .whisker_cells()
            .expect("a finite world has whisker cells");
        let (_, cell) = cells.dimensions();
        let surroundings = surroundings(&w, &walls, &index);
        for _ in 0..3000 {
            let p = near_point(r, &w, walls.felt(), cell);
            let tips = tips(r, &body, p, walls.felt());
            let me = r.below(4) as usize; // 3: no creature is the sensing one
            let got = surroundings.whiskers_and_food(me, &body, p, tips);
            let want = plain_loops(&surroundings, me, &body, p, tips);
            assert_eq!(got, want, "seed {seed}: at {p:?} tips {tips:?}");
            let (lo, hi) = (p.min(tips[0]).min(tips[1]), p.max(tips[0]).max(tips[1]));
            if cells.lists(p, lo, hi, body.radius).is_some() {
                listed += 1;
            } else {
                fallback += 1;
            }
            touching += usize::from(want.0[0] || want.0[1]);
            detecting += usize::from(want.1.iter().any(|&d| d));
        }
    }
    // The draws must exercise both paths and both kinds of answer.
    assert!(listed > 50_000, "{listed} queries used the lists");
    assert!(
        fallback > 5_000,
        "{fallback} queries fell back to the index"
    );
    assert!(touching > 10_000, "{touching} queries touched");
    assert!(detecting > 2_000, "{detecting} queries detected food");
}

#[test]
fn each_list_holds_every_wall_and_food_object_in_reach() {
    for seed in 0..40u64 {
        let text = random_world(seed);
        let setup = sim_common::setup(&text);
        let Ok(w) = World::new(&setup.world, &setup.creature, 1, sim_common::rng(seed)) else {
            continue;
        };
        let walls = Walls::build(&setup.world);
        let fixed = &walls.felt()[..walls.fixed_count()];
        let r = &mut Mix(seed ^ 0xCE11);
        let reach = r.uniform(0.0, 20.0);
        let cells = WhiskerCells::build(w.arena(), reach, fixed, w.food()).unwrap();
        let (_, cell) = cells.dimensions();
        for _ in 0..2000 {
            let p = near_point(r, &w, fixed, cell);
            // Any whisker boxes within `reach` of p, and any body radius up to `reach`.
            let (lo, hi) = (
                p - Vec2::new(r.uniform(0.0, reach), r.uniform(0.0, reach)),
                p + Vec2::new(r.uniform(0.0, reach), r.uniform(0.0, reach)),
            );
            let radius = r.uniform(0.0, reach);
            // Off the grid: the index answers.
            let Some((wall_list, food_list)) = cells.lists(p, lo, hi, radius) else {
                continue;
            };
            assert!(wall_list.windows(2).all(|k| k[0] < k[1]), "wall order");
            assert!(food_list.windows(2).all(|k| k[0] < k[1]), "food order");
            for (k, wall) in fixed.iter().enumerate() {
                if wall.may_meet(lo, hi) {
                    assert!(
                        wall_list.contains(&(k as u32)),
                        "seed {seed}: wall {k} at {p:?}"
                    );
                }
            }
            for (k, f) in w.food().iter().enumerate() {
                let g = reach + f.radius;
                let near = (f.position - p).abs().max_element() <= g;
                if near {
                    assert!(
                        food_list.contains(&(k as u32)),
                        "seed {seed}: food {k} at {p:?}"
                    );
                }
            }
        }
    }
}

#[test]
fn grazing_a_wall_end_with_the_tip_counts_through_the_lists() {
    // A wall whose end lies exactly on the whisker tip, and one whose end is a hair beyond
    // it: touching counts (§7.3), missing by a hair does not, from any cell.
    for k in 0..64 {
        let x = 50.0 + k as f64 * 3.7;
        let text = format!(
            "[world]\narena = [300, 300]\n[[world.walls]]\nfrom = [{x}, 100]\nto = [{x}, 140]\n\
             [[world.walls]]\nfrom = [{x}, 200.000001]\nto = [{x}, 240]\n\
             [world.start]\nregion = [10, 10, 10, 10]"
        );
        let setup = sim_common::setup(&text);
        let w = World::new(&setup.world, &setup.creature, 1, sim_common::rng(1)).unwrap();
        let walls = Walls::build(&setup.world);
        let body = Body {
            radius: 2.5,
            whisker_length: 5.0,
            whisker_cos: 1.0,
            whisker_sin: 0.0,
            smell: Smell::new(&[0.0; 8], 0.0, None),
        };
        let index = StaticIndex::build(w.arena(), 5.0, w.food(), w.aversives(), &walls);
        assert!(index.whisker_cells().is_some());
        let s = Surroundings {
            walls: walls.felt(),
            opaque: walls.opaque(),
            food: w.food(),
            aversives: w.aversives(),
            areas: w.areas(),
            creatures: &[],
            things: &[],
            skip_thing: usize::MAX,
            smell_c: 0.01,
            index: &index,
        };
        let down = Vec2::new(0.0, 1.0);
        let touch = |p: Vec2| s.whiskers_and_food(0, &body, p, [p + down * 5.0, p]).0[0];
        assert!(touch(Vec2::new(x, 95.0)), "x = {x}: tip on the wall's end");
        assert!(
            !touch(Vec2::new(x, 195.0)),
            "x = {x}: tip short of the wall's end"
        );
        let plain = |p: Vec2| {
            let seg = Segment::new(p, p + down * 5.0);
            s.walls.iter().any(|w| segments_intersect(&seg, &w.segment))
        };
        assert!(plain(Vec2::new(x, 95.0)) && !plain(Vec2::new(x, 195.0)));
    }
}

#[test]
fn worlds_that_are_not_finite_get_no_lists() {
    let wall =
        |a: [f64; 2], b: [f64; 2]| BoxedSegment::new(Segment::new(Vec2::from(a), Vec2::from(b)));
    let good = [wall([0.0, 0.0], [10.0, 0.0])];
    assert!(WhiskerCells::build([100.0, 100.0], 5.0, &good, &[]).is_some());
    assert!(WhiskerCells::build([f64::INFINITY, 100.0], 5.0, &good, &[]).is_none());
    assert!(WhiskerCells::build([100.0, 0.0], 5.0, &good, &[]).is_none());
    assert!(WhiskerCells::build([100.0, 100.0], f64::NAN, &good, &[]).is_none());
    assert!(WhiskerCells::build([100.0, 100.0], -1.0, &good, &[]).is_none());
    let bad = [wall([0.0, 0.0], [f64::INFINITY, 0.0])];
    assert!(WhiskerCells::build([100.0, 100.0], 5.0, &bad, &[]).is_none());
    // A query off the grid, with a NaN centre, whiskers longer than the reach, or a body
    // wider than it gets no lists either.
    let cells = WhiskerCells::build([100.0, 100.0], 5.0, &good, &[]).unwrap();
    let p = Vec2::new(50.0, 50.0);
    assert!(cells.lists(p, p - 5.0, p + 5.0, 5.0).is_some());
    assert!(cells.lists(p, p - 5.0, p + 5.1, 5.0).is_none());
    assert!(cells.lists(p, p - 5.0, p + 5.0, 5.1).is_none());
    assert!(cells.lists(p, p - 5.0, p + 5.0, -0.1).is_none());
    let off = Vec2::new(-0.5, 50.0);
    assert!(cells.lists(off, off, off, 1.0).is_none());
    let nan = Vec2::new(f64::NAN, 50.0);
    assert!(cells.lists(nan, nan, nan, 1.0).is_none());
}

/// Whiskers whose tips (or centre) are not finite: the box of both whiskers, which rejects
/// far food before the exact test only when everything is finite, and the lists' guard must
/// still give the plain loops' answers. The left tip gets NaN or an infinity (a NaN there
/// drops out of the box of both, so the lists serve the query), the right one huge finite
/// values. (A NaN in the right tip makes the box of both NaN, and the grid's query over it
/// then hands out no wall, as it always has: not asked here.)
#[test]
fn tips_that_are_not_finite_give_the_plain_loops_answers() {
    let odd = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, 1e300, -1e300];
    let mut asked = 0;
    for seed in 0..30u64 {
        let text = random_world(seed);
        let setup = sim_common::setup(&text);
        let Ok(w) = World::new(&setup.world, &setup.creature, 3, sim_common::rng(seed)) else {
            continue;
        };
        let walls = Walls::build(&setup.world);
        let r = &mut Mix(seed ^ 0xBAD);
        let body = Body {
            radius: r.uniform(0.1, 8.0),
            whisker_length: setup.creature.whisker_length,
            whisker_cos: 0.8,
            whisker_sin: 0.6,
            smell: Smell::new(&[0.0; 8], 0.0, None),
        };
        let reach = body.whisker_length.max(body.radius);
        let index = StaticIndex::build(w.arena(), reach, w.food(), w.aversives(), &walls);
        let (_, cell) = index.whisker_cells().expect("lists").dimensions();
        let surroundings = surroundings(&w, &walls, &index);
        for _ in 0..2000 {
            let mut p = near_point(r, &w, walls.felt(), cell);
            let heading = sim_common::heading(r.uniform(0.0, 360.0));
            let mut tips = body.whisker_tips(p, heading);
            // Spoil one to three coordinates of the tips, and sometimes the centre.
            for _ in 0..1 + r.below(3) {
                let side = r.below(2) as usize;
                let v = if side == 0 {
                    odd[r.below(odd.len() as u64) as usize]
                } else {
                    odd[3 + r.below(2) as usize]
                };
                let t = &mut tips[side];
                if r.chance(0.5) {
                    t.x = v;
                } else {
                    t.y = v;
                }
            }
            if r.chance(0.1) {
                p.x = odd[r.below(odd.len() as u64) as usize];
            }
            let me = r.below(4) as usize;
            let got = surroundings.whiskers_and_food(me, &body, p, tips);
            let want = plain_loops(&surroundings, me, &body, p, tips);
            assert_eq!(got, want, "seed {seed}: at {p:?} tips {tips:?}");
            asked += 1;
        }
    }
    assert!(asked > 20_000, "{asked} queries");
}

/// The cell lookup (a floor, read from the bits of the floor plus 2⁵²) on cell edges, just
/// below them, at the origin and near the far sides: each list still holds every wall in
/// reach.
#[test]
fn queries_on_cell_edges_and_far_sides_get_every_wall_in_reach() {
    let wall = |a: Vec2, b: Vec2| BoxedSegment::new(Segment::new(a, b));
    // Short walls every 2.5 LU, each cell side (5 LU, the reach) holding two.
    let mut walls = Vec::new();
    for i in 0..=40 {
        for j in 0..=40 {
            let a = Vec2::new(i as f64 * 2.5, j as f64 * 2.5);
            walls.push(wall(a, a + Vec2::new(0.1, 0.05)));
        }
    }
    let cells = WhiskerCells::build([100.0, 100.0], 5.0, &walls, &[]).unwrap();
    let ([nx, ny], cell) = cells.dimensions();
    assert_eq!(([nx, ny], cell), ([20, 20], 5.0));
    let below = |v: f64| f64::from_bits(v.to_bits() - 1);
    let mut coordinates: Vec<f64> = (0..20).map(|k| k as f64 * cell).collect();
    coordinates.extend([99.9, below(95.0), below(5.0), 1e-300, 2.5]);
    for &x in &coordinates {
        for &y in &coordinates {
            let p = Vec2::new(x, y);
            // Whiskers a little shorter than the reach, whatever the rounding of p ± 4.5.
            let (lo, hi) = (p - 4.5, p + 4.5);
            let (wall_list, food_list) = cells
                .lists(p, lo, hi, 4.5)
                .unwrap_or_else(|| panic!("{p:?} on the grid"));
            assert!(food_list.is_empty());
            for (k, w) in walls.iter().enumerate() {
                if w.may_meet(lo, hi) {
                    assert!(wall_list.contains(&(k as u32)), "wall {k} at {p:?}");
                }
            }
        }
    }
    // On the far sides themselves the query is off the grid.
    let p = Vec2::new(100.0, 50.0);
    assert!(cells.lists(p, p - 5.0, p + 5.0, 5.0).is_none());
}
