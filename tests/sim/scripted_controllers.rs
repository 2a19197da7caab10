//! Scripted controllers: the Braitenberg vehicle 2b turns towards a smell on either side and
//! finds its source; a constant controller drives as told.

use crate::sim_common::{assert_close, put, world};
use berry_evolve::sim::scripted::{Scripted, ScriptedSpec};
use berry_evolve::sim::World;

/// A rose smelling of receptor 1 at (150, 100), no range, gentle falloff, weak enough that
/// the vehicle's motors (base 0.02 + gain 0.5 x at most 0.4) never reach max_rpt.
const ROSE: &str = r#"
[world]
smell_c = 0.001

[world.kinds.rose]
class = "food"
odour = [1, 0, 0, 0, 0, 0, 0, 0]
intensity = 0.4
depletes = false

[[world.objects]]
kind = "rose"
position = [150, 100]

[world.start]
region = [250, 250, 260, 260]
"#;

fn vehicle(w: &World) -> Scripted {
    ScriptedSpec::Braitenberg {
        receptor: 1,
        gain: 0.5,
        base: 0.02,
    }
    .build(w.layout())
    .unwrap()
}

#[test]
fn vehicle_2b_turns_towards_a_smell_on_its_left_and_on_its_right() {
    // Facing +x from (100, 150), the rose at (150, 100) is up the screen: on the left.
    let mut w = world(ROSE, 1, 1);
    put(&mut w, 0, 100.0, 150.0, 0.0);
    let mut c = [vehicle(&w)];
    w.step(&mut c);
    let cmd = w.creatures()[0].command;
    assert!(
        cmd.right > cmd.left,
        "smell on the left speeds the right wheel: {cmd:?}"
    );
    // φ = (d_L − d_R)/w < 0: a counter-clockwise (left) turn, the heading gains −y.
    assert!(w.creatures()[0].pose.heading.y < 0.0);

    // Facing −y from (100, 150), the rose is to the right (+x).
    put(&mut w, 0, 100.0, 150.0, 270.0);
    w.step(&mut c);
    let cmd = w.creatures()[0].command;
    assert!(
        cmd.left > cmd.right,
        "smell on the right speeds the left wheel: {cmd:?}"
    );
    assert!(
        w.creatures()[0].pose.heading.x > 0.0,
        "turned right, towards +x"
    );
}

#[test]
fn vehicle_2b_finds_the_rose_and_a_blind_one_does_not() {
    let mut smelling = world(ROSE, 1, 2);
    put(&mut smelling, 0, 100.0, 150.0, 0.0);
    let mut c = [vehicle(&smelling)];
    let mut reached = None;
    for _ in 0..2000 {
        smelling.step(&mut c);
        if smelling.creatures()[0].food_detectors == [false; 4] {
            continue;
        }
        reached = Some(smelling.tick());
        break;
    }
    assert!(reached.is_some(), "the vehicle never touched the rose");

    // Driving straight on at the same base speed misses it.
    let mut blind = world(ROSE, 1, 2);
    put(&mut blind, 0, 100.0, 150.0, 0.0);
    let mut c = [ScriptedSpec::Constant {
        left: 0.02,
        right: 0.02,
    }
    .build(blind.layout())
    .unwrap()];
    for _ in 0..2000 {
        blind.step(&mut c);
        assert_eq!(blind.creatures()[0].food_detectors, [false; 4]);
    }
}

#[test]
fn constant_controller_drives_as_told() {
    let mut w = world(ROSE, 1, 3);
    put(&mut w, 0, 100.0, 150.0, 0.0);
    let mut c = [ScriptedSpec::Constant {
        left: 0.1,
        right: 0.1,
    }
    .build(w.layout())
    .unwrap()];
    w.step(&mut c);
    // 2π · w · 0.1 = 0.4π LU straight ahead.
    assert_close(
        w.creatures()[0].pose.position.x,
        100.0 + 0.4 * std::f64::consts::PI,
        "x",
    );
}

#[test]
fn a_braitenberg_vehicle_needs_smell_input() {
    let w = world("[creature.inputs]\nsmell = false", 1, 4);
    let e = ScriptedSpec::Braitenberg {
        receptor: 1,
        gain: 1.0,
        base: 0.0,
    }
    .build(w.layout())
    .unwrap_err();
    assert_eq!(e.key, "demo.controller.kind");
    assert!(e.reason.contains("smell"), "{e}");
}
