//! The Elman network: one hidden layer whose activations from the previous tick are fed back
//! as extra inputs (context units), then tanh output units.
//!
//! Each tick, with x the inputs and c the context (the previous tick's hidden activations, 0
//! after [`Elman::reset`]):
//!
//! ```text
//! h_j = act(dot(W_h[j], [x, c]) + b_h[j])      for every hidden unit j
//! o_k = tanh(dot(W_out[k], h) + b_out[k])      for every output k
//! c   = h
//! ```
//!
//! A hidden unit's input and context weights are one contiguous row of the parameter vector
//! (layout in [`crate::brain::Topology`]), dotted with the buffer `[x, c]`.

use super::activation::{dot, logistic, nan_to_zero, relu, Activation};

/// An Elman network with its parameters, context and scratch buffers.
#[derive(Debug, Clone, PartialEq)]
pub struct Elman {
    inputs: usize,
    hidden: usize,
    outputs: usize,
    activation: Activation,
    parameters: Vec<f64>,
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
        Elman {
            inputs,
            hidden,
            outputs,
            activation,
            parameters: parameters.to_vec(),
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
        let (n, h) = (self.inputs, self.hidden);
        self.extended[..n].copy_from_slice(inputs);
        let row = n + h;
        let (hidden_part, output_part) = self.parameters.split_at(h * (row + 1));
        let (weights, biases) = hidden_part.split_at(h * row);
        let x = &self.extended[..];
        let y = &mut self.current[..];
        match self.activation {
            Activation::Tanh => hidden_layer(weights, biases, row, x, y, libm::tanh),
            Activation::Sigmoid => hidden_layer(weights, biases, row, x, y, logistic),
            Activation::Relu => hidden_layer(weights, biases, row, x, y, relu),
        }
        let (weights, biases) = output_part.split_at(self.outputs * h);
        for (o, out) in outputs[..self.outputs].iter_mut().enumerate() {
            let a = dot(&weights[o * h..(o + 1) * h], &self.current) + biases[o];
            *out = nan_to_zero(libm::tanh(a));
        }
        self.extended[n..].copy_from_slice(&self.current);
    }
}

/// y_j = f(dot(W[j], x) + b_j), rows of length `row`.
#[inline(always)]
fn hidden_layer(
    weights: &[f64],
    biases: &[f64],
    row: usize,
    x: &[f64],
    y: &mut [f64],
    f: impl Fn(f64) -> f64,
) {
    for (j, (y, b)) in y.iter_mut().zip(biases).enumerate() {
        *y = f(dot(&weights[j * row..(j + 1) * row], x) + b);
    }
}
