//! Building a world's gadgets and actors from their `[world]` tables: doors, teleporters,
//! wanderers and ground predators (placed on free spots with the world's generator), air
//! predators (entering on their first flight), and the things senses meet of them.

use super::{Actor, Door, Flyer, Gadgets, Role, Teleporter, Thing, TurnAway};
use crate::geometry::{circle_touches_segment, circles_touch, Segment, Vec2};
use crate::seed::{below, uniform, Rng};
use crate::sim::motion::Pose;
use crate::sim::placement::PlacementError;
use crate::sim::smell::Smell;
use crate::sim::spec::WorldSpec;

/// Placement attempts for one wanderer or predator.
const ACTOR_ATTEMPTS: u32 = 10_000;

impl Gadgets {
    /// The gadgets and actors of `world` and their things, in this order: door triggers,
    /// teleporter entries, wanderers, ground predators, air predators. Wanderers and
    /// predators are bodies of radius `radius` and height `body_height`, placed where they
    /// touch no wall of `walls`, no creature at `creatures` and no body placed before them;
    /// then the air predators enter. Every draw from `rng` in that order.
    pub fn build(
        world: &WorldSpec,
        radius: f64,
        body_height: f64,
        walls: &[Segment],
        creatures: &[Pose],
        rng: &mut Rng,
    ) -> Result<(Gadgets, Vec<Thing>), PlacementError> {
        let n_actors = world.wanderers.count as usize + world.predators.len();
        let mut things = Vec::with_capacity(
            world.doors.len() + world.teleporters.len() + n_actors + world.air_predators.len(),
        );
        let doors = doors(world, &mut things);
        let teleporters = teleporters(world, &mut things);
        let ground = Ground {
            radius,
            body_height,
            walls,
            creatures,
        };
        let mut actors = Vec::with_capacity(n_actors);
        wanderers(world, &ground, &mut actors, &mut things, rng)?;
        predators(world, &ground, &mut actors, &mut things, rng)?;
        let waypoints = world
            .predators
            .iter()
            .map(|p| p.waypoints.iter().map(|&w| Vec2::from(w)).collect())
            .collect();
        let flyers = flyers(world, &mut things, rng);
        let active =
            !(teleporters.is_empty() && doors.is_empty() && actors.is_empty() && flyers.is_empty());
        let gadgets = Gadgets {
            doors,
            teleporters,
            actors,
            waypoints,
            flyers,
            active,
        };
        Ok((gadgets, things))
    }
}

/// Where wanderers and ground predators are placed, and their bodies.
struct Ground<'a> {
    /// Body radius in LU.
    radius: f64,
    /// Body height for the eye in LU.
    body_height: f64,
    /// Every wall's segment.
    walls: &'a [Segment],
    /// The creatures' start poses.
    creatures: &'a [Pose],
}

/// The doors, their triggers pushed onto `things`.
fn doors(world: &WorldSpec, things: &mut Vec<Thing>) -> Vec<Door> {
    let mut doors = Vec::with_capacity(world.doors.len());
    for d in &world.doors {
        doors.push(Door {
            trigger: things.len(),
            open_ticks: d.open_ticks,
            open_until: None,
        });
        things.push(Thing {
            position: Vec2::from(d.trigger),
            radius: d.trigger_radius,
            smell: Smell::new(&d.odour, d.intensity, d.range),
            felt: true,
            blocks: false,
            seen: false,
            colour: d.colour,
            height: 0.0,
        });
    }
    doors
}

/// The teleporters, their entries pushed onto `things`.
fn teleporters(world: &WorldSpec, things: &mut Vec<Thing>) -> Vec<Teleporter> {
    let mut teleporters = Vec::with_capacity(world.teleporters.len());
    for t in &world.teleporters {
        teleporters.push(Teleporter {
            entry: Vec2::from(t.entry),
            radius: t.radius,
            exit: Vec2::from(t.exit),
            exit_heading: t.exit_heading.map(|deg| {
                let a = deg.to_radians();
                Vec2::new(libm::cos(a), libm::sin(a))
            }),
        });
        things.push(Thing {
            position: Vec2::from(t.entry),
            radius: t.radius,
            smell: Smell::new(&t.odour, t.intensity, t.range),
            felt: true,
            blocks: false,
            seen: false,
            colour: [0.0; 3],
            height: 0.0,
        });
    }
    teleporters
}

/// The wanderers onto `actors`, their bodies onto `things` (see [`Gadgets::build`]).
fn wanderers(
    world: &WorldSpec,
    ground: &Ground<'_>,
    actors: &mut Vec<Actor>,
    things: &mut Vec<Thing>,
    rng: &mut Rng,
) -> Result<(), PlacementError> {
    let w = &world.wanderers;
    for k in 0..w.count as usize {
        let pose = free_pose(
            w.region.unwrap_or(world.arena_region()),
            None,
            ground.radius,
            ground.walls,
            ground.creatures,
            things,
            rng,
        )
        .ok_or(PlacementError::Actor {
            what: format!("wanderer {}", k + 1),
            attempts: ACTOR_ATTEMPTS,
        })?;
        actors.push(Actor {
            thing: things.len(),
            role: Role::Wanderer,
            pose,
            max_rpt: w.max_rpt,
            hold_ticks: w.hold_ticks,
            held: (0.0, 0.0),
            hold_left: 0,
            on_held: false,
            waypoint: 0,
            turn_away: TurnAway::new(w.max_rpt, w.turn_degrees),
            asleep: 0,
        });
        things.push(Thing {
            position: pose.position,
            radius: ground.radius,
            smell: Smell::new(&w.odour, w.intensity, w.range),
            felt: true,
            blocks: true,
            seen: true,
            colour: w.colour,
            height: ground.body_height,
        });
    }
    Ok(())
}

/// The ground predators onto `actors`, their bodies onto `things` (see [`Gadgets::build`]).
fn predators(
    world: &WorldSpec,
    ground: &Ground<'_>,
    actors: &mut Vec<Actor>,
    things: &mut Vec<Thing>,
    rng: &mut Rng,
) -> Result<(), PlacementError> {
    for (k, p) in world.predators.iter().enumerate() {
        let pose = free_pose(
            world.arena_region(),
            p.start.map(Vec2::from),
            ground.radius,
            ground.walls,
            ground.creatures,
            things,
            rng,
        )
        .ok_or(PlacementError::Actor {
            what: format!("world.predators[{k}]"),
            attempts: ACTOR_ATTEMPTS,
        })?;
        // No draw without a sleep, so that worlds without one keep their bytes.
        let asleep = if p.asleep[1] > 0 {
            p.asleep[0] + below(rng, p.asleep[1] - p.asleep[0] + 1)
        } else {
            0
        };
        actors.push(Actor {
            thing: things.len(),
            role: Role::Predator {
                predator: k,
                strategy: p.strategy,
                effect: p.effect,
            },
            pose,
            max_rpt: p.max_rpt,
            hold_ticks: p.hold_ticks,
            held: (0.0, 0.0),
            hold_left: 0,
            on_held: false,
            waypoint: 0,
            turn_away: TurnAway::new(p.max_rpt, p.turn_degrees),
            asleep,
        });
        let mut smell = Smell::new(&p.odour, p.intensity, p.range);
        smell.set_quiet(asleep > 0);
        things.push(Thing {
            position: pose.position,
            radius: ground.radius,
            smell,
            felt: true,
            blocks: false,
            seen: true,
            colour: p.colour,
            height: ground.body_height,
        });
    }
    Ok(())
}

/// The air predators, each entering on its first flight (draws from `rng` in file order),
/// their smells onto `things`.
fn flyers(world: &WorldSpec, things: &mut Vec<Thing>, rng: &mut Rng) -> Vec<Flyer> {
    let mut flyers = Vec::with_capacity(world.air_predators.len());
    for a in &world.air_predators {
        let mut f = Flyer {
            thing: things.len(),
            position: Vec2::new(0.0, 0.0),
            velocity: Vec2::new(0.0, 0.0),
            speed: a.speed,
            strike_radius: a.strike_radius,
            effect: a.effect,
            pause: a.pause,
            away: 0,
            entry: Vec2::new(0.0, 0.0),
        };
        f.enter(world.arena, rng);
        let mut smell = Smell::new(&a.odour, a.intensity, a.range);
        smell.set_quiet(!f.in_flight());
        things.push(Thing {
            position: f.position,
            radius: 0.0,
            smell,
            felt: false,
            blocks: false,
            seen: false,
            colour: [0.0; 3],
            height: 0.0,
        });
        flyers.push(f);
    }
    flyers
}

/// A start pose for a wanderer or predator: at `at` when given, else a uniform point of
/// `region` (draws x, then y, repeated until free) whose body touches no wall, creature or
/// blocking thing; then a uniform heading (one draw). None when no free spot was found.
fn free_pose(
    region: [f64; 4],
    at: Option<Vec2>,
    radius: f64,
    walls: &[Segment],
    creatures: &[Pose],
    things: &[Thing],
    rng: &mut Rng,
) -> Option<Pose> {
    let position = match at {
        Some(p) => p,
        None => (0..ACTOR_ATTEMPTS)
            .map(|_| {
                let x = uniform(rng, region[0], region[2]);
                let y = uniform(rng, region[1], region[3]);
                Vec2::new(x, y)
            })
            .find(|&p| {
                !walls.iter().any(|s| circle_touches_segment(p, radius, s))
                    && !creatures
                        .iter()
                        .any(|c| circles_touch(p, radius, c.position, radius))
                    && !things
                        .iter()
                        .any(|t| t.blocks && circles_touch(p, radius, t.position, t.radius))
            })?,
    };
    let angle = uniform(rng, 0.0, std::f64::consts::TAU);
    Some(Pose {
        position,
        heading: Vec2::new(libm::cos(angle), libm::sin(angle)),
    })
}
