//! [`LifePlan`]: what a trial must watch and how it scores, resolved once per trial from the
//! experiment's `[fitness]` and `[behaviour]` tables and the trial world's areas.

use crate::evo::choices::ChoicePlan;
use crate::evo::fitness::gain::Goal;
use crate::evo::trial_plan::TrialPlan;
use crate::experiment::tables::area_index;
use crate::experiment::terms::{self, Follows, TERM_COUNT};
use crate::experiment::{Balance, FitnessMode, FitnessSpec, GoalAt, Measure};
use crate::geometry::Vec2;
use crate::sim::area::Area;
use crate::sim::world::World;

/// What a trial must watch and how it scores, decided once per trial from the experiment
/// (and the trial world's areas).
#[derive(Debug, Clone, PartialEq)]
pub struct LifePlan {
    pub(super) weights: [f64; 4],
    pub(super) mode: FitnessMode,
    pub(super) shock_penalty: f64,
    pub(super) balance: Balance,
    pub(super) imbalance_penalty: f64,
    /// `Balance::Sum` without a penalty: the gain is [`super::weighted`].
    pub(super) plain_gain: bool,
    /// Each term's weight, in [`terms::TERMS`] order.
    pub(super) terms: [f64; TERM_COUNT],
    /// The area `area_bonus` pays for, with the bonus.
    pub(super) area_bonus: Option<(Area, f64)>,
    /// The goal, its bonus, its range and when the distance is taken.
    pub(super) goal: Option<(Goal, f64, f64, GoalAt)>,
    /// Threatened and sheltered ticks are counted (for `shelter_bonus` or the measure).
    pub(super) counts_threats: bool,
    /// The measures the experiment reports, in its order.
    pub(super) measures: Vec<Measure>,
    /// `[behaviour] area`.
    pub(super) behaviour_area: Option<Area>,
    /// The areas a search's descriptors count the ticks in, in descriptor order (usually
    /// none; `None` for an index the world lacks, so that the slots stay in order).
    pub(super) described_areas: Vec<Option<Area>>,
    pub(super) threat_radius: f64,
    /// Some measure follows the pose tick by tick (`forward_share`, `path_length`,
    /// `final_x`, `final_y`, `still_share`).
    pub(super) follows_motion: bool,
    /// `forward_bonus` or a measure that follows the motion: the pose is kept every tick.
    pub(super) tracks_pose: bool,
    /// Some term or measure needs the world at the end of every tick.
    pub(super) per_tick: bool,
    /// ... and it is more than the forward distance: an area, the closest approach to a goal
    /// or a measure that looks around the creature.
    pub(super) watches_places: bool,
    /// Some term or measure needs the food objects each creature eats from.
    pub(super) bites: bool,
    /// Some measure reads the world's events (`door_opened`, `aversive_contacts`): the
    /// trial world's event log is switched on ([`LifePlan::prepare`]).
    pub(super) events: bool,
    /// The switch measures' objects (`adapted_choice`, `good_bite_share`).
    pub(super) choices: Option<ChoicePlan>,
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
            described_areas: Vec::new(),
            threat_radius: 0.0,
            follows_motion: false,
            tracks_pose: false,
            per_tick: false,
            watches_places: false,
            bites: spec.term_following(Follows::Bites).is_some(),
            events: false,
            choices: None,
        }
    }

    /// The plan of the trial's `[fitness]` and `[behaviour]` tables in `world` (a trial
    /// world of the experiment: its areas are the experiment's, in file order).
    pub fn new(trial_plan: &TrialPlan, world: &World) -> LifePlan {
        let spec = trial_plan.fitness;
        let behaviour = trial_plan.behaviour;
        let area = |name: &Option<String>| -> Option<Area> {
            let name = name.as_deref()?;
            let k = area_index(trial_plan.world, "", name).ok()?;
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
        plan.described_areas = trial_plan
            .described_areas
            .indices()
            .iter()
            .map(|&k| world.areas().get(k).copied())
            .collect();
        plan.threat_radius = behaviour.threat_radius;
        let follows = |f: Follows| spec.term_following(f).is_some();
        if follows(Follows::Choices) || plan.measures.iter().any(|m| m.needs_switch()) {
            plan.choices = ChoicePlan::new(trial_plan, world);
        }
        plan.counts_threats =
            follows(Follows::Threats) || plan.measures.contains(&Measure::ShelterWhileThreat);
        plan.events = plan
            .measures
            .iter()
            .any(|m| matches!(m, Measure::DoorOpened | Measure::AversiveContacts));
        let closest = matches!(plan.goal, Some((_, _, _, GoalAt::Closest)));
        plan.watches_places = plan.area_bonus.is_some()
            || closest
            || plan.counts_threats
            || plan.choices.is_some()
            || plan.events
            || !plan.described_areas.is_empty()
            || plan.measures.iter().any(|m| {
                matches!(
                    m,
                    Measure::AreaReached
                        | Measure::TimeInArea
                        | Measure::StrikesSurvived
                        | Measure::RichestSideFirst
                )
            });
        plan.follows_motion = plan.measures.iter().any(|m| m.follows_motion());
        plan.tracks_pose = follows(Follows::Pose) || plan.follows_motion;
        plan.per_tick = plan.watches_places || plan.tracks_pose;
        plan.bites = follows(Follows::Bites)
            || plan.choices.is_some()
            || plan.measures.iter().any(|m| {
                matches!(
                    m,
                    Measure::DistinctFood | Measure::FoodInAreaEaten | Measure::RichestSideFirst
                )
            });
        plan
    }

    /// Must the trial world note which food objects each creature eats from
    /// ([`World::track_bites`])?
    pub fn needs_bites(&self) -> bool {
        self.bites
    }

    /// Must the trial world tell its events ([`World::set_event_log`])? Only a plan with a
    /// measure read from them does, so that a life without one costs what it always did.
    pub fn needs_events(&self) -> bool {
        self.events
    }

    /// Must [`super::LifeScore::record_world`] be called after every tick?
    pub fn needs_world_every_tick(&self) -> bool {
        self.per_tick
    }

    /// The measures reported, in the experiment's order.
    pub fn measures(&self) -> &[Measure] {
        &self.measures
    }

    /// A trial world ready for this plan, before its first tick: bite tracking and the
    /// event log turned on when needed. The log is only ever switched on here, never off,
    /// so a watcher that listens ([`crate::evo::trial::TickObserver::listens`]) keeps it.
    /// Every trial path (one world at a time, lockstep, the step-by-step episode) prepares
    /// its worlds here, through `evo::life::start_scores`.
    pub fn prepare(&self, world: &mut World) {
        if self.bites {
            world.track_bites();
        }
        if self.events {
            world.set_event_log(true);
        }
    }
}
