//! The experiment tables that belong to evaluation rather than to the world, the brain or
//! the genetic algorithm: `[evaluation]`, `[fitness]`, `[behaviour]`, `[validation]` and
//! `[output]`.

use crate::sim::spec::{CreatureSpec, WorldSpec};
use crate::validate::{
    all_finite, count_within, finite, non_negative, positive, InvalidValue, Valid,
};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// Most trials per individual: beyond this a generation would take days.
pub const MAX_TRIALS: u64 = 10_000;
/// Most ticks per trial (a life of 10^7 ticks is about an hour of one core).
pub const MAX_TICKS: u64 = 10_000_000;
/// Most creature-ticks one generation may ask for (population × trials × ticks): about
/// a day of one core at the simulator's speed; anything above is almost surely a typo.
pub const MAX_CREATURE_TICKS_PER_GENERATION: u64 = 200_000_000_000;

/// How the trials of an individual are combined into one fitness.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Aggregate {
    /// The mean over trials.
    Mean,
    /// The worst trial: rewards controllers that never fail.
    Min,
}

/// `[evaluation]`: how an individual's fitness is measured.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct EvaluationSpec {
    /// Trial worlds per individual (default: 3).
    pub trials: u64,
    /// Ticks per trial, i.e. the length of a life (default: 500).
    pub ticks: u64,
    /// How trial scores are combined: `"mean"` or `"min"` (default: mean).
    pub aggregate: Aggregate,
    /// Common random numbers: every individual of a generation faces the same trial worlds,
    /// new worlds each generation (default: true). When false each individual gets its own.
    pub common_random_numbers: bool,
    /// Individuals that share one world (default: 1). With k > 1 the population is cut into
    /// groups of k consecutive individuals that live together; it must divide the population.
    pub group_size: u64,
    /// Episodes per life, K (default: 1). A life is K consecutive episodes, each a fresh trial
    /// world (positions, food and creatures reset; episode 1 is the world a life of one
    /// episode meets, the later ones come from their own seed streams), while the creature's
    /// brain (recurrent state, plastic weights) carries over: it is built and reset once per
    /// life, never between episodes. `ticks` is per episode; the life's score is the sum over
    /// its episodes of the episode scores under `[fitness]`, and the behaviour measures are
    /// per life (the mean over its episodes, except the switch measures `adapted_choice` and
    /// `good_bite_share`, which are taken over the life). Death or a non-finite output ends
    /// an episode; a non-finite output also ends the life. Only with `group_size = 1`.
    #[serde(skip_serializing_if = "is_one")]
    pub episodes_per_life: u64,
    /// `[evaluation.switch]`: what changes between the episodes of a life (default: absent,
    /// nothing changes).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub switch: Option<SwitchSpec>,
}

fn is_one(x: &u64) -> bool {
    *x == 1
}

/// Whether a life's payoffs start as written or are drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum SwitchStart {
    /// Each kind pays as `[world.kinds]` writes it in episode 1 (default).
    #[default]
    AsWritten,
    /// Per life, 50:50 from the life's seed stream, the payoffs start exchanged.
    Random,
}

/// `[evaluation.switch]`: the payoffs of two object kinds are exchanged at switches during a
/// life, while their look (odour, intensity, range, colour, height, radius, positions)
/// stays, so that which kind pays must be learnt, and learnt again after each switch.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SwitchSpec {
    /// Two distinct food kinds of `[world.kinds]`, e.g. `["left_goal", "right_goal"]`, whose
    /// payoffs (substance, capacity, bite, regen, depletes) are exchanged at each switch. The
    /// kind whose substance has the larger fitness-weighted value (`[fitness] weights`) pays.
    pub kinds: Vec<String>,
    /// `"as_written"` or `"random"` (default: as_written): see [`SwitchStart`].
    #[serde(default)]
    pub start: SwitchStart,
    /// One `[lo, hi]` pair per switch: the switch comes before an episode drawn uniformly
    /// in lo..=hi (episodes numbered from 1; lo = hi: always that episode), per life, from
    /// the life's seed stream. Ranges lie within 2..=episodes_per_life, in order, without
    /// overlap (default: none).
    #[serde(default)]
    pub at: Vec<[u64; 2]>,
}

impl SwitchSpec {
    /// Checks the table against the world's kinds and the life's `episodes` (K).
    pub fn validate(&self, world: &WorldSpec, fitness_weights: &[f64; 4], episodes: u64) -> Valid {
        if episodes < 2 {
            return Err(InvalidValue::new(
                "evaluation.switch",
                "needs evaluation.episodes_per_life of at least 2 (a switch happens between \
                 episodes); set episodes_per_life or remove [evaluation.switch]",
            ));
        }
        let key = "evaluation.switch.kinds";
        if self.kinds.len() != 2 || self.kinds[0] == self.kinds[1] {
            return Err(InvalidValue::new(
                key,
                format!(
                    "must name two distinct kinds of [world.kinds], got {:?}",
                    self.kinds
                ),
            ));
        }
        let mut values = [0.0; 2];
        for (value, name) in values.iter_mut().zip(&self.kinds) {
            match world.kinds.get(name) {
                None => {
                    let names: Vec<&str> = world.kinds.keys().map(String::as_str).collect();
                    return Err(InvalidValue::new(
                        key,
                        format!(
                            "`{name}` is not a kind of [world.kinds] (kinds: {})",
                            names.join(", ")
                        ),
                    ));
                }
                Some(crate::sim::spec::KindSpec::Food(f)) => {
                    // The dot product evo's fitness takes (`evo::fitness::weighted`).
                    let (w, m) = (fitness_weights, &f.substance);
                    *value = w[0] * m[0] + w[1] * m[1] + w[2] * m[2] + w[3] * m[3];
                }
                Some(_) => {
                    return Err(InvalidValue::new(
                        key,
                        format!(
                            "`{name}` is not a food kind: only food kinds have a payoff to \
                             exchange"
                        ),
                    ));
                }
            }
        }
        if values[0] == values[1] {
            return Err(InvalidValue::new(
                key,
                format!(
                    "the two kinds' substances have the same fitness-weighted value ({}): one \
                     must pay more than the other",
                    values[0]
                ),
            ));
        }
        let mut after = 1;
        for (i, &[lo, hi]) in self.at.iter().enumerate() {
            let what = if lo > hi {
                Some(format!("lo {lo} > hi {hi}"))
            } else if lo < 2 || hi > episodes {
                Some(format!(
                    "lies outside 2..={episodes} (a switch comes before one of the episodes \
                     2..=episodes_per_life)"
                ))
            } else if lo <= after {
                Some(
                    "overlaps or comes before the previous range: give the ranges in order, \
                      without overlap"
                        .to_string(),
                )
            } else {
                None
            };
            if let Some(what) = what {
                return Err(InvalidValue::new(
                    "evaluation.switch.at",
                    format!("range {} ([{lo}, {hi}]): {what}", i + 1),
                ));
            }
            after = hi;
        }
        Ok(())
    }
}

impl Default for EvaluationSpec {
    fn default() -> Self {
        EvaluationSpec {
            trials: 3,
            ticks: 500,
            aggregate: Aggregate::Mean,
            common_random_numbers: true,
            group_size: 1,
            episodes_per_life: 1,
            switch: None,
        }
    }
}

impl EvaluationSpec {
    /// Checks the table on its own.
    pub fn validate(&self) -> Valid {
        count_within(
            "evaluation.trials",
            self.trials,
            1,
            MAX_TRIALS,
            "trials per individual",
        )?;
        count_within(
            "evaluation.ticks",
            self.ticks,
            1,
            MAX_TICKS,
            "ticks per trial",
        )?;
        count_within(
            "evaluation.group_size",
            self.group_size,
            1,
            1_000,
            "creatures per world",
        )?;
        count_within(
            "evaluation.episodes_per_life",
            self.episodes_per_life,
            1,
            MAX_TRIALS,
            "episodes per life",
        )?;
        if self.episodes_per_life > 1 && self.group_size > 1 {
            return Err(InvalidValue::new(
                "evaluation.episodes_per_life",
                format!(
                    "lives of several episodes ({}) are for creatures alone: set \
                     evaluation.group_size = 1 (got {}) or episodes_per_life = 1",
                    self.episodes_per_life, self.group_size
                ),
            ));
        }
        Ok(())
    }

    /// Checks the constraints that involve the population size.
    pub fn validate_against_population(&self, population: usize) -> Valid {
        let population = population as u64;
        if population % self.group_size != 0 {
            return Err(InvalidValue::new(
                "evaluation.group_size",
                format!(
                    "must divide the population ({population}) so that every group is full, got {}",
                    self.group_size
                ),
            ));
        }
        let work = population
            .saturating_mul(self.trials)
            .saturating_mul(self.episodes_per_life)
            .saturating_mul(self.ticks);
        if work > MAX_CREATURE_TICKS_PER_GENERATION {
            return Err(InvalidValue::new(
                "evaluation.ticks",
                format!(
                    "population × trials × episodes × ticks = {work} creature-ticks per generation exceeds \
                     the limit of {MAX_CREATURE_TICKS_PER_GENERATION} (about a day of one core)"
                ),
            ));
        }
        Ok(())
    }
}

/// How a life's metabolic history becomes a score.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum FitnessMode {
    /// `weights · m` at the end of life.
    Final,
    /// `weights · m` summed over every tick of life (rewards eating early and keeping it).
    Integrated,
}

/// How the weighted metabolic components `wᵢ·mᵢ` become the metabolic gain of `[fitness]`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Balance {
    /// `Σᵢ wᵢ·mᵢ` (default).
    #[default]
    Sum,
    /// `minᵢ wᵢ·mᵢ` over the components with a non-zero weight: only the scarcest counts,
    /// so a balanced diet is needed (all components 0 weight: 0).
    Min,
}

/// When the distance to `[fitness] goal` is taken.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum GoalAt {
    /// Where the creature is at the end of its life (default).
    #[default]
    End,
    /// The closest it came over its life (partial credit for having been near).
    Closest,
}

fn is_zero(x: &f64) -> bool {
    *x == 0.0 && x.is_sign_positive()
}

fn is_default<T: Default + PartialEq>(x: &T) -> bool {
    *x == T::default()
}

/// `[fitness]`: the score of one trial (report §5.3 leaves it open; SPEC-NOTES).
///
/// The score of a life is
///
/// ```text
/// score = gain
///       + alive_bonus × ticks_alive
///       + area_bonus × ticks_in_area
///       + goal_bonus × max(0, 1 − d / goal_range)
///       + distinct_food_bonus × distinct_food
///       + forward_bonus × forward_distance
///       + shelter_bonus × sheltered_threat_ticks
///       + choice_bonus × correct_first_choice
///       − shock_penalty × shocked_ticks
///       − death_penalty × (1 if dead at the end, else 0)
/// ```
///
/// where `gain` is the metabolic part (`mode`, `balance`, `imbalance_penalty`). Every term
/// but `gain` is off by default, so an experiment without the new keys scores as before.
/// Ticks are counted as evo's `LifeScore` (`evo::fitness`) records them: a tick counts when
/// the creature is alive (and its brain's output finite) at its end.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct FitnessSpec {
    /// Weight of each metabolic component fA, fB, fC, fD (default: [1, 1, 1, 1]). Negative
    /// weights make a food type poisonous.
    pub weights: [f64; 4],
    /// `"final"` or `"integrated"` (default: final). Final: `gain = B(m_end)`; integrated:
    /// `gain = Σ_ticks B(m_t)`, where `B` is the balance below.
    pub mode: FitnessMode,
    /// Subtracted once per tick on which the shock sensor is on (default: 0).
    pub shock_penalty: f64,
    /// How the weighted components `wᵢ·mᵢ` combine into `B(m)`: `"sum"` (Σᵢ wᵢ·mᵢ) or `"min"`
    /// (minᵢ wᵢ·mᵢ over components with wᵢ ≠ 0) (default: sum).
    #[serde(skip_serializing_if = "is_default")]
    pub balance: Balance,
    /// Imbalance penalty p: `B(m)` becomes `B(m) − p × (maxᵢ wᵢ·mᵢ − minᵢ wᵢ·mᵢ)` over the
    /// components with wᵢ ≠ 0, applied wherever `B` is (the end of life, or every tick when
    /// integrated) (default: 0).
    #[serde(skip_serializing_if = "is_zero")]
    pub imbalance_penalty: f64,
    /// Added once per tick alive: `alive_bonus × ticks_alive`, the ticks at whose end the
    /// creature was alive (ticks are numbered from 1, as in traces: one killed in tick 58
    /// lived 57 ticks) (default: 0).
    #[serde(skip_serializing_if = "is_zero")]
    pub alive_bonus: f64,
    /// Subtracted once when the creature is dead at the end of the trial (killed by a
    /// predator) (default: 0).
    #[serde(skip_serializing_if = "is_zero")]
    pub death_penalty: f64,
    /// The `[[world.areas]]` entry (by `name`) that `area_bonus` pays for (default: none).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub area: Option<String>,
    /// Added per tick alive whose end finds the creature's centre inside `area` (bounds
    /// included): `area_bonus × ticks_in_area` (default: 0; needs `area`).
    #[serde(skip_serializing_if = "is_zero")]
    pub area_bonus: f64,
    /// A `[[world.areas]]` entry (by `name`) to end close to (default: none). The distance d
    /// is from the creature's centre to the nearest point of the rectangle (0 inside).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub goal: Option<String>,
    /// A point `[x, y]` in LU to end close to, instead of `goal` (default: none).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub goal_point: Option<[f64; 2]>,
    /// Goal shaping: adds `goal_bonus × max(0, 1 − d / goal_range)`: the full bonus at the
    /// goal, falling linearly to 0 at `goal_range` LU away (default: 0; needs `goal` or
    /// `goal_point`).
    #[serde(skip_serializing_if = "is_zero")]
    pub goal_bonus: f64,
    /// The distance in LU at which the goal bonus reaches 0 (default: absent = the arena's
    /// diagonal, so every place but the farthest corner earns some).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub goal_range: Option<f64>,
    /// `"end"` (d at the end of life) or `"closest"` (the smallest d over the life,
    /// measured at the end of each tick alive, the start included) (default: end).
    #[serde(skip_serializing_if = "is_default")]
    pub goal_at: GoalAt,
    /// Added once per distinct food object the creature took substance from at least once
    /// over its life: `distinct_food_bonus × distinct_food` (default: 0). Rewards moving on
    /// over parking on one regrowing object.
    #[serde(skip_serializing_if = "is_zero")]
    pub distinct_food_bonus: f64,
    /// Locomotion shaping in the manner of Floreano & Mondada (1994): added per LU the
    /// creature's centre moves forward, along its heading at the start of each tick alive;
    /// moving backwards or being pushed back earns nothing: `forward_bonus ×
    /// forward_distance` (default: 0). Rewards driving where the whiskers and the smell
    /// receptors point over circling backwards.
    #[serde(skip_serializing_if = "is_zero")]
    pub forward_bonus: f64,
    /// Added per tick alive at whose end a threat is near (a ground or air predator's centre
    /// within `[behaviour] threat_radius` LU of the creature's centre) and the creature's
    /// centre is inside a safe area: `shelter_bonus × sheltered_threat_ticks` (default: 0).
    /// Pays for taking shelter when a predator comes, not for sitting in a nest it never
    /// nears (report §4.6, §4.7).
    #[serde(skip_serializing_if = "is_zero")]
    pub shelter_bonus: f64,
    /// Added once per episode whose first bite of the two `[evaluation.switch]` kinds was of
    /// the kind that pays in that episode: `choice_bonus × correct_first_choice` (a life of K
    /// episodes earns it up to K times) (default: 0; needs `[evaluation.switch]`). Pays for
    /// choosing right, however late, where the metabolic gain also pays for eating early.
    #[serde(skip_serializing_if = "is_zero")]
    pub choice_bonus: f64,
}

impl Default for FitnessSpec {
    fn default() -> Self {
        FitnessSpec {
            weights: [1.0; 4],
            mode: FitnessMode::Final,
            shock_penalty: 0.0,
            balance: Balance::Sum,
            imbalance_penalty: 0.0,
            alive_bonus: 0.0,
            death_penalty: 0.0,
            area: None,
            area_bonus: 0.0,
            goal: None,
            goal_point: None,
            goal_bonus: 0.0,
            goal_range: None,
            goal_at: GoalAt::End,
            distinct_food_bonus: 0.0,
            forward_bonus: 0.0,
            shelter_bonus: 0.0,
            choice_bonus: 0.0,
        }
    }
}

impl FitnessSpec {
    /// Checks the table on its own.
    pub fn validate(&self) -> Valid {
        all_finite("fitness.weights", &self.weights)?;
        non_negative("fitness.shock_penalty", self.shock_penalty)?;
        finite("fitness.shock_penalty", self.shock_penalty)?;
        non_negative("fitness.imbalance_penalty", self.imbalance_penalty)?;
        self.validate_terms()?;
        if let Some(p) = self.goal_point {
            all_finite("fitness.goal_point", &p)?;
        }
        if let Some(r) = self.goal_range {
            positive("fitness.goal_range", r)?;
        }
        if self.area_bonus != 0.0 && self.area.is_none() {
            return Err(InvalidValue::new(
                "fitness.area_bonus",
                "is set, but `fitness.area` names no area to pay for; add `area = \"<name>\"`",
            ));
        }
        if self.goal.is_some() && self.goal_point.is_some() {
            return Err(InvalidValue::new(
                "fitness.goal_point",
                "and `fitness.goal` are both set; keep one of them",
            ));
        }
        if self.goal_bonus != 0.0 && self.goal.is_none() && self.goal_point.is_none() {
            return Err(InvalidValue::new(
                "fitness.goal_bonus",
                "is set, but there is no goal; add `goal = \"<area name>\"` or `goal_point = [x, y]`",
            ));
        }
        Ok(())
    }

    /// Checks the area names against the world's areas.
    pub fn validate_against_world(&self, world: &WorldSpec) -> Valid {
        if let Some(name) = &self.area {
            area_index(world, "fitness.area", name)?;
        }
        if let Some(name) = &self.goal {
            area_index(world, "fitness.goal", name)?;
        }
        Ok(())
    }

    /// Can anything a creature does make its score differ from another's in `world`? False
    /// only when that is certain: the world holds nothing (no object, no placement rule with
    /// a count, no predator, no wanderer, no shocking walls that the score counts), moving
    /// costs no metabolism, and no term pays for where the creature goes or how far. Then
    /// every life scores the same and selection is blind (e.g. the defaults file's empty
    /// world). Anything in the world counts as a possible change, so this never cries wolf.
    pub fn can_vary(&self, world: &WorldSpec, creature: &CreatureSpec) -> bool {
        let world_holds_something = !world.objects.is_empty()
            || world.place.iter().any(|p| p.count > 0)
            || !world.predators.is_empty()
            || !world.air_predators.is_empty()
            || world.wanderers.count > 0
            || (world.wall_shock && self.shock_penalty != 0.0);
        let moving_counts =
            creature.decay_per_lu.iter().any(|&d| d != 0.0) || self.pays_for_motion();
        world_holds_something || moving_counts
    }

    /// Is every term beyond the metabolic gain and the shock penalty off? Then a life's score
    /// needs nothing but the metabolism and the shock flag of each tick.
    pub fn is_plain(&self) -> bool {
        self.balance == Balance::Sum && self.imbalance_penalty == 0.0 && self.terms_off()
    }
}

/// The index in `[[world.areas]]` of the area named `name`; the error names `key`.
pub fn area_index(world: &WorldSpec, key: &str, name: &str) -> Result<usize, InvalidValue> {
    let mut found = world
        .areas
        .iter()
        .enumerate()
        .filter(|(_, a)| a.name.as_deref() == Some(name));
    let Some((index, _)) = found.next() else {
        let names: Vec<&str> = world
            .areas
            .iter()
            .filter_map(|a| a.name.as_deref())
            .collect();
        return Err(InvalidValue::new(
            key,
            format!(
                "no [[world.areas]] entry is named `{name}` (named areas: {}); give the area \
                 `name = \"{name}\"`",
                if names.is_empty() {
                    "none".to_string()
                } else {
                    names.join(", ")
                }
            ),
        ));
    };
    if found.next().is_some() {
        return Err(InvalidValue::new(
            key,
            format!("several [[world.areas]] entries are named `{name}`; names must differ"),
        ));
    }
    Ok(index)
}

/// A behaviour measure: a number per trial, next to fitness, that says whether the behaviour
/// an experiment is about happened (`[behaviour] measures`). Each is averaged over an
/// individual's trials.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize, JsonSchema,
)]
#[serde(rename_all = "snake_case")]
pub enum Measure {
    /// Ticks the creature was alive at the end of (and its brain's output finite): one
    /// killed in tick 58 (ticks numbered from 1, as in traces) lived 57 ticks.
    TicksAlive,
    /// Distinct food objects it took substance from at least once.
    DistinctFood,
    /// Food types A–D of which it received some substance (0–4).
    FoodTypes,
    /// 1 when its centre was inside `[behaviour] area` at the end of some tick alive (or at
    /// the start), else 0.
    AreaReached,
    /// Ticks alive at whose end its centre was inside `[behaviour] area`.
    TimeInArea,
    /// 1 when some door of the world was open at the end of some tick it was alive, else 0.
    DoorOpened,
    /// Distinct food objects lying inside `[behaviour] area` that it took substance from.
    FoodInAreaEaten,
    /// Of the ticks alive at whose end a threat was near (a ground or air predator's centre
    /// within `[behaviour] threat_radius` LU of its centre), the share it spent inside a safe
    /// area; 1 when no threat came near.
    ShelterWhileThreat,
    /// Air predator passes over it survived: a pass is a run of ticks at whose end its
    /// centre is within the air predator's strike radius; it is survived when the creature
    /// was inside a safe area at the end of every tick of the pass and lived through it
    /// (a pass still going at the end of the trial counts when so far survived).
    StrikesSurvived,
    /// Contacts with aversive objects: ticks at whose end its body touches an aversive
    /// object and did not at the end of the tick before (each contact counted once).
    AversiveContacts,
    /// Ticks on which the shock sensor was on (aversive objects, walls with `wall_shock`,
    /// shocking predators).
    ShockedTicks,
    /// Share of its ticks alive (0–1) on which it moved forward: its centre's displacement
    /// over the tick, along its heading at the tick's start, exceeded 0.01 LU
    /// ([`FORWARD_STEP`]; a creature spinning in place moves 0, one reversing a negative
    /// distance). 0 when it lived no tick.
    ForwardShare,
    /// LU its centre travelled: over its ticks alive, the sum of the straight distances from
    /// where each tick started to where it ended (a tick's curve counts as its chord).
    PathLength,
    /// x of its centre in LU (arena frame: from the left edge, to the right) at the end of
    /// its last tick alive, or at the start when it lived none: where a creature killed in a
    /// tick stood when the tick began, the end of the path `path_length` measures.
    FinalX,
    /// y of its centre in LU (arena frame: from the top edge, downwards), taken as `final_x`.
    FinalY,
    /// Substance it received, all types summed (A + B + C + D taken from food over the
    /// trial; what the metabolic vector would hold at the end without decay or spending).
    Eaten,
    /// Share of its ticks alive (0–1) on which its centre moved less than 0.05 LU
    /// ([`STILL_STEP`]) in any direction: parked, or spinning in place. 0 when it lived no
    /// tick.
    StillShare,
    /// The T-maze choice (report §4.5.1), in any world: 1 when it ate from the richest food
    /// object (the most substance when full, A + B + C + D of its capacity; the first such in
    /// the world's order) and, before its first bite of it, never strayed onto the other
    /// side of its start line (the line through its start position along its start heading)
    /// by more than half as far as that food lies on its own side; else 0. A food on the
    /// start line has no other side: eating it counts.
    RichestSideFirst,
    /// With `[evaluation.switch]`: the share of correct first choices over the episodes that
    /// are not the first of their phase (a phase starts at episode 1 and at each switch). An
    /// episode's first choice is correct when its first bite of an object of the two switch
    /// kinds is of the kind that pays now; an episode without such a bite counts as wrong.
    /// With one episode per life: 1 when that first bite is of the paying kind, else 0.
    AdaptedChoice,
    /// With `[evaluation.switch]`: of the bites of the two switch kinds after the first such
    /// bite of each phase, the share of the kind that pays now (0 without such bites). A bite
    /// is the first taking from an object in an episode (each object counts once).
    GoodBiteShare,
}

/// The smallest displacement along its heading, in LU, that makes a tick count as forward
/// motion for [`Measure::ForwardShare`]: above rounding, so spinning in place (exactly 0)
/// or a wobble never counts, and about 0.3% of the default top speed (0.25 RPT with a
/// wheel of 2 LU: 3.1 LU per tick), so any deliberate drive does.
pub const FORWARD_STEP: f64 = 0.01;

/// The largest displacement, in LU, of a tick that [`Measure::StillShare`] counts as still:
/// 1.6% of the default top speed (3.1 LU per tick), so a creature creeping along or turning
/// on one wheel moves, one parked or spinning on the spot does not.
pub const STILL_STEP: f64 = 0.05;

/// Every measure, in the order their columns and lines appear.
pub const MEASURES: [Measure; 20] = [
    Measure::TicksAlive,
    Measure::DistinctFood,
    Measure::FoodTypes,
    Measure::AreaReached,
    Measure::TimeInArea,
    Measure::DoorOpened,
    Measure::FoodInAreaEaten,
    Measure::ShelterWhileThreat,
    Measure::StrikesSurvived,
    Measure::AversiveContacts,
    Measure::ShockedTicks,
    Measure::ForwardShare,
    Measure::PathLength,
    Measure::FinalX,
    Measure::FinalY,
    Measure::Eaten,
    Measure::StillShare,
    Measure::RichestSideFirst,
    Measure::AdaptedChoice,
    Measure::GoodBiteShare,
];

impl Measure {
    /// Its name in files and columns (`distinct_food`).
    pub fn name(self) -> &'static str {
        match self {
            Measure::TicksAlive => "ticks_alive",
            Measure::DistinctFood => "distinct_food",
            Measure::FoodTypes => "food_types",
            Measure::AreaReached => "area_reached",
            Measure::TimeInArea => "time_in_area",
            Measure::DoorOpened => "door_opened",
            Measure::FoodInAreaEaten => "food_in_area_eaten",
            Measure::ShelterWhileThreat => "shelter_while_threat",
            Measure::StrikesSurvived => "strikes_survived",
            Measure::AversiveContacts => "aversive_contacts",
            Measure::ShockedTicks => "shocked_ticks",
            Measure::ForwardShare => "forward_share",
            Measure::PathLength => "path_length",
            Measure::FinalX => "final_x",
            Measure::FinalY => "final_y",
            Measure::Eaten => "eaten",
            Measure::StillShare => "still_share",
            Measure::RichestSideFirst => "richest_side_first",
            Measure::AdaptedChoice => "adapted_choice",
            Measure::GoodBiteShare => "good_bite_share",
        }
    }

    /// Its position in [`MEASURES`] (and in a trial's array of measure values).
    pub fn index(self) -> usize {
        MEASURES.iter().position(|&m| m == self).unwrap_or(0)
    }

    /// Does it follow the creature's pose tick by tick (its motion and where it ends)?
    pub fn follows_motion(self) -> bool {
        matches!(
            self,
            Measure::ForwardShare
                | Measure::PathLength
                | Measure::FinalX
                | Measure::FinalY
                | Measure::StillShare
        )
    }

    /// Does it need `[evaluation.switch]` (which kinds' payoffs are exchanged)?
    pub fn needs_switch(self) -> bool {
        matches!(self, Measure::AdaptedChoice | Measure::GoodBiteShare)
    }

    /// Does it need `[behaviour] area`?
    pub fn needs_area(self) -> bool {
        matches!(
            self,
            Measure::AreaReached | Measure::TimeInArea | Measure::FoodInAreaEaten
        )
    }
}

/// `[behaviour]`: which behaviour measures an experiment reports (in `fitness.csv`,
/// `compare`, `replay` and `summary`). Measures never change fitness or evolution.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct BehaviourSpec {
    /// The measures, by name, e.g. `["ticks_alive", "distinct_food"]` (default: none). See
    /// [`Measure`] for each one's definition.
    pub measures: Vec<Measure>,
    /// The `[[world.areas]]` entry (by `name`) of `area_reached`, `time_in_area` and
    /// `food_in_area_eaten` (default: none).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub area: Option<String>,
    /// How close in LU a predator's centre must come to the creature's centre for
    /// `shelter_while_threat` (and `[fitness] shelter_bonus`) to count the tick as threatened
    /// (default: 40).
    pub threat_radius: f64,
}

/// `[behaviour] threat_radius` when not given.
pub const DEFAULT_THREAT_RADIUS: f64 = 40.0;

impl Default for BehaviourSpec {
    fn default() -> Self {
        BehaviourSpec {
            measures: Vec::new(),
            area: None,
            threat_radius: DEFAULT_THREAT_RADIUS,
        }
    }
}

impl BehaviourSpec {
    /// No measure asked for and nothing else set: the table is left out of written files.
    pub fn is_default(&self) -> bool {
        *self == BehaviourSpec::default()
    }

    /// Checks the table against the world it measures.
    pub fn validate(&self, world: &WorldSpec) -> Valid {
        positive("behaviour.threat_radius", self.threat_radius)?;
        for (i, m) in self.measures.iter().enumerate() {
            if self.measures[..i].contains(m) {
                return Err(InvalidValue::new(
                    "behaviour.measures",
                    format!("names `{}` twice", m.name()),
                ));
            }
            if m.needs_area() && self.area.is_none() {
                return Err(InvalidValue::new(
                    "behaviour.area",
                    format!(
                        "is needed by the measure `{}`; add `area = \"<name of a [[world.areas]] entry>\"`",
                        m.name()
                    ),
                ));
            }
        }
        if let Some(name) = &self.area {
            area_index(world, "behaviour.area", name)?;
        }
        Ok(())
    }
}

/// `[validation]`: choosing the champion on validation worlds (default: off). Every `every`
/// generations the generation's `top` best individuals (by training fitness) are evaluated on
/// `trials` fixed validation worlds, the same every time and never trained on (their own seed
/// stream, distinct from the training worlds and from `compare`'s held-out worlds); `best.json`
/// is then the best on validation so far.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct ValidationSpec {
    /// Validate every this many generations, and always after the last (default: 0 = off).
    pub every: u64,
    /// How many of the generation's best individuals to validate (default: 3).
    pub top: u64,
    /// Validation worlds per candidate (default: 10).
    pub trials: u64,
}

impl Default for ValidationSpec {
    fn default() -> Self {
        ValidationSpec {
            every: 0,
            top: 3,
            trials: 10,
        }
    }
}

impl ValidationSpec {
    /// Is validation on?
    pub fn enabled(&self) -> bool {
        self.every > 0
    }

    /// Off and nothing else set: the table is left out of written files.
    pub fn is_default(&self) -> bool {
        *self == ValidationSpec::default()
    }

    /// Checks the table.
    pub fn validate(&self) -> Valid {
        count_within(
            "validation.every",
            self.every,
            0,
            u32::MAX as u64,
            "generations",
        )?;
        count_within("validation.top", self.top, 1, 10_000, "individuals")?;
        count_within(
            "validation.trials",
            self.trials,
            1,
            MAX_TRIALS,
            "validation worlds",
        )
    }
}

/// `[output]`: how often a run saves itself. Not part of the config hash: it changes where
/// results go, never what they are.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct OutputSpec {
    /// Write a checkpoint every this many generations, and always at the end (default: 10).
    pub checkpoint_every: u64,
    /// How many checkpoints to keep; older ones are deleted (default: 3, at least 1).
    pub keep_checkpoints: u64,
    /// A hand-designed genome file to compare the champion with at the end of a run (the
    /// held-out check), e.g. `"../genomes/foraging-baseline.json"`: a path relative to the
    /// folder of the experiment file (default: none). A run's experiment.toml keeps it as
    /// written (the same bytes on any machine) and the check keeps a copy of the genome in the
    /// run folder (`baseline.json`), which a later `resume` uses; a file that is not there is
    /// left out of the check with a note, never an error.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub baseline: Option<String>,
}

impl Default for OutputSpec {
    fn default() -> Self {
        OutputSpec {
            checkpoint_every: 10,
            keep_checkpoints: 3,
            baseline: None,
        }
    }
}

impl OutputSpec {
    /// Checks the table.
    pub fn validate(&self) -> Valid {
        count_within(
            "output.checkpoint_every",
            self.checkpoint_every,
            1,
            u32::MAX as u64,
            "generations",
        )?;
        count_within(
            "output.keep_checkpoints",
            self.keep_checkpoints,
            1,
            1_000,
            "files",
        )?;
        if let Some(path) = &self.baseline {
            if path.trim().is_empty() || path.contains('\0') {
                return Err(InvalidValue::new(
                    "output.baseline",
                    "must name a genome file (a path relative to the experiment file's \
                     folder, e.g. \"../genomes/foraging-baseline.json\"), or be left out",
                ));
            }
        }
        Ok(())
    }

    /// The baseline genome file, resolved against `folder` (the folder of the experiment file
    /// that names it; an absolute path stays as it is); `None` when there is none.
    pub fn baseline_in(&self, folder: &Path) -> Option<PathBuf> {
        self.baseline.as_ref().map(|b| folder.join(b))
    }
}
