//! The end of a life: its score ([`LifeScore::finish`], [`LifeScore::finish_in`]), the
//! `[fitness]` terms added to the metabolic gain, and the `[behaviour]` measures.

use crate::evo::fitness::gain::{balanced_gain, goal_nearness, weighted};
use crate::evo::fitness::plan::LifePlan;
use crate::evo::fitness::score::LifeScore;
use crate::evo::fitness::MEASURE_COUNT;
use crate::experiment::evolution::MAX_DESCRIBED_AREAS;
use crate::experiment::terms::{Quantity, Sign, TERMS};
use crate::experiment::{FitnessMode, GoalAt, Measure};
use crate::sim::metabolism::Metabolism;
use crate::sim::world::{Creature, World};

impl LifeScore {
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

    /// The life's score and its measures (one value per [`crate::experiment::MEASURES`]
    /// entry; those the plan does not report are 0) for creature `creature` of `world` at
    /// the end of its trial.
    pub fn finish_in(
        &self,
        plan: &LifePlan,
        world: &World,
        creature: usize,
    ) -> (f64, [f64; MEASURE_COUNT]) {
        let c: &Creature = &world.creatures()[creature];
        let bitten = world.bitten(creature);
        let distinct = bitten.iter().filter(|&&b| b).count();
        let score = self.terms(plan, c, distinct);
        let mut measures = [0.0; MEASURE_COUNT];
        for &m in &plan.measures {
            measures[m.index()] = self.measure(m, plan, world, c, bitten, distinct);
        }
        (score, measures)
    }

    /// The ticks alive in each area the plan's descriptors name, in its order (0 past them).
    pub fn described_area_ticks(&self) -> [f64; MAX_DESCRIBED_AREAS] {
        self.ticks_in_described.map(|t| t as f64)
    }

    /// [`LifeScore::finish`] with the extra terms of `plan` for creature `c`, which took
    /// from `distinct` food objects. Each term is added only when on, so that a plain table
    /// gives the bits of `finish` alone.
    fn terms(&self, plan: &LifePlan, c: &Creature, distinct: usize) -> f64 {
        let mut score = self.finish(&c.metabolism);
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
                Quantity::CorrectFirstChoice => {
                    f64::from(u8::from(self.choices().and_then(|c| c.first) == Some(true)))
                }
            };
            score = match term.sign {
                Sign::Add => score + weight * quantity,
                Sign::Subtract => score - weight * quantity,
            };
        }
        score
    }

    /// The value of measure `m` for creature `c` of `world`, `bitten` its food objects
    /// (`distinct` of them).
    fn measure(
        &self,
        m: Measure,
        plan: &LifePlan,
        world: &World,
        c: &Creature,
        bitten: &[bool],
        distinct: usize,
    ) -> f64 {
        let share = |count: u64| {
            if self.ticks == 0 {
                0.0
            } else {
                count as f64 / self.ticks as f64
            }
        };
        match m {
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
            Measure::StrikesSurvived => self.passes.survived(c.alive) as f64,
            Measure::AversiveContacts => self.aversive.count as f64,
            Measure::ShockedTicks => self.shocked_ticks as f64,
            Measure::ForwardShare => share(self.forward_ticks),
            Measure::PathLength => self.path_length,
            Measure::FinalX => self.last_pose.position.x,
            Measure::FinalY => self.last_pose.position.y,
            Measure::Eaten => c.eaten.iter().sum(),
            Measure::StillShare => share(self.still_ticks),
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
        }
    }
}
