//! The numeric kernels every brain shares: a fast deterministic tanh, the logistic function
//! built on it, ReLU, the output squashing that keeps motor outputs in [-1, 1], and the affine
//! map (weights times inputs plus biases) of the hot loop.
//!
//! # Why these kernels
//!
//! A brain runs once per creature per tick, and `libm::tanh` costs about 90 instructions a
//! call (through `expm1`). [`tanh`] is instead a rational function evaluated with plain f64
//! `+ - * /` and comparisons, which IEEE 754 rounds exactly the same way on every platform
//! (Rust never contracts `a * b + c` into a fused multiply-add on its own), so it gives the
//! same bits everywhere, like `libm`, at a fraction of the cost. It has no branches, so a
//! loop over a slice ([`tanh_slice`], [`logistic_slice`]) compiles to SIMD code.
//!
//! # Accuracy
//!
//! * [`tanh`]: max |tanh(x) − libm::tanh(x)| ≤ 5.4e-10 for every x ([`TANH_MAX_ERROR`]);
//!   odd (tanh(−x) = −tanh(x) bit for bit), monotone (non-decreasing), |tanh(x)| ≤ 1,
//!   exactly ±1 for |x| ≥ 11.03 and ±∞, ±0 for ±0, NaN for NaN.
//! * [`logistic`] σ(x) = 0.5 + 0.5·tanh(x/2): max error ≤ 2.8e-10 ([`LOGISTIC_MAX_ERROR`]),
//!   in [0, 1], exactly 0 and 1 far out and at ∓∞, exactly 0.5 at 0, NaN for NaN.
//!
//! The unit tests measure both bounds against `libm` (tanh: every 1e-4 on [-20, 20] and every
//! 1e-6 where it reaches 1; σ: every 2e-4 on [-40, 40]) plus edge cases (±0, ±∞, NaN, huge and
//! subnormal inputs); the measured maxima are 5.33e-10 and 2.67e-10. These errors are far below anything evolution can select for, but they are
//! not zero: a brain's outputs differ from the `libm` ones in the ninth or tenth decimal.
//!
//! # Summation order
//!
//! [`affine`] computes every unit's sum as the plain left-to-right sum
//! `b_j + w_j0 x_0 + w_j1 x_1 + …` (bias first, then the inputs in index order). It runs
//! across units rather than across inputs: starting from y = b, it adds x_i times the weights
//! from input i to every unit, for i = 0, 1, …, an axpy over a contiguous row of the
//! input-major (transposed) weight matrix. Each unit's sum keeps its own order, so the
//! compiler can put several units in one SIMD register without reassociating anything (no
//! relaxed floating-point flags), and the result is the same at any vector width.
//!
//! [`affine_batch`] does the same for several samples at once (the samples of a batch share
//! each weight load; see its docs), with every sample's sums in the same order, so each sample
//! gets the bits [`affine`] gives it alone. The kernels are generic over [`Real`] (f64, and
//! f32 for `precision = "f32"` MLPs): in f64 each term is a multiply then an add, in f32 one
//! fused multiply-add ([`Real::add_product`]); IEEE 754 specifies the result of each exactly.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// The activation function of hidden units (`brain.activation`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Activation {
    /// Hyperbolic tangent, output in [-1, 1] (the default); the fast [`tanh`].
    #[default]
    Tanh,
    /// Logistic function 1 / (1 + e^(-x)), output in [0, 1]; the fast [`logistic`].
    Sigmoid,
    /// Rectified linear unit max(0, x), output in [0, ∞). A NaN input gives 0.
    Relu,
}

impl Activation {
    /// The function's value at `x`.
    #[inline]
    pub fn apply(self, x: f64) -> f64 {
        match self {
            Activation::Tanh => tanh(x),
            Activation::Sigmoid => logistic(x),
            Activation::Relu => relu(x),
        }
    }

    /// Replaces every element of `y` by the function's value there (the match is outside the
    /// loop, so each loop is branch-free and vectorised).
    #[inline(always)]
    pub fn apply_slice(self, y: &mut [f64]) {
        match self {
            Activation::Tanh => tanh_slice(y),
            Activation::Sigmoid => logistic_slice(y),
            Activation::Relu => y.iter_mut().for_each(|v| *v = relu(*v)),
        }
    }

    /// The name used in TOML (`"tanh"`, `"sigmoid"`, `"relu"`).
    pub fn name(self) -> &'static str {
        match self {
            Activation::Tanh => "tanh",
            Activation::Sigmoid => "sigmoid",
            Activation::Relu => "relu",
        }
    }
}

/// Upper bound of |fast tanh(x) − tanh(x)| over all x ([`tanh`]); this module's tests measure
/// 5.33e-10.
pub const TANH_MAX_ERROR: f64 = 5.4e-10;

/// Upper bound of |fast σ(x) − σ(x)| over all x ([`logistic`]); this module's tests measure
/// 2.67e-10.
pub const LOGISTIC_MAX_ERROR: f64 = 2.8e-10;

/// [`tanh`] clamps its argument into [-TANH_CLAMP, TANH_CLAMP] (tanh(12) = 1 − 7.6e-11); the
/// rational function has already reached 1 there (it crosses 1 at x ≈ 11.0227 and keeps
/// rising), so the output clamp makes every |x| ≥ 11.03 give exactly ±1.
const TANH_CLAMP: f64 = 12.0;

/// Numerator coefficients p_0 … p_5 of [`tanh`] (powers of x²).
const TANH_P: [f64; 6] = [
    0.9999999980137508,
    0.14019297868708977,
    0.00432010491550617,
    3.960279616433942e-05,
    9.651182760981751e-08,
    2.8229605914669833e-11,
];

/// Denominator coefficients q_1 … q_5 of [`tanh`] (q_0 = 1).
const TANH_Q: [f64; 5] = [
    0.47352630350693203,
    0.028828883373201844,
    0.0004806371281892068,
    2.3603680302778393e-06,
    2.425082880664088e-09,
];

/// Fast deterministic hyperbolic tangent, max absolute error ≤ [`TANH_MAX_ERROR`] (5.4e-10).
///
/// With c = clamp(x, −12, 12) and t = c², it is
///
/// ```text
/// tanh(x) ≈ clamp(c · P(t) / Q(t), −1, 1),
/// P(t) = p0 + p1 t + … + p5 t⁵,   Q(t) = 1 + q1 t + … + q5 t⁵   (both by Horner's rule)
/// ```
///
/// a (5, 5) rational minimax fit of tanh(x)/x in x² for absolute error on [0, 11] (Remez
/// exchange in 40-digit arithmetic, coefficients rounded to f64). The fit is monotone on
/// [0, 12], so the approximation is too; its error equioscillates at ±3.7e-10 on [0, 11], and
/// the maximum 5.3e-10 is where it reaches 1 (x ≈ 11.0227, tanh(x) = 1 − 5.3e-10).
///
/// Both clamps are comparisons that keep a NaN (`if x > c { c } else { x }` is false for NaN),
/// so NaN in gives NaN out, as `libm::tanh` does; ±∞ give ±1. The code has no branches (the
/// clamps become min/max instructions), so loops over slices vectorise.
#[inline(always)]
pub fn tanh(x: f64) -> f64 {
    tanh_with(&TANH, x)
}

/// The constants of [`tanh`]: the clamps, the coefficients, 1 and −1.
///
/// [`tanh`] passes them as compile-time constants; the brains' sample-lane pass passes a copy
/// kept in the network (`lanes::TanhLanes`), so that the compiler reads the ones that do not
/// fit in registers from memory instead of re-broadcasting them. One formula either way.
#[derive(Debug, Clone, PartialEq)]
pub struct TanhConstants {
    /// TANH_CLAMP, −TANH_CLAMP.
    clamp: [f64; 2],
    /// p0 … p5.
    p: [f64; 6],
    /// q1 … q5.
    q: [f64; 5],
    /// 1, −1.
    unit: [f64; 2],
}

/// [`tanh`]'s constants.
pub const TANH: TanhConstants = TanhConstants {
    clamp: [TANH_CLAMP, -TANH_CLAMP],
    p: TANH_P,
    q: TANH_Q,
    unit: [1.0, -1.0],
};

/// [`tanh`] computed with the constants `k` (which are [`TANH`]'s, wherever they are read
/// from): the same comparisons, Horner steps and division.
#[inline(always)]
pub fn tanh_with(k: &TanhConstants, x: f64) -> f64 {
    let [hi, lo] = k.clamp;
    let [p0, p1, p2, p3, p4, p5] = k.p;
    let [q1, q2, q3, q4, q5] = k.q;
    let [one, minus_one] = k.unit;
    let c = if x > hi { hi } else { x };
    let c = if c < lo { lo } else { c };
    let t = c * c;
    let p = ((((p5 * t + p4) * t + p3) * t + p2) * t + p1) * t + p0;
    let q = ((((q5 * t + q4) * t + q3) * t + q2) * t + q1) * t + one;
    let y = c * p / q;
    let y = if y > one { one } else { y };
    if y < minus_one {
        minus_one
    } else {
        y
    }
}

/// [`tanh`] of every element, in place (vectorised).
#[inline(always)]
pub fn tanh_slice(y: &mut [f64]) {
    for v in y {
        *v = tanh(*v);
    }
}

/// [`nan_to_zero`] of [`tanh`] for every element, in place: output units (vectorised).
#[inline(always)]
pub fn tanh_outputs(y: &mut [f64]) {
    for v in y {
        *v = nan_to_zero(tanh(*v));
    }
}

/// The logistic function σ(x) = 1 / (1 + e^(-x)), computed as 0.5 + 0.5·tanh(0.5·x) (an
/// identity) with the fast [`tanh`], so max absolute error ≤ [`LOGISTIC_MAX_ERROR`] (2.8e-10:
/// half of tanh's, plus rounding). Total: in [0, 1] for every input, exactly 0 and 1 for x ≤ −22.06 and
/// x ≥ 22.06 (±∞ included), exactly 0.5 at 0; NaN gives NaN.
#[inline(always)]
pub fn logistic(x: f64) -> f64 {
    0.5 + 0.5 * tanh(0.5 * x)
}

/// [`logistic`] of every element, in place (vectorised).
#[inline(always)]
pub fn logistic_slice(y: &mut [f64]) {
    for v in y {
        *v = logistic(*v);
    }
}

/// max(0, x), written so that NaN (and -0.0) give +0.0.
#[inline]
pub fn relu(x: f64) -> f64 {
    if x > 0.0 {
        x
    } else {
        0.0
    }
}

/// Makes a motor output total: a NaN becomes 0 (no command).
///
/// A NaN can only arise from parameters near `f64::MAX`, whose products overflow to +∞ and
/// -∞ within one sum (or meet a zero weight); every finite parameter vector is a valid brain,
/// so such brains must still give outputs in [-1, 1] rather than poison the simulator.
#[inline]
pub fn nan_to_zero(x: f64) -> f64 {
    if x.is_nan() {
        0.0
    } else {
        x
    }
}

/// A float type the layer kernels compute in: f64, or f32 for an MLP with
/// `precision = "f32"` (see [`crate::brain::mlp`]). Each term of a sum is added by
/// [`Real::add_product`], whose result IEEE 754 specifies exactly in either type, so every sum
/// has the same bits on every CPU.
pub trait Real: Copy + std::fmt::Debug + 'static {
    /// Values per 256-bit AVX2 register (4 for f64, 8 for f32): the unit block sizes follow.
    const LANES: usize;

    /// One term of a sum: `self + w · x`. f64: a multiply, then an add (two roundings, never
    /// fused, so the bits do not depend on whether the CPU has FMA). f32: one fused
    /// multiply-add (IEEE 754 fusedMultiplyAdd, a single rounding), which is exactly specified
    /// too, so the FMA instruction and `f32::mul_add`'s software fallback give the same bits.
    fn add_product(self, w: Self, x: Self) -> Self;

    /// A hidden layer's activation function on every element. f32 values are widened to f64,
    /// go through the f64 function and are rounded back, so both types share one function.
    fn activate(activation: Activation, y: &mut [Self]);

    /// The output units' function ([`tanh_outputs`]: tanh, NaN to 0), widened and rounded
    /// back the same way.
    fn squash(y: &mut [Self]);
}

impl Real for f64 {
    const LANES: usize = 4;

    #[inline(always)]
    fn add_product(self, w: f64, x: f64) -> f64 {
        self + w * x
    }

    #[inline(always)]
    fn activate(activation: Activation, y: &mut [f64]) {
        activation.apply_slice(y);
    }

    #[inline(always)]
    fn squash(y: &mut [f64]) {
        tanh_outputs(y);
    }
}

impl Real for f32 {
    const LANES: usize = 8;

    #[inline(always)]
    fn add_product(self, w: f32, x: f32) -> f32 {
        // Fused on purpose: the f32 precision is defined with fused multiply-adds (one
        // rounding, exactly specified by IEEE 754, so deterministic on every CPU), which the
        // AVX2+FMA build runs as vfmadd on 8 lanes.
        w.mul_add(x, self)
    }

    #[inline(always)]
    fn activate(activation: Activation, y: &mut [f32]) {
        // The match outside the loops keeps each loop branch-free (vectorised); plain loops,
        // not closures, so that nothing leaves the caller's AVX2 compilation.
        match activation {
            Activation::Tanh => {
                for v in y {
                    *v = tanh(f64::from(*v)) as f32;
                }
            }
            Activation::Sigmoid => {
                for v in y {
                    *v = logistic(f64::from(*v)) as f32;
                }
            }
            Activation::Relu => {
                for v in y {
                    *v = relu(f64::from(*v)) as f32;
                }
            }
        }
    }

    #[inline(always)]
    fn squash(y: &mut [f32]) {
        for v in y {
            *v = nan_to_zero(tanh(f64::from(*v))) as f32;
        }
    }
}

/// The input-major copy of a units × inputs row-major weight matrix (the genome's layout):
/// element `[i * units + j]` is the weight from input i to unit j, so the weights leaving one
/// input are contiguous (the rows [`accumulate`] reads).
pub fn transpose(weights: &[f64], units: usize, inputs: usize) -> Vec<f64> {
    debug_assert_eq!(weights.len(), units * inputs);
    let mut t = vec![0.0; units * inputs];
    for (j, row) in weights.chunks_exact(inputs.max(1)).take(units).enumerate() {
        for (i, &w) in row.iter().enumerate() {
            t[i * units + j] = w;
        }
    }
    t
}

/// y_j += Σ_i w_ij x_i for every unit j, adding the inputs one at a time in index order:
/// for i = 0, 1, …: y_j ← y_j + w_ij · x_i (an axpy over row i of the input-major matrix
/// `transposed`, see [`transpose`]). Each y_j is thus the plain left-to-right sum
/// y_j + w_j0 x_0 + w_j1 x_1 + …, whatever the vector width the compiler chooses.
///
/// The number of units is `y.len()`; the number of inputs is `x.len()`, and `transposed`
/// must hold `x.len() * y.len()` weights.
///
/// For speed the units are taken in blocks of 8, then 4, 2 and 1, each block's sums kept in
/// registers over all the inputs (a fixed-size array the compiler maps to SIMD registers)
/// instead of being loaded and stored once per input. This changes nothing in the arithmetic:
/// every unit still gets exactly the sum above.
#[inline]
pub fn accumulate(transposed: &[f64], x: &[f64], y: &mut [f64]) {
    kernel(transposed, None, x, y);
}

/// y = b + W x: y_j = b_j + w_j0 x_0 + w_j1 x_1 + … summed left to right (see
/// [`accumulate`]), with `transposed` the input-major weights (see [`transpose`]) and
/// `biases.len() == y.len()`.
#[inline]
pub fn affine(transposed: &[f64], biases: &[f64], x: &[f64], y: &mut [f64]) {
    debug_assert_eq!(biases.len(), y.len());
    kernel(transposed, Some(biases), x, y);
}

/// y_j = start_j + Σ_i w_ij x_i, with start = `biases` or, without biases, y itself.
///
/// On x86-64 CPUs with AVX2 the same code is run compiled for AVX2 (four f64 per register
/// instead of two): each unit's sum is still the same sequence of separate multiplies and
/// adds (Rust never fuses them into FMA), so the bits are the same on every CPU; a test
/// checks both versions against each other.
#[inline]
fn kernel(transposed: &[f64], biases: Option<&[f64]>, x: &[f64], y: &mut [f64]) {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: `kernel_avx2` only requires the CPU to support AVX2, checked just above.
        unsafe { kernel_avx2(transposed, biases, x, y) };
        return;
    }
    kernel_portable(transposed, biases, x, y);
}

/// [`kernel_portable`] compiled for AVX2.
///
/// # Safety
/// The CPU must support AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn kernel_avx2(transposed: &[f64], biases: Option<&[f64]>, x: &[f64], y: &mut [f64]) {
    kernel_portable(transposed, biases, x, y);
}

/// [`kernel`] for any CPU, in either float type (f32 also takes blocks of 16 units: two
/// AVX2 registers, like 8 f64).
#[inline(always)]
pub(crate) fn kernel_portable<F: Real>(
    transposed: &[F],
    biases: Option<&[F]>,
    x: &[F],
    y: &mut [F],
) {
    debug_assert_eq!(transposed.len(), y.len() * x.len());
    let mut j = 0;
    if F::LANES == 8 {
        j = blocks::<F, 16>(transposed, biases, x, y, j);
    }
    j = blocks::<F, 8>(transposed, biases, x, y, j);
    j = blocks::<F, 4>(transposed, biases, x, y, j);
    j = blocks::<F, 2>(transposed, biases, x, y, j);
    blocks::<F, 1>(transposed, biases, x, y, j);
}

/// [`kernel`] for the units j.. in whole blocks of `N`; returns where it stopped.
#[inline(always)]
fn blocks<F: Real, const N: usize>(
    transposed: &[F],
    biases: Option<&[F]>,
    x: &[F],
    y: &mut [F],
    mut j: usize,
) -> usize {
    let units = y.len();
    while j + N <= units {
        let start: &[F] = biases.unwrap_or(&*y);
        let mut acc: [F; N] = start[j..j + N].try_into().expect("N units");
        // `units` ≥ N ≥ 1 here, and every row has exactly `units` weights, so the slice
        // below needs no bounds check inside the loop.
        for (row, &xi) in transposed.chunks_exact(units).zip(x) {
            let w: &[F; N] = row[j..j + N].try_into().expect("N weights");
            for k in 0..N {
                acc[k] = acc[k].add_product(w[k], xi);
            }
        }
        y[j..j + N].copy_from_slice(&acc);
        j += N;
    }
    j
}

/// Samples per tile of [`affine_batch`]: the tile's sums for one block of units stay in
/// registers while the inputs are walked, so each weight load serves this many samples.
pub const BATCH_TILE: usize = 4;

/// [`affine`] for `n` samples at once: `x` holds n input vectors one after another (n × p
/// values, p = `x.len() / n`), `y` receives n output vectors (n × `biases.len()` values), and
/// sample s gets exactly the bits [`affine`] gives it alone. `tile` is scratch space for at
/// least [`BATCH_TILE`] × p values (the caller keeps it, so a batch allocates nothing).
///
/// The samples are taken in tiles of [`BATCH_TILE`] (then 2, then 1 for the remainder). A
/// tile's inputs are first copied input-major into `tile` (the T values of input i side by
/// side), then the units are taken in blocks of 8 and 4 (then 2 and 1 in smaller tiles) as in
/// [`accumulate`]: for one block, the tile × block sums live in registers while the inputs
/// are walked in index order (two per loop step), so each row slice of weights is loaded once
/// and multiplied by every sample's input i. In a full tile the last 1–3 units (the motor
/// outputs) instead get one register per unit holding the tile's samples.
/// Every sum is still y_sj = b_j + w_j0 x_s0 + w_j1 x_s1 + … left to right with separate
/// multiplies and adds; tiling only changes which sums are in flight together, never the
/// order inside one.
///
/// # Panics
/// When the lengths disagree (`x.len()` not n × p with `transposed.len()` = p × units,
/// `y.len()` not n × units, `tile` shorter than [`BATCH_TILE`] × p); with no sample or no
/// unit there is nothing to do, and nothing is checked.
#[inline]
pub fn affine_batch(
    transposed: &[f64],
    biases: &[f64],
    x: &[f64],
    y: &mut [f64],
    n: usize,
    tile: &mut [f64],
) {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: `affine_batch_avx2` only requires the CPU to support AVX2, checked just above.
        unsafe { affine_batch_avx2(transposed, biases, x, y, n, tile) };
        return;
    }
    affine_batch_portable(transposed, biases, x, y, n, tile);
}

/// [`affine_batch_portable`] compiled for AVX2.
///
/// # Safety
/// The CPU must support AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn affine_batch_avx2(
    transposed: &[f64],
    biases: &[f64],
    x: &[f64],
    y: &mut [f64],
    n: usize,
    tile: &mut [f64],
) {
    affine_batch_portable(transposed, biases, x, y, n, tile);
}

/// [`affine_batch`] for any CPU (inlined into callers that are themselves compiled for AVX2,
/// such as the MLP's batched forward pass), in either float type; f32 takes blocks of 16
/// units before those of 8, and adds each term with a fused multiply-add.
#[inline(always)]
pub(crate) fn affine_batch_portable<F: Real>(
    transposed: &[F],
    biases: &[F],
    x: &[F],
    y: &mut [F],
    n: usize,
    tile: &mut [F],
) {
    let units = biases.len();
    if units == 0 || n == 0 {
        return;
    }
    let p = x.len() / n;
    assert_eq!(x.len(), n * p, "batch inputs");
    assert_eq!(y.len(), n * units, "batch outputs");
    assert_eq!(transposed.len(), p * units, "batch weights");
    assert!(tile.len() >= BATCH_TILE * p, "batch tile scratch");
    let mut s = 0;
    s = sample_tiles::<F, BATCH_TILE>(transposed, biases, x, y, (n, p), tile, s);
    s = sample_tiles::<F, 2>(transposed, biases, x, y, (n, p), tile, s);
    sample_tiles::<F, 1>(transposed, biases, x, y, (n, p), tile, s);
}

/// [`affine_batch`] for the samples s.. in whole tiles of `T`; returns where it stopped.
#[inline(always)]
fn sample_tiles<F: Real, const T: usize>(
    transposed: &[F],
    biases: &[F],
    x: &[F],
    y: &mut [F],
    (n, p): (usize, usize),
    tile: &mut [F],
    mut s: usize,
) -> usize {
    let units = biases.len();
    let xt = &mut tile[..T * p];
    while s + T <= n {
        // Input-major copy of the tile: the inner loop then reads one contiguous group of T
        // inputs per step, without a bounds check per sample.
        let xs = &x[s * p..(s + T) * p];
        for (i, group) in xt.chunks_exact_mut(T).enumerate() {
            for (t, v) in group.iter_mut().enumerate() {
                *v = xs[t * p + i];
            }
        }
        let ys = &mut y[s * units..(s + T) * units];
        let mut j = 0;
        if F::LANES == 8 {
            // f32: blocks of 16 units (4 × 16 sums = 8 accumulator registers). With fused
            // multiply-adds a term needs no register for its product, so the tile fits the 16
            // AVX2 registers with the two weight registers and a broadcast input.
            j = unit_blocks::<F, T, 16>(transposed, biases, xt, ys, j);
        }
        let j = unit_blocks::<F, T, 8>(transposed, biases, xt, ys, j);
        let j = unit_blocks::<F, T, 4>(transposed, biases, xt, ys, j);
        if T >= 4 {
            // Fewer than 4 units left (all of a 2- or 3-unit output layer): one register
            // per unit across the tile's samples beats half-empty unit blocks.
            match units - j {
                1 => lane_block::<F, T, 1>(transposed, biases, xt, ys, j),
                2 => lane_block::<F, T, 2>(transposed, biases, xt, ys, j),
                3 => lane_block::<F, T, 3>(transposed, biases, xt, ys, j),
                _ => {}
            }
        } else {
            let j = unit_blocks::<F, T, 2>(transposed, biases, xt, ys, j);
            unit_blocks::<F, T, 1>(transposed, biases, xt, ys, j);
        }
        s += T;
    }
    s
}

/// One tile of `T` samples (inputs `xt`, input-major) over the units j.. in whole blocks of
/// `N`: the T × N sums stay in registers over all the inputs; returns where it stopped.
#[inline(always)]
fn unit_blocks<F: Real, const T: usize, const N: usize>(
    transposed: &[F],
    biases: &[F],
    xt: &[F],
    ys: &mut [F],
    mut j: usize,
) -> usize {
    let units = biases.len();
    while j + N <= units {
        let start: [F; N] = biases[j..j + N].try_into().expect("N biases");
        let mut acc = [start; T];
        // `units` ≥ N ≥ 1 and every row has exactly `units` weights, so the slices need no
        // bounds check inside the loops. Two inputs per iteration (in index order) halve the
        // loop overhead.
        let pairs = transposed
            .chunks_exact(2 * units)
            .zip(xt.chunks_exact(2 * T));
        for (rows, groups) in pairs {
            tile_step(&mut acc, &rows[j..j + N], &groups[..T]);
            tile_step(&mut acc, &rows[units + j..units + j + N], &groups[T..]);
        }
        let done = transposed.len() / (2 * units) * 2;
        if let (Some(row), Some(group)) = (
            transposed.chunks_exact(units).nth(done),
            xt.chunks_exact(T).nth(done),
        ) {
            tile_step(&mut acc, &row[j..j + N], group);
        }
        for (t, sums) in acc.iter().enumerate() {
            ys[t * units + j..t * units + j + N].copy_from_slice(sums);
        }
        j += N;
    }
    j
}

/// One input of a tile: every sum gains its term w[k] · x_t ([`Real::add_product`]: a
/// multiply and an add in f64, a fused multiply-add in f32). (A function, not
/// a closure: a closure is not `inline(always)`, and left out of line it would lose the AVX2
/// compilation of its caller.)
#[inline(always)]
fn tile_step<F: Real, const T: usize, const N: usize>(acc: &mut [[F; N]; T], w: &[F], x: &[F]) {
    let w: &[F; N] = w.try_into().expect("N weights");
    let x: &[F; T] = x.try_into().expect("T inputs");
    for t in 0..T {
        for k in 0..N {
            acc[t][k] = acc[t][k].add_product(w[k], x[t]);
        }
    }
}

/// One tile of `T` samples (inputs `xt`, input-major) over the last `N` units j..j + N,
/// with one register per unit holding the T samples' sums (the tile's inputs for one input
/// index are contiguous in `xt`): for a handful of units this wastes no lanes.
#[inline(always)]
fn lane_block<F: Real, const T: usize, const N: usize>(
    transposed: &[F],
    biases: &[F],
    xt: &[F],
    ys: &mut [F],
    j: usize,
) {
    let units = biases.len();
    let mut acc = [[biases[j]; T]; N];
    for (k, sums) in acc.iter_mut().enumerate() {
        *sums = [biases[j + k]; T];
    }
    for (row, group) in transposed.chunks_exact(units).zip(xt.chunks_exact(T)) {
        let w: &[F; N] = row[j..j + N].try_into().expect("N weights");
        let group: &[F; T] = group.try_into().expect("T inputs");
        for k in 0..N {
            for t in 0..T {
                acc[k][t] = acc[k][t].add_product(w[k], group[t]);
            }
        }
    }
    for (k, sums) in acc.iter().enumerate() {
        for (t, &sum) in sums.iter().enumerate() {
            ys[t * units + j + k] = sum;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// σ(x) computed the reference way, with libm.
    fn reference_logistic(x: f64) -> f64 {
        1.0 / (1.0 + libm::exp(-x))
    }

    /// Every 1e-4 on [-20, 20], computed from an integer index so that no step drifts.
    fn grid() -> impl Iterator<Item = f64> {
        (-200_000i32..=200_000).map(|i| f64::from(i) * 1e-4)
    }

    #[test]
    fn tanh_error_symmetry_range_and_monotonicity_on_a_dense_grid() {
        let mut max_error: f64 = 0.0;
        let mut previous = -1.0;
        for x in grid() {
            let y = tanh(x);
            max_error = max_error.max((y - libm::tanh(x)).abs());
            assert!(y.abs() <= 1.0, "tanh({x}) = {y}");
            assert_eq!(tanh(-x).to_bits(), (-y).to_bits(), "odd at {x}");
            assert!(y >= previous, "not monotone at {x}: {y} < {previous}");
            previous = y;
        }
        // A finer grid where the approximation reaches 1, which is where its error is largest.
        for x in (0..=300_000).map(|i| 10.9 + f64::from(i) * 1e-6) {
            max_error = max_error.max((tanh(x) - libm::tanh(x)).abs());
        }
        assert!(max_error <= TANH_MAX_ERROR, "max error {max_error:e}");
        // The documented bound is tight: the measured maximum is within 10% of it.
        assert!(max_error > 0.9 * TANH_MAX_ERROR, "max error {max_error:e}");
    }

    #[test]
    fn tanh_edge_cases() {
        assert_eq!(tanh(0.0).to_bits(), 0.0f64.to_bits());
        assert_eq!(tanh(-0.0).to_bits(), (-0.0f64).to_bits());
        assert!(tanh(f64::NAN).is_nan());
        for (x, y) in [
            (f64::INFINITY, 1.0),
            (f64::MAX, 1.0),
            (1e300, 1.0),
            (40.0, 1.0),
            (11.03, 1.0),
            (f64::NEG_INFINITY, -1.0),
            (-f64::MAX, -1.0),
            (-40.0, -1.0),
        ] {
            assert_eq!(tanh(x), y, "tanh({x})");
        }
        // Tiny and subnormal inputs: tanh(x) = x to within p0 = 1 − 2e-9, same sign.
        for x in [f64::MIN_POSITIVE, 1e-310, 5e-324, 1e-20] {
            for x in [x, -x] {
                let y = tanh(x);
                assert_eq!(
                    y.is_sign_negative(),
                    x.is_sign_negative(),
                    "tanh({x}) = {y}"
                );
                assert!((y - x).abs() <= 3e-9 * x.abs(), "tanh({x}) = {y}");
            }
        }
    }

    #[test]
    fn logistic_error_range_and_edge_cases() {
        let mut max_error: f64 = 0.0;
        let mut previous = 0.0;
        for x in grid().map(|x| 2.0 * x) {
            let y = logistic(x);
            max_error = max_error.max((y - reference_logistic(x)).abs());
            assert!((0.0..=1.0).contains(&y), "σ({x}) = {y}");
            assert!(y >= previous, "not monotone at {x}");
            previous = y;
        }
        assert!(max_error <= LOGISTIC_MAX_ERROR, "max error {max_error:e}");
        assert_eq!(logistic(0.0), 0.5);
        assert_eq!(logistic(f64::INFINITY), 1.0);
        assert_eq!(logistic(f64::NEG_INFINITY), 0.0);
        assert_eq!(logistic(f64::MAX), 1.0);
        assert_eq!(logistic(-f64::MAX), 0.0);
        assert_eq!(logistic(-1e6), 0.0);
        assert!(logistic(f64::NAN).is_nan());
    }

    #[test]
    fn slice_kernels_match_the_scalar_ones_bit_for_bit() {
        // The vectorised loops must not change a single bit (any length, any alignment).
        let xs: Vec<f64> = (0..37)
            .map(|i| f64::from(i - 18) * 0.731)
            .chain([f64::NAN, f64::INFINITY, -0.0, 1e-310])
            .collect();
        for start in 0..3 {
            let mut t = xs[start..].to_vec();
            tanh_slice(&mut t);
            let mut s = xs[start..].to_vec();
            logistic_slice(&mut s);
            for (k, &x) in xs[start..].iter().enumerate() {
                assert_eq!(t[k].to_bits(), tanh(x).to_bits(), "tanh({x})");
                assert_eq!(s[k].to_bits(), logistic(x).to_bits(), "σ({x})");
            }
        }
    }

    #[test]
    fn avx2_and_portable_kernels_agree_bit_for_bit() {
        // Awkward sizes exercise every block width; values span many magnitudes.
        use crate::seed::{
            below, stream, uniform, Generation, IndividualId, Purpose, Seed, TrialIndex,
        };
        let mut rng = stream(
            Seed(41),
            Purpose::Baseline,
            Generation(0),
            IndividualId(0),
            TrialIndex(0),
        );
        let mut next = || {
            let scale = libm::exp2(below(&mut rng, 41) as f64 - 20.0);
            uniform(&mut rng, -0.5, 0.5) * scale
        };
        for (units, inputs) in [
            (1, 1),
            (3, 5),
            (8, 24),
            (15, 7),
            (16, 24),
            (100, 98),
            (37, 0),
        ] {
            let w: Vec<f64> = (0..units * inputs).map(|_| next()).collect();
            let b: Vec<f64> = (0..units).map(|_| next()).collect();
            let x: Vec<f64> = (0..inputs).map(|_| next()).collect();
            let mut portable = vec![0.0; units];
            kernel_portable(&w, Some(&b), &x, &mut portable);
            let mut dispatched = vec![0.0; units];
            kernel(&w, Some(&b), &x, &mut dispatched);
            let bits = |v: &[f64]| v.iter().map(|f| f.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&portable), bits(&dispatched), "{units} x {inputs}");
            #[cfg(target_arch = "x86_64")]
            if std::arch::is_x86_feature_detected!("avx2") {
                let mut avx2 = vec![0.0; units];
                // SAFETY: AVX2 is supported (checked just above).
                unsafe { kernel_avx2(&w, Some(&b), &x, &mut avx2) };
                assert_eq!(bits(&portable), bits(&avx2), "{units} x {inputs}");
            }
        }
    }

    #[test]
    fn batch_kernels_agree_with_single_sample_affine_bit_for_bit() {
        // Every tile remainder (n mod 4) and block remainder (units mod 8), AVX2 and portable.
        use crate::seed::{
            below, stream, uniform, Generation, IndividualId, Purpose, Seed, TrialIndex,
        };
        let mut rng = stream(
            Seed(46),
            Purpose::Baseline,
            Generation(0),
            IndividualId(0),
            TrialIndex(0),
        );
        let mut next = || {
            let scale = libm::exp2(below(&mut rng, 41) as f64 - 20.0);
            uniform(&mut rng, -0.5, 0.5) * scale
        };
        let bits = |v: &[f64]| v.iter().map(|f| f.to_bits()).collect::<Vec<_>>();
        for (units, inputs) in [
            (1, 1),
            (3, 5),
            (10, 4),
            (15, 7),
            (16, 24),
            (100, 98),
            (37, 0),
        ] {
            let w: Vec<f64> = (0..units * inputs).map(|_| next()).collect();
            let b: Vec<f64> = (0..units).map(|_| next()).collect();
            let mut tile = vec![0.0; BATCH_TILE * inputs];
            for n in [0, 1, 2, 3, 4, 5, 6, 7, 9, 16, 33] {
                let x: Vec<f64> = (0..n * inputs).map(|_| next()).collect();
                let mut expected = vec![0.0; n * units];
                for (s, ys) in expected.chunks_exact_mut(units).enumerate() {
                    affine(&w, &b, &x[s * inputs..(s + 1) * inputs], ys);
                }
                let mut portable = vec![0.0; n * units];
                affine_batch_portable(&w, &b, &x, &mut portable, n, &mut tile);
                assert_eq!(
                    bits(&portable),
                    bits(&expected),
                    "{units} x {inputs}, n={n}"
                );
                let mut dispatched = vec![0.0; n * units];
                affine_batch(&w, &b, &x, &mut dispatched, n, &mut tile);
                assert_eq!(
                    bits(&dispatched),
                    bits(&expected),
                    "{units} x {inputs}, n={n}"
                );
                #[cfg(target_arch = "x86_64")]
                if std::arch::is_x86_feature_detected!("avx2") {
                    let mut avx2 = vec![0.0; n * units];
                    // SAFETY: AVX2 is supported (checked just above).
                    unsafe { affine_batch_avx2(&w, &b, &x, &mut avx2, n, &mut tile) };
                    assert_eq!(bits(&avx2), bits(&expected), "{units} x {inputs}, n={n}");
                }
            }
        }
    }

    #[test]
    fn affine_sums_left_to_right_from_the_bias() {
        // 11 inputs, 3 units, W[j][i] = (i + 1) / (j + 1); the sum order is b + w0x0 + w1x1 + ….
        let (units, inputs) = (3, 11);
        let w: Vec<f64> = (0..units * inputs)
            .map(|k| (k % inputs + 1) as f64 / (k / inputs + 1) as f64)
            .collect();
        let x: Vec<f64> = (1..=inputs).map(|i| 1.0 / i as f64 + 0.1).collect();
        let b = [0.3, -0.7, 1e-3];
        let t = transpose(&w, units, inputs);
        let mut y = [0.0; 3];
        affine(&t, &b, &x, &mut y);
        for j in 0..units {
            let mut expected = b[j];
            for i in 0..inputs {
                expected += w[j * inputs + i] * x[i];
                assert_eq!(t[i * units + j].to_bits(), w[j * inputs + i].to_bits());
            }
            assert_eq!(y[j].to_bits(), expected.to_bits(), "unit {j}");
        }
        // No inputs: the biases. No units: nothing.
        let mut y = [0.0; 2];
        affine(&[], &[0.5, -0.25], &[], &mut y);
        assert_eq!(y, [0.5, -0.25]);
        affine(&[], &[], &[1.0, 2.0], &mut []);
    }

    #[test]
    fn kernels_are_total() {
        assert_eq!(relu(f64::NAN), 0.0);
        assert_eq!(relu(-0.0).to_bits(), 0.0f64.to_bits());
        assert_eq!(nan_to_zero(f64::NAN), 0.0);
        assert_eq!(nan_to_zero(-0.5), -0.5);
    }
}
