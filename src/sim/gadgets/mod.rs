//! Gadgets and other actors of a world (§4.5.1, §4.5.2, §4.7, §4.8): locked doors and their
//! triggers, teleporters, irrelevant creatures ("wanderers"), ground and air predators.
//! [`Gadgets`] owns their running state, is built from their `[world]` tables
//! ([`crate::sim::spec`]) and is stepped by the world in the tick order of §9 through a
//! [`Context`] that borrows what it reads and changes of the world. The world keeps what
//! gadgets share with creatures: an actor's whiskers and move are the world's (the same senses
//! and motion as a creature's), its decision and its attacks are here.

mod actor;
mod build;
mod flyer;

pub use actor::{Actor, Role, Turn, TurnAway};
pub use flyer::Flyer;

use crate::geometry::{circle_touches_segment, circles_touch, Vec2};
use crate::seed::Rng;
use crate::sim::area::Area;
use crate::sim::creature::Creature;
use crate::sim::events::{Attacker, DeathCause, EventLog, ShockCause, WorldEvent};
use crate::sim::motion::Pose;
use crate::sim::smell::Smell;
use crate::sim::spec::{Effect, Strategy};
use crate::sim::wall::Walls;

/// Something round other than food, aversive objects and creatures that senses may meet:
/// door triggers, teleporter entries, wanderers, predators (their ground position), and
/// landmarks that smell (a point that is only smelled).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Thing {
    /// Centre in LU.
    pub position: Vec2,
    /// Radius in LU (0 = a point, never felt nor seen).
    pub radius: f64,
    /// Its smell.
    pub smell: Smell,
    /// Felt by whiskers (when radius > 0).
    pub felt: bool,
    /// Blocks the movement of bodies.
    pub blocks: bool,
    /// Seen by eyes as a cylinder (when radius > 0).
    pub seen: bool,
    /// Colour for the eye.
    pub colour: [f64; 3],
    /// Height for the eye in LU.
    pub height: f64,
}

/// The running state of a locked door.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Door {
    /// Index of its trigger in the world's things.
    pub trigger: usize,
    /// Ticks it stays open after a contact.
    pub open_ticks: u64,
    /// Last tick it is open, when it was opened at all.
    pub open_until: Option<u64>,
}

/// The running state of a teleporter.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Teleporter {
    /// Entry centre.
    pub entry: Vec2,
    /// Entry radius.
    pub radius: f64,
    /// Exit point.
    pub exit: Vec2,
    /// Heading after the jump, unit (None = keep).
    pub exit_heading: Option<Vec2>,
}

/// The running state of a world's gadgets and actors.
#[derive(Debug, Clone)]
pub struct Gadgets {
    /// Locked doors (§4.5.2), in file order.
    doors: Vec<Door>,
    /// Teleporters (§4.5.1), in file order.
    teleporters: Vec<Teleporter>,
    /// Wanderers then ground predators, in file order.
    actors: Vec<Actor>,
    /// Each ground predator's patrol waypoints.
    waypoints: Vec<Vec<Vec2>>,
    /// Air predators, in file order.
    flyers: Vec<Flyer>,
    /// There are teleporters, doors, wanderers or predators: the tick runs them (most worlds
    /// have none, and none is added during a trial).
    active: bool,
}

/// What gadgets read and change of the world they run in, borrowed for one call.
pub struct Context<'a> {
    /// Ticks done so far.
    pub tick: u64,
    /// Arena `[width, height]` in LU.
    pub arena: [f64; 2],
    /// Body radius of creatures, wanderers and ground predators in LU.
    pub radius: f64,
    /// The walls; doors open and close in them.
    pub walls: &'a mut Walls,
    /// The creatures, in index order.
    pub creatures: &'a mut [Creature],
    /// The world's things (actors' bodies and flyers' ground positions move with them).
    pub things: &'a mut [Thing],
    /// Areas (§4.6), for the safe ones.
    pub areas: &'a [Area],
    /// The trial's generator.
    pub rng: &'a mut Rng,
    /// The world's events of this tick (pushed only when [`EventLog::on`]).
    pub events: &'a mut EventLog,
}

/// Is `position` inside a safe area of `areas` (bounds included)? Predators leave such
/// creatures alone.
#[inline]
pub fn in_safe_area(areas: &[Area], position: Vec2) -> bool {
    areas.iter().any(|a| a.is_safe() && a.contains(position))
}

impl Context<'_> {
    /// [`in_safe_area`] of the world's areas.
    #[inline]
    fn in_safe_area(&self, position: Vec2) -> bool {
        in_safe_area(self.areas, position)
    }

    /// `by`'s attack on creature `i` (outside safe areas, checked by the caller), told to
    /// the event log with the death it causes; `contacts`: in the creature's contacts phase,
    /// where a shock it gives stands to the end of the tick (and is told as a shock).
    #[inline]
    fn attack(&mut self, i: usize, effect: Effect, by: Attacker, contacts: bool) {
        let c = &mut self.creatures[i];
        let was_alive = c.alive;
        match effect {
            Effect::Lethal => c.alive = false,
            Effect::Shock => c.shocked = true,
        }
        if self.events.on() {
            self.tell_attack(i, effect, by, contacts, was_alive);
        }
    }

    /// The events of [`Context::attack`]: the attack, then a death (a lethal attack on a
    /// living creature) or a shock (a shock in the contacts phase).
    #[inline(never)]
    fn tell_attack(&mut self, i: usize, effect: Effect, by: Attacker, contacts: bool, was: bool) {
        self.events.push(WorldEvent::Attack {
            creature: i,
            by,
            effect,
        });
        match effect {
            Effect::Lethal if was => self.events.push(WorldEvent::Death {
                creature: i,
                cause: DeathCause::Attack(by),
            }),
            Effect::Shock if contacts => self.events.push(WorldEvent::Shock {
                creature: i,
                cause: ShockCause::Attack(by),
            }),
            _ => {}
        }
    }

    /// Attacks by predator `by` at `position` (ground: body contact; air: `reach` = strike
    /// radius, `radius` = 0) on every living creature outside safe areas.
    fn strike_all(&mut self, position: Vec2, reach: f64, own: f64, effect: Effect, by: Attacker) {
        for i in 0..self.creatures.len() {
            let c = &self.creatures[i];
            if c.alive
                && circles_touch(c.pose.position, own, position, reach)
                && !self.in_safe_area(c.pose.position)
            {
                self.attack(i, effect, by, false);
            }
        }
    }

    /// The centre of the nearest living creature outside safe areas (lowest index on ties).
    #[inline]
    fn nearest_prey(&self, from: Vec2) -> Option<Vec2> {
        let mut best: Option<(f64, Vec2)> = None;
        for c in self.creatures.iter() {
            if c.alive && !self.in_safe_area(c.pose.position) {
                let d = from.distance_squared(c.pose.position);
                if best.is_none_or(|(b, _)| d < b) {
                    best = Some((d, c.pose.position));
                }
            }
        }
        best.map(|(_, p)| p)
    }
}

impl Gadgets {
    /// Are there teleporters, doors, wanderers or predators? When not, the tick skips them.
    #[inline]
    pub fn active(&self) -> bool {
        self.active
    }

    /// Phase 1 (gadgets): doors whose time is up close.
    #[inline]
    pub fn close_doors(&self, ctx: &mut Context<'_>) {
        for k in 0..self.doors.len() {
            if ctx.walls.door_open(k) && self.doors[k].open_until.is_some_and(|u| ctx.tick > u) {
                ctx.walls.set_door_open(k, false);
                if ctx.events.on() {
                    ctx.events.push(WorldEvent::DoorClosed { door: k });
                }
            }
        }
    }

    /// Phase 2 (predators and wanderers), the decision: actor `a`'s motor command (left,
    /// right) when its whiskers feel `whiskers`, and its effect when it is a predator (which
    /// then attacks what it touches after its move, [`Gadgets::moved`]).
    #[inline]
    pub fn command(
        &mut self,
        a: usize,
        whiskers: [bool; 2],
        ctx: &mut Context<'_>,
    ) -> (f64, f64, Option<Effect>) {
        let actor = self.actors[a];
        let r = ctx.radius;
        match actor.role {
            Role::Wanderer => {
                let (l, rr) = self.actors[a].wander(whiskers, ctx.rng);
                (l, rr, None)
            }
            Role::Predator { .. } if !actor.awake() => {
                // Asleep where it lies; it wakes (and smells) after this tick's command.
                let a = &mut self.actors[a];
                a.on_held = false;
                a.asleep -= 1;
                if a.awake() {
                    ctx.things[a.thing].smell.set_quiet(false);
                }
                (0.0, 0.0, None)
            }
            Role::Predator {
                predator,
                strategy,
                effect,
            } => {
                let target = match strategy {
                    Strategy::Wander => None,
                    Strategy::Chase => ctx.nearest_prey(actor.pose.position),
                    Strategy::Patrol => {
                        let points = &self.waypoints[predator];
                        let mut k = actor.waypoint % points.len();
                        if actor.pose.position.distance_squared(points[k]) <= r * r {
                            k = (k + 1) % points.len();
                            self.actors[a].waypoint = k;
                        }
                        Some(points[k])
                    }
                };
                let (l, rr) = match target {
                    Some(t) => {
                        self.actors[a].on_held = false;
                        actor.steer(t)
                    }
                    None => {
                        let command = self.actors[a].wander(whiskers, ctx.rng);
                        // A chaser with no prey in reach waits on its held command, blocked
                        // or not: the redraw is the wanderers' rule (§4.8), and predator-arena's
                        // results were measured with chasers that wait.
                        if strategy == Strategy::Chase {
                            self.actors[a].on_held = false;
                        }
                        command
                    }
                };
                (l, rr, Some(effect))
            }
        }
    }

    /// Phase 2, after actor `a`'s move to `pose`: its body goes there (a held random command
    /// that could not move it ends its hold, [`Actor::moved_on`]), and a predator
    /// (`predator`: its effect) attacks every living creature it touches outside safe areas.
    #[inline]
    pub fn moved(&mut self, a: usize, pose: Pose, predator: Option<Effect>, ctx: &mut Context<'_>) {
        let actor = &mut self.actors[a];
        actor.moved_on(pose);
        ctx.things[actor.thing].position = pose.position;
        if let (Some(effect), Role::Predator { predator: k, .. }) = (predator, actor.role) {
            let r = ctx.radius;
            ctx.strike_all(pose.position, r, r, effect, Attacker::Predator(k));
        }
    }

    /// Phase 2 (air predators): each flyer in file order flies one tick, entering anew when
    /// it left the arena (after its pause, if any), and strikes every creature within its
    /// strike radius while in flight.
    #[inline]
    pub fn fly(&mut self, ctx: &mut Context<'_>) {
        for f in 0..self.flyers.len() {
            self.flyers[f].fly(ctx.arena, ctx.rng);
            let fl = self.flyers[f];
            let thing = &mut ctx.things[fl.thing];
            thing.position = fl.position;
            if fl.pause[1] > 0 {
                // Away between flights it is not smelled.
                thing.smell.set_quiet(!fl.in_flight());
            }
            if fl.in_flight() {
                let by = Attacker::AirPredator(f);
                ctx.strike_all(fl.position, fl.strike_radius, 0.0, fl.effect, by);
            }
        }
    }

    /// Phase 3.6: teleporters, door triggers and predators meet creature `i`.
    #[inline]
    pub fn contacts(&mut self, i: usize, ctx: &mut Context<'_>) {
        let shocked = ctx.creatures[i].shocked;
        if !self.teleporters.is_empty() {
            self.teleport(i, ctx);
        }
        if !self.doors.is_empty() {
            self.trigger_doors(i, ctx);
        }
        if !self.actors.is_empty() || !self.flyers.is_empty() {
            self.predator_contacts(i, ctx);
        }
        // A predator's shock counts too.
        let c = &mut ctx.creatures[i];
        if c.shocked && !shocked {
            c.shock_ticks += 1;
        }
    }

    /// Contacts: creature `i`'s body touching a door's trigger opens the door until tick
    /// `now + open_ticks` (included).
    #[inline]
    fn trigger_doors(&mut self, i: usize, ctx: &mut Context<'_>) {
        let position = ctx.creatures[i].pose.position;
        for k in 0..self.doors.len() {
            let t = &ctx.things[self.doors[k].trigger];
            if circles_touch(position, ctx.radius, t.position, t.radius) {
                self.doors[k].open_until = Some(ctx.tick + self.doors[k].open_ticks);
                if ctx.events.on() && !ctx.walls.door_open(k) {
                    ctx.events.push(WorldEvent::DoorOpened {
                        door: k,
                        creature: i,
                    });
                }
                ctx.walls.set_door_open(k, true);
            }
        }
    }

    /// Contacts: creature `i`'s body touching a teleporter's entry (the first in file order)
    /// jumps to its exit, unless a body there would touch a wall, another living creature or
    /// a wanderer.
    #[inline]
    fn teleport(&self, i: usize, ctx: &mut Context<'_>) {
        let r = ctx.radius;
        let position = ctx.creatures[i].pose.position;
        let Some(k) = self
            .teleporters
            .iter()
            .position(|t| circles_touch(position, r, t.entry, t.radius))
        else {
            return;
        };
        let t = self.teleporters[k];
        let walls_free = !ctx
            .walls
            .blocking()
            .iter()
            .any(|s| circle_touches_segment(t.exit, r, s));
        let bodies_free = !ctx
            .creatures
            .iter()
            .enumerate()
            .any(|(j, c)| j != i && c.alive && circles_touch(t.exit, r, c.pose.position, r))
            && !ctx
                .things
                .iter()
                .any(|b| b.blocks && circles_touch(t.exit, r, b.position, b.radius));
        if walls_free && bodies_free {
            let c = &mut ctx.creatures[i];
            c.pose.position = t.exit;
            if let Some(h) = t.exit_heading {
                c.pose.heading = h;
            }
            if ctx.events.on() {
                ctx.events.push(WorldEvent::Teleport {
                    creature: i,
                    teleporter: k,
                });
            }
        }
    }

    /// Contacts: ground predators touching creature `i` and air predators within their strike
    /// radius of it attack it, unless its centre is in a safe area.
    #[inline]
    fn predator_contacts(&self, i: usize, ctx: &mut Context<'_>) {
        let position = ctx.creatures[i].pose.position;
        if ctx.in_safe_area(position) {
            return;
        }
        let r = ctx.radius;
        for a in 0..self.actors.len() {
            if let Role::Predator {
                effect, predator, ..
            } = self.actors[a].role
            {
                if self.actors[a].awake()
                    && circles_touch(position, r, self.actors[a].pose.position, r)
                {
                    ctx.attack(i, effect, Attacker::Predator(predator), true);
                }
            }
        }
        for f in 0..self.flyers.len() {
            let fl = self.flyers[f];
            if fl.in_flight() && circles_touch(position, 0.0, fl.position, fl.strike_radius) {
                ctx.attack(i, fl.effect, Attacker::AirPredator(f), true);
            }
        }
    }

    /// The locked doors' running state, in file order.
    pub fn doors(&self) -> &[Door] {
        &self.doors
    }

    /// The teleporters, in file order.
    pub fn teleporters(&self) -> &[Teleporter] {
        &self.teleporters
    }

    /// Wanderers then ground predators, in file order.
    pub fn actors(&self) -> &[Actor] {
        &self.actors
    }

    /// Air predators, in file order.
    pub fn flyers(&self) -> &[Flyer] {
        &self.flyers
    }

    /// Puts wanderer or ground predator `actor` at `pose` (the heading is re-normalised), its
    /// body among `things` with it (for tests and demos).
    pub fn set_actor_pose(&mut self, actor: usize, pose: Pose, things: &mut [Thing]) {
        let a = &mut self.actors[actor];
        a.pose = Pose {
            position: pose.position,
            heading: pose.heading.normalize_or(Vec2::X),
        };
        things[a.thing].position = pose.position;
    }

    /// Puts air predator `flyer` at `position` flying `velocity` LU per tick, its smell among
    /// `things` with it (for tests and demos).
    pub fn set_flyer(
        &mut self,
        flyer: usize,
        position: Vec2,
        velocity: Vec2,
        things: &mut [Thing],
    ) {
        let f = &mut self.flyers[flyer];
        f.position = position;
        f.velocity = velocity;
        things[f.thing].position = position;
    }
}
