//! The whole-world trace of a trial, recorded by a [`TickObserver`] ([`TraceRecorder`]) on the
//! one trial path: a [`WorldDescription`] of the world as built (enough to draw it), then per
//! tick every creature's pose, motor command, observation, shock and metabolism, every
//! wanderer's and predator's pose, the food whose amount changed, and the [`Event`]s of the
//! tick.
//!
//! The trial path ends a life after the first tick in which no creature recorded a score
//! (all dead, or their brains' output not finite), so a trace ends on that tick: a creature
//! killed in tick 58 (ticks are numbered from 1: the ticks done) has rows up to tick 58,
//! alive = 0 there, and lived 57 ticks. `simulate`'s trace ([`crate::record::trace`]) ends
//! by the same rule. While others live, a dead creature keeps a row per tick with alive = 0.
//!
//! Events are told by the world where it decides them ([`crate::sim::events`]): the recorder
//! switches the world's event log on when a trial starts and turns each tick's
//! [`WorldEvent`]s into rows, in this order within a tick:
//!
//! - `eat`: one row per bite, in food order (the eater, the object, what it received per type
//!   A–D);
//! - then per creature in index order: `teleport` (at the exit, `from` the entry); `attack`,
//!   one row per predator that attacked it (ground predators, then air predators, each by
//!   index; a predator that struck in phase 2 and again in the contacts phase is one row);
//!   `shock`, an onset only (shocked after this tick and not after the one before: the
//!   creature rows carry every shocked tick), with its cause: the aversive object, else the
//!   predator, else the wall; `death`;
//! - then `door_open` (by the creature whose body touched the closed door's trigger) and
//!   `door_close`, in door order.
//!
//! Shock, attack and death rows stand at the creature's position after the tick.
//!
//! # Episodes
//!
//! A life of several episodes (`[evaluation] episodes_per_life`) stays one trial per episode
//! here (each its own world, ticks from 1, its own outcome), as the trial path shows it; each
//! carries an [`EpisodeInfo`] (which episode, whether a switch came before it and whether the
//! switch kinds' payoffs are exchanged). Keeping episodes apart keeps every world-drawing
//! consumer as it was; what crosses episodes (a plastic brain's weights) runs on continuously.
//!
//! # Learning
//!
//! For a plastic brain the recorder also reads the brain after each tick
//! ([`TickObserver::brain`]): the modulatory signal m and its gate g = tanh(m/2) (g = 1 for a
//! Hebbian rule), ‖Δw‖ (the L2 norm of the tick's change over all plastic weights, from the
//! weights after the tick before, or at the life's start), and the weights of a few chosen
//! synapses ([`LearningTick`]). The synapses are those named ([`TraceRecorder::with_synapses`])
//! or else the [`DEFAULT_SYNAPSES`] whose weight moved most over the life (|w_end − w_start|,
//! ties to the lower index): the recorder keeps every weight of the life in progress and keeps
//! the chosen ones when the life ends (the next life's start, or
//! [`TraceRecorder::into_trials`]), so the choice is exact and the life is lived once.

use crate::brain::activation::tanh;
use crate::brain::spec::Topology;
use crate::brain::Brain;
use crate::evo::life::TrialOutcome;
use crate::evo::trial::{EpisodeMark, TickObserver, TrialId};
use crate::experiment::Experiment;
use crate::geometry::Vec2;
use crate::sim::events::{Attacker, ShockCause, WorldEvent};
use crate::sim::gadgets::Role;
use crate::sim::metabolism::Metabolism;
use crate::sim::spec::Effect;
use crate::sim::world::World;
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// A 2-D point or vector `[x, y]` in LU.
pub type Point = [f64; 2];

fn point(v: Vec2) -> Point {
    [v.x, v.y]
}

/// A heading (unit vector) as an angle in radians: atan2(y, x), positive clockwise on screen.
pub fn heading_angle(v: Vec2) -> f64 {
    libm::atan2(v.y, v.x)
}

/// The world of one trial as built, before its first tick: what a picture of it needs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct WorldDescription {
    /// The experiment's name.
    pub experiment: String,
    /// The experiment's master seed.
    pub seed: u64,
    /// Generation, group and trial index the world comes from.
    pub generation: u64,
    /// The group of genomes living it.
    pub group: u64,
    /// The trial index.
    pub trial: u64,
    /// The trial's length in ticks (the life may end earlier).
    pub ticks: u64,
    /// Arena `[width, height]` in LU; x to the right, y downwards.
    pub arena: Point,
    /// Body radius of every creature, wanderer and ground predator in LU.
    pub creature_radius: f64,
    /// Whisker length in LU.
    pub whisker_length: f64,
    /// Angle of each whisker from the heading, radians.
    pub whisker_angle: f64,
    /// The observation's input names ([`crate::sim::controller::ObservationLayout::names`]).
    pub inputs: Vec<String>,
    /// Boundary and interior walls (boundary first); they stand all trial.
    pub walls: Vec<WallInfo>,
    /// Locked doors, in file order (closed at the start).
    pub doors: Vec<DoorInfo>,
    /// Teleporters, in file order.
    pub teleporters: Vec<TeleporterInfo>,
    /// Areas, in file order.
    pub areas: Vec<AreaInfo>,
    /// Distal landmarks, in file order.
    pub landmarks: Vec<Point>,
    /// Food objects (explicit ones first, then each placement rule's) as placed.
    pub food: Vec<FoodInfo>,
    /// Aversive objects.
    pub aversives: Vec<AversiveInfo>,
    /// The evolving creatures' start poses.
    pub creatures: Vec<PoseInfo>,
    /// Wanderers then ground predators, in file order, at their start.
    pub actors: Vec<ActorInfo>,
    /// Air predators, in file order, at their start.
    pub air_predators: Vec<AirPredatorInfo>,
    /// Which episode of its life this world is (absent for a life of one episode).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub episode: Option<EpisodeInfo>,
}

/// Which episode of a life of several a trial is.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EpisodeInfo {
    /// The episode, numbered from 1 (as `[evaluation.switch] at` numbers them).
    pub episode: u64,
    /// Episodes in the life.
    pub episodes: u64,
    /// A switch came before this episode: the two switch kinds' payoffs were exchanged
    /// relative to the episode before.
    pub switched: bool,
    /// In this episode the switch kinds' payoffs are exchanged relative to `[world.kinds]`.
    pub exchanged: bool,
    /// The two switch kinds (`[evaluation.switch] kinds`; empty without a switch).
    pub switch_kinds: Vec<String>,
}

/// A synapse of a plastic MLP: weight layer `layer` (0 = the first hidden layer, …, the last
/// = the output layer), from input or unit `from` of the layer before to unit `to`.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Synapse {
    /// Weight layer: 0 = the first hidden layer, the last = the output layer.
    pub layer: usize,
    /// The presynaptic input (or unit of the layer before).
    pub from: usize,
    /// The receiving unit.
    pub to: usize,
    /// Its genome name (`w_h0[to][from]`, `w_out[to][from]`), as `inspect` names it.
    pub name: String,
    /// Its index in the brain's live weights ([`Brain::plastic_weights`]).
    pub index: usize,
}

/// How many synapses a trace follows when none are named: those that moved most.
pub const DEFAULT_SYNAPSES: usize = 6;

/// One creature's plastic brain in a trial: the synapses followed and their weights at the
/// trial's start (tick 0: the genome's initial weights in a life's first episode, the last
/// episode's final weights later).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LearningInfo {
    /// Creature index.
    pub creature: usize,
    /// `moved_most` (the synapses whose weight moved most over the life) or `named`.
    pub chosen: String,
    /// The synapses followed, in [`LearningTick::weights`] order.
    pub synapses: Vec<Synapse>,
    /// Their weights at tick 0.
    pub start: Vec<f64>,
}

/// A plastic brain after one tick.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LearningTick {
    /// Ticks done.
    pub tick: u64,
    /// Creature index.
    pub creature: usize,
    /// The tick's modulatory signal m (None for a Hebbian rule).
    pub m: Option<f64>,
    /// The gate g = tanh(m/2) (1 for a Hebbian rule).
    pub g: f64,
    /// ‖Δw‖: the L2 norm of this tick's change of all plastic weights.
    pub dw_norm: f64,
    /// The followed synapses' weights after the tick ([`LearningInfo::synapses`] order).
    pub weights: Vec<f64>,
}

/// Why a list of synapses cannot be followed.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum SynapseError {
    /// Not `layer:from:to`.
    #[error("`{0}` is not layer:from:to (e.g. h0:3:5 or out:7:1; the layer may also be its number from 0)")]
    Syntax(String),
    /// The brain is not a plastic MLP.
    #[error(
        "the brain is not plastic (set `brain.plasticity`), so it has no synapses that change"
    )]
    NotPlastic,
    /// Out of range.
    #[error("`{given}`: {what}")]
    OutOfRange {
        /// The entry.
        given: String,
        /// What the brain has.
        what: String,
    },
}

/// The plastic weight layers of `topology`: (name, units, inputs, first index in the live
/// weights), or None when the brain is not a plastic MLP.
fn plastic_layers(topology: &Topology) -> Option<Vec<(String, usize, usize, usize)>> {
    topology.spec.plastic_settings()?;
    let (sizes, _) = topology.weight_layers();
    let last = sizes.len() - 1;
    let mut at = 0;
    Some(
        sizes
            .iter()
            .enumerate()
            .map(|(l, &(units, inputs))| {
                let name = if l == last {
                    "out".to_string()
                } else {
                    format!("h{l}")
                };
                let first = at;
                at += units * inputs;
                (name, units, inputs, first)
            })
            .collect(),
    )
}

/// The synapse of weight layer `layer` from `from` to `to`.
fn synapse(
    layers: &[(String, usize, usize, usize)],
    layer: usize,
    from: usize,
    to: usize,
) -> Synapse {
    let (name, units, _, first) = &layers[layer];
    Synapse {
        layer,
        from,
        to,
        name: format!("w_{name}[{to}][{from}]"),
        index: first + from * units + to,
    }
}

/// The synapse at `index` of the live weights.
fn synapse_at(layers: &[(String, usize, usize, usize)], index: usize) -> Option<Synapse> {
    let l = layers
        .iter()
        .rposition(|&(_, _, _, first)| first <= index)?;
    let (_, units, inputs, first) = layers[l];
    let k = index - first;
    (k < units * inputs).then(|| synapse(layers, l, k / units, k % units))
}

/// Parses `layer:from:to,...` (layer `h0`, `h1`, …, `out`, or its number from 0) against
/// `topology`'s plastic weight layers.
pub fn parse_synapses(text: &str, topology: &Topology) -> Result<Vec<Synapse>, SynapseError> {
    let layers = plastic_layers(topology).ok_or(SynapseError::NotPlastic)?;
    let names: Vec<&str> = layers.iter().map(|l| l.0.as_str()).collect();
    let mut out = Vec::new();
    for given in text.split(',').map(str::trim).filter(|t| !t.is_empty()) {
        let parts: Vec<&str> = given.split(':').collect();
        let [layer, from, to] = parts[..] else {
            return Err(SynapseError::Syntax(given.into()));
        };
        let range = |what: String| SynapseError::OutOfRange {
            given: given.into(),
            what,
        };
        let listed = || {
            format!(
                "the brain has weight layers {} (0 to {})",
                names.join(", "),
                layers.len() - 1
            )
        };
        let l = match names.iter().position(|&n| n == layer) {
            Some(l) => l,
            // A hidden layer the brain does not have, e.g. h3.
            None if layer
                .strip_prefix('h')
                .is_some_and(|n| n.parse::<usize>().is_ok()) =>
            {
                return Err(range(listed()));
            }
            None => layer
                .parse::<usize>()
                .map_err(|_| SynapseError::Syntax(given.into()))?,
        };
        let Some(&(ref name, units, inputs, _)) = layers.get(l) else {
            return Err(range(listed()));
        };
        let number = |x: &str| {
            x.parse::<usize>()
                .map_err(|_| SynapseError::Syntax(given.into()))
        };
        let (from, to) = (number(from)?, number(to)?);
        if from >= inputs || to >= units {
            return Err(range(format!(
                "layer {name} has inputs 0..{inputs} and units 0..{units}"
            )));
        }
        out.push(synapse(&layers, l, from, to));
    }
    if out.is_empty() {
        return Err(SynapseError::Syntax(text.into()));
    }
    Ok(out)
}

/// A wall segment.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct WallInfo {
    /// One end.
    pub from: Point,
    /// The other end.
    pub to: Point,
    /// Blocks smell (glass does not).
    pub opaque: bool,
    /// RGB in [0, 1].
    pub colour: [f64; 3],
    /// Height in LU.
    pub height: f64,
}

/// A locked door and its trigger.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DoorInfo {
    /// One end of the door's wall.
    pub from: Point,
    /// The other end.
    pub to: Point,
    /// Blocks smell while closed.
    pub opaque: bool,
    /// RGB in [0, 1].
    pub colour: [f64; 3],
    /// Centre of the trigger region.
    pub trigger: Point,
    /// Radius of the trigger region.
    pub trigger_radius: f64,
    /// Ticks the door stays open after a contact.
    pub open_ticks: u64,
}

/// A teleporter.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TeleporterInfo {
    /// Entry centre.
    pub entry: Point,
    /// Entry radius.
    pub radius: f64,
    /// Exit point.
    pub exit: Point,
    /// Heading after the jump, radians (None: the creature keeps its own).
    pub exit_heading: Option<f64>,
}

/// An area.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AreaInfo {
    /// Smallest corner.
    pub lo: Point,
    /// Largest corner.
    pub hi: Point,
    /// `safe` or `plain`.
    pub kind: String,
}

/// A food object as placed.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FoodInfo {
    /// Its kind's name in `[world.kinds]`.
    pub kind: String,
    /// The type A–D it holds most of (by capacity): 0 = A.
    pub food_type: usize,
    /// Centre.
    pub position: Point,
    /// Radius (0 = a point).
    pub radius: f64,
    /// Amount per type A–D at the start.
    pub amount: [f64; 4],
    /// Capacity per type A–D.
    pub capacity: [f64; 4],
    /// Bites take substance away.
    pub depletes: bool,
    /// RGB for the eye.
    pub colour: [f64; 3],
}

/// An aversive object.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AversiveInfo {
    /// Its kind's name.
    pub kind: String,
    /// Centre.
    pub position: Point,
    /// Radius.
    pub radius: f64,
    /// RGB for the eye.
    pub colour: [f64; 3],
}

/// A position and heading.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PoseInfo {
    /// Centre.
    pub position: Point,
    /// Heading, radians.
    pub heading: f64,
}

/// A wanderer or ground predator at its start.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ActorInfo {
    /// `wanderer` or `predator`.
    pub role: String,
    /// A predator's strategy (`wander`, `chase`, `patrol`).
    pub strategy: Option<String>,
    /// A predator's effect (`lethal`, `shock`).
    pub effect: Option<String>,
    /// A patrol's waypoints.
    pub waypoints: Vec<Point>,
    /// RGB for the eye.
    pub colour: [f64; 3],
    /// Start pose.
    pub start: PoseInfo,
}

/// An air predator at its start.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AirPredatorInfo {
    /// Strike radius around its ground position.
    pub strike_radius: f64,
    /// `lethal` or `shock`.
    pub effect: String,
    /// Ground position at the start.
    pub position: Point,
    /// Velocity in LU per tick at the start.
    pub velocity: Point,
}

/// One creature after one tick.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CreatureTick {
    /// Ticks done (1 after the first).
    pub tick: u64,
    /// Creature index.
    pub creature: usize,
    /// Centre after the tick.
    pub x: f64,
    /// Centre after the tick.
    pub y: f64,
    /// Heading after the tick, radians.
    pub heading: f64,
    /// Left motor signal of the tick (clamped), rotations per tick.
    pub left: f64,
    /// Right motor signal.
    pub right: f64,
    /// Eat output.
    pub eat: f64,
    /// Alive after the tick.
    pub alive: bool,
    /// Shock state at the end of the tick (the sensor reads it next tick).
    pub shock: bool,
    /// Metabolic vector after the tick.
    pub metabolism: Metabolism,
    /// Whiskers sensed at the start of the tick (left, right).
    pub whiskers: [bool; 2],
    /// Food detectors A–D sensed at the start of the tick.
    pub food: [bool; 4],
    /// Distance travelled so far, LU.
    pub travelled: f64,
    /// The observation its brain received this tick (noise included), in
    /// [`WorldDescription::inputs`] order.
    pub inputs: Vec<f64>,
}

/// What moves besides the creatures.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ActorKind {
    /// An irrelevant creature.
    Wanderer,
    /// A ground predator.
    Predator,
    /// An air predator.
    AirPredator,
}

impl ActorKind {
    /// The name in CSV files.
    pub fn name(self) -> &'static str {
        match self {
            ActorKind::Wanderer => "wanderer",
            ActorKind::Predator => "predator",
            ActorKind::AirPredator => "air_predator",
        }
    }
}

/// A wanderer or predator after one tick.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ActorTick {
    /// Ticks done.
    pub tick: u64,
    /// What it is.
    pub kind: ActorKind,
    /// Index among its kind (wanderer k, predator k of `[[world.predators]]`, air predator k).
    pub index: usize,
    /// Ground position.
    pub x: f64,
    /// Ground position.
    pub y: f64,
    /// Heading (an air predator's direction of flight), radians.
    pub heading: f64,
}

/// A food object whose amount changed in a tick.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ObjectTick {
    /// Ticks done.
    pub tick: u64,
    /// Food index.
    pub object: usize,
    /// Amount per type A–D after the tick.
    pub amount: [f64; 4],
}

/// What happened (see the module docs for how each is found).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum EventKind {
    /// A creature ate from a food object.
    Eat,
    /// A creature's shock turned on.
    Shock,
    /// A creature jumped through a teleporter.
    Teleport,
    /// A door opened.
    DoorOpen,
    /// A door closed.
    DoorClose,
    /// A predator attacked a creature.
    Attack,
    /// A creature died.
    Death,
}

impl EventKind {
    /// The name in CSV files.
    pub fn name(self) -> &'static str {
        match self {
            EventKind::Eat => "eat",
            EventKind::Shock => "shock",
            EventKind::Teleport => "teleport",
            EventKind::DoorOpen => "door_open",
            EventKind::DoorClose => "door_close",
            EventKind::Attack => "attack",
            EventKind::Death => "death",
        }
    }
}

/// One event of a tick.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Event {
    /// Ticks done when it had happened.
    pub tick: u64,
    /// What.
    pub event: EventKind,
    /// The creature it concerns (None for a door nobody touched, e.g. one closing).
    pub creature: Option<usize>,
    /// What it met: `food`, `aversive`, `teleporter`, `door`, `predator`, `air_predator` or
    /// `wall` (None: nothing in particular).
    pub target_kind: Option<String>,
    /// Index of the target among its kind (None for walls and no target).
    pub target: Option<usize>,
    /// Where: the food object (eat), the exit (teleport), the door's middle (doors), the
    /// creature (shock, attack, death).
    pub x: f64,
    /// Where.
    pub y: f64,
    /// A teleport's entry.
    pub from: Option<Point>,
    /// What an eat moved, per type A–D.
    pub amount: Option<[f64; 4]>,
}

/// One creature's outcome of the trial.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct OutcomeInfo {
    /// The trial's score under `[fitness]`.
    pub score: f64,
    /// The metabolic vector at the end of life.
    pub metabolism: Metabolism,
    /// Shocked ticks.
    pub shocked_ticks: u64,
    /// The brain produced a non-finite output.
    pub non_finite: bool,
}

/// Everything recorded of one trial.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TrialTrace {
    /// The world as built.
    pub world: WorldDescription,
    /// Per tick, one row per creature (dead ones included), in tick then creature order.
    pub creatures: Vec<CreatureTick>,
    /// Per tick, one row per wanderer, ground predator and air predator.
    pub actors: Vec<ActorTick>,
    /// The food objects whose amount changed, per tick.
    pub objects: Vec<ObjectTick>,
    /// Events, in tick order.
    pub events: Vec<Event>,
    /// Each creature's outcome, when the trial finished.
    pub outcomes: Vec<OutcomeInfo>,
    /// Per plastic creature, the synapses followed (empty for fixed brains).
    pub learning: Vec<LearningInfo>,
    /// Per tick, one row per plastic creature (empty for fixed brains).
    pub learning_ticks: Vec<LearningTick>,
}

impl TrialTrace {
    /// Ticks recorded (the last tick's number).
    pub fn ticks(&self) -> u64 {
        self.creatures.last().map_or(0, |c| c.tick)
    }

    /// How many creatures lived the trial.
    pub fn creature_count(&self) -> usize {
        self.world.creatures.len()
    }
}

/// What the rows of a tick compare with the tick before: each creature's shock state (for
/// shock onsets) and each food object's amount (for the objects whose amount changed).
#[derive(Debug, Clone, Default)]
struct Previous {
    shocked: Vec<bool>,
    amount: Vec<[f64; 4]>,
}

impl Previous {
    fn of(world: &World) -> Previous {
        Previous {
            shocked: world.creatures().iter().map(|c| c.shocked).collect(),
            amount: world.food().iter().map(|f| f.amount).collect(),
        }
    }
}

/// The target of an attack or a shock in the CSV's terms: kind and index.
fn attacker_target(by: Attacker) -> (&'static str, usize) {
    match by {
        Attacker::Predator(k) => ("predator", k),
        Attacker::AirPredator(k) => ("air_predator", k),
    }
}

/// Records every trial it observes into a [`TrialTrace`] (all in memory: about 8 bytes per
/// number, so a 10,000-tick trial of a creature with 24 inputs takes a few MB).
#[derive(Debug, Clone)]
pub struct TraceRecorder {
    experiment: String,
    seed: u64,
    ticks: u64,
    whisker_length: f64,
    whisker_angle: f64,
    waypoints: Vec<Vec<Point>>,
    /// The trials recorded, in the order they ran (a plastic brain's synapses are chosen
    /// when its life ends: read them through [`TraceRecorder::into_trials`]).
    pub trials: Vec<TrialTrace>,
    previous: Previous,
    switch_kinds: Vec<String>,
    /// The episode the next trial starts (lives of several episodes).
    mark: Option<EpisodeMark>,
    /// The plastic weight layers (None for other brains).
    layers: Option<Vec<(String, usize, usize, usize)>>,
    /// The synapses to follow (None: those that move most).
    named: Option<Vec<Synapse>>,
    /// The life in progress: its first trial, and per creature the weights at its start and
    /// after the last tick seen.
    life_start: usize,
    weights: Vec<(Vec<f64>, Vec<f64>)>,
}

impl TraceRecorder {
    /// A recorder for trials of `experiment`.
    pub fn new(experiment: &Experiment) -> TraceRecorder {
        TraceRecorder {
            experiment: experiment.name.clone(),
            seed: experiment.seed,
            ticks: experiment.evaluation.ticks,
            whisker_length: experiment.creature.whisker_length,
            whisker_angle: experiment.creature.whisker_angle.to_radians(),
            waypoints: experiment
                .world
                .predators
                .iter()
                .map(|p| p.waypoints.clone())
                .collect(),
            trials: Vec::new(),
            previous: Previous::default(),
            switch_kinds: experiment
                .evaluation
                .switch
                .as_ref()
                .map(|s| s.kinds.to_vec())
                .unwrap_or_default(),
            mark: None,
            layers: plastic_layers(&experiment.topology()),
            named: None,
            life_start: 0,
            weights: Vec::new(),
        }
    }

    /// Records the brain `topology` describes (the genome file's, which may differ from the
    /// experiment's: a plastic genome replayed in a file whose brain is fixed is still
    /// plastic, and its weights are still followed).
    pub fn for_brain(mut self, topology: &Topology) -> TraceRecorder {
        self.layers = plastic_layers(topology);
        self
    }

    /// Follows `synapses` (see [`parse_synapses`]) instead of those that move most.
    pub fn with_synapses(mut self, synapses: Vec<Synapse>) -> TraceRecorder {
        self.named = Some(synapses);
        self
    }

    /// The trials recorded, a plastic brain's synapses chosen.
    pub fn into_trials(mut self) -> Vec<TrialTrace> {
        self.end_life();
        self.trials
    }

    /// The life in progress is over: chooses each plastic creature's synapses (named, or
    /// the [`DEFAULT_SYNAPSES`] that moved most, |w_end − w_start|, ties to the lower index)
    /// and keeps only their weights in the life's trials.
    fn end_life(&mut self) {
        let Some(layers) = &self.layers else {
            return;
        };
        let (named, chosen) = match &self.named {
            Some(list) => (Some(list), "named"),
            None => (None, "moved_most"),
        };
        let picks: Vec<Vec<Synapse>> = self
            .weights
            .iter()
            .map(|(start, last)| match named {
                Some(list) => list.clone(),
                None => {
                    let mut order: Vec<usize> = (0..start.len()).collect();
                    let moved = |k: usize| (last[k] - start[k]).abs();
                    // Stable sort: equal movements keep index order.
                    order.sort_by(|&a, &b| moved(b).total_cmp(&moved(a)));
                    order.truncate(DEFAULT_SYNAPSES);
                    order
                        .into_iter()
                        .filter_map(|k| synapse_at(layers, k))
                        .collect()
                }
            })
            .collect();
        let from = self.life_start.min(self.trials.len());
        for trace in &mut self.trials[from..] {
            for info in &mut trace.learning {
                let Some(list) = picks.get(info.creature) else {
                    continue;
                };
                info.start = list.iter().map(|s| info.start[s.index]).collect();
                info.synapses = list.clone();
                info.chosen = chosen.into();
            }
            for row in &mut trace.learning_ticks {
                if let Some(list) = picks.get(row.creature) {
                    row.weights = list.iter().map(|s| row.weights[s.index]).collect();
                }
            }
        }
        self.weights.clear();
        self.life_start = self.trials.len();
    }

    fn describe(&self, id: TrialId, world: &World) -> WorldDescription {
        let kinds = world.kinds();
        let wall = |w: &crate::sim::wall::Wall| WallInfo {
            from: point(w.segment.a),
            to: point(w.segment.b),
            opaque: w.opaque,
            colour: w.colour,
            height: w.height,
        };
        let things = world.things();
        WorldDescription {
            experiment: self.experiment.clone(),
            seed: self.seed,
            generation: id.generation.0,
            group: id.group,
            trial: id.trial.0,
            ticks: self.ticks,
            arena: world.arena(),
            creature_radius: world.creature_radius(),
            whisker_length: self.whisker_length,
            whisker_angle: self.whisker_angle,
            inputs: world.layout().names().to_vec(),
            walls: world.fixed_walls().iter().map(wall).collect(),
            doors: world
                .door_walls()
                .iter()
                .zip(world.doors())
                .map(|(w, d)| {
                    let t = things[d.trigger];
                    DoorInfo {
                        from: point(w.segment.a),
                        to: point(w.segment.b),
                        opaque: w.opaque,
                        colour: w.colour,
                        trigger: point(t.position),
                        trigger_radius: t.radius,
                        open_ticks: d.open_ticks,
                    }
                })
                .collect(),
            teleporters: world
                .teleporters()
                .iter()
                .map(|t| TeleporterInfo {
                    entry: point(t.entry),
                    radius: t.radius,
                    exit: point(t.exit),
                    exit_heading: t.exit_heading.map(heading_angle),
                })
                .collect(),
            areas: world
                .areas()
                .iter()
                .map(|a| AreaInfo {
                    lo: point(a.lo),
                    hi: point(a.hi),
                    kind: if a.is_safe() { "safe" } else { "plain" }.into(),
                })
                .collect(),
            landmarks: world.landmarks().iter().map(|&l| point(l)).collect(),
            food: world
                .food()
                .iter()
                .map(|f| FoodInfo {
                    kind: kinds.get(f.kind).cloned().unwrap_or_default(),
                    food_type: main_type(&f.capacity),
                    position: point(f.position),
                    radius: f.radius,
                    amount: f.amount,
                    capacity: f.capacity,
                    depletes: f.depletes,
                    colour: f.colour,
                })
                .collect(),
            aversives: world
                .aversives()
                .iter()
                .map(|a| AversiveInfo {
                    kind: kinds.get(a.kind).cloned().unwrap_or_default(),
                    position: point(a.position),
                    radius: a.radius,
                    colour: a.colour,
                })
                .collect(),
            creatures: world
                .creatures()
                .iter()
                .map(|c| PoseInfo {
                    position: point(c.pose.position),
                    heading: heading_angle(c.pose.heading),
                })
                .collect(),
            actors: world
                .actors()
                .iter()
                .map(|a| {
                    let (role, strategy, effect, waypoints) = match a.role {
                        Role::Wanderer => ("wanderer", None, None, Vec::new()),
                        Role::Predator {
                            predator,
                            strategy,
                            effect,
                        } => (
                            "predator",
                            Some(format!("{strategy:?}").to_lowercase()),
                            Some(effect_name(effect).to_string()),
                            self.waypoints.get(predator).cloned().unwrap_or_default(),
                        ),
                    };
                    ActorInfo {
                        role: role.into(),
                        strategy,
                        effect,
                        waypoints,
                        colour: things[a.thing].colour,
                        start: PoseInfo {
                            position: point(a.pose.position),
                            heading: heading_angle(a.pose.heading),
                        },
                    }
                })
                .collect(),
            air_predators: world
                .flyers()
                .iter()
                .map(|f| AirPredatorInfo {
                    strike_radius: f.strike_radius,
                    effect: effect_name(f.effect).into(),
                    position: point(f.position),
                    velocity: point(f.velocity),
                })
                .collect(),
            episode: self.mark.map(|m| EpisodeInfo {
                episode: m.index + 1,
                episodes: m.episodes,
                switched: m.switched,
                exchanged: m.exchanged,
                switch_kinds: self.switch_kinds.clone(),
            }),
        }
    }

    /// The rows of the events `world` told for tick `tick` (see the module docs for their
    /// order).
    fn events(&self, world: &World, tick: u64, events: &mut Vec<Event>) {
        let told = world.events();
        let creatures = world.creatures();
        let event = |event, creature, target_kind: Option<&str>, target, at: Vec2| Event {
            tick,
            event,
            creature,
            target_kind: target_kind.map(str::to_string),
            target,
            x: at.x,
            y: at.y,
            from: None,
            amount: None,
        };
        // Bites, in food order (the world tells them in creature order).
        let mut bites: Vec<(usize, usize, [f64; 4])> = told
            .iter()
            .filter_map(|e| match *e {
                WorldEvent::Bite {
                    creature,
                    food,
                    amount,
                } => Some((food, creature, amount)),
                _ => None,
            })
            .collect();
        bites.sort_by_key(|&(food, _, _)| food);
        for (k, i, amount) in bites {
            let at = world.food()[k].position;
            let mut e = event(EventKind::Eat, Some(i), Some("food"), Some(k), at);
            e.amount = Some(amount);
            events.push(e);
        }
        for (i, c) in creatures.iter().enumerate() {
            let here = c.pose.position;
            let mine = told.iter().filter(|e| creature_of(e) == Some(i));
            for e in mine.clone() {
                if let WorldEvent::Teleport { teleporter: k, .. } = *e {
                    let mut e = event(
                        EventKind::Teleport,
                        Some(i),
                        Some("teleporter"),
                        Some(k),
                        here,
                    );
                    e.from = Some(point(world.teleporters()[k].entry));
                    events.push(e);
                }
            }
            let mut attackers: Vec<Attacker> = mine
                .clone()
                .filter_map(|e| match *e {
                    WorldEvent::Attack { by, .. } => Some(by),
                    _ => None,
                })
                .collect();
            attackers.sort();
            attackers.dedup();
            for &by in &attackers {
                let (kind, k) = attacker_target(by);
                events.push(event(EventKind::Attack, Some(i), Some(kind), Some(k), here));
            }
            if c.shocked && !self.previous.shocked[i] {
                let causes = || {
                    mine.clone().filter_map(|e| match *e {
                        WorldEvent::Shock { cause, .. } => Some(cause),
                        _ => None,
                    })
                };
                let aversive = causes().find(|c| matches!(c, ShockCause::Aversive(_)));
                let attack = causes().find(|c| matches!(c, ShockCause::Attack(_)));
                let wall = causes().find(|c| matches!(c, ShockCause::Wall));
                let (kind, target) = match aversive.or(attack).or(wall) {
                    Some(ShockCause::Aversive(k)) => (Some("aversive"), Some(k)),
                    Some(ShockCause::Attack(by)) => {
                        let (kind, k) = attacker_target(by);
                        (Some(kind), Some(k))
                    }
                    Some(ShockCause::Wall) => (Some("wall"), None),
                    None => (None, None),
                };
                events.push(event(EventKind::Shock, Some(i), kind, target, here));
            }
            if mine.clone().any(|e| matches!(e, WorldEvent::Death { .. })) {
                events.push(event(EventKind::Death, Some(i), None, None, here));
            }
        }
        // Doors, in door order (closed in phase 1, opened in the creatures' contacts).
        let mut doors: Vec<(usize, EventKind, Option<usize>)> = told
            .iter()
            .filter_map(|e| match *e {
                WorldEvent::DoorOpened { door, creature } => {
                    Some((door, EventKind::DoorOpen, Some(creature)))
                }
                WorldEvent::DoorClosed { door } => Some((door, EventKind::DoorClose, None)),
                _ => None,
            })
            .collect();
        doors.sort_by_key(|&(door, _, _)| door);
        for (d, kind, who) in doors {
            let w = &world.door_walls()[d];
            let middle = (w.segment.a + w.segment.b) * 0.5;
            events.push(event(kind, who, Some("door"), Some(d), middle));
        }
    }
}

/// The creature an event concerns (None for a door closing).
fn creature_of(e: &WorldEvent) -> Option<usize> {
    match *e {
        WorldEvent::Bite { creature, .. }
        | WorldEvent::Shock { creature, .. }
        | WorldEvent::Attack { creature, .. }
        | WorldEvent::Teleport { creature, .. }
        | WorldEvent::DoorOpened { creature, .. }
        | WorldEvent::Death { creature, .. } => Some(creature),
        WorldEvent::DoorClosed { .. } => None,
    }
}

/// The type A–D a food object holds most of by capacity (the first of equals).
fn main_type(capacity: &[f64; 4]) -> usize {
    let mut best = 0;
    for t in 1..4 {
        if capacity[t] > capacity[best] {
            best = t;
        }
    }
    best
}

fn effect_name(effect: Effect) -> &'static str {
    match effect {
        Effect::Lethal => "lethal",
        Effect::Shock => "shock",
    }
}

impl TickObserver for TraceRecorder {
    fn listens(&self) -> bool {
        true
    }

    fn start(&mut self, trial: TrialId, world: &World) {
        // A new life: the first episode of one, or a life of one episode.
        if self.mark.is_none_or(|m| m.index == 0) {
            self.end_life();
        }
        let world_description = self.describe(trial, world);
        self.mark = None;
        self.trials.push(TrialTrace {
            world: world_description,
            creatures: Vec::new(),
            actors: Vec::new(),
            objects: Vec::new(),
            events: Vec::new(),
            outcomes: Vec::new(),
            learning: Vec::new(),
            learning_ticks: Vec::new(),
        });
        self.previous = Previous::of(world);
    }

    fn episode(&mut self, mark: EpisodeMark) {
        self.mark = Some(mark);
    }

    fn watches_brains(&self) -> bool {
        self.layers.is_some()
    }

    fn brain(&mut self, tick: u64, creature: usize, brain: &Brain) {
        let Some(w) = brain.plastic_weights() else {
            return;
        };
        let Some(trace) = self.trials.last_mut() else {
            return;
        };
        if self.weights.len() <= creature {
            self.weights.resize(creature + 1, (Vec::new(), Vec::new()));
        }
        let (start, last) = &mut self.weights[creature];
        if start.is_empty() {
            // The life's first look: the weights it starts from.
            *start = w.to_vec();
            *last = w.to_vec();
        }
        if tick == 0 {
            // Every weight for now; the followed ones are kept when the life ends.
            trace.learning.push(LearningInfo {
                creature,
                chosen: String::new(),
                synapses: Vec::new(),
                start: w.to_vec(),
            });
            return;
        }
        let mut sum = 0.0;
        for (now, before) in w.iter().zip(last.iter()) {
            let d = now - before;
            sum += d * d;
        }
        last.copy_from_slice(w);
        let m = brain.last_modulation();
        trace.learning_ticks.push(LearningTick {
            tick,
            creature,
            m,
            g: m.map_or(1.0, |m| tanh(m * 0.5)),
            dw_norm: sum.sqrt(),
            weights: w.to_vec(),
        });
    }

    fn tick(&mut self, world: &World, tick: u64) {
        let mut events = Vec::new();
        self.events(world, tick, &mut events);
        let Some(trace) = self.trials.last_mut() else {
            return;
        };
        trace.events.append(&mut events);
        for (i, c) in world.creatures().iter().enumerate() {
            trace.creatures.push(CreatureTick {
                tick,
                creature: i,
                x: c.pose.position.x,
                y: c.pose.position.y,
                heading: heading_angle(c.pose.heading),
                left: c.command.left,
                right: c.command.right,
                eat: c.command.eat,
                alive: c.alive,
                shock: c.shocked,
                metabolism: c.metabolism,
                whiskers: c.whiskers,
                food: c.food_detectors,
                travelled: c.travelled,
                inputs: world.observation(i).to_vec(),
            });
        }
        let mut predators = 0;
        let mut wanderers = 0;
        for a in world.actors() {
            let (kind, index) = match a.role {
                Role::Wanderer => {
                    wanderers += 1;
                    (ActorKind::Wanderer, wanderers - 1)
                }
                Role::Predator { .. } => {
                    predators += 1;
                    (ActorKind::Predator, predators - 1)
                }
            };
            trace.actors.push(ActorTick {
                tick,
                kind,
                index,
                x: a.pose.position.x,
                y: a.pose.position.y,
                heading: heading_angle(a.pose.heading),
            });
        }
        for (k, f) in world.flyers().iter().enumerate() {
            trace.actors.push(ActorTick {
                tick,
                kind: ActorKind::AirPredator,
                index: k,
                x: f.position.x,
                y: f.position.y,
                heading: heading_angle(f.velocity),
            });
        }
        for (k, f) in world.food().iter().enumerate() {
            if f.amount != self.previous.amount[k] {
                trace.objects.push(ObjectTick {
                    tick,
                    object: k,
                    amount: f.amount,
                });
            }
        }
        self.previous = Previous::of(world);
    }

    fn finish(&mut self, _world: &World, outcomes: &[TrialOutcome]) {
        if let Some(trace) = self.trials.last_mut() {
            trace.outcomes = outcomes
                .iter()
                .map(|o| OutcomeInfo {
                    score: o.score,
                    metabolism: o.metabolism,
                    shocked_ticks: o.shocked_ticks,
                    non_finite: o.non_finite,
                })
                .collect();
        }
    }
}
