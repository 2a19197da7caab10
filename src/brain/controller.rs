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

    /// True when every command this controller gives is finite, whatever the observation:
    /// an MLP's outputs are always in [−1, 1] (a NaN output becomes 0, see
    /// [`crate::brain::activation::tanh_outputs`]), so with a finite `max_rpt` the motor
    /// signals are at most ±`max_rpt` (|o · max_rpt| ≤ |max_rpt| after rounding too) and
    /// eat = (o + 1) / 2 is in [0, 1]. The lockstep then skips its per-command check.
    pub fn commands_always_finite(&self) -> bool {
        self.brain.is_stateless() && self.max_rpt.is_finite()
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

impl BrainController {
    /// The motor command for brain outputs `out` (see the module docs).
    #[inline]
    fn command(&self, out: &[f64]) -> MotorCommand {
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

    /// [`Controller::act`] for several observations at once, for a
    /// [stateless](Brain::is_stateless) brain shared by several trial worlds: `observations`
    /// holds `commands.len()` observations one after another, and command k is exactly what
    /// `act` would give for observation k. [`BrainController::last_outputs`] afterwards holds
    /// every observation's outputs. The output buffer grows to the largest batch seen, so
    /// after the first tick this allocates nothing.
    ///
    /// # Panics
    /// When the brain keeps state (see [`Brain::activate_batch`]).
    pub fn act_batch(&mut self, observations: &[f64], commands: &mut [MotorCommand]) {
        let m = self.brain.outputs();
        let n = commands.len();
        if self.outputs.len() != n * m {
            self.outputs.resize(n * m, 0.0);
        }
        let mut outputs = std::mem::take(&mut self.outputs);
        self.brain.activate_batch(observations, &mut outputs);
        for (command, out) in commands.iter_mut().zip(outputs.chunks_exact(m)) {
            *command = self.command(out);
        }
        self.outputs = outputs;
    }
}

impl Controller for BrainController {
    fn act(&mut self, observation: &[f64]) -> MotorCommand {
        let m = self.brain.outputs();
        if self.outputs.len() != m {
            // After a batch the buffer held another number of observations' outputs.
            self.outputs.resize(m, 0.0);
        }
        self.brain.activate(observation, &mut self.outputs);
        self.command(&self.outputs)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::brain::spec::{BrainSpec, Topology};

    /// A batch gives every observation the command `act` gives it alone, and `act` still
    /// works after batches of any size, the empty one included.
    #[test]
    fn batches_match_single_observations() {
        let spec: BrainSpec = toml::from_str("kind = \"mlp\"\nhidden = [5]").expect("spec");
        let topology = Topology::new(spec, 4, 3).expect("topology");
        let parameters: Vec<f64> = (0..topology.parameter_count())
            .map(|k| ((k * 37 % 23) as f64 - 11.0) / 7.0)
            .collect();
        let brain = Brain::new(&topology, &parameters).expect("brain");
        let mut batch = BrainController::new(brain.clone(), 0.5, true);
        let mut single = BrainController::new(brain, 0.5, true);
        let observations: Vec<f64> = (0..4 * 6).map(|k| libm::sin(k as f64 * 0.37)).collect();
        for n in [6, 0, 2, 6] {
            let mut commands = vec![MotorCommand::default(); n];
            batch.act_batch(&observations[..4 * n], &mut commands);
            for (k, command) in commands.iter().enumerate() {
                assert_eq!(*command, single.act(&observations[4 * k..4 * k + 4]));
            }
            assert_eq!(
                batch.act(&observations[..4]),
                single.act(&observations[..4])
            );
        }
    }

    /// An MLP controller with a finite `max_rpt` knows its commands are finite, and they
    /// are, even for parameters and observations that overflow every sum; recurrent brains
    /// and an infinite `max_rpt` do not claim it.
    #[test]
    fn mlp_commands_are_always_finite() {
        let topology = |text: &str| {
            let spec: BrainSpec = toml::from_str(text).expect("spec");
            Topology::new(spec, 4, 3).expect("topology")
        };
        let mlp = topology("kind = \"mlp\"\nhidden = [5]");
        let values = [1e308, -1e308, 0.0, -0.0, 3.5, f64::MAX, f64::MIN];
        for (round, max_rpt) in [0.5, 1e308, f64::MAX].into_iter().enumerate() {
            let parameters: Vec<f64> = (0..mlp.parameter_count())
                .map(|k| values[(k * 3 + round) % values.len()])
                .collect();
            let brain = Brain::new(&mlp, &parameters).expect("brain");
            let mut controller = BrainController::new(brain, max_rpt, true);
            assert!(controller.commands_always_finite());
            let observations: Vec<f64> = (0..4 * 9).map(|k| values[k % values.len()]).collect();
            let mut commands = vec![MotorCommand::default(); 9];
            controller.act_batch(&observations, &mut commands);
            for c in commands {
                assert!(c.left.is_finite() && c.right.is_finite() && c.eat.is_finite());
            }
        }
        let brain = Brain::new(&mlp, &vec![0.5; mlp.parameter_count()]).expect("brain");
        assert!(!BrainController::new(brain, f64::INFINITY, true).commands_always_finite());
        let elman = topology("kind = \"recurrent\"\nhidden = [3]");
        let brain = Brain::new(&elman, &vec![0.5; elman.parameter_count()]).expect("brain");
        assert!(!BrainController::new(brain, 0.5, true).commands_always_finite());
    }
}
