//! Brains: the neural-network controllers that genomes encode (MLP, Elman recurrent network,
//! CTRNN), the `[brain]` table that chooses one, and the controller that drives a creature.
//!
//! A [`Topology`] (the [`BrainSpec`] plus the numbers of inputs and outputs) fixes how many
//! parameters a genome carries and what each means (see [`Topology`] for the layout).
//! [`Brain::new`] decodes a parameter vector; [`Brain::parameters`] gives it back bit for bit.
//! Every finite parameter vector of the right length is a valid brain, whose outputs are
//! always in [-1, 1].
//!
//! [`Brain::activate`] runs once per creature per tick, millions of times per second: it
//! allocates nothing (each brain keeps its scratch buffers), and it gives the same bits on
//! every platform and thread count. The genome stores weights row-major per receiving unit,
//! but each brain also keeps an input-major copy made at construction, so that a layer is
//! computed across units ([`activation::affine`]: y = b, then y += x_i · (weights from input
//! i) for each input in index order, a vectorised axpy that sums every unit plainly left to
//! right). Activations are the fast rational [`activation::tanh`] (max error 5.4e-10) and
//! the [`activation::logistic`] built on it, written in plain f64 arithmetic without branches
//! so that they vectorise too; `libm` is only used where a brain is built (CTRNN time
//! constants).
//!
//! An MLP keeps no state, so one brain can drive the creatures of several trial worlds in
//! lockstep: [`Brain::activate_batch`] (and [`BrainController::act_batch`]) run n observations
//! through each layer as one matrix-matrix product, tiles of 4 samples × blocks of units with
//! the tile's sums in registers, so that each weight load serves several samples. Each
//! observation's outputs are bit-identical to [`Brain::activate`] on it alone, and once the
//! scratch has grown to the largest batch, a batch allocates nothing (see [`mlp`]).
//!
//! `precision = "f32"` (MLP only, opt-in because it changes results) computes the MLP's sums
//! in single precision, as float32 frameworks such as EvoJAX do: parameters rounded to f32
//! once at construction (the genome stays f64), inputs rounded on every pass, the same
//! summation order with each term a fused multiply-add (one rounding, exactly specified by
//! IEEE 754), activation functions in f64 on the widened sum, rounded back. It is as
//! deterministic as f64 and runs 8 lanes per AVX2+FMA register ([`mlp`] documents the
//! details).
//! The key belongs to the `[brain]` table, so genome files and checkpointed experiments
//! carry it; left unset it is not written, so older files read and hash as before.

pub mod ablation;
pub mod activation;
pub mod controller;
pub mod ctrnn;
pub mod genome;
mod lanes;
pub mod mlp;
pub mod plasticity;
pub mod recurrent;
pub mod spec;
pub mod summary;

pub use activation::Activation;
pub use controller::{output_count, BrainController};
pub use ctrnn::Ctrnn;
pub use genome::Genome;
pub use mlp::Mlp;
pub use plasticity::{LifeKey, Plasticity, SignalInputs};
pub use recurrent::Elman;
pub use spec::{BrainKind, BrainSpec, Precision, Topology};

use crate::validate::InvalidValue;
use spec::Architecture;
use thiserror::Error;

/// Why a parameter vector could not become a brain.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum BrainError {
    /// The topology itself is invalid (see [`Topology::validate`]); the message is the
    /// invalid value's, which names the `brain.*` key.
    #[error(transparent)]
    Topology(#[from] InvalidValue),
    /// The parameter vector does not have the topology's length.
    #[error("wrong number of brain parameters: the topology needs {expected}, got {got}")]
    ParameterCount {
        /// The topology's parameter count.
        expected: usize,
        /// The length of the vector given.
        got: usize,
    },
    /// A parameter is NaN or infinite.
    #[error("brain parameter {index} (`{name}`) is not finite: {value}")]
    NonFinite {
        /// Its index in the vector.
        index: usize,
        /// Its name (see [`Topology::parameter_names`]).
        name: String,
        /// The value.
        value: f64,
    },
    /// A controller was given a brain with the wrong number of outputs.
    #[error(
        "the brain has {got} outputs but the controller needs {expected} \
         (left, right{})", if *expected == 3 { ", eat" } else { "" }
    )]
    OutputCount {
        /// [`output_count`] for the controller's eat setting.
        expected: usize,
        /// The brain's number of outputs.
        got: usize,
    },
}

/// A network decoded from a parameter vector, with its own state and scratch buffers.
#[derive(Debug, Clone, PartialEq)]
pub enum Brain {
    /// Feed-forward multilayer perceptron.
    Mlp(Mlp),
    /// Elman recurrent network.
    Recurrent(Elman),
    /// Continuous-time recurrent neural network.
    Ctrnn(Ctrnn),
}

impl Brain {
    /// Decodes `parameters` (in the order [`Topology`] documents) into a brain with a reset
    /// state. Errors when the topology is invalid, when the vector's length is not
    /// [`Topology::parameter_count`], or when a parameter is NaN or infinite.
    pub fn new(topology: &Topology, parameters: &[f64]) -> Result<Brain, BrainError> {
        topology.validate()?;
        let expected = topology.parameter_count();
        if parameters.len() != expected {
            return Err(BrainError::ParameterCount {
                expected,
                got: parameters.len(),
            });
        }
        if let Some(index) = parameters.iter().position(|p| !p.is_finite()) {
            let name = topology.parameter_names().swap_remove(index);
            return Err(BrainError::NonFinite {
                index,
                name,
                value: parameters[index],
            });
        }
        let (n, m) = (topology.inputs, topology.outputs);
        Ok(match topology.spec.architecture() {
            Architecture::Mlp {
                hidden,
                activation,
                precision,
            } => match topology.spec.plastic_settings() {
                None => Brain::Mlp(Mlp::new(n, &hidden, m, activation, precision, parameters)),
                Some(settings) => {
                    // The fixed network's share of the genome (none with random initial
                    // weights: zeros stand in, the first reset draws the weights).
                    let fixed = Topology {
                        spec: BrainSpec {
                            hidden: Some(hidden.clone()),
                            activation: Some(activation),
                            ..BrainSpec::default()
                        },
                        inputs: n,
                        outputs: m,
                        signals: SignalInputs::default(),
                    }
                    .parameter_count();
                    let zeros;
                    let (base, genes) = match settings.initial {
                        plasticity::InitialWeights::Evolved => parameters.split_at(fixed),
                        plasticity::InitialWeights::Random => {
                            zeros = vec![0.0; fixed];
                            (&zeros[..], parameters)
                        }
                    };
                    Brain::Mlp(Mlp::new_plastic(
                        (n, &hidden, m),
                        activation,
                        &settings,
                        &topology.signals,
                        (parameters, base, genes),
                    ))
                }
            },
            Architecture::Recurrent { hidden, activation } => {
                Brain::Recurrent(Elman::new(n, hidden, m, activation, parameters))
            }
            Architecture::Ctrnn(settings) => Brain::Ctrnn(Ctrnn::new(n, m, &settings, parameters)),
        })
    }

    /// The parameter vector, bit for bit as given to [`Brain::new`].
    pub fn parameters(&self) -> Vec<f64> {
        self.parameter_slice().to_vec()
    }

    /// The parameter vector, borrowed.
    pub fn parameter_slice(&self) -> &[f64] {
        match self {
            Brain::Mlp(b) => b.parameters(),
            Brain::Recurrent(b) => b.parameters(),
            Brain::Ctrnn(b) => b.parameters(),
        }
    }

    /// Which kind of network this is.
    pub fn kind(&self) -> BrainKind {
        match self {
            Brain::Mlp(_) => BrainKind::Mlp,
            Brain::Recurrent(_) => BrainKind::Recurrent,
            Brain::Ctrnn(_) => BrainKind::Ctrnn,
        }
    }

    /// Number of inputs [`Brain::activate`] expects.
    pub fn inputs(&self) -> usize {
        match self {
            Brain::Mlp(b) => b.inputs(),
            Brain::Recurrent(b) => b.inputs(),
            Brain::Ctrnn(b) => b.inputs(),
        }
    }

    /// Number of outputs [`Brain::activate`] writes.
    pub fn outputs(&self) -> usize {
        match self {
            Brain::Mlp(b) => b.outputs(),
            Brain::Recurrent(b) => b.outputs(),
            Brain::Ctrnn(b) => b.outputs(),
        }
    }

    /// The start of a life: clears the recurrent state (Elman context units and CTRNN states
    /// to 0) and restores a plastic MLP's weights (the genome's, or its life's random draw,
    /// see [`plasticity`]). Nothing else restores plastic weights, so a brain that lives
    /// several episodes keeps what it learned between them. A fixed MLP has no state.
    pub fn reset(&mut self) {
        match self {
            Brain::Mlp(b) => b.reset(),
            Brain::Recurrent(b) => b.reset(),
            Brain::Ctrnn(b) => b.reset(),
        }
    }

    /// True when the brain keeps no state from one tick to the next (an MLP): one such brain
    /// can then drive the creatures of several trial worlds at once with
    /// [`Brain::activate_batch`].
    pub fn is_stateless(&self) -> bool {
        matches!(self, Brain::Mlp(b) if !b.is_plastic())
    }

    /// A plastic brain's live weights (input-major per weight layer, hidden layers then the
    /// output layer, as [`Mlp::live_weights`]); None for a brain whose weights are fixed.
    /// Only reads: what a trace records after each tick.
    pub fn plastic_weights(&self) -> Option<&[f64]> {
        match self {
            Brain::Mlp(b) => b.plastic_weights(),
            _ => None,
        }
    }

    /// A neuromodulated brain's modulatory signal m of its last tick (gate g = tanh(m/2));
    /// None for other brains.
    pub fn last_modulation(&self) -> Option<f64> {
        match self {
            Brain::Mlp(b) => b.last_modulation(),
            _ => None,
        }
    }

    /// Tells a plastic brain with random initial weights which life it lives (its weights
    /// are drawn from that life's stream, see [`LifeKey`]) and resets it; other brains
    /// ignore it (their reset does not depend on the life).
    pub fn start_life(&mut self, life: LifeKey) {
        if let Brain::Mlp(b) = self {
            b.start_life(life);
        }
    }

    /// [`Brain::activate`] for `n` observations at once: `inputs` holds n × inputs values (one
    /// observation after another), `outputs` receives n × outputs. Each observation's outputs
    /// have exactly the bits [`Brain::activate`] gives it alone.
    ///
    /// # Panics
    /// When the brain is not [stateless](Brain::is_stateless) (its state belongs to one
    /// life), or when the lengths are not whole multiples of the brain's sizes for the same n
    /// (programming errors).
    pub fn activate_batch(&mut self, inputs: &[f64], outputs: &mut [f64]) {
        let (n_in, n_out) = (self.inputs(), self.outputs());
        // A brain without inputs (allowed, if useless) takes its batch size from the outputs.
        let n = inputs
            .len()
            .checked_div(n_in)
            .or_else(|| outputs.len().checked_div(n_out))
            .unwrap_or(0);
        assert_eq!(inputs.len(), n * n_in, "brain batch input count");
        assert_eq!(outputs.len(), n * n_out, "brain batch output count");
        match self {
            Brain::Mlp(b) if !b.is_plastic() => b.activate_batch(inputs, outputs),
            Brain::Mlp(_) | Brain::Recurrent(_) | Brain::Ctrnn(_) => {
                panic!("a recurrent brain's state belongs to one life: it cannot run a batch")
            }
        }
    }

    /// One tick: reads `inputs`, writes `outputs`, each output in [-1, 1]. Allocates nothing.
    ///
    /// # Panics
    /// When `inputs.len()` or `outputs.len()` is not the brain's number of inputs or outputs
    /// (a programming error: both are fixed when the topology is built).
    #[inline]
    pub fn activate(&mut self, inputs: &[f64], outputs: &mut [f64]) {
        assert_eq!(inputs.len(), self.inputs(), "brain input count");
        assert_eq!(outputs.len(), self.outputs(), "brain output count");
        match self {
            Brain::Mlp(b) => b.activate(inputs, outputs),
            Brain::Recurrent(b) => b.activate(inputs, outputs),
            Brain::Ctrnn(b) => b.activate(inputs, outputs),
        }
    }
}
