//! The behaviour measures that read the world's events (`door_opened`, `aversive_contacts`)
//! on hand-made worlds: the plan switches the event log on only when it has such a measure;
//! a door the creature opens is told and counted (and, as the measure is defined, one another
//! creature opens); each aversive contact is told as a shock and counted once; a teleporter
//! jump onto or off an aversive object is measured at the exit; and both evaluation paths
//! (lockstep and trial by trial) switch the log on.

use crate::door::{evaluate_group, evaluate_population};
use berry_evolve::brain::genome::Genome;
use berry_evolve::evo::fitness::{LifePlan, LifeScore, MEASURE_COUNT};
use berry_evolve::evo::lockstep;
use berry_evolve::evo::TrialPlan;
use berry_evolve::experiment::{Experiment, Measure};
use berry_evolve::geometry::Vec2;
use berry_evolve::seed::{stream, Generation, IndividualId, Purpose, Seed, TrialIndex};
use berry_evolve::sim::controller::{Controller, MotorCommand};
use berry_evolve::sim::events::{ShockCause, WorldEvent};
use berry_evolve::sim::motion::Pose;
use berry_evolve::sim::world::World;
use std::path::Path;

/// A 200 × 200 arena: a food object at (50, 50), a nettle (radius 3) at (100, 150), a door
/// across (120, 0)–(120, 40) whose trigger is at (60, 100), a teleporter from (150, 100) to
/// (100, 146) (the exit touches the nettle) and one from (100, 20) to (20, 150). Bodies have
/// radius 3; the creature starts near the bottom left corner.
const WORLD: &str = r#"
name = "events"
seed = 5

[world]
arena = [200.0, 200.0]
[world.kinds.food_a]
class = "food"
radius = 2.0
substance = [4.0, 0.0, 0.0, 0.0]
bite = [0.5, 0.0, 0.0, 0.0]
[world.kinds.nettle]
class = "aversive"
radius = 3.0
[[world.objects]]
kind = "food_a"
position = [50.0, 50.0]
[[world.objects]]
kind = "nettle"
position = [100.0, 150.0]
[[world.doors]]
from = [120.0, 0.0]
to = [120.0, 40.0]
trigger = [60.0, 100.0]
trigger_radius = 2.0
open_ticks = 3
[[world.teleporters]]
entry = [150.0, 100.0]
radius = 4.0
exit = [100.0, 146.0]
[[world.teleporters]]
entry = [100.0, 20.0]
radius = 4.0
exit = [20.0, 150.0]
[world.start]
region = [10.0, 165.0, 30.0, 190.0]
"#;

const REST: &str = r#"
[brain]
kind = "mlp"
hidden = [3]

[evolution]
population = 4
generations = 2

[evaluation]
trials = 2
ticks = 30
"#;

fn experiment(world_extra: &str, measures: &str) -> Experiment {
    let text = format!("{WORLD}{world_extra}{REST}[behaviour]\nmeasures = [{measures}]\n");
    Experiment::from_toml(&text, Path::new("events.toml")).unwrap_or_else(|e| panic!("{e}"))
}

struct Still;

impl Controller for Still {
    fn act(&mut self, _: &[f64]) -> MotorCommand {
        MotorCommand::default()
    }
}

fn demo_world(e: &Experiment, creatures: usize) -> World {
    let rng = stream(
        Seed(1),
        Purpose::Demo,
        Generation(0),
        IndividualId(0),
        TrialIndex(0),
    );
    World::new(&e.world, &e.creature, creatures, rng).unwrap()
}

fn put(world: &mut World, creature: usize, (x, y): (f64, f64)) {
    let pose = Pose {
        position: Vec2::new(x, y),
        heading: Vec2::X,
    };
    world.set_pose(creature, pose);
}

/// Lives creature 0 along `path` (where it is put before each tick; creature 1, when there
/// is one, stands at `other`) as evaluation does, and returns its measures and each tick's
/// events.
fn live(
    e: &Experiment,
    path: &[(f64, f64)],
    other: Option<(f64, f64)>,
) -> ([f64; MEASURE_COUNT], Vec<Vec<WorldEvent>>) {
    let mut world = demo_world(e, 1 + usize::from(other.is_some()));
    let plan = LifePlan::new(&TrialPlan::new(e), &world);
    plan.prepare(&mut world);
    let mut score = LifeScore::start(&plan, &world, 0);
    let mut told = Vec::new();
    for &at in path {
        put(&mut world, 0, at);
        if let Some(at) = other {
            put(&mut world, 1, at);
        }
        let mut still = vec![Still, Still];
        still.truncate(world.creatures().len());
        world.step(&mut still);
        told.push(world.events().to_vec());
        let c = &world.creatures()[0];
        score.record_tick(&c.metabolism, c.shocked);
        if plan.needs_world_every_tick() {
            score.record_world(&plan, &world, 0);
        }
    }
    (score.finish_in(&plan, &world, 0).1, told)
}

fn measure(values: &[f64; MEASURE_COUNT], m: Measure) -> f64 {
    values[m.index()]
}

#[test]
fn only_a_plan_with_a_measure_read_from_events_switches_the_log_on() {
    for (measures, on) in [
        ("\"door_opened\"", true),
        ("\"aversive_contacts\"", true),
        (
            "\"ticks_alive\", \"strikes_survived\", \"distinct_food\"",
            false,
        ),
    ] {
        let e = experiment("", measures);
        let mut world = demo_world(&e, 1);
        let plan = LifePlan::new(&TrialPlan::new(&e), &world);
        assert_eq!(plan.needs_events(), on, "{measures}");
        plan.prepare(&mut world);
        assert_eq!(world.event_log_on(), on, "{measures}");
        // A bite is made either way; only a listening world tells it.
        put(&mut world, 0, (54.0, 50.0));
        world.step(&mut [Still]);
        assert_eq!(!world.events().is_empty(), on, "{measures}");
    }
}

#[test]
fn a_door_the_creature_opens_is_told_and_counted() {
    let e = experiment("", "\"door_opened\"");
    let (m, told) = live(&e, &[(100.0, 100.0), (60.0, 100.0), (80.0, 100.0)], None);
    assert_eq!(told[0], []);
    assert_eq!(
        told[1],
        [WorldEvent::DoorOpened {
            door: 0,
            creature: 0
        }]
    );
    assert_eq!(measure(&m, Measure::DoorOpened), 1.0);
    let (m, told) = live(&e, &[(100.0, 100.0), (80.0, 100.0)], None);
    assert!(told.iter().all(Vec::is_empty));
    assert_eq!(measure(&m, Measure::DoorOpened), 0.0);
}

/// `door_opened` is "some door of the world was open at the end of a tick it lived": a door
/// another creature opens counts too.
#[test]
fn a_door_another_creature_opens_counts_as_the_measure_defines_it() {
    let e = experiment("", "\"door_opened\"");
    let (m, told) = live(&e, &[(100.0, 100.0)], Some((60.0, 100.0)));
    assert_eq!(
        told[0],
        [WorldEvent::DoorOpened {
            door: 0,
            creature: 1
        }]
    );
    assert_eq!(measure(&m, Measure::DoorOpened), 1.0);
}

#[test]
fn each_aversive_contact_is_told_as_a_shock_and_counted_once() {
    let e = experiment("", "\"aversive_contacts\", \"shocked_ticks\"");
    let on = (100.0, 155.0); // 5 from the nettle: touching (3 + 3)
    let off = (100.0, 170.0);
    let (m, told) = live(&e, &[off, on, on, off, on], None);
    let shock = WorldEvent::Shock {
        creature: 0,
        cause: ShockCause::Aversive(0),
    };
    let shocked: Vec<bool> = told.iter().map(|t| t.contains(&shock)).collect();
    assert_eq!(shocked, [false, true, true, false, true]);
    assert_eq!(measure(&m, Measure::AversiveContacts), 2.0);
    assert_eq!(measure(&m, Measure::ShockedTicks), 3.0);
}

/// The world tests aversive contact after the move, before a teleporter moves the body: a
/// jump onto the nettle is a contact at the tick's end (measured at the exit, where the world
/// has not tested yet), a jump off it ends the contact, although the world shocked the body
/// where it stood before jumping.
#[test]
fn a_teleporter_jump_onto_or_off_an_aversive_object_is_measured_at_the_exit() {
    let e = experiment("", "\"aversive_contacts\"");
    // Onto: the entry at (150, 100) is clear, its exit (100, 146) touches the nettle.
    let (m, told) = live(&e, &[(100.0, 170.0), (152.0, 100.0)], None);
    assert!(told[1].contains(&WorldEvent::Teleport {
        creature: 0,
        teleporter: 0
    }));
    assert!(!told[1]
        .iter()
        .any(|e| matches!(e, WorldEvent::Shock { .. })));
    assert_eq!(measure(&m, Measure::AversiveContacts), 1.0);
    // Off: a nettle on the entry at (100, 20), whose exit (20, 150) is clear. The body is
    // shocked on the entry and jumps: no contact at the tick's end.
    let nettle = "[[world.objects]]\nkind = \"nettle\"\nposition = [100.0, 24.0]\n";
    let e = experiment(nettle, "\"aversive_contacts\"");
    let (m, told) = live(&e, &[(100.0, 170.0), (100.0, 19.0)], None);
    assert!(told[1].contains(&WorldEvent::Shock {
        creature: 0,
        cause: ShockCause::Aversive(1)
    }));
    assert!(told[1].contains(&WorldEvent::Teleport {
        creature: 0,
        teleporter: 1
    }));
    assert_eq!(measure(&m, Measure::AversiveContacts), 0.0);
}

/// A door whose trigger covers the start region opens in the first tick whatever the
/// genomes do: both evaluation paths switch the event log on and count it.
#[test]
fn both_evaluation_paths_read_the_door_from_the_events() {
    let wide = WORLD.replace("trigger_radius = 2.0", "trigger_radius = 40.0");
    let wide = wide.replace("trigger = [60.0, 100.0]", "trigger = [11.0, 186.0]");
    let text = format!("{wide}{REST}[behaviour]\nmeasures = [\"door_opened\"]\n");
    let e = Experiment::from_toml(&text, Path::new("events.toml")).unwrap();
    let topology = e.topology();
    assert!(lockstep::stateless(&topology));
    let population: Vec<Genome> = (0..4)
        .map(|k| Genome::new(vec![0.1 * k as f64 - 0.15; topology.parameter_count()]))
        .collect();
    let together = evaluate_population(&e, &topology, &population, Generation(1)).unwrap();
    let alone = evaluate_group(&e, &topology, &population[..1], Generation(1), 0).unwrap();
    assert_eq!(alone[0].measures, [1.0]);
    assert!(together.iter().all(|e| e.measures == [1.0]), "{together:?}");
}
