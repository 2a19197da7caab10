//! The world's event list ([`World::events`]): each kind told once, where the world decides
//! it, on hand-made worlds (a bite with its amount, two eaters at one object, a shock from
//! aversive k and from a wall, attacks by ground predator k and air predator k, a death, a
//! teleport through the second of two teleporters sharing one exit, a door opened by the
//! creature on its trigger and closed when its time is up); nothing with the log off; the
//! list cleared every tick; and the same world with the log on and off.

use crate::sim_common::{put, world, Fixed, Still};
use berry_evolve::geometry::Vec2;
use berry_evolve::sim::controller::MotorCommand;
use berry_evolve::sim::events::{Attacker, DeathCause, ShockCause, WorldEvent};
use berry_evolve::sim::motion::Pose;
use berry_evolve::sim::scripted::ScriptedSpec;
use berry_evolve::sim::spec::Effect;
use berry_evolve::sim::World;

/// One food object at (100, 100), radius 2, 4 A, bites of 0.5; two nettles (radius 3) at
/// (50, 50) and (50, 250). Bodies have radius 3.
const OBJECTS: &str = r#"
[world.kinds.food]
class = "food"
radius = 2.0
substance = [4.0, 0.0, 0.0, 0.0]
bite = [0.5, 0.0, 0.0, 0.0]
[world.kinds.nettle]
class = "aversive"
radius = 3.0
[[world.objects]]
kind = "food"
position = [100.0, 100.0]
[[world.objects]]
kind = "nettle"
position = [50.0, 50.0]
[[world.objects]]
kind = "nettle"
position = [50.0, 250.0]
"#;

fn listening(text: &str, creatures: usize) -> World {
    let mut w = world(text, creatures, 1);
    w.set_event_log(true);
    w
}

#[test]
fn a_creature_on_a_food_object_bites_it_once_with_the_amount() {
    let mut w = listening(OBJECTS, 1);
    put(&mut w, 0, 104.0, 100.0, 0.0); // 4 apart: touching (3 + 2)
    w.step(&mut [Still]);
    assert_eq!(
        w.events(),
        [WorldEvent::Bite {
            creature: 0,
            food: 0,
            amount: [0.5, 0.0, 0.0, 0.0]
        }]
    );
}

/// Two creatures touching one object in one tick: two bites, one per eater, in creature
/// order. (The trace's old re-derivation from two world states told one `eat` row with both
/// bites' sum, credited to the nearer creature.)
#[test]
fn two_eaters_at_one_object_are_two_bites() {
    let mut w = listening(OBJECTS, 2);
    put(&mut w, 0, 104.0, 100.0, 0.0);
    put(&mut w, 1, 95.0, 100.0, 0.0);
    w.step(&mut [Still, Still]);
    let bite = |creature| WorldEvent::Bite {
        creature,
        food: 0,
        amount: [0.5, 0.0, 0.0, 0.0],
    };
    assert_eq!(w.events(), [bite(0), bite(1)]);
}

#[test]
fn a_creature_on_an_aversive_object_is_shocked_by_that_object() {
    let mut w = listening(OBJECTS, 1);
    put(&mut w, 0, 50.0, 245.0, 0.0); // touches nettle 1 only
    w.step(&mut [Still]);
    assert_eq!(
        w.events(),
        [WorldEvent::Shock {
            creature: 0,
            cause: ShockCause::Aversive(1)
        }]
    );
    // Still there: shocked again (every shocked tick is told, not only the onset).
    w.step(&mut [Still]);
    assert_eq!(w.events().len(), 1);
}

#[test]
fn a_wall_that_stops_a_move_shocks_with_wall_shock() {
    let mut w = listening("[world]\nwall_shock = true\n", 1);
    put(&mut w, 0, 296.5, 150.0, 0.0); // facing the east boundary, 0.5 LU away
    let forward = MotorCommand {
        left: 0.25,
        right: 0.25,
        eat: 0.0,
    };
    w.step(&mut [Fixed(forward)]);
    assert_eq!(
        w.events(),
        [WorldEvent::Shock {
            creature: 0,
            cause: ShockCause::Wall
        }]
    );
}

/// Two patrolling predators; the second is put against the creature.
const PREDATORS: &str = r#"
[[world.predators]]
strategy = "patrol"
waypoints = [[20.0, 20.0], [30.0, 20.0]]
max_rpt = 0.0
effect = "EFFECT"
start = [20.0, 20.0]
[[world.predators]]
strategy = "patrol"
waypoints = [[200.0, 150.0], [210.0, 150.0]]
max_rpt = 0.0
effect = "EFFECT"
start = [200.0, 150.0]
"#;

fn predators(effect: &str) -> World {
    let mut w = listening(&PREDATORS.replace("EFFECT", effect), 1);
    w.set_actor_pose(
        1,
        Pose {
            position: Vec2::new(200.0, 150.0),
            heading: Vec2::X,
        },
    );
    put(&mut w, 0, 205.0, 150.0, 0.0); // 5 apart: bodies touch (3 + 3)
    w
}

#[test]
fn a_lethal_predator_reaching_a_creature_attacks_and_kills_it() {
    let mut w = predators("lethal");
    w.step(&mut [Still]);
    let by = Attacker::Predator(1);
    assert_eq!(
        w.events(),
        [
            WorldEvent::Attack {
                creature: 0,
                by,
                effect: Effect::Lethal
            },
            WorldEvent::Death {
                creature: 0,
                cause: DeathCause::Attack(by)
            }
        ]
    );
    assert!(!w.creatures()[0].alive);
}

#[test]
fn a_shock_predator_attacks_after_its_move_and_in_the_creatures_contacts() {
    let mut w = predators("shock");
    w.step(&mut [Still]);
    let by = Attacker::Predator(1);
    let attack = WorldEvent::Attack {
        creature: 0,
        by,
        effect: Effect::Shock,
    };
    // Phase 2 (the predator's move), then the creature's contacts, where the shock stands.
    assert_eq!(
        w.events(),
        [
            attack,
            attack,
            WorldEvent::Shock {
                creature: 0,
                cause: ShockCause::Attack(by)
            }
        ]
    );
    assert!(w.creatures()[0].shocked);
}

#[test]
fn an_air_predator_overhead_attacks_by_its_index() {
    let text = "[[world.air_predators]]\nspeed = 1\nstrike_radius = 10\n\
                [[world.air_predators]]\nspeed = 1\nstrike_radius = 10\n";
    let mut w = listening(text, 1);
    w.set_flyer(0, Vec2::new(20.0, 20.0), Vec2::new(0.0, 1.0));
    w.set_flyer(1, Vec2::new(150.0, 150.0), Vec2::new(0.0, 1.0));
    put(&mut w, 0, 150.0, 155.0, 0.0);
    w.step(&mut [Still]);
    let by = Attacker::AirPredator(1);
    assert_eq!(
        w.events(),
        [
            WorldEvent::Attack {
                creature: 0,
                by,
                effect: Effect::Lethal
            },
            WorldEvent::Death {
                creature: 0,
                cause: DeathCause::Attack(by)
            }
        ]
    );
}

/// The t-maze's arms: two teleporters with one exit. The world names the one the creature
/// went through. (The trace's old re-derivation named the first teleporter whose exit the
/// creature stood on: teleporter 0 for a jump through either arm.)
#[test]
fn a_teleport_names_the_teleporter_even_when_two_share_an_exit() {
    let text = r#"
[[world.teleporters]]
entry = [70.0, 100.0]
radius = 4.0
exit = [150.0, 270.0]
[[world.teleporters]]
entry = [230.0, 100.0]
radius = 4.0
exit = [150.0, 270.0]
"#;
    let mut w = listening(text, 1);
    put(&mut w, 0, 233.0, 100.0, 0.0);
    w.step(&mut [Still]);
    assert_eq!(
        w.events(),
        [WorldEvent::Teleport {
            creature: 0,
            teleporter: 1
        }]
    );
    assert_eq!(w.creatures()[0].pose.position, Vec2::new(150.0, 270.0));
}

const DOOR: &str = r#"
[[world.doors]]
from = [150, 0]
to = [150, 300]
trigger = [100, 150]
trigger_radius = 5
open_ticks = 3
"#;

#[test]
fn a_creature_on_a_door_trigger_opens_it_and_the_door_closes_when_its_time_is_up() {
    let mut w = listening(DOOR, 2);
    put(&mut w, 0, 40.0, 40.0, 0.0);
    put(&mut w, 1, 108.0, 150.0, 0.0); // 8 from the trigger centre: touching (3 + 5)
    w.step(&mut [Still, Still]); // tick 0: opened by creature 1, open until tick 3
    assert_eq!(
        w.events(),
        [WorldEvent::DoorOpened {
            door: 0,
            creature: 1
        }]
    );
    w.step(&mut [Still, Still]); // tick 1: still on the trigger, the door stays open
    assert_eq!(w.events(), []);
    put(&mut w, 1, 40.0, 250.0, 0.0);
    let mut closed = Vec::new();
    for tick in 2..8 {
        w.step(&mut [Still, Still]);
        if w.events() == [WorldEvent::DoorClosed { door: 0 }] {
            closed.push(tick);
        } else {
            assert_eq!(w.events(), [], "tick {tick}");
        }
    }
    // Last touched at tick 1: open through tick 1 + 3, closed at the start of tick 5.
    assert_eq!(closed, [5]);
}

#[test]
fn with_the_log_off_no_event_is_told_and_a_quiet_tick_clears_the_list() {
    let mut w = world(OBJECTS, 1, 1);
    put(&mut w, 0, 104.0, 100.0, 0.0);
    w.step(&mut [Still]);
    assert_eq!(w.events(), [], "off by default");
    w.set_event_log(true);
    w.step(&mut [Still]);
    assert_eq!(w.events().len(), 1);
    put(&mut w, 0, 200.0, 200.0, 0.0);
    w.step(&mut [Still]);
    assert_eq!(w.events(), [], "a tick with nothing to tell");
    w.set_event_log(false);
    put(&mut w, 0, 104.0, 100.0, 0.0);
    w.step(&mut [Still]);
    assert_eq!(w.events(), [], "switched off again");
    // `kill` between ticks is told too.
    w.set_event_log(true);
    w.kill(0);
    assert_eq!(
        w.events(),
        [WorldEvent::Death {
            creature: 0,
            cause: DeathCause::Killed
        }]
    );
}

/// Everything at once (food, nettles, a door, teleporters, wanderers, chasing and
/// patrolling predators, an air predator), three Braitenberg creatures, 600 ticks: the
/// world with the log on is the world with it off, to the bit.
#[test]
fn the_log_changes_nothing() {
    let text = format!(
        "{OBJECTS}{DOOR}{}",
        r#"
[[world.teleporters]]
entry = [250.0, 250.0]
radius = 10.0
exit = [60.0, 150.0]
[world.wanderers]
count = 2
[[world.predators]]
strategy = "chase"
effect = "shock"
max_rpt = 0.1
[[world.air_predators]]
speed = 3
strike_radius = 15
effect = "shock"
[[world.place]]
kind = "food"
count = 20
[[world.place]]
kind = "nettle"
count = 10
"#
    );
    let spec = ScriptedSpec::Braitenberg {
        receptor: 1,
        gain: 0.5,
        base: 0.2,
    };
    let run = |listen: bool| {
        let mut w = world(&text, 3, 7);
        w.set_event_log(listen);
        let mut controllers = vec![spec.build(w.layout()).unwrap(); 3];
        let mut told = 0;
        for _ in 0..600 {
            w.step(&mut controllers);
            told += w.events().len();
        }
        (w.creatures().to_vec(), w.food().to_vec(), told)
    };
    let (creatures_on, food_on, told) = run(true);
    let (creatures_off, food_off, none) = run(false);
    assert_eq!(creatures_on, creatures_off);
    assert_eq!(food_on, food_off);
    assert_eq!(none, 0);
    assert!(told > 0, "something happened");
}
