//! A tick allocates nothing: a counting global allocator watches `World::step` on a world
//! with walls, smelly food, aversive objects, landmarks, smelly areas and several creatures,
//! every sensor switched on (the eye with a 2-D retina) and noise on several groups; and with
//! the world's event log on, once its list has room.

use crate::sim_common;
use berry_evolve::sim::scripted::ScriptedSpec;

use crate::alloc_common::allocations;

const WORLD: &str = r#"
[[world.walls]]
from = [150, 20]
to = [150, 280]

[[world.walls]]
from = [20, 150]
to = [120, 150]
opaque = false

[world.kinds.rose]
class = "food"
radius = 1
regen = [0.01, 0, 0, 0]
capacity = [2, 0, 0, 0]
smell_follows_amount = true
odour = [1, 0, 0, 0, 0, 0, 0, 0]
intensity = 0.5

[world.kinds.nettle]
class = "aversive"
radius = 2
odour = [0, 1, 0, 0, 0, 0, 0, 0]
intensity = 0.5
range = 50

[[world.place]]
kind = "rose"
count = 30

[[world.place]]
kind = "nettle"
count = 10

[creature]
odour = [0, 0, 1, 0, 0, 0, 0, 0]
odour_intensity = 0.3
eating = "action"
decay_per_lu = [0.01, 0, 0, 0]

[[world.landmarks]]
position = [0, 0]

[[world.landmarks]]
position = [500, 150]

[[world.areas]]
region = [200, 200, 300, 300]
kind = "safe"
odour = [0, 0, 0, 1, 0, 0, 0, 0]
intensity = 1

[[world.doors]]
from = [150, 280]
to = [150, 300]
trigger = [100, 100]
trigger_radius = 40
open_ticks = 5

[[world.teleporters]]
entry = [250, 100]
radius = 20
exit = [60, 60]
odour = [0, 0, 0, 0, 1, 0, 0, 0]
intensity = 1

[world.wanderers]
count = 4
odour = [0, 0, 0, 0, 0, 1, 0, 0]
intensity = 1

[[world.predators]]
strategy = "chase"
effect = "shock"
odour = [0, 0, 0, 0, 0, 0, 1, 0]
intensity = 1

[[world.predators]]
strategy = "patrol"
waypoints = [[30, 30], [270, 30]]
effect = "shock"

[[world.air_predators]]
speed = 5
effect = "shock"
strike_radius = 20
odour = [0, 0, 0, 0, 0, 0, 0, 1]
intensity = 1

[creature.inputs]
metabolism = true
landmarks = true
areas = true
eye = true

[creature.eye]
width = 12
height = 4
range = 150

[creature.noise.smell]
n = 0.1
n_sigma = 0.05
m = 0.2
m_sigma = 0.1

[creature.noise.eye]
n = 0.05
n_sigma = 0.05

[creature.noise.landmarks]
m = 0.1
m_sigma = 0.1
"#;

#[test]
fn step_does_not_allocate() {
    let mut w = sim_common::world(WORLD, 5, 1);
    w.set_full_sensing(true);
    let spec = ScriptedSpec::Braitenberg {
        receptor: 1,
        gain: 0.5,
        base: 0.1,
    };
    let mut controllers = vec![spec.build(w.layout()).unwrap(); 5];
    // One tick outside the count, in case anything lazy happens on first use.
    w.step(&mut controllers);
    let before = allocations();
    for _ in 0..2_000 {
        w.step(&mut controllers);
    }
    let n = allocations() - before;
    assert_eq!(n, 0, "{n} heap allocations in 2000 ticks");
    assert!(
        w.creatures().iter().any(|c| c.travelled > 10.0),
        "nobody moved"
    );
}

#[test]
fn step_with_the_event_log_on_does_not_allocate() {
    let mut w = sim_common::world(WORLD, 5, 1);
    w.set_event_log(true);
    let spec = ScriptedSpec::Braitenberg {
        receptor: 1,
        gain: 0.5,
        base: 0.1,
    };
    let mut controllers = vec![spec.build(w.layout()).unwrap(); 5];
    // The first event makes the list's room: step until something is told.
    w.step(&mut controllers);
    while w.events().is_empty() {
        w.step(&mut controllers);
    }
    let before = allocations();
    let mut told = 0;
    for _ in 0..2_000 {
        w.step(&mut controllers);
        told += w.events().len();
    }
    let n = allocations() - before;
    assert_eq!(n, 0, "{n} heap allocations in 2000 ticks");
    assert!(told > 0, "nothing was told");
}
