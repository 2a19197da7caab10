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
//! them.
//!
//! # Same bits
//!
//! Each lane's sum is the same sequence as in the single pass: the bias, then + w_ji · x_i
//! for i = 0, 1, … with a separate multiply and add (no fused multiply-add), and the
//! activation and output functions are the same scalar functions applied lane by lane. A
//! last tile of fewer than 4 samples fills its empty lanes with zeros, whose results are
//! dropped.

use super::activation::{tanh_outputs, Activation};

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
/// registers only if nothing indexes them at run time). The same loops as a single pass's
/// ([`Activation::apply_slice`], [`tanh_outputs`]) on the flattened values: vectorised,
/// and the same function value by value.
#[inline(always)]
pub fn finish(y: &mut [Lanes], stage: Stage) {
    let values = y.as_flattened_mut();
    match stage {
        Stage::Hidden(activation) => activation.apply_slice(values),
        Stage::Output => tanh_outputs(values),
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
}
