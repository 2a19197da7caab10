//! What happened in a tick, told by the world where it decides it: bites, shocks, attacks,
//! teleports, doors opening and closing, deaths ([`WorldEvent`]). The world keeps the events
//! of its last tick in an [`EventLog`], which is off unless someone listens
//! ([`crate::sim::world::World::set_event_log`]): switched off, no event is made or pushed,
//! so a tick costs what it cost without the log and no result changes either way.
//!
//! Readers (the trace of `replay --trace`, [`crate::evo::trace`]) take these events instead of
//! working them out again from two world states, so a change to a rule (who eats, when a
//! predator attacks) is told the way the world decided it. Positions are not in the events:
//! a reader looks them up in the world (the creature, the food object, the door).

use crate::sim::spec::Effect;

/// Who attacked: a ground predator (its index in `[[world.predators]]`) or an air predator
/// (its index in `[[world.air_predators]]`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Attacker {
    /// Ground predator k.
    Predator(usize),
    /// Air predator k.
    AirPredator(usize),
}

/// Why a creature is shocked in a tick.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ShockCause {
    /// Its body touches aversive object k (the first in the world's order) after its move.
    Aversive(usize),
    /// A wall stopped its move in a world with `wall_shock`.
    Wall,
    /// A predator with the shock effect met it in its contacts phase.
    Attack(Attacker),
}

/// Why a creature died.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum DeathCause {
    /// A lethal predator's attack.
    Attack(Attacker),
    /// Ended from outside the tick ([`crate::sim::world::World::kill`]).
    Killed,
}

/// One thing the world decided in a tick. Creatures, food objects, aversive objects,
/// teleporters and doors are named by their index in the world's lists.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum WorldEvent {
    /// Creature `creature` took `amount` (per type A–D, some of it > 0) from food object
    /// `food` in its contacts phase (one event per object per bite).
    Bite {
        /// The eater.
        creature: usize,
        /// The food object.
        food: usize,
        /// What it received per type A–D.
        amount: [f64; 4],
    },
    /// Creature `creature` is shocked in this tick (every tick it is, not only the onset;
    /// one event per cause): its shock state at the end of the tick, which its shock sensor
    /// reads next tick. A shock-effect predator's strike in phase 2 is an [`WorldEvent::Attack`]
    /// only: the creature's own contacts then set its shock state afresh (§9).
    Shock {
        /// The shocked creature.
        creature: usize,
        /// Why.
        cause: ShockCause,
    },
    /// A predator attacked creature `creature` (outside safe areas): in phase 2 after the
    /// predator's move or flight, or in the creature's contacts phase. A predator that meets
    /// a creature in both is told twice.
    Attack {
        /// The attacked creature.
        creature: usize,
        /// Who attacked.
        by: Attacker,
        /// Lethal or shock.
        effect: Effect,
    },
    /// Creature `creature` jumped through teleporter `teleporter` to its exit.
    Teleport {
        /// Who jumped.
        creature: usize,
        /// Which teleporter (index in `[[world.teleporters]]`).
        teleporter: usize,
    },
    /// Creature `creature`'s body touched the trigger of door `door`, which was closed, and
    /// opened it (touching an open door's trigger only keeps it open: no event).
    DoorOpened {
        /// Which door (index in `[[world.doors]]`).
        door: usize,
        /// Who opened it.
        creature: usize,
    },
    /// Door `door`'s open time was over: it closed (phase 1).
    DoorClosed {
        /// Which door.
        door: usize,
    },
    /// Creature `creature` died.
    Death {
        /// Who died.
        creature: usize,
        /// Why.
        cause: DeathCause,
    },
}

/// The events of a world's last tick, and whether anyone listens (switched by the trial
/// runner before the first tick, from its watcher's [`crate::evo::trial::TickObserver`]
/// `listens`).
#[derive(Debug, Clone, Default)]
pub struct EventLog {
    on: bool,
    list: Vec<WorldEvent>,
}

impl EventLog {
    /// Does anyone listen? Every push site asks first.
    #[inline(always)]
    pub fn on(&self) -> bool {
        self.on
    }

    /// Switches the log on or off.
    pub fn set(&mut self, on: bool) {
        self.on = on;
    }

    /// A new tick begins: the last tick's events go (one store: the list keeps its room,
    /// so once it has grown a tick allocates nothing). Called whether or not anyone
    /// listens, which costs less than asking.
    #[inline(always)]
    pub fn clear(&mut self) {
        self.list.clear();
    }

    /// Events the list makes room for at its first event: more than a busy tick of a
    /// shipped experiment tells.
    pub const ROOM: usize = 256;

    /// Adds `event` to this tick's events. Callers check [`EventLog::on`] first, so that
    /// nothing is built when no one listens.
    #[inline]
    pub fn push(&mut self, event: WorldEvent) {
        if self.list.capacity() == 0 {
            self.list.reserve(Self::ROOM);
        }
        self.list.push(event);
    }

    /// The events of the last tick, in the order the world decided them.
    pub fn events(&self) -> &[WorldEvent] {
        &self.list
    }
}
