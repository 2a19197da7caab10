//! The continuous-time recurrent neural network (Beer 1995), integrated with Euler steps.
//!
//! N fully connected neurons (self-connections included), each with a state y_i, a time
//! constant τ_i, a bias θ_i and a gain g_i. Its firing rate is s_i = σ(g_i (y_i + θ_i)) with
//! σ the logistic function, and its state follows
//!
//! ```text
//! τ_i dy_i/dt = -y_i + Σ_j w_ij s_j + I_i,     I_i = Σ_k w_in[i][k] x_k
//! ```
//!
//! Every sensor input x_k is weighted into every neuron (Beer's sensory inputs): there are no
//! dedicated sensor neurons, and evolution decides which neurons listen to what. One world
//! tick computes I once from the observation, then takes `substeps` Euler steps of size
//! dt = `step`, each synchronous (all rates from the old states, then all states updated):
//!
//! ```text
//! y_i ← y_i + (dt/τ_i) ((-y_i + Σ_j w_ij s_j) + I_i)
//! ```
//!
//! Both sums run across neurons with [`accumulate`] over input-major copies of the weight
//! matrices made once at construction: `I_i = 0 + w_in[i][0] x_0 + w_in[i][1] x_1 + …` and
//! `Σ_j w_ij s_j = 0 + w_i0 s_0 + w_i1 s_1 + …`, each the plain left-to-right sum. σ is the fast
//! [`logistic`] (max error 2.8e-10, see [`super::activation`]), for firing rates, outputs and
//! the gene mappings below alike.
//!
//! Motor output o is read from neuron o (neurons 0, 1 and, with an eat output, 2) as
//! 2 s_o − 1 ∈ [−1, 1], from the state after the tick's last step. [`Ctrnn::reset`] sets every
//! state to 0.
//!
//! # From genes to parameters
//!
//! Weights and biases are genes as they are. Time constants and gains are genes squashed into
//! their configured ranges, so that every finite gene vector is a valid network:
//! τ = τ_min (τ_max/τ_min)^σ(gene) (log scale: gene 0 gives the geometric middle) and
//! g = g_min + (g_max − g_min) σ(gene), both clamped into their range against rounding.
//! Validation guarantees dt ≤ τ_min, so dt/τ_i ≤ 1 for every neuron and each Euler step moves
//! a state at most all the way to its target: the integration cannot oscillate or diverge
//! for any genes.

use super::activation::{accumulate, logistic, nan_to_zero, transpose};
use super::spec::CtrnnSettings;

/// The time constant a gene encodes: τ_min (τ_max/τ_min)^σ(gene), within [τ_min, τ_max] for
/// every gene (±∞ included; NaN is refused before it gets here). `range` = [τ_min, τ_max],
/// 0 < τ_min ≤ τ_max.
pub fn time_constant(gene: f64, range: [f64; 2]) -> f64 {
    let [lo, hi] = range;
    (lo * libm::pow(hi / lo, logistic(gene))).clamp(lo, hi)
}

/// The gain a gene encodes: g_min + (g_max − g_min) σ(gene), within [g_min, g_max] for every
/// gene. `range` = [g_min, g_max], 0 ≤ g_min ≤ g_max.
pub fn gain(gene: f64, range: [f64; 2]) -> f64 {
    let [lo, hi] = range;
    (lo + (hi - lo) * logistic(gene)).clamp(lo, hi)
}

/// A CTRNN with its parameters, state and scratch buffers.
#[derive(Debug, Clone, PartialEq)]
pub struct Ctrnn {
    inputs: usize,
    neurons: usize,
    outputs: usize,
    substeps: usize,
    parameters: Vec<f64>,
    /// w_in transposed to input-major order (inputs × N): the weights from input k are
    /// contiguous.
    input_weights: Vec<f64>,
    /// w transposed (N × N, element `[j * N + i]` = w_ij): the weights from neuron j are
    /// contiguous.
    weights: Vec<f64>,
    /// τ_i, decoded from the genes.
    tau: Vec<f64>,
    /// dt/τ_i, each in (0, 1].
    rate: Vec<f64>,
    /// g_i, decoded from the genes.
    gain: Vec<f64>,
    /// The states y_i.
    state: Vec<f64>,
    /// Scratch: the firing rates s_j of the current Euler step.
    firing: Vec<f64>,
    /// Scratch: the external inputs I_i of the current tick.
    external: Vec<f64>,
    /// Scratch: the recurrent inputs Σ_j w_ij s_j of the current Euler step.
    recurrent: Vec<f64>,
}

impl Ctrnn {
    /// Builds the network with all states 0; `parameters.len()` must be the topology's
    /// parameter count (checked by [`crate::brain::Brain::new`]).
    pub(crate) fn new(
        inputs: usize,
        outputs: usize,
        settings: &CtrnnSettings,
        parameters: &[f64],
    ) -> Ctrnn {
        let n = settings.neurons;
        debug_assert_eq!(parameters.len(), n * inputs + n * n + 3 * n);
        let genes = &parameters[n * inputs + n * n + n..];
        let (tau_genes, gain_genes) = genes.split_at(n);
        let tau: Vec<f64> = tau_genes
            .iter()
            .map(|&g| time_constant(g, settings.tau))
            .collect();
        let rate = tau.iter().map(|&t| settings.step / t).collect();
        let gain = gain_genes.iter().map(|&g| gain(g, settings.gain)).collect();
        let input_weights = transpose(&parameters[..n * inputs], n, inputs);
        let weights = transpose(&parameters[n * inputs..n * inputs + n * n], n, n);
        Ctrnn {
            inputs,
            neurons: n,
            outputs,
            substeps: settings.substeps,
            parameters: parameters.to_vec(),
            input_weights,
            weights,
            tau,
            rate,
            gain,
            state: vec![0.0; n],
            firing: vec![0.0; n],
            external: vec![0.0; n],
            recurrent: vec![0.0; n],
        }
    }

    /// The parameters (genes), exactly as given.
    pub fn parameters(&self) -> &[f64] {
        &self.parameters
    }

    /// Number of inputs.
    pub fn inputs(&self) -> usize {
        self.inputs
    }

    /// Number of neurons N.
    pub fn neurons(&self) -> usize {
        self.neurons
    }

    /// Number of outputs (read from neurons 0..outputs).
    pub fn outputs(&self) -> usize {
        self.outputs
    }

    /// The time constants τ_i decoded from the genes.
    pub fn time_constants(&self) -> &[f64] {
        &self.tau
    }

    /// The gains g_i decoded from the genes.
    pub fn gains(&self) -> &[f64] {
        &self.gain
    }

    /// The biases θ_i.
    pub fn biases(&self) -> &[f64] {
        let start = self.neurons * (self.inputs + self.neurons);
        &self.parameters[start..start + self.neurons]
    }

    /// The states y_i.
    pub fn state(&self) -> &[f64] {
        &self.state
    }

    /// Sets the states (for dynamical analysis and tests); `state.len()` must be N.
    ///
    /// # Panics
    /// When `state.len()` is not the number of neurons.
    pub fn set_state(&mut self, state: &[f64]) {
        self.state.copy_from_slice(state);
    }

    /// Sets every state to 0, as at the start of a trial.
    pub fn reset(&mut self) {
        self.state.fill(0.0);
    }

    /// One world tick: `substeps` Euler steps, then the outputs. `inputs` and `outputs` must
    /// have the network's sizes.
    pub(crate) fn activate(&mut self, inputs: &[f64], outputs: &mut [f64]) {
        let n = self.neurons;
        let bias = &self.parameters[n * (self.inputs + n)..n * (self.inputs + n + 1)];
        self.external.fill(0.0);
        accumulate(&self.input_weights, inputs, &mut self.external);
        for _ in 0..self.substeps {
            for (((s, y), b), g) in self
                .firing
                .iter_mut()
                .zip(&self.state)
                .zip(bias)
                .zip(&self.gain)
            {
                *s = logistic(g * (y + b));
            }
            self.recurrent.fill(0.0);
            accumulate(&self.weights, &self.firing, &mut self.recurrent);
            for (((y, w), r), e) in self
                .state
                .iter_mut()
                .zip(&self.recurrent)
                .zip(&self.rate)
                .zip(&self.external)
            {
                *y += r * ((-*y + w) + e);
            }
        }
        for (o, out) in outputs[..self.outputs].iter_mut().enumerate() {
            let s = logistic(self.gain[o] * (self.state[o] + bias[o]));
            *out = nan_to_zero(2.0 * s - 1.0);
        }
    }
}
