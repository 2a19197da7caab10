//! The `[world]`, `[creature]` and `[demo]` tables: a complete example parses, validates and
//! builds a world; bad input is rejected with the key that is wrong.

use crate::sim_common::rng;
use berry_evolve::sim::controller::SensorGroup;
use berry_evolve::sim::scripted::{DemoSpec, ScriptedSpec};
use berry_evolve::sim::spec::KindSpec;
use berry_evolve::sim::{CreatureSpec, Eating, PlacementError, World, WorldSpec};

/// Every key of the three tables, as the documentation shows them.
const COMPLETE: &str = r#"
[world]
arena = [300, 300]          # width, height in LU
boundary_walls = true
slippery_walls = false
wall_shock = false
smell_c = 0.01              # c of eq. 25, 1/LU²
search_steps = 20

[[world.walls]]
from = [100, 50]
to = [100, 250]
opaque = true
colour = [0.8, 0.2, 0.2]
height = 10

[[world.walls]]
from = [200, 150]
to = [280, 150]
opaque = false

[world.kinds.apple]
class = "food"
radius = 0
substance = [5, 0, 0, 0]
capacity = [5, 0, 0, 0]
bite = [1, 0, 0, 0]
regen = [0.01, 0, 0, 0]
depletes = true
smell_follows_amount = true
odour = [1, 0, 0, 0, 0, 0, 0, 0]
intensity = 1.0
range = 80

[world.kinds.nettle]
class = "aversive"
radius = 2
odour = [0, 1, 0, 0, 0, 0, 0, 0]
intensity = 0.5

[[world.objects]]
kind = "apple"
position = [50, 50]

[[world.place]]
kind = "apple"
count = 10
region = [110, 10, 290, 290]
min_spacing = 20
grid = 5

[[world.place]]
kind = "nettle"
count = 5
min_spacing = 10

[world.start]
region = [10, 10, 90, 290]
heading = 90                # degrees; absent = random

[creature]
diameter = 6
whisker_angle = 45          # degrees
whisker_length = 5
a = 2
wheel = 2
odour = [0, 0, 1, 0, 0, 0, 0, 0]
odour_intensity = 0.2
max_rpt = 0.25
eating = "action"
inhibit_smell_on_whisker = false
initial_metabolism = [1, 0, 0, 0]
decay_per_tick = [0.001, 0, 0, 0]
decay_per_lu = [0.0005, 0, 0, 0]

[creature.inputs]
smell = true
whiskers = true
food = true
shock = true
metabolism = true
bias = true

[demo]
creatures = 3

[demo.controller]
kind = "braitenberg"
receptor = 1
gain = 1.5
base = 0.05
"#;

#[derive(Debug, serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    world: WorldSpec,
    creature: CreatureSpec,
    demo: DemoSpec,
}

#[test]
fn complete_example_parses_validates_and_builds() {
    let file: File = toml::from_str(COMPLETE).unwrap_or_else(|e| panic!("{e}"));
    file.creature.validate().unwrap();
    file.world.validate(&file.creature).unwrap();
    file.demo.validate().unwrap();
    assert_eq!(file.creature.eating, Eating::Action);
    assert!(file.creature.eats_by_action());
    assert_eq!(
        file.world.walls[1].colour,
        [0.5, 0.5, 0.5],
        "default colour"
    );
    assert!(matches!(file.world.kinds["nettle"], KindSpec::Aversive(_)));
    // Written back out, the tables read back the same (config hashes depend on it).
    let text = toml::to_string(&file.world).unwrap();
    assert_eq!(
        toml::from_str::<WorldSpec>(&text).unwrap(),
        file.world,
        "{text}"
    );
    let text = toml::to_string(&file.creature).unwrap();
    assert_eq!(
        toml::from_str::<CreatureSpec>(&text).unwrap(),
        file.creature,
        "{text}"
    );
    let text = toml::to_string(&file.demo).unwrap();
    assert_eq!(
        toml::from_str::<DemoSpec>(&text).unwrap(),
        file.demo,
        "{text}"
    );
    let layout = file.creature.layout(&file.world);
    assert_eq!(layout.range(SensorGroup::Metabolism), Some(23..27));
    let controller = file.demo.controller.build(&layout).unwrap();
    let w = World::new(&file.world, &file.creature, file.demo.creatures, rng(1)).unwrap();
    assert_eq!(w.walls().len(), 6);
    assert_eq!(w.food().len(), 11);
    assert_eq!(w.aversives().len(), 5);
    assert_eq!(w.kinds(), ["apple", "nettle"]);
    assert_eq!(w.creatures().len(), 3);
    for c in w.creatures() {
        assert!(
            c.pose.heading.y > 0.999_999,
            "heading 90° points down the screen"
        );
    }
    let mut controllers = vec![controller; 3];
    let mut w = w;
    for _ in 0..50 {
        w.step(&mut controllers);
    }
    assert_eq!(w.tick(), 50);
}

#[test]
fn defaults_are_the_reports() {
    let world: WorldSpec = toml::from_str("").unwrap();
    assert_eq!(world, WorldSpec::default());
    assert_eq!(world.arena, [300.0, 300.0]);
    assert!(world.boundary_walls);
    let creature: CreatureSpec = toml::from_str("").unwrap();
    assert_eq!(
        (
            creature.diameter,
            creature.whisker_angle,
            creature.whisker_length,
            creature.a,
            creature.wheel
        ),
        (6.0, 45.0, 5.0, 2.0, 2.0)
    );
    creature.validate().unwrap();
    world.validate(&creature).unwrap();
    let w = World::new(&world, &creature, 1, rng(2)).unwrap();
    assert_eq!(w.walls().len(), 4);
    assert!(w.food().is_empty());
}

/// Parses `text` as a `[world]` table and validates it; the error text.
fn world_error(text: &str) -> String {
    match toml::from_str::<WorldSpec>(text) {
        Err(e) => e.to_string(),
        Ok(spec) => match spec.validate(&CreatureSpec::default()) {
            Err(e) => e.to_string(),
            Ok(()) => panic!("accepted:\n{text}"),
        },
    }
}

#[track_caller]
fn rejects(text: &str, needles: &[&str]) {
    let e = world_error(text);
    for n in needles {
        assert!(e.contains(n), "error should mention `{n}`:\n{e}");
    }
}

const APPLE: &str = "[kinds.apple]\nclass = \"food\"\n";

#[test]
fn unknown_keys_are_rejected() {
    rejects("arena = [300, 300]\nwals = []", &["wals"]);
    rejects(&format!("{APPLE}radius = 1\nradious = 2"), &["radious"]);
    // A food-only key on an aversive kind.
    rejects(
        "[kinds.thorn]\nclass = \"aversive\"\nbite = [1, 1, 1, 1]",
        &["bite"],
    );
    rejects("[kinds.thorn]\nclass = \"spiky\"", &["spiky"]);
    rejects("[start]\nheadings = 3", &["headings"]);
    rejects(
        "[[walls]]\nfrom = [1, 1]\nto = [2, 2]\ncolor = [1, 0, 0]",
        &["color"],
    );
}

#[test]
fn wrong_types_are_rejected() {
    rejects("arena = \"big\"", &["arena"]);
    rejects("arena = [300, 300, 300]", &["arena"]);
    rejects("boundary_walls = 1", &["boundary_walls"]);
    rejects(&format!("{APPLE}substance = [1, 2]"), &["substance"]);
    // The toml crate alone would drop extra elements silently.
    rejects(
        &format!("{APPLE}odour = [0, 0, 0, 0, 0, 0, 0, 0, 1]"),
        &["odour", "length 9"],
    );
    rejects(
        "[start]\nregion = [0, 0, 10, 10, 20]",
        &["region", "length 5"],
    );
    rejects("[[place]]\nkind = \"apple\"\ncount = -3", &["count"]);
}

#[test]
fn bad_values_name_their_key() {
    rejects(
        &format!("{APPLE}radius = -1"),
        &["`world.kinds.apple.radius`", "must be >= 0"],
    );
    rejects(
        "[[walls]]\nfrom = [1, 1]\nto = [2, 2]\n[[walls]]\nfrom = [10, 20]\nto = [10, 20]",
        &["`world.walls[1].to`", "length"],
    );
    rejects(
        &format!("{APPLE}[[objects]]\nkind = \"apple\"\nposition = [150, 301]"),
        &["`world.objects[0].position`", "outside the arena"],
    );
    rejects(
        "[[walls]]\nfrom = [-1, 1]\nto = [2, 2]",
        &["`world.walls[0].from`", "outside the arena"],
    );
    rejects(
        &format!("{APPLE}[[place]]\nkind = \"pear\"\ncount = 1"),
        &["`world.place[0].kind`", "pear", "apple"],
    );
    rejects(
        &format!("{APPLE}[[place]]\nkind = \"apple\"\ncount = 1\nregion = [50, 50, 10, 10]"),
        &["`world.place[0].region`", "x0 <= x1"],
    );
    rejects(
        &format!("{APPLE}[[place]]\nkind = \"apple\"\ncount = 1\nregion = [0, 0, 400, 10]"),
        &["`world.place[0].region`", "outside"],
    );
    rejects(
        &format!("{APPLE}[[place]]\nkind = \"apple\"\ncount = 100001"),
        &["`world.place[0].count`", "at most 100000"],
    );
    rejects(
        &format!("{APPLE}[[place]]\nkind = \"apple\"\ncount = 1\nregion = [1, 1, 2, 2]\ngrid = 5"),
        &["`world.place[0].grid`", "no point"],
    );
    rejects(
        &format!("{APPLE}substance = [2, 0, 0, 0]\ncapacity = [1, 0, 0, 0]"),
        &["`world.kinds.apple.capacity[0]`"],
    );
    rejects(
        &format!("{APPLE}substance = [0, 0, 0, 0]\nsmell_follows_amount = true"),
        &["`world.kinds.apple.smell_follows_amount`"],
    );
    rejects(
        &format!("{APPLE}odour = [0, 0, 0, nan, 0, 0, 0, 0]"),
        &["`world.kinds.apple.odour[3]`", "finite"],
    );
    rejects(&format!("{APPLE}range = 0"), &["`world.kinds.apple.range`"]);
    rejects("smell_c = inf", &["`world.smell_c`"]);
    rejects("search_steps = 0", &["`world.search_steps`"]);
    rejects("arena = [300, 0]", &["`world.arena[1]`"]);
    rejects(
        "arena = [300, 5]",
        &["`world.arena[1]`", "creature diameter"],
    );
    rejects(
        "[start]\nregion = [10, 10, 20, 310]",
        &["`world.start.region`"],
    );
    rejects("[start]\nheading = nan", &["`world.start.heading`"]);
}

#[test]
fn bad_creature_values_name_their_key() {
    let cases = [
        ("diameter = 0", "creature.diameter"),
        ("whisker_angle = 200", "creature.whisker_angle"),
        ("whisker_length = -1", "creature.whisker_length"),
        ("wheel = 0", "creature.wheel"),
        ("max_rpt = -0.1", "creature.max_rpt"),
        ("odour = [0, 0, 0, 0, 0, 0, 0, -1]", "creature.odour[7]"),
        ("decay_per_lu = [0, inf, 0, 0]", "creature.decay_per_lu[1]"),
    ];
    for (text, key) in cases {
        let spec: CreatureSpec = toml::from_str(text).unwrap();
        let e = spec.validate().unwrap_err();
        assert_eq!(e.key, key, "{text}: {e}");
    }
    let e = toml::from_str::<CreatureSpec>("eating = \"always\"").unwrap_err();
    assert!(e.to_string().contains("always"), "{e}");
    let e = toml::from_str::<CreatureSpec>("initial_metabolism = [1, 2, 3, 4, 5]").unwrap_err();
    assert!(e.to_string().contains("initial_metabolism"), "{e}");
    let e = toml::from_str::<CreatureSpec>("diameterr = 6").unwrap_err();
    assert!(e.to_string().contains("diameterr"), "{e}");
}

#[test]
fn world_new_refuses_an_invalid_spec_instead_of_panicking() {
    let mut spec = WorldSpec::default();
    spec.objects.push(berry_evolve::sim::spec::ObjectSpec {
        kind: "ghost".into(),
        position: [1.0, 1.0],
    });
    match World::new(&spec, &CreatureSpec::default(), 1, rng(3)) {
        Err(PlacementError::Invalid(e)) => assert_eq!(e.key, "world.objects[0].kind"),
        other => panic!("expected an invalid-spec error, got {other:?}"),
    }
}

#[test]
fn demo_table_is_strict() {
    let demo: DemoSpec = toml::from_str("").unwrap();
    assert_eq!(demo.creatures, 1);
    let demo: DemoSpec =
        toml::from_str("[controller]\nkind = \"constant\"\nleft = 0.2\nright = 0.1").unwrap();
    assert_eq!(
        demo.controller,
        ScriptedSpec::Constant {
            left: 0.2,
            right: 0.1
        }
    );
    for bad in [
        "creaturs = 2",
        "[controller]\nkind = \"constant\"\nleft = 0.2\nright = 0.1\ngain = 1",
        "[controller]\nkind = \"rocket\"",
        "[controller]\nkind = \"braitenberg\"\nreceptor = 1",
    ] {
        assert!(toml::from_str::<DemoSpec>(bad).is_err(), "accepted {bad:?}");
    }
    let demo: DemoSpec =
        toml::from_str("[controller]\nkind = \"braitenberg\"\nreceptor = 9\ngain = 1\nbase = 0")
            .unwrap();
    assert_eq!(demo.validate().unwrap_err().key, "demo.controller.receptor");
    let demo: DemoSpec = toml::from_str("creatures = 0").unwrap();
    assert_eq!(demo.validate().unwrap_err().key, "demo.creatures");
}
