//! The sample-lane batch pass of small f64 MLPs (the standard brain: 24 → 16 → 2): one AVX2
//! register holds one unit's sums for 4 samples of a batch, instead of 4 units of one sample.
//!
//! # Why
//!
//! The unit-lane batch kernel ([`super::activation::affine_batch_portable`]) must broadcast
//! every sample's input i into a register before multiplying it by a row of weights: for a tile
//! of 4 samples × 8 units, 4 broadcasts and 2 weight loads per 16 multiply-adds. Here the 4
//! samples' input i is one register (the tile is copied input-major once) and every weight is
//! stored repeated in 4 lanes, so a term of 4 samples is one multiply with the weight as memory
//! operand and one add: per input, 1 load and 8 + 8 arithmetic instructions for 8 units × 4
//! samples. The repeated weights take 4 times the memory (32 bytes a weight), so only
//! networks of at most [`MAX_WEIGHTS`] weights (64 KiB repeated, L1/L2-resident) use it;
//! larger ones (WaterWorld's 98 → 100 → 2) keep the unit-lane kernel.
//!
//! The batch goes layer by layer (see `lane_pass` in [`super::mlp`]): each layer's sums tile
//! by tile and block of units by block ([`sums`]), written in the lane layout the next layer
//! reads (unit-major, 4 samples side by side), so the hidden activations need no copy; then
//! the layer's function over all the tiles in one vectorised loop ([`finish`]). Only the
//! inputs are copied into tiles ([`load_tile`], a 4 × 4 transpose) and the outputs out of
//! them. The tanh reads its constants from memory ([`TanhLanes`]), which saves a broadcast
//! per constant that does not fit in a register.
//!
//! The first layer leaves out the inputs that are ±0 in every sample of the batch (in a
//! world, the smell components no odour uses, the shock without aversive objects):
//! [`LiveInputs`] finds them, and their terms are dropped only where that provably keeps
//! every bit (see there).
//!
//! # Same bits
//!
//! Each lane's sum is the same sequence as in the single pass: the bias, then + w_ji · x_i
//! for i = 0, 1, … with a separate multiply and add (no fused multiply-add), and the
//! activation and output functions are the same scalar functions applied lane by lane. A
//! last tile of fewer than 4 samples fills its empty lanes with zeros, whose results are
//! dropped.

use super::activation::{tanh_with, Activation, TanhConstants};

/// Samples per tile: the f64 values of one AVX2 register.
pub const LANES: usize = 4;

/// One value per sample of a tile.
pub type Lanes = [f64; LANES];

/// Networks with at most this many weights (all layers) take the sample-lane pass: their
/// repeated weights take at most 64 KiB.
pub const MAX_WEIGHTS: usize = 2048;

/// What a layer's sums go through before they are stored.
#[derive(Debug, Clone, Copy)]
pub enum Stage {
    /// A hidden layer: its activation function.
    Hidden(Activation),
    /// The output layer: tanh, NaN to 0 (as [`super::activation::tanh_outputs`]).
    Output,
}

/// The width of the unit block that starts with `remaining` units left: 8, then 4, 2, 1
/// (the order [`layer`] takes them in).
fn block_width(remaining: usize) -> usize {
    [8, 4, 2, 1]
        .into_iter()
        .find(|&n| n <= remaining)
        .unwrap_or(1)
}

/// A layer's weights for [`layer`], from its input-major ones (`transposed`, inputs × units,
/// see [`super::activation::transpose`]): block by block of units (widths 8, 4, 2, 1 as
/// [`layer`] takes them), input by input, the block's weights, each repeated in the 4 lanes.
/// The block of units j..j + N thus owns the contiguous range p·j..p·(j + N) (p inputs), in
/// which input i's N weights are contiguous: the kernel walks it without any index arithmetic.
pub fn repeat(transposed: &[f64], units: usize) -> Vec<Lanes> {
    let inputs = transposed.len().checked_div(units).unwrap_or(0);
    let mut repeated = Vec::with_capacity(transposed.len());
    let mut j = 0;
    while j < units {
        let n = block_width(units - j);
        for row in transposed.chunks_exact(units).take(inputs) {
            repeated.extend(row[j..j + n].iter().map(|&w| [w; LANES]));
        }
        j += n;
    }
    repeated
}

/// Copies `count` (1 to 4) samples' inputs (`x`: `count` rows of `xt.len()` values) into the
/// input-major tile `xt` (input i of sample t at `xt[i][t]`); the empty lanes become 0.
#[inline(always)]
pub fn load_tile(x: &[f64], count: usize, xt: &mut [Lanes]) {
    let p = xt.len();
    if count == LANES {
        let (r0, rest) = x.split_at(p);
        let (r1, rest) = rest.split_at(p);
        let (r2, r3) = rest.split_at(p);
        let rows = r0.iter().zip(r1).zip(r2.iter().zip(&r3[..p]));
        for (lane, ((&a, &b), (&c, &d))) in xt.iter_mut().zip(rows) {
            *lane = [a, b, c, d];
        }
    } else {
        xt.fill([0.0; LANES]);
        for (t, row) in x.chunks_exact(p.max(1)).take(count).enumerate() {
            for (lane, &v) in xt.iter_mut().zip(row) {
                lane[t] = v;
            }
        }
    }
}

/// The first layer's inputs that are zero in every sample of a batch, and how to leave them
/// out of the sums.
///
/// # Why it keeps the bits
///
/// A sum is acc = b_j, then acc += w_ji · x_i for i = 0, 1, … (separate multiply and add,
/// rounded to nearest). With x_i = ±0 and w_ji finite the term is ±0, and a + (±0) is a, bit
/// for bit, unless a is −0 (−0 + +0 = +0). In round-to-nearest a sum is −0 only when both of
/// its operands are −0, so if b_j is not −0 the accumulator is never −0 and a zero term
/// changes nothing: leaving it out keeps every bit. A NaN b_j is excluded too (its sum is NaN
/// whatever the terms, but a signalling NaN is only quieted by an addition). So a network is
/// skip-safe when no first-layer bias is −0 or NaN ([`LiveInputs::new`]), and then an input
/// is skipped only when it is ±0 in every sample of the batch and all its weights are finite
/// (w · 0 is NaN for w = ±∞ or NaN).
///
/// # How
///
/// Per batch: the inputs' bits (sign cleared) OR-ed over the samples tell the zero columns;
/// the live inputs' weights are compacted into a copy of the first layer in the [`repeat`]
/// layout for that many inputs, rebuilt only when the set of live inputs changes (the zero
/// columns of a world, such as smell components no odour uses, stay zero for the whole run),
/// and the tiles take only the live inputs ([`load_live_tile`]), so [`sums`] runs as for a
/// narrower layer. On the standard foraging world 9 of the 24 inputs never change from 0.
/// Where few inputs are zero the search and the gather cost more than they save: then the
/// full layer runs and the search backs off ([`LiveInputs::worth_it`]).
#[derive(Debug, Clone, PartialEq)]
pub struct LiveInputs {
    /// Per input, where its OR starts: 0 if a zero there may be skipped (all its first-layer
    /// weights finite), all ones otherwise (so that it is always live).
    start: Vec<u64>,
    /// Per input: the OR of its bits over the batch's samples (scratch).
    seen: Vec<u64>,
    /// The live inputs of the last batch as a bit set, 64 inputs a word (input i at bit
    /// i % 64 of word i / 64).
    mask: Vec<u64>,
    /// The live inputs the compacted weights are for, in index order (never empty: input 0
    /// stays live when every input is zero, since [`sums`] needs an input).
    live: Vec<usize>,
    /// The first layer's weights for the `live` inputs only ([`compact`]).
    weights: Vec<Lanes>,
    /// Batches to run in full before looking for zero columns again, after a batch where
    /// skipping did not pay ([`LiveInputs::worth_it`]).
    idle: u32,
    /// The last wait: doubled after every batch where skipping did not pay (up to 64),
    /// 0 after one where it did.
    backoff: u32,
}

/// The bits of a value but its sign: 0 exactly for ±0.
const MAGNITUDE: u64 = !(1 << 63);

impl LiveInputs {
    /// The skipping state of a first layer of `units` units whose input-major weights are
    /// `transposed` (inputs × units) and biases `biases`; `None` when the layer is not
    /// skip-safe (a bias is −0 or NaN) or no input has all-finite weights.
    pub fn new(transposed: &[f64], biases: &[f64], units: usize) -> Option<LiveInputs> {
        let unsafe_bias = biases
            .iter()
            .any(|b| b.is_nan() || b.to_bits() == (-0.0f64).to_bits());
        if unsafe_bias || units == 0 {
            return None;
        }
        let start: Vec<u64> = transposed
            .chunks_exact(units)
            .map(|weights| {
                if weights.iter().all(|w| w.is_finite()) {
                    0
                } else {
                    u64::MAX
                }
            })
            .collect();
        let p = start.len();
        // Every input live to begin with: what `repeat` gives, so no compaction is needed
        // until a batch has a zero column.
        let mut mask = vec![u64::MAX; p.div_ceil(64)];
        if let Some(last) = mask.last_mut().filter(|_| p % 64 != 0) {
            *last = (1 << (p % 64)) - 1;
        }
        start.contains(&0).then(|| LiveInputs {
            start,
            seen: vec![0; p],
            mask,
            live: (0..p).collect(),
            weights: Vec::with_capacity(p * units),
            idle: 0,
            backoff: 0,
        })
    }

    /// Finds the live inputs of the batch `x` (rows of p inputs, p the layer's input count)
    /// and, if they changed, compacts the first layer's `weights` ([`repeat`] layout, `units`
    /// units) for them. Returns the live inputs and their weights, or `None` when the full
    /// layer is to run as it is: every input live, or too few zero columns to pay for
    /// finding them and gathering the others (see [`LiveInputs::worth_it`]).
    #[inline(always)]
    pub fn update(
        &mut self,
        x: &[f64],
        weights: &[Lanes],
        units: usize,
    ) -> Option<(&[usize], &[Lanes])> {
        if self.idle > 0 {
            self.idle -= 1;
            return None;
        }
        let p = self.seen.len();
        // 24 inputs (the standard world's) in one pass over the rows, else 16, 8, 4.
        let c = or_columns::<6>(x, p, (&self.start, &mut self.seen), 0);
        let c = or_columns::<4>(x, p, (&self.start, &mut self.seen), c);
        let c = or_columns::<2>(x, p, (&self.start, &mut self.seen), c);
        let c = or_columns::<1>(x, p, (&self.start, &mut self.seen), c);
        for (i, (seen, &start)) in self.seen.iter_mut().zip(&self.start).enumerate().skip(c) {
            *seen = x
                .chunks_exact(p)
                .fold(start, |or, row| or | row[i].to_bits());
        }
        let (mut same, mut live) = (true, 0);
        for (cached, seen) in self.mask.iter().zip(self.seen.chunks(64)) {
            let word = mask_word(seen);
            same &= *cached == word;
            live += word.count_ones() as usize;
        }
        if !Self::worth_it(p, live.max(1), units) {
            // Back off: look again after 1, 2, 4, … 64 batches of the full layer.
            self.backoff = (2 * self.backoff).clamp(1, 64);
            self.idle = self.backoff;
            return None;
        }
        self.backoff = 0;
        if !same {
            for (cached, seen) in self.mask.iter_mut().zip(self.seen.chunks(64)) {
                *cached = mask_word(seen);
            }
            self.live.clear();
            for (i, &seen) in self.seen.iter().enumerate() {
                if seen & MAGNITUDE != 0 {
                    self.live.push(i);
                }
            }
            if self.live.is_empty() {
                self.live.push(0);
            }
            compact(weights, units, p, &self.live, &mut self.weights);
        }
        Some((&self.live[..], &self.weights[..]))
    }

    /// Whether leaving out all but `live` of `p` inputs of a layer of `units` units saves
    /// instructions: per tile of 4 samples and input, the full layer copies the input in
    /// about 4 instructions (a 4 × 4 transpose) and multiplies and adds about 2 per unit,
    /// while finding the zero columns costs about 2 per input and gathering a live input
    /// about 10. With most inputs live (eye-predators' 72 inputs, 5 to 6 of them zero) it
    /// does not pay; on the foraging world (12 of 24 zero) it does.
    fn worth_it(p: usize, live: usize, units: usize) -> bool {
        live < p && p + units * (p - live) > 5 * live
    }
}

/// The bit set of the inputs (up to 64) whose OR `seen` is not ±0.
#[inline(always)]
fn mask_word(seen: &[u64]) -> u64 {
    let mut word = 0;
    for (b, &s) in seen.iter().enumerate() {
        word |= u64::from(s & MAGNITUDE != 0) << b;
    }
    word
}

/// The OR of the bits of the inputs c.. of every row of `x` (rows of `p`), each starting from
/// `start`, into `seen`, in whole groups of `G` × 4 inputs (their ORs stay in registers while
/// the rows are walked); returns where it stopped.
#[inline(always)]
fn or_columns<const G: usize>(
    x: &[f64],
    p: usize,
    (start, seen): (&[u64], &mut [u64]),
    mut c: usize,
) -> usize {
    while c + 4 * G <= p {
        let mut or = [[0u64; LANES]; G];
        for (or, start) in or.iter_mut().zip(start[c..c + 4 * G].chunks_exact(LANES)) {
            or.copy_from_slice(start);
        }
        for row in x.chunks_exact(p) {
            for (or, v) in or.iter_mut().zip(row[c..c + 4 * G].chunks_exact(LANES)) {
                for t in 0..LANES {
                    or[t] |= v[t].to_bits();
                }
            }
        }
        seen[c..c + 4 * G].copy_from_slice(or.as_flattened());
        c += 4 * G;
    }
    c
}

/// The weights of a layer laid out by [`repeat`] (`weights`, `units` units, `p` inputs) for
/// the inputs `live` only (in index order), in the layout [`repeat`] gives a layer of
/// `live.len()` inputs, into `out` (cleared first; within its capacity once it has held a
/// layer's weights, so no allocation).
pub fn compact(weights: &[Lanes], units: usize, p: usize, live: &[usize], out: &mut Vec<Lanes>) {
    out.clear();
    let mut j = 0;
    while j < units {
        let n = block_width(units - j);
        // The block j..j + n owns p·j..p·(j + n), input i's n weights at p·j + i·n.
        let block = &weights[p * j..p * (j + n)];
        for &i in live {
            out.extend_from_slice(&block[i * n..(i + 1) * n]);
        }
        j += n;
    }
}

/// [`load_tile`] for the inputs `live` only: `x` holds `count` (1 to 4) rows of `p` inputs,
/// and `xt[k]` receives input `live[k]` of each sample (the empty lanes 0).
#[inline(always)]
pub fn load_live_tile(x: &[f64], p: usize, count: usize, live: &[usize], xt: &mut [Lanes]) {
    if count == LANES {
        let (r0, rest) = x.split_at(p);
        let (r1, rest) = rest.split_at(p);
        let (r2, r3) = rest.split_at(p);
        let r3 = &r3[..p];
        for (lane, &i) in xt.iter_mut().zip(live) {
            *lane = [r0[i], r1[i], r2[i], r3[i]];
        }
    } else {
        xt.fill([0.0; LANES]);
        for (t, row) in x.chunks_exact(p).take(count).enumerate() {
            for (lane, &i) in xt.iter_mut().zip(live) {
                lane[t] = row[i];
            }
        }
    }
}

/// [`load_live_tile`] for whole tiles: `x` holds rows of `p` inputs, 4 rows a tile, and
/// tile k's `live.len()` [`Lanes`] in `xt` receive its samples' inputs `live` (as many
/// tiles as both hold). Never inlined: in its own frame the gather keeps its pointers in
/// registers (inlined into the pass it reloaded spilled ones for every input), and it takes
/// the live inputs two at a time.
#[inline(never)]
pub fn load_live_tiles(x: &[f64], p: usize, live: &[usize], xt: &mut [Lanes]) {
    let width = live.len();
    if p == 0 || width == 0 {
        return;
    }
    for (x, xt) in x.chunks_exact(LANES * p).zip(xt.chunks_exact_mut(width)) {
        let (r0, rest) = x.split_at(p);
        let (r1, rest) = rest.split_at(p);
        let (r2, r3) = rest.split_at(p);
        let pairs = xt.chunks_exact_mut(2).zip(live.chunks_exact(2));
        for (lanes, pair) in pairs {
            let (i, j) = (pair[0], pair[1]);
            lanes[0] = [r0[i], r1[i], r2[i], r3[i]];
            lanes[1] = [r0[j], r1[j], r2[j], r3[j]];
        }
        if width % 2 == 1 {
            let i = live[width - 1];
            xt[width - 1] = [r0[i], r1[i], r2[i], r3[i]];
        }
    }
}

/// One layer's sums for every tile: y_j = b_j + w_j0 x_0 + w_j1 x_1 + … in every lane, with
/// `weights` the layer's weights as [`repeat`] lays them out, `x` the tiles' inputs (p
/// [`Lanes`] per tile, one per input; p ≥ 1), `y` the tiles' sums (one [`Lanes`] per unit
/// and tile). Block by block of units, tile by tile: the block's biases and weights are
/// located once for all the tiles. The layer's function comes after ([`finish`]).
#[inline(always)]
pub fn sums(weights: &[Lanes], biases: &[f64], x: &[Lanes], p: usize, y: &mut [Lanes]) {
    let j = blocks::<8>(weights, biases, (x, p), y, 0);
    let j = blocks::<4>(weights, biases, (x, p), y, j);
    let j = blocks::<2>(weights, biases, (x, p), y, j);
    blocks::<1>(weights, biases, (x, p), y, j);
}

/// [`sums`] for the units j.. in whole blocks of `N` (N registers of sums over all the
/// inputs); returns where it stopped.
#[inline(always)]
fn blocks<const N: usize>(
    weights: &[Lanes],
    biases: &[f64],
    (x, p): (&[Lanes], usize),
    y: &mut [Lanes],
    mut j: usize,
) -> usize {
    let units = biases.len();
    while j + N <= units {
        let start: &[f64; N] = biases[j..j + N].try_into().expect("N biases");
        // The block's weights, input by input (see `repeat`).
        let block = &weights[p * j..p * (j + N)];
        for (x, y) in x.chunks_exact(p).zip(y.chunks_exact_mut(units)) {
            let mut acc = [[0.0; LANES]; N];
            for k in 0..N {
                acc[k] = [start[k]; LANES];
            }
            // Four inputs per step (in index order) to spread the loop overhead, then the
            // last 0–3 one by one.
            let (rows, xs) = (block.chunks_exact(4 * N), x.chunks_exact(4));
            let rest = rows.remainder().chunks_exact(N).zip(xs.remainder());
            for (rows, xs) in rows.zip(xs) {
                let (w01, w23) = rows.split_at(2 * N);
                let ((w0, w1), (w2, w3)) = (w01.split_at(N), w23.split_at(N));
                step(&mut acc, w0, &xs[0]);
                step(&mut acc, w1, &xs[1]);
                step(&mut acc, w2, &xs[2]);
                step(&mut acc, w3, &xs[3]);
            }
            for (row, xi) in rest {
                step(&mut acc, row, xi);
            }
            y[j..j + N].copy_from_slice(&acc);
        }
        j += N;
    }
    j
}

/// One input of a tile: every sum gains its term w · x (a multiply, then an add).
#[inline(always)]
fn step<const N: usize>(acc: &mut [Lanes; N], w: &[Lanes], x: &Lanes) {
    let w: &[Lanes; N] = w.try_into().expect("N weights");
    for k in 0..N {
        for t in 0..LANES {
            acc[k][t] += w[k][t] * x[t];
        }
    }
}

/// The stage's function on every value of `y` (after the sums are stored: the sums stay in
/// registers only if nothing indexes them at run time). tanh (hidden tanh units and the
/// outputs) runs [`TanhLanes::apply`]; the other functions the same loops as a single pass's
/// ([`Activation::apply_slice`]) on the flattened values. Either way the same function
/// value by value.
#[inline(always)]
pub fn finish(y: &mut [Lanes], stage: Stage, tanh: &TanhLanes) {
    match stage {
        Stage::Hidden(Activation::Tanh) => tanh.apply::<false>(y),
        Stage::Hidden(activation) => activation.apply_slice(y.as_flattened_mut()),
        Stage::Output => tanh.apply::<true>(y),
    }
}

/// The constants of [`super::activation::tanh`], kept in the network, so that the lane pass
/// reads them from memory.
///
/// Why: with its temporaries, the tanh's 15 constants do not fit in the 16 AVX2 registers;
/// constants the compiler cannot see are broadcast once and the spilled ones read back as
/// memory operands, instead of re-broadcast in every iteration (docs/performance.md). The
/// formula is [`tanh_with`]'s, so the bits are [`super::activation::tanh`]'s.
#[derive(Debug, Clone, PartialEq)]
pub struct TanhLanes(TanhConstants);

impl Default for TanhLanes {
    fn default() -> Self {
        TanhLanes(super::activation::TANH)
    }
}

impl TanhLanes {
    /// [`super::activation::tanh`] of every value of `y` (then NaN to 0 when `OUTPUT`, as
    /// [`super::activation::tanh_outputs`]), vectorised over the values.
    #[inline(always)]
    pub fn apply<const OUTPUT: bool>(&self, y: &mut [Lanes]) {
        for v in y.as_flattened_mut() {
            let r = tanh_with(&self.0, *v);
            *v = if OUTPUT && r.is_nan() { 0.0 } else { r };
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The block of units j..j + N owns p·j..p·(j + N), input by input, every weight in all
    /// the lanes: 11 units are blocks of 8, 2 and 1.
    #[test]
    fn repeat_lays_the_weights_out_block_by_block() {
        let (units, inputs) = (11, 3);
        // Input-major: weight from input i to unit j at i * units + j.
        let transposed: Vec<f64> = (0..units * inputs).map(|k| k as f64).collect();
        let repeated = repeat(&transposed, units);
        assert_eq!(repeated.len(), transposed.len());
        let mut expected = Vec::new();
        for (j, n) in [(0, 8), (8, 2), (10, 1)] {
            for i in 0..inputs {
                for k in j..j + n {
                    expected.push([transposed[i * units + k]; LANES]);
                }
            }
        }
        assert_eq!(repeated, expected);
        assert!(repeat(&[], 0).is_empty());
    }

    /// Each lane gets the single-sample sum b_j + w_j0 x_0 + … (left to right, separate
    /// multiplies and adds) for every unit-block remainder and input-step remainder.
    #[test]
    fn sums_are_the_single_sample_sums_in_every_lane() {
        for (units, inputs) in [(1, 1), (3, 5), (16, 24), (15, 7), (2, 16), (9, 4)] {
            let transposed: Vec<f64> = (0..units * inputs)
                .map(|k| ((k * 37 % 23) as f64 - 11.0) / 7.3)
                .collect();
            let biases: Vec<f64> = (0..units).map(|j| j as f64 * 0.31 - 1.0).collect();
            let tiles = 3;
            let x: Vec<Lanes> = (0..tiles * inputs)
                .map(|k| std::array::from_fn(|t| libm::sin((k * 4 + t) as f64 * 0.77)))
                .collect();
            let mut y = vec![[f64::NAN; LANES]; tiles * units];
            sums(&repeat(&transposed, units), &biases, &x, inputs, &mut y);
            for k in 0..tiles {
                for t in 0..LANES {
                    for j in 0..units {
                        let mut sum = biases[j];
                        for i in 0..inputs {
                            sum += transposed[i * units + j] * x[k * inputs + i][t];
                        }
                        let got = y[k * units + j][t];
                        assert_eq!(got.to_bits(), sum.to_bits(), "{units} x {inputs}");
                    }
                }
            }
        }
    }

    /// Deterministic values for a test, varied by index.
    fn value(k: usize) -> f64 {
        ((k * 37 % 23) as f64 - 11.0) / 7.3
    }

    /// The live inputs of a batch: those not ±0 in every sample, plus those with a
    /// non-finite weight; input 0 when all are zero; `None` while all are live. The
    /// compacted weights are the full layer's for the live inputs.
    #[test]
    fn live_inputs_are_the_nonzero_and_the_unskippable_columns() {
        let (units, p) = (11, 70);
        let mut transposed: Vec<f64> = (0..units * p).map(value).collect();
        transposed[5 * units + 3] = f64::INFINITY;
        transposed[66 * units] = f64::NAN;
        let biases: Vec<f64> = (0..units).map(|j| j as f64 - 5.0).collect();
        let full = repeat(&transposed, units);
        let mut live = LiveInputs::new(&transposed, &biases, units).expect("skip-safe");
        let rows = 6;
        let batch = |zero: &dyn Fn(usize) -> bool| -> Vec<f64> {
            (0..rows * p)
                .map(|k| match (zero(k % p), k / p) {
                    (true, r) if r % 2 == 0 => 0.0,
                    (true, _) => -0.0,
                    (false, r) => value(k) + r as f64 * 0.01 + 0.5,
                })
                .collect()
        };
        // Input 9 nonzero in one sample only: live.
        let mut x = batch(&|i| i % 3 != 0 || i == 5 || i == 66);
        x[4 * p + 9] = 1e-310;
        for round in 0..2 {
            let (inputs, weights) = live.update(&x, &full, units).expect("zero columns");
            let expected: Vec<usize> = (0..p)
                .filter(|&i| i % 3 == 0 || [5, 9, 66].contains(&i))
                .collect();
            assert_eq!(inputs, expected, "round {round}");
            let mut by_hand = Vec::new();
            compact(&full, units, p, &expected, &mut by_hand);
            let bits = |w: &[Lanes]| -> Vec<u64> {
                w.as_flattened().iter().map(|v| v.to_bits()).collect()
            };
            assert!(bits(weights) == bits(&by_hand));
            let narrow: Vec<f64> = expected
                .iter()
                .flat_map(|&i| transposed[i * units..(i + 1) * units].to_vec())
                .collect();
            assert!(bits(&by_hand) == bits(&repeat(&narrow, units)));
        }
        let (inputs, _) = live.update(&batch(&|_| true), &full, units).expect("zero");
        assert_eq!(inputs, [5, 66]);
        let mut all_zero = LiveInputs::new(&transposed[..units * 4], &biases, units).unwrap();
        let (inputs, _) = all_zero
            .update(&[0.0; 4 * 3], &full[..units * 4], units)
            .unwrap();
        assert_eq!(inputs, [0]);
        // Every input live: the full layer, and the next batch runs it without looking.
        assert!(live.update(&batch(&|_| false), &full, units).is_none());
        assert!(live.update(&x, &full, units).is_none());
        assert!(live.update(&x, &full, units).is_some());
    }

    /// Skipping runs when it saves instructions (many zero columns); otherwise the full layer
    /// runs, without looking for zero columns for 1, 2, 4, … up to 64 batches.
    #[test]
    fn few_zero_columns_back_off() {
        assert!(LiveInputs::worth_it(24, 12, 16));
        assert!(LiveInputs::worth_it(24, 1, 1));
        assert!(!LiveInputs::worth_it(72, 66, 16));
        assert!(!LiveInputs::worth_it(24, 24, 16));
        let (units, p) = (16, 72);
        let transposed: Vec<f64> = (0..units * p).map(value).collect();
        let full = repeat(&transposed, units);
        let mut live = LiveInputs::new(&transposed, &[1.0; 16], units).unwrap();
        let batch = |zeros: usize| -> Vec<f64> {
            (0..4 * p)
                .map(|k| if k % p < zeros { 0.0 } else { value(k) + 0.5 })
                .collect()
        };
        let (few, many) = (batch(6), batch(40));
        for _ in 0..9 {
            // Not worth it: the full layer, then one batch without looking.
            assert!(live.update(&few, &full, units).is_none());
            assert!(live.update(&many, &full, units).is_none());
            // Worth it: skipping, and the backoff starts over.
            assert!(live.update(&many, &full, units).is_some());
        }
        let mut waits = Vec::new();
        for _ in 0..400 {
            let looked = live.idle == 0;
            assert!(live.update(&few, &full, units).is_none());
            if looked {
                waits.push(live.idle);
            }
        }
        assert_eq!(waits[..9], [1, 2, 4, 8, 16, 32, 64, 64, 64]);
    }

    /// Not skip-safe: a first-layer bias that is −0 or NaN (its sum could differ without
    /// the zero terms), or no input whose weights are all finite.
    #[test]
    fn layers_with_a_negative_zero_or_nan_bias_skip_nothing() {
        let transposed = [1.0, 2.0, 3.0, 4.0];
        assert!(LiveInputs::new(&transposed, &[0.0, 1.0], 2).is_some());
        assert!(LiveInputs::new(&transposed, &[1.0, -0.0], 2).is_none());
        assert!(LiveInputs::new(&transposed, &[f64::NAN, 1.0], 2).is_none());
        assert!(LiveInputs::new(&[1.0, f64::INFINITY, f64::NAN, 4.0], &[0.0, 1.0], 2).is_none());
        assert!(LiveInputs::new(&[1.0, f64::INFINITY, 3.0, 4.0], &[0.0, 1.0], 2).is_some());
    }

    /// The tiles of the live inputs and the compacted weights give, in every lane and for
    /// every tile remainder, the single-sample sums over all the inputs when the skipped
    /// ones are ±0 in every sample (and the biases are not −0).
    #[test]
    fn sums_over_the_live_inputs_are_the_full_sums() {
        for (units, p) in [(1, 1), (3, 5), (16, 24), (15, 7), (2, 16), (9, 70)] {
            let transposed: Vec<f64> = (0..units * p).map(value).collect();
            let biases: Vec<f64> = (0..units).map(|j| j as f64 * 0.31 - 1.0).collect();
            let full = repeat(&transposed, units);
            let zero = |i: usize| i % 3 != 0;
            let mut live = LiveInputs::new(&transposed, &biases, units).unwrap();
            for n in 1..=9 {
                let x: Vec<f64> = (0..n * p)
                    .map(|k| match (zero(k % p), k % 2) {
                        (true, 0) => 0.0,
                        (true, _) => -0.0,
                        _ => libm::sin(k as f64 * 0.77),
                    })
                    .collect();
                let Some((inputs, weights)) = live.update(&x, &full, units) else {
                    assert_eq!(p, 1, "{units} x {p}: skipping pays");
                    continue;
                };
                let (inputs, weights) = (inputs.to_vec(), weights.to_vec());
                let width = inputs.len();
                let tiles = n.div_ceil(LANES);
                let mut xt = vec![[f64::NAN; LANES]; tiles * width];
                for k in 0..tiles {
                    let count = (n - k * LANES).min(LANES);
                    let rows = &x[k * LANES * p..(k * LANES + count) * p];
                    let tile = &mut xt[k * width..(k + 1) * width];
                    load_live_tile(rows, p, count, &inputs, tile);
                }
                let mut y = vec![[f64::NAN; LANES]; tiles * units];
                sums(&weights, &biases, &xt, width, &mut y);
                for (s, x) in x.chunks_exact(p).enumerate() {
                    for j in 0..units {
                        let mut sum = biases[j];
                        for (i, &xi) in x.iter().enumerate() {
                            sum += transposed[i * units + j] * xi;
                        }
                        let got = y[s / LANES * units + j][s % LANES];
                        assert_eq!(got.to_bits(), sum.to_bits(), "{units} x {p}, n = {n}");
                    }
                }
            }
        }
    }

    /// [`TanhLanes::apply`] is [`super::super::activation::tanh`] (and, for the outputs,
    /// `nan_to_zero` of it) bit for bit: on a sweep, the clamps and where the rational
    /// function crosses 1, ±0, subnormals, ±∞ and NaNs.
    #[test]
    fn lane_tanh_is_the_scalar_tanh_bit_for_bit() {
        use crate::brain::activation::{nan_to_zero, tanh};
        let mut values: Vec<f64> = (-4000..=4000).map(|k| k as f64 * 0.00371).collect();
        values.extend((0..400).map(|k| 11.0 + k as f64 * 0.0025));
        values.extend((0..400).map(|k| -(11.0 + k as f64 * 0.0025)));
        values.extend([
            0.0,
            -0.0,
            5e-324,
            -5e-324,
            1e-300,
            12.0,
            -12.0,
            12.000000000000002,
            11.0227,
            f64::MAX,
            f64::MIN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            -f64::NAN,
        ]);
        while values.len() % LANES != 0 {
            values.push(0.5);
        }
        let lanes: Vec<Lanes> = values
            .chunks_exact(LANES)
            .map(|c| c.try_into().unwrap())
            .collect();
        let tanh_lanes = TanhLanes::default();
        for output in [false, true] {
            let mut y = lanes.clone();
            if output {
                tanh_lanes.apply::<true>(&mut y);
            } else {
                tanh_lanes.apply::<false>(&mut y);
            }
            for (&x, &got) in values.iter().zip(y.as_flattened()) {
                let expected = if output {
                    nan_to_zero(tanh(x))
                } else {
                    tanh(x)
                };
                assert_eq!(got.to_bits(), expected.to_bits(), "{x:e} output {output}");
            }
        }
    }

    /// [`load_live_tiles`] fills whole tiles as [`load_live_tile`] does one by one, for odd
    /// and even numbers of live inputs, and touches no tile beyond the whole ones.
    #[test]
    fn whole_tiles_gather_the_live_inputs_as_single_tiles_do() {
        let p = 13;
        for live in [
            vec![0],
            vec![2, 3],
            vec![0, 4, 5, 12],
            vec![1, 2, 6, 7, 9, 11, 12],
        ] {
            for tiles in 0..4 {
                let x: Vec<f64> = (0..tiles * LANES * p).map(value).collect();
                let width = live.len();
                let mut xt = vec![[f64::NAN; LANES]; (tiles + 1) * width];
                load_live_tiles(&x, p, &live, &mut xt);
                for k in 0..tiles {
                    let rows = &x[k * LANES * p..(k + 1) * LANES * p];
                    let mut tile = vec![[0.0; LANES]; width];
                    load_live_tile(rows, p, LANES, &live, &mut tile);
                    let got = &xt[k * width..(k + 1) * width];
                    assert!(got
                        .as_flattened()
                        .iter()
                        .zip(tile.as_flattened())
                        .all(|(a, b)| a.to_bits() == b.to_bits()));
                }
                assert!(xt[tiles * width..]
                    .as_flattened()
                    .iter()
                    .all(|v| v.is_nan()));
            }
        }
    }
}
