//! What the configuration types cannot say about a key: its unit, the range validation
//! enforces, the report section it implements, and (for the few keys serde leaves out of
//! files at their default) the default. One entry per key, named `Struct.field` as in the
//! derived schema; the reference tests check that every key has an entry, that no entry
//! names a key that is gone, and that each range is the one validation refuses outside of.
//! Limits are the code's own constants, so a changed limit changes the page.

use crate::brain::plasticity::MAX_MODULATORY_NEURONS;
use crate::brain::spec::{MAX_HIDDEN_LAYERS, MAX_SUBSTEPS, MAX_UNITS};
use crate::experiment::evolution::{
    DEFAULT_ARCHIVE_PROBABILITY, DEFAULT_GAUSSIAN_SIGMA, DEFAULT_ISO_SIGMA, DEFAULT_LINE_SIGMA,
    MAX_GENERATIONS, MAX_GRID_CELLS, MAX_GRID_DIMENSIONS, MAX_MAGNITUDE, MAX_NOVELTY_ARCHIVE,
    MAX_POPULATION,
};
use crate::experiment::tables::{MAX_CREATURE_TICKS_PER_GENERATION, MAX_TICKS, MAX_TRIALS};
use crate::experiment::terms::{Sign, TERMS};
use crate::experiment::MAX_GENERATION_PARAMETERS;
use crate::experiment::{Algorithm, Balance, GoalAt};
use crate::sim::controller::InputsSpec;
use crate::sim::scripted::MAX_DEMO_CREATURES;
use crate::sim::spec::{
    FoodKind, MAX_ACTORS, MAX_ARENA_SIDE, MAX_CREATURES, MAX_LANDMARKS, MAX_OBJECTS,
    MAX_RETINA_PIXELS, MAX_RETINA_SIDE, MAX_SEARCH_STEPS, MAX_TICKS as MAX_HOLD_TICKS, MAX_WALLS,
};
use serde_json::Value;

/// One end of a range.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bound {
    /// The limit.
    pub value: f64,
    /// Whether the limit itself is allowed.
    pub inclusive: bool,
}

/// The values validation accepts (for a list: each element's), plus what no bound can say.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Range {
    /// The lower end, if any.
    pub min: Option<Bound>,
    /// The upper end, if any.
    pub max: Option<Bound>,
    /// A constraint beyond the bounds ("at most the population"), or "".
    pub note: String,
}

impl Range {
    /// No bound (a number must still be finite).
    pub fn any() -> Range {
        Range::default()
    }
    /// At least `x`.
    pub fn ge(x: f64) -> Range {
        Range {
            min: Some(Bound {
                value: x,
                inclusive: true,
            }),
            ..Range::default()
        }
    }
    /// Greater than `x`.
    pub fn gt(x: f64) -> Range {
        Range {
            min: Some(Bound {
                value: x,
                inclusive: false,
            }),
            ..Range::default()
        }
    }
    /// From `a` to `b`, both included.
    pub fn between(a: f64, b: f64) -> Range {
        Range::ge(a).le(b)
    }
    /// And at most `x`.
    pub fn le(mut self, x: f64) -> Range {
        self.max = Some(Bound {
            value: x,
            inclusive: true,
        });
        self
    }
    /// And below `x`.
    pub fn lt(mut self, x: f64) -> Range {
        self.max = Some(Bound {
            value: x,
            inclusive: false,
        });
        self
    }
    /// And a constraint no bound can say.
    pub fn note(mut self, note: impl Into<String>) -> Range {
        self.note = note.into();
        self
    }
}

/// The metadata of one key.
#[derive(Debug, Clone)]
pub struct KeyMeta {
    /// `Struct.field`, as the derived schema names it.
    pub key: &'static str,
    /// The unit ("LU", "ticks", "degrees"), or "" for a plain count, flag or word.
    pub unit: &'static str,
    /// The values validation accepts.
    pub range: Range,
    /// The BERRY III report section (or SPEC-NOTES decision) the key implements.
    pub section: &'static str,
    /// The default of a key that serde leaves out of files at its default (so the schema
    /// cannot show it), taken from the code's `Default`.
    pub default: Option<Value>,
}

/// The controller: the report leaves networks out (§1).
const NET: &str = "— (controller; not in the report, §1)";
/// The genetic algorithm: the report leaves evolution out (§1).
const GA: &str = "— (evolution; not in the report, §1)";
/// How individuals are evaluated and scored (§5.3 leaves fitness open; SPEC-NOTES).
const EVAL: &str = "§5.3 (fitness left open; SPEC-NOTES)";
/// The platform's own settings.
const RUN: &str = "— (platform)";

fn k(key: &'static str, unit: &'static str, range: Range, section: &'static str) -> KeyMeta {
    KeyMeta {
        key,
        unit,
        range,
        section,
        default: None,
    }
}

/// A key whose default serde leaves out of files.
fn kd(
    key: &'static str,
    unit: &'static str,
    range: Range,
    section: &'static str,
    default: impl serde::Serialize,
) -> KeyMeta {
    KeyMeta {
        default: Some(serde_json::to_value(default).expect("a default is plain data")),
        ..k(key, unit, range, section)
    }
}

/// Every key's metadata. Tables and lists of tables have entries too (their range is on
/// how many entries they hold, where validation limits it).
pub fn keys() -> Vec<KeyMeta> {
    let any = Range::any;
    let ge0 = || Range::ge(0.0);
    let gt0 = || Range::gt(0.0);
    let unit01 = || Range::between(0.0, 1.0);
    let odour = || Range::ge(0.0);
    let food = FoodKind::default();
    let inputs = InputsSpec::default();
    vec![
        // The top level.
        k("ExperimentConfig.name", "", any().note("letters, digits, '-', '_' and '.'; not only dots; at most 100 characters"), RUN),
        k("ExperimentConfig.seed", "", ge0().note("below 2^63"), RUN),
        k("ExperimentConfig.world", "", any(), "§3, §4"),
        k("ExperimentConfig.creature", "", any(), "§5"),
        k("ExperimentConfig.brain", "", any(), NET),
        k("ExperimentConfig.evolution", "", any(), GA),
        k("ExperimentConfig.evaluation", "", any(), EVAL),
        k("ExperimentConfig.fitness", "", any(), EVAL),
        k("ExperimentConfig.behaviour", "", any(), RUN),
        k("ExperimentConfig.validation", "", any(), GA),
        k("ExperimentConfig.output", "", any(), RUN),
        k("ExperimentConfig.demo", "", any(), RUN),
        // [world]
        k("WorldSpec.arena", "LU", gt0().le(MAX_ARENA_SIDE).note("each side at least the creature's diameter"), "§3"),
        k("WorldSpec.boundary_walls", "", any(), "§3"),
        k("WorldSpec.slippery_walls", "", any(), "§8.1"),
        k("WorldSpec.wall_shock", "", any(), "§5.2"),
        k("WorldSpec.smell_c", "1/LU²", ge0(), "§7.2 (eq. 25)"),
        k("WorldSpec.search_steps", "", Range::between(1.0, MAX_SEARCH_STEPS as f64), "§8.2"),
        k("WorldSpec.walls", "", any().note(format!("at most {MAX_WALLS} walls, boundary included")), "§4.1"),
        k("WorldSpec.kinds", "", any(), "§4.3, §4.4"),
        k("WorldSpec.objects", "", any().note(format!("at most {MAX_OBJECTS} objects, placed ones included")), "§4.3, §4.4"),
        k("WorldSpec.place", "", any(), "§2, §4.3"),
        k("WorldSpec.start", "", any(), "§2, §5.1"),
        k("WorldSpec.landmarks", "", any().note(format!("at most {MAX_LANDMARKS}")), "§4.5.3"),
        k("WorldSpec.areas", "", any().note(format!("at most {MAX_LANDMARKS}")), "§4.6"),
        k("WorldSpec.doors", "", any().note(format!("at most {MAX_ACTORS}")), "§4.5.2"),
        k("WorldSpec.teleporters", "", any().note(format!("at most {MAX_ACTORS}")), "§4.5.1"),
        k("WorldSpec.wanderers", "", any(), "§4.8"),
        k("WorldSpec.predators", "", any().note(format!("at most {MAX_ACTORS}")), "§4.7"),
        k("WorldSpec.air_predators", "", any().note(format!("at most {MAX_ACTORS}")), "§4.7"),
        // [[world.walls]]
        k("WallSpec.from", "LU", any().note("inside the arena"), "§4.1"),
        k("WallSpec.to", "LU", any().note("inside the arena, not equal to `from`"), "§4.1"),
        k("WallSpec.opaque", "", any(), "§4.1, §7.2"),
        k("WallSpec.colour", "", unit01(), "§7.4"),
        k("WallSpec.height", "LU", ge0(), "§4.1, §7.4"),
        // [world.kinds.<name>]
        k("KindSpec.class", "", any(), "§4.3, §4.4"),
        k("KindSpec.radius", "LU", ge0(), "§4.3, §4.4"),
        kd("KindSpec.substance", "", ge0(), "§4.3, §5.3", food.substance),
        k("KindSpec.capacity", "", ge0().note("at least `substance`, type by type"), "§4.3"),
        kd("KindSpec.bite", "", ge0(), "§4.3, §5.3", food.bite),
        kd("KindSpec.regen", "per tick", ge0(), "§4.3", food.regen),
        kd("KindSpec.depletes", "", any(), "§4.3", food.depletes),
        kd("KindSpec.smell_follows_amount", "", any().note("needs a capacity with a positive total"), "§4.3, §7.2", food.smell_follows_amount),
        kd("KindSpec.odour", "", odour(), "§4.2, §7.1", food.odour),
        k("KindSpec.intensity", "", ge0(), "§7.2 (eq. 25)"),
        k("KindSpec.range", "LU", gt0(), "§7.2 (eq. 26)"),
        k("KindSpec.colour", "", unit01(), "§7.4"),
        k("KindSpec.height", "LU", ge0(), "§7.4"),
        // [[world.objects]], [[world.place]], [world.start]
        k("ObjectSpec.kind", "", any().note("a name in [world.kinds]"), "§4.3, §4.4"),
        k("ObjectSpec.position", "LU", any().note("inside the arena"), "§2"),
        k("PlaceSpec.kind", "", any().note("a name in [world.kinds]"), "§4.3, §4.4"),
        k("PlaceSpec.count", "", Range::between(0.0, MAX_OBJECTS as f64).note(format!("all objects of the world together at most {MAX_OBJECTS}")), "§4.3"),
        k("PlaceSpec.region", "LU", any().note("[x0, y0, x1, y1] inside the arena, x0 ≤ x1, y0 ≤ y1"), "§2"),
        k("PlaceSpec.min_spacing", "LU", ge0(), "§2"),
        k("PlaceSpec.grid", "LU", Range::ge(crate::sim::spec::MIN_GRID_PITCH).note("a grid point must lie in the region"), "§2"),
        k("StartSpec.region", "LU", any().note("[x0, y0, x1, y1] inside the arena, x0 ≤ x1, y0 ≤ y1"), "§2, §5.1"),
        k("StartSpec.heading", "degrees", any(), "§3 (frame, SPEC-NOTES)"),
        k("StartSpec.grid", "LU", Range::ge(crate::sim::spec::MIN_GRID_PITCH).note("a grid point must lie in the region"), "§2"),
        // [[world.landmarks]], [[world.areas]]
        k("LandmarkSpec.position", "LU", any().note("may lie outside the arena"), "§4.5.3"),
        kd("LandmarkSpec.odour", "", odour(), "§4.2", [0.0; 8]),
        kd("LandmarkSpec.intensity", "", ge0(), "§7.2 (eq. 25)", 0.0),
        k("LandmarkSpec.range", "LU", gt0(), "§7.2 (eq. 26)"),
        k("AreaSpec.name", "", any().note("names differ from one another"), "§4.6"),
        k("AreaSpec.region", "LU", any().note("[x0, y0, x1, y1] inside the arena, x0 ≤ x1, y0 ≤ y1"), "§4.6"),
        k("AreaSpec.kind", "", any(), "§4.6, §4.7"),
        k("AreaSpec.odour", "", odour(), "§4.2, §4.6"),
        k("AreaSpec.intensity", "", ge0(), "§7.2 (eq. 25)"),
        k("AreaSpec.range", "LU", gt0(), "§7.2 (eq. 26)"),
        // [[world.doors]], [[world.teleporters]]
        k("DoorSpec.from", "LU", any().note("inside the arena"), "§4.5.2"),
        k("DoorSpec.to", "LU", any().note("inside the arena, not equal to `from`"), "§4.5.2"),
        k("DoorSpec.opaque", "", any(), "§4.5.2, §7.2"),
        k("DoorSpec.colour", "", unit01(), "§7.4"),
        k("DoorSpec.height", "LU", ge0(), "§7.4"),
        k("DoorSpec.trigger", "LU", any().note("inside the arena"), "§4.5.2"),
        k("DoorSpec.trigger_radius", "LU", ge0(), "§4.5.2"),
        k("DoorSpec.open_ticks", "ticks", Range::between(1.0, MAX_HOLD_TICKS as f64), "§4.5.2"),
        kd("DoorSpec.odour", "", odour(), "§4.2", [0.0; 8]),
        kd("DoorSpec.intensity", "", ge0(), "§7.2 (eq. 25)", 0.0),
        k("DoorSpec.range", "LU", gt0(), "§7.2 (eq. 26)"),
        k("TeleporterSpec.entry", "LU", any().note("inside the arena"), "§4.5.1"),
        k("TeleporterSpec.radius", "LU", ge0(), "§4.5.1"),
        k("TeleporterSpec.exit", "LU", any().note("inside the arena"), "§4.5.1"),
        k("TeleporterSpec.exit_heading", "degrees", any(), "§4.5.1"),
        k("TeleporterSpec.odour", "", odour(), "§4.2"),
        k("TeleporterSpec.intensity", "", ge0(), "§7.2 (eq. 25)"),
        k("TeleporterSpec.range", "LU", gt0(), "§7.2 (eq. 26)"),
        // [world.wanderers], [[world.predators]], [[world.air_predators]]
        k("WanderersSpec.count", "", Range::between(0.0, MAX_ACTORS as f64), "§4.8"),
        k("WanderersSpec.region", "LU", any().note("[x0, y0, x1, y1] inside the arena, x0 ≤ x1, y0 ≤ y1"), "§4.8"),
        k("WanderersSpec.max_rpt", "RPT", ge0(), "§4.8, §8.1"),
        k("WanderersSpec.hold_ticks", "ticks", Range::between(1.0, MAX_HOLD_TICKS as f64).note("min ≤ max"), "§4.8"),
        k("WanderersSpec.odour", "", odour(), "§4.2, §5.1"),
        k("WanderersSpec.intensity", "", ge0(), "§7.2 (eq. 25)"),
        k("WanderersSpec.range", "LU", gt0(), "§7.2 (eq. 26)"),
        k("WanderersSpec.colour", "", unit01(), "§7.4"),
        k("WanderersSpec.turn_degrees", "degrees", Range::gt(0.0).le(180.0), "§4.8 (SPEC-NOTES)"),
        k("PredatorSpec.strategy", "", any(), "§4.7"),
        k("PredatorSpec.waypoints", "LU", any().note("inside the arena; at least one for patrol"), "§4.7"),
        k("PredatorSpec.effect", "", any(), "§4.7"),
        k("PredatorSpec.max_rpt", "RPT", ge0(), "§4.7, §8.1"),
        k("PredatorSpec.start", "LU", any().note("inside the arena"), "§4.7"),
        k("PredatorSpec.hold_ticks", "ticks", Range::between(1.0, MAX_HOLD_TICKS as f64).note("min ≤ max"), "§4.7"),
        k("PredatorSpec.odour", "", odour(), "§4.2"),
        k("PredatorSpec.intensity", "", ge0(), "§7.2 (eq. 25)"),
        k("PredatorSpec.range", "LU", gt0(), "§7.2 (eq. 26)"),
        k("PredatorSpec.colour", "", unit01(), "§7.4"),
        k("PredatorSpec.turn_degrees", "degrees", Range::gt(0.0).le(180.0), "§4.7 (SPEC-NOTES)"),
        kd("PredatorSpec.asleep", "ticks", Range::between(0.0, MAX_HOLD_TICKS as f64).note("min ≤ max"), "§4.7", [0u64, 0]),
        k("AirPredatorSpec.speed", "LU per tick", gt0(), "§4.7"),
        k("AirPredatorSpec.strike_radius", "LU", ge0(), "§4.7"),
        k("AirPredatorSpec.effect", "", any(), "§4.7"),
        k("AirPredatorSpec.odour", "", odour(), "§4.2"),
        k("AirPredatorSpec.intensity", "", ge0(), "§7.2 (eq. 25)"),
        k("AirPredatorSpec.range", "LU", gt0(), "§7.2 (eq. 26)"),
        kd("AirPredatorSpec.pause", "ticks", Range::between(0.0, MAX_HOLD_TICKS as f64).note("min ≤ max"), "§4.7", [0u64, 0]),
        // [creature]
        k("CreatureSpec.diameter", "LU", gt0(), "§5.1"),
        k("CreatureSpec.whisker_angle", "degrees", Range::between(0.0, 180.0), "§5.1, §7.3"),
        k("CreatureSpec.whisker_length", "LU", ge0(), "§5.1, §7.3"),
        k("CreatureSpec.a", "LU", ge0(), "§5.1"),
        k("CreatureSpec.wheel", "LU", gt0(), "§5.1, §8.1"),
        k("CreatureSpec.odour", "", odour(), "§5.1, §4.2"),
        k("CreatureSpec.odour_intensity", "", ge0(), "§5.1, §7.2"),
        kd("CreatureSpec.odours", "", odour().note(format!("at most {MAX_CREATURES} odours")), "§5.1", Vec::<[f64; 8]>::new()),
        k("CreatureSpec.max_rpt", "RPT", ge0(), "§8.1"),
        k("CreatureSpec.eating", "", any(), "§5.2 (SPEC-NOTES)"),
        k("CreatureSpec.inhibit_smell_on_whisker", "", any(), "§7.3"),
        k("CreatureSpec.initial_metabolism", "", ge0(), "§5.3"),
        kd("CreatureSpec.initial_metabolism_spread", "", ge0(), "§5.3", [0.0; 4]),
        k("CreatureSpec.decay_per_tick", "per tick", ge0(), "§5.3"),
        k("CreatureSpec.decay_per_lu", "per LU", ge0(), "§5.3"),
        k("CreatureSpec.inputs", "", any(), "§7"),
        k("CreatureSpec.colour", "", unit01(), "§7.4"),
        k("CreatureSpec.height", "LU", ge0(), "§7.4"),
        k("CreatureSpec.eye", "", any(), "§7.4"),
        k("CreatureSpec.noise", "", any(), "§7.5"),
        // [creature.inputs]
        k("InputsSpec.smell", "", any(), "§7.1"),
        k("InputsSpec.whiskers", "", any(), "§7.3"),
        k("InputsSpec.food", "", any(), "§5.2"),
        k("InputsSpec.shock", "", any(), "§5.2"),
        k("InputsSpec.metabolism", "", any(), "§5.3"),
        k("InputsSpec.bias", "", any(), NET),
        kd("InputsSpec.landmarks", "", any().note("needs [[world.landmarks]]"), "§4.5.3", inputs.landmarks),
        kd("InputsSpec.areas", "", any().note("needs [[world.areas]]"), "§4.6", inputs.areas),
        kd("InputsSpec.eye", "", any(), "§7.4", inputs.eye),
        // [creature.eye]
        k("EyeSpec.fov", "degrees", Range::gt(0.0).le(360.0), "§7.4"),
        k("EyeSpec.vertical_fov", "degrees", Range::gt(0.0).lt(180.0), "§7.4"),
        k("EyeSpec.width", "pixels", Range::between(1.0, MAX_RETINA_SIDE as f64).note(format!("width × height at most {MAX_RETINA_PIXELS}")), "§7.4"),
        k("EyeSpec.height", "pixels", Range::between(1.0, MAX_RETINA_SIDE as f64).note(format!("width × height at most {MAX_RETINA_PIXELS}")), "§7.4"),
        k("EyeSpec.eye_height", "LU", ge0(), "§7.4"),
        k("EyeSpec.background", "", unit01(), "§7.4"),
        k("EyeSpec.range", "LU", gt0(), "§7.4"),
        // [creature.noise.<group>]
        k("NoiseSpec.smell", "", any(), "§7.5"),
        k("NoiseSpec.whiskers", "", any(), "§7.5"),
        k("NoiseSpec.food", "", any(), "§7.5"),
        k("NoiseSpec.shock", "", any(), "§7.5"),
        k("NoiseSpec.metabolism", "", any(), "§7.5"),
        k("NoiseSpec.landmarks", "", any(), "§7.5"),
        k("NoiseSpec.areas", "", any(), "§7.5"),
        k("NoiseSpec.eye", "", any(), "§7.5"),
        k("NoiseChannel.n", "", ge0(), "§7.5 (eq. 27)"),
        k("NoiseChannel.n_sigma", "", ge0(), "§7.5 (eq. 27)"),
        k("NoiseChannel.m", "", unit01(), "§7.5 (eq. 27)"),
        k("NoiseChannel.m_sigma", "", ge0(), "§7.5 (eq. 27)"),
        // [brain]
        k("BrainSpec.kind", "", any(), NET),
        k("BrainSpec.hidden", "units", Range::between(1.0, MAX_UNITS as f64).note(format!("mlp: at most {MAX_HIDDEN_LAYERS} layers; recurrent: exactly one")), NET),
        k("BrainSpec.activation", "", any(), NET),
        k("BrainSpec.precision", "", any(), NET),
        k("BrainSpec.neurons", "", Range::between(1.0, MAX_UNITS as f64).note("at least the number of motor outputs"), NET),
        k("BrainSpec.step", "CTRNN time units", gt0().note("at most tau[0]"), NET),
        k("BrainSpec.substeps", "", Range::between(1.0, MAX_SUBSTEPS as f64), NET),
        k("BrainSpec.tau", "CTRNN time units", gt0().note("min ≤ max"), NET),
        k("BrainSpec.gain", "", ge0().note("min ≤ max"), NET),
        k("BrainSpec.plasticity", "", any().note("mlp with precision = \"f64\" only"), NET),
        k("BrainSpec.granularity", "", any(), NET),
        k("BrainSpec.weight_bounds", "", any().note("min < max"), NET),
        k("BrainSpec.initial_weights", "", any(), NET),
        k("BrainSpec.modulators", "", any().note("neuromodulated only; each needs its sensor in [creature.inputs]"), NET),
        k("BrainSpec.modulatory_neurons", "", Range::between(1.0, MAX_MODULATORY_NEURONS as f64).note("with \"neurons\" in modulators"), NET),
        // [evolution]
        kd("EvolutionSpec.algorithm", "", any(), GA, Algorithm::default()),
        k("EvolutionSpec.population", "individuals", Range::between(2.0, MAX_POPULATION as f64).note(format!("even for pgpe; population × brain parameters at most {MAX_GENERATION_PARAMETERS}")), GA),
        k("EvolutionSpec.generations", "", Range::between(1.0, MAX_GENERATIONS as f64), GA),
        k("EvolutionSpec.elitism", "individuals", ge0().note("at most the population"), GA),
        k("EvolutionSpec.init_range", "parameter units", Range::between(0.0, MAX_MAGNITUDE), GA),
        k("EvolutionSpec.selection", "", any(), GA),
        k("EvolutionSpec.crossover", "", any(), GA),
        k("EvolutionSpec.mutation", "", any(), GA),
        k("EvolutionSpec.pgpe", "", any().note("only with algorithm = \"pgpe\""), GA),
        kd("EvolutionSpec.draw_order", "", Range::between(1.0, 2.0).note("1 or 2"), GA, 1u32),
        k("SelectionSpec.kind", "", any(), GA),
        k("SelectionSpec.tournament_size", "individuals", Range::ge(1.0).note("at most the population"), GA),
        k("SelectionSpec.truncation_fraction", "", Range::gt(0.0).le(1.0), GA),
        k("SelectionSpec.rank_pressure", "", Range::between(1.0, 2.0), GA),
        k("CrossoverSpec.kind", "", any(), GA),
        k("CrossoverSpec.probability", "", unit01(), GA),
        k("MutationSpec.probability", "", unit01(), GA),
        k("MutationSpec.sigma", "parameter units", Range::between(0.0, MAX_MAGNITUDE), GA),
        k("MutationSpec.self_adaptive", "", any(), GA),
        k("MutationSpec.tau", "", ge0(), GA),
        k("MutationSpec.min_sigma", "parameter units", ge0().note("at most sigma"), GA),
        k("EvolutionSpec.cma_es", "", any().note("only with algorithm = \"sep-cma-es\" or \"cma-es\""), GA),
        k("EvolutionSpec.novelty", "", any().note("only with algorithm = \"novelty\""), GA),
        k("NoveltySpec.descriptors", "", any().note("at least one; each a [behaviour] measure or the time in a named area, at most once"), GA),
        k("NoveltySpec.k", "individuals", Range::ge(1.0).note("at most population − 1 + archive_size"), GA),
        k("NoveltySpec.archive_threshold", "scaled descriptor units", ge0().note("not with archive_probability"), GA),
        kd("NoveltySpec.archive_probability", "", unit01(), GA, DEFAULT_ARCHIVE_PROBABILITY),
        k("NoveltySpec.archive_size", "entries", Range::between(0.0, MAX_NOVELTY_ARCHIVE as f64), GA),
        k("NoveltySpec.fitness_weight", "", unit01(), GA),
        k("EvolutionSpec.map_elites", "", any().note("only with algorithm = \"map-elites\""), GA),
        k("MapElitesSpec.descriptors", "", any().note(format!("1 to {MAX_GRID_DIMENSIONS}; each a [behaviour] measure or the time in a named area, at most once; at most {MAX_GRID_CELLS} cells")), GA),
        k("MapElitesSpec.initial_random", "elites", Range::ge(1.0).note("at most the grid's cells"), GA),
        k("MapElitesSpec.emitter", "", any(), GA),
        kd("MapElitesSpec.sigma", "parameter units", Range::between(0.0, MAX_MAGNITUDE).note("only with emitter = \"gaussian\""), GA, DEFAULT_GAUSSIAN_SIGMA),
        kd("MapElitesSpec.iso_sigma", "parameter units", Range::between(0.0, MAX_MAGNITUDE).note("only with emitter = \"iso-line\""), GA, DEFAULT_ISO_SIGMA),
        kd("MapElitesSpec.line_sigma", "", Range::between(0.0, MAX_MAGNITUDE).note("only with emitter = \"iso-line\""), GA, DEFAULT_LINE_SIGMA),
        k("MapElitesSpec.qd_offset", "fitness units", any(), GA),
        k("GridDescriptorSpec.measure", "", any().note("one of [behaviour] measures, but with `area`"), GA),
        k("GridDescriptorSpec.min", "the measure's unit", any().note("below max"), GA),
        k("GridDescriptorSpec.max", "the measure's unit", any().note("above min"), GA),
        k("GridDescriptorSpec.bins", "cells", Range::ge(1.0), GA),
        k("GridDescriptorSpec.area", "", any().note("a name in [[world.areas]]; time_in_area only; at most 3"), GA),
        k("DescriptorSpec.measure", "", any().note("one of [behaviour] measures, but with `area`"), GA),
        k("DescriptorSpec.min", "the measure's unit", any().note("below max"), GA),
        k("DescriptorSpec.max", "the measure's unit", any().note("above min"), GA),
        k("DescriptorSpec.area", "", any().note("a name in [[world.areas]]; time_in_area only; at most 3"), GA),
        k("CmaEsSpec.sigma_init", "parameter units", Range::gt(0.0).le(MAX_MAGNITUDE), GA),
        k("PgpeSpec.center_learning_rate", "parameter units", Range::gt(0.0).le(MAX_MAGNITUDE), GA),
        k("PgpeSpec.max_speed", "parameter units", Range::gt(0.0).le(MAX_MAGNITUDE), GA),
        k("PgpeSpec.momentum", "", Range::ge(0.0).lt(1.0), GA),
        k("PgpeSpec.stdev_init", "parameter units", Range::gt(0.0).le(MAX_MAGNITUDE), GA),
        k("PgpeSpec.stdev_learning_rate", "", Range::between(0.0, MAX_MAGNITUDE), GA),
        k("PgpeSpec.stdev_max_change", "", Range::ge(0.0).lt(1.0), GA),
        // [evaluation]
        k("EvaluationSpec.trials", "trials", Range::between(1.0, MAX_TRIALS as f64), EVAL),
        k("EvaluationSpec.ticks", "ticks", Range::between(1.0, MAX_TICKS as f64).note(format!("population × trials × episodes × ticks at most {MAX_CREATURE_TICKS_PER_GENERATION} a generation")), "§2 (time), §9"),
        k("EvaluationSpec.aggregate", "", any(), EVAL),
        k("EvaluationSpec.common_random_numbers", "", any(), EVAL),
        k("EvaluationSpec.group_size", "creatures", Range::between(1.0, 1000.0).note("divides the population"), "§5.1 (other creatures)"),
        kd("EvaluationSpec.episodes_per_life", "episodes", Range::between(1.0, MAX_TRIALS as f64).note("above 1 only with group_size = 1"), EVAL, 1u64),
        k("EvaluationSpec.switch", "", any(), EVAL),
        k("SwitchSpec.kinds", "", any().note("two distinct food kinds of [world.kinds]"), EVAL),
        k("SwitchSpec.start", "", any(), EVAL),
        k("SwitchSpec.at", "episodes", any().note("each [lo, hi] within 2..=episodes_per_life, in order, without overlap"), EVAL),
        // [fitness]
        k("FitnessSpec.weights", "", any(), EVAL),
        k("FitnessSpec.mode", "", any(), EVAL),
        k("FitnessSpec.shock_penalty", "per tick", ge0(), EVAL),
        kd("FitnessSpec.balance", "", any(), EVAL, Balance::default()),
        kd("FitnessSpec.imbalance_penalty", "", ge0(), EVAL, 0.0),
        k("FitnessSpec.area", "", any().note("a name in [[world.areas]]"), "§4.6"),
        k("FitnessSpec.goal", "", any().note("a name in [[world.areas]]; not with goal_point"), "§4.6"),
        k("FitnessSpec.goal_point", "LU", any(), EVAL),
        k("FitnessSpec.goal_range", "LU", gt0(), EVAL),
        kd("FitnessSpec.goal_at", "", any(), EVAL, GoalAt::default()),
        // [behaviour], [validation], [output], [demo]
        k("BehaviourSpec.measures", "", any().note("each at most once; area measures need `area`"), RUN),
        k("BehaviourSpec.area", "", any().note("a name in [[world.areas]]"), "§4.6"),
        k("BehaviourSpec.threat_radius", "LU", gt0(), "§4.7"),
        k("ValidationSpec.every", "generations", Range::between(0.0, u32::MAX as f64), GA),
        k("ValidationSpec.top", "individuals", Range::between(1.0, 10_000.0), GA),
        k("ValidationSpec.trials", "trials", Range::between(1.0, MAX_TRIALS as f64), GA),
        k("OutputSpec.checkpoint_every", "generations", Range::between(1.0, u32::MAX as f64), RUN),
        k("OutputSpec.keep_checkpoints", "files", Range::between(1.0, 1000.0), RUN),
        k("OutputSpec.baseline", "", any().note("a genome file, relative to the experiment file's folder"), RUN),
        k("DemoSpec.creatures", "creatures", Range::between(1.0, MAX_DEMO_CREATURES as f64).note("checked by `simulate`"), RUN),
        k("DemoSpec.controller", "", any(), RUN),
        k("ScriptedSpec.kind", "", any(), RUN),
        k("ScriptedSpec.left", "RPT", any(), "§8.1"),
        k("ScriptedSpec.right", "RPT", any(), "§8.1"),
        k("ScriptedSpec.receptor", "", Range::between(1.0, 8.0), "§7.1"),
        k("ScriptedSpec.gain", "RPT", any(), "§8.1"),
        k("ScriptedSpec.base", "RPT", any(), "§8.1"),
    ]
    .into_iter()
    .chain(TERMS.iter().map(|t| {
        let range = match t.sign {
            Sign::Add => Range::any(),
            Sign::Subtract => Range::ge(0.0),
        };
        kd(t.schema_key, t.unit, range.note(t.note), t.section, 0.0)
    }))
    .collect()
}
