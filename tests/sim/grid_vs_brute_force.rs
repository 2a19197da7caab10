//! The spatial grid changes no result: seeded random worlds with many walls, doors, food and
//! aversive objects of mixed smell ranges (finite and unlimited), areas, teleporters,
//! wanderers, predators and many creatures run side by side with the grid and with the plain
//! loops over every object (`World::set_brute_force`), and must agree to the bit after every
//! tick: whiskers, smell, food detectors, eating, shocks, motion, regeneration, doors. Worlds
//! whose only smells are food and aversive objects of finite range check the tick loop's
//! common smell path the same way.

use crate::sim_common;

use crate::sim_common::Mix;
use berry_evolve::geometry::Vec2;
use berry_evolve::sim::controller::{Controller, MotorCommand};
use berry_evolve::sim::motion::Pose;
use berry_evolve::sim::World;
use std::fmt::Write;

/// A controller driven by its own seeded generator: random motors, sometimes eating.
struct Random(Mix);

impl Controller for Random {
    fn act(&mut self, _: &[f64]) -> MotorCommand {
        let r = &mut self.0;
        MotorCommand {
            left: r.uniform(-0.6, 0.6),
            right: r.uniform(-0.6, 0.6),
            eat: r.uniform(0.0, 1.0),
        }
    }
}

fn odour(r: &mut Mix) -> String {
    let v: Vec<String> = (0..8)
        .map(|_| {
            if r.chance(0.4) {
                format!("{:.3}", r.uniform(0.0, 1.0))
            } else {
                "0".into()
            }
        })
        .collect();
    format!("[{}]", v.join(", "))
}

fn range(r: &mut Mix, max: f64) -> String {
    if r.chance(0.25) {
        String::new()
    } else {
        format!("range = {:.3}\n", r.uniform(1.0, max))
    }
}

/// A random world: arena, walls (axis-aligned, diagonal, long, transparent), doors with
/// triggers, kinds of food and aversive objects, explicit objects anywhere (on walls too),
/// placed objects, areas, gadgets and a creature spec.
fn random_world(seed: u64) -> String {
    let r = &mut Mix(seed);
    let (w, h) = (r.uniform(150.0, 1200.0), r.uniform(150.0, 1200.0));
    let mut t = String::new();
    writeln!(t, "[world]\narena = [{w:.3}, {h:.3}]").unwrap();
    writeln!(t, "smell_c = {:.4}", r.uniform(0.0005, 0.05)).unwrap();
    writeln!(t, "wall_shock = {}", r.chance(0.5)).unwrap();
    writeln!(t, "slippery_walls = {}", r.chance(0.5)).unwrap();
    writeln!(t, "boundary_walls = {}", r.chance(0.8)).unwrap();
    let point = |r: &mut Mix| (r.uniform(0.0, w), r.uniform(0.0, h));
    let many = r.chance(0.5);
    let walls = 10 + r.below(if many { 80 } else { 20 });
    for _ in 0..walls {
        let Some([x0, y0, x1, y1]) = sim_common::random_wall(r, (w, h), 0.1, (3.0, 60.0)) else {
            continue;
        };
        writeln!(
            t,
            "[[world.walls]]\nfrom = [{x0:.3}, {y0:.3}]\nto = [{x1:.3}, {y1:.3}]\nopaque = {}",
            r.chance(0.8)
        )
        .unwrap();
    }
    for _ in 0..r.below(4) {
        let (x0, y0) = point(r);
        let (x1, y1) = (
            (x0 + r.uniform(5.0, 40.0)).min(w),
            (y0 + r.uniform(-20.0, 20.0)).clamp(0.0, h),
        );
        let (tx, ty) = point(r);
        writeln!(
            t,
            "[[world.doors]]\nfrom = [{x0:.3}, {y0:.3}]\nto = [{x1:.3}, {y1:.3}]\nopaque = {}\n\
             trigger = [{tx:.3}, {ty:.3}]\ntrigger_radius = {:.3}\nopen_ticks = {}",
            r.chance(0.7),
            r.uniform(5.0, 40.0),
            r.below(40)
        )
        .unwrap();
    }
    let max_range = r.uniform(10.0, 200.0);
    let food_kinds = 1 + r.below(4);
    for k in 0..food_kinds {
        let radius = if r.chance(0.2) {
            0.0
        } else {
            r.uniform(0.5, 6.0)
        };
        let substance: Vec<String> = (0..4)
            .map(|_| format!("{:.3}", r.uniform(0.0, 5.0)))
            .collect();
        let bite: Vec<String> = (0..4)
            .map(|_| format!("{:.3}", r.uniform(0.0, 1.5)))
            .collect();
        let regen: Vec<String> = (0..4)
            .map(|_| {
                if r.chance(0.5) {
                    format!("{:.4}", r.uniform(0.0, 0.2))
                } else {
                    "0".into()
                }
            })
            .collect();
        writeln!(
            t,
            "[world.kinds.food{k}]\nclass = \"food\"\nradius = {radius:.3}\nsubstance = [{}]\n\
             bite = [{}]\nregen = [{}]\ndepletes = {}\nsmell_follows_amount = {}\n\
             odour = {}\nintensity = {:.3}\n{}",
            substance.join(", "),
            bite.join(", "),
            regen.join(", "),
            r.chance(0.8),
            r.chance(0.4),
            odour(r),
            r.uniform(0.1, 2.0),
            range(r, max_range)
        )
        .unwrap();
    }
    let aversive_kinds = r.below(3);
    for k in 0..aversive_kinds {
        let radius = if r.chance(0.2) {
            0.0
        } else {
            r.uniform(0.5, 6.0)
        };
        writeln!(
            t,
            "[world.kinds.nettle{k}]\nclass = \"aversive\"\nradius = {radius:.3}\n\
             odour = {}\nintensity = {:.3}\n{}",
            odour(r),
            r.uniform(0.1, 2.0),
            range(r, max_range)
        )
        .unwrap();
    }
    let mut kinds: Vec<String> = (0..food_kinds).map(|k| format!("food{k}")).collect();
    kinds.extend((0..aversive_kinds).map(|k| format!("nettle{k}")));
    for _ in 0..r.below(60) {
        let (x, y) = point(r);
        let kind = &kinds[r.below(kinds.len() as u64) as usize];
        writeln!(
            t,
            "[[world.objects]]\nkind = \"{kind}\"\nposition = [{x:.3}, {y:.3}]"
        )
        .unwrap();
    }
    for kind in &kinds {
        writeln!(
            t,
            "[[world.place]]\nkind = \"{kind}\"\ncount = {}",
            r.below(150)
        )
        .unwrap();
    }
    for _ in 0..r.below(3) {
        let (x0, y0) = point(r);
        let (x1, y1) = ((x0 + 30.0).min(w), (y0 + 30.0).min(h));
        writeln!(
            t,
            "[[world.areas]]\nregion = [{x0:.3}, {y0:.3}, {x1:.3}, {y1:.3}]\nkind = \"{}\"\n\
             odour = {}\nintensity = 0.5\n{}",
            if r.chance(0.5) { "safe" } else { "plain" },
            odour(r),
            range(r, max_range)
        )
        .unwrap();
    }
    if r.chance(0.5) {
        let (x0, y0) = point(r);
        let (x1, y1) = point(r);
        writeln!(
            t,
            "[[world.teleporters]]\nentry = [{x0:.3}, {y0:.3}]\nradius = 6\nexit = [{x1:.3}, {y1:.3}]\n\
             odour = {}\nintensity = 1\n{}",
            odour(r),
            range(r, max_range)
        )
        .unwrap();
    }
    if r.chance(0.5) {
        writeln!(
            t,
            "[world.wanderers]\ncount = {}\nodour = {}\nintensity = 1\n{}",
            1 + r.below(4),
            odour(r),
            range(r, max_range)
        )
        .unwrap();
    }
    if r.chance(0.4) {
        writeln!(
            t,
            "[[world.predators]]\nstrategy = \"wander\"\neffect = \"shock\"\nodour = {}\n\
             intensity = 1\n{}",
            odour(r),
            range(r, max_range)
        )
        .unwrap();
    }
    if r.chance(0.3) {
        writeln!(
            t,
            "[[world.air_predators]]\neffect = \"shock\"\nstrike_radius = 10"
        )
        .unwrap();
    }
    writeln!(
        t,
        "[creature]\nodour = {}\nodour_intensity = {:.3}\neating = \"{}\"\nwhisker_length = {:.3}\n\
         inhibit_smell_on_whisker = {}\nmax_rpt = {:.3}",
        odour(r),
        r.uniform(0.0, 1.0),
        if r.chance(0.5) { "action" } else { "contact" },
        r.uniform(0.0, 20.0),
        r.chance(0.3),
        r.uniform(0.05, 1.0)
    )
    .unwrap();
    // Most worlds' creatures also see: the eye takes its food and aversive objects from the
    // grid when its range is finite.
    if r.chance(0.7) {
        writeln!(
            t,
            "[creature.inputs]\neye = true\n[creature.eye]\nfov = {:.3}\nwidth = {}\n\
             height = {}\n{}",
            r.uniform(10.0, 360.0),
            1 + r.below(40),
            1 + r.below(3),
            if r.chance(0.85) {
                format!("range = {:.3}", r.uniform(2.0, 300.0))
            } else {
                String::new()
            }
        )
        .unwrap();
    }
    t
}

/// [`random_world`] with only the smells the smell grid lists: no doors, areas, teleporters,
/// wanderers or predators, every food and aversive kind of finite range, and creatures that
/// give off no smell, so that the tick loop's smell takes its common path
/// (`Surroundings::smell_listed`) wherever the receptors share a list.
fn listed_smells_world(seed: u64) -> String {
    let text = random_world(seed);
    let dropped = [
        "[[world.doors]]",
        "[[world.areas]]",
        "[[world.teleporters]]",
        "[world.wanderers]",
        "[[world.predators]]",
        "[[world.air_predators]]",
    ];
    let mut out = String::new();
    let mut block: Vec<&str> = Vec::new();
    let flush = |block: &mut Vec<&str>, out: &mut String| {
        let Some(&head) = block.first() else { return };
        if dropped.contains(&head) {
            block.clear();
            return;
        }
        let kind = head.starts_with("[world.kinds.");
        for line in block.iter() {
            if head == "[creature]" && line.starts_with("odour_intensity") {
                out.push_str("odour_intensity = 0\n");
            } else {
                out.push_str(line);
                out.push('\n');
            }
        }
        if kind && !block.iter().any(|l| l.starts_with("range")) {
            out.push_str("range = 45.5\n");
        }
        block.clear();
    };
    for line in text.lines() {
        if line.starts_with('[') {
            flush(&mut block, &mut out);
        }
        block.push(line);
    }
    flush(&mut block, &mut out);
    out
}

/// [`listed_smells_world`] with every kind's odour cut down to one component (a random one of
/// the eight, of random strength), the smells the smell grid sums one term at a time
/// ([`berry_evolve::sim::index::smell_grid::Odour::lone`]).
fn one_component_smells_world(seed: u64) -> String {
    let mut r = Mix(seed ^ 0x0D0E);
    let mut out = String::new();
    let mut in_kind = false;
    for line in listed_smells_world(seed).lines() {
        if line.starts_with('[') {
            in_kind = line.starts_with("[world.kinds.");
        }
        if in_kind && line.starts_with("odour") {
            let mut v = [
                "0".to_string(),
                "0".into(),
                "0".into(),
                "0".into(),
                "0".into(),
                "0".into(),
                "0".into(),
                "0".into(),
            ];
            v[r.below(8) as usize] = format!("{:.3}", r.uniform(0.01, 1.0));
            writeln!(out, "odour = [{}]", v.join(", ")).unwrap();
        } else {
            out.push_str(line);
            out.push('\n');
        }
    }
    out
}

/// Runs `text` with the grid and with the plain loops for 300 ticks, `creatures` creatures,
/// and checks that both agree after every tick; false when the world leaves no room.
fn grid_agrees_with_brute_force(text: &str, creatures: usize, seed: u64) -> bool {
    let Some((mut grid, mut brute)) = sim_common::twin_worlds(text, creatures, seed) else {
        return false;
    };
    brute.set_brute_force(true);
    grid.set_full_sensing(true);
    brute.set_full_sensing(true);
    let mut jumps = Mix(seed ^ 0xABCD);
    let [w, h] = grid.arena();
    // Creatures anywhere now and then, some beyond the arena and its grid.
    let jump = |tick: u64, _: usize, _: &World| {
        (tick % 25 == 24).then(|| Pose {
            position: Vec2::new(
                jumps.uniform(-0.1 * w, 1.1 * w),
                jumps.uniform(-0.1 * h, 1.1 * h),
            ),
            heading: sim_common::heading(jumps.uniform(0.0, 360.0)),
        })
    };
    let check = |tick: u64, grid: &World, brute: &World| {
        let (a, b) = (state(grid), state(brute));
        assert!(
            a == b,
            "seed {seed}, tick {tick}: the grid and the plain loops differ\n{text}"
        );
    };
    let random = |i: u64| Random(Mix(seed * 100 + i));
    sim_common::side_by_side((&mut grid, &mut brute), random, 300, jump, check);
    true
}

#[test]
fn grid_and_brute_force_agree_on_worlds_of_listed_smells_only() {
    let mut checked = 0;
    for seed in 0..30u64 {
        let text = listed_smells_world(seed);
        // One creature (nothing else smells) or several whose bodies give off no smell.
        let creatures = if seed % 2 == 0 { 1 } else { 6 };
        checked += usize::from(grid_agrees_with_brute_force(&text, creatures, seed));
    }
    eprintln!("{checked} random worlds checked");
    assert!(checked >= 15, "only {checked} random worlds could be built");
}

#[test]
fn grid_and_brute_force_agree_on_worlds_of_one_component_smells() {
    let mut checked = 0;
    for seed in 0..30u64 {
        let text = one_component_smells_world(seed);
        assert!(
            text.contains("odour = ["),
            "seed {seed}: no odour to cut down"
        );
        let creatures = if seed % 2 == 0 { 1 } else { 6 };
        checked += usize::from(grid_agrees_with_brute_force(&text, creatures, seed));
    }
    eprintln!("{checked} random worlds checked");
    assert!(checked >= 15, "only {checked} random worlds could be built");
}

/// [`random_world`] with the report's last smells (§4.2, §5.1): every door trigger and a few
/// landmarks (inside and outside the arena) smell, and each creature has its own body odour
/// (`[creature] odours`), drawn from a generator of their own so that the rest is the world
/// `random_world` gives.
fn every_object_smells_world(seed: u64) -> String {
    let mut r = Mix(seed ^ 0x5EED);
    let mut out = String::new();
    for line in random_world(seed).lines() {
        out.push_str(line);
        out.push('\n');
        if line.starts_with("open_ticks") {
            let o = odour(&mut r);
            let range = range(&mut r, 150.0);
            writeln!(
                out,
                "odour = {o}\nintensity = {:.3}\n{range}",
                r.uniform(0.1, 2.0)
            )
            .unwrap();
        }
        if line == "[creature]" {
            let odours: Vec<String> = (0..1 + r.below(5)).map(|_| odour(&mut r)).collect();
            writeln!(out, "odours = [{}]", odours.join(", ")).unwrap();
        }
    }
    for _ in 0..1 + r.below(3) {
        let (x, y) = (r.uniform(-50.0, 1250.0), r.uniform(-50.0, 1250.0));
        let o = odour(&mut r);
        let range = range(&mut r, 150.0);
        writeln!(
            out,
            "[[world.landmarks]]\nposition = [{x:.3}, {y:.3}]\nodour = {o}\nintensity = {:.3}\n{range}",
            r.uniform(0.1, 2.0)
        )
        .unwrap();
    }
    out
}

#[test]
fn grid_and_brute_force_agree_when_triggers_landmarks_and_each_body_smell() {
    let mut checked = 0;
    for seed in 0..16u64 {
        let text = every_object_smells_world(seed);
        checked += usize::from(grid_agrees_with_brute_force(&text, 6, seed));
    }
    eprintln!("{checked} random worlds checked");
    assert!(checked >= 8, "only {checked} random worlds could be built");
}

/// Everything a tick can change, printed exactly (`{:?}` of an f64 round-trips its bits).
fn state(w: &World) -> String {
    let mut s = format!("{:?}\n{:?}\n", w.creatures(), w.food());
    for i in 0..w.creatures().len() {
        writeln!(s, "{:?}", w.observation(i)).unwrap();
    }
    writeln!(s, "{:?}\n{:?}\n{:?}", w.actors(), w.flyers(), w.things()).unwrap();
    writeln!(s, "{:?}", w.walls()).unwrap();
    s
}

#[test]
fn grid_and_brute_force_agree_to_the_bit_on_random_worlds() {
    let mut checked = 0;
    for seed in 0..40u64 {
        // A random world may leave no room for its creatures; the next seed will do.
        checked += usize::from(grid_agrees_with_brute_force(&random_world(seed), 12, seed));
    }
    eprintln!("{checked} random worlds checked");
    assert!(checked >= 20, "only {checked} random worlds could be built");
}

#[test]
fn the_grid_has_cells_as_wide_as_the_largest_finite_range() {
    let w = sim_common::world(
        r#"
[world]
arena = [3000, 1500]

[world.kinds.near]
class = "food"
odour = [1, 0, 0, 0, 0, 0, 0, 0]
range = 40
intensity = 1

[world.kinds.far]
class = "aversive"
odour = [0, 1, 0, 0, 0, 0, 0, 0]
range = 75
intensity = 1

[world.kinds.everywhere]
class = "food"
odour = [0, 0, 1, 0, 0, 0, 0, 0]
intensity = 1

[[world.place]]
kind = "near"
count = 200

[[world.place]]
kind = "far"
count = 5

[[world.place]]
kind = "everywhere"
count = 3
"#,
        1,
        1,
    );
    // 800 cells for 208 objects and 4 walls: within 4 cells per item.
    let index = w.index();
    assert_eq!(index.smell_reach(), 75.0);
    assert_eq!(index.cell_size(), 75.0);
    assert_eq!(index.dimensions(), [40, 20]);
}

/// A world without smell would get cells as narrow as the whisker reach; its grid is capped
/// at 4 cells per object and wall instead (at least 64), since every trial builds one.
#[test]
fn a_grid_has_few_cells_per_object() {
    let w = sim_common::world(
        r#"
[world]
arena = [600, 600]

[world.kinds.food]
class = "food"
radius = 10

[world.kinds.poison]
class = "aversive"
radius = 10

[[world.place]]
kind = "food"
count = 25

[[world.place]]
kind = "poison"
count = 25
"#,
        1,
        1,
    );
    // 50 objects, and the 4 boundary walls in both the felt and the opaque lists.
    let items = 50 + 2 * 4;
    let index = w.index();
    let [nx, ny] = index.dimensions();
    assert!(nx * ny <= 4 * items, "{nx} x {ny} cells");
    // Halving the cells' side would break the cap: the cells are as narrow as it allows.
    assert!(4 * nx * ny > 4 * items, "{nx} x {ny} cells");
    assert!(index.cell_size() >= 600.0 / nx as f64);
}

/// The smell grid's lists against plain loops, at random points in and around random worlds
/// (hundreds of objects, unlimited ranges, aversive objects, doors, transparent walls): each
/// point's cell lists, in increasing id order, every object of finite range whose smell
/// reaches the point, and for each the fixed opaque walls crossing the segment from the point
/// to it; the objects of unlimited range are listed apart, in order. A list that serves a
/// pair of nearby receptors does so for both.
#[test]
fn smell_cells_list_every_source_in_range_and_every_wall_that_may_hide_it() {
    use berry_evolve::geometry::BoxedSegment;
    use berry_evolve::geometry::{
        segments_intersect, segments_intersect_past_box, side_of, Segment,
    };
    use berry_evolve::sim::index::smell_grid::{FacedShade, Source};
    let (mut checked, mut listed_in_range) = (0, 0);
    let (mut pairs, mut pairs_served, mut hidden_unlisted) = (0, 0, 0);
    for seed in 0..40u64 {
        let text = random_world(seed);
        let setup = sim_common::setup(&text);
        let Ok(w) = World::new(&setup.world, &setup.creature, 1, sim_common::rng(seed)) else {
            continue;
        };
        checked += 1;
        let index = w.index();
        let opaque: Vec<Segment> = w
            .walls()
            .iter()
            .filter(|w| w.opaque)
            .map(|w| w.segment)
            .take(index.fixed_opaque())
            .collect();
        let n = w.food().len();
        let follows: Vec<bool> = (0..n)
            .map(|k| w.food()[k].smell_follows_amount)
            .chain(w.aversives().iter().map(|_| false))
            .collect();
        let smells: Vec<(Vec2, _)> = w
            .food()
            .iter()
            .map(|f| (f.position, f.smell))
            .chain(w.aversives().iter().map(|a| (a.position, a.smell)))
            .collect();
        let always: Vec<u32> = (0..smells.len() as u32)
            .filter(|&k| {
                let s = &smells[k as usize].1;
                !s.silent && s.range_squared == f64::INFINITY
            })
            .collect();
        assert_eq!(index.smell_always(), &always[..], "seed {seed}");
        assert_eq!(index.food_count(), n);
        let [aw, ah] = w.arena();
        let mut r = Mix(seed ^ 0x5E11);
        let mut q = Mix(seed ^ 0x9A12);
        for t in 0..2000 {
            // Half the points anywhere, half near an object (on cell borders now and then).
            let p = if t % 2 == 0 || smells.is_empty() {
                Vec2::new(
                    r.uniform(-0.2 * aw, 1.2 * aw),
                    r.uniform(-0.2 * ah, 1.2 * ah),
                )
            } else {
                let (c, _) = smells[r.below(smells.len() as u64) as usize];
                let p = c + Vec2::new(r.uniform(-100.0, 100.0), r.uniform(-100.0, 100.0));
                let cell = index.smell_dimensions().1;
                if r.chance(0.1) {
                    (p / cell).round() * cell
                } else {
                    p
                }
            };
            let mut check = |p: Vec2, list: &[Source]| {
                assert!(list.windows(2).all(|s| s[0].id < s[1].id), "seed {seed}");
                for (k, (centre, smell)) in smells.iter().enumerate() {
                    let finite = !smell.silent && smell.range_squared.is_finite();
                    let entry = list.iter().find(|s| s.id as usize == k);
                    if !finite {
                        assert!(entry.is_none(), "seed {seed}: object {k} listed");
                        continue;
                    }
                    if let Some(e) = entry {
                        assert_eq!(e.centre, *centre, "seed {seed}: object {k}");
                        assert_eq!(e.range_squared, smell.range_squared, "seed {seed}: {k}");
                        // The odour is the object's emission to the bit, with its lone
                        // non-zero component and its scale.
                        let o = index.odour(e);
                        let bits = |v: &[f64; 8]| v.map(f64::to_bits);
                        assert_eq!(bits(&o.emission), bits(&smell.emission), "seed {seed}");
                        let nonzero: Vec<u8> = (0..8u8)
                            .filter(|&j| smell.emission[j as usize] != 0.0)
                            .collect();
                        let lone = (nonzero.len() == 1).then(|| nonzero[0]);
                        assert_eq!(o.lone, lone, "seed {seed}: object {k}");
                        assert_eq!(o.follows, follows[k], "seed {seed}: object {k}");
                        // Each wall's shade answers the box test of the segment from any
                        // receptor (infinite ones too) to the centre.
                        let walls = index.source_walls(e);
                        let shaded = index.source_shaded_walls(e);
                        assert_eq!(walls.len(), shaded.len(), "seed {seed}");
                        // Each entry carries a copy of its wall, to the bit.
                        for (&j, w) in walls.iter().zip(shaded) {
                            let (a, b) = (opaque[j as usize].a, opaque[j as usize].b);
                            let bits = |v: Vec2| [v.x.to_bits(), v.y.to_bits()];
                            assert_eq!(bits(w.segment.a), bits(a), "seed {seed}: {k} {j}");
                            assert_eq!(bits(w.segment.b), bits(b), "seed {seed}: {k} {j}");
                        }
                        let shades = shaded.iter().map(|w| &w.shade);
                        assert_eq!(e.has_walls(), !walls.is_empty(), "seed {seed}");
                        let inf = f64::INFINITY;
                        let points = [
                            p,
                            Vec2::new(inf, p.y),
                            Vec2::new(p.x, -inf),
                            Vec2::new(-inf, inf),
                        ];
                        for (&j, shade) in walls.iter().zip(shades) {
                            let wall = BoxedSegment::new(opaque[j as usize]);
                            for r in points {
                                let meets = wall.may_meet(r.min(*centre), r.max(*centre));
                                let key = FacedShade::key(r);
                                assert_eq!(shade.holds(&key, true), meets, "seed {seed}: {k} {r}");
                                assert!(!shade.holds(&key, false), "seed {seed}");
                            }
                        }
                        // Each wall's stored side of the centre is side_of to the bit, and
                        // where the wall's shade holds, the occlusion test given it answers
                        // as segments_intersect does (elsewhere the segments cannot meet).
                        let sides = shaded.iter().map(|w| w.side);
                        let shades = shaded.iter().map(|w| &w.shade);
                        for ((&j, side), shade) in walls.iter().zip(sides).zip(shades) {
                            let wall = &opaque[j as usize];
                            let exact = side_of(wall, *centre);
                            assert_eq!(side.to_bits(), exact.to_bits(), "seed {seed}: {k} {j}");
                            let ends = [wall.a, wall.b, *centre, (wall.a + wall.b) * 0.5];
                            for r in points.into_iter().chain(ends) {
                                let line = Segment::new(r, *centre);
                                let meets = segments_intersect(&line, wall);
                                if shade.holds(&FacedShade::key(r), true) {
                                    let past = segments_intersect_past_box(&line, wall, side);
                                    assert_eq!(past, meets, "seed {seed}: {k} {j} {r}");
                                } else {
                                    assert!(!meets, "seed {seed}: {k} {j} {r}");
                                }
                            }
                        }
                    }
                    if p.distance_squared(*centre) >= smell.range_squared {
                        continue;
                    }
                    let line = Segment::new(p, *centre);
                    let Some(entry) = entry else {
                        // Only a source that a fixed opaque wall hides from p may be left out.
                        let hidden = opaque.iter().any(|wall| segments_intersect(&line, wall));
                        assert!(hidden, "seed {seed}: {k} not listed at {p}");
                        hidden_unlisted += 1;
                        continue;
                    };
                    listed_in_range += 1;
                    let walls = index.source_walls(entry);
                    for (j, wall) in opaque.iter().enumerate() {
                        if segments_intersect(&line, wall) {
                            assert!(
                                walls.contains(&(j as u32)),
                                "seed {seed}: wall {j} hides {k} from {p} but is not listed"
                            );
                        }
                    }
                }
            };
            check(p, index.smell_sources(index.smell_cell(p)));
            // A pair of whisker tips around p (a separate generator keeps the points above
            // the same): one list, when the index gives one, must serve both.
            let d = Vec2::new(q.uniform(-8.0, 8.0), q.uniform(-8.0, 8.0));
            let tips = [p, p + d];
            if let Some(list) = index.smell_pair_sources(tips) {
                pairs_served += 1;
                check(tips[0], list);
                check(tips[1], list);
            }
            pairs += 1;
        }
    }
    assert!(checked >= 20, "only {checked} random worlds could be built");
    assert!(
        listed_in_range > 10_000,
        "{listed_in_range} objects in range"
    );
    // Sources hidden from a whole cell are left out of it.
    assert!(
        hidden_unlisted > 100,
        "{hidden_unlisted} hidden sources left out"
    );
    // Most pairs of tips this close take one list.
    assert!(
        2 * pairs_served > pairs,
        "{pairs_served} of {pairs} pairs served by one list"
    );
}

/// A listed wall's shade as four lower bounds answers as the [`WallShade`] it comes from, for
/// every receptor: infinite ones, NaN and both zeros included, on bounds of the same kinds.
#[test]
fn a_faced_shade_answers_as_its_wall_shade() {
    use berry_evolve::sim::index::smell_grid::FacedShade;
    use berry_evolve::sim::smell::WallShade;
    let inf = f64::INFINITY;
    let values = [-inf, -2.5, -1.0, -0.0, 0.0, 1.0, 2.5, inf, f64::NAN];
    for x0 in values {
        for x1 in values {
            for y0 in values {
                for y1 in values {
                    let shade = WallShade { x0, x1, y0, y1 };
                    let faced = FacedShade::new(shade);
                    for x in values {
                        for y in values {
                            let r = Vec2::new(x, y);
                            let key = FacedShade::key(r);
                            for ask in [false, true] {
                                assert_eq!(
                                    faced.holds(&key, ask),
                                    shade.holds(r, ask),
                                    "{shade:?} {r} {ask}"
                                );
                            }
                        }
                    }
                }
            }
        }
    }
}
