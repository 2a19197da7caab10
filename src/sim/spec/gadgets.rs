//! The gadget and actor tables of `[world]` (§4.5.1, §4.5.2, §4.7, §4.8): locked doors,
//! teleporters, wanderers, ground and air predators, their defaults and their validation.
//! Their running state is [`crate::sim::gadgets`].

use super::values::{Point, Region, DEFAULT_WALL_COLOUR, DEFAULT_WALL_HEIGHT};
use crate::validate::{
    all_finite, count_within, finite, non_negative, positive, InvalidValue, Valid,
};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Most wanderers, predators, air predators, doors or teleporters of one kind in a world.
pub const MAX_ACTORS: u64 = 1000;
/// Longest hold or open time in ticks (far beyond any trial).
pub const MAX_TICKS: u64 = 1_000_000_000;

/// A locked door (`[[world.doors]]`, §4.5.2): a wall segment that opens for `open_ticks` ticks
/// when an evolving creature's body touches its trigger circle. Closed, it is a wall (blocks,
/// felt, seen, occludes smell when opaque); open, it is nothing.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct DoorSpec {
    /// First end point `[x, y]` of the door segment in LU (required; inside the arena).
    #[serde(deserialize_with = "crate::sim::spec::values::exact::array")]
    pub from: Point,
    /// Second end point `[x, y]` in LU (required; inside the arena, not equal to `from`).
    #[serde(deserialize_with = "crate::sim::spec::values::exact::array")]
    pub to: Point,
    /// A closed door stops smells (default: true).
    #[serde(default = "yes")]
    pub opaque: bool,
    /// Colour `[r, g, b]` in [0, 1] for the eye (default: grey 0.5).
    #[serde(
        default = "grey",
        deserialize_with = "crate::sim::spec::values::exact::array"
    )]
    pub colour: [f64; 3],
    /// Height in LU for the eye (default: 10).
    #[serde(default = "wall_height")]
    pub height: f64,
    /// Centre `[x, y]` of the trigger circle in LU (required; inside the arena). The trigger
    /// does not block and is not seen; whiskers feel it when its radius is > 0.
    #[serde(deserialize_with = "crate::sim::spec::values::exact::array")]
    pub trigger: Point,
    /// Radius of the trigger circle in LU (default: 5; 0 = a point, touched by the body).
    #[serde(default = "five")]
    pub trigger_radius: f64,
    /// Ticks the door stays open after the last contact with the trigger (default: 100, at
    /// least 1). Contact during tick t opens it at once; it closes at the start of tick
    /// t + open_ticks + 1 unless touched again.
    #[serde(default = "hundred")]
    pub open_ticks: u64,
    /// Odour given off at the trigger's centre (§4.2: every object but walls may smell),
    /// whether the door is open or closed, smelled like a teleporter entry's (default:
    /// zeros = no smell).
    #[serde(
        default,
        skip_serializing_if = "crate::sim::spec::values::exact::is_zero",
        deserialize_with = "crate::sim::spec::values::exact::array"
    )]
    pub odour: [f64; 8],
    /// Smell intensity at the trigger (default: 0).
    #[serde(
        default,
        skip_serializing_if = "crate::sim::spec::values::exact::is_zero_scalar"
    )]
    pub intensity: f64,
    /// Smell range θ of the trigger in LU (default: absent = unlimited).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub range: Option<f64>,
}

/// A teleporter (`[[world.teleporters]]`, §4.5.1): body contact with the entry circle moves an
/// evolving creature to the exit at the end of its move, unless the body would touch a wall
/// or another body there.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct TeleporterSpec {
    /// Centre `[x, y]` of the entry circle in LU (required; inside the arena).
    #[serde(deserialize_with = "crate::sim::spec::values::exact::array")]
    pub entry: Point,
    /// Radius of the entry circle in LU (default: 5). Felt by whiskers when > 0; not seen,
    /// does not block.
    #[serde(default = "five")]
    pub radius: f64,
    /// Exit point `[x, y]` in LU (required; inside the arena): the new body centre.
    #[serde(deserialize_with = "crate::sim::spec::values::exact::array")]
    pub exit: Point,
    /// Heading after the jump in degrees, 0 = facing +x, positive clockwise on screen
    /// (default: absent = keep the heading).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub exit_heading: Option<f64>,
    /// Odour given off at the entry's centre (default: zeros).
    #[serde(default, deserialize_with = "crate::sim::spec::values::exact::array")]
    pub odour: [f64; 8],
    /// Smell intensity at the entry (default: 0).
    #[serde(default)]
    pub intensity: f64,
    /// Smell range θ in LU (default: absent = unlimited).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub range: Option<f64>,
}

/// Irrelevant creatures (`[world.wanderers]`, §4.8): bodies like the creatures' driven by
/// random motor signals held for a random number of ticks, turning away from whatever a
/// whisker touches (see [`TurnAway`](crate::sim::gadgets::TurnAway)). They block movement, smell, are felt and seen.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct WanderersSpec {
    /// How many (default: 0).
    pub count: u64,
    /// Where they start, `[x0, y0, x1, y1]` in LU (default: absent = the whole arena).
    #[serde(
        skip_serializing_if = "Option::is_none",
        deserialize_with = "crate::sim::spec::values::exact::option_array"
    )]
    pub region: Option<Region>,
    /// Largest motor signal in rotations per tick (default: 0.25).
    pub max_rpt: f64,
    /// Each random motor command is held for a number of ticks drawn uniformly from
    /// `[min, max]` (default: `[5, 30]`, min >= 1). Ticks spent turning away from a touch
    /// count towards the hold, and a held command that cannot move the wanderer (its move
    /// blocked before it travels any distance, e.g. backing into a wall) ends its hold: the
    /// next tick draws a fresh one. See docs/simulator-decisions.md.
    #[serde(deserialize_with = "exact_lists::pair")]
    pub hold_ticks: [u64; 2],
    /// Odour of their bodies (default: zeros).
    #[serde(deserialize_with = "crate::sim::spec::values::exact::array")]
    pub odour: [f64; 8],
    /// Smell intensity (default: 0).
    pub intensity: f64,
    /// Smell range θ in LU (default: absent = unlimited).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub range: Option<f64>,
    /// Body colour for the eye (default: `[0.6, 0.4, 0.8]`).
    #[serde(deserialize_with = "crate::sim::spec::values::exact::array")]
    pub colour: [f64; 3],
    /// Largest turn per tick in degrees while turning away from what a whisker touches, in
    /// (0, 180] (default: absent = 30). The turn is a spin in place, at most `max_rpt` per
    /// wheel (a spin of s RPT turns 720·s degrees), kept in one direction until neither
    /// whisker touches; see [`TurnAway`](crate::sim::gadgets::TurnAway). Where no heading
    /// frees both whiskers it drives its held command for one tick after every ⌈360 / step⌉
    /// turning ticks (step: the turn per tick), also when the step does not divide 360°
    /// (12 ticks at 30°, 15 at 25°).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub turn_degrees: Option<f64>,
}

impl Default for WanderersSpec {
    fn default() -> Self {
        WanderersSpec {
            count: 0,
            region: None,
            max_rpt: 0.25,
            hold_ticks: [5, 30],
            odour: [0.0; 8],
            intensity: 0.0,
            range: None,
            colour: [0.6, 0.4, 0.8],
            turn_degrees: None,
        }
    }
}

/// How a ground predator moves (§4.7).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Strategy {
    /// Like a wanderer (default).
    #[default]
    Wander,
    /// Steers towards the nearest living creature whose centre is outside safe areas;
    /// wanders when there is none.
    Chase,
    /// Visits `waypoints` in order, cyclically.
    Patrol,
}

/// What a predator does to a creature it attacks (§4.7).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Effect {
    /// The creature dies (default).
    #[default]
    Lethal,
    /// The creature's shock sensor turns on.
    Shock,
}

/// A ground predator (`[[world.predators]]`, §4.7): a creature body with a fixed strategy.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct PredatorSpec {
    /// `"wander"`, `"chase"` or `"patrol"` (default: `"wander"`).
    pub strategy: Strategy,
    /// Points `[x, y]` in LU visited in order by `patrol` (required for patrol, default: none).
    #[serde(deserialize_with = "exact_lists::points")]
    pub waypoints: Vec<Point>,
    /// `"lethal"` or `"shock"` (default: `"lethal"`).
    pub effect: Effect,
    /// Largest motor signal in rotations per tick: its speed (default: 0.15).
    pub max_rpt: f64,
    /// Start position `[x, y]` in LU (default: absent = a random free spot in the arena).
    #[serde(
        skip_serializing_if = "Option::is_none",
        deserialize_with = "crate::sim::spec::values::exact::option_array"
    )]
    pub start: Option<Point>,
    /// `wander` (and `chase` with no prey) holds each random command for `[min, max]`
    /// ticks, by the rules of `[world.wanderers] hold_ticks` (default: `[5, 30]`).
    #[serde(deserialize_with = "exact_lists::pair")]
    pub hold_ticks: [u64; 2],
    /// Odour of its body (default: zeros).
    #[serde(deserialize_with = "crate::sim::spec::values::exact::array")]
    pub odour: [f64; 8],
    /// Smell intensity (default: 0).
    pub intensity: f64,
    /// Smell range θ in LU (default: absent = unlimited).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub range: Option<f64>,
    /// Body colour for the eye (default: red `[0.9, 0.1, 0.1]`).
    #[serde(deserialize_with = "crate::sim::spec::values::exact::array")]
    pub colour: [f64; 3],
    /// Largest turn per tick in degrees while a wandering predator turns away from a touch,
    /// by the rules of `[world.wanderers] turn_degrees` (default: absent = 30).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub turn_degrees: Option<f64>,
    /// Ticks it sleeps where it starts at the beginning of a trial, drawn uniformly from
    /// `[min, max]` for each trial (default: `[0, 0]` = awake from the start). Asleep it
    /// neither moves, smells nor attacks (its body is still felt and seen), so that a creature
    /// cannot know when the hunt begins except by the predator's smell.
    #[serde(
        skip_serializing_if = "no_pause",
        deserialize_with = "exact_lists::pair"
    )]
    pub asleep: [u64; 2],
}

impl Default for PredatorSpec {
    fn default() -> Self {
        PredatorSpec {
            strategy: Strategy::Wander,
            waypoints: Vec::new(),
            effect: Effect::Lethal,
            max_rpt: 0.15,
            start: None,
            hold_ticks: [5, 30],
            odour: [0.0; 8],
            intensity: 0.0,
            range: None,
            colour: [0.9, 0.1, 0.1],
            turn_degrees: None,
            asleep: [0, 0],
        }
    }
}

/// Air predators (`[[world.air_predators]]`, §4.7): each entry is one predator in the air at
/// a time. It enters at a random point of a random side, flies straight towards a random
/// point of the opposite side at constant speed, ignoring walls, and attacks creatures whose
/// centre is within `strike_radius` of its ground position and outside safe areas. When it
/// leaves the arena a new one enters, at once or after a pause (`pause`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct AirPredatorSpec {
    /// Ground speed in LU per tick (default: 2).
    pub speed: f64,
    /// Attack radius around its ground position in LU (default: 10).
    pub strike_radius: f64,
    /// `"lethal"` or `"shock"` (default: `"lethal"`).
    pub effect: Effect,
    /// Odour at its ground position (default: zeros).
    #[serde(deserialize_with = "crate::sim::spec::values::exact::array")]
    pub odour: [f64; 8],
    /// Smell intensity (default: 0).
    pub intensity: f64,
    /// Smell range θ in LU (default: absent = unlimited).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub range: Option<f64>,
    /// Ticks away between two flights, drawn uniformly from `[min, max]` for each flight,
    /// the first one included (default: `[0, 0]` = the next enters as one leaves). While
    /// away it neither strikes nor smells, so that raids come at times a creature cannot
    /// know in advance and quiet spells lie between them.
    #[serde(
        skip_serializing_if = "no_pause",
        deserialize_with = "exact_lists::pair"
    )]
    pub pause: [u64; 2],
}

/// Serde's `skip_serializing_if` for `pause` and `asleep` at `[0, 0]` (their default), so
/// that files without them keep their configuration hash.
fn no_pause(pause: &[u64; 2]) -> bool {
    *pause == [0, 0]
}

impl Default for AirPredatorSpec {
    fn default() -> Self {
        AirPredatorSpec {
            speed: 2.0,
            strike_radius: 10.0,
            effect: Effect::Lethal,
            odour: [0.0; 8],
            intensity: 0.0,
            range: None,
            pause: [0, 0],
        }
    }
}

/// Lists of points and pairs of counts read exactly (the `toml` crate silently drops extra
/// array elements when it fills a Rust array, see `spec::exact`).
mod exact_lists {
    use serde::de::Error;
    use serde::{Deserialize, Deserializer};

    pub fn points<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<[f64; 2]>, D::Error> {
        Vec::<Vec<f64>>::deserialize(d)?
            .into_iter()
            .map(|p| {
                let n = p.len();
                p.try_into()
                    .map_err(|_| D::Error::invalid_length(n, &"a point [x, y]"))
            })
            .collect()
    }

    pub fn pair<'de, D: Deserializer<'de>>(d: D) -> Result<[u64; 2], D::Error> {
        let v = Vec::<u64>::deserialize(d)?;
        let n = v.len();
        v.try_into()
            .map_err(|_| D::Error::invalid_length(n, &"[min, max]"))
    }
}

fn yes() -> bool {
    true
}
fn grey() -> [f64; 3] {
    DEFAULT_WALL_COLOUR
}
fn wall_height() -> f64 {
    DEFAULT_WALL_HEIGHT
}
fn five() -> f64 {
    5.0
}
fn hundred() -> u64 {
    100
}

fn inside(key: &str, p: Point, arena: [f64; 2]) -> Valid {
    all_finite(key, &p)?;
    if p[0] < 0.0 || p[0] > arena[0] || p[1] < 0.0 || p[1] > arena[1] {
        return Err(InvalidValue::new(
            key,
            format!(
                "{p:?} lies outside the arena [0, {}] x [0, {}]",
                arena[0], arena[1]
            ),
        ));
    }
    Ok(())
}

fn smell(key: &str, odour: &[f64; 8], intensity: f64, range: Option<f64>) -> Valid {
    for (k, o) in odour.iter().enumerate() {
        non_negative(&format!("{key}.odour[{k}]"), *o)?;
    }
    non_negative(&format!("{key}.intensity"), intensity)?;
    if let Some(r) = range {
        positive(&format!("{key}.range"), r)?;
    }
    Ok(())
}

fn colour(key: &str, c: &[f64; 3]) -> Valid {
    for (k, v) in c.iter().enumerate() {
        crate::validate::within(&format!("{key}[{k}]"), *v, 0.0, 1.0)?;
    }
    Ok(())
}

fn turn(key: &str, degrees: Option<f64>) -> Valid {
    if let Some(d) = degrees {
        positive(key, d)?;
        crate::validate::within(key, d, 0.0, 180.0)?;
    }
    Ok(())
}

/// A `[min, max]` of ticks with `lowest ≤ min ≤ max ≤ MAX_TICKS`.
fn ticks_range(key: &str, t: [u64; 2], lowest: u64) -> Valid {
    count_within(&format!("{key}[0]"), t[0], lowest, MAX_TICKS, "ticks")?;
    count_within(
        &format!("{key}[1]"),
        t[1],
        t[0],
        MAX_TICKS,
        "ticks, at least min",
    )
}

/// Hold ranges of random commands: at least one tick.
fn hold(key: &str, h: [u64; 2]) -> Valid {
    ticks_range(key, h, 1)
}

/// Validates every gadget and actor table of a world with arena `arena`; keys start with
/// `world.`.
pub fn validate(
    arena: [f64; 2],
    doors: &[DoorSpec],
    teleporters: &[TeleporterSpec],
    wanderers: &WanderersSpec,
    predators: &[PredatorSpec],
    air: &[AirPredatorSpec],
) -> Valid {
    count_within("world.doors", doors.len() as u64, 0, MAX_ACTORS, "doors")?;
    for (i, d) in doors.iter().enumerate() {
        let key = format!("world.doors[{i}]");
        inside(&format!("{key}.from"), d.from, arena)?;
        inside(&format!("{key}.to"), d.to, arena)?;
        if d.from == d.to {
            return Err(InvalidValue::new(
                format!("{key}.to"),
                "a door must have a length, but `to` equals `from`",
            ));
        }
        colour(&format!("{key}.colour"), &d.colour)?;
        non_negative(&format!("{key}.height"), d.height)?;
        inside(&format!("{key}.trigger"), d.trigger, arena)?;
        non_negative(&format!("{key}.trigger_radius"), d.trigger_radius)?;
        smell(&key, &d.odour, d.intensity, d.range)?;
        count_within(
            &format!("{key}.open_ticks"),
            d.open_ticks,
            1,
            MAX_TICKS,
            "ticks",
        )?;
    }
    count_within(
        "world.teleporters",
        teleporters.len() as u64,
        0,
        MAX_ACTORS,
        "teleporters",
    )?;
    for (i, t) in teleporters.iter().enumerate() {
        let key = format!("world.teleporters[{i}]");
        inside(&format!("{key}.entry"), t.entry, arena)?;
        non_negative(&format!("{key}.radius"), t.radius)?;
        inside(&format!("{key}.exit"), t.exit, arena)?;
        if let Some(h) = t.exit_heading {
            finite(&format!("{key}.exit_heading"), h)?;
        }
        smell(&key, &t.odour, t.intensity, t.range)?;
    }
    let key = "world.wanderers";
    count_within(
        &format!("{key}.count"),
        wanderers.count,
        0,
        MAX_ACTORS,
        "wanderers",
    )?;
    if let Some(r) = wanderers.region {
        inside(&format!("{key}.region"), [r[0], r[1]], arena)?;
        inside(&format!("{key}.region"), [r[2], r[3]], arena)?;
        if r[0] > r[2] || r[1] > r[3] {
            return Err(InvalidValue::new(
                format!("{key}.region"),
                format!("must be [x0, y0, x1, y1] with x0 <= x1 and y0 <= y1, got {r:?}"),
            ));
        }
    }
    non_negative(&format!("{key}.max_rpt"), wanderers.max_rpt)?;
    hold(&format!("{key}.hold_ticks"), wanderers.hold_ticks)?;
    turn(&format!("{key}.turn_degrees"), wanderers.turn_degrees)?;
    smell(key, &wanderers.odour, wanderers.intensity, wanderers.range)?;
    colour(&format!("{key}.colour"), &wanderers.colour)?;
    count_within(
        "world.predators",
        predators.len() as u64,
        0,
        MAX_ACTORS,
        "predators",
    )?;
    for (i, p) in predators.iter().enumerate() {
        let key = format!("world.predators[{i}]");
        if p.strategy == Strategy::Patrol && p.waypoints.is_empty() {
            return Err(InvalidValue::new(
                format!("{key}.waypoints"),
                "a patrol needs at least one waypoint",
            ));
        }
        for (k, w) in p.waypoints.iter().enumerate() {
            inside(&format!("{key}.waypoints[{k}]"), *w, arena)?;
        }
        non_negative(&format!("{key}.max_rpt"), p.max_rpt)?;
        if let Some(s) = p.start {
            inside(&format!("{key}.start"), s, arena)?;
        }
        hold(&format!("{key}.hold_ticks"), p.hold_ticks)?;
        ticks_range(&format!("{key}.asleep"), p.asleep, 0)?;
        turn(&format!("{key}.turn_degrees"), p.turn_degrees)?;
        smell(&key, &p.odour, p.intensity, p.range)?;
        colour(&format!("{key}.colour"), &p.colour)?;
    }
    count_within(
        "world.air_predators",
        air.len() as u64,
        0,
        MAX_ACTORS,
        "air predators",
    )?;
    for (i, a) in air.iter().enumerate() {
        let key = format!("world.air_predators[{i}]");
        positive(&format!("{key}.speed"), a.speed)?;
        non_negative(&format!("{key}.strike_radius"), a.strike_radius)?;
        smell(&key, &a.odour, a.intensity, a.range)?;
        ticks_range(&format!("{key}.pause"), a.pause, 0)?;
    }
    Ok(())
}
