//! The running world of one trial: walls, food, aversive objects, landmarks, areas and
//! creatures, and the tick loop of §9 in its fixed order. Everything the loop needs is
//! allocated when the world is built; a tick allocates nothing.
//!
//! # One tick ([`World::step`])
//!
//! 1. **Food** regenerates, each object on its own (§4.3; objects at capacity, which
//!    regeneration leaves unchanged, are skipped); **doors** whose open time is over close
//!    (§4.5.2).
//! 2. **Wanderers** then **ground predators** (file order) feel with their whiskers, pick a
//!    command and move; a predator attacks every creature its body then touches outside safe
//!    areas. **Air predators** (file order) fly one tick, re-entering when they left the
//!    arena, and strike every creature within their strike radius outside safe areas (§4.7,
//!    §4.8).
//! 3. Each **living creature**, in index order, does in turn (§9; it sees the world as left by
//!    the creatures before it in this tick):
//!    1. *sense*: whiskers, smell (food, aversive objects, areas, other creatures), food
//!       detectors; the shock sensor carries the creature's shock state from the end of its
//!       previous tick; landmark bearings, area flags and the eye's retina when the
//!       controller receives them; the observation is written, then sensor noise (§7.5) is
//!       applied to it with draws from the trial's generator (see [`crate::sim::noise`]);
//!    2. *act*: its controller turns the observation into a motor command;
//!    3. *move*: the motors are clamped to ±`max_rpt` and the body moves (§8), blocked by
//!       walls, closed doors, wanderers and the other living creatures' bodies;
//!    4. *contacts*: it eats from every food object its body touches (§4.3, §5.2), and is
//!       shocked if its body touches an aversive object or, with `wall_shock`, a wall stopped
//!       its move (§5.2);
//!    5. *metabolism*: m gains what was eaten, then loses the decay per tick and per LU
//!       travelled, never dropping below 0 (§5.3);
//!    6. *gadgets*: it jumps to a teleporter's exit when its body touches the entry and the
//!       exit is free (§4.5.1), opens the doors whose trigger it touches (§4.5.2), and is
//!       attacked by the predators it touches or is under, outside safe areas (§4.7).
//! 4. The tick counter advances.
//!
//! [`World::begin_tick`] (1, 2), [`World::observe`] (3.1), [`World::apply`] (3.3 to 3.6) and
//! [`World::end_tick`] (4) are these phases one by one, for callers that compute the commands
//! (3.2) themselves; `step` is exactly those calls in that order.
//!
//! # What a tick costs
//!
//! Senses, eating and contacts look food, aversive objects and fixed walls up in a uniform
//! grid ([`crate::sim::index`]) instead of looping over every object, and a move is tested
//! only against the walls near it (the walls listed for its start's cell, see `MoverCells`,
//! or while a door stands those the grid finds within its reach), so a creature-tick costs
//! what is around the creature, not what is in the world. Eating and shock take the food and
//! aversive objects a body may touch from the lists of the cell it ends in (also in
//! `MoverCells`), and the next move reuses that cell when it starts where the last one ended.
//! Regeneration visits only food below capacity; worlds without teleporters, doors,
//! wanderers or predators skip those phases on one flag. The answers are the plain loops' to
//! the bit (same tests, same order): [`World::set_brute_force`] runs the plain loops, and
//! the tests compare the two.

use crate::geometry::{circles_touch, Circle, Segment, Vec2};
use crate::seed::Rng;
use crate::sim::area::{bearing, Area};
use crate::sim::controller::{Controller, MotorCommand, ObservationLayout, SensorGroup};
use crate::sim::events::{DeathCause, EventLog, ShockCause, WorldEvent};
use crate::sim::eye::{Eye, Scene};
use crate::sim::food::{Aversive, Food};
use crate::sim::gadgets::{self, Actor, Context, Door, Flyer, Gadgets, Teleporter, Thing};
use crate::sim::index::mover_cells::{LastCell, MoverCells, NearWalls};
use crate::sim::index::{self, Scratch, StaticIndex};
use crate::sim::metabolism::{self, Decay, Metabolism};
use crate::sim::motion::{
    clamp_rpt, plan_clamped_move_inline, plan_move, Blockers, MotionParams, Pose,
};
use crate::sim::noise::Noise;
use crate::sim::placement::{place_creatures, place_objects, PlacementError};
use crate::sim::sensors::{Body, Offsets, Senses, Surroundings};
use crate::sim::smell::Smell;
use crate::sim::spec::{CreatureSpec, Eating, WorldSpec};
use crate::sim::wall::{Wall, Walls};

pub use crate::sim::creature::Creature;

/// A trial world (see the module docs for the tick order).
#[derive(Debug, Clone)]
pub struct World {
    tick: u64,
    arena: [f64; 2],
    walls: Walls,
    /// Kind names; `Food::kind` and `Aversive::kind` index this.
    kinds: Vec<String>,
    food: Vec<Food>,
    /// Indices of the food objects that regeneration would change now (some substance with
    /// r > 0 below capacity), so that phase 1 skips the full ones, on which it does nothing.
    /// Eating adds to it; phase 1 drops the objects it fills. Capacity: the food count.
    regrowing: Vec<u32>,
    /// Is food object k in `regrowing`?
    listed: Vec<bool>,
    aversives: Vec<Aversive>,
    /// The grid over food, aversive objects and fixed walls the senses and contacts query.
    index: StaticIndex,
    /// The grid queries' scratch space.
    scratch: Scratch,
    /// Per-cell lists of the fixed walls a creature's move may reach (see [`MoverCells`]).
    mover_cells: Option<MoverCells>,
    /// Per creature, where its last contacts phase found its body and the cell of
    /// `mover_cells` it was in (see [`LastCell`]).
    last_cell: Vec<LastCell>,
    /// Sense, eat and regenerate with plain loops over every object instead of the grid and
    /// the list of regrowing food (the reference the tests compare the grid against).
    brute_force: bool,
    creatures: Vec<Creature>,
    body: Body,
    motion: MotionParams,
    smell_c: f64,
    inhibit_smell_on_whisker: bool,
    layout: ObservationLayout,
    offsets: Offsets,
    /// Compute smell even when the controller does not receive it (for traces).
    full_sensing: bool,
    /// Every creature's last observation, `layout.len()` values each, back to back.
    observations: Vec<f64>,
    /// Scratch list of the bodies that may block the creature now moving (every other living
    /// creature); refilled for each move, never reallocated.
    blockers: Vec<Circle>,
    /// Distal landmarks (§4.5.3), in file order.
    landmarks: Vec<Vec2>,
    /// Areas (§4.6), in file order.
    areas: Vec<Area>,
    /// The eye, built only when the controller receives it (no cost otherwise).
    eye: Option<Eye>,
    /// Body colour and height of every creature, for eyes.
    creature_colour: [f64; 3],
    creature_height: f64,
    /// Sensor noise on the groups that have it (§7.5).
    noise: Noise,
    /// The trial's generator, kept for what is random during a trial. Draw order within a
    /// tick follows the tick order: wanderers' and wandering predators' new commands (actor
    /// order), air predators' new flights (file order), then each creature's sensor noise
    /// (in the order [`crate::sim::noise`] documents).
    rng: Rng,
    /// Door triggers, teleporter entries, wanderers, ground predators, air predators and the
    /// landmarks that smell, in that order: what senses meet besides food, aversive objects
    /// and creatures.
    things: Vec<Thing>,
    /// Doors, teleporters, wanderers, ground and air predators (§4.5, §4.7, §4.8).
    gadgets: Gadgets,
    /// What [`World::apply`] reads of the above on every move, copied side by side.
    rules: CreatureRules,
    /// Per creature and food object (`creature * food.len() + k`): has the creature taken
    /// substance from the object? Empty (and not kept) unless [`World::track_bites`] asked
    /// for it, so that eating costs nothing more when no one needs it.
    bitten: Vec<bool>,
    /// The events of the last tick, told where they are decided; off unless someone
    /// listens ([`World::set_event_log`]).
    events: EventLog,
}

/// The world's constants that a creature's move, contacts and metabolism read on every tick
/// ([`World::apply`]; some are copies of `World` fields other phases read), side by side in
/// two cache lines. Evaluation runs many worlds in lockstep, so when a world's creature
/// moves, the world's own lines have mostly left the cache since it sensed; spread over
/// `World` these values cost a line each.
#[derive(Debug, Clone, Copy)]
#[repr(align(64))]
struct CreatureRules {
    /// `World::motion`.
    motion: MotionParams,
    /// The body radius, `World::body.radius`.
    radius: f64,
    /// How m decays (§5.3).
    decay: Decay,
    /// How a creature eats.
    eating: Eating,
    /// A wall that stops a move shocks (§5.2).
    wall_shock: bool,
    /// `World::brute_force` (kept equal by [`World::set_brute_force`]).
    brute_force: bool,
    /// `World::gadgets` is active.
    gadgets: bool,
    /// Other bodies may block a move: more than one creature, or things (neither count
    /// changes during a trial).
    bodies: bool,
    /// The world has doors: walls besides the fixed ones may stand.
    doors: bool,
    /// The world has aversive objects (none is added during a trial): without any, the
    /// contacts phase does not look for them.
    aversives: bool,
}

impl CreatureRules {
    /// The rules of `creature` in `world` with `gadgets`; `bodies` and `aversives` as the
    /// fields of the same names say.
    fn new(
        world: &WorldSpec,
        creature: &CreatureSpec,
        gadgets: &Gadgets,
        bodies: bool,
        aversives: bool,
    ) -> CreatureRules {
        CreatureRules {
            motion: motion_params(world, creature),
            radius: creature.radius(),
            decay: Decay {
                per_tick: creature.decay_per_tick,
                per_lu: creature.decay_per_lu,
            },
            eating: creature.eating,
            wall_shock: world.wall_shock,
            brute_force: false,
            gadgets: gadgets.active(),
            bodies,
            doors: !gadgets.doors().is_empty(),
            aversives,
        }
    }
}

/// How the creatures of `creature` move in `world`.
fn motion_params(world: &WorldSpec, creature: &CreatureSpec) -> MotionParams {
    MotionParams {
        wheel: creature.wheel,
        max_rpt: creature.max_rpt,
        search_steps: world.search_steps,
        slippery_walls: world.slippery_walls,
    }
}

/// Landmarks that smell (§4.2) are smelled from their position, as things with no body,
/// pushed onto `things` after the gadgets' in file order; silent ones are left out, so that a
/// world of silent landmarks keeps the senses' paths of a world without things.
fn push_smelling_landmarks(world: &WorldSpec, things: &mut Vec<Thing>) {
    for l in &world.landmarks {
        let smell = Smell::new(&l.odour, l.intensity, l.range);
        if !smell.silent {
            things.push(Thing {
                position: Vec2::from(l.position),
                radius: 0.0,
                smell,
                felt: false,
                blocks: false,
                seen: false,
                colour: [0.0; 3],
                height: 0.0,
            });
        }
    }
}

/// A world and a creature specification validated together: the proof [`World::build`] asks
/// for. Evaluation builds many worlds from the same specifications (a lockstep job builds up
/// to 16), and validating them costs as much as building a small world's grid.
#[derive(Debug, Clone, Copy)]
pub struct ValidSpecs<'a> {
    world: &'a WorldSpec,
    creature: &'a CreatureSpec,
}

impl<'a> ValidSpecs<'a> {
    /// Validates `creature`, then `world` for it.
    pub fn new(
        world: &'a WorldSpec,
        creature: &'a CreatureSpec,
    ) -> Result<ValidSpecs<'a>, PlacementError> {
        creature.validate()?;
        world.validate(creature)?;
        Ok(ValidSpecs { world, creature })
    }
}

/// The [`Surroundings`] of a world's creatures: borrows only the fields it names, so that
/// the scratch space stays free for the senses to use alongside.
macro_rules! surroundings {
    ($world:expr) => {
        Surroundings {
            walls: $world.walls.felt(),
            opaque: $world.walls.opaque(),
            food: &$world.food,
            aversives: &$world.aversives,
            areas: &$world.areas,
            creatures: &$world.creatures,
            things: &$world.things,
            skip_thing: usize::MAX,
            smell_c: $world.smell_c,
            index: &$world.index,
        }
    };
}

/// The [`Context`] the gadgets of a world run in: borrows only the fields it names, so that
/// the gadgets (another field) can be stepped alongside.
macro_rules! gadget_context {
    ($world:expr) => {
        Context {
            tick: $world.tick,
            arena: $world.arena,
            radius: $world.body.radius,
            walls: &mut $world.walls,
            creatures: &mut $world.creatures,
            things: &mut $world.things,
            areas: &$world.areas,
            rng: &mut $world.rng,
            events: &mut $world.events,
        }
    };
}

impl World {
    /// Builds a trial world: validates both specifications, places the explicit objects, the
    /// placement rules' objects and `creatures` creatures with `rng` (in that order), then
    /// keeps `rng` for everything random during the trial.
    pub fn new(
        world: &WorldSpec,
        creature: &CreatureSpec,
        creatures: usize,
        rng: Rng,
    ) -> Result<World, PlacementError> {
        World::build(ValidSpecs::new(world, creature)?, creatures, rng)
    }

    /// [`World::new`] from specifications already validated.
    pub fn build(
        specs: ValidSpecs<'_>,
        creatures: usize,
        mut rng: Rng,
    ) -> Result<World, PlacementError> {
        let ValidSpecs { world, creature } = specs;
        let walls = Walls::build(world);
        let objects = place_objects(world, walls.blocking(), &mut rng)?;
        let radius = creature.radius();
        let poses = place_creatures(
            world,
            radius,
            creatures,
            walls.blocking(),
            &objects,
            &mut rng,
        )?;
        let listed: Vec<bool> = objects.food.iter().map(Food::regrows_now).collect();
        let mut regrowing = Vec::with_capacity(objects.food.len());
        regrowing.extend((0..objects.food.len() as u32).filter(|&k| listed[k as usize]));
        // Whiskers reach `whisker_length` from the centre, contacts the body radius.
        let (index, scratch, mover_cells) = index::build(
            world.arena,
            creature.whisker_length.max(radius),
            radius,
            travel_bound(creature.wheel, creature.max_rpt.abs()),
            &objects.food,
            &objects.aversives,
            &walls,
        );
        let phi = creature.whisker_angle_radians();
        let layout = creature.layout(world);
        let eye = layout
            .range(SensorGroup::Eye)
            .map(|_| Eye::new(&creature.eye));
        let noise = Noise::new(&creature.noise, &layout);
        let (gadgets, mut things) = Gadgets::build(
            world,
            radius,
            creature.body_height(),
            walls.blocking(),
            &poses,
            &mut rng,
        )?;
        push_smelling_landmarks(world, &mut things);
        // After every other draw of the build, so that worlds without a spread keep theirs.
        let births: Vec<Metabolism> = (0..creatures)
            .map(|_| {
                metabolism::at_birth(
                    creature.initial_metabolism,
                    creature.initial_metabolism_spread,
                    &mut rng,
                )
            })
            .collect();
        let rules = CreatureRules::new(
            world,
            creature,
            &gadgets,
            creatures > 1 || !things.is_empty(),
            !objects.aversives.is_empty(),
        );
        Ok(World {
            tick: 0,
            arena: world.arena,
            walls,
            kinds: world.kinds.keys().cloned().collect(),
            food: objects.food,
            regrowing,
            listed,
            aversives: objects.aversives,
            index,
            scratch,
            mover_cells,
            last_cell: vec![LastCell::NONE; creatures],
            brute_force: false,
            creatures: poses
                .into_iter()
                .zip(births)
                .enumerate()
                .map(|(i, (p, m))| Creature::new(p, m, creature.body_smell(i)))
                .collect(),
            body: Body {
                radius,
                whisker_length: creature.whisker_length,
                whisker_cos: libm::cos(phi),
                whisker_sin: libm::sin(phi),
                smell: creature.strongest_body_smell(),
            },
            motion: motion_params(world, creature),
            smell_c: world.smell_c,
            inhibit_smell_on_whisker: creature.inhibit_smell_on_whisker,
            offsets: Offsets::new(&layout),
            observations: vec![0.0; layout.len() * creatures],
            layout,
            full_sensing: false,
            blockers: Vec::with_capacity(creatures + gadgets.actors().len()),
            landmarks: world
                .landmarks
                .iter()
                .map(|l| Vec2::from(l.position))
                .collect(),
            areas: world.areas.iter().map(Area::from_spec).collect(),
            eye,
            creature_colour: creature.body_colour(),
            creature_height: creature.body_height(),
            noise,
            rng,
            things,
            gadgets,
            rules,
            bitten: Vec::new(),
            events: EventLog::default(),
        })
    }

    /// One tick of §9 (fixed order, see the module docs). `controllers.len()` must equal the
    /// number of creatures; creature i is driven by `controllers[i]`. Dead creatures are
    /// skipped (their controllers are not called).
    ///
    /// This is [`World::begin_tick`], then for each creature in index order
    /// [`World::observe`], its controller and [`World::apply`], then [`World::end_tick`].
    ///
    /// # Panics
    /// When `controllers.len()` differs from the number of creatures (a programming error).
    pub fn step<C: Controller>(&mut self, controllers: &mut [C]) {
        assert_eq!(
            controllers.len(),
            self.creatures.len(),
            "World::step needs one controller per creature"
        );
        self.begin_tick();
        for (i, controller) in controllers.iter_mut().enumerate() {
            let Some(observation) = self.observe(i) else {
                continue;
            };
            let command = controller.act(observation);
            self.apply(i, command);
        }
        self.end_tick();
    }

    /// The phases of [`World::step`], for a caller that computes the motor commands itself
    /// (e.g. one brain driving the same creature index in several worlds at once,
    /// [`crate::evo::lockstep`]). Phases 1 and 2 of the tick: food regenerates, doors close,
    /// wanderers, ground and air predators act.
    ///
    /// The only valid order is the one `step` uses: `begin_tick`, then for each creature i
    /// in index order `observe(i)` and, when it returned an observation, `apply(i, command)`,
    /// then `end_tick`. Any other order gives another world (creature i senses the world as
    /// creatures 0..i left it in this tick; noise draws follow the tick order).
    #[inline]
    pub fn begin_tick(&mut self) {
        self.events.clear();
        // Nothing to regrow (every object full, the common case) and no gadgets: nothing
        // to do, known without entering the loops.
        if self.brute_force {
            self.regenerate_all_food();
        } else if !self.regrowing.is_empty() {
            self.regenerate_food();
        }
        if self.gadgets.active() {
            self.begin_gadgets();
        }
    }

    /// Phase 1 (doors) and 2 of the tick.
    #[inline(never)]
    fn begin_gadgets(&mut self) {
        self.gadgets.close_doors(&mut gadget_context!(self));
        for a in 0..self.gadgets.actors().len() {
            self.act_actor(a);
        }
        self.gadgets.fly(&mut gadget_context!(self));
    }

    /// Phase 3.1 of the tick (see [`World::begin_tick`] for the order): creature `creature`
    /// senses and its observation is returned, or None when it is dead (a dead creature
    /// neither senses nor draws noise, and must not be given a command).
    ///
    /// # Panics
    /// When `creature` is out of range.
    pub fn observe(&mut self, creature: usize) -> Option<&[f64]> {
        if !self.creatures[creature].alive {
            return None;
        }
        let width = self.layout.len();
        // Out of `self` while `sense` writes into it (no allocation: the buffer moves).
        let mut observations = std::mem::take(&mut self.observations);
        self.sense(
            creature,
            &mut observations[creature * width..(creature + 1) * width],
        );
        self.observations = observations;
        Some(self.observation(creature))
    }

    /// [`World::observe`], writing the observation into `out` (for instance straight into
    /// a batch of observations, [`crate::evo::lockstep`]) instead of the world's own buffer:
    /// the same senses, noise draws and values. Returns false, writing nothing, when the
    /// creature is dead. [`World::observation`] keeps what `observe` last wrote.
    ///
    /// # Panics
    /// When `creature` is out of range, or `out` is not [`World::layout`]`.len()` long.
    #[inline]
    pub fn observe_into(&mut self, creature: usize, out: &mut [f64]) -> bool {
        if !self.creatures[creature].alive {
            return false;
        }
        assert_eq!(out.len(), self.layout.len(), "one observation's width");
        self.sense(creature, out);
        true
    }

    /// Phases 3.3 to 3.6 of the tick (see [`World::begin_tick`] for the order): creature
    /// `creature` moves by `command` (clamped), then eats, is shocked, teleports, opens
    /// doors and meets predators. Call it only after [`World::observe`] returned an
    /// observation for this creature in this tick.
    ///
    /// # Panics
    /// When `creature` is out of range.
    pub fn apply(&mut self, creature: usize, command: MotorCommand) {
        debug_assert!(
            self.creatures[creature].alive,
            "World::apply on a dead creature"
        );
        self.move_and_contact(creature, command);
    }

    /// Phase 4 of the tick (see [`World::begin_tick`] for the order): the tick counter
    /// advances.
    pub fn end_tick(&mut self) {
        self.tick += 1;
    }

    /// Phase 1: every food object regenerates. Only those in `regrowing` can change, each
    /// on its own, so the others are skipped and the order does not matter.
    #[inline(never)]
    fn regenerate_food(&mut self) {
        let mut kept = 0;
        for n in 0..self.regrowing.len() {
            let k = self.regrowing[n];
            let f = &mut self.food[k as usize];
            f.regenerate();
            if f.regrows_now() {
                self.regrowing[kept] = k;
                kept += 1;
            } else {
                self.listed[k as usize] = false;
            }
        }
        self.regrowing.truncate(kept);
    }

    /// Phase 1 with the plain loop over every food object (under `brute_force`).
    #[inline(never)]
    fn regenerate_all_food(&mut self) {
        for f in &mut self.food {
            f.regenerate();
        }
    }

    /// Phase 3.1: creature `i` senses and its observation is written into `out`.
    ///
    /// [`Surroundings::sense`] step by step, so that the smell sensors land in one local
    /// that both the creature and the observation are copied from (no [`Senses`] in
    /// between); [`World::set_brute_force`] goes through [`World::sense_brute_force`].
    fn sense(&mut self, i: usize, out: &mut [f64]) {
        if self.brute_force {
            return self.sense_brute_force(i, out);
        }
        let surroundings = surroundings!(self);
        let body = &self.body;
        let pose = self.creatures[i].pose;
        let tips = body.whisker_tips(pose.position, pose.heading);
        let (whiskers, food) = surroundings.whiskers_and_food(i, body, pose.position, tips);
        let inhibited = self.inhibit_smell_on_whisker && (whiskers[0] || whiskers[1]);
        let mut smell = [[0.0; 8]; 2];
        if (self.full_sensing || self.offsets.has_smell()) && !inhibited {
            surroundings.smell_pair(i, body, tips, &mut self.scratch, &mut smell);
        }
        self.record_senses(i, out, whiskers, &smell, food);
    }

    /// [`World::sense`] with the plain loops ([`Surroundings::sense_all`]).
    #[inline(never)]
    fn sense_brute_force(&mut self, i: usize, out: &mut [f64]) {
        let smell = self.full_sensing || self.offsets.has_smell();
        let inhibit = self.inhibit_smell_on_whisker;
        let senses: Senses = surroundings!(self).sense_all(i, &self.body, smell, inhibit);
        self.record_senses(i, out, senses.whiskers, &senses.smell, senses.food);
    }

    /// The rest of phase 3.1 once creature `i` has sensed `whiskers`, `smell` and `food`:
    /// they are kept in the creature, the observation is written into `out`, then sensor
    /// noise is applied to it.
    #[inline(always)]
    fn record_senses(
        &mut self,
        i: usize,
        out: &mut [f64],
        whiskers: [bool; 2],
        smell: &[[f64; 8]; 2],
        food: [bool; 4],
    ) {
        let c = &mut self.creatures[i];
        c.whiskers = whiskers;
        c.smell = *smell;
        c.food_detectors = food;
        self.offsets
            .write_senses(out, whiskers, smell, food, c.shocked, &c.metabolism);
        let pose = c.pose;
        if self.offsets.world_groups {
            self.write_world_groups(i, out, pose);
        }
        if !self.noise.is_empty() {
            self.noise.apply(out, &mut self.rng);
        }
    }

    /// Landmark bearings, area flags and the eye's retina of creature `i` at `pose`, into
    /// its observation `out` (the groups of [`Offsets::world_groups`]).
    #[inline(never)]
    fn write_world_groups(&mut self, i: usize, out: &mut [f64], pose: Pose) {
        if let Some(o) = self.offsets.landmarks {
            for (k, &l) in self.landmarks.iter().enumerate() {
                let (s, c) = bearing(pose.position, pose.heading, l);
                out[o + 2 * k] = s;
                out[o + 2 * k + 1] = c;
            }
        }
        if let Some(o) = self.offsets.areas {
            for (k, a) in self.areas.iter().enumerate() {
                out[o + k] = if a.contains(pose.position) { 1.0 } else { 0.0 };
            }
        }
        if let (Some(o), Some(eye)) = (self.offsets.eye, self.eye.as_mut()) {
            let scene = Scene {
                walls: self.walls.all(),
                food: &self.food,
                aversives: &self.aversives,
                creatures: &self.creatures,
                creature_radius: self.body.radius,
                creature_colour: self.creature_colour,
                creature_height: self.creature_height,
                things: &self.things,
            };
            let n = eye.len();
            eye.render(&scene, pose.position, pose.heading, i, &mut out[o..o + n]);
        }
    }

    /// Phases 3.3 to 3.5: clamp the motors and move creature `i`, blocked by walls and by the
    /// other living creatures, then its contacts: eating, shock and metabolism. One function,
    /// so that the creature is looked up once for its move and its contacts. The brute-force
    /// choice is made here, once for the phase.
    #[inline(always)]
    fn move_and_contact(&mut self, i: usize, command: MotorCommand) {
        if self.rules.brute_force {
            self.move_and_contact_brute_force(i, command);
        } else {
            self.move_and_contact_with::<false>(i, command);
        }
    }

    /// [`World::move_and_contact`] with the plain loops over every wall and object.
    #[inline(never)]
    fn move_and_contact_brute_force(&mut self, i: usize, command: MotorCommand) {
        self.move_and_contact_with::<true>(i, command);
    }

    /// [`World::move_and_contact`], with the plain loops when `BRUTE` and the indexes else.
    #[inline(always)]
    fn move_and_contact_with<const BRUTE: bool>(&mut self, i: usize, command: MotorCommand) {
        let rules = &self.rules;
        let command = MotorCommand {
            left: clamp_motor(command.left, rules.motion.max_rpt),
            right: clamp_motor(command.right, rules.motion.max_rpt),
            eat: command.eat,
        };
        let start = self.creatures[i].pose.position;
        let near = self.creature_walls_near::<BRUTE>(i, start, command);
        // A lone creature in a world without things has no bodies to meet (the common case),
        // and its move does not read `blockers` (another cache line).
        let circles: &[Circle] = if self.rules.bodies {
            self.fill_blockers(i);
            &self.blockers
        } else {
            &[]
        };
        let rules = &self.rules;
        let blockers = Blockers {
            segments: near.walls(&self.mover_cells, &self.scratch),
            circles,
        };
        let c = &mut self.creatures[i];
        // Clamped above: with a positive bound, clamping again as `plan_move` does changes
        // nothing, so only a bound of 0 (or below) needs `plan_move`'s own clamp.
        let (pose, radius) = (c.pose, rules.radius);
        let (left, right) = if rules.motion.max_rpt > 0.0 {
            (command.left, command.right)
        } else {
            let max = rules.motion.max_rpt;
            (clamp_rpt(command.left, max), clamp_rpt(command.right, max))
        };
        let outcome = plan_clamped_move_inline(pose, left, right, radius, &rules.motion, &blockers);
        c.pose = outcome.pose;
        c.travelled += outcome.travelled;
        c.command = command;
        c.blocked = outcome.blocked;
        // Phases 3.4 and 3.5: eating, shock and metabolism of the creature after its move.
        //
        // The food and aversive objects the body may touch come from the list of its cell in
        // `mover_cells` when it ends in one (see [`MoverCells::with_contacts`]), else from the
        // grid: both hold every object it touches, and each is tested as before, in food order.
        let position = outcome.pose.position;
        let eats = match rules.eating {
            Eating::Contact => true,
            Eating::Action => command.eat > 0.5,
        };
        let cell = match &self.mover_cells {
            Some(cells) if !BRUTE => {
                let last = &mut self.last_cell[i];
                let f = cells.grid_coordinates(position);
                // Most moves end in the cell they started in (cells are far wider than a
                // tick's move): its range settles it without the index computation.
                let lists = if last.holds(f) {
                    last.at = position;
                    Some(last.lists)
                } else {
                    cells.cell_at(f).map(|k| {
                        *last = LastCell::new(position, cells.lists[k], f);
                        last.lists
                    })
                };
                lists.map(|lists| (cells, lists))
            }
            _ => None,
        };
        let mut received = [0.0; 4];
        if eats {
            // Bites in food list order: `received` adds floats.
            let near: &[u32] = if let Some((cells, lists)) = cell {
                cells.food(lists)
            } else {
                let (lo, hi) = (position - radius, position + radius);
                if BRUTE {
                    self.scratch.food.clear();
                    self.scratch.food.extend(0..self.food.len() as u32);
                } else {
                    let food = &self.food;
                    self.index.food_where(lo, hi, &mut self.scratch, |k| {
                        circles_touch(position, radius, food[k].position, food[k].radius)
                    });
                }
                &self.scratch.food
            };
            // Asked once per eating creature-tick, not per bite.
            let listened = self.events.on();
            for &k in near {
                let f = &mut self.food[k as usize];
                if circles_touch(position, radius, f.position, f.radius) {
                    let bite = f.take_bite();
                    for (r, g) in received.iter_mut().zip(bite) {
                        *r += g;
                    }
                    if !self.bitten.is_empty() && bite.iter().any(|&g| g > 0.0) {
                        self.bitten[i * self.listed.len() + k as usize] = true;
                    }
                    if listened && bite.iter().any(|&g| g > 0.0) {
                        self.events.push(WorldEvent::Bite {
                            creature: i,
                            food: k as usize,
                            amount: bite,
                        });
                    }
                    if !self.listed[k as usize] && f.regrows_now() {
                        self.listed[k as usize] = true;
                        self.regrowing.push(k);
                    }
                }
            }
        }
        for (e, r) in c.eaten.iter_mut().zip(received) {
            *e += r;
        }
        let touches = |a: &Aversive| circles_touch(position, radius, a.position, a.radius);
        let aversive = if !rules.aversives {
            false
        } else if BRUTE {
            self.aversives.iter().any(touches)
        } else if let Some((cells, lists)) = cell {
            cells
                .aversives(lists)
                .iter()
                .any(|&a| touches(&self.aversives[a as usize]))
        } else {
            let (lo, hi) = (position - radius, position + radius);
            self.index
                .any_aversive(lo, hi, |k| touches(&self.aversives[k]))
        };
        c.shocked = aversive || (rules.wall_shock && outcome.blocked_by_wall);
        if c.shocked && self.events.on() {
            tell_shock(
                &mut self.events,
                &self.aversives,
                i,
                position,
                radius,
                aversive,
            );
        }
        rules
            .decay
            .apply(&mut c.metabolism, &received, outcome.travelled);
        c.age += 1;
        if c.shocked {
            c.shock_ticks += 1;
        }
        if rules.gadgets {
            self.gadget_contacts(i);
        }
    }

    /// `blockers`: the bodies that may block creature `i`'s move, every other living
    /// creature and every blocking thing.
    #[inline(never)]
    fn fill_blockers(&mut self, i: usize) {
        self.blockers.clear();
        for (j, other) in self.creatures.iter().enumerate() {
            if j != i && other.alive {
                self.blockers
                    .push(Circle::new(other.pose.position, self.rules.radius));
            }
        }
        for t in &self.things {
            if t.blocks {
                self.blockers.push(Circle::new(t.position, t.radius));
            }
        }
    }

    /// An upper bound on how far a body's centre moves in one tick with motor signals `left`
    /// and `right` clamped to ±`max_rpt`: the chord of eq. 30 is at most the larger wheel
    /// distance 2πw·|RPT| (|sinc| ≤ 1), with a margin for rounding. +∞ when not finite.
    fn max_travel(&self, left: f64, right: f64, max_rpt: f64) -> f64 {
        let m = max_rpt.abs();
        let clamp = |x: f64| {
            if x.is_nan() {
                0.0
            } else {
                x.min(m).max(-m).abs()
            }
        };
        self.travel_bound(clamp(left).max(clamp(right)))
    }

    /// [`World::max_travel`] for the larger clamped signal magnitude `rpt`.
    #[inline]
    fn travel_bound(&self, rpt: f64) -> f64 {
        travel_bound(self.motion.wheel, rpt)
    }

    /// [`World::walls_near`] for creature `i` starting at `start` with the clamped `command`.
    /// With no door standing, the cells of `mover_cells` cover its move: they were built for
    /// `travel_bound(wheel, |max_rpt|)`, and the clamped signals' magnitudes are at most
    /// |max_rpt|, so their bound (monotone in the magnitude) is no larger. The bound is then
    /// not computed; `walls_near` would have compared it and taken the same cell.
    #[inline]
    fn creature_walls_near<const BRUTE: bool>(
        &mut self,
        i: usize,
        start: Vec2,
        command: MotorCommand,
    ) -> NearWalls {
        if let (Some(cells), false) = (&self.mover_cells, BRUTE) {
            if !self.rules.doors || self.walls.felt().len() == self.walls.fixed_count() {
                debug_assert!(
                    self.travel_bound(command.left.abs().max(command.right.abs())) <= cells.travel
                );
                let last = self.last_cell[i];
                if last.at == start {
                    return NearWalls::Cell(last.lists);
                }
                if let Some(k) = cells.cell_of(start) {
                    return NearWalls::Cell(cells.lists[k]);
                }
            }
        }
        // The signals are clamped already (not NaN, within ±max_rpt): `max_travel`'s own
        // clamping would leave their magnitudes as they are.
        let travel = self.travel_bound(command.left.abs().max(command.right.abs()));
        self.walls_near(start, travel, Some(i))
    }

    /// The walls that may block a body of this world's radius moving at most `travel` from
    /// `start` (every standing wall under `brute_force`): the list of the start's cell in
    /// `mover_cells` when no door stands and the move is within the reach the lists were
    /// built for, else `scratch.blocking`, filled by the grid. Motion's verdict is a yes/no
    /// over the walls, so leaving out walls that cannot be reached changes nothing, and
    /// listing more walls than needed changes nothing either (see [`MoverCells`]).
    ///
    /// `creature`: the mover, when a creature, whose last cell is tried first.
    #[inline(always)]
    fn walls_near(&mut self, start: Vec2, travel: f64, creature: Option<usize>) -> NearWalls {
        let felt = self.walls.felt();
        if self.brute_force {
            self.scratch.blocking.clear();
            self.scratch.blocking.extend(felt.iter().map(|w| w.segment));
            return NearWalls::Scratch;
        }
        if let Some(cells) = &self.mover_cells {
            if felt.len() == self.walls.fixed_count() && travel <= cells.travel {
                if let Some(last) = creature.map(|i| self.last_cell[i]) {
                    if last.at == start {
                        return NearWalls::Cell(last.lists);
                    }
                }
                if let Some(k) = cells.cell_of(start) {
                    return NearWalls::Cell(cells.lists[k]);
                }
            }
        }
        self.index
            .blocking_near(start, travel, self.body.radius, felt, &mut self.scratch);
        NearWalls::Scratch
    }

    /// Phase 3.6: teleporters, door triggers and predators meet creature `i`.
    fn gadget_contacts(&mut self, i: usize) {
        self.gadgets.contacts(i, &mut gadget_context!(self));
    }

    /// Phase 2 (predators and wanderers): actor `a` feels with its whiskers, picks its
    /// command ([`Gadgets::command`]), moves, and (a predator) attacks what it touches
    /// ([`Gadgets::moved`]). Wanderers are blocked by
    /// walls, creatures and each other; ground predators by walls and wanderers only (they
    /// reach their prey: contact is the attack).
    fn act_actor(&mut self, a: usize) {
        let actor = self.gadgets.actors()[a];
        let r = self.body.radius;
        let tips = self
            .body
            .whisker_tips(actor.pose.position, actor.pose.heading);
        let surroundings = Surroundings {
            walls: self.walls.felt(),
            opaque: self.walls.opaque(),
            food: &self.food,
            aversives: &self.aversives,
            areas: &self.areas,
            creatures: &self.creatures,
            things: &self.things,
            skip_thing: actor.thing,
            smell_c: self.smell_c,
            index: &self.index,
        };
        let feel = |tip| {
            if self.brute_force {
                surroundings.whisker_touches_all(usize::MAX, &self.body, actor.pose.position, tip)
            } else {
                surroundings.whisker_touches(usize::MAX, &self.body, actor.pose.position, tip)
            }
        };
        let whiskers = [feel(tips[0]), feel(tips[1])];
        let (left, right, predator) = self
            .gadgets
            .command(a, whiskers, &mut gadget_context!(self));
        self.blockers.clear();
        if predator.is_none() {
            for c in &self.creatures {
                if c.alive {
                    self.blockers.push(Circle::new(c.pose.position, r));
                }
            }
        }
        for (k, t) in self.things.iter().enumerate() {
            if t.blocks && k != actor.thing {
                self.blockers.push(Circle::new(t.position, t.radius));
            }
        }
        let params = MotionParams {
            max_rpt: actor.max_rpt,
            ..self.motion
        };
        let travel = self.max_travel(left, right, params.max_rpt);
        let near = self.walls_near(actor.pose.position, travel, None);
        let blockers = Blockers {
            segments: near.walls(&self.mover_cells, &self.scratch),
            circles: &self.blockers,
        };
        let outcome = plan_move(actor.pose, left, right, r, &params, &blockers);
        self.gadgets
            .moved(a, outcome.pose, predator, &mut gadget_context!(self));
    }

    /// Ticks done so far.
    pub fn tick(&self) -> u64 {
        self.tick
    }

    /// The creatures, in index order.
    pub fn creatures(&self) -> &[Creature] {
        &self.creatures
    }

    /// The observation creature `creature`'s controller received at the last step (all zeros
    /// before the first), laid out as [`World::layout`] says.
    ///
    /// # Panics
    /// When `creature` is out of range.
    pub fn observation(&self, creature: usize) -> &[f64] {
        let width = self.layout.len();
        &self.observations[creature * width..(creature + 1) * width]
    }

    /// The observation layout (the creature spec's [`CreatureSpec::layout`]).
    pub fn layout(&self) -> &ObservationLayout {
        &self.layout
    }

    /// Every wall, the four boundary walls first when the world has them.
    pub fn walls(&self) -> &[Wall] {
        self.walls.all()
    }

    /// Segments of every wall (what blocks motion and whiskers).
    pub fn wall_segments(&self) -> &[Segment] {
        self.walls.blocking()
    }

    /// The food objects, explicit ones first, then each placement rule's.
    pub fn food(&self) -> &[Food] {
        &self.food
    }

    /// The aversive objects, in the same order as food.
    pub fn aversives(&self) -> &[Aversive] {
        &self.aversives
    }

    /// Kind names (sorted); `Food::kind` and `Aversive::kind` index this.
    pub fn kinds(&self) -> &[String] {
        &self.kinds
    }

    /// Arena `[width, height]` in LU.
    pub fn arena(&self) -> [f64; 2] {
        self.arena
    }

    /// Body radius d/2 of every creature in LU.
    pub fn creature_radius(&self) -> f64 {
        self.body.radius
    }

    /// The whisker tips (left, right) of creature `creature` now: where its smell sensors sit.
    pub fn whisker_tips(&self, creature: usize) -> [Vec2; 2] {
        let pose = self.creatures[creature].pose;
        self.body.whisker_tips(pose.position, pose.heading)
    }

    /// Compute smell every tick even when the controller does not receive it, so that
    /// [`Creature::smell`] is filled for traces and demos (default: off, smell costs the most
    /// of all senses). Does not change the observations or any other result.
    pub fn set_full_sensing(&mut self, on: bool) {
        self.full_sensing = on;
    }

    /// Sense, eat and regenerate food with plain loops over every object instead of the
    /// spatial grid (default: off). The results are the same to the bit; tests compare the
    /// two.
    pub fn set_brute_force(&mut self, on: bool) {
        self.brute_force = on;
        self.rules.brute_force = on;
    }

    /// The grid the senses query (for tests and benchmarks).
    pub fn index(&self) -> &StaticIndex {
        &self.index
    }

    /// Distal landmarks (§4.5.3), in file order.
    pub fn landmarks(&self) -> &[Vec2] {
        &self.landmarks
    }

    /// Areas (§4.6), in file order.
    pub fn areas(&self) -> &[Area] {
        &self.areas
    }

    /// Is `position` inside a safe area (bounds included)? Predators leave such creatures
    /// alone.
    pub fn in_safe_area(&self, position: Vec2) -> bool {
        gadgets::in_safe_area(&self.areas, position)
    }

    /// Renders what creature `creature` sees now into `out` (3 × width × height values, the
    /// layout of the eye group), without noise, or returns false when the creature has no
    /// eye (its controller does not receive it). For tests and pictures.
    pub fn render_eye(&mut self, creature: usize, out: &mut [f64]) -> bool {
        let Some(eye) = self.eye.as_mut() else {
            return false;
        };
        let pose = self.creatures[creature].pose;
        let scene = Scene {
            walls: self.walls.all(),
            food: &self.food,
            aversives: &self.aversives,
            creatures: &self.creatures,
            creature_radius: self.body.radius,
            creature_colour: self.creature_colour,
            creature_height: self.creature_height,
            things: &self.things,
        };
        eye.render(&scene, pose.position, pose.heading, creature, out);
        true
    }

    /// The retina `[width, height]` of the creatures' eye, when their controller receives it.
    pub fn retina_size(&self) -> Option<[usize; 2]> {
        self.eye.as_ref().map(Eye::size)
    }

    /// Puts creature `creature` at `pose` (the heading is re-normalised). For tests, demos and
    /// gadgets such as teleporters; the caller is responsible for not putting it in a wall
    /// (motion never moves a body deeper into an obstacle it starts in).
    pub fn set_pose(&mut self, creature: usize, pose: Pose) {
        self.creatures[creature].pose = Pose {
            position: pose.position,
            heading: pose.heading.normalize_or(Vec2::X),
        };
    }

    /// Is locked door `door` (index in `[[world.doors]]`) open now?
    ///
    /// # Panics
    /// When `door` is out of range.
    pub fn door_open(&self, door: usize) -> bool {
        self.walls.door_open(door)
    }

    /// The boundary and interior walls, which stand all trial (boundary walls first); the
    /// doors are [`World::door_walls`].
    pub fn fixed_walls(&self) -> &[Wall] {
        self.walls.fixed()
    }

    /// Every locked door's wall (index in `[[world.doors]]`), open or closed.
    pub fn door_walls(&self) -> &[Wall] {
        self.walls.doors()
    }

    /// The locked doors' running state (their triggers are [`World::things`]), in file order.
    pub fn doors(&self) -> &[Door] {
        self.gadgets.doors()
    }

    /// The teleporters, in file order.
    pub fn teleporters(&self) -> &[Teleporter] {
        self.gadgets.teleporters()
    }

    /// Wanderers then ground predators, in file order.
    pub fn actors(&self) -> &[Actor] {
        self.gadgets.actors()
    }

    /// Air predators, in file order.
    pub fn flyers(&self) -> &[Flyer] {
        self.gadgets.flyers()
    }

    /// Door triggers, teleporter entries, wanderers, ground and air predators, then the
    /// landmarks that smell, in that order, as the senses meet them.
    pub fn things(&self) -> &[Thing] {
        &self.things
    }

    /// Puts wanderer or ground predator `actor` at `pose` (for tests and demos).
    pub fn set_actor_pose(&mut self, actor: usize, pose: Pose) {
        self.gadgets.set_actor_pose(actor, pose, &mut self.things);
    }

    /// Puts air predator `flyer` at `position` flying `velocity` LU per tick (for tests and
    /// demos).
    pub fn set_flyer(&mut self, flyer: usize, position: Vec2, velocity: Vec2) {
        self.gadgets
            .set_flyer(flyer, position, velocity, &mut self.things);
    }

    /// Locked doors (`[[world.doors]]`), in file order: how many.
    pub fn door_count(&self) -> usize {
        self.gadgets.doors().len()
    }

    /// From now on, notes which food objects each creature takes substance from (for
    /// behaviour measures and fitness terms that count distinct objects; see
    /// [`World::bitten`]). Off unless asked for: eating then does nothing more.
    pub fn track_bites(&mut self) {
        if self.bitten.is_empty() {
            self.bitten = vec![false; self.creatures.len() * self.food.len()];
        }
    }

    /// For each food object (in [`World::food`] order), has creature `creature` taken some
    /// substance from it since [`World::track_bites`]? Empty when bites are not tracked.
    ///
    /// # Panics
    /// When `creature` is out of range while bites are tracked.
    pub fn bitten(&self, creature: usize) -> &[bool] {
        if self.bitten.is_empty() {
            return &[];
        }
        let n = self.food.len();
        &self.bitten[creature * n..(creature + 1) * n]
    }

    /// Ends creature `creature`'s life now: it no longer senses, moves, eats, blocks, or is
    /// felt or smelled by others. Its last state stays readable.
    pub fn kill(&mut self, creature: usize) {
        let c = &mut self.creatures[creature];
        if c.alive && self.events.on() {
            self.events.push(WorldEvent::Death {
                creature,
                cause: DeathCause::Killed,
            });
        }
        c.alive = false;
    }

    /// Switches the event log on or off (default: off). On, each tick's [`World::events`]
    /// tell what the world decided in it; off, nothing is recorded and a tick costs what it
    /// did without the log. Neither changes any result.
    pub fn set_event_log(&mut self, on: bool) {
        self.events.set(on);
    }

    /// Is the event log on ([`World::set_event_log`])?
    pub fn event_log_on(&self) -> bool {
        self.events.on()
    }

    /// The events of the last tick, in the order the world decided them (empty while the
    /// log is off; cleared when a tick begins). A [`World::kill`] between ticks is added to
    /// the list of the tick before.
    pub fn events(&self) -> &[WorldEvent] {
        self.events.events()
    }
}

/// Tells the shock creature `i` received in its contacts phase at `position` (body `radius`):
/// from the first aversive object it touches when `aversive`, else from a wall. Out of the
/// tick's path: only a listened-to world comes here.
#[inline(never)]
fn tell_shock(
    events: &mut EventLog,
    aversives: &[Aversive],
    i: usize,
    position: Vec2,
    radius: f64,
    aversive: bool,
) {
    let cause = aversives
        .iter()
        .position(|a| aversive && circles_touch(position, radius, a.position, a.radius))
        .map_or(ShockCause::Wall, ShockCause::Aversive);
    events.push(WorldEvent::Shock { creature: i, cause });
}

/// Motor clamping: to ±`max_rpt`; NaN (a broken controller) counts as 0 so that the world
/// stays finite, as motion does.
#[inline]
fn clamp_motor(x: f64, max_rpt: f64) -> f64 {
    // `f64::clamp`'s steps without its check that -max_rpt <= max_rpt, which the
    // specification's validation settles once (max_rpt is a number >= 0): the same bits.
    if x.is_nan() {
        0.0
    } else {
        let mut x = x;
        if x < -max_rpt {
            x = -max_rpt;
        }
        if x > max_rpt {
            x = max_rpt;
        }
        x
    }
}

/// An upper bound on how far a body's centre moves in one tick with wheel diameter `wheel` and
/// clamped signal magnitudes at most `rpt` (see [`World::max_travel`]). +∞ when not finite.
fn travel_bound(wheel: f64, rpt: f64) -> f64 {
    let d = std::f64::consts::TAU * wheel.abs() * rpt;
    if d.is_finite() {
        d * (1.0 + 1e-9) + 1e-9
    } else {
        f64::INFINITY
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::index::mover_cells::tests::step;
    use rand::{Rng as _, SeedableRng};

    /// Motor clamping gives `f64::clamp`'s bits (NaN as 0) for every bound the
    /// specification allows (a number ≥ 0, ±0 included) and every kind of signal.
    #[test]
    fn clamp_motor_is_f64_clamp() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
        let bounds = [0.0, 0.25, 1.0, 1e300, f64::INFINITY, f64::MIN_POSITIVE];
        let special = [
            0.0,
            -0.0,
            0.25,
            -0.25,
            1.0,
            -1.0,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            f64::MIN_POSITIVE,
            -f64::MIN_POSITIVE,
            5e-324,
        ];
        let check = |x: f64, m: f64| {
            let want = if x.is_nan() { 0.0 } else { x.clamp(-m, m) };
            assert_eq!(
                clamp_motor(x, m).to_bits(),
                want.to_bits(),
                "{x:e} to ±{m:e}"
            );
        };
        for &m in &bounds {
            for &x in &special {
                check(x, m);
            }
            if m > 0.0 && m.is_finite() {
                check(step(m, 1), m);
                check(step(m, -1), m);
                check(-step(m, 1), m);
                check(-step(m, -1), m);
            }
            for _ in 0..10_000 {
                check(rng.gen_range(-2.0..2.0), m);
                check(f64::from_bits(rng.gen::<u64>()), m);
            }
        }
    }
}
