//! The feed-forward multilayer perceptron: hidden layers of a configurable activation, then
//! tanh output units.
//!
//! Each unit computes `act(dot(w_row, x) + b)` with [`dot`]'s fixed summation order; the
//! weights live in the parameter vector itself (layout in [`crate::brain::Topology`]), so a
//! row is a contiguous slice and [`Mlp::parameters`] is an exact copy.

use super::activation::{dot, nan_to_zero, Activation};
use std::ops::Range;

/// One layer's place in the parameter vector and in the activation buffer.
#[derive(Debug, Clone, PartialEq)]
struct Layer {
    inputs: usize,
    units: usize,
    /// Offset of the weight matrix (units × inputs, row-major) in the parameters.
    weights: usize,
    /// Offset of the biases in the parameters.
    biases: usize,
    /// Where the layer's activations are kept in `activations` (hidden layers only).
    out: Range<usize>,
}

/// A multilayer perceptron with its parameters and scratch buffers.
#[derive(Debug, Clone, PartialEq)]
pub struct Mlp {
    inputs: usize,
    outputs: usize,
    activation: Activation,
    parameters: Vec<f64>,
    hidden: Vec<Layer>,
    output: Layer,
    /// Every hidden layer's activations, one after another (preallocated scratch).
    activations: Vec<f64>,
}

impl Mlp {
    /// Builds the network; `parameters.len()` must be the topology's parameter count (checked
    /// by [`crate::brain::Brain::new`]).
    pub(crate) fn new(
        inputs: usize,
        hidden: &[usize],
        outputs: usize,
        activation: Activation,
        parameters: &[f64],
    ) -> Mlp {
        let mut offset = 0;
        let mut buffer = 0;
        let mut previous = inputs;
        let mut layer = |units: usize, previous: usize, buffer: &mut usize| {
            let weights = offset;
            let biases = weights + units * previous;
            offset = biases + units;
            let out = *buffer..*buffer + units;
            *buffer += units;
            Layer {
                inputs: previous,
                units,
                weights,
                biases,
                out,
            }
        };
        let mut layers = Vec::with_capacity(hidden.len());
        for &units in hidden {
            layers.push(layer(units, previous, &mut buffer));
            previous = units;
        }
        let output = layer(outputs, previous, &mut 0);
        debug_assert_eq!(offset, parameters.len());
        Mlp {
            inputs,
            outputs,
            activation,
            parameters: parameters.to_vec(),
            hidden: layers,
            output,
            activations: vec![0.0; buffer],
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

    /// Number of outputs.
    pub fn outputs(&self) -> usize {
        self.outputs
    }

    /// The hidden units' activation function.
    pub fn activation(&self) -> Activation {
        self.activation
    }

    /// One forward pass. `inputs` and `outputs` must have the network's sizes.
    pub(crate) fn activate(&mut self, inputs: &[f64], outputs: &mut [f64]) {
        let params = &self.parameters;
        let mut previous: Range<usize> = 0..0;
        for (l, layer) in self.hidden.iter().enumerate() {
            // Earlier layers sit before this one in the buffer: split to read and write.
            let (done, rest) = self.activations.split_at_mut(layer.out.start);
            let x = if l == 0 { inputs } else { &done[previous] };
            let y = &mut rest[..layer.units];
            match self.activation {
                Activation::Tanh => forward(params, layer, x, y, libm::tanh),
                Activation::Sigmoid => forward(params, layer, x, y, super::activation::logistic),
                Activation::Relu => forward(params, layer, x, y, super::activation::relu),
            }
            previous = layer.out.clone();
        }
        let x = if self.hidden.is_empty() {
            inputs
        } else {
            &self.activations[previous]
        };
        forward(params, &self.output, x, outputs, |a| {
            nan_to_zero(libm::tanh(a))
        });
    }
}

/// y_j = f(dot(W_j, x) + b_j) for every unit j of `layer`.
#[inline(always)]
fn forward(params: &[f64], layer: &Layer, x: &[f64], y: &mut [f64], f: impl Fn(f64) -> f64) {
    let n = layer.inputs;
    let weights = &params[layer.weights..layer.weights + layer.units * n];
    let biases = &params[layer.biases..layer.biases + layer.units];
    let x = &x[..n];
    if n == 0 {
        // chunks_exact(0) would panic; a layer without inputs is its biases.
        for (y, b) in y.iter_mut().zip(biases) {
            *y = f(0.0 + b);
        }
        return;
    }
    for ((y, row), b) in y.iter_mut().zip(weights.chunks_exact(n)).zip(biases) {
        *y = f(dot(row, x) + b);
    }
}
