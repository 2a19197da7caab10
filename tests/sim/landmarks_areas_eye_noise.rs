//! Distal landmarks, areas, the eye and sensor noise through the running world: known poses,
//! hand-computed values, ASCII pictures of the retina, validation key paths, and
//! reproducibility of noisy runs.

use crate::sim_common;
use crate::sim_common::{put, rng, setup, world, Fixed, Still};
use berry_evolve::geometry::Vec2;
use berry_evolve::record::trace::TraceWriter;
use berry_evolve::sim::controller::{MotorCommand, SensorGroup};
use berry_evolve::sim::scripted::{Scripted, ScriptedSpec};
use berry_evolve::sim::World;

/// The observation values of `group` for creature 0 after one step with a still controller.
fn sensed(w: &mut World, group: SensorGroup) -> Vec<f64> {
    w.step(&mut [Still]);
    let range = w.layout().range(group).expect("group is switched on");
    w.observation(0)[range].to_vec()
}

// ---------------------------------------------------------------- landmarks

const LANDMARKS: &str = r#"
[[world.landmarks]]
position = [300, 150]

[[world.landmarks]]
position = [150, 1000]

[[world.landmarks]]
position = [-50, 150]

[world.start]
region = [150, 150, 150, 150]
heading = 0

[creature.inputs]
landmarks = true
"#;

#[test]
fn landmark_bearings_at_known_poses() {
    let mut w = world(LANDMARKS, 1, 1);
    let names = &w.layout().names()[w.layout().range(SensorGroup::Landmarks).unwrap()];
    assert_eq!(
        names,
        [
            "landmark_1_sin",
            "landmark_1_cos",
            "landmark_2_sin",
            "landmark_2_cos",
            "landmark_3_sin",
            "landmark_3_cos"
        ]
    );
    // Heading east: the first landmark straight ahead (0, 1); the second far down the
    // screen, which is clockwise = the creature's right (1, 0) (it lies outside the arena:
    // distal landmarks may); the third behind (0, −1).
    put(&mut w, 0, 150.0, 150.0, 0.0);
    assert_eq!(
        sensed(&mut w, SensorGroup::Landmarks),
        [0.0, 1.0, 1.0, 0.0, 0.0, -1.0]
    );
    // Heading north (up the screen, −90°): the first is now on the right, the second behind,
    // the third on the left.
    put(&mut w, 0, 150.0, 150.0, -90.0);
    let got = sensed(&mut w, SensorGroup::Landmarks);
    let want = [1.0, 0.0, 0.0, -1.0, -1.0, 0.0];
    for (g, e) in got.iter().zip(want) {
        assert!((g - e).abs() < 1e-15, "{got:?} != {want:?}");
    }
    // Heading 45° (down-right): the first landmark is 45° to the left, the second 45° to
    // the right, the third 135° to the right.
    put(&mut w, 0, 150.0, 150.0, 45.0);
    let got = sensed(&mut w, SensorGroup::Landmarks);
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let want = [-h, h, h, h, h, -h];
    for (g, e) in got.iter().zip(want) {
        assert!((g - e).abs() < 1e-15, "{got:?} != {want:?}");
    }
}

// ---------------------------------------------------------------- areas

const AREAS: &str = r#"
[[world.areas]]
region = [100, 100, 200, 200]
kind = "safe"

[[world.areas]]
region = [0, 0, 50, 50]

[world.start]
region = [150, 150, 150, 150]
heading = 0

[creature.inputs]
areas = true
"#;

#[test]
fn area_inputs_and_safety_are_inclusive() {
    let mut w = world(AREAS, 1, 1);
    assert_eq!(
        &w.layout().names()[w.layout().range(SensorGroup::Areas).unwrap()],
        ["area_1", "area_2"]
    );
    assert_eq!(sensed(&mut w, SensorGroup::Areas), [1.0, 0.0]);
    put(&mut w, 0, 200.0, 100.0, 0.0); // on the corner: inside
    assert_eq!(sensed(&mut w, SensorGroup::Areas), [1.0, 0.0]);
    put(&mut w, 0, 25.0, 50.0, 0.0);
    assert_eq!(sensed(&mut w, SensorGroup::Areas), [0.0, 1.0]);
    put(&mut w, 0, 250.0, 250.0, 0.0);
    assert_eq!(sensed(&mut w, SensorGroup::Areas), [0.0, 0.0]);

    assert!(w.in_safe_area(Vec2::new(150.0, 150.0)));
    assert!(w.in_safe_area(Vec2::new(200.0, 200.0)));
    assert!(!w.in_safe_area(Vec2::new(200.000_001, 150.0)));
    // A plain area is not safe.
    assert!(!w.in_safe_area(Vec2::new(25.0, 25.0)));
}

const SMELLY_AREA: &str = r#"
[[world.areas]]
region = [0, 0, 40, 40]
odour = [1, 0, 0, 0, 0, 0, 0, 0.5]
intensity = 0.8

[world.start]
region = [20, 80, 20, 80]
heading = -90
"#;

#[test]
fn area_smell_comes_from_its_centre_and_opaque_walls_hide_it() {
    let mut w = world(SMELLY_AREA, 1, 1);
    let smell = sensed(&mut w, SensorGroup::Smell);
    let tips = w.whisker_tips(0);
    let centre = Vec2::new(20.0, 20.0);
    for (side, tip) in tips.iter().enumerate() {
        let d2 = tip.distance_squared(centre);
        let i = 0.8 / (1.0 + 0.01 * d2);
        sim_common::assert_close(smell[8 * side], i, "receptor 1");
        sim_common::assert_close(smell[8 * side + 7], 0.5 * i, "receptor 8");
        assert_eq!(smell[8 * side + 1], 0.0);
    }

    let walled = format!("{SMELLY_AREA}\n[[world.walls]]\nfrom = [0, 60]\nto = [100, 60]\n");
    let mut w = world(&walled, 1, 1);
    assert_eq!(sensed(&mut w, SensorGroup::Smell), [0.0; 16]);
}

// ---------------------------------------------------------------- eye

/// One letter per colour, so that retinas can be compared as pictures.
fn letter(rgb: &[f64]) -> char {
    match rgb {
        [0.0, 0.0, 0.0] => '.',
        [0.5, 0.5, 0.5] => 'W',
        [1.0, 1.0, 0.0] => 'T',
        [1.0, 0.0, 1.0] => 'L',
        [0.0, 1.0, 0.0] => 'f',
        [1.0, 0.0, 0.0] => 'a',
        [0.0, 0.0, 1.0] => 'c',
        other => panic!("unexpected colour {other:?}"),
    }
}

/// Creature 0's retina as rows of letters.
fn picture(w: &mut World) -> Vec<String> {
    let [width, height] = w.retina_size().expect("the creature has an eye");
    let mut out = vec![0.0; 3 * width * height];
    assert!(w.render_eye(0, &mut out));
    out.chunks(3 * width)
        .map(|row| row.chunks(3).map(letter).collect())
        .collect()
}

const EYE_1D: &str = r#"
[world]
boundary_walls = false

[[world.walls]]
from = [250, 0]
to = [250, 300]

[world.kinds.apple]
class = "food"
radius = 5

[world.kinds.low]
class = "food"
radius = 5
height = 4

[[world.objects]]
kind = "apple"
position = [200, 150]

[world.start]
region = [150, 150, 150, 150]
heading = 0

[creature.inputs]
eye = true
"#;

#[test]
fn one_row_retina_pictures() {
    let mut w = world(EYE_1D, 1, 1);
    assert_eq!(w.retina_size(), Some([16, 1]));
    // Heading east: columns look from −45° (left) to +45° in steps of 5.625°, centred on
    // ±2.8125° nearest the heading. The apple (radius 5 at distance 50) spans ±5.74°, so it
    // fills the two middle columns; the wall 100 LU away fills the rest.
    assert_eq!(picture(&mut w), ["WWWWWWWffWWWWWWW"]);
    // The observation holds the same retina, 48 values.
    w.step(&mut [Still]);
    let eye = w.layout().range(SensorGroup::Eye).unwrap();
    assert_eq!(eye.len(), 48);
    let mut out = vec![0.0; 48];
    w.render_eye(0, &mut out);
    assert_eq!(&w.observation(0)[eye], &out[..]);

    // Heading south (down the screen): the wall is on the left (east), seen only by the
    // columns at 47.8° and 53.4° from east, whose rays meet x = 250 before y = 300.
    put(&mut w, 0, 150.0, 150.0, 90.0);
    assert_eq!(picture(&mut w), ["WW.............."]);

    // A 1-row retina sees a surface iff it is at least eye_height (5) tall: a 4 LU apple is
    // invisible and the wall shows through.
    let low = EYE_1D.replace("kind = \"apple\"", "kind = \"low\"");
    let mut w = world(&low, 1, 1);
    assert_eq!(picture(&mut w), ["WWWWWWWWWWWWWWWW"]);

    // A range shorter than the wall's distance hides it.
    let near = format!("{EYE_1D}\n[creature.eye]\nrange = 60\n");
    let mut w = world(&near, 1, 1);
    assert_eq!(picture(&mut w), [".......ff......."]);
}

const EYE_2D: &str = r#"
[world]
boundary_walls = false

# A low magenta wall 20 LU ahead, 6 LU high.
[[world.walls]]
from = [170, 100]
to = [170, 200]
colour = [1, 0, 1]
height = 6

# A tall yellow wall 100 LU ahead, 40 LU high.
[[world.walls]]
from = [250, 0]
to = [250, 300]
colour = [1, 1, 0]
height = 40

[world.start]
region = [150, 150, 150, 150]
heading = 0

[creature.inputs]
eye = true

[creature.eye]
fov = 30
vertical_fov = 90
width = 3
height = 8
"#;

#[test]
fn tall_far_wall_shows_above_low_near_one() {
    let mut w = world(EYE_2D, 1, 1);
    // Rows look at 39.4°, 28.1°, 16.9°, 5.6°, −5.6°, −16.9°, −28.1°, −39.4°. The near wall
    // (d = 20, top 1 LU above the eye, bottom 5 below) covers −14.0° to 2.9°: row 4 only.
    // The far wall (d = 100, top 35 LU above the eye) covers −2.9° to 19.3°: rows 2 and 3.
    // Nothing covers the rest (the floor and sky are background).
    assert_eq!(
        picture(&mut w),
        ["...", "...", "TTT", "TTT", "LLL", "...", "...", "..."]
    );
    // Without the near wall, row 4 looks below the far wall's foot.
    let far_only = EYE_2D.replacen("from = [170, 100]", "from = [170, 290]", 1);
    let far_only = far_only.replacen("to = [170, 200]", "to = [170, 300]", 1);
    let mut w = world(&far_only, 1, 1);
    assert_eq!(
        picture(&mut w),
        ["...", "...", "TTT", "TTT", "...", "...", "...", "..."]
    );
}

const EYE_OBJECTS: &str = r#"
[world]
boundary_walls = false

[world.kinds.nettle]
class = "aversive"
radius = 4

[world.kinds.dot]
class = "food"

[[world.objects]]
kind = "nettle"
position = [150, 100]

[[world.objects]]
kind = "dot"
position = [190, 150]

[creature.inputs]
eye = true

[creature.eye]
fov = 180
width = 9
"#;

#[test]
fn eye_sees_other_creatures_and_aversives_but_not_points_or_itself() {
    let mut w = world(EYE_OBJECTS, 2, 1);
    // Columns look at −80°, −60°, …, 0°, …, +80°. Heading east, the middle column looks
    // straight at the radius-0 food "dot", which is a point and is not seen; the nettle
    // straight up (−90°, radius 4 at 50 LU spans ±4.6°) is outside the field of view;
    // creature 1, 50 LU away at +80°, fills the last column.
    put(&mut w, 0, 150.0, 150.0, 0.0);
    let p = Vec2::new(150.0, 150.0) + 50.0 * sim_common::heading(80.0);
    put(&mut w, 1, p.x, p.y, 0.0);
    assert_eq!(picture(&mut w), ["........c"]);
    // Dead creatures are not seen.
    w.kill(1);
    assert_eq!(picture(&mut w), ["........."]);
    // Heading −10°, the first column looks at −90°: the nettle.
    put(&mut w, 0, 150.0, 150.0, -10.0);
    assert_eq!(picture(&mut w), ["a........"]);
}

// ---------------------------------------------------------------- noise

const NOISY: &str = r#"
[world.kinds.rose]
class = "food"
radius = 1
odour = [1, 0, 0, 0, 0, 0, 0, 0]
intensity = 0.5

[[world.place]]
kind = "rose"
count = 20

[[world.landmarks]]
position = [0, 0]

[[world.areas]]
region = [0, 0, 150, 150]

[creature.inputs]
landmarks = true
areas = true
metabolism = true
"#;

const NOISE_TABLES: &str = r#"
[creature.noise.smell]
n = 0.1
n_sigma = 0.05
m = 0.2
m_sigma = 0.1

[creature.noise.landmarks]
n = 0.05
n_sigma = 0.05
m = 0.1
m_sigma = 0.1

[creature.noise.areas]
n = 0.2
n_sigma = 0.2
"#;

const ZERO_NOISE: &str = r#"
[creature.noise.smell]
[creature.noise.whiskers]
[creature.noise.landmarks]
n = 0
m = 0
"#;

/// Every observation of every tick, as bits.
fn observations(text: &str, seed: u64, ticks: usize) -> Vec<u64> {
    let mut w = world(text, 2, seed);
    let mut c = [
        Fixed(MotorCommand {
            left: 0.2,
            right: 0.1,
            eat: 0.0,
        }),
        Fixed(MotorCommand {
            left: 0.1,
            right: 0.25,
            eat: 0.0,
        }),
    ];
    let mut out = Vec::new();
    for _ in 0..ticks {
        w.step(&mut c);
        for i in 0..2 {
            out.extend(w.observation(i).iter().map(|x| x.to_bits()));
        }
    }
    out
}

#[test]
fn zero_noise_is_bit_identical_and_noise_reproduces() {
    let clean = observations(NOISY, 3, 300);
    let zero = observations(&format!("{NOISY}{ZERO_NOISE}"), 3, 300);
    assert_eq!(clean, zero);

    let noisy_text = format!("{NOISY}{NOISE_TABLES}");
    let a = observations(&noisy_text, 3, 300);
    let b = observations(&noisy_text, 3, 300);
    assert_eq!(a, b, "same seed, same noisy observations");
    assert_ne!(a, clean);
    assert_ne!(a, observations(&noisy_text, 4, 300));

    // Only the configured groups change, and they stay in range.
    let w = world(&noisy_text, 2, 3);
    let layout = w.layout().clone();
    let width = layout.len();
    let range = |g| layout.range(g).unwrap();
    for (t, (x, y)) in a
        .chunks(width)
        .zip(clean.chunks(width))
        .enumerate()
        .take(50)
    {
        let x: Vec<f64> = x.iter().map(|b| f64::from_bits(*b)).collect();
        let y: Vec<f64> = y.iter().map(|b| f64::from_bits(*b)).collect();
        for g in [SensorGroup::Whiskers, SensorGroup::Food, SensorGroup::Bias] {
            assert_eq!(x[range(g)], y[range(g)], "tick {t} {g:?}");
        }
        assert!(x[range(SensorGroup::Smell)]
            .iter()
            .all(|v| (0.0..=1.0).contains(v)));
        assert!(x[range(SensorGroup::Landmarks)]
            .iter()
            .all(|v| (-1.0..=1.0).contains(v)));
        assert!(x[range(SensorGroup::Areas)]
            .iter()
            .all(|v| (0.0..=1.0).contains(v)));
    }
}

// ---------------------------------------------------------------- everything on

const EVERYTHING: &str = r#"
[[world.walls]]
from = [150, 40]
to = [150, 260]
colour = [0.2, 0.3, 0.9]
height = 20

[world.kinds.rose]
class = "food"
radius = 2
odour = [1, 0, 0, 0, 0, 0, 0, 0]
intensity = 0.5
colour = [0.9, 0.1, 0.1]
height = 6

[world.kinds.nettle]
class = "aversive"
radius = 3
odour = [0, 1, 0, 0, 0, 0, 0, 0]
intensity = 0.3

[[world.place]]
kind = "rose"
count = 20

[[world.place]]
kind = "nettle"
count = 6

[[world.landmarks]]
position = [0, 0]

[[world.landmarks]]
position = [600, 150]

[[world.areas]]
region = [200, 200, 300, 300]
kind = "safe"
odour = [0, 0, 1, 0, 0, 0, 0, 0]
intensity = 1
range = 80

[[world.areas]]
region = [0, 0, 100, 100]

[creature]
odour = [0, 0, 0, 1, 0, 0, 0, 0]
odour_intensity = 0.2
colour = [0.1, 0.8, 0.8]

[creature.inputs]
metabolism = true
landmarks = true
areas = true
eye = true

[creature.eye]
fov = 120
width = 12
height = 3
range = 200

[creature.noise.smell]
n = 0.1
n_sigma = 0.05
m = 0.2
m_sigma = 0.1

[creature.noise.eye]
n = 0.05
n_sigma = 0.05

[creature.noise.whiskers]
m = 0.1
m_sigma = 0.1
"#;

fn everything_trace(seed: u64, ticks: u64) -> Vec<u8> {
    let mut w = world(EVERYTHING, 3, seed);
    w.set_full_sensing(true);
    let mut controllers: Vec<Scripted> = [
        ScriptedSpec::Braitenberg {
            receptor: 1,
            gain: 0.5,
            base: 0.05,
        },
        ScriptedSpec::Braitenberg {
            receptor: 3,
            gain: 0.5,
            base: 0.08,
        },
        ScriptedSpec::Constant {
            left: 0.2,
            right: 0.15,
        },
    ]
    .iter()
    .map(|s| s.build(w.layout()).unwrap())
    .collect();
    let mut out = TraceWriter::new(Vec::new());
    let mut obs = Vec::new();
    for _ in 0..ticks {
        w.step(&mut controllers);
        out.write_tick(&w).unwrap();
        for i in 0..3 {
            obs.extend(w.observation(i).iter().flat_map(|x| x.to_le_bytes()));
        }
    }
    let mut bytes = out.into_inner().unwrap();
    bytes.extend(obs);
    bytes
}

#[test]
fn everything_on_same_seed_same_bytes() {
    let a = everything_trace(11, 400);
    assert_eq!(a, everything_trace(11, 400));
    assert_ne!(a, everything_trace(12, 400));
    let w = world(EVERYTHING, 3, 11);
    // 16 + 2 + 4 + 1 + 4 + 2·2 + 2 + 12·3·3 + 1.
    assert_eq!(w.layout().len(), 16 + 2 + 4 + 1 + 4 + 4 + 2 + 108 + 1);
}

// ---------------------------------------------------------------- validation

#[track_caller]
fn rejects(text: &str, key: &str) {
    let s = setup(text);
    let err = s
        .creature
        .validate()
        .and_then(|()| s.world.validate(&s.creature))
        .expect_err("must be rejected");
    assert_eq!(err.key, key, "{err}");
    assert!(World::new(&s.world, &s.creature, 1, rng(1)).is_err());
}

#[test]
fn bad_values_are_rejected_with_their_key() {
    rejects("[creature.eye]\nfov = 0", "creature.eye.fov");
    rejects("[creature.eye]\nfov = 361", "creature.eye.fov");
    rejects(
        "[creature.eye]\nvertical_fov = 180",
        "creature.eye.vertical_fov",
    );
    rejects("[creature.eye]\nwidth = 0", "creature.eye.width");
    rejects(
        "[creature.eye]\nwidth = 4096\nheight = 4096",
        "creature.eye.height",
    );
    rejects("[creature.eye]\neye_height = -1", "creature.eye.eye_height");
    rejects(
        "[creature.eye]\nbackground = [0, 2, 0]",
        "creature.eye.background[1]",
    );
    rejects("[creature.eye]\nrange = 0", "creature.eye.range");
    rejects("[creature]\ncolour = [0, 0, -1]", "creature.colour[2]");
    rejects("[creature]\nheight = nan", "creature.height");
    rejects("[creature.noise.smell]\nm = 1.5", "creature.noise.smell.m");
    rejects(
        "[creature.noise.eye]\nn_sigma = -1",
        "creature.noise.eye.n_sigma",
    );
    rejects(
        "[[world.landmarks]]\nposition = [inf, 0]",
        "world.landmarks[0].position[0]",
    );
    rejects(
        "[[world.areas]]\nregion = [0, 0, 10, 10]\n[[world.areas]]\nregion = [0, 0, 10, 400]",
        "world.areas[1].region",
    );
    rejects(
        "[[world.areas]]\nregion = [10, 0, 0, 10]",
        "world.areas[0].region",
    );
    rejects(
        "[[world.areas]]\nregion = [0, 0, 10, 10]\nintensity = -1",
        "world.areas[0].intensity",
    );
    rejects(
        "[world.kinds.rose]\nclass = \"food\"\ncolour = [0, 1.5, 0]",
        "world.kinds.rose.colour[1]",
    );
    rejects(
        "[world.kinds.nettle]\nclass = \"aversive\"\nheight = -2",
        "world.kinds.nettle.height",
    );
    rejects(
        "[creature.inputs]\nlandmarks = true",
        "creature.inputs.landmarks",
    );
    rejects("[creature.inputs]\nareas = true", "creature.inputs.areas");
}

#[test]
fn unknown_keys_and_wrong_lengths_are_refused() {
    for text in [
        "[creature.eye]\nfocus = 1",
        "[creature.noise.smel]\nn = 1",
        "[creature.noise.smell]\nsigma = 1",
        "[[world.landmarks]]\nposition = [1, 2]\nheight = 3",
        "[[world.landmarks]]\nposition = [1, 2, 3]",
        "[[world.areas]]\nregion = [0, 0, 1, 1]\nkind = \"deadly\"",
        "[creature.inputs]\nears = true",
        "[creature.eye]\nbackground = [0, 0]",
    ] {
        assert!(
            toml::from_str::<sim_common::Setup>(text).is_err(),
            "accepted {text}"
        );
    }
}

#[test]
fn creatures_without_eye_input_render_nothing() {
    let mut w = world(AREAS, 1, 1);
    assert_eq!(w.retina_size(), None);
    assert!(!w.render_eye(0, &mut [0.0; 48]));
}
