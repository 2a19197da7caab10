//! The feed-forward multilayer perceptron: hidden layers of a configurable activation, then
//! tanh output units.
//!
//! Each layer computes `y = act(b + W x)`: starting from the biases, it adds each input's
//! contribution to every unit at once, input by input in index order, so unit j's
//! pre-activation is the plain left-to-right sum `b_j + w_j0 x_0 + w_j1 x_1 + …` with separate
//! multiplies and adds (never a fused multiply-add). Then the activation runs over the whole
//! layer ([`Activation::apply_slice`]). Both loops run across units, which the compiler
//! vectorises without reassociating any sum, so the bits are the same on every CPU.
//!
//! The genome keeps its layout (units × inputs row-major per layer, see
//! [`crate::brain::Topology`]) and [`Mlp::parameters`] is an exact copy of it; the forward pass
//! reads an input-major copy of each weight matrix ([`transpose`]) built once at construction,
//! so that the weights leaving one input are contiguous.
//!
//! # Batches
//!
//! An MLP keeps no state, so one network can serve several trial worlds per tick:
//! [`crate::brain::Brain::activate_batch`] runs n observations through each layer as one
//! matrix-matrix product ([`super::activation::affine_batch`]). Samples go in tiles of 4 and units in
//! blocks of 8 (two AVX2 registers of f64); a tile × block of sums stays in registers while
//! the inputs are walked, so each weight load serves 4 samples, and for the last 1–3 units
//! (the motor outputs) one register holds the 4 samples' sums of one unit. Every sum keeps
//! the order above, so each sample's outputs are bit-identical to
//! [`crate::brain::Brain::activate`] on it alone. The scratch buffers grow to the largest
//! batch seen and are never shrunk: once warmed up, a batch allocates nothing.
//!
//! Small f64 networks (at most `lanes::MAX_WEIGHTS` weights, such as the standard
//! 24 → 16 → 2 brain) run batches of 4 or more samples through the sample-lane pass instead
//! (the private module `brain::lanes`): one register holds one unit's sums for 4 samples,
//! each weight is kept repeated in 4 lanes so that it is a memory operand of the multiply,
//! and the batch goes layer by layer in tiles of 4 samples. Same sums in the same order, so
//! the same bits. Its first layer also leaves out the inputs that are ±0 in every sample of
//! the batch, where that provably keeps every bit and saves instructions
//! (`lanes::LiveInputs`), and its tanh reads its constants from memory (`lanes::TanhLanes`).
//! What each of these saved is in docs/performance.md.
//!
//! # Precision
//!
//! `precision = "f64"` (the default) computes as above in f64. `precision = "f32"` (opt-in:
//! it changes results; meant for comparisons with float32 frameworks such as EvoJAX) keeps the
//! genome in f64 but rounds the parameters to f32 once when the brain is built (a parameter
//! beyond the f32 range becomes ±∞, which the output stage still maps into [-1, 1]) and the
//! inputs on every pass; every sum is then done in f32 in the same documented order (bias,
//! then inputs left to right), each term added by a fused multiply-add: s = b_j, then
//! s = fma(w_ji, x_i, s) for i = 0, 1, … (IEEE 754 fusedMultiplyAdd, one rounding per term).
//! An FMA is exactly specified, so the FMA instruction and `f32::mul_add`'s software fallback
//! give the same bits, and f32 results are deterministic across CPUs and thread counts too.
//! On x86-64 CPUs with AVX2 and FMA the pass is compiled for both (8 f32 per register, one
//! vfmadd per 8 terms); elsewhere the portable build calls `f32::mul_add` (same bits,
//! slower). Activations are applied by widening the f32 sum to f64, applying the f64 function
//! ([`super::activation::tanh`] etc., so their error bounds still hold) and rounding back to
//! f32; the outputs are widened to f64. A single pass takes 16 units per block, a batch tile
//! 4 samples × 16 units (8 accumulator registers).

use super::activation::{
    affine_batch_portable, kernel_portable, transpose, Activation, Real, BATCH_TILE,
};
use super::lanes::{self, Lanes, Stage, LANES};
use super::plasticity::{LifeKey, Plastic, PlasticSettings, SignalInputs};
use super::spec::Precision;
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
    /// Where the layer's activations are kept in `activations` for one sample (hidden layers
    /// only); a batch of n samples keeps them at n times this range.
    out: Range<usize>,
}

/// What the forward pass reads and writes, in the float type it computes in.
#[derive(Debug, Clone, PartialEq)]
struct Buffers<F> {
    /// Every layer's weights, transposed to input-major order (derived from the parameters).
    transposed: Vec<F>,
    /// Every hidden layer's activations, one after another (preallocated scratch); a batch
    /// of n samples uses n times as much (see [`Mlp::activate_batch`]).
    activations: Vec<F>,
    /// One tile of a batch's inputs to a layer, input-major ([`BATCH_TILE`] × the widest
    /// layer input; scratch for [`affine_batch_portable`]).
    tile: Vec<F>,
}

/// The sample-lane batch pass of a small f64 network ([`super::lanes`]).
#[derive(Debug, Clone, PartialEq)]
struct SampleLanes {
    /// Every layer's weights, each repeated in the lanes, block by block of units
    /// ([`lanes::repeat`]), at the layer's `weights` range.
    weights: Vec<Lanes>,
    /// The tiles' values (scratch, grown to the largest batch, never shrunk): all the tiles'
    /// inputs, then every hidden layer's activations for all the tiles, then the outputs; one
    /// [`Lanes`] per input or unit and tile.
    values: Vec<Lanes>,
    /// The values one tile takes in `values`: its inputs and all the units.
    tile: usize,
    /// Which inputs to leave out of the first layer's sums in a batch (zero in every sample;
    /// `None` when the network is not skip-safe, see [`lanes::LiveInputs`]).
    live: Option<lanes::LiveInputs>,
    /// tanh's constants for the layers' functions ([`lanes::TanhLanes`]; boxed, so that a
    /// brain stays small to move).
    tanh: Box<lanes::TanhLanes>,
}

/// The float type of the pass and its buffers.
#[derive(Debug, Clone, PartialEq)]
enum Numbers {
    /// `precision = "f64"`: biases are read from the parameters themselves. Batches of
    /// networks of at most [`lanes::MAX_WEIGHTS`] weights take the sample-lane pass (`lanes`).
    F64 {
        buffers: Buffers<f64>,
        lanes: Option<SampleLanes>,
    },
    /// `precision = "f32"`.
    F32 {
        /// The parameters rounded to f32 (the biases are read from here).
        parameters: Vec<f32>,
        buffers: Buffers<f32>,
        /// The inputs rounded to f32 (scratch, n × inputs for a batch of n).
        inputs: Vec<f32>,
        /// The f32 outputs before widening (scratch, n × outputs).
        outputs: Vec<f32>,
    },
}

/// A multilayer perceptron with its parameters and scratch buffers.
#[derive(Debug, Clone, PartialEq)]
pub struct Mlp {
    inputs: usize,
    outputs: usize,
    activation: Activation,
    /// The parameters exactly as given (the genome's f64 values, whatever the precision).
    parameters: Vec<f64>,
    hidden: Vec<Layer>,
    output: Layer,
    numbers: Numbers,
    /// The rule, modulation and per-life state of a plastic network (`None`: fixed weights,
    /// and then nothing below runs). Boxed, so that a fixed brain stays small to move.
    plastic: Option<Box<Plastic>>,
    /// A plastic network's whole genome (`parameters` then holds only the network's weights
    /// and biases, zeros for random initial weights).
    genome: Option<Vec<f64>>,
}

impl Mlp {
    /// Builds the network; `parameters.len()` must be the topology's parameter count (checked
    /// by [`crate::brain::Brain::new`]).
    pub(crate) fn new(
        inputs: usize,
        hidden: &[usize],
        outputs: usize,
        activation: Activation,
        precision: Precision,
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
        let tile = BATCH_TILE * hidden.iter().fold(inputs, |m, &h| m.max(h));
        let numbers = match precision {
            Precision::F64 => Numbers::F64 {
                // (Sizes of 0 are valid but useless: left to the unit-lane pass.)
                lanes: (transposed.len() <= lanes::MAX_WEIGHTS
                    && inputs > 0
                    && hidden.iter().all(|&units| units > 0))
                .then(|| {
                    let first = layers.first().unwrap_or(&output);
                    SampleLanes {
                        weights: lane_weights(&transposed, &layers, &output),
                        values: Vec::new(),
                        tile: inputs + buffer + outputs,
                        live: lanes::LiveInputs::new(
                            &transposed[first.weights.clone()],
                            &parameters[first.biases.clone()],
                            first.units,
                        ),
                        tanh: Box::default(),
                    }
                }),
                buffers: Buffers {
                    transposed,
                    activations: vec![0.0; buffer],
                    tile: vec![0.0; tile],
                },
            },
            // Rounding to nearest, once: `as` rounds f64 to the nearest f32 (ties to even).
            Precision::F32 => Numbers::F32 {
                parameters: parameters.iter().map(|&p| p as f32).collect(),
                buffers: Buffers {
                    transposed: transposed.iter().map(|&w| w as f32).collect(),
                    activations: vec![0.0; buffer],
                    tile: vec![0.0; tile],
                },
                inputs: vec![0.0; inputs],
                outputs: vec![0.0; outputs],
            },
        };
        Mlp {
            inputs,
            outputs,
            activation,
            parameters: parameters.to_vec(),
            hidden: layers,
            output,
            numbers,
            plastic: None,
            genome: None,
        }
    }

    /// A plastic network (`precision = "f64"` only, checked by the spec): `genome` is the
    /// whole parameter vector, `base` the weights and biases to build the network from (the
    /// genome's, or zeros for random initial weights, which the first reset draws) and `genes`
    /// the plasticity genes (see [`crate::brain::plasticity`]). A plastic network never takes
    /// the batch passes (its weights belong to one life), so it keeps no lane copy.
    pub(crate) fn new_plastic(
        (inputs, hidden, outputs): (usize, &[usize], usize),
        activation: Activation,
        settings: &PlasticSettings,
        signals: &SignalInputs,
        (genome, base, genes): (&[f64], &[f64], &[f64]),
    ) -> Mlp {
        let mut mlp = Mlp::new(inputs, hidden, outputs, activation, Precision::F64, base);
        let sizes: Vec<(usize, usize)> = mlp
            .hidden
            .iter()
            .chain([&mlp.output])
            .map(|layer| (layer.units, layer.weights.len() / layer.units.max(1)))
            .collect();
        let source = mlp.hidden.last().map_or(inputs, |layer| layer.units);
        if let Numbers::F64 { buffers, lanes } = &mut mlp.numbers {
            *lanes = None;
            let plastic = Plastic::new(
                settings,
                &sizes,
                source,
                signals,
                genes,
                &mut buffers.transposed,
            );
            mlp.plastic = Some(Box::new(plastic));
        }
        mlp.genome = Some(genome.to_vec());
        mlp
    }

    /// True when the weights change during a life (`brain.plasticity`).
    pub fn is_plastic(&self) -> bool {
        self.plastic.is_some()
    }

    /// The start of a life: a plastic network's weights back to where a life starts (see
    /// [`crate::brain::plasticity`]); nothing for a fixed one.
    pub(crate) fn reset(&mut self) {
        if let (Some(plastic), Numbers::F64 { buffers, .. }) =
            (&mut self.plastic, &mut self.numbers)
        {
            plastic.reset(&mut buffers.transposed);
        }
    }

    /// Sets which life a plastic network with random initial weights lives, and resets it
    /// (see [`LifeKey`]); nothing for other networks.
    pub(crate) fn start_life(&mut self, life: LifeKey) {
        if let (Some(plastic), Numbers::F64 { buffers, .. }) =
            (&mut self.plastic, &mut self.numbers)
        {
            plastic.start_life(life, &mut buffers.transposed);
        }
    }

    /// The live weights of every layer, input-major (hidden layers then the output layer,
    /// each `inputs × units` with the weights leaving input i contiguous): what the forward
    /// pass reads, which a plastic network changes every tick.
    pub fn live_weights(&self) -> Vec<f64> {
        match &self.numbers {
            Numbers::F64 { buffers, .. } => buffers.transposed.clone(),
            Numbers::F32 { buffers, .. } => {
                buffers.transposed.iter().map(|&w| f64::from(w)).collect()
            }
        }
    }

    /// A plastic network's live weights, borrowed ([`Mlp::live_weights`]'s order); None for
    /// fixed weights. A read accessor for traces: the tick does no work for it.
    pub fn plastic_weights(&self) -> Option<&[f64]> {
        match (&self.plastic, &self.numbers) {
            (Some(_), Numbers::F64 { buffers, .. }) => Some(&buffers.transposed),
            _ => None,
        }
    }

    /// A neuromodulated network's last modulatory signal m (see
    /// [`crate::brain::plasticity`]); None for Hebbian and fixed networks.
    pub fn last_modulation(&self) -> Option<f64> {
        self.plastic.as_ref().and_then(|p| p.last_modulation())
    }

    /// The parameters, exactly as given (a plastic network's whole genome).
    pub fn parameters(&self) -> &[f64] {
        self.genome.as_deref().unwrap_or(&self.parameters)
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

    /// The float type the forward pass computes in.
    pub fn precision(&self) -> Precision {
        match self.numbers {
            Numbers::F64 { .. } => Precision::F64,
            Numbers::F32 { .. } => Precision::F32,
        }
    }

    /// One forward pass. `inputs` and `outputs` must have the network's sizes.
    ///
    /// On x86-64 CPUs with AVX2 the whole pass (sums and activation functions) runs compiled
    /// for AVX2; the operations per value are the same, so are the bits (see
    /// [`super::activation`] and the tests below).
    pub(crate) fn activate(&mut self, inputs: &[f64], outputs: &mut [f64]) {
        self.dispatch(inputs, outputs, 1);
        if self.plastic.is_some() {
            self.learn(inputs, outputs);
        }
    }

    /// A plastic network's weight update after the forward pass of `inputs` gave `outputs`
    /// (see [`crate::brain::plasticity`] for the rule and its order), compiled for AVX2 when
    /// the CPU has it: the same separate multiplies and adds, so the same bits.
    #[inline]
    fn learn(&mut self, inputs: &[f64], outputs: &[f64]) {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: `learn_avx2` only requires AVX2, checked just above.
            unsafe { self.learn_avx2(inputs, outputs) };
            return;
        }
        self.learn_portable(inputs, outputs);
    }

    /// [`Mlp::learn_portable`] compiled for AVX2 (without FMA).
    ///
    /// # Safety
    /// The CPU must support AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn learn_avx2(&mut self, inputs: &[f64], outputs: &[f64]) {
        self.learn_portable(inputs, outputs);
    }

    /// The weight update for any CPU.
    #[inline(always)]
    fn learn_portable(&mut self, inputs: &[f64], outputs: &[f64]) {
        let (Some(plastic), Numbers::F64 { buffers, .. }) = (&mut self.plastic, &mut self.numbers)
        else {
            return;
        };
        let Buffers {
            transposed,
            activations,
            ..
        } = buffers;
        let activations: &[f64] = activations;
        let hidden = &self.hidden;
        let values = |l: usize| -> &[f64] {
            if l == 0 {
                inputs
            } else {
                &activations[hidden[l - 1].out.clone()]
            }
        };
        let layers = hidden
            .iter()
            .enumerate()
            .map(|(l, layer)| {
                (
                    layer.weights.clone(),
                    values(l),
                    &activations[layer.out.clone()],
                )
            })
            .chain([(
                self.output.weights.clone(),
                values(hidden.len()),
                &outputs[..self.output.units],
            )]);
        plastic.update(transposed, layers, inputs, values(hidden.len()));
    }

    /// [`Mlp::activate`] for n samples at once: `inputs` holds n input vectors one after
    /// another, `outputs` receives n output vectors, and each sample's outputs have exactly the
    /// bits [`Mlp::activate`] gives it alone (see the module docs).
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
        self.grow(n);
        self.dispatch(inputs, outputs, n);
    }

    /// Makes the scratch buffers hold a batch of n samples (never shrinks them).
    fn grow(&mut self, n: usize) {
        fn at_least<F: Copy + Default>(v: &mut Vec<F>, len: usize) {
            if v.len() < len {
                v.resize(len, F::default());
            }
        }
        let hidden = n * self.hidden.last().map_or(0, |layer| layer.out.end);
        match &mut self.numbers {
            Numbers::F64 { buffers, lanes } => {
                at_least(&mut buffers.activations, hidden);
                if let Some(lanes) = lanes {
                    at_least(&mut lanes.values, n.div_ceil(LANES) * lanes.tile);
                }
            }
            Numbers::F32 {
                buffers,
                inputs,
                outputs,
                ..
            } => {
                at_least(&mut buffers.activations, hidden);
                at_least(inputs, n * self.inputs);
                at_least(outputs, n * self.outputs);
            }
        }
    }

    /// Runs [`Mlp::forward`] compiled for AVX2 when the CPU has it (f64), or for AVX2 and FMA
    /// when it has both (f32: its fused multiply-adds then become vfmadd instructions instead
    /// of calls to the software `fmaf`); otherwise the portable build. Each build computes the
    /// same IEEE 754 operations, so all give the same bits.
    #[inline]
    fn dispatch(&mut self, inputs: &[f64], outputs: &mut [f64], n: usize) {
        #[cfg(target_arch = "x86_64")]
        match self.numbers {
            Numbers::F64 { .. } => {
                if std::arch::is_x86_feature_detected!("avx2") {
                    // SAFETY: `forward_avx2` only requires AVX2, checked just above.
                    unsafe { self.forward_avx2(inputs, outputs, n) };
                    return;
                }
            }
            Numbers::F32 { .. } => {
                if std::arch::is_x86_feature_detected!("avx2")
                    && std::arch::is_x86_feature_detected!("fma")
                {
                    // SAFETY: `forward_avx2_fma` only requires AVX2 and FMA, checked just
                    // above.
                    unsafe { self.forward_avx2_fma(inputs, outputs, n) };
                    return;
                }
            }
        }
        self.forward(inputs, outputs, n);
    }

    /// [`Mlp::forward`] compiled for AVX2 (f64 networks: compiled without FMA, although Rust
    /// would not fuse their separate multiplies and adds anyway).
    ///
    /// # Safety
    /// The CPU must support AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn forward_avx2(&mut self, inputs: &[f64], outputs: &mut [f64], n: usize) {
        self.forward(inputs, outputs, n);
    }

    /// [`Mlp::forward`] compiled for AVX2 and FMA (f32 networks: `f32::mul_add` becomes one
    /// vfmadd per 8 lanes).
    ///
    /// # Safety
    /// The CPU must support AVX2 and FMA.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,fma")]
    unsafe fn forward_avx2_fma(&mut self, inputs: &[f64], outputs: &mut [f64], n: usize) {
        self.forward(inputs, outputs, n);
    }

    /// The forward pass of n samples for any CPU, in the network's precision; the scratch
    /// buffers must hold n samples (see [`Mlp::grow`]).
    #[inline(always)]
    fn forward(&mut self, inputs: &[f64], outputs: &mut [f64], n: usize) {
        let shape = (&self.hidden[..], &self.output, self.activation);
        match &mut self.numbers {
            Numbers::F64 {
                lanes: Some(lanes), ..
            } if n >= LANES => lane_pass(shape, &self.parameters, lanes, inputs, outputs, n),
            Numbers::F64 { buffers, .. } => {
                pass(shape, &self.parameters, buffers, inputs, outputs, n)
            }
            Numbers::F32 {
                parameters,
                buffers,
                inputs: narrow_inputs,
                outputs: narrow_outputs,
            } => {
                let x = &mut narrow_inputs[..inputs.len()];
                for (narrow, &wide) in x.iter_mut().zip(inputs) {
                    *narrow = wide as f32;
                }
                let y = &mut narrow_outputs[..outputs.len()];
                pass(shape, parameters, buffers, x, y, n);
                for (wide, &narrow) in outputs.iter_mut().zip(y.iter()) {
                    *wide = f64::from(narrow);
                }
            }
        }
    }
}

/// The layers of an MLP for n samples in float type `F`: `params` holds the biases (at each
/// layer's `biases` range), `buffers` the transposed weights and scratch; layer l's
/// activations for the n samples occupy n × its `out` range (the ranges are prefix sums of the
/// layer sizes, so scaling them by n keeps the layers apart).
#[inline(always)]
fn pass<F: Real>(
    (hidden, output, activation): (&[Layer], &Layer, Activation),
    params: &[F],
    buffers: &mut Buffers<F>,
    inputs: &[F],
    outputs: &mut [F],
    n: usize,
) {
    let weights = &buffers.transposed;
    let mut previous: Range<usize> = 0..0;
    for (l, layer) in hidden.iter().enumerate() {
        let out = n * layer.out.start..n * layer.out.end;
        // Earlier layers sit before this one in the buffer: split to read and write.
        let (done, rest) = buffers.activations.split_at_mut(out.start);
        let x = if l == 0 { inputs } else { &done[previous] };
        let y = &mut rest[..out.len()];
        let (w, b) = (
            &weights[layer.weights.clone()],
            &params[layer.biases.clone()],
        );
        affine_layer(w, b, x, y, n, &mut buffers.tile);
        F::activate(activation, y);
        previous = out;
    }
    let x = if hidden.is_empty() {
        inputs
    } else {
        &buffers.activations[previous]
    };
    let (w, b) = (
        &weights[output.weights.clone()],
        &params[output.biases.clone()],
    );
    affine_layer(
        w,
        b,
        x,
        &mut outputs[..n * output.units],
        n,
        &mut buffers.tile,
    );
    F::squash(outputs);
}

/// Every layer's weights laid out for the sample-lane pass ([`lanes::repeat`]), at the same
/// places as in `transposed` (each layer's `weights` range).
fn lane_weights(transposed: &[f64], hidden: &[Layer], output: &Layer) -> Vec<Lanes> {
    let mut weights = Vec::with_capacity(transposed.len());
    for layer in hidden.iter().chain([output]) {
        weights.extend(lanes::repeat(
            &transposed[layer.weights.clone()],
            layer.units,
        ));
    }
    weights
}

/// The sample-lane pass of n ≥ [`LANES`] samples ([`super::lanes`]), layer by layer like
/// [`pass`]: the inputs copied into tiles of 4 samples (the last one possibly fewer), every
/// layer's sums tile by tile, then its function over all the tiles at once (one loop for the
/// batch), and the outputs copied out of the tiles; the scratch must hold the tiles (see
/// [`Mlp::grow`]).
#[inline(always)]
fn lane_pass(
    (hidden, output, activation): (&[Layer], &Layer, Activation),
    params: &[f64],
    lanes: &mut SampleLanes,
    inputs: &[f64],
    outputs: &mut [f64],
    n: usize,
) {
    let SampleLanes {
        weights,
        values,
        live,
        tanh,
        ..
    } = lanes;
    let tiles = n.div_ceil(LANES);
    let p = inputs.len() / n;
    let first = hidden.first().unwrap_or(output);
    // The first layer's live inputs and their weights when some inputs are zero in every
    // sample (see `lanes::LiveInputs`): the tiles then hold only those.
    let live = match live {
        Some(live) => live.update(inputs, &weights[first.weights.clone()], first.units),
        None => None,
    };
    let width = live.map_or(p, |(live, _)| live.len());
    let (xt, mut free) = values.split_at_mut(tiles * width);
    // The whole tiles, then the last one of fewer than 4 samples, if any.
    let whole = n / LANES;
    let (rows, rest) = inputs.split_at(whole * LANES * p);
    let (whole_tiles, last_tile) = xt.split_at_mut(whole * width);
    match live {
        Some((live, _)) => {
            lanes::load_live_tiles(rows, p, live, whole_tiles);
            if !rest.is_empty() {
                lanes::load_live_tile(rest, p, n - whole * LANES, live, last_tile);
            }
        }
        None => {
            for (x, xt) in rows
                .chunks_exact(LANES * p)
                .zip(whole_tiles.chunks_exact_mut(width))
            {
                lanes::load_tile(x, LANES, xt);
            }
            if !rest.is_empty() {
                lanes::load_tile(rest, n - whole * LANES, last_tile);
            }
        }
    }
    let (mut x, mut width): (&[Lanes], usize) = (xt, width);
    let layers = hidden
        .iter()
        .map(|layer| (layer, Stage::Hidden(activation)));
    for (l, (layer, stage)) in layers.chain([(output, Stage::Output)]).enumerate() {
        let units = layer.units;
        let (y, after) = std::mem::take(&mut free).split_at_mut(tiles * units);
        let w = match live {
            Some((_, compacted)) if l == 0 => compacted,
            _ => &weights[layer.weights.clone()],
        };
        lanes::sums(w, &params[layer.biases.clone()], x, width, y);
        lanes::finish(y, stage, tanh);
        (x, width) = (y, units);
        free = after;
    }
    // `x` now holds the outputs, tile by tile: sample t of tile k is lane t. The whole
    // tiles first (fixed-size copies), then the last one of fewer than 4 samples, if any.
    let m = output.units;
    if m == 0 {
        return;
    }
    let (outputs, last) = outputs.split_at_mut(whole * LANES * m);
    let (x, x_last) = x.split_at(whole * m);
    if m == 2 {
        // Two motor outputs (the usual case): no inner loop.
        for (out, sums) in outputs.chunks_exact_mut(2 * LANES).zip(x.chunks_exact(2)) {
            let out: &mut [f64; 2 * LANES] = out.try_into().expect("one tile");
            for t in 0..LANES {
                out[2 * t] = sums[0][t];
                out[2 * t + 1] = sums[1][t];
            }
        }
    } else {
        for (out, sums) in outputs.chunks_exact_mut(m * LANES).zip(x.chunks_exact(m)) {
            scatter(out, sums, m);
        }
    }
    scatter(last, x_last, m);
}

/// Copies one tile's outputs `sums` (one [`Lanes`] per output unit) into `out`, `m` values
/// per sample, as many samples as `out` holds (up to 4).
#[inline(always)]
fn scatter(out: &mut [f64], sums: &[Lanes], m: usize) {
    for (t, sample) in out.chunks_exact_mut(m).enumerate() {
        for (o, v) in sample.iter_mut().zip(sums) {
            *o = v[t];
        }
    }
}

/// One layer's sums for n samples: the single-sample kernel for one (no tile to share), the
/// batch kernel otherwise. Both give the same bits per sample.
#[inline(always)]
fn affine_layer<F: Real>(w: &[F], b: &[F], x: &[F], y: &mut [F], n: usize, tile: &mut [F]) {
    if n == 1 {
        kernel_portable(w, Some(b), x, y);
    } else {
        affine_batch_portable(w, b, x, y, n, tile);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::brain::activation::{nan_to_zero, tanh};
    use crate::seed::{stream, uniform, Generation, IndividualId, Purpose, Rng, Seed, TrialIndex};

    fn rng(seed: u64) -> Rng {
        stream(
            Seed(seed),
            Purpose::Baseline,
            Generation(0),
            IndividualId(0),
            TrialIndex(0),
        )
    }

    fn parameter_count(inputs: usize, hidden: &[usize], outputs: usize) -> usize {
        let mut count = 0;
        let mut previous = inputs;
        for &h in hidden {
            count += h * previous + h;
            previous = h;
        }
        count + outputs * previous + outputs
    }

    /// One random network of the shape per activation, parameters uniform in ±`bound`.
    fn networks(
        seed: u64,
        (inputs, hidden, outputs): (usize, &[usize], usize),
        precision: Precision,
        bound: f64,
    ) -> Vec<Mlp> {
        let mut rng = rng(seed);
        let count = parameter_count(inputs, hidden, outputs);
        [Activation::Tanh, Activation::Sigmoid, Activation::Relu]
            .into_iter()
            .map(|activation| {
                let parameters: Vec<f64> = (0..count)
                    .map(|_| uniform(&mut rng, -bound, bound))
                    .collect();
                Mlp::new(inputs, hidden, outputs, activation, precision, &parameters)
            })
            .collect()
    }

    fn bits(v: &[f64]) -> Vec<u64> {
        v.iter().map(|f| f.to_bits()).collect()
    }

    /// The outputs of `single` for the samples of `x` (rows of `inputs`), one pass each: what
    /// a batch must give bit for bit.
    fn single_passes(single: &mut Mlp, x: &[f64], inputs: usize, outputs: usize) -> Vec<f64> {
        let mut expected = vec![0.0; x.len() / inputs * outputs];
        for (xs, ys) in x
            .chunks_exact(inputs)
            .zip(expected.chunks_exact_mut(outputs))
        {
            single.activate(xs, ys);
        }
        expected
    }

    const SHAPES: [(usize, &[usize], usize); 6] = [
        (24, &[16], 2),
        (24, &[16], 3),
        (98, &[100], 2),
        (5, &[7, 3], 3),
        (1, &[], 2),
        (13, &[1, 15, 9], 7),
    ];

    /// A batch gives every sample the bits of a single pass, for batch sizes around the tile
    /// size and its multiples and for unit counts that leave every block-size remainder, on
    /// the dispatched (AVX2 where available) and the portable batch paths alike, in both
    /// precisions.
    #[test]
    fn batch_matches_single_passes_bit_for_bit() {
        let mut rng = rng(43);
        let sizes: Vec<usize> = (0..=9).chain([16, 33]).collect();
        for precision in [Precision::F64, Precision::F32] {
            for shape @ (inputs, hidden, outputs) in SHAPES {
                for mut mlp in networks(44, shape, precision, 3.0) {
                    let mut single = mlp.clone();
                    let mut portable = mlp.clone();
                    // Sizes up and down: the scratch grows, then smaller batches reuse it.
                    for &n in sizes.iter().chain(sizes.iter().rev()) {
                        let x: Vec<f64> = (0..n * inputs)
                            .map(|_| uniform(&mut rng, -3.0, 3.0))
                            .collect();
                        let what = format!(
                            "{precision:?} {inputs} {hidden:?} {outputs} {:?} n={n}",
                            mlp.activation
                        );
                        assert_batch_is_single_passes(
                            [&mut mlp, &mut single, &mut portable],
                            &x,
                            &what,
                        );
                    }
                }
            }
        }
    }

    /// Small f64 networks take the sample-lane batch pass (so the bit-for-bit tests above
    /// cover it), networks of more than 2,048 weights (WaterWorld's), f32 ones and those with a
    /// size of 0 the unit-lane pass.
    #[test]
    fn small_f64_networks_take_the_sample_lane_pass() {
        let lanes = |shape, precision| {
            let mlp = networks(52, shape, precision, 1.0).swap_remove(0);
            matches!(mlp.numbers, Numbers::F64 { lanes: Some(_), .. })
        };
        assert!(lanes((24, &[16], 2), Precision::F64));
        assert!(lanes((13, &[1, 15, 9], 7), Precision::F64));
        assert!(lanes((1, &[], 2), Precision::F64));
        assert!(!lanes((98, &[100], 2), Precision::F64));
        assert!(!lanes((24, &[16], 2), Precision::F32));
        assert!(!lanes((0, &[4], 2), Precision::F64));
    }

    /// Batches through the sample-lane pass keep the single-pass bits with extreme
    /// parameters and inputs too (overflowing products, ±∞ and NaN sums, which the outputs map
    /// to ±1 and 0), in every tile remainder.
    #[test]
    fn sample_lane_batches_match_single_passes_on_extreme_values() {
        let mut rng = rng(53);
        let specials = [
            0.0,
            -0.0,
            1e300,
            -1e300,
            f64::MAX,
            1e-310,
            f64::INFINITY,
            f64::NAN,
        ];
        let pick = |rng: &mut Rng| {
            if uniform(rng, 0.0, 1.0) < 0.3 {
                specials[(uniform(rng, 0.0, 8.0) as usize).min(7)]
            } else {
                uniform(rng, -3.0, 3.0)
            }
        };
        let (inputs, hidden, outputs) = (6, [9usize], 3);
        for activation in [Activation::Tanh, Activation::Sigmoid, Activation::Relu] {
            let count = parameter_count(inputs, &hidden, outputs);
            let parameters: Vec<f64> = (0..count).map(|_| pick(&mut rng)).collect();
            let mut mlp = Mlp::new(
                inputs,
                &hidden,
                outputs,
                activation,
                Precision::F64,
                &parameters,
            );
            let mut single = mlp.clone();
            for n in 4..=13 {
                let x: Vec<f64> = (0..n * inputs).map(|_| pick(&mut rng)).collect();
                let expected = single_passes(&mut single, &x, inputs, outputs);
                let mut batch = vec![f64::NAN; n * outputs];
                mlp.activate_batch(&x, &mut batch);
                assert_eq!(bits(&batch), bits(&expected), "{activation:?} n={n}");
            }
        }
    }

    /// Batches with inputs that are ±0 in every sample in many columns (which the first layer
    /// of the sample-lane pass leaves out of its sums) keep the single-pass bits: also with
    /// first-layer biases of ±0 (a −0 one forbids skipping), weights of ±∞ or NaN on zero
    /// inputs (those inputs stay), every input zero, and columns zero in all samples but one,
    /// for every batch size 1 to 17, on the dispatched and the portable paths.
    #[test]
    fn batches_with_zero_columns_match_single_passes_bit_for_bit() {
        let mut rng = rng(54);
        let shapes: [(usize, &[usize], usize); 5] = [
            (24, &[16], 2),
            (6, &[9], 3),
            (7, &[], 5),
            (70, &[20], 2),
            (13, &[1, 15, 9], 7),
        ];
        let activations = [Activation::Tanh, Activation::Sigmoid, Activation::Relu];
        let specials = [f64::INFINITY, f64::NEG_INFINITY, f64::NAN];
        for (inputs, hidden, outputs) in shapes {
            let units = hidden.first().copied().unwrap_or(outputs);
            for case in 0..18 {
                let count = parameter_count(inputs, hidden, outputs);
                let mut parameters: Vec<f64> =
                    (0..count).map(|_| uniform(&mut rng, -2.0, 2.0)).collect();
                // The first layer: units × inputs weights, then its biases.
                let (w, b) = parameters[..units * (inputs + 1)].split_at_mut(units * inputs);
                match case % 6 {
                    1 => b[case % units] = -0.0,
                    2 => b.fill(0.0),
                    3 => b.fill(-0.0),
                    _ => {}
                }
                if case % 4 == 3 {
                    let k = (uniform(&mut rng, 0.0, 1.0) * w.len() as f64) as usize;
                    w[k.min(w.len() - 1)] = specials[case % 3];
                }
                let activation = activations[case % 3];
                let mut mlp = Mlp::new(
                    inputs,
                    hidden,
                    outputs,
                    activation,
                    Precision::F64,
                    &parameters,
                );
                let (mut single, mut portable) = (mlp.clone(), mlp.clone());
                let share = [0.6, 0.9, 1.0][case % 3];
                let zero: Vec<bool> = (0..inputs)
                    .map(|_| uniform(&mut rng, 0.0, 1.0) < share)
                    .collect();
                for n in (1..=17).chain((1..=17).rev()) {
                    let mut x: Vec<f64> = (0..n * inputs)
                        .map(|k| match (zero[k % inputs], uniform(&mut rng, 0.0, 1.0)) {
                            (true, u) if u < 0.5 => 0.0,
                            (true, _) => -0.0,
                            (false, _) => uniform(&mut rng, -3.0, 3.0),
                        })
                        .collect();
                    if uniform(&mut rng, 0.0, 1.0) < 0.3 {
                        // One sample wakes a column up.
                        let last = x.len() - 1;
                        let k = (uniform(&mut rng, 0.0, 1.0) * x.len() as f64) as usize;
                        x[k.min(last)] = uniform(&mut rng, -1.0, 1.0);
                    }
                    let what = format!("{inputs} {hidden:?} {outputs} case {case} n={n}");
                    assert_batch_is_single_passes(
                        [&mut mlp, &mut single, &mut portable],
                        &x,
                        &what,
                    );
                }
            }
        }
    }

    /// A zero input still counts when leaving it out would change a bit: under a bias of −0
    /// (−0 + +0 is +0, so the zero terms turn the sum to +0) and with an infinite weight
    /// (∞ · 0 is NaN, an output of 0). Both cases are checked to matter.
    #[test]
    fn zero_inputs_that_change_bits_are_not_skipped() {
        let (inputs, outputs) = (3, 2);
        let zero = 0.0f64.to_bits();
        assert_eq!(tanh(-0.0).to_bits(), (-0.0f64).to_bits(), "−0 would show");
        assert_ne!(tanh(0.5).to_bits(), zero, "∞ · 0 would show");
        // Outputs straight from the inputs, weights 1: biases −0 and 0.5, then 0.25 and 0.5
        // with an infinite weight from input 2 to output 1 (input 0 stays live when all are
        // zero).
        let mut negative_zero = vec![1.0; inputs * outputs];
        negative_zero.extend([-0.0, 0.5]);
        let mut infinite = vec![1.0; inputs * outputs];
        infinite.extend([0.25, 0.5]);
        infinite[inputs + 2] = f64::INFINITY;
        let cases = [
            (negative_zero, [zero, tanh(0.5).to_bits()]),
            (infinite, [tanh(0.25).to_bits(), zero]),
        ];
        for (parameters, expected) in cases {
            let mut mlp = Mlp::new(
                inputs,
                &[],
                outputs,
                Activation::Tanh,
                Precision::F64,
                &parameters,
            );
            for n in 1..=9 {
                let x: Vec<f64> = (0..n * inputs)
                    .map(|k| if k % 2 == 0 { 0.0 } else { -0.0 })
                    .collect();
                let mut y = vec![f64::NAN; n * outputs];
                mlp.activate_batch(&x, &mut y);
                for sample in y.chunks_exact(outputs) {
                    assert_eq!(bits(sample), expected, "n = {n}");
                }
            }
        }
    }

    /// `x` (a batch of `mlp`'s inputs) through `mlp`'s batch pass and through `portable`'s
    /// portable pass gives, bit for bit, what `single` gives sample by sample (three clones
    /// of one network, each keeping its own scratch).
    fn assert_batch_is_single_passes(
        [mlp, single, portable]: [&mut Mlp; 3],
        x: &[f64],
        what: &str,
    ) {
        let (inputs, outputs) = (mlp.inputs, mlp.outputs);
        let n = x.len() / inputs;
        let expected = single_passes(single, x, inputs, outputs);
        let mut batch = vec![f64::NAN; n * outputs];
        mlp.activate_batch(x, &mut batch);
        assert_eq!(bits(&batch), bits(&expected), "{what}");
        portable.grow(n);
        let mut by_portable = vec![f64::NAN; n * outputs];
        portable.forward(x, &mut by_portable, n);
        assert_eq!(bits(&by_portable), bits(&expected), "portable {what}");
    }

    /// (activations length, tile length, activations address) of either precision.
    fn scratch(mlp: &Mlp) -> (usize, usize, usize) {
        match &mlp.numbers {
            Numbers::F64 { buffers: b, .. } => (
                b.activations.len(),
                b.tile.len(),
                b.activations.as_ptr() as usize,
            ),
            Numbers::F32 { buffers: b, .. } => (
                b.activations.len(),
                b.tile.len(),
                b.activations.as_ptr() as usize,
            ),
        }
    }

    /// The batch scratch grows to the largest batch and is never shrunk, so a warmed-up brain
    /// serves any smaller batch without allocating.
    #[test]
    fn batch_scratch_grows_to_the_largest_batch_only() {
        for precision in [Precision::F64, Precision::F32] {
            let mut mlp = networks(45, (6, &[10, 4], 2), precision, 1.0).swap_remove(0);
            assert_eq!(scratch(&mlp).0, 14);
            assert_eq!(scratch(&mlp).1, BATCH_TILE * 10);
            let mut warm = None;
            for (n, len) in [(3, 42), (32, 448), (5, 448), (0, 448), (32, 448)] {
                let x = vec![0.25; n * 6];
                let mut y = vec![0.0; n * 2];
                mlp.activate_batch(&x, &mut y);
                let (activations, tile, address) = scratch(&mlp);
                assert_eq!(activations, len, "n = {n}");
                assert_eq!(tile, BATCH_TILE * 10);
                if n == 32 {
                    // The same buffer once warmed up: no reallocation.
                    assert_eq!(*warm.get_or_insert(address), address);
                }
            }
        }
    }

    /// The AVX2 build of the forward pass gives the same bits as the portable one.
    #[test]
    fn dispatched_and_portable_passes_agree_bit_for_bit() {
        let mut rng = rng(42);
        for precision in [Precision::F64, Precision::F32] {
            for shape @ (inputs, hidden, outputs) in SHAPES {
                for mut a in networks(47, shape, precision, 3.0) {
                    let mut b = a.clone();
                    for _ in 0..20 {
                        let x: Vec<f64> =
                            (0..inputs).map(|_| uniform(&mut rng, -3.0, 3.0)).collect();
                        let (mut ya, mut yb) = (vec![0.0; outputs], vec![0.0; outputs]);
                        a.activate(&x, &mut ya);
                        b.forward(&x, &mut yb, 1);
                        assert_eq!(bits(&ya), bits(&yb), "{precision:?} {inputs} {hidden:?}");
                    }
                }
            }
        }
    }

    /// f32 is exactly the documented computation: parameters and inputs rounded to f32, sums
    /// in f32 from the bias, input by input, each term a fused multiply-add, activations in
    /// f64 on the widened sum, rounded.
    #[test]
    fn f32_follows_the_documented_order_bit_for_bit() {
        let mut rng = rng(48);
        let (inputs, hidden, outputs) = (5, [7usize, 3], 3);
        for mut mlp in networks(49, (inputs, &hidden, outputs), Precision::F32, 2.0) {
            let act = mlp.activation;
            let p: Vec<f32> = mlp.parameters.iter().map(|&v| v as f32).collect();
            for _ in 0..50 {
                let x: Vec<f64> = (0..inputs).map(|_| uniform(&mut rng, -3.0, 3.0)).collect();
                let mut a: Vec<f32> = x.iter().map(|&v| v as f32).collect();
                let mut offset = 0;
                for (l, units) in hidden.iter().copied().chain([outputs]).enumerate() {
                    let (w, rest) = p[offset..].split_at(units * a.len());
                    let next: Vec<f32> = (0..units)
                        .map(|j| {
                            let mut sum = rest[j];
                            for (i, &xi) in a.iter().enumerate() {
                                sum = w[j * a.len() + i].mul_add(xi, sum);
                            }
                            if l < hidden.len() {
                                act.apply(f64::from(sum)) as f32
                            } else {
                                nan_to_zero(tanh(f64::from(sum))) as f32
                            }
                        })
                        .collect();
                    offset += units * a.len() + units;
                    a = next;
                }
                let expected: Vec<f64> = a.iter().map(|&v| f64::from(v)).collect();
                let mut y = vec![0.0; outputs];
                mlp.activate(&x, &mut y);
                assert_eq!(bits(&y), bits(&expected), "{act:?}");
            }
        }
    }

    /// The f32 sums are fused: with w = x = 1 + 2⁻¹² and bias −1, w·x = 1 + 2⁻¹¹ + 2⁻²⁴
    /// exactly, which a separate f32 multiply rounds (a tie, to even) to 1 + 2⁻¹¹, so an
    /// unfused sum gives 2⁻¹¹ while the fused one keeps 2⁻¹¹ + 2⁻²⁴. Nineteen output units
    /// (a block of 16 and the remainders) see it in single passes and batches of every tile
    /// remainder, on the dispatched (AVX2+FMA where available) and the portable paths.
    #[test]
    fn f32_sums_are_fused_multiply_adds() {
        let w = 1.0 + libm::exp2(-12.0);
        let fused = libm::exp2(-11.0) + libm::exp2(-24.0);
        let unfused = ((w as f32) * (w as f32)) + -1.0f32;
        assert_eq!(
            f64::from(unfused),
            libm::exp2(-11.0),
            "the case needs fusing"
        );
        let output = |sum: f64| f64::from(nan_to_zero(tanh(sum)) as f32);
        assert_ne!(
            output(fused).to_bits(),
            output(f64::from(unfused)).to_bits()
        );
        let units = 19;
        let parameters: Vec<f64> = [vec![w; units], vec![-1.0; units]].concat();
        let mut mlp = Mlp::new(1, &[], units, Activation::Tanh, Precision::F32, &parameters);
        let mut portable = mlp.clone();
        for n in 1..=9 {
            let x = vec![w; n];
            let expected = vec![output(fused).to_bits(); n * units];
            let mut y = vec![f64::NAN; n * units];
            mlp.activate_batch(&x, &mut y);
            assert_eq!(bits(&y), expected, "batch of {n}");
            mlp.activate(&x[..1], &mut y[..units]);
            assert_eq!(bits(&y[..units]), expected[..units], "single");
            portable.grow(n);
            let mut by_portable = vec![f64::NAN; n * units];
            portable.forward(&x, &mut by_portable, n);
            assert_eq!(bits(&by_portable), expected, "portable batch of {n}");
        }
    }

    /// f32 sums stay within 1e-4 of the f64 ones on ordinary networks (and differ from them:
    /// the precision really changes).
    #[test]
    fn f32_outputs_are_close_to_f64_outputs() {
        let mut rng = rng(50);
        let mut differ = 0;
        for shape @ (inputs, _, outputs) in SHAPES {
            let wide = networks(51, shape, Precision::F64, 0.5);
            let narrow = networks(51, shape, Precision::F32, 0.5);
            for (mut a, mut b) in wide.into_iter().zip(narrow) {
                for _ in 0..50 {
                    let x: Vec<f64> = (0..inputs).map(|_| uniform(&mut rng, -1.0, 1.0)).collect();
                    let (mut ya, mut yb) = (vec![0.0; outputs], vec![0.0; outputs]);
                    a.activate(&x, &mut ya);
                    b.activate(&x, &mut yb);
                    for (u, v) in ya.iter().zip(&yb) {
                        assert!((u - v).abs() <= 1e-4, "{shape:?}: {u} vs {v}");
                        differ += usize::from(u != v);
                    }
                }
            }
        }
        assert!(differ > 0, "f32 gave the f64 bits everywhere");
    }

    /// Parameters beyond the f32 range round to ±∞; the outputs stay in [-1, 1] (NaN sums
    /// become 0), as for every f64 brain.
    #[test]
    fn f32_brains_with_huge_parameters_stay_total() {
        let shape = (4, &[3][..], 2);
        let mut p = vec![0.5; parameter_count(4, &[3], 2)];
        p[0] = 1e300;
        p[1] = -1e300;
        p[20] = f64::MAX;
        for activation in [Activation::Tanh, Activation::Sigmoid, Activation::Relu] {
            let mut mlp = Mlp::new(shape.0, shape.1, shape.2, activation, Precision::F32, &p);
            for x in [[1.0, 1.0, 0.0, -2.0], [0.0; 4], [1e300, -1e300, 3.0, 0.5]] {
                let mut y = [f64::NAN; 2];
                mlp.activate(&x, &mut y);
                assert!(y.iter().all(|v| (-1.0..=1.0).contains(v)), "{y:?}");
            }
        }
    }
}
