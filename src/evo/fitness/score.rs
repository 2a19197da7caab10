//! [`LifeScore`]: what a life's score and measures need, accumulated tick by tick under a
//! [`LifePlan`] (the score and measures at the end: `finish.rs`).

use crate::evo::choices::{ChoiceTrack, EpisodeChoices};
use crate::evo::fitness::gain::{balanced_gain, weighted};
use crate::evo::fitness::plan::LifePlan;
use crate::evo::fitness::trackers::{door_opened, AversiveContacts, FlyerPasses, SideChoice};
use crate::experiment::evolution::MAX_DESCRIBED_AREAS;
use crate::experiment::tables::{FORWARD_STEP, STILL_STEP};
use crate::experiment::{Balance, FitnessMode, FitnessSpec, GoalAt, Measure};
use crate::geometry::{circles_touch, Vec2};
use crate::sim::gadgets::Role;
use crate::sim::metabolism::Metabolism;
use crate::sim::motion::Pose;
use crate::sim::world::World;

/// Accumulates what a life's score and measures need, tick by tick.
#[derive(Debug, Clone)]
pub struct LifeScore {
    pub(super) weights: [f64; 4],
    pub(super) mode: FitnessMode,
    pub(super) shock_penalty: f64,
    pub(super) integral: f64,
    pub(super) shocked_ticks: u64,
    /// The gain is [`weighted`] (no balance term): the per-tick fast path.
    pub(super) plain_gain: bool,
    pub(super) balance: Balance,
    pub(super) imbalance_penalty: f64,
    /// Ticks recorded: the creature alive at their end.
    pub(super) ticks: u64,
    pub(super) ticks_in_fitness_area: u64,
    pub(super) goal_closest: f64,
    pub(super) area_reached: bool,
    pub(super) ticks_in_area: u64,
    /// Ticks in each of the plan's described areas, in its order.
    pub(super) ticks_in_described: [u64; MAX_DESCRIBED_AREAS],
    pub(super) door_opened: bool,
    pub(super) threat_ticks: u64,
    pub(super) sheltered_threat_ticks: u64,
    pub(super) passes: FlyerPasses,
    pub(super) aversive: AversiveContacts,
    /// The pose at the end of the previous tick (or the start), for `forward_distance` and
    /// the motion measures (kept only when the plan tracks the pose).
    pub(super) last_pose: Pose,
    pub(super) forward_distance: f64,
    /// Ticks whose step along the heading exceeded [`FORWARD_STEP`].
    pub(super) forward_ticks: u64,
    /// Ticks whose displacement was below [`STILL_STEP`].
    pub(super) still_ticks: u64,
    pub(super) path_length: f64,
    pub(super) side_choice: Option<SideChoice>,
    /// The bites of the switch kinds (`adapted_choice`, `good_bite_share`).
    pub(super) choices: Option<ChoiceTrack>,
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
            ticks_in_described: [0; MAX_DESCRIBED_AREAS],
            door_opened: false,
            threat_ticks: 0,
            sheltered_threat_ticks: 0,
            passes: FlyerPasses::default(),
            aversive: AversiveContacts::default(),
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
            score.passes = FlyerPasses::start(world);
        }
        if plan.measures.contains(&Measure::AversiveContacts) {
            score.aversive = AversiveContacts::start(world, p);
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
    /// [`LifePlan::needs_world_every_tick`], in a world the plan prepared,
    /// [`LifePlan::prepare`], so that it tells the events the plan reads). The forward
    /// distance is summed inline (it is the main job's one per-tick term), with the motion
    /// measures when asked for; the rest is looked up out of line, only when the plan watches
    /// places or gadgets.
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
    /// `creature`'s position `p` or read the world's events of the tick.
    #[inline(never)]
    fn record_places(&mut self, plan: &LifePlan, world: &World, creature: usize, p: Vec2) {
        debug_assert!(
            !plan.events || world.event_log_on(),
            "a plan that reads events needs a world it prepared"
        );
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
        // The same count as `time_in_area`'s, one per area a descriptor names.
        for (ticks, area) in self
            .ticks_in_described
            .iter_mut()
            .zip(&plan.described_areas)
        {
            if let Some(area) = area {
                *ticks += u64::from(area.contains(p));
            }
        }
        if let (Some(track), Some(choices)) = (&mut self.choices, &plan.choices) {
            track.record(choices, world.bitten(creature));
        }
        if plan.counts_threats {
            self.record_threats(plan, world, p);
        }
        for &m in &plan.measures {
            match m {
                Measure::DoorOpened => self.door_opened |= door_opened(world),
                Measure::StrikesSurvived => self.passes.record(world, p),
                Measure::AversiveContacts => self.aversive.record(world, creature, p),
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

    /// Threatened and sheltered ticks. Measured, not read from the events: a predator
    /// within `threat_radius` and a creature inside a safe area are descriptions of the
    /// scene, not things the world decides (it decides an attack, which a sheltered creature
    /// never suffers).
    fn record_threats(&mut self, plan: &LifePlan, world: &World, p: Vec2) {
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
}
