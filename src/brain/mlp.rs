//! The feed-forward multilayer perceptron: hidden layers of a configurable activation, then
//! tanh output units.
//!
//! Each layer computes `y = act(b + W x)` with [`affine`]: starting from the biases, it adds
//! each input's contribution to every unit at once, input by input in index order, so unit j's
//! pre-activation is the plain left-to-right sum `b_j + w_j0 x_0 + w_j1 x_1 + …`. Then the
//! activation runs over the whole layer ([`Activation::apply_slice`]). Both loops run across
//! units, which the compiler vectorises without reassociating any sum.
//!
//! The genome keeps its layout (units × inputs row-major per layer, see
//! [`crate::brain::Topology`]) and [`Mlp::parameters`] is an exact copy of it; the forward pass
//! reads an input-major copy of each weight matrix ([`transpose`]) built once at construction,
//! so that the weights leaving one input are contiguous.

use super::activation::{
    affine, affine_batch_portable, tanh_outputs, transpose, Activation, BATCH_TILE,
};
use std::ops::Range;

/// One layer's place in the parameter vector, the transposed weights and the activation
/// buffer.
#[derive(Debug, Clone, PartialEq)]
struct Layer {
    units: usize,
    /// The layer's input-major weights (inputs × units) in `transposed`.
    weights: Range<usize>,
    /// The biases in the parameters.
    biases: Range<usize>,
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
    /// Every layer's weights, transposed to input-major order (derived from `parameters`).
    transposed: Vec<f64>,
    hidden: Vec<Layer>,
    output: Layer,
    /// Every hidden layer's activations, one after another (preallocated scratch); a batch
    /// of n samples uses n times as much (see [`Mlp::activate_batch`]).
    activations: Vec<f64>,
    /// One tile of a batch's inputs to a layer, input-major ([`BATCH_TILE`] × the widest
    /// layer input; scratch for [`affine_batch_portable`]).
    tile: Vec<f64>,
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
        let mut transposed = Vec::with_capacity(parameters.len());
        let mut layer = |units: usize, previous: usize, buffer: &mut usize| {
            let weights = offset..offset + units * previous;
            let biases = weights.end..weights.end + units;
            offset = biases.end;
            let start = transposed.len();
            transposed.extend(transpose(&parameters[weights], units, previous));
            let out = *buffer..*buffer + units;
            *buffer += units;
            Layer {
                units,
                weights: start..transposed.len(),
                biases,
                out,
            }
        };
        let mut buffer = 0;
        let mut previous = inputs;
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
            transposed,
            hidden: layers,
            output,
            activations: vec![0.0; buffer],
            tile: vec![0.0; BATCH_TILE * hidden.iter().fold(inputs, |m, &h| m.max(h))],
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
    ///
    /// On x86-64 CPUs with AVX2 the whole pass (sums and activation functions) runs compiled
    /// for AVX2; the operations per value are the same, so are the bits (see
    /// [`super::activation`] and the test below).
    pub(crate) fn activate(&mut self, inputs: &[f64], outputs: &mut [f64]) {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: `forward_avx2` only requires the CPU to support AVX2, checked just above.
            unsafe { self.forward_avx2(inputs, outputs) };
            return;
        }
        self.forward(inputs, outputs);
    }

    /// [`Mlp::forward`] compiled for AVX2.
    ///
    /// # Safety
    /// The CPU must support AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn forward_avx2(&mut self, inputs: &[f64], outputs: &mut [f64]) {
        self.forward(inputs, outputs);
    }

    /// [`Mlp::activate`] for n samples at once: `inputs` holds n input vectors one after
    /// another, `outputs` receives n output vectors, and each sample's outputs have exactly the
    /// bits [`Mlp::activate`] gives it alone.
    ///
    /// Each layer is one matrix-matrix product ([`super::activation::affine_batch`]: tiles of
    /// samples × blocks of units, so that each weight load serves several samples), then the
    /// activation over the whole n × units block. The hidden activations of all n samples are
    /// kept in the scratch buffer, which grows to the largest batch seen and is never shrunk:
    /// once warmed up, a batch allocates nothing.
    ///
    /// # Panics
    /// When the lengths are not n × inputs and n × outputs for the same n.
    pub(crate) fn activate_batch(&mut self, inputs: &[f64], outputs: &mut [f64]) {
        // Without inputs (allowed, if useless) the batch size comes from the outputs.
        let n = inputs
            .len()
            .checked_div(self.inputs)
            .or_else(|| outputs.len().checked_div(self.outputs))
            .unwrap_or(0);
        assert_eq!(inputs.len(), n * self.inputs, "mlp batch input count");
        assert_eq!(outputs.len(), n * self.outputs, "mlp batch output count");
        if n == 1 {
            // One sample: nothing to share, and the single pass skips the tile copy.
            self.activate(inputs, outputs);
            return;
        }
        let needed = n * self.hidden.last().map_or(0, |layer| layer.out.end);
        if self.activations.len() < needed {
            self.activations.resize(needed, 0.0);
        }
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: `forward_batch_avx2` only requires the CPU to support AVX2, checked just
            // above.
            unsafe { self.forward_batch_avx2(inputs, outputs, n) };
            return;
        }
        self.forward_batch(inputs, outputs, n);
    }

    /// [`Mlp::forward_batch`] compiled for AVX2.
    ///
    /// # Safety
    /// The CPU must support AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn forward_batch_avx2(&mut self, inputs: &[f64], outputs: &mut [f64], n: usize) {
        self.forward_batch(inputs, outputs, n);
    }

    /// The batched forward pass for any CPU; the scratch buffer must hold n × (hidden units)
    /// values. Layer l's activations for the n samples occupy n × its `out` range (the ranges
    /// are prefix sums of the layer sizes, so scaling them by n keeps the layers apart).
    #[inline(always)]
    fn forward_batch(&mut self, inputs: &[f64], outputs: &mut [f64], n: usize) {
        let (params, weights) = (&self.parameters, &self.transposed);
        let mut previous: Range<usize> = 0..0;
        for (l, layer) in self.hidden.iter().enumerate() {
            let out = n * layer.out.start..n * layer.out.end;
            let (done, rest) = self.activations.split_at_mut(out.start);
            let x = if l == 0 { inputs } else { &done[previous] };
            let y = &mut rest[..out.len()];
            affine_batch_portable(
                &weights[layer.weights.clone()],
                &params[layer.biases.clone()],
                x,
                y,
                n,
                &mut self.tile,
            );
            self.activation.apply_slice(y);
            previous = out;
        }
        let x = if self.hidden.is_empty() {
            inputs
        } else {
            &self.activations[previous]
        };
        let out = &self.output;
        affine_batch_portable(
            &weights[out.weights.clone()],
            &params[out.biases.clone()],
            x,
            outputs,
            n,
            &mut self.tile,
        );
        tanh_outputs(outputs);
    }

    /// The forward pass for any CPU.
    #[inline(always)]
    fn forward(&mut self, inputs: &[f64], outputs: &mut [f64]) {
        let (params, weights) = (&self.parameters, &self.transposed);
        let mut previous: Range<usize> = 0..0;
        for (l, layer) in self.hidden.iter().enumerate() {
            // Earlier layers sit before this one in the buffer: split to read and write.
            let (done, rest) = self.activations.split_at_mut(layer.out.start);
            let x = if l == 0 { inputs } else { &done[previous] };
            let y = &mut rest[..layer.units];
            affine(
                &weights[layer.weights.clone()],
                &params[layer.biases.clone()],
                x,
                y,
            );
            self.activation.apply_slice(y);
            previous = layer.out.clone();
        }
        let x = if self.hidden.is_empty() {
            inputs
        } else {
            &self.activations[previous]
        };
        let out = &self.output;
        let y = &mut outputs[..out.units];
        affine(
            &weights[out.weights.clone()],
            &params[out.biases.clone()],
            x,
            y,
        );
        tanh_outputs(y);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Random networks of `topology` for every activation, drawn from a fixed stream.
    fn networks(seed: u64, inputs: usize, hidden: &[usize], outputs: usize) -> Vec<Mlp> {
        use crate::seed::{stream, uniform, Generation, IndividualId, Purpose, Seed, TrialIndex};
        let mut rng = stream(
            Seed(seed),
            Purpose::Baseline,
            Generation(0),
            IndividualId(0),
            TrialIndex(0),
        );
        let mut count = 0;
        let mut previous = inputs;
        for &h in hidden {
            count += h * previous + h;
            previous = h;
        }
        count += outputs * previous + outputs;
        [Activation::Tanh, Activation::Sigmoid, Activation::Relu]
            .into_iter()
            .map(|activation| {
                let parameters: Vec<f64> =
                    (0..count).map(|_| uniform(&mut rng, -3.0, 3.0)).collect();
                Mlp::new(inputs, hidden, outputs, activation, &parameters)
            })
            .collect()
    }

    fn bits(v: &[f64]) -> Vec<u64> {
        v.iter().map(|f| f.to_bits()).collect()
    }

    /// A batch gives every sample the bits of a single pass, for batch sizes around the tile
    /// size and its multiples and for unit counts that leave every block-size remainder, on
    /// the dispatched (AVX2 where available) and the portable batch paths alike.
    #[test]
    fn batch_matches_single_passes_bit_for_bit() {
        use crate::seed::{stream, uniform, Generation, IndividualId, Purpose, Seed, TrialIndex};
        let mut rng = stream(
            Seed(43),
            Purpose::Baseline,
            Generation(0),
            IndividualId(0),
            TrialIndex(0),
        );
        let topologies: [(usize, &[usize], usize); 6] = [
            (24, &[16], 2),
            (24, &[16], 3),
            (98, &[100], 2),
            (5, &[7, 3], 3),
            (1, &[], 2),
            (13, &[1, 15, 9], 7),
        ];
        let sizes: Vec<usize> = (0..=9).chain([16, 33]).collect();
        for (inputs, hidden, outputs) in topologies {
            for mut mlp in networks(44, inputs, hidden, outputs) {
                let mut single = mlp.clone();
                let mut portable = mlp.clone();
                // Sizes up and down: the scratch grows, then smaller batches reuse it.
                for &n in sizes.iter().chain(sizes.iter().rev()) {
                    let x: Vec<f64> = (0..n * inputs)
                        .map(|_| uniform(&mut rng, -3.0, 3.0))
                        .collect();
                    let mut expected = vec![0.0; n * outputs];
                    for (xs, ys) in x
                        .chunks_exact(inputs)
                        .zip(expected.chunks_exact_mut(outputs))
                    {
                        single.activate(xs, ys);
                    }
                    let mut batch = vec![f64::NAN; n * outputs];
                    mlp.activate_batch(&x, &mut batch);
                    let what = format!("{inputs} {hidden:?} {outputs} {:?} n={n}", mlp.activation);
                    assert_eq!(bits(&batch), bits(&expected), "{what}");
                    let needed = n * hidden.iter().sum::<usize>();
                    if portable.activations.len() < needed {
                        portable.activations.resize(needed, 0.0);
                    }
                    let mut by_portable = vec![f64::NAN; n * outputs];
                    portable.forward_batch(&x, &mut by_portable, n);
                    assert_eq!(bits(&by_portable), bits(&expected), "portable {what}");
                }
            }
        }
    }

    /// The batch scratch grows to the largest batch and is never shrunk, so a warmed-up brain
    /// serves any smaller batch without allocating.
    #[test]
    fn batch_scratch_grows_to_the_largest_batch_only() {
        let mut mlp = networks(45, 6, &[10, 4], 2).swap_remove(0);
        assert_eq!(mlp.activations.len(), 14);
        let tile = mlp.tile.len();
        assert_eq!(tile, BATCH_TILE * 10);
        let mut warm = None;
        for (n, len) in [(3, 42), (32, 448), (5, 448), (0, 448), (32, 448)] {
            let x = vec![0.25; n * 6];
            let mut y = vec![0.0; n * 2];
            mlp.activate_batch(&x, &mut y);
            assert_eq!(mlp.activations.len(), len, "n = {n}");
            assert_eq!(mlp.tile.len(), tile);
            if n == 32 {
                // The same buffer once warmed up: no reallocation.
                let address = mlp.activations.as_ptr();
                assert_eq!(*warm.get_or_insert(address), address);
            }
        }
    }

    /// The AVX2 build of the forward pass gives the same bits as the portable one.
    #[test]
    fn dispatched_and_portable_passes_agree_bit_for_bit() {
        use crate::seed::{stream, uniform, Generation, IndividualId, Purpose, Seed, TrialIndex};
        let mut rng = stream(
            Seed(42),
            Purpose::Baseline,
            Generation(0),
            IndividualId(0),
            TrialIndex(0),
        );
        let mut next = || uniform(&mut rng, -3.0, 3.0);
        for (inputs, hidden, outputs) in [(24, vec![16], 2), (98, vec![100], 2), (5, vec![7, 3], 3)]
        {
            for activation in [Activation::Tanh, Activation::Sigmoid, Activation::Relu] {
                let mut count = 0;
                let mut previous = inputs;
                for &h in &hidden {
                    count += h * previous + h;
                    previous = h;
                }
                count += outputs * previous + outputs;
                let parameters: Vec<f64> = (0..count).map(|_| next()).collect();
                let mut a = Mlp::new(inputs, &hidden, outputs, activation, &parameters);
                let mut b = a.clone();
                for _ in 0..20 {
                    let x: Vec<f64> = (0..inputs).map(|_| next()).collect();
                    let (mut ya, mut yb) = (vec![0.0; outputs], vec![0.0; outputs]);
                    a.activate(&x, &mut ya);
                    b.forward(&x, &mut yb);
                    let bits = |v: &[f64]| v.iter().map(|f| f.to_bits()).collect::<Vec<_>>();
                    assert_eq!(bits(&ya), bits(&yb), "{inputs} {hidden:?} {activation:?}");
                }
            }
        }
    }
}
