//! Locked doors, teleporters, wanderers and predators through the running world: hand-computed
//! tick numbers, blocked exits, kills and shocks in and out of safe areas, strike radii,
//! validation key paths, and reproducibility with everything on.

use crate::sim_common;
use crate::sim_common::{put, rng, setup, world, Fixed, Still};
use berry_evolve::geometry::Vec2;
use berry_evolve::record::trace::TraceWriter;
use berry_evolve::sim::controller::{MotorCommand, SensorGroup};
use berry_evolve::sim::motion::Pose;
use berry_evolve::sim::scripted::{Scripted, ScriptedSpec};
use berry_evolve::sim::World;

fn forward(rpt: f64) -> Fixed {
    Fixed(MotorCommand {
        left: rpt,
        right: rpt,
        eat: 0.0,
    })
}

// ---------------------------------------------------------------- doors

// A door across the whole arena at x = 150; its trigger at (100, 150), radius 5. The body
// radius is 3 (default diameter 6).
const DOOR: &str = r#"
[[world.doors]]
from = [150, 0]
to = [150, 300]
trigger = [100, 150]
trigger_radius = 5
open_ticks = 3
"#;

#[test]
fn a_closed_door_blocks_and_is_felt() {
    let mut w = world(DOOR, 1, 1);
    assert!(!w.door_open(0));
    put(&mut w, 0, 140.0, 150.0, 0.0);
    let mut c = [forward(0.25)];
    for _ in 0..20 {
        w.step(&mut c);
    }
    let x = w.creatures()[0].pose.position.x;
    assert!(x < 147.0 && x > 146.0, "stopped by the door: x = {x}");
    assert!(w.creatures()[0].blocked);
    // Whiskers (length 5 at ±45° by default) reach the door from 3 LU away.
    assert_eq!(w.creatures()[0].whiskers, [true, true]);
}

#[test]
fn a_door_opens_on_trigger_contact_and_closes_after_its_time() {
    let mut w = world(DOOR, 1, 1);
    // Body (radius 3) at distance 8 from the trigger centre: touching (3 + 5 = 8).
    put(&mut w, 0, 108.0, 150.0, 0.0);
    w.step(&mut [Still]); // tick 0: contact, open until tick 0 + 3.
    assert!(w.door_open(0));
    put(&mut w, 0, 50.0, 50.0, 0.0); // away from the trigger
    let mut open = Vec::new();
    for _ in 1..=5 {
        w.step(&mut [Still]); // ticks 1..=5
        open.push(w.door_open(0));
    }
    // Open through tick 3, closed from the start of tick 4.
    assert_eq!(open, [true, true, true, false, false]);
    // Re-contact restarts the count.
    put(&mut w, 0, 108.0, 150.0, 0.0);
    w.step(&mut [Still]); // tick 5: open until 8
    put(&mut w, 0, 50.0, 50.0, 0.0);
    w.step(&mut [Still]); // tick 6
    put(&mut w, 0, 108.0, 150.0, 0.0);
    w.step(&mut [Still]); // tick 7: open until 10
    put(&mut w, 0, 50.0, 50.0, 0.0);
    let mut open = Vec::new();
    for _ in 8..=11 {
        w.step(&mut [Still]);
        open.push(w.door_open(0));
    }
    assert_eq!(open, [true, true, true, false]);
}

#[test]
fn an_open_door_lets_a_creature_through_and_is_not_felt() {
    let text = DOOR.replace("open_ticks = 3", "open_ticks = 100");
    let mut w = world(&text, 1, 1);
    put(&mut w, 0, 108.0, 150.0, 0.0);
    w.step(&mut [Still]);
    assert!(w.door_open(0));
    put(&mut w, 0, 140.0, 150.0, 0.0);
    let mut c = [forward(0.25)];
    w.step(&mut c);
    assert_eq!(w.creatures()[0].whiskers, [false, false]);
    for _ in 0..10 {
        w.step(&mut c);
    }
    let x = w.creatures()[0].pose.position.x;
    assert!(x > 160.0, "passed the open door: x = {x}");
}

// ---------------------------------------------------------------- teleporters

const TELEPORTER: &str = r#"
[[world.teleporters]]
entry = [100, 100]
radius = 5
exit = [200, 200]
exit_heading = 90
odour = [0, 0, 0, 0, 0, 0, 0, 1]
intensity = 1
"#;

#[test]
fn contact_with_the_entry_teleports_to_the_exit() {
    let mut w = world(TELEPORTER, 1, 1);
    put(&mut w, 0, 108.0, 100.0, 0.0);
    w.step(&mut [Still]);
    let p = w.creatures()[0].pose;
    assert_eq!(p.position, Vec2::new(200.0, 200.0));
    assert!(p.heading.x.abs() < 1e-15 && (p.heading.y - 1.0).abs() < 1e-15);
    // Not touching: stays.
    put(&mut w, 0, 108.5, 100.0, 0.0);
    w.step(&mut [Still]);
    assert_eq!(w.creatures()[0].pose.position, Vec2::new(108.5, 100.0));
    // The entry smells (receptor 8).
    put(&mut w, 0, 130.0, 100.0, 180.0);
    w.set_full_sensing(true);
    w.step(&mut [Still]);
    assert!(w.creatures()[0].smell[0][7] > 0.0);
}

#[test]
fn a_blocked_exit_keeps_the_creature_in_place() {
    let mut w = world(TELEPORTER, 2, 1);
    put(&mut w, 0, 108.0, 100.0, 0.0);
    put(&mut w, 1, 205.0, 200.0, 0.0); // body touches a body at the exit
    w.step(&mut [Still, Still]);
    assert_eq!(w.creatures()[0].pose.position, Vec2::new(108.0, 100.0));
    // A wall at the exit blocks it too.
    let text = format!("{TELEPORTER}\n[[world.walls]]\nfrom = [202, 150]\nto = [202, 250]\n");
    let mut w = world(&text, 1, 1);
    put(&mut w, 0, 108.0, 100.0, 0.0);
    w.step(&mut [Still]);
    assert_eq!(w.creatures()[0].pose.position, Vec2::new(108.0, 100.0));
}

// ---------------------------------------------------------------- predators

const CHASE: &str = r#"
[[world.predators]]
strategy = "chase"
start = [50, 150]
max_rpt = 0.25
"#;

/// The tick (0-based) at which the chase predator of `text`, put at (50, 150) facing +y,
/// kills a still creature at (150, 150), with the world `w` it ran in.
fn kill_tick(text: &str) -> (Option<u64>, World) {
    let mut w = world(text, 1, 1);
    w.set_actor_pose(
        0,
        Pose {
            position: Vec2::new(50.0, 150.0),
            heading: Vec2::new(0.0, 1.0),
        },
    );
    put(&mut w, 0, 150.0, 150.0, 0.0);
    for t in 0..300 {
        w.step(&mut [Still]);
        if !w.creatures()[0].alive {
            return (Some(t), w);
        }
    }
    (None, w)
}

#[test]
fn a_chase_predator_reaches_a_still_creature_and_kills_it() {
    let (died, w) = kill_tick(CHASE);
    // 100 − 6 LU at π LU per tick, after turning a quarter turn: about 32 ticks.
    let t = died.expect("the predator kills the creature");
    assert!((25..60).contains(&t), "died at tick {t}");
    let d = w.actors()[0]
        .pose
        .position
        .distance_squared(w.creatures()[0].pose.position);
    assert!(d <= 36.0, "bodies touch at the kill: d² = {d}");
}

#[test]
fn a_sleeping_predator_neither_moves_smells_nor_kills_until_it_wakes() {
    let smelly = format!("{CHASE}odour = [0, 0, 0, 0, 0, 0, 1, 0]\nintensity = 1\n");
    let (awake_kill, _) = kill_tick(&smelly);
    let awake_kill = awake_kill.expect("the awake predator kills");
    // Asleep for exactly 20 ticks: the same chase, 20 ticks later.
    let sleepy = format!("{smelly}asleep = [20, 20]\n");
    let (kill, _) = kill_tick(&sleepy);
    assert_eq!(kill, Some(awake_kill + 20));
    let mut w = world(&sleepy, 1, 1);
    put(&mut w, 0, 150.0, 150.0, 0.0);
    let start = w.actors()[0].pose;
    let thing = w.actors()[0].thing;
    for step in 1..=19 {
        w.step(&mut [Still]);
        let pose = w.actors()[0].pose;
        assert_eq!(pose.position, start.position, "moved asleep, step {step}");
        assert!(
            pose.heading.distance(start.heading) < 1e-12,
            "turned asleep, step {step}"
        );
        assert!(
            w.things()[thing].smell.silent,
            "smelled asleep, step {step}"
        );
    }
    w.step(&mut [Still]);
    assert!(w.actors()[0].awake());
    assert!(!w.things()[thing].smell.silent);
    // Lying against a creature it does not kill it while asleep.
    let text = format!("{CHASE}asleep = [50, 50]\n");
    let mut w = world(&text, 1, 1);
    put(&mut w, 0, 54.0, 150.0, 0.0);
    for _ in 0..49 {
        w.step(&mut [Still]);
    }
    assert!(w.creatures()[0].alive);
}

#[test]
fn a_predators_sleep_is_drawn_per_world_within_its_range() {
    let text = format!("{CHASE}asleep = [10, 30]\n");
    let sleeps: Vec<u64> = (1..=40)
        .map(|seed| world(&text, 1, seed).actors()[0].asleep)
        .collect();
    assert!(sleeps.iter().all(|s| (10..=30).contains(s)), "{sleeps:?}");
    assert!(sleeps.iter().any(|&s| s != sleeps[0]), "{sleeps:?}");
}

#[test]
fn a_chase_predator_spares_a_creature_in_a_safe_area() {
    let text =
        format!("{CHASE}\n[[world.areas]]\nregion = [140, 140, 160, 160]\nkind = \"safe\"\n");
    let mut w = world(&text, 1, 1);
    put(&mut w, 0, 150.0, 150.0, 0.0);
    for _ in 0..300 {
        w.step(&mut [Still]);
    }
    assert!(w.creatures()[0].alive);
}

const AIR: &str = r#"
[[world.air_predators]]
speed = 1
strike_radius = 10
"#;

#[test]
fn an_air_predator_strikes_inside_its_radius_only() {
    let mut w = world(AIR, 2, 1);
    w.set_flyer(0, Vec2::new(100.0, 100.0), Vec2::new(0.0, 0.0));
    put(&mut w, 0, 110.0, 100.0, 0.0); // exactly at the strike radius: inside
    put(&mut w, 1, 100.0, 110.001, 0.0); // just outside
    w.step(&mut [Still, Still]);
    assert!(!w.creatures()[0].alive);
    assert!(w.creatures()[1].alive);
    // Dead creatures are no longer attacked, nor do they move or age.
    let age = w.creatures()[0].age;
    w.step(&mut [Still, Still]);
    assert_eq!(w.creatures()[0].age, age);
}

#[test]
fn air_predators_fly_across_and_reenter() {
    let mut w = world("[[world.air_predators]]\nspeed = 50\n", 1, 3);
    put(&mut w, 0, 5.0, 5.0, 0.0);
    let mut entries = 0;
    let mut last = w.flyers()[0].position;
    for _ in 0..100 {
        w.step(&mut [Still]);
        let p = w.flyers()[0].position;
        assert!(p.x >= 0.0 && p.y >= 0.0 && p.x <= 300.0 && p.y <= 300.0);
        if p.distance_squared(last) > 51.0 * 51.0 {
            entries += 1;
        }
        last = p;
    }
    assert!(entries >= 5, "re-entered {entries} times");
}

#[test]
fn a_paused_air_predator_is_away_for_its_pause_and_neither_strikes_nor_smells() {
    // pause = [5, 5]: it waits 5 ticks before its first flight. Its strike radius covers the
    // whole arena, so the creature lives exactly as long as it is away: after steps 1-4 it is
    // alive and the raider silent, on step 5 the raider enters and strikes.
    let text = "[[world.air_predators]]\nspeed = 50\nstrike_radius = 1000\npause = [5, 5]\n\
                odour = [0, 0, 0, 0, 0, 0, 1, 0]\nintensity = 1\n";
    let mut w = world(text, 1, 3);
    put(&mut w, 0, 150.0, 150.0, 0.0);
    let thing = w.flyers()[0].thing;
    for step in 1..=4 {
        assert!(!w.flyers()[0].in_flight());
        w.step(&mut [Still]);
        assert!(w.creatures()[0].alive, "struck while away, step {step}");
        assert!(
            w.things()[thing].smell.silent,
            "smelled while away, step {step}"
        );
    }
    w.step(&mut [Still]);
    assert!(w.flyers()[0].in_flight());
    assert!(!w.things()[thing].smell.silent);
    assert!(!w.creatures()[0].alive);
}

#[test]
fn a_paused_air_predator_waits_between_min_and_max_ticks_between_flights() {
    // At 50 LU per tick a flight across 300 LU lasts at most 9 ticks; each wait is drawn from
    // [20, 40], the first one included.
    let text = "[[world.air_predators]]\nspeed = 50\npause = [20, 40]\n";
    let mut w = world(text, 1, 3);
    put(&mut w, 0, 5.0, 5.0, 0.0);
    let mut waits = Vec::new();
    let mut run = 0;
    for _ in 0..2000 {
        if w.flyers()[0].in_flight() {
            if run > 0 {
                waits.push(run);
            }
            run = 0;
        } else {
            run += 1;
        }
        w.step(&mut [Still]);
    }
    assert!(waits.len() >= 40, "{} flights", waits.len());
    assert!(waits.iter().all(|w| (20..=40).contains(w)), "{waits:?}");
    assert!(
        waits.iter().any(|&w| w != waits[0]),
        "the waits are drawn: {waits:?}"
    );
}

#[test]
fn the_shock_effect_sets_the_shock_sensor() {
    let text = AIR.replace(
        "strike_radius = 10",
        "strike_radius = 10\neffect = \"shock\"",
    );
    let mut w = world(&text, 1, 1);
    w.set_flyer(0, Vec2::new(100.0, 100.0), Vec2::new(0.0, 0.0));
    put(&mut w, 0, 105.0, 100.0, 0.0);
    w.step(&mut [Still]);
    let c = &w.creatures()[0];
    assert!(c.alive && c.shocked);
    assert_eq!(c.shock_ticks, 1);
    let r = w.layout().range(SensorGroup::Shock).unwrap();
    assert_eq!(w.observation(0)[r], [1.0]);
    // Out of reach: the shock ends.
    put(&mut w, 0, 200.0, 200.0, 0.0);
    w.step(&mut [Still]);
    assert!(!w.creatures()[0].shocked);
}

#[test]
fn a_ground_shock_predator_on_patrol_shocks_in_passing() {
    let text = r#"
[[world.predators]]
strategy = "patrol"
waypoints = [[100, 150], [200, 150]]
effect = "shock"
start = [100, 150]
max_rpt = 0.25
"#;
    let mut w = world(text, 1, 1);
    put(&mut w, 0, 150.0, 152.0, 90.0);
    let mut shocked = 0;
    for _ in 0..200 {
        w.step(&mut [Still]);
        shocked += u32::from(w.creatures()[0].shocked);
    }
    assert!(w.creatures()[0].alive);
    assert!(shocked > 0);
}

// ---------------------------------------------------------------- wanderers

const WANDERERS: &str = r#"
[world.wanderers]
count = 6
max_rpt = 0.3
hold_ticks = [3, 10]
odour = [1, 0, 0, 0, 0, 0, 0, 0]
intensity = 1
"#;

#[test]
fn wanderers_move_stay_clear_of_bodies_and_smell() {
    let mut w = world(WANDERERS, 2, 5);
    w.set_full_sensing(true);
    let start: Vec<Vec2> = w.actors().iter().map(|a| a.pose.position).collect();
    let r = w.creature_radius();
    let mut c = [forward(0.2), forward(0.0)];
    for _ in 0..300 {
        w.step(&mut c);
        let bodies: Vec<Vec2> = w
            .actors()
            .iter()
            .map(|a| a.pose.position)
            .chain(w.creatures().iter().map(|c| c.pose.position))
            .collect();
        for (i, a) in bodies.iter().enumerate() {
            for b in &bodies[i + 1..] {
                assert!(a.distance_squared(*b) > 4.0 * r * r - 1e-9);
            }
        }
    }
    let moved = w
        .actors()
        .iter()
        .zip(&start)
        .filter(|(a, s)| a.pose.position.distance_squared(**s) > 1.0)
        .count();
    assert!(moved >= 5, "{moved} wanderers moved");
    assert!(w.creatures()[1].smell[0][0] > 0.0 || w.creatures()[1].smell[1][0] > 0.0);
}

// ---------------------------------------------------------------- everything on

const EVERYTHING: &str = r#"
[[world.walls]]
from = [100, 0]
to = [100, 120]

[[world.doors]]
from = [100, 120]
to = [100, 180]
trigger = [60, 150]

[[world.teleporters]]
entry = [250, 250]
exit = [50, 50]
odour = [0, 1, 0, 0, 0, 0, 0, 0]
intensity = 1

[world.wanderers]
count = 3
odour = [0, 0, 1, 0, 0, 0, 0, 0]
intensity = 1

[[world.predators]]
strategy = "chase"
effect = "shock"
odour = [0, 0, 0, 1, 0, 0, 0, 0]
intensity = 1

[[world.predators]]
strategy = "wander"
effect = "shock"

[[world.air_predators]]
effect = "shock"
strike_radius = 15

[[world.areas]]
region = [0, 0, 60, 60]
kind = "safe"

[world.kinds.food]
class = "food"
substance = [1, 0, 0, 0]
radius = 4
odour = [1, 0, 0, 0, 0, 0, 0, 0]
intensity = 1

[[world.place]]
kind = "food"
count = 10

[creature.inputs]
areas = true
eye = true

[creature.eye]
width = 8
height = 1

[creature.noise.smell]
n = 0.1
n_sigma = 0.05
m = 0.2
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
        ScriptedSpec::Constant {
            left: 0.2,
            right: 0.15,
        },
        ScriptedSpec::Constant {
            left: 0.25,
            right: 0.25,
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
        for a in w.actors() {
            obs.extend(a.pose.position.x.to_le_bytes());
            obs.extend(a.pose.position.y.to_le_bytes());
        }
        for f in w.flyers() {
            obs.extend(f.position.x.to_le_bytes());
        }
    }
    let mut bytes = out.into_inner().unwrap();
    bytes.extend(obs);
    bytes
}

#[test]
fn everything_on_same_seed_same_bytes() {
    let a = everything_trace(21, 400);
    assert_eq!(a, everything_trace(21, 400));
    assert_ne!(a, everything_trace(22, 400));
}

// ---------------------------------------------------------------- validation

#[track_caller]
fn rejects(text: &str, key: &str) {
    let s = setup(text);
    let err = s.world.validate(&s.creature).expect_err("must be rejected");
    assert_eq!(err.key, key, "{err}");
    assert!(World::new(&s.world, &s.creature, 1, rng(1)).is_err());
}

#[test]
fn bad_values_are_rejected_with_their_key() {
    rejects(
        "[[world.doors]]\nfrom = [1, 1]\nto = [1, 1]\ntrigger = [5, 5]",
        "world.doors[0].to",
    );
    rejects(
        "[[world.doors]]\nfrom = [1, 1]\nto = [1, 9]\ntrigger = [5, 5]\nopen_ticks = 0",
        "world.doors[0].open_ticks",
    );
    rejects(
        "[[world.doors]]\nfrom = [1, 1]\nto = [1, 9]\ntrigger = [5, 500]",
        "world.doors[0].trigger",
    );
    rejects(
        "[[world.teleporters]]\nentry = [5, 5]\nexit = [5, 5]\nradius = -1",
        "world.teleporters[0].radius",
    );
    rejects(
        "[[world.teleporters]]\nentry = [5, 5]\nexit = [5, 5]\nexit_heading = nan",
        "world.teleporters[0].exit_heading",
    );
    rejects(
        "[world.wanderers]\ncount = 1\nhold_ticks = [5, 2]",
        "world.wanderers.hold_ticks[1]",
    );
    rejects(
        "[world.wanderers]\ncount = 1\nhold_ticks = [0, 2]",
        "world.wanderers.hold_ticks[0]",
    );
    rejects(
        "[[world.predators]]\nstrategy = \"patrol\"",
        "world.predators[0].waypoints",
    );
    rejects(
        "[[world.predators]]\nmax_rpt = -1",
        "world.predators[0].max_rpt",
    );
    rejects(
        "[[world.air_predators]]\nspeed = 0",
        "world.air_predators[0].speed",
    );
    rejects(
        "[[world.air_predators]]\nintensity = -1",
        "world.air_predators[0].intensity",
    );
    rejects(
        "[[world.air_predators]]\npause = [5, 2]",
        "world.air_predators[0].pause[1]",
    );
    rejects(
        "[[world.predators]]\nasleep = [5, 2]",
        "world.predators[0].asleep[1]",
    );
    for bad in [
        "[[world.doors]]\nfrom = [1, 1]\nto = [1, 9]\ntrigger = [5, 5]\nwidth = 3",
        "[world.wanderers]\nspeed = 1",
        "[[world.predators]]\nstrategy = \"hunt\"",
        "[[world.air_predators]]\neffect = \"stun\"",
        "[[world.teleporters]]\nentry = [5, 5, 5]\nexit = [5, 5]",
        "[[world.predators]]\nstrategy = \"patrol\"\nwaypoints = [[5, 5, 5]]",
        "[world.wanderers]\nhold_ticks = [1, 2, 3]",
        "[[world.air_predators]]\npause = [1]",
    ] {
        let parsed: Result<sim_common::Setup, _> = toml::from_str(bad);
        assert!(parsed.is_err(), "{bad}");
    }
}

// ---------------------------------------------------------------- what senses meet

#[test]
fn a_closed_door_is_seen_and_hides_smell_an_open_one_neither() {
    let text = r#"
[[world.doors]]
from = [150, 0]
to = [150, 300]
colour = [0.6, 0.3, 0.1]
trigger = [100, 250]
trigger_radius = 5
open_ticks = 100

[world.kinds.rose]
class = "food"
radius = 1
odour = [1, 0, 0, 0, 0, 0, 0, 0]
intensity = 1

[[world.objects]]
kind = "rose"
position = [200, 150]

[creature.inputs]
eye = true

[creature.eye]
width = 3
fov = 10
"#;
    let mut w = world(text, 1, 1);
    w.set_full_sensing(true);
    let n = 3 * 3;
    let mut pixels = vec![0.0; n];
    put(&mut w, 0, 120.0, 150.0, 0.0);
    w.step(&mut [Still]);
    assert_eq!(
        w.creatures()[0].smell,
        [[0.0; 8]; 2],
        "the door hides the rose"
    );
    assert!(w.render_eye(0, &mut pixels));
    let door_colour = |p: &[f64]| p.contains(&0.6) && p.contains(&0.1);
    assert!(door_colour(&pixels), "{pixels:?}");
    put(&mut w, 0, 108.0, 250.0, 0.0); // touch the trigger
    w.step(&mut [Still]);
    assert!(w.door_open(0));
    put(&mut w, 0, 120.0, 150.0, 0.0);
    w.step(&mut [Still]);
    assert!(w.creatures()[0].smell[0][0] > 0.0, "the rose is smelled");
    assert!(w.render_eye(0, &mut pixels));
    assert!(!door_colour(&pixels), "{pixels:?}");
}

#[test]
fn triggers_entries_and_wanderers_are_felt_predators_seen() {
    let text = r#"
[[world.doors]]
from = [290, 0]
to = [290, 20]
trigger = [103.5, 95.5]
trigger_radius = 1

[[world.teleporters]]
entry = [103.5, 204.5]
radius = 1
exit = [250, 250]

[[world.predators]]
strategy = "wander"
max_rpt = 0
start = [60, 60]
colour = [0.9, 0.1, 0.2]

[creature.inputs]
eye = true

[creature.eye]
width = 3
fov = 10
"#;
    let mut w = world(text, 1, 1);
    // Whiskers of length 5 at ±45° from (100, y) facing east end at (103.54, y ∓ 3.54):
    // the trigger lies on the left one, the entry on the right one, both out of the body's
    // reach (5.7 LU > 3 + 1).
    put(&mut w, 0, 100.0, 100.0, 0.0);
    w.step(&mut [Still]);
    assert_eq!(w.creatures()[0].whiskers, [true, false]);
    assert!(!w.door_open(0));
    put(&mut w, 0, 100.0, 200.0, 0.0);
    w.step(&mut [Still]);
    assert_eq!(w.creatures()[0].whiskers, [false, true]);
    assert_eq!(w.creatures()[0].pose.position, Vec2::new(100.0, 200.0));
    put(&mut w, 0, 30.0, 60.0, 0.0);
    let mut pixels = vec![0.0; 9];
    w.step(&mut [Still]);
    assert!(w.render_eye(0, &mut pixels));
    assert!(pixels.contains(&0.9) && pixels.contains(&0.2), "{pixels:?}");
}
