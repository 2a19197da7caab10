//! Fitness of one life: the `[fitness]` table applied to a creature's metabolic history
//! (report §5.3 leaves the function open; SPEC-NOTES lists the choices offered here), and the
//! `[behaviour]` measures taken over the same life.
//!
//! What a trial must watch is decided once per trial ([`LifePlan`]): with only the
//! metabolic gain and the shock penalty (every shipped experiment before the new keys), a
//! tick costs what it always did, and a world query is made only for a term or measure that
//! needs it.

use crate::evo::choices::{ChoicePlan, ChoiceTrack, EpisodeChoices};
use crate::experiment::tables::{area_index, FORWARD_STEP, STILL_STEP};
use crate::experiment::terms::{self, Quantity, Sign, TERMS, TERM_COUNT};
use crate::experiment::{Balance, Experiment, FitnessMode, FitnessSpec, GoalAt, Measure, MEASURES};
use crate::geometry::{circles_touch, Vec2};
use crate::sim::area::Area;
use crate::sim::gadgets::Role;
use crate::sim::metabolism::Metabolism;
use crate::sim::motion::Pose;
use crate::sim::world::{Creature, World};

/// How many behaviour measures there are ([`MEASURES`]); a trial's measure values are an
/// array of this length, in that order.
pub const MEASURE_COUNT: usize = MEASURES.len();

pub use crate::sim::metabolism::weighted;

/// The metabolic gain `B(m)` of one metabolic vector (see [`FitnessSpec`]): `Σ wᵢ·mᵢ` or
/// `min wᵢ·mᵢ` over the components with wᵢ ≠ 0, minus `imbalance_penalty × (max − min)` of
/// those components. With `Balance::Sum` and no penalty this is [`weighted`], bit for bit.
pub fn balanced_gain(weights: &[f64; 4], m: &[f64; 4], balance: Balance, penalty: f64) -> f64 {
    let base = match balance {
        Balance::Sum => weighted(weights, m),
        Balance::Min => weighted_extremes(weights, m).map_or(0.0, |(lo, _)| lo),
    };
    if penalty == 0.0 {
        return base;
    }
    let spread = weighted_extremes(weights, m).map_or(0.0, |(lo, hi)| hi - lo);
    base - penalty * spread
}

/// The smallest and largest `wᵢ·mᵢ` over the components with wᵢ ≠ 0 (None when every
/// weight is 0).
fn weighted_extremes(weights: &[f64; 4], m: &[f64; 4]) -> Option<(f64, f64)> {
    let mut extremes: Option<(f64, f64)> = None;
    for (w, x) in weights.iter().zip(m) {
        if *w != 0.0 {
            let v = w * x;
            extremes = Some(extremes.map_or((v, v), |(lo, hi)| (lo.min(v), hi.max(v))));
        }
    }
    extremes
}

/// The goal-shaping term: `bonus × max(0, 1 − distance / range)`.
pub fn goal_term(bonus: f64, distance: f64, range: f64) -> f64 {
    bonus * goal_nearness(distance, range)
}

/// What the goal term counts: `max(0, 1 − distance / range)`.
pub fn goal_nearness(distance: f64, range: f64) -> f64 {
    (1.0 - distance / range).max(0.0)
}

/// The distance from `p` to the nearest point of `area` (0 inside or on its border).
pub fn distance_to_area(area: &Area, p: Vec2) -> f64 {
    let dx = (area.lo.x - p.x).max(0.0).max(p.x - area.hi.x);
    let dy = (area.lo.y - p.y).max(0.0).max(p.y - area.hi.y);
    (dx * dx + dy * dy).sqrt()
}

/// What `[fitness] goal` points at.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Goal {
    /// A named area: the distance is to its nearest point.
    Area(Area),
    /// A point.
    Point(Vec2),
}

impl Goal {
    /// The distance from `p` to the goal.
    pub fn distance(&self, p: Vec2) -> f64 {
        match self {
            Goal::Area(a) => distance_to_area(a, p),
            Goal::Point(g) => g.distance(p),
        }
    }
}

/// What a trial must watch and how it scores, decided once per trial from the experiment
/// (and the trial world's areas).
#[derive(Debug, Clone, PartialEq)]
pub struct LifePlan {
    weights: [f64; 4],
    mode: FitnessMode,
    shock_penalty: f64,
    balance: Balance,
    imbalance_penalty: f64,
    /// `Balance::Sum` without a penalty: the gain is [`weighted`].
    plain_gain: bool,
    /// Each term's weight, in [`TERMS`] order.
    terms: [f64; TERM_COUNT],
    /// The area `area_bonus` pays for, with the bonus.
    area_bonus: Option<(Area, f64)>,
    /// The goal, its bonus, its range and when the distance is taken.
    goal: Option<(Goal, f64, f64, GoalAt)>,
    /// Threatened and sheltered ticks are counted (for `shelter_bonus` or the measure).
    counts_threats: bool,
    /// The measures the experiment reports, in its order.
    measures: Vec<Measure>,
    /// `[behaviour] area`.
    behaviour_area: Option<Area>,
    threat_radius: f64,
    /// Some measure follows the pose tick by tick (`forward_share`, `path_length`,
    /// `final_x`, `final_y`, `still_share`).
    follows_motion: bool,
    /// `forward_bonus` or a measure that follows the motion: the pose is kept every tick.
    tracks_pose: bool,
    /// Some term or measure needs the world at the end of every tick.
    per_tick: bool,
    /// ... and it is more than the forward distance: an area, the closest approach to a goal
    /// or a measure that looks around the creature.
    watches_places: bool,
    /// Some term or measure needs the food objects each creature eats from.
    bites: bool,
    /// The switch measures' objects (`adapted_choice`, `good_bite_share`).
    choices: Option<ChoicePlan>,
}

impl LifePlan {
    /// The plan of a `[fitness]` table with no world-dependent term and no measure (areas
    /// and goals named in it are ignored: use [`LifePlan::new`] for those).
    pub fn plain(spec: &FitnessSpec) -> LifePlan {
        LifePlan {
            weights: spec.weights,
            mode: spec.mode,
            shock_penalty: spec.shock_penalty,
            balance: spec.balance,
            imbalance_penalty: spec.imbalance_penalty,
            plain_gain: spec.balance == Balance::Sum && spec.imbalance_penalty == 0.0,
            terms: terms::weights(spec),
            area_bonus: None,
            goal: None,
            counts_threats: false,
            measures: Vec::new(),
            behaviour_area: None,
            threat_radius: 0.0,
            follows_motion: false,
            tracks_pose: false,
            per_tick: false,
            watches_places: false,
            bites: spec.distinct_food_bonus != 0.0,
            choices: None,
        }
    }

    /// The plan of `experiment`'s `[fitness]` and `[behaviour]` tables in `world` (a trial
    /// world of the experiment: its areas are the experiment's, in file order).
    pub fn new(experiment: &Experiment, world: &World) -> LifePlan {
        let spec = &experiment.fitness;
        let behaviour = &experiment.behaviour;
        let area = |name: &Option<String>| -> Option<Area> {
            let name = name.as_deref()?;
            let k = area_index(&experiment.world, "", name).ok()?;
            world.areas().get(k).copied()
        };
        let mut plan = LifePlan::plain(spec);
        if spec.area_bonus != 0.0 {
            plan.area_bonus = area(&spec.area).map(|a| (a, spec.area_bonus));
        }
        if spec.goal_bonus != 0.0 {
            let target = match spec.goal_point {
                Some([x, y]) => Some(Goal::Point(Vec2::new(x, y))),
                None => area(&spec.goal).map(Goal::Area),
            };
            let [w, h] = world.arena();
            let range = spec.goal_range.unwrap_or_else(|| (w * w + h * h).sqrt());
            plan.goal = target.map(|g| (g, spec.goal_bonus, range, spec.goal_at));
        }
        plan.measures = behaviour.measures.clone();
        plan.behaviour_area = area(&behaviour.area);
        plan.threat_radius = behaviour.threat_radius;
        if plan.measures.iter().any(|m| m.needs_switch()) {
            plan.choices = ChoicePlan::new(experiment, world);
        }
        plan.counts_threats = plan.weight(Quantity::ShelteredThreatTicks) != 0.0
            || plan.measures.contains(&Measure::ShelterWhileThreat);
        let closest = matches!(plan.goal, Some((_, _, _, GoalAt::Closest)));
        plan.watches_places = plan.area_bonus.is_some()
            || closest
            || plan.counts_threats
            || plan.choices.is_some()
            || plan.measures.iter().any(|m| {
                matches!(
                    m,
                    Measure::AreaReached
                        | Measure::TimeInArea
                        | Measure::DoorOpened
                        | Measure::StrikesSurvived
                        | Measure::AversiveContacts
                        | Measure::RichestSideFirst
                )
            });
        plan.follows_motion = plan.measures.iter().any(|m| m.follows_motion());
        plan.tracks_pose = plan.weight(Quantity::ForwardDistance) != 0.0 || plan.follows_motion;
        plan.per_tick = plan.watches_places || plan.tracks_pose;
        plan.bites = plan.weight(Quantity::DistinctFood) != 0.0
            || plan.choices.is_some()
            || plan.measures.iter().any(|m| {
                matches!(
                    m,
                    Measure::DistinctFood | Measure::FoodInAreaEaten | Measure::RichestSideFirst
                )
            });
        plan
    }

    /// The weight of the term that counts `quantity` (0 when none does).
    fn weight(&self, quantity: Quantity) -> f64 {
        TERMS
            .iter()
            .zip(self.terms)
            .find(|(t, _)| t.counts == quantity)
            .map_or(0.0, |(_, w)| w)
    }

    /// Must the trial world note which food objects each creature eats from
    /// ([`World::track_bites`])?
    pub fn needs_bites(&self) -> bool {
        self.bites
    }

    /// Must [`LifeScore::record_world`] be called after every tick?
    pub fn needs_world_every_tick(&self) -> bool {
        self.per_tick
    }

    /// The measures reported, in the experiment's order.
    pub fn measures(&self) -> &[Measure] {
        &self.measures
    }

    /// A trial world ready for this plan: bite tracking turned on when needed.
    pub fn prepare(&self, world: &mut World) {
        if self.bites {
            world.track_bites();
        }
    }
}

/// One air predator pass over a creature, as [`Measure::StrikesSurvived`] follows it.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
struct Pass {
    /// The creature is inside the predator's strike radius now.
    over: bool,
    /// ... and was sheltered on every tick of this pass so far.
    sheltered: bool,
}

/// The T-maze choice as [`Measure::RichestSideFirst`] follows it: which side of its start
/// line a creature strays to before it first bites the richest food object.
#[derive(Debug, Clone, Copy, PartialEq)]
struct SideChoice {
    /// The richest food object, in [`World::food`] order.
    food: usize,
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
    strayed: bool,
    /// It has bitten the food (from then on nothing is followed).
    bitten: bool,
}

impl SideChoice {
    /// The choice creature `creature` of `world` faces at its start; None in a world
    /// without food.
    fn start(world: &World, creature: usize) -> Option<SideChoice> {
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
    fn record(&mut self, bitten: bool, p: Vec2) {
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

/// Accumulates what a life's score and measures need, tick by tick.
#[derive(Debug, Clone)]
pub struct LifeScore {
    weights: [f64; 4],
    mode: FitnessMode,
    shock_penalty: f64,
    integral: f64,
    shocked_ticks: u64,
    /// The gain is [`weighted`] (no balance term): the per-tick fast path.
    plain_gain: bool,
    balance: Balance,
    imbalance_penalty: f64,
    /// Ticks recorded: the creature alive at their end.
    ticks: u64,
    ticks_in_fitness_area: u64,
    goal_closest: f64,
    area_reached: bool,
    ticks_in_area: u64,
    door_opened: bool,
    threat_ticks: u64,
    sheltered_threat_ticks: u64,
    passes: Vec<Pass>,
    strikes_survived: u64,
    touching_aversive: bool,
    aversive_contacts: u64,
    /// The pose at the end of the previous tick (or the start), for `forward_distance` and
    /// the motion measures (kept only when the plan tracks the pose).
    last_pose: Pose,
    forward_distance: f64,
    /// Ticks whose step along the heading exceeded [`FORWARD_STEP`].
    forward_ticks: u64,
    /// Ticks whose displacement was below [`STILL_STEP`].
    still_ticks: u64,
    path_length: f64,
    side_choice: Option<SideChoice>,
    /// The bites of the switch kinds (`adapted_choice`, `good_bite_share`).
    choices: Option<ChoiceTrack>,
}

impl LifeScore {
    /// A score for a life that has not started yet, under a plain `[fitness]` table
    /// ([`LifePlan::plain`]).
    pub fn new(spec: &FitnessSpec) -> Self {
        Self::with_plan(&LifePlan::plain(spec))
    }

    fn with_plan(plan: &LifePlan) -> Self {
        LifeScore {
            weights: plan.weights,
            mode: plan.mode,
            shock_penalty: plan.shock_penalty,
            integral: 0.0,
            shocked_ticks: 0,
            plain_gain: plan.plain_gain,
            balance: plan.balance,
            imbalance_penalty: plan.imbalance_penalty,
            ticks: 0,
            ticks_in_fitness_area: 0,
            goal_closest: f64::INFINITY,
            area_reached: false,
            ticks_in_area: 0,
            door_opened: false,
            threat_ticks: 0,
            sheltered_threat_ticks: 0,
            passes: Vec::new(),
            strikes_survived: 0,
            touching_aversive: false,
            aversive_contacts: 0,
            last_pose: Pose {
                position: Vec2::ZERO,
                heading: Vec2::X,
            },
            forward_distance: 0.0,
            forward_ticks: 0,
            still_ticks: 0,
            path_length: 0.0,
            side_choice: None,
            choices: None,
        }
    }

    /// A score for creature `creature` of `world` before its first tick: with a plan that
    /// watches the world, the start counts (the closest approach to the goal, an area
    /// reached, a contact already going on).
    pub fn start(plan: &LifePlan, world: &World, creature: usize) -> Self {
        let mut score = Self::with_plan(plan);
        if !plan.per_tick {
            return score;
        }
        let p = world.creatures()[creature].pose.position;
        if let Some((goal, _, _, GoalAt::Closest)) = &plan.goal {
            score.goal_closest = goal.distance(p);
        }
        score.last_pose = world.creatures()[creature].pose;
        if let Some(a) = &plan.behaviour_area {
            score.area_reached = a.contains(p);
        }
        if plan.measures.contains(&Measure::StrikesSurvived) {
            score.passes = vec![Pass::default(); world.flyers().len()];
        }
        if plan.measures.contains(&Measure::AversiveContacts) {
            score.touching_aversive = touches_aversive(world, p);
        }
        if plan.measures.contains(&Measure::RichestSideFirst) {
            score.side_choice = SideChoice::start(world, creature);
        }
        score.choices = plan.choices.as_ref().map(ChoiceTrack::new);
        score
    }

    /// Records one lived tick: the metabolic vector after it and whether the creature was
    /// shocked on it.
    #[inline]
    pub fn record_tick(&mut self, metabolism: &Metabolism, shocked: bool) {
        if self.mode == FitnessMode::Integrated {
            self.integral += if self.plain_gain {
                weighted(&self.weights, metabolism)
            } else {
                balanced_gain(
                    &self.weights,
                    metabolism,
                    self.balance,
                    self.imbalance_penalty,
                )
            };
        }
        self.shocked_ticks += u64::from(shocked);
        self.ticks += 1;
    }

    /// Records what `plan` watches in `world` at the end of a tick that creature `creature`
    /// lived through (after [`LifeScore::record_tick`]; only when
    /// [`LifePlan::needs_world_every_tick`]). The forward distance is summed inline (it is
    /// the main job's one per-tick term), with the motion measures when asked for; the rest
    /// is looked up out of line, only when the plan watches places or gadgets.
    #[inline]
    pub fn record_world(&mut self, plan: &LifePlan, world: &World, creature: usize) {
        let pose = world.creatures()[creature].pose;
        if plan.tracks_pose {
            let last = self.last_pose;
            let step = pose.position - last.position;
            let along = step.dot(last.heading);
            // The same operations as before the motion measures: the same bits.
            self.forward_distance += along.max(0.0);
            if plan.follows_motion {
                self.forward_ticks += u64::from(along > FORWARD_STEP);
                let length = step.length();
                self.path_length += length;
                self.still_ticks += u64::from(length < STILL_STEP);
            }
            self.last_pose = pose;
        }
        if plan.watches_places {
            self.record_places(plan, world, creature, pose.position);
        }
    }

    /// The areas, the goal and the measures that look at the world around creature
    /// `creature`'s position `p`.
    #[inline(never)]
    fn record_places(&mut self, plan: &LifePlan, world: &World, creature: usize, p: Vec2) {
        if let Some((area, _)) = &plan.area_bonus {
            self.ticks_in_fitness_area += u64::from(area.contains(p));
        }
        if let Some((goal, _, _, GoalAt::Closest)) = &plan.goal {
            self.goal_closest = self.goal_closest.min(goal.distance(p));
        }
        if let Some(area) = &plan.behaviour_area {
            let inside = area.contains(p);
            self.area_reached |= inside;
            self.ticks_in_area += u64::from(inside);
        }
        if let (Some(track), Some(choices)) = (&mut self.choices, &plan.choices) {
            track.record(choices, world.bitten(creature));
        }
        if plan.counts_threats {
            let r = plan.threat_radius;
            let ground = world.actors().iter().any(|a| {
                matches!(a.role, Role::Predator { .. })
                    && a.awake()
                    && circles_touch(p, 0.0, a.pose.position, r)
            });
            let air = world
                .flyers()
                .iter()
                .any(|f| f.in_flight() && circles_touch(p, 0.0, f.position, r));
            if ground || air {
                self.threat_ticks += 1;
                self.sheltered_threat_ticks += u64::from(world.in_safe_area(p));
            }
        }
        for &m in &plan.measures {
            match m {
                Measure::DoorOpened => {
                    self.door_opened |= (0..world.door_count()).any(|k| world.door_open(k));
                }
                Measure::StrikesSurvived => {
                    let safe = world.in_safe_area(p);
                    for (pass, f) in self.passes.iter_mut().zip(world.flyers()) {
                        let over =
                            f.in_flight() && circles_touch(p, 0.0, f.position, f.strike_radius);
                        if over {
                            pass.sheltered = if pass.over {
                                pass.sheltered && safe
                            } else {
                                safe
                            };
                        } else if pass.over && pass.sheltered {
                            self.strikes_survived += 1;
                        }
                        pass.over = over;
                    }
                }
                Measure::AversiveContacts => {
                    let touching = touches_aversive(world, p);
                    self.aversive_contacts += u64::from(touching && !self.touching_aversive);
                    self.touching_aversive = touching;
                }
                Measure::RichestSideFirst => {
                    if let Some(choice) = &mut self.side_choice {
                        let bitten = world.bitten(creature).get(choice.food) == Some(&true);
                        choice.record(bitten, p);
                    }
                }
                _ => {}
            }
        }
    }

    /// Ticks on which the creature was shocked.
    pub fn shocked_ticks(&self) -> u64 {
        self.shocked_ticks
    }

    /// The episode's bites of the switch kinds (None when no switch measure is reported).
    pub fn choices(&self) -> Option<EpisodeChoices> {
        self.choices.as_ref().map(ChoiceTrack::choices)
    }

    /// Ticks recorded (the creature alive at their end).
    pub fn ticks_alive(&self) -> u64 {
        self.ticks
    }

    /// The life's score under a plain plan ([`LifeScore::new`]), given the metabolic vector
    /// at its end: the metabolic gain minus the shock penalty (the other terms are added by
    /// [`LifeScore::finish_in`]).
    pub fn finish(&self, final_metabolism: &Metabolism) -> f64 {
        let gain = match self.mode {
            FitnessMode::Final if self.plain_gain => weighted(&self.weights, final_metabolism),
            FitnessMode::Final => balanced_gain(
                &self.weights,
                final_metabolism,
                self.balance,
                self.imbalance_penalty,
            ),
            FitnessMode::Integrated => self.integral,
        };
        gain - self.shock_penalty * self.shocked_ticks as f64
    }

    /// The life's score and its measures (one value per [`MEASURES`] entry; those the plan
    /// does not report are 0) for creature `creature` of `world` at the end of its trial.
    pub fn finish_in(
        &self,
        plan: &LifePlan,
        world: &World,
        creature: usize,
    ) -> (f64, [f64; MEASURE_COUNT]) {
        let c: &Creature = &world.creatures()[creature];
        let mut score = self.finish(&c.metabolism);
        let bitten = world.bitten(creature);
        let distinct = bitten.iter().filter(|&&b| b).count();
        // The extra terms, each added only when on, so that a plain table gives the bits of
        // `finish` alone.
        for (term, &weight) in TERMS.iter().zip(&plan.terms) {
            if weight == 0.0 {
                continue;
            }
            let quantity = match term.counts {
                Quantity::TicksAlive => self.ticks as f64,
                Quantity::TicksInArea => match plan.area_bonus {
                    Some(_) => self.ticks_in_fitness_area as f64,
                    None => continue,
                },
                Quantity::GoalNearness => match &plan.goal {
                    Some((goal, _, range, at)) => {
                        let d = match at {
                            GoalAt::End => goal.distance(c.pose.position),
                            GoalAt::Closest => {
                                self.goal_closest.min(goal.distance(c.pose.position))
                            }
                        };
                        goal_nearness(d, *range)
                    }
                    None => continue,
                },
                Quantity::DistinctFood => distinct as f64,
                Quantity::ForwardDistance => self.forward_distance,
                Quantity::ShelteredThreatTicks => self.sheltered_threat_ticks as f64,
                Quantity::Died => f64::from(u8::from(!c.alive)),
            };
            score = match term.sign {
                Sign::Add => score + weight * quantity,
                Sign::Subtract => score - weight * quantity,
            };
        }
        let mut measures = [0.0; MEASURE_COUNT];
        for &m in &plan.measures {
            measures[m.index()] = match m {
                Measure::TicksAlive => self.ticks as f64,
                Measure::DistinctFood => distinct as f64,
                Measure::FoodTypes => c.eaten.iter().filter(|&&e| e > 0.0).count() as f64,
                Measure::AreaReached => f64::from(u8::from(self.area_reached)),
                Measure::TimeInArea => self.ticks_in_area as f64,
                Measure::DoorOpened => f64::from(u8::from(self.door_opened)),
                Measure::FoodInAreaEaten => match &plan.behaviour_area {
                    Some(area) => bitten
                        .iter()
                        .zip(world.food())
                        .filter(|(&b, f)| b && area.contains(f.position))
                        .count() as f64,
                    None => 0.0,
                },
                Measure::ShelterWhileThreat => {
                    if self.threat_ticks == 0 {
                        1.0
                    } else {
                        self.sheltered_threat_ticks as f64 / self.threat_ticks as f64
                    }
                }
                Measure::StrikesSurvived => {
                    // A pass still going counts when the creature lived and was sheltered.
                    let open = if c.alive {
                        self.passes.iter().filter(|p| p.over && p.sheltered).count() as u64
                    } else {
                        0
                    };
                    (self.strikes_survived + open) as f64
                }
                Measure::AversiveContacts => self.aversive_contacts as f64,
                Measure::ShockedTicks => self.shocked_ticks as f64,
                Measure::ForwardShare => {
                    if self.ticks == 0 {
                        0.0
                    } else {
                        self.forward_ticks as f64 / self.ticks as f64
                    }
                }
                Measure::PathLength => self.path_length,
                Measure::FinalX => self.last_pose.position.x,
                Measure::FinalY => self.last_pose.position.y,
                Measure::Eaten => c.eaten.iter().sum(),
                Measure::StillShare => {
                    if self.ticks == 0 {
                        0.0
                    } else {
                        self.still_ticks as f64 / self.ticks as f64
                    }
                }
                Measure::RichestSideFirst => match &self.side_choice {
                    Some(s) => f64::from(u8::from(bitten.get(s.food) == Some(&true) && !s.strayed)),
                    None => 0.0,
                },
                // One episode's values; a life of several combines its episodes' bites
                // (`evo::episodes::Life::outcome`).
                Measure::AdaptedChoice => {
                    let first = self.choices().and_then(|c| c.first);
                    f64::from(u8::from(first == Some(true)))
                }
                Measure::GoodBiteShare => match self.choices() {
                    Some(c) if c.bites > 1 => {
                        let first = u64::from(c.first == Some(true));
                        (c.good - first) as f64 / (c.bites - 1) as f64
                    }
                    _ => 0.0,
                },
            };
        }
        (score, measures)
    }
}

/// Does a body of the world's creature radius at `p` touch an aversive object?
fn touches_aversive(world: &World, p: Vec2) -> bool {
    let r = world.creature_radius();
    world
        .aversives()
        .iter()
        .any(|a| circles_touch(p, r, a.position, a.radius))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(weights: [f64; 4], mode: FitnessMode, shock_penalty: f64) -> FitnessSpec {
        FitnessSpec {
            weights,
            mode,
            shock_penalty,
            ..FitnessSpec::default()
        }
    }

    #[test]
    fn final_mode_is_weights_dot_final_m_minus_shocks() {
        let spec = spec([1.0, 2.0, 0.0, -1.0], FitnessMode::Final, 0.5);
        let mut s = LifeScore::new(&spec);
        s.record_tick(&[9.0, 9.0, 9.0, 9.0], true);
        s.record_tick(&[1.0, 1.0, 1.0, 1.0], false);
        s.record_tick(&[0.0, 0.0, 0.0, 0.0], true);
        // 1*3 + 2*4 + 0*5 - 1*1 = 10, minus 2 shocked ticks * 0.5.
        assert_eq!(s.finish(&[3.0, 4.0, 5.0, 1.0]), 9.0);
        assert_eq!(s.shocked_ticks(), 2);
        assert_eq!(s.ticks_alive(), 3);
    }

    #[test]
    fn integrated_mode_sums_every_tick() {
        let spec = spec([1.0; 4], FitnessMode::Integrated, 1.0);
        let mut s = LifeScore::new(&spec);
        s.record_tick(&[1.0, 0.0, 0.0, 0.0], false);
        s.record_tick(&[1.0, 1.0, 0.0, 0.0], false);
        s.record_tick(&[1.0, 1.0, 1.0, 0.0], true);
        // 1 + 2 + 3 - 1.
        assert_eq!(s.finish(&[100.0; 4]), 5.0);
    }

    #[test]
    fn balance_min_scores_the_scarcest_weighted_component() {
        // Weighted components 2*1, 1*5, (weight 0 ignored), 0.5*8 = 2, 5, -, 4: min 2.
        let w = [2.0, 1.0, 0.0, 0.5];
        let m = [1.0, 5.0, -7.0, 8.0];
        assert_eq!(balanced_gain(&w, &m, Balance::Min, 0.0), 2.0);
        // Sum with an imbalance penalty 0.25: 11 - 0.25 * (5 - 2) = 10.25.
        assert_eq!(balanced_gain(&w, &m, Balance::Sum, 0.25), 10.25);
        // Min with the penalty: 2 - 0.5 * 3 = 0.5.
        assert_eq!(balanced_gain(&w, &m, Balance::Min, 0.5), 0.5);
        // No weight: nothing to take the minimum of.
        assert_eq!(balanced_gain(&[0.0; 4], &m, Balance::Min, 1.0), 0.0);
        // Sum without a penalty is the plain dot product.
        assert_eq!(balanced_gain(&w, &m, Balance::Sum, 0.0), weighted(&w, &m));
    }

    #[test]
    fn balance_min_in_final_and_integrated_modes() {
        let mut s = FitnessSpec {
            balance: Balance::Min,
            ..FitnessSpec::default()
        };
        let mut life = LifeScore::new(&s);
        life.record_tick(&[1.0, 2.0, 3.0, 4.0], false);
        assert_eq!(life.finish(&[3.0, 0.5, 2.0, 9.0]), 0.5);
        s.mode = FitnessMode::Integrated;
        let mut life = LifeScore::new(&s);
        life.record_tick(&[1.0, 2.0, 3.0, 4.0], false);
        life.record_tick(&[3.0, 0.5, 2.0, 9.0], false);
        // min 1 then min 0.5.
        assert_eq!(life.finish(&[0.0; 4]), 1.5);
    }

    #[test]
    fn goal_term_falls_linearly_to_zero_at_the_range() {
        assert_eq!(goal_term(10.0, 0.0, 100.0), 10.0);
        assert_eq!(goal_term(10.0, 25.0, 100.0), 7.5);
        assert_eq!(goal_term(10.0, 100.0, 100.0), 0.0);
        assert_eq!(goal_term(10.0, 250.0, 100.0), 0.0);
    }

    #[test]
    fn distance_to_an_area_is_to_its_nearest_point() {
        let a = Area {
            lo: Vec2::new(10.0, 20.0),
            hi: Vec2::new(30.0, 40.0),
            kind: crate::sim::spec::AreaKind::Plain,
            smell: crate::sim::smell::Smell::new(&[0.0; 8], 0.0, None),
        };
        assert_eq!(distance_to_area(&a, Vec2::new(20.0, 30.0)), 0.0);
        assert_eq!(distance_to_area(&a, Vec2::new(30.0, 40.0)), 0.0);
        assert_eq!(distance_to_area(&a, Vec2::new(0.0, 30.0)), 10.0);
        assert_eq!(distance_to_area(&a, Vec2::new(33.0, 44.0)), 5.0);
        assert_eq!(Goal::Point(Vec2::new(3.0, 4.0)).distance(Vec2::ZERO), 5.0);
    }
}
