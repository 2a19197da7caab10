//! The running world of one trial: walls, food, aversive objects, landmarks, areas and
//! creatures, and the tick loop of §9 in its fixed order. Everything the loop needs is
//! allocated when the world is built; a tick allocates nothing.
//!
//! # One tick ([`World::step`])
//!
//! 1. **Food** regenerates, each object in list order (§4.3).
//! 2. Each **living creature**, in index order, does in turn (§9; it sees the world as left by
//!    the creatures before it in this tick):
//!    1. *sense*: whiskers, smell (food, aversive objects, areas, other creatures), food
//!       detectors; the shock sensor carries the creature's shock state from the end of its
//!       previous tick; landmark bearings, area flags and the eye's retina when the
//!       controller receives them; the observation is written, then sensor noise (§7.5) is
//!       applied to it with draws from the trial's generator (see [`crate::sim::noise`]);
//!    2. *act*: its controller turns the observation into a motor command;
//!    3. *move*: the motors are clamped to ±`max_rpt` and the body moves (§8), blocked by
//!       walls and by the other living creatures' bodies;
//!    4. *contacts*: it eats from every food object its body touches (§4.3, §5.2), and is
//!       shocked if its body touches an aversive object or, with `wall_shock`, a wall stopped
//!       its move (§5.2);
//!    5. *metabolism*: m gains what was eaten, then loses the decay per tick and per LU
//!       travelled, never dropping below 0 (§5.3).
//! 3. The tick counter advances.

use crate::geometry::{circles_touch, Circle, Segment, Vec2};
use crate::seed::Rng;
use crate::sim::area::{bearing, Area};
use crate::sim::controller::{Controller, MotorCommand, ObservationLayout, SensorGroup};
use crate::sim::eye::{Eye, Scene};
use crate::sim::food::{Aversive, Food};
use crate::sim::metabolism::Decay;
use crate::sim::motion::{plan_move, Blockers, MotionParams, MoveOutcome, Pose};
use crate::sim::noise::Noise;
use crate::sim::placement::{place_creatures, place_objects, PlacementError};
use crate::sim::sensors::{Body, Offsets, Senses, Surroundings};
use crate::sim::smell::Smell;
use crate::sim::spec::{CreatureSpec, Eating, WorldSpec};
use crate::sim::wall::{Wall, Walls};

/// One creature: its pose, its metabolism and what it sensed and did in its last tick.
#[derive(Debug, Clone, PartialEq)]
pub struct Creature {
    /// Where the body is and which way it faces.
    pub pose: Pose,
    /// The metabolic state m = ⟨fA, fB, fC, fD⟩ (§5.3).
    pub metabolism: [f64; 4],
    /// Total substance received by eating over its life, per type (before any decay).
    pub eaten: [f64; 4],
    /// Shock state at the end of its last tick: its body touched an aversive object after
    /// moving, or (with `wall_shock`) a wall stopped its move. The shock sensor reads this at
    /// the start of the next tick.
    pub shocked: bool,
    /// Number of ticks that ended with `shocked` set.
    pub shock_ticks: u64,
    /// Living creatures sense, move, eat, block others and are felt and smelled by them.
    pub alive: bool,
    /// Distance travelled over its life in LU.
    pub travelled: f64,
    /// Number of ticks it has lived through.
    pub age: u64,
    /// Left and right whisker at the start of its last tick (§7.3).
    pub whiskers: [bool; 2],
    /// Left and right smell sensors at the start of its last tick, 8 receptors each (§7.1).
    /// All zeros when smell was not computed (see [`World::set_full_sensing`]). Without sensor
    /// noise: noise goes only into the observation.
    pub smell: [[f64; 8]; 2],
    /// Food detectors A–D at the start of its last tick (§5.2).
    pub food_detectors: [bool; 4],
    /// The motor command of its last tick, after clamping to ±`max_rpt`.
    pub command: MotorCommand,
    /// Its last move was cut short by an obstacle.
    pub blocked: bool,
}

impl Creature {
    fn new(pose: Pose, metabolism: [f64; 4]) -> Creature {
        Creature {
            pose,
            metabolism,
            eaten: [0.0; 4],
            shocked: false,
            shock_ticks: 0,
            alive: true,
            travelled: 0.0,
            age: 0,
            whiskers: [false; 2],
            smell: [[0.0; 8]; 2],
            food_detectors: [false; 4],
            command: MotorCommand::default(),
            blocked: false,
        }
    }
}

/// A trial world (see the module docs for the tick order).
#[derive(Debug, Clone)]
pub struct World {
    tick: u64,
    arena: [f64; 2],
    walls: Walls,
    /// Kind names; `Food::kind` and `Aversive::kind` index this.
    kinds: Vec<String>,
    food: Vec<Food>,
    /// Indices of the food objects that regenerate, in list order, so that worlds of
    /// non-regenerating food pay nothing for phase 1.
    regrowing: Vec<usize>,
    aversives: Vec<Aversive>,
    creatures: Vec<Creature>,
    body: Body,
    motion: MotionParams,
    eating: Eating,
    decay: Decay,
    smell_c: f64,
    wall_shock: bool,
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
    /// The trial's generator, kept for what is random during a trial: sensor noise (drawn
    /// in the order [`crate::sim::noise`] documents), and later wanderers and predators.
    rng: Rng,
}

impl World {
    /// Builds a trial world: validates both specifications, places the explicit objects, the
    /// placement rules' objects and `creatures` creatures with `rng` (in that order), then
    /// keeps `rng` for everything random during the trial.
    pub fn new(
        world: &WorldSpec,
        creature: &CreatureSpec,
        creatures: usize,
        mut rng: Rng,
    ) -> Result<World, PlacementError> {
        creature.validate()?;
        world.validate(creature)?;
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
        let regrowing = (0..objects.food.len())
            .filter(|&i| objects.food[i].regen.iter().any(|&r| r > 0.0))
            .collect();
        let phi = creature.whisker_angle_radians();
        let layout = creature.layout(world);
        let eye = layout
            .range(SensorGroup::Eye)
            .map(|_| Eye::new(&creature.eye));
        let noise = Noise::new(&creature.noise, &layout);
        Ok(World {
            tick: 0,
            arena: world.arena,
            walls,
            kinds: world.kinds.keys().cloned().collect(),
            food: objects.food,
            regrowing,
            aversives: objects.aversives,
            creatures: poses
                .into_iter()
                .map(|p| Creature::new(p, creature.initial_metabolism))
                .collect(),
            body: Body {
                radius,
                whisker_length: creature.whisker_length,
                whisker_cos: libm::cos(phi),
                whisker_sin: libm::sin(phi),
                smell: Smell::new(&creature.odour, creature.odour_intensity, None),
            },
            motion: MotionParams {
                wheel: creature.wheel,
                max_rpt: creature.max_rpt,
                search_steps: world.search_steps,
                slippery_walls: world.slippery_walls,
            },
            eating: creature.eating,
            decay: Decay {
                per_tick: creature.decay_per_tick,
                per_lu: creature.decay_per_lu,
            },
            smell_c: world.smell_c,
            wall_shock: world.wall_shock,
            inhibit_smell_on_whisker: creature.inhibit_smell_on_whisker,
            offsets: Offsets::new(&layout),
            observations: vec![0.0; layout.len() * creatures],
            layout,
            full_sensing: false,
            blockers: Vec::with_capacity(creatures),
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
        })
    }

    /// One tick of §9 (fixed order, see the module docs). `controllers.len()` must equal the
    /// number of creatures; creature i is driven by `controllers[i]`. Dead creatures are
    /// skipped (their controllers are not called).
    ///
    /// # Panics
    /// When `controllers.len()` differs from the number of creatures (a programming error).
    pub fn step<C: Controller>(&mut self, controllers: &mut [C]) {
        assert_eq!(
            controllers.len(),
            self.creatures.len(),
            "World::step needs one controller per creature"
        );
        self.regenerate_food();
        let width = self.layout.len();
        for (i, controller) in controllers.iter_mut().enumerate() {
            if !self.creatures[i].alive {
                continue;
            }
            self.sense(i);
            let command = controller.act(&self.observations[i * width..(i + 1) * width]);
            let outcome = self.move_creature(i, command);
            self.contacts(i, &outcome);
        }
        self.tick += 1;
    }

    /// Phase 1: every food object regenerates, in list order.
    fn regenerate_food(&mut self) {
        for &i in &self.regrowing {
            self.food[i].regenerate();
        }
    }

    /// Phase 2.1: creature `i` senses and its observation is written.
    fn sense(&mut self, i: usize) {
        let surroundings = Surroundings {
            walls: self.walls.felt(),
            opaque: self.walls.opaque(),
            food: &self.food,
            aversives: &self.aversives,
            areas: &self.areas,
            creatures: &self.creatures,
            smell_c: self.smell_c,
        };
        let smell = self.full_sensing || self.offsets.has_smell();
        let senses: Senses =
            surroundings.sense(i, &self.body, smell, self.inhibit_smell_on_whisker);
        let c = &mut self.creatures[i];
        c.whiskers = senses.whiskers;
        c.smell = senses.smell;
        c.food_detectors = senses.food;
        let width = self.layout.len();
        let out = &mut self.observations[i * width..(i + 1) * width];
        self.offsets.write(out, &senses, c.shocked, &c.metabolism);
        let pose = c.pose;
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
            };
            let n = eye.len();
            eye.render(&scene, pose.position, pose.heading, i, &mut out[o..o + n]);
        }
        if !self.noise.is_empty() {
            self.noise.apply(out, &mut self.rng);
        }
    }

    /// Phase 2.3: clamp the motors and move creature `i`, blocked by walls and by the other
    /// living creatures.
    fn move_creature(&mut self, i: usize, command: MotorCommand) -> MoveOutcome {
        let command = MotorCommand {
            left: clamp_motor(command.left, self.motion.max_rpt),
            right: clamp_motor(command.right, self.motion.max_rpt),
            eat: command.eat,
        };
        self.blockers.clear();
        for (j, other) in self.creatures.iter().enumerate() {
            if j != i && other.alive {
                self.blockers
                    .push(Circle::new(other.pose.position, self.body.radius));
            }
        }
        let blockers = Blockers {
            segments: self.walls.blocking(),
            circles: &self.blockers,
        };
        let c = &mut self.creatures[i];
        let outcome = plan_move(
            c.pose,
            command.left,
            command.right,
            self.body.radius,
            &self.motion,
            &blockers,
        );
        c.pose = outcome.pose;
        c.travelled += outcome.travelled;
        c.command = command;
        c.blocked = outcome.blocked;
        outcome
    }

    /// Phases 2.4 and 2.5: eating, shock and metabolism of creature `i` after its move.
    fn contacts(&mut self, i: usize, outcome: &MoveOutcome) {
        let c = &mut self.creatures[i];
        let position = c.pose.position;
        let radius = self.body.radius;
        let eats = match self.eating {
            Eating::Contact => true,
            Eating::Action => c.command.eat > 0.5,
        };
        let mut received = [0.0; 4];
        if eats {
            for f in &mut self.food {
                if circles_touch(position, radius, f.position, f.radius) {
                    for (r, g) in received.iter_mut().zip(f.take_bite()) {
                        *r += g;
                    }
                }
            }
        }
        for (e, r) in c.eaten.iter_mut().zip(received) {
            *e += r;
        }
        c.shocked = self
            .aversives
            .iter()
            .any(|a| circles_touch(position, radius, a.position, a.radius))
            || (self.wall_shock && outcome.blocked_by_wall);
        if c.shocked {
            c.shock_ticks += 1;
        }
        self.decay
            .apply(&mut c.metabolism, &received, outcome.travelled);
        c.age += 1;
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
        self.areas
            .iter()
            .any(|a| a.is_safe() && a.contains(position))
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

    /// Ends creature `creature`'s life now: it no longer senses, moves, eats, blocks, or is
    /// felt or smelled by others. Its last state stays readable.
    pub fn kill(&mut self, creature: usize) {
        self.creatures[creature].alive = false;
    }
}

/// Motor clamping: to ±`max_rpt`; NaN (a broken controller) counts as 0 so that the world
/// stays finite, as motion does.
#[inline]
fn clamp_motor(x: f64, max_rpt: f64) -> f64 {
    if x.is_nan() {
        0.0
    } else {
        x.clamp(-max_rpt, max_rpt)
    }
}
