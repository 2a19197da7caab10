//! The `[world]` and `[creature]` configuration tables: raw serde structs with strict parsing
//! (`deny_unknown_fields`), documented defaults, and validation that names the full key path
//! of the first bad value.
//!
//! Units: lengths in LU, time in ticks, motor speeds in rotations per tick (RPT). **Angles in
//! the configuration are in degrees** (easier to read and write); the simulator converts them
//! to radians. Frame (SPEC-NOTES): x grows to the right, y grows downwards, the arena is
//! `[0, width] x [0, height]`, and a positive angle turns clockwise on screen (towards the
//! creature's right), so heading 0° points along +x and 90° along +y (down the screen).

use crate::sim::controller::{GroupSizes, InputsSpec, ObservationLayout};
use crate::sim::smell::Smell;
use crate::validate::{
    all_finite, all_non_negative, count_within, finite, non_negative, positive, within,
    InvalidValue, Valid,
};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

mod gadgets;
mod values;
pub use gadgets::{
    AirPredatorSpec, DoorSpec, Effect, PredatorSpec, Strategy, TeleporterSpec, WanderersSpec,
    MAX_ACTORS, MAX_TICKS,
};
pub(crate) use values::exact;
pub use values::{Point, Region, DEFAULT_WALL_COLOUR, DEFAULT_WALL_HEIGHT};

/// Most creatures a world may hold.
pub const MAX_CREATURES: usize = 10_000;
/// Most objects a world may hold (explicit plus placed): beyond this a trial world costs more
/// memory and set-up time than any BERRY experiment needs, and a typo in a count is likelier.
pub const MAX_OBJECTS: u64 = 100_000;
/// Most walls a world may hold (explicit plus boundary).
pub const MAX_WALLS: u64 = 100_000;
/// Longest arena side in LU: far beyond the report's 300 LU, small enough that positions keep
/// sub-micro-LU precision in f64.
pub const MAX_ARENA_SIDE: f64 = 1.0e6;
/// Finest placement grid pitch in LU.
pub const MIN_GRID_PITCH: f64 = 1.0e-6;
/// Most halvings of the §8.2 binary search: after 64 the midpoint no longer changes in f64.
pub const MAX_SEARCH_STEPS: u64 = 64;
/// Most distal landmarks or areas a world may hold: each adds inputs to every brain.
pub const MAX_LANDMARKS: u64 = 1_000;
/// Most pixels on either side of the retina.
pub const MAX_RETINA_SIDE: u64 = 4_096;
/// Most pixels of a retina (width × height): 3 inputs each.
pub const MAX_RETINA_PIXELS: u64 = 65_536;

/// The `[world]` table: the arena, its walls, the kinds of objects, where objects go and where
/// creatures start. The default is the report's empty 300 x 300 LU arena bounded by four walls.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct WorldSpec {
    /// Arena size `[width, height]` in LU; the arena is `[0, width] x [0, height]`
    /// (default: `[300, 300]`, §3).
    #[serde(deserialize_with = "exact::array")]
    pub arena: [f64; 2],
    /// Add the four walls along the arena's edges (default: true, §3). Boundary walls are
    /// opaque, grey and 10 LU high.
    pub boundary_walls: bool,
    /// §8.1 "slippery walls": a creature stopped by an obstacle still turns its full angle
    /// φ' = φ instead of the fraction that fits its shortened path (default: false).
    pub slippery_walls: bool,
    /// The shock sensor also reads 1 after a tick in which a wall stopped the creature's move
    /// (§5.2; default: false).
    pub wall_shock: bool,
    /// The constant c of the smell diffusion eq. 25, I(d) = i / (1 + c d²), in 1/LU²
    /// (default: 0.01).
    pub smell_c: f64,
    /// Number of halvings in the §8.2 binary search for the collision point (default: 20).
    pub search_steps: u32,
    /// Interior walls (`[[world.walls]]`), after the boundary walls.
    pub walls: Vec<WallSpec>,
    /// Object templates by name (`[world.kinds.<name>]`), used by `objects` and `place`.
    pub kinds: BTreeMap<String, KindSpec>,
    /// Objects at fixed positions (`[[world.objects]]`), placed first, in this order.
    pub objects: Vec<ObjectSpec>,
    /// Random placement rules (`[[world.place]]`), applied after `objects`, in this order.
    pub place: Vec<PlaceSpec>,
    /// Where and how the creatures start (`[world.start]`).
    pub start: StartSpec,
    /// Distal landmarks (`[[world.landmarks]]`, §4.5.3): positions whose bearing every
    /// creature knows everywhere; they have no body (default: none).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub landmarks: Vec<LandmarkSpec>,
    /// Areas (`[[world.areas]]`, §4.6): rectangles a creature can be inside (default: none).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub areas: Vec<AreaSpec>,
    /// Locked doors (`[[world.doors]]`, §4.5.2; default: none).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub doors: Vec<DoorSpec>,
    /// Teleporters (`[[world.teleporters]]`, §4.5.1; default: none).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub teleporters: Vec<TeleporterSpec>,
    /// Irrelevant creatures (`[world.wanderers]`, §4.8; default: none).
    pub wanderers: WanderersSpec,
    /// Ground predators (`[[world.predators]]`, §4.7; default: none).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub predators: Vec<PredatorSpec>,
    /// Air predators (`[[world.air_predators]]`, §4.7; default: none).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub air_predators: Vec<AirPredatorSpec>,
}

/// A distal landmark (`[[world.landmarks]]`, §4.5.3): a point with no body, not felt, not
/// seen, not blocking; its bearing is sensed, and it may smell (§4.2 "all objects ... except
/// for walls, smell").
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LandmarkSpec {
    /// Position `[x, y]` in LU (required; may lie outside the arena: distal landmarks are
    /// typically far away).
    #[serde(deserialize_with = "exact::array")]
    pub position: Point,
    /// Odour given off at its position, smelled through eq. 25 like any other object's: from
    /// the position, fading with the distance to it, hidden by opaque walls between (so a
    /// landmark outside the boundary walls, which are opaque, is never smelled inside)
    /// (default: zeros = no smell).
    #[serde(
        default,
        skip_serializing_if = "exact::is_zero",
        deserialize_with = "exact::array"
    )]
    pub odour: [f64; 8],
    /// Smell intensity at its position (default: 0).
    #[serde(default, skip_serializing_if = "exact::is_zero_scalar")]
    pub intensity: f64,
    /// Smell range θ in LU (eq. 26; default: absent = unlimited).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub range: Option<f64>,
}

/// What an area is for (§4.6).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum AreaKind {
    /// A region with no effect of its own (default): sensed, and may smell.
    #[default]
    Plain,
    /// A safe area: predators do not attack creatures whose centre is inside
    /// ([`crate::sim::World::in_safe_area`]).
    Safe,
}

/// An area (`[[world.areas]]`, §4.6): an axis-aligned rectangle, optionally smelling at its
/// centre. Areas neither block, nor are felt, nor are seen.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct AreaSpec {
    /// A name that `[fitness]` and `[behaviour]` refer to the area by (default: none).
    /// Names must differ from one another; a name changes nothing in the world.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// `[x0, y0, x1, y1]` in LU inside the arena, x0 <= x1, y0 <= y1 (required). A point is
    /// inside when x0 <= x <= x1 and y0 <= y <= y1 (bounds included).
    #[serde(deserialize_with = "exact::array")]
    pub region: Region,
    /// `"plain"` or `"safe"` (default: `"plain"`).
    #[serde(default)]
    pub kind: AreaKind,
    /// Odour o = ⟨o1..o8⟩ given off at the centre of the region (default: zeros, no smell).
    #[serde(default, deserialize_with = "exact::array")]
    pub odour: [f64; 8],
    /// Smell intensity i at the centre (eq. 25; default: 0).
    #[serde(default)]
    pub intensity: f64,
    /// Smell range θ of eq. 26 in LU (default: absent = unlimited).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub range: Option<f64>,
}

impl Default for WorldSpec {
    fn default() -> Self {
        WorldSpec {
            arena: [300.0, 300.0],
            boundary_walls: true,
            slippery_walls: false,
            wall_shock: false,
            smell_c: 0.01,
            search_steps: 20,
            walls: Vec::new(),
            kinds: BTreeMap::new(),
            objects: Vec::new(),
            place: Vec::new(),
            start: StartSpec::default(),
            landmarks: Vec::new(),
            areas: Vec::new(),
            doors: Vec::new(),
            teleporters: Vec::new(),
            wanderers: WanderersSpec::default(),
            predators: Vec::new(),
            air_predators: Vec::new(),
        }
    }
}

/// One wall (`[[world.walls]]`, §4.1): a segment that blocks movement and is felt by whiskers;
/// an opaque wall also stops smells.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct WallSpec {
    /// First end point `[x, y]` in LU (required; inside the arena).
    #[serde(deserialize_with = "exact::array")]
    pub from: Point,
    /// Second end point `[x, y]` in LU (required; inside the arena, not equal to `from`).
    #[serde(deserialize_with = "exact::array")]
    pub to: Point,
    /// Stops smells passing through it (default: true). Every wall blocks movement and is
    /// felt by whiskers, opaque or not.
    #[serde(default = "default_true")]
    pub opaque: bool,
    /// Colour `[r, g, b]`, each in [0, 1], for the eye and for pictures (default: grey 0.5).
    #[serde(default = "default_wall_colour", deserialize_with = "exact::array")]
    pub colour: [f64; 3],
    /// Height in LU, for the eye (default: 10, §4.1).
    #[serde(default = "default_wall_height")]
    pub height: f64,
}

fn default_true() -> bool {
    true
}

fn default_wall_colour() -> [f64; 3] {
    DEFAULT_WALL_COLOUR
}

fn default_wall_height() -> f64 {
    DEFAULT_WALL_HEIGHT
}

/// A kind of object (`[world.kinds.<name>]`), chosen by `class = "food"` or
/// `class = "aversive"`. Each class accepts only its own keys.
///
/// Read through a flat raw table (every key optional) rather than serde's internally tagged enums: those buffer the
/// table before choosing the variant, and the `toml` crate then loses the key of a bad value
/// inside it ("invalid length 2" without saying which array).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(tag = "class", rename_all = "snake_case", try_from = "RawKind")]
pub enum KindSpec {
    /// Food (§4.3): substance a creature can eat.
    Food(FoodKind),
    /// An aversive object (§4.4): shocks a creature touching it.
    Aversive(AversiveKind),
}

/// The class of a kind.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
enum Class {
    Food,
    Aversive,
}

/// Every key a kind table may hold, as read from the file; see [`FoodKind`] and
/// [`AversiveKind`] for their meaning and defaults.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
struct RawKind {
    /// `"food"` (§4.3) or `"aversive"` (§4.4) (required).
    class: Class,
    /// Radius in LU; 0 is a point (default: 0).
    #[serde(default)]
    radius: f64,
    /// Food only: substance amounts ⟨A, B, C, D⟩ a new object holds (default: `[1, 0, 0, 0]`).
    #[serde(default, deserialize_with = "exact::option_array")]
    substance: Option<[f64; 4]>,
    /// Food only: most substance the object can hold, at least `substance` (default: absent =
    /// equal to `substance`).
    #[serde(default, deserialize_with = "exact::option_array")]
    capacity: Option<[f64; 4]>,
    /// Food only: bite b, substance moved to the creature per eating tick, per type; it gets
    /// min(bite, what is left) (default: `[1, 1, 1, 1]`).
    #[serde(default, deserialize_with = "exact::option_array")]
    bite: Option<[f64; 4]>,
    /// Food only: regeneration r, substance added per tick, per type, up to `capacity`
    /// (default: zeros).
    #[serde(default, deserialize_with = "exact::option_array")]
    regen: Option<[f64; 4]>,
    /// Food only: eating removes the substance from the object; when false it feeds without
    /// end (default: true).
    #[serde(default)]
    depletes: Option<bool>,
    /// Food only: the smell intensity scales with total amount / total capacity (default:
    /// false).
    #[serde(default)]
    smell_follows_amount: Option<bool>,
    /// Odour o = ⟨o1..o8⟩, usually in [0, 1] (default: zeros, no smell).
    #[serde(default, deserialize_with = "exact::option_array")]
    odour: Option<[f64; 8]>,
    /// Smell intensity i at the centre (eq. 25; default: 0).
    #[serde(default)]
    intensity: f64,
    /// Smell range θ of eq. 26 in LU: the smell is zero at distance ≥ θ (default: absent =
    /// unlimited).
    #[serde(default)]
    range: Option<f64>,
    /// Colour `[r, g, b]`, each in [0, 1], as the eye sees the object (default: absent =
    /// green `[0, 1, 0]` for food, red `[1, 0, 0]` for aversive objects).
    #[serde(default, deserialize_with = "exact::option_array")]
    colour: Option<[f64; 3]>,
    /// Height in LU of the cylinder the eye sees (default: absent = 5). Objects of radius 0
    /// are never seen.
    #[serde(default)]
    height: Option<f64>,
}

impl TryFrom<RawKind> for KindSpec {
    type Error = String;

    fn try_from(raw: RawKind) -> Result<KindSpec, String> {
        let odour = raw.odour.unwrap_or([0.0; 8]);
        match raw.class {
            Class::Food => {
                let d = FoodKind::default();
                Ok(KindSpec::Food(FoodKind {
                    radius: raw.radius,
                    substance: raw.substance.unwrap_or(d.substance),
                    capacity: raw.capacity,
                    bite: raw.bite.unwrap_or(d.bite),
                    regen: raw.regen.unwrap_or(d.regen),
                    depletes: raw.depletes.unwrap_or(d.depletes),
                    smell_follows_amount: raw
                        .smell_follows_amount
                        .unwrap_or(d.smell_follows_amount),
                    odour,
                    intensity: raw.intensity,
                    range: raw.range,
                    colour: raw.colour,
                    height: raw.height,
                }))
            }
            Class::Aversive => {
                let food_only = [
                    ("substance", raw.substance.is_some()),
                    ("capacity", raw.capacity.is_some()),
                    ("bite", raw.bite.is_some()),
                    ("regen", raw.regen.is_some()),
                    ("depletes", raw.depletes.is_some()),
                    ("smell_follows_amount", raw.smell_follows_amount.is_some()),
                ];
                if let Some((key, _)) = food_only.iter().find(|(_, set)| *set) {
                    return Err(format!(
                        "`{key}` applies only to food kinds, and this kind has class = \"aversive\""
                    ));
                }
                Ok(KindSpec::Aversive(AversiveKind {
                    radius: raw.radius,
                    odour,
                    intensity: raw.intensity,
                    range: raw.range,
                    colour: raw.colour,
                    height: raw.height,
                }))
            }
        }
    }
}

impl KindSpec {
    /// Radius in LU.
    pub fn radius(&self) -> f64 {
        match self {
            KindSpec::Food(f) => f.radius,
            KindSpec::Aversive(a) => a.radius,
        }
    }
}

/// A food kind (§4.3, §5.2–5.3). Substance vectors are ⟨A, B, C, D⟩.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct FoodKind {
    /// Radius in LU; 0 is a point (default: 0, "typically the radius is 0").
    pub radius: f64,
    /// Substance amounts ⟨A, B, C, D⟩ a new object holds (default: `[1, 0, 0, 0]`).
    pub substance: [f64; 4],
    /// Most substance the object can hold: regeneration stops there, and `smell_follows_amount`
    /// divides by its total (default: absent = equal to `substance`). Must be >= `substance`.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "exact::option_array"
    )]
    pub capacity: Option<[f64; 4]>,
    /// Bite b: substance moved to the creature per eating tick, per type; the creature gets
    /// min(bite, what is left) (default: `[1, 1, 1, 1]`).
    pub bite: [f64; 4],
    /// Regeneration r: substance added per tick, per type, up to `capacity` (default: zeros).
    pub regen: [f64; 4],
    /// Eating removes the substance from the object (default: true). When false the object
    /// keeps its amount and feeds without end.
    pub depletes: bool,
    /// The smell intensity scales with total amount / total capacity (default: false).
    pub smell_follows_amount: bool,
    /// Odour o = ⟨o1..o8⟩, usually in [0, 1] (default: zeros, no smell).
    pub odour: [f64; 8],
    /// Smell intensity i at the centre (eq. 25; default: 0).
    pub intensity: f64,
    /// Smell range θ of eq. 26 in LU: the smell is zero at distance >= θ (default: absent =
    /// eq. 25, unlimited range).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub range: Option<f64>,
    /// Colour `[r, g, b]`, each in [0, 1], as the eye sees the object (default: absent =
    /// green `[0, 1, 0]`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub colour: Option<[f64; 3]>,
    /// Height in LU of the cylinder the eye sees (default: absent = 5, the default eye
    /// height, so that a 1-row retina sees it). Objects of radius 0 are never seen.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub height: Option<f64>,
}

/// Default colour of food for the eye.
pub const DEFAULT_FOOD_COLOUR: [f64; 3] = [0.0, 1.0, 0.0];
/// Default colour of aversive objects for the eye.
pub const DEFAULT_AVERSIVE_COLOUR: [f64; 3] = [1.0, 0.0, 0.0];
/// Default colour of creatures for the eye.
pub const DEFAULT_CREATURE_COLOUR: [f64; 3] = [0.0, 0.0, 1.0];
/// Default height of food and aversive objects in LU (the default eye height).
pub const DEFAULT_OBJECT_HEIGHT: f64 = 5.0;
/// Default height of a creature's body in LU (the default body diameter).
pub const DEFAULT_CREATURE_HEIGHT: f64 = 6.0;

impl Default for FoodKind {
    fn default() -> Self {
        FoodKind {
            radius: 0.0,
            substance: [1.0, 0.0, 0.0, 0.0],
            capacity: None,
            bite: [1.0; 4],
            regen: [0.0; 4],
            depletes: true,
            smell_follows_amount: false,
            odour: [0.0; 8],
            intensity: 0.0,
            range: None,
            colour: None,
            height: None,
        }
    }
}

impl FoodKind {
    /// The capacity, with the documented default (equal to the initial substance).
    pub fn capacity(&self) -> [f64; 4] {
        self.capacity.unwrap_or(self.substance)
    }
}

/// An aversive kind (§4.4): a circle or point that shocks creatures touching it, and smells.
#[derive(Debug, Clone, PartialEq, Serialize, Default, JsonSchema)]
pub struct AversiveKind {
    /// Radius in LU; 0 is a point (default: 0).
    pub radius: f64,
    /// Odour o = ⟨o1..o8⟩ (default: zeros).
    pub odour: [f64; 8],
    /// Smell intensity i at the centre (default: 0).
    pub intensity: f64,
    /// Smell range θ in LU (default: absent = unlimited, eq. 25).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub range: Option<f64>,
    /// Colour `[r, g, b]` for the eye (default: absent = red `[1, 0, 0]`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub colour: Option<[f64; 3]>,
    /// Height in LU for the eye (default: absent = 5). Radius-0 objects are never seen.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub height: Option<f64>,
}

/// An object at a fixed position (`[[world.objects]]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ObjectSpec {
    /// Name of its kind in `[world.kinds]` (required).
    pub kind: String,
    /// Centre `[x, y]` in LU, inside the arena (required).
    #[serde(deserialize_with = "exact::array")]
    pub position: Point,
}

/// A random placement rule (`[[world.place]]`): `count` objects of `kind`, uniform in
/// `region`, at least `min_spacing` from every object placed before, never touching a wall.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PlaceSpec {
    /// Name of the kind in `[world.kinds]` (required).
    pub kind: String,
    /// How many objects (required; the world's total is at most 100000).
    pub count: u64,
    /// `[x0, y0, x1, y1]` in LU where centres may go (default: absent = the whole arena).
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "exact::option_array"
    )]
    pub region: Option<Region>,
    /// Smallest distance in LU between the centre of a new object and the centre of every
    /// object placed before it, explicit or random (default: 0 = no constraint).
    #[serde(default)]
    pub min_spacing: f64,
    /// Grid pitch in LU (§2): centres are drawn among the grid points `(i·pitch, j·pitch)`
    /// inside the region (default: absent = anywhere).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub grid: Option<f64>,
}

/// Where creatures start (`[world.start]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct StartSpec {
    /// `[x0, y0, x1, y1]` in LU where body centres may start (default: absent = the whole
    /// arena). Each creature is placed uniformly in it, touching no wall, other creature, food
    /// or aversive object.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "exact::option_array"
    )]
    pub region: Option<Region>,
    /// Initial heading in degrees, 0 = +x, 90 = +y (down the screen) (default: absent = a
    /// uniformly random heading for each creature).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub heading: Option<f64>,
    /// Grid pitch in LU (§2), as `[[world.place]] grid`: body centres are drawn uniformly
    /// among the grid points `(i·pitch, j·pitch)` inside the region, each still touching no
    /// wall, other creature, food or aversive object (default: absent = anywhere in the
    /// region). At least one grid point must lie in the region.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub grid: Option<f64>,
}

/// How a creature eats (SPEC-NOTES: the report does not say).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Eating {
    /// Every tick of body contact with a food object transfers a bite (default).
    #[default]
    Contact,
    /// The controller has an eat output; the creature eats when it exceeds 0.5 in contact.
    Action,
}

/// The `[creature]` table: the body tuple ⟨d, φ, s, a, w, o⟩ of §5.1, motors, eating,
/// metabolism and which sensors the controller receives. Defaults are the report's (Figure 2).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct CreatureSpec {
    /// Body diameter d in LU (default: 6).
    pub diameter: f64,
    /// Whisker angle φ between the heading and each whisker, in degrees, 0..=180
    /// (default: 45).
    pub whisker_angle: f64,
    /// Whisker length s in LU, from the body centre (default: 5).
    pub whisker_length: f64,
    /// The report's parameter a in LU (default: 2). Figure 2, which defined it, is missing
    /// and no equation uses it; it is kept for completeness and has no effect.
    pub a: f64,
    /// Wheel parameter w of eq. 28–33 in LU (default: 2).
    pub wheel: f64,
    /// Body odour o = ⟨o1..o8⟩ that other creatures smell (default: zeros).
    #[serde(deserialize_with = "exact::array")]
    pub odour: [f64; 8],
    /// Intensity of the body odour (default: 0); with `odours`, of each creature's.
    pub odour_intensity: f64,
    /// A body odour per creature (§5.1: "may be distinct for each individual creature"):
    /// creature i of a world (its index in the group evaluated together, from 0) gives off
    /// `odours[i mod n]` at `odour_intensity` instead of `odour`, so a list as long as the
    /// group gives each creature its own and a shorter one repeats (two entries: alternate
    /// creatures share one of two odours). A creature never smells its own body (default:
    /// empty = every creature gives off `odour`).
    #[serde(
        skip_serializing_if = "Vec::is_empty",
        deserialize_with = "exact::arrays"
    )]
    pub odours: Vec<[f64; 8]>,
    /// Largest motor speed in RPT; motor commands are clamped to ±max_rpt (default: 0.25,
    /// about 3.1 LU per tick with w = 2).
    pub max_rpt: f64,
    /// `"contact"` or `"action"` (default: `"contact"`).
    pub eating: Eating,
    /// §7.3: both smell sensors read 0 while either whisker touches something
    /// (default: false).
    pub inhibit_smell_on_whisker: bool,
    /// Metabolic state m = ⟨fA, fB, fC, fD⟩ at birth (default: zeros).
    #[serde(deserialize_with = "exact::array")]
    pub initial_metabolism: [f64; 4],
    /// Spread of m at birth: each component is `initial_metabolism` plus a uniform draw from
    /// [0, spread) for every creature in every trial (default: zeros = no draw). With a
    /// spread the substance a creature lacks most differs from trial to trial, so only its
    /// metabolism inputs can tell it which food to seek.
    #[serde(
        skip_serializing_if = "exact::is_zero",
        deserialize_with = "exact::array"
    )]
    pub initial_metabolism_spread: [f64; 4],
    /// Decrease of m per tick (default: zeros).
    #[serde(deserialize_with = "exact::array")]
    pub decay_per_tick: [f64; 4],
    /// Decrease of m per LU travelled (default: zeros).
    #[serde(deserialize_with = "exact::array")]
    pub decay_per_lu: [f64; 4],
    /// Sensor groups the controller receives (`[creature.inputs]`).
    pub inputs: InputsSpec,
    /// Body colour `[r, g, b]` as other creatures' eyes see it (default: absent = blue
    /// `[0, 0, 1]`).
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "exact::option_array"
    )]
    pub colour: Option<[f64; 3]>,
    /// Body height in LU as other creatures' eyes see it (default: absent = 6).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub height: Option<f64>,
    /// The eye (`[creature.eye]`, §7.4); rendered only when `inputs.eye` is on.
    #[serde(skip_serializing_if = "EyeSpec::is_default")]
    pub eye: EyeSpec,
    /// Sensor noise (`[creature.noise.<group>]`, §7.5, eq. 27); default: none.
    #[serde(skip_serializing_if = "NoiseSpec::is_none")]
    pub noise: NoiseSpec,
}

/// The eye (`[creature.eye]`, §7.4): a cyclopean eye at the body centre, `eye_height` above
/// the ground, looking along the heading. Pixel column i (from 0, left to right) looks along
/// the heading rotated by −fov/2 + (i + ½)·fov/width (positive = clockwise = right); row j
/// (from 0, top to bottom) at elevation vertical_fov/2 − (j + ½)·vertical_fov/height above
/// the horizontal (0 for a 1-row retina). A surface of height H at distance d along a pixel's
/// ray covers the elevations e with −eye_height ≤ d·tan e ≤ H − eye_height, so a 1-row
/// retina sees exactly the surfaces at least `eye_height` tall.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct EyeSpec {
    /// Horizontal field of view in degrees, in (0, 360] (default: 90).
    pub fov: f64,
    /// Vertical field of view in degrees, in (0, 180), used when `height` > 1 (default: 60).
    pub vertical_fov: f64,
    /// Pixels per row (default: 16).
    pub width: u64,
    /// Rows of pixels; 1 is a 1-D retina (default: 1).
    pub height: u64,
    /// Height of the eye above the ground in LU (default: 5).
    pub eye_height: f64,
    /// Colour `[r, g, b]` of a pixel whose ray meets nothing (default: black `[0, 0, 0]`).
    #[serde(deserialize_with = "exact::array")]
    pub background: [f64; 3],
    /// Largest distance in LU at which a surface is seen (default: absent = unlimited).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub range: Option<f64>,
}

impl Default for EyeSpec {
    fn default() -> Self {
        EyeSpec {
            fov: 90.0,
            vertical_fov: 60.0,
            width: 16,
            height: 1,
            eye_height: 5.0,
            background: [0.0; 3],
            range: None,
        }
    }
}

impl EyeSpec {
    fn is_default(&self) -> bool {
        *self == EyeSpec::default()
    }

    /// Checks every value; keys start with `key`.
    pub fn validate(&self, key: &str) -> Valid {
        finite(&format!("{key}.fov"), self.fov)?;
        if !(self.fov > 0.0 && self.fov <= 360.0) {
            return Err(InvalidValue::new(
                format!("{key}.fov"),
                format!("must be in (0, 360] degrees, got {}", self.fov),
            ));
        }
        finite(&format!("{key}.vertical_fov"), self.vertical_fov)?;
        if !(self.vertical_fov > 0.0 && self.vertical_fov < 180.0) {
            return Err(InvalidValue::new(
                format!("{key}.vertical_fov"),
                format!("must be in (0, 180) degrees, got {}", self.vertical_fov),
            ));
        }
        let why = "retina side in pixels";
        count_within(&format!("{key}.width"), self.width, 1, MAX_RETINA_SIDE, why)?;
        count_within(
            &format!("{key}.height"),
            self.height,
            1,
            MAX_RETINA_SIDE,
            why,
        )?;
        count_within(
            &format!("{key}.height"),
            self.width * self.height,
            1,
            MAX_RETINA_PIXELS,
            "pixels of the retina (width x height)",
        )?;
        non_negative(&format!("{key}.eye_height"), self.eye_height)?;
        for (c, value) in self.background.iter().enumerate() {
            within(&format!("{key}.background[{c}]"), *value, 0.0, 1.0)?;
        }
        if let Some(range) = self.range {
            positive(&format!("{key}.range"), range)?;
        }
        Ok(())
    }
}

/// Noise on one sensor group (eq. 27): each input s becomes ŝ = N + (1 + M)·s, clipped to
/// the group's range, with N = |normal(0, n_sigma)| clipped to [0, n] and M =
/// normal(0, m_sigma) clipped to [−m, m].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, Default, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct NoiseChannel {
    /// Largest additive noise N (default: 0).
    pub n: f64,
    /// Standard deviation of the normal draw behind N (default: 0).
    pub n_sigma: f64,
    /// Largest multiplicative noise |M|, at most 1 so that 1 + M is never negative
    /// (default: 0).
    pub m: f64,
    /// Standard deviation of M (default: 0).
    pub m_sigma: f64,
}

impl NoiseChannel {
    fn validate(&self, key: &str) -> Valid {
        non_negative(&format!("{key}.n"), self.n)?;
        non_negative(&format!("{key}.n_sigma"), self.n_sigma)?;
        within(&format!("{key}.m"), self.m, 0.0, 1.0)?;
        non_negative(&format!("{key}.m_sigma"), self.m_sigma)
    }
}

/// Sensor noise per group (`[creature.noise.<group>]`, §7.5). A group without a table gets no
/// noise and costs no random draws, so noise-free runs are unchanged. Ranges the noisy value
/// is clipped to: [0, 1] for smell, whiskers, food, shock, areas and eye; [0, ∞) for
/// metabolism; [−1, 1] for landmarks. The bias is never noisy.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct NoiseSpec {
    /// Noise on the 16 smell receptors (default: none).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub smell: Option<NoiseChannel>,
    /// Noise on the whiskers (default: none).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub whiskers: Option<NoiseChannel>,
    /// Noise on the food detectors (default: none).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub food: Option<NoiseChannel>,
    /// Noise on the shock sensor (default: none).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shock: Option<NoiseChannel>,
    /// Noise on the metabolism inputs (default: none).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub metabolism: Option<NoiseChannel>,
    /// Noise on the landmark bearings (default: none).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub landmarks: Option<NoiseChannel>,
    /// Noise on the area inputs (default: none).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub areas: Option<NoiseChannel>,
    /// Noise on every retina value (default: none).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub eye: Option<NoiseChannel>,
}

impl NoiseSpec {
    fn is_none(&self) -> bool {
        *self == NoiseSpec::default()
    }

    /// The noise on `group`, if configured.
    pub fn channel(&self, group: crate::sim::controller::SensorGroup) -> Option<NoiseChannel> {
        use crate::sim::controller::SensorGroup as G;
        match group {
            G::Smell => self.smell,
            G::Whiskers => self.whiskers,
            G::Food => self.food,
            G::Shock => self.shock,
            G::Metabolism => self.metabolism,
            G::Landmarks => self.landmarks,
            G::Areas => self.areas,
            G::Eye => self.eye,
            G::Bias => None,
        }
    }

    /// Checks every value; keys start with `creature.noise.`.
    pub fn validate(&self) -> Valid {
        let groups = [
            ("smell", self.smell),
            ("whiskers", self.whiskers),
            ("food", self.food),
            ("shock", self.shock),
            ("metabolism", self.metabolism),
            ("landmarks", self.landmarks),
            ("areas", self.areas),
            ("eye", self.eye),
        ];
        for (name, channel) in groups {
            if let Some(c) = channel {
                c.validate(&format!("creature.noise.{name}"))?;
            }
        }
        Ok(())
    }
}

impl Default for CreatureSpec {
    fn default() -> Self {
        CreatureSpec {
            diameter: 6.0,
            whisker_angle: 45.0,
            whisker_length: 5.0,
            a: 2.0,
            wheel: 2.0,
            odour: [0.0; 8],
            odour_intensity: 0.0,
            odours: Vec::new(),
            max_rpt: 0.25,
            eating: Eating::Contact,
            inhibit_smell_on_whisker: false,
            initial_metabolism: [0.0; 4],
            initial_metabolism_spread: [0.0; 4],
            decay_per_tick: [0.0; 4],
            decay_per_lu: [0.0; 4],
            inputs: InputsSpec::default(),
            colour: None,
            height: None,
            eye: EyeSpec::default(),
            noise: NoiseSpec::default(),
        }
    }
}

impl CreatureSpec {
    /// Checks every value; keys start with `creature.`.
    pub fn validate(&self) -> Valid {
        positive("creature.diameter", self.diameter)?;
        within("creature.whisker_angle", self.whisker_angle, 0.0, 180.0)?;
        non_negative("creature.whisker_length", self.whisker_length)?;
        non_negative("creature.a", self.a)?;
        positive("creature.wheel", self.wheel)?;
        all_non_negative("creature.odour", &self.odour)?;
        non_negative("creature.odour_intensity", self.odour_intensity)?;
        count_within(
            "creature.odours",
            self.odours.len() as u64,
            0,
            MAX_CREATURES as u64,
            "odours, one per creature at most",
        )?;
        for (i, odour) in self.odours.iter().enumerate() {
            all_non_negative(&format!("creature.odours[{i}]"), odour)?;
        }
        non_negative("creature.max_rpt", self.max_rpt)?;
        all_non_negative("creature.initial_metabolism", &self.initial_metabolism)?;
        all_non_negative(
            "creature.initial_metabolism_spread",
            &self.initial_metabolism_spread,
        )?;
        all_non_negative("creature.decay_per_tick", &self.decay_per_tick)?;
        all_non_negative("creature.decay_per_lu", &self.decay_per_lu)?;
        if let Some(colour) = self.colour {
            for (c, value) in colour.iter().enumerate() {
                within(&format!("creature.colour[{c}]"), *value, 0.0, 1.0)?;
            }
        }
        if let Some(height) = self.height {
            non_negative("creature.height", height)?;
        }
        self.eye.validate("creature.eye")?;
        self.noise.validate()?;
        Ok(())
    }

    /// The smell of creature `i`'s body: `odours[i mod n]` when `odours` is given, else
    /// `odour`, at `odour_intensity`, with unlimited range.
    pub fn body_smell(&self, i: usize) -> Smell {
        let odour = match self.odours.len() {
            0 => &self.odour,
            n => &self.odours[i % n],
        };
        Smell::new(odour, self.odour_intensity, None)
    }

    /// What every creature's body smell is at most, component by component (`odour`'s smell
    /// without `odours`): silent when no creature's body smells.
    pub fn strongest_body_smell(&self) -> Smell {
        if self.odours.is_empty() {
            return self.body_smell(0);
        }
        let mut most = [0.0f64; 8];
        for o in &self.odours {
            for (m, v) in most.iter_mut().zip(o) {
                *m = m.max(*v);
            }
        }
        Smell::new(&most, self.odour_intensity, None)
    }

    /// Where each input sits in the observation of this creature in `world` (the number of
    /// landmarks and areas decides the width of their groups).
    pub fn layout(&self, world: &WorldSpec) -> ObservationLayout {
        ObservationLayout::new(&self.inputs, &self.group_sizes(world))
    }

    /// The widths of the world- and creature-dependent sensor groups.
    pub fn group_sizes(&self, world: &WorldSpec) -> GroupSizes {
        GroupSizes {
            landmarks: world.landmarks.len(),
            areas: world.areas.len(),
            retina: [self.eye.width as usize, self.eye.height as usize],
        }
    }

    /// Body colour for the eye, with its default.
    pub fn body_colour(&self) -> [f64; 3] {
        self.colour.unwrap_or(DEFAULT_CREATURE_COLOUR)
    }

    /// Body height for the eye, with its default.
    pub fn body_height(&self) -> f64 {
        self.height.unwrap_or(DEFAULT_CREATURE_HEIGHT)
    }

    /// Does the controller need an eat output?
    pub fn eats_by_action(&self) -> bool {
        self.eating == Eating::Action
    }

    /// Body radius d/2 in LU.
    pub fn radius(&self) -> f64 {
        0.5 * self.diameter
    }

    /// The whisker angle φ in radians.
    pub fn whisker_angle_radians(&self) -> f64 {
        self.whisker_angle.to_radians()
    }
}

impl WorldSpec {
    /// Checks every value, and that everything fits in the arena; keys start with `world.`.
    /// `creature` is needed to check that a body fits in the arena at all.
    pub fn validate(&self, creature: &CreatureSpec) -> Valid {
        for (i, side) in self.arena.iter().enumerate() {
            let key = format!("world.arena[{i}]");
            positive(&key, *side)?;
            if *side > MAX_ARENA_SIDE {
                return Err(InvalidValue::new(
                    key,
                    format!("must be at most {MAX_ARENA_SIDE} LU (f64 precision), got {side}"),
                ));
            }
            if creature.diameter.is_finite() && *side < creature.diameter {
                return Err(InvalidValue::new(
                    key,
                    format!(
                        "must be at least the creature diameter {}, got {side}",
                        creature.diameter
                    ),
                ));
            }
        }
        non_negative("world.smell_c", self.smell_c)?;
        count_within(
            "world.search_steps",
            u64::from(self.search_steps),
            1,
            MAX_SEARCH_STEPS,
            "further halvings no longer move the midpoint",
        )?;

        let boundary = if self.boundary_walls { 4 } else { 0 };
        count_within(
            "world.walls",
            self.walls.len() as u64 + boundary,
            0,
            MAX_WALLS,
            "the largest world this simulator supports",
        )?;
        for (i, wall) in self.walls.iter().enumerate() {
            self.validate_wall(&format!("world.walls[{i}]"), wall)?;
        }

        for (name, kind) in &self.kinds {
            validate_kind(&format!("world.kinds.{name}"), name, kind)?;
        }

        count_within(
            "world.objects",
            self.objects.len() as u64,
            0,
            MAX_OBJECTS,
            "total objects in a world, explicit and placed",
        )?;
        for (i, object) in self.objects.iter().enumerate() {
            let key = format!("world.objects[{i}]");
            self.known_kind(&format!("{key}.kind"), &object.kind)?;
            self.inside_arena(&format!("{key}.position"), object.position)?;
        }

        let mut total = self.objects.len() as u64;
        for (i, rule) in self.place.iter().enumerate() {
            let key = format!("world.place[{i}]");
            self.known_kind(&format!("{key}.kind"), &rule.kind)?;
            total = total.saturating_add(rule.count);
            count_within(
                &format!("{key}.count"),
                total,
                0,
                MAX_OBJECTS,
                "total objects in a world, explicit and placed",
            )?;
            if let Some(region) = rule.region {
                self.region_in_arena(&format!("{key}.region"), region)?;
            }
            non_negative(&format!("{key}.min_spacing"), rule.min_spacing)?;
            if let Some(pitch) = rule.grid {
                let region = rule.region.unwrap_or(self.arena_region());
                validate_grid(&format!("{key}.grid"), pitch, region)?;
            }
        }

        if let Some(region) = self.start.region {
            self.region_in_arena("world.start.region", region)?;
        }
        if let Some(pitch) = self.start.grid {
            let region = self.start.region.unwrap_or(self.arena_region());
            validate_grid("world.start.grid", pitch, region)?;
        }
        if let Some(heading) = self.start.heading {
            finite("world.start.heading", heading)?;
        }

        let why = "landmarks or areas in a world (each adds brain inputs)";
        count_within(
            "world.landmarks",
            self.landmarks.len() as u64,
            0,
            MAX_LANDMARKS,
            why,
        )?;
        for (i, landmark) in self.landmarks.iter().enumerate() {
            all_finite(
                &format!("world.landmarks[{i}].position"),
                &landmark.position,
            )?;
            validate_smell(
                &format!("world.landmarks[{i}]"),
                &landmark.odour,
                landmark.intensity,
                landmark.range,
            )?;
        }
        if creature.inputs.landmarks && self.landmarks.is_empty() {
            return Err(InvalidValue::new(
                "creature.inputs.landmarks",
                "is on, but the world has no [[world.landmarks]] to sense",
            ));
        }
        count_within(
            "world.areas",
            self.areas.len() as u64,
            0,
            MAX_LANDMARKS,
            why,
        )?;
        if creature.inputs.areas && self.areas.is_empty() {
            return Err(InvalidValue::new(
                "creature.inputs.areas",
                "is on, but the world has no [[world.areas]] to sense",
            ));
        }
        for (i, area) in self.areas.iter().enumerate() {
            let key = format!("world.areas[{i}]");
            self.region_in_arena(&format!("{key}.region"), area.region)?;
            validate_smell(&key, &area.odour, area.intensity, area.range)?;
        }
        gadgets::validate(
            self.arena,
            &self.doors,
            &self.teleporters,
            &self.wanderers,
            &self.predators,
            &self.air_predators,
        )
    }

    /// The whole arena as a region.
    pub fn arena_region(&self) -> Region {
        [0.0, 0.0, self.arena[0], self.arena[1]]
    }

    fn validate_wall(&self, key: &str, wall: &WallSpec) -> Valid {
        self.inside_arena(&format!("{key}.from"), wall.from)?;
        self.inside_arena(&format!("{key}.to"), wall.to)?;
        if wall.from == wall.to {
            return Err(InvalidValue::new(
                format!("{key}.to"),
                format!(
                    "a wall must have a length, but `to` equals `from` {:?}",
                    wall.from
                ),
            ));
        }
        for (c, value) in wall.colour.iter().enumerate() {
            within(&format!("{key}.colour[{c}]"), *value, 0.0, 1.0)?;
        }
        non_negative(&format!("{key}.height"), wall.height)
    }

    fn known_kind(&self, key: &str, name: &str) -> Valid {
        if self.kinds.contains_key(name) {
            return Ok(());
        }
        let known: Vec<&str> = self.kinds.keys().map(String::as_str).collect();
        Err(InvalidValue::new(
            key,
            format!("unknown kind `{name}`; the kinds defined in [world.kinds] are {known:?}"),
        ))
    }

    fn inside_arena(&self, key: &str, p: Point) -> Valid {
        all_finite(key, &p)?;
        let [w, h] = self.arena;
        if p[0] < 0.0 || p[0] > w || p[1] < 0.0 || p[1] > h {
            return Err(InvalidValue::new(
                key,
                format!("{p:?} lies outside the arena [0, {w}] x [0, {h}]"),
            ));
        }
        Ok(())
    }

    fn region_in_arena(&self, key: &str, r: Region) -> Valid {
        all_finite(key, &r)?;
        if r[0] > r[2] || r[1] > r[3] {
            return Err(InvalidValue::new(
                key,
                format!("must be [x0, y0, x1, y1] with x0 <= x1 and y0 <= y1, got {r:?}"),
            ));
        }
        self.inside_arena(key, [r[0], r[1]])?;
        self.inside_arena(key, [r[2], r[3]])
    }
}

/// The grid indices `lo..=hi` whose points `i·pitch` lie in `[a, b]`, or `None` when none do.
pub(crate) fn grid_span(a: f64, b: f64, pitch: f64) -> Option<(i64, i64)> {
    let lo = (a / pitch).ceil();
    let hi = (b / pitch).floor();
    // Rounding of a / pitch could put a point a hair outside the interval; step inwards.
    let lo = if lo * pitch < a { lo + 1.0 } else { lo };
    let hi = if hi * pitch > b { hi - 1.0 } else { hi };
    (lo <= hi).then_some((lo as i64, hi as i64))
}

/// A placement grid of pitch `pitch` (§2) for `region`: at least [`MIN_GRID_PITCH`], with
/// a grid point inside the region.
fn validate_grid(key: &str, pitch: f64, region: Region) -> Valid {
    positive(key, pitch)?;
    if pitch < MIN_GRID_PITCH {
        return Err(InvalidValue::new(
            key,
            format!("must be at least {MIN_GRID_PITCH} LU (finer is below f64 precision at large arenas), got {pitch}"),
        ));
    }
    let [x0, y0, x1, y1] = region;
    if grid_span(x0, x1, pitch).is_none() || grid_span(y0, y1, pitch).is_none() {
        return Err(InvalidValue::new(
            key,
            format!("no point of a {pitch} LU grid lies inside the region"),
        ));
    }
    Ok(())
}

fn validate_smell(key: &str, odour: &[f64; 8], intensity: f64, range: Option<f64>) -> Valid {
    all_non_negative(&format!("{key}.odour"), odour)?;
    non_negative(&format!("{key}.intensity"), intensity)?;
    if let Some(range) = range {
        positive(&format!("{key}.range"), range)?;
    }
    Ok(())
}

fn validate_kind(key: &str, name: &str, kind: &KindSpec) -> Valid {
    if name.is_empty() {
        return Err(InvalidValue::new(key, "a kind needs a non-empty name"));
    }
    match kind {
        KindSpec::Aversive(a) => {
            non_negative(&format!("{key}.radius"), a.radius)?;
            validate_look(key, a.colour, a.height)?;
            validate_smell(key, &a.odour, a.intensity, a.range)
        }
        KindSpec::Food(f) => {
            non_negative(&format!("{key}.radius"), f.radius)?;
            all_non_negative(&format!("{key}.substance"), &f.substance)?;
            all_non_negative(&format!("{key}.bite"), &f.bite)?;
            all_non_negative(&format!("{key}.regen"), &f.regen)?;
            if let Some(capacity) = f.capacity {
                all_non_negative(&format!("{key}.capacity"), &capacity)?;
                for (t, (s, c)) in f.substance.iter().zip(capacity).enumerate() {
                    if *s > c {
                        return Err(InvalidValue::new(
                            format!("{key}.capacity[{t}]"),
                            format!("must be at least the initial substance {s}, got {c}"),
                        ));
                    }
                }
            }
            if f.smell_follows_amount && f.capacity().iter().sum::<f64>() <= 0.0 {
                return Err(InvalidValue::new(
                    format!("{key}.smell_follows_amount"),
                    "needs a capacity with a positive total (the smell scales with amount / capacity)",
                ));
            }
            validate_look(key, f.colour, f.height)?;
            validate_smell(key, &f.odour, f.intensity, f.range)
        }
    }
}

/// Colour and height for the eye.
fn validate_look(key: &str, colour: Option<[f64; 3]>, height: Option<f64>) -> Valid {
    if let Some(colour) = colour {
        for (c, value) in colour.iter().enumerate() {
            within(&format!("{key}.colour[{c}]"), *value, 0.0, 1.0)?;
        }
    }
    if let Some(height) = height {
        non_negative(&format!("{key}.height"), height)?;
    }
    Ok(())
}
