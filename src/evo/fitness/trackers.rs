//! The measures that follow a creature through its life tick by tick and need more than a
//! counter: air predator passes over it ([`FlyerPasses`], `strikes_survived`), the T-maze
//! side it strays to ([`SideChoice`], `richest_side_first`) and its contacts with aversive
//! objects ([`AversiveContacts`]), and the door measure, which the world's events tell.
//!
//! Which of them read the world's events ([`World::events`]) and which measure geometry:
//! - a door opening and an aversive shock are the world's decisions, told where it makes
//!   them, so `door_opened` and `aversive_contacts` read the events (the plan switches the
//!   log on, [`super::LifePlan::prepare`]);
//! - an air predator over a sheltered creature is not an attack (the world decides nothing
//!   then), so `strikes_survived` measures where the flyer is;
//! - "a threat within `threat_radius`" and "inside a safe area" are measurements of the
//!   scene, not events: `shelter_while_threat` stays on geometry too.

use crate::geometry::{circles_touch, Vec2};
use crate::sim::events::{ShockCause, WorldEvent};
use crate::sim::world::World;

/// Did some door open in the world's last tick, whoever opened it?
///
/// `door_opened` is "some door was open at the end of some tick the creature lived"; doors
/// start closed, the world tells every closed door it opens ([`WorldEvent::DoorOpened`]),
/// and a door opened in a tick is still open at that tick's end (doors close in phase 1 of a
/// later tick). So over the ticks of a life, from the first, "some door opened" and "some
/// door open at a tick's end" are the same. Any creature's opening counts: in a group, a door
/// another opened is open for this creature too (the measure's definition).
pub(super) fn door_opened(world: &World) -> bool {
    world
        .events()
        .iter()
        .any(|e| matches!(e, WorldEvent::DoorOpened { .. }))
}

/// `aversive_contacts`: contacts with aversive objects, each counted at its first tick.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(super) struct AversiveContacts {
    /// The body touched an aversive object at the end of the last tick (or at the start).
    touching: bool,
    /// Contacts begun.
    pub(super) count: u64,
}

impl AversiveContacts {
    /// Before the first tick, a contact already going on (the world has decided nothing yet,
    /// so it is measured) at the creature's start position `p`.
    pub(super) fn start(world: &World, p: Vec2) -> AversiveContacts {
        AversiveContacts {
            touching: touches_aversive(world, p),
            count: 0,
        }
    }

    /// Follows creature `creature`, at `p` at the end of the world's last tick.
    pub(super) fn record(&mut self, world: &World, creature: usize, p: Vec2) {
        let touching = touching_aversive(world, creature, p);
        self.count += u64::from(touching && !self.touching);
        self.touching = touching;
    }
}

/// Does creature `creature`'s body, at `p` at the end of the world's last tick, touch an
/// aversive object?
///
/// The world decides it after the creature's move: an aversive object touching the body
/// shocks it ([`ShockCause::Aversive`], told every tick it touches). Nothing moves the body
/// after that in the tick but a teleporter: after a jump ([`WorldEvent::Teleport`]) the body
/// stands somewhere the world has not tested yet (it does so after the next move), so there
/// the contact is measured, as the measure is defined at the tick's end.
fn touching_aversive(world: &World, creature: usize, p: Vec2) -> bool {
    let mut shocked = false;
    for event in world.events() {
        match *event {
            WorldEvent::Shock {
                creature: c,
                cause: ShockCause::Aversive(_),
            } if c == creature => shocked = true,
            WorldEvent::Teleport { creature: c, .. } if c == creature => {
                return touches_aversive(world, p);
            }
            _ => {}
        }
    }
    shocked
}

/// Does a body of the world's creature radius at `p` touch an aversive object? (The test
/// the world makes after a move.)
fn touches_aversive(world: &World, p: Vec2) -> bool {
    let r = world.creature_radius();
    world
        .aversives()
        .iter()
        .any(|a| circles_touch(p, r, a.position, a.radius))
}

/// One air predator pass over a creature, as `strikes_survived` follows it.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
struct Pass {
    /// The creature is inside the predator's strike radius now.
    over: bool,
    /// ... and was sheltered on every tick of this pass so far.
    sheltered: bool,
}

/// `strikes_survived`: every air predator's passes over a creature. Geometry, not events: a
/// pass over a sheltered creature is no attack, so the world tells nothing of it.
#[derive(Debug, Clone, PartialEq, Default)]
pub(super) struct FlyerPasses {
    /// One per air predator, in the world's order.
    passes: Vec<Pass>,
    /// Passes over that were sheltered throughout.
    survived: u64,
}

impl FlyerPasses {
    /// No pass yet over a creature of `world`.
    pub(super) fn start(world: &World) -> FlyerPasses {
        FlyerPasses {
            passes: vec![Pass::default(); world.flyers().len()],
            survived: 0,
        }
    }

    /// Follows the creature at `p` at the end of a tick.
    pub(super) fn record(&mut self, world: &World, p: Vec2) {
        let safe = world.in_safe_area(p);
        for (pass, f) in self.passes.iter_mut().zip(world.flyers()) {
            let over = f.in_flight() && circles_touch(p, 0.0, f.position, f.strike_radius);
            if over {
                pass.sheltered = if pass.over {
                    pass.sheltered && safe
                } else {
                    safe
                };
            } else if pass.over && pass.sheltered {
                self.survived += 1;
            }
            pass.over = over;
        }
    }

    /// Passes survived; one still going counts when the creature is `alive` and was
    /// sheltered so far.
    pub(super) fn survived(&self, alive: bool) -> u64 {
        let open = if alive {
            self.passes.iter().filter(|p| p.over && p.sheltered).count() as u64
        } else {
            0
        };
        self.survived + open
    }
}

/// The T-maze choice as `richest_side_first` follows it: which side of its start line a
/// creature strays to before it first bites the richest food object.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct SideChoice {
    /// The richest food object, in [`World::food`] order.
    pub(super) food: usize,
    /// The creature's start position.
    origin: Vec2,
    /// A unit normal of its start heading: `(p − origin) · normal` is how far `p` lies to
    /// one side of the start line (negative: the other side).
    normal: Vec2,
    /// The food's side (+1 or −1; 0 on the line) ...
    side: f64,
    /// ... and how far onto the other side counts as straying (half the food's distance
    /// from the line).
    limit: f64,
    /// It strayed to the other side before its first bite of the food.
    pub(super) strayed: bool,
    /// It has bitten the food (from then on nothing is followed).
    bitten: bool,
}

impl SideChoice {
    /// The choice creature `creature` of `world` faces at its start; None in a world
    /// without food.
    pub(super) fn start(world: &World, creature: usize) -> Option<SideChoice> {
        let mut richest: Option<(usize, f64)> = None;
        for (k, f) in world.food().iter().enumerate() {
            let full: f64 = f.capacity.iter().sum();
            if richest.is_none_or(|(_, most)| full > most) {
                richest = Some((k, full));
            }
        }
        let (food, _) = richest?;
        let pose = world.creatures()[creature].pose;
        let normal = pose.heading.normalize_or_zero().perp();
        let offset = (world.food()[food].position - pose.position).dot(normal);
        Some(SideChoice {
            food,
            origin: pose.position,
            normal,
            side: if offset == 0.0 { 0.0 } else { offset.signum() },
            limit: offset.abs() / 2.0,
            strayed: false,
            bitten: false,
        })
    }

    /// Follows the creature at `p` after a tick, having bitten the food or not.
    pub(super) fn record(&mut self, bitten: bool, p: Vec2) {
        if self.bitten {
            return;
        }
        self.bitten = bitten;
        // The tick of the first bite ends at the food, on its own side.
        if !bitten && self.side * (p - self.origin).dot(self.normal) < -self.limit {
            self.strayed = true;
        }
    }
}
