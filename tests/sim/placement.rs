//! Placement of objects and creatures: minimum spacing, grid snapping, regions, never
//! touching a wall, reproducibility, and clear errors when a rule cannot be met.

use crate::sim_common::{rng, setup};
use berry_evolve::geometry::{circle_touches_segment, circles_touch, Vec2};
use berry_evolve::sim::{PlacementError, World};

fn build(text: &str, creatures: usize, seed: u64) -> Result<World, PlacementError> {
    let s = setup(text);
    World::new(&s.world, &s.creature, creatures, rng(seed))
}

/// Centres of every object, food then aversive.
fn centres(w: &World) -> Vec<(Vec2, f64)> {
    w.food()
        .iter()
        .map(|f| (f.position, f.radius))
        .chain(w.aversives().iter().map(|a| (a.position, a.radius)))
        .collect()
}

const MAZE: &str = r#"
[[world.walls]]
from = [100, 0]
to = [100, 200]

[[world.walls]]
from = [200, 300]
to = [200, 100]

[[world.walls]]
from = [20, 280]
to = [90, 210]

[[world.walls]]
from = [220, 50]
to = [280, 50]
"#;

#[test]
fn min_spacing_holds_between_all_objects_of_all_rules() {
    let text = r#"
[world.kinds.apple]
class = "food"
radius = 1

[world.kinds.thorn]
class = "aversive"
radius = 2

[[world.objects]]
kind = "apple"
position = [150, 150]

[[world.place]]
kind = "apple"
count = 150
min_spacing = 12

[[world.place]]
kind = "thorn"
count = 50
min_spacing = 12
"#;
    for seed in 0..5 {
        let w = build(text, 0, seed).unwrap();
        let objects = centres(&w);
        assert_eq!(objects.len(), 201);
        for (i, a) in objects.iter().enumerate() {
            for (j, b) in objects.iter().enumerate().skip(i + 1) {
                let d = a.0.distance(b.0);
                assert!(
                    d >= 12.0,
                    "seed {seed}: objects {i} at {} and {j} at {} are {d} LU apart",
                    a.0,
                    b.0
                );
            }
        }
    }
}

#[test]
fn grid_snaps_centres_to_multiples_of_the_pitch_inside_the_region() {
    let text = r#"
[world.kinds.apple]
class = "food"

[[world.place]]
kind = "apple"
count = 60
region = [10, 10, 200, 100]
grid = 7.5
"#;
    let w = build(text, 0, 1).unwrap();
    let mut xs = std::collections::BTreeSet::new();
    for f in w.food() {
        let p = f.position;
        for v in [p.x, p.y] {
            let k = (v / 7.5).round();
            assert_eq!(v, k * 7.5, "{p} is not on the 7.5 LU grid");
        }
        assert!(
            (10.0..=200.0).contains(&p.x) && (10.0..=100.0).contains(&p.y),
            "{p} outside the region"
        );
        xs.insert(p.x.to_bits());
    }
    // 26 columns (15 .. 195) are available; 60 draws use many of them.
    assert!(xs.len() > 10, "only {} distinct columns", xs.len());
}

#[test]
fn objects_and_creatures_never_touch_walls_and_creatures_start_clear() {
    let text = format!(
        r#"
{MAZE}
[world.kinds.apple]
class = "food"
radius = 2

[world.kinds.point]
class = "food"

[world.kinds.thorn]
class = "aversive"
radius = 3

[[world.place]]
kind = "apple"
count = 300

[[world.place]]
kind = "point"
count = 300
region = [95, 0, 105, 300]

[[world.place]]
kind = "thorn"
count = 100
"#
    );
    for seed in 0..5 {
        let w = build(&text, 20, seed).unwrap();
        for (p, r) in centres(&w) {
            for wall in w.wall_segments() {
                assert!(
                    !circle_touches_segment(p, r, wall),
                    "seed {seed}: object at {p} (r = {r}) touches wall {wall:?}"
                );
            }
        }
        let r = w.creature_radius();
        for (i, c) in w.creatures().iter().enumerate() {
            let p = c.pose.position;
            assert!((c.pose.heading.length() - 1.0).abs() < 1e-12);
            for wall in w.wall_segments() {
                assert!(
                    !circle_touches_segment(p, r, wall),
                    "seed {seed}: creature {i} touches a wall"
                );
            }
            for (q, qr) in centres(&w) {
                assert!(
                    !circles_touch(p, r, q, qr),
                    "seed {seed}: creature {i} at {p} touches an object at {q}"
                );
            }
            for (j, other) in w.creatures().iter().enumerate().skip(i + 1) {
                assert!(
                    !circles_touch(p, r, other.pose.position, r),
                    "seed {seed}: creatures {i} and {j} touch"
                );
            }
        }
    }
}

#[test]
fn start_region_and_heading_are_honoured() {
    let text = "[world.start]\nregion = [20, 30, 60, 50]\nheading = 180";
    let w = build(text, 5, 4).unwrap();
    for c in w.creatures() {
        let p = c.pose.position;
        assert!(
            (20.0..=60.0).contains(&p.x) && (30.0..=50.0).contains(&p.y),
            "{p}"
        );
        assert!((c.pose.heading.x + 1.0).abs() < 1e-15, "{}", c.pose.heading);
    }
    // Without a heading, headings are random and differ.
    let w = build("", 5, 4).unwrap();
    let h: Vec<_> = w.creatures().iter().map(|c| c.pose.heading).collect();
    assert!(h.windows(2).all(|p| p[0] != p[1]), "{h:?}");
}

#[test]
fn same_seed_same_world_and_another_seed_another() {
    let text = format!(
        "{MAZE}\n[world.kinds.apple]\nclass = \"food\"\n[[world.place]]\nkind = \"apple\"\ncount = 30\nmin_spacing = 5"
    );
    let positions = |seed| {
        let w = build(&text, 3, seed).unwrap();
        let mut v: Vec<Vec2> = w.food().iter().map(|f| f.position).collect();
        v.extend(w.creatures().iter().map(|c| c.pose.position));
        v
    };
    assert_eq!(positions(7), positions(7));
    assert_ne!(positions(7), positions(8));
}

#[test]
fn impossible_density_is_a_placement_error_naming_the_rule() {
    // 1000 objects 50 LU apart cannot fit in 300 x 300 LU (at most about 45 can).
    let text = r#"
[world.kinds.apple]
class = "food"

[world.kinds.pear]
class = "food"

[[world.place]]
kind = "pear"
count = 3

[[world.place]]
kind = "apple"
count = 1000
min_spacing = 50
"#;
    let e = build(text, 1, 1).expect_err("must fail");
    match &e {
        PlacementError::Object {
            rule, kind, number, ..
        } => {
            assert_eq!((*rule, kind.as_str()), (1, "apple"));
            assert!(*number > 10 && *number < 100, "failed at object {number}");
        }
        other => panic!("wrong error {other:?}"),
    }
    let message = e.to_string();
    assert!(
        message.contains("`world.place[1]`") && message.contains("`apple`"),
        "{message}"
    );
}

#[test]
fn creatures_that_cannot_fit_are_a_placement_error() {
    // A 1 x 1 LU start region holds one body of diameter 6, not two.
    let e = build("[world.start]\nregion = [10, 10, 11, 11]", 2, 1).expect_err("must fail");
    assert!(
        matches!(
            e,
            PlacementError::Creature {
                number: 2,
                count: 2,
                ..
            }
        ),
        "{e:?}"
    );
    assert!(e.to_string().contains("creature 2 of 2"), "{e}");
    // A region against the boundary wall: every body there touches it.
    let e = build("[world.start]\nregion = [0, 0, 2, 300]", 1, 1).expect_err("must fail");
    assert!(
        matches!(e, PlacementError::Creature { number: 1, .. }),
        "{e:?}"
    );
    let e = build("", 1_000_000, 1).expect_err("must fail");
    assert!(
        matches!(e, PlacementError::TooManyCreatures { .. }),
        "{e:?}"
    );
}

#[test]
fn ten_thousand_spaced_objects_place_quickly() {
    let text = r#"
[world.kinds.seed]
class = "food"

[[world.place]]
kind = "seed"
count = 10000
min_spacing = 2
"#;
    let start = std::time::Instant::now();
    let w = build(text, 1, 1).unwrap();
    assert_eq!(w.food().len(), 10_000);
    // The spatial index makes this linear; a scan of all earlier objects would take seconds
    // in a debug build.
    assert!(
        start.elapsed().as_secs_f64() < 5.0,
        "placement took {:?}",
        start.elapsed()
    );
}
