//! The controller that lets a brain drive a creature: brain outputs in [-1, 1] become motor
//! signals in rotations per tick and, optionally, an eat signal.
//!
//! Output o0 drives the left motor, o1 the right one, each scaled by `max_rpt`
//! (left = o0 · max_rpt, right = o1 · max_rpt). With an eat output (`eating = "action"`), o2
//! becomes eat = (o2 + 1) / 2 ∈ [0, 1], so the creature eats when o2 > 0; otherwise eat = 0.

use super::{Brain, BrainError};
use crate::sim::controller::{Controller, MotorCommand};

/// The number of brain outputs a creature needs: left and right motor, plus the eat output
/// when eating is an action.
pub fn output_count(eat_output: bool) -> usize {
    if eat_output {
        3
    } else {
        2
    }
}

/// A brain driving a creature, with its output buffer (so [`Controller::act`] allocates
/// nothing).
#[derive(Debug, Clone, PartialEq)]
pub struct BrainController {
    brain: Brain,
    max_rpt: f64,
    eat_output: bool,
    outputs: Vec<f64>,
}

impl BrainController {
    /// A controller for `brain`, whose outputs scale to ±`max_rpt` RPT; `eat_output` says
    /// whether the brain has the third (eat) output.
    ///
    /// # Panics
    /// When the brain does not have [`output_count`]`(eat_output)` outputs: the topology is
    /// built from the same setting, so a mismatch is a programming error. Use
    /// [`BrainController::try_new`] to get an error instead.
    pub fn new(brain: Brain, max_rpt: f64, eat_output: bool) -> Self {
        match Self::try_new(brain, max_rpt, eat_output) {
            Ok(controller) => controller,
            Err(e) => panic!("{e}"),
        }
    }

    /// Like [`BrainController::new`], but a brain with the wrong number of outputs is an error.
    pub fn try_new(brain: Brain, max_rpt: f64, eat_output: bool) -> Result<Self, BrainError> {
        let expected = output_count(eat_output);
        if brain.outputs() != expected {
            return Err(BrainError::OutputCount {
                expected,
                got: brain.outputs(),
            });
        }
        Ok(BrainController {
            brain,
            max_rpt,
            eat_output,
            outputs: vec![0.0; expected],
        })
    }

    /// The brain.
    pub fn brain(&self) -> &Brain {
        &self.brain
    }

    /// The brain, mutably (e.g. to inspect or set a CTRNN's state).
    pub fn brain_mut(&mut self) -> &mut Brain {
        &mut self.brain
    }

    /// Gives the brain back.
    pub fn into_brain(self) -> Brain {
        self.brain
    }

    /// The brain outputs of the last [`Controller::act`] (zeros before the first).
    pub fn last_outputs(&self) -> &[f64] {
        &self.outputs
    }

    /// Clears the brain's recurrent state, as at the start of a trial.
    pub fn reset(&mut self) {
        self.brain.reset();
        self.outputs.fill(0.0);
    }
}

impl Controller for BrainController {
    fn act(&mut self, observation: &[f64]) -> MotorCommand {
        self.brain.activate(observation, &mut self.outputs);
        let out = &self.outputs;
        MotorCommand {
            left: out[0] * self.max_rpt,
            right: out[1] * self.max_rpt,
            eat: if self.eat_output {
                (out[2] + 1.0) / 2.0
            } else {
                0.0
            },
        }
    }
}
