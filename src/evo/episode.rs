//! One creature's trial, stepped one tick at a time by a caller that chooses each motor
//! command itself (a reinforcement-learning agent, a hand-written controller in Python's
//! Gymnasium environments): the trial path of [`crate::evo::trial`] turned inside out.
//!
//! An [`Episode`] holds the world of a trial and its score bookkeeping. Its tick is the
//! phases of [`crate::sim::world::World::step`] in their one valid order, split where the
//! controller acts: `begin_tick` and `observe` end one call (the observation the caller then
//! reads), `apply` and `end_tick` start the next, followed by the same score bookkeeping as
//! `trial::live` (`life::record_tick`), which also decides the end (no life left to record).
//! So an episode driven by a genome's brain lives, to the bit, the life evaluation scores
//! (tested in tests/evo/episode_steps.rs). The evaluation paths do not use this file: their
//! speed and bytes are untouched.

use crate::evo::fitness::{LifePlan, LifeScore};
use crate::evo::life::{
    finite_command, outcomes, record_tick, start_scores, trial_world, EvaluationError, TrialOutcome,
};
use crate::evo::trial_plan::TrialPlan;
use crate::seed::{Generation, TrialIndex};
use crate::sim::controller::MotorCommand;
use crate::sim::world::World;

/// What one tick of an [`Episode`] gave.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Step {
    /// The score's change in this tick: the trial's score under `[fitness]` if the life
    /// ended now, minus the same after the previous tick (0 before the first), so that the
    /// rewards of a whole episode add up to the trial's score (up to rounding).
    pub reward: f64,
    /// The life is over: the creature died, or gave a non-finite command.
    pub terminated: bool,
    /// The trial's `[evaluation] ticks` ran out with the creature alive.
    pub truncated: bool,
}

/// One creature living one trial world, a tick per [`Episode::step`].
#[derive(Debug, Clone)]
pub struct Episode {
    world: World,
    plan: LifePlan,
    scores: Vec<LifeScore>,
    observation: Vec<f64>,
    score: f64,
    ticks: u64,
    non_finite: bool,
    over: bool,
}

impl Episode {
    /// Trial `trial` of generation `generation` for one creature (group 0): the world a
    /// genome evaluated alone meets there (`berry-evolve compare --worlds training
    /// --generation G`; the held-out worlds for
    /// [`crate::evo::worlds::HELD_OUT_GENERATION`]), before its first tick.
    pub fn new(
        plan: &TrialPlan,
        generation: Generation,
        trial: TrialIndex,
    ) -> Result<Episode, EvaluationError> {
        let episodes = plan.episodes_per_life;
        if episodes > 1 {
            return Err(EvaluationError::Episodes {
                episodes,
                path: "the step-by-step episode (the Python package's environments)",
            });
        }
        let world = trial_world(plan, 1, generation, 0, trial)?;
        Ok(Episode::in_world(plan, world))
    }

    /// An episode in a world built beforehand for one creature (e.g. a validation world).
    pub fn in_world(plan: &TrialPlan, mut world: World) -> Episode {
        let (life_plan, scores) = start_scores(plan, &mut world);
        let mut episode = Episode {
            observation: vec![0.0; world.layout().len()],
            world,
            plan: life_plan,
            scores,
            score: 0.0,
            ticks: plan.ticks,
            non_finite: false,
            over: plan.ticks == 0,
        };
        if !episode.over {
            episode.sense();
        }
        episode
    }

    /// The first phases of the next tick: the world moves on (food, doors, predators) and
    /// the creature senses.
    fn sense(&mut self) {
        self.world.begin_tick();
        let alive = self.world.observe_into(0, &mut self.observation);
        debug_assert!(alive, "an episode senses only while its creature lives");
    }

    /// What the creature senses now, for the command of the next [`Episode::step`], laid out
    /// as [`crate::experiment::ExperimentConfig::layout`] names it (the last one once over).
    pub fn observation(&self) -> &[f64] {
        &self.observation
    }

    /// True once the episode ended (terminated or truncated): [`Episode::step`] does nothing.
    pub fn is_over(&self) -> bool {
        self.over
    }

    /// The world, as it is now.
    pub fn world(&self) -> &World {
        &self.world
    }

    /// Ends the tick with `command` (a non-finite one stops the life, as in evaluation) and
    /// starts the next; once the episode is over, changes nothing and returns a zero reward,
    /// both flags as they ended.
    pub fn step(&mut self, command: MotorCommand) -> Step {
        if self.over {
            return Step {
                reward: 0.0,
                terminated: self.terminated(),
                truncated: !self.terminated(),
            };
        }
        let command = finite_command(command).unwrap_or_else(|| {
            self.non_finite = true;
            MotorCommand::default()
        });
        self.world.apply(0, command);
        self.world.end_tick();
        let living = record_tick(
            &self.world,
            &[self.non_finite],
            &mut self.scores,
            &self.plan,
        );
        let now = self.scores[0].finish_in(&self.plan, &self.world, 0).0;
        let reward = now - self.score;
        self.score = now;
        let terminated = !living;
        let truncated = living && self.world.tick() >= self.ticks;
        self.over = terminated || truncated;
        if !self.over {
            self.sense();
        }
        Step {
            reward,
            terminated,
            truncated,
        }
    }

    /// True when the life ended before the trial's ticks ran out.
    fn terminated(&self) -> bool {
        self.non_finite || !self.world.creatures()[0].alive
    }

    /// The life's outcome so far (its score, metabolism and behaviour measures as if it
    /// ended now): at the end, the [`TrialOutcome`] evaluation reports.
    pub fn outcome(&self) -> TrialOutcome {
        outcomes(&self.world, &self.scores, &[self.non_finite], &self.plan)[0]
    }
}
