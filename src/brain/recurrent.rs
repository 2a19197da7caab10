//! The Elman network: one hidden layer whose activations from the previous tick are fed back
//! as extra inputs (context units), then tanh output units.
//!
//! Each tick, with x the inputs and c the context (the previous tick's hidden activations, 0
//! after [`Elman::reset`]):
//!
//! ```text
//! h = act(b_h + W_h [x, c])      (hidden units)
//! o = tanh(b_out + W_out h)      (outputs)
//! c = h
//! ```
//!
//! with `act` and `tanh` the fast kernels of [`super::activation`]. Both matrix products are
//! [`affine`]: each unit's sum is the plain left-to-right sum b_j + w_j0 v_0 + w_j1 v_1 + …
//! over the buffer v = `[x, c]` (inputs first, then context) or v = h, computed across units
//! from input-major copies of the weights made once at construction. A hidden unit's input and
//! context weights stay one contiguous row of the parameter vector (layout in
//! [`crate::brain::Topology`]), so [`Elman::parameters`] is an exact copy.

use super::activation::{affine, tanh_outputs, transpose, Activation};

/// An Elman network with its parameters, context and scratch buffers.
#[derive(Debug, Clone, PartialEq)]
pub struct Elman {
    inputs: usize,
    hidden: usize,
    outputs: usize,
    activation: Activation,
    parameters: Vec<f64>,
    /// W_h transposed to input-major order ((inputs + hidden) × hidden), from `parameters`.
    hidden_weights: Vec<f64>,
    /// W_out transposed to input-major order (hidden × outputs), from `parameters`.
    output_weights: Vec<f64>,
    /// [inputs of this tick, context = hidden activations of the previous tick].
    extended: Vec<f64>,
    /// Hidden activations of this tick.
    current: Vec<f64>,
}

impl Elman {
    /// Builds the network with a zero context; `parameters.len()` must be the topology's
    /// parameter count (checked by [`crate::brain::Brain::new`]).
    pub(crate) fn new(
        inputs: usize,
        hidden: usize,
        outputs: usize,
        activation: Activation,
        parameters: &[f64],
    ) -> Elman {
        debug_assert_eq!(
            parameters.len(),
            hidden * (inputs + hidden + 1) + outputs * (hidden + 1)
        );
        let row = inputs + hidden;
        let output_start = hidden * (row + 1);
        let hidden_weights = transpose(&parameters[..hidden * row], hidden, row);
        let output_weights = transpose(
            &parameters[output_start..output_start + outputs * hidden],
            outputs,
            hidden,
        );
        Elman {
            inputs,
            hidden,
            outputs,
            activation,
            parameters: parameters.to_vec(),
            hidden_weights,
            output_weights,
            extended: vec![0.0; inputs + hidden],
            current: vec![0.0; hidden],
        }
    }

    /// The parameters, exactly as given.
    pub fn parameters(&self) -> &[f64] {
        &self.parameters
    }

    /// Number of inputs.
    pub fn inputs(&self) -> usize {
        self.inputs
    }

    /// Number of hidden (and context) units.
    pub fn hidden(&self) -> usize {
        self.hidden
    }

    /// Number of outputs.
    pub fn outputs(&self) -> usize {
        self.outputs
    }

    /// The hidden units' activation function.
    pub fn activation(&self) -> Activation {
        self.activation
    }

    /// The context: the hidden activations of the last tick (zeros after a reset).
    pub fn context(&self) -> &[f64] {
        &self.extended[self.inputs..]
    }

    /// Sets the context units to 0, as at the start of a trial.
    pub fn reset(&mut self) {
        self.extended[self.inputs..].fill(0.0);
    }

    /// One tick. `inputs` and `outputs` must have the network's sizes.
    pub(crate) fn activate(&mut self, inputs: &[f64], outputs: &mut [f64]) {
        let (n, h, m) = (self.inputs, self.hidden, self.outputs);
        self.extended[..n].copy_from_slice(inputs);
        let row = n + h;
        let hidden_biases = &self.parameters[h * row..h * (row + 1)];
        let output_biases = &self.parameters[h * (row + 1) + m * h..];
        affine(
            &self.hidden_weights,
            hidden_biases,
            &self.extended,
            &mut self.current,
        );
        self.activation.apply_slice(&mut self.current);
        let y = &mut outputs[..m];
        affine(&self.output_weights, output_biases, &self.current, y);
        tanh_outputs(y);
        self.extended[n..].copy_from_slice(&self.current);
    }
}
