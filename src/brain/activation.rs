//! The numeric kernels every brain shares: activation functions, the logistic function, the
//! output squashing that keeps motor outputs in [-1, 1], and the dot product of the hot loop.
//!
//! All transcendental functions come from `libm` so that a brain gives the same bits on every
//! platform; the dot product's summation order is fixed by the code (see [`dot`]).

use serde::{Deserialize, Serialize};

/// The activation function of hidden units (`brain.activation`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Activation {
    /// Hyperbolic tangent, output in (-1, 1) (the default).
    #[default]
    Tanh,
    /// Logistic function 1 / (1 + e^(-x)), output in (0, 1).
    Sigmoid,
    /// Rectified linear unit max(0, x), output in [0, ∞). A NaN input gives 0.
    Relu,
}

impl Activation {
    /// The function's value at `x`.
    #[inline]
    pub fn apply(self, x: f64) -> f64 {
        match self {
            Activation::Tanh => libm::tanh(x),
            Activation::Sigmoid => logistic(x),
            Activation::Relu => relu(x),
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

/// The logistic function σ(x) = 1 / (1 + e^(-x)), in [0, 1]. Total on every finite or
/// infinite input: e^(-x) overflowing to +∞ gives exactly 0.
#[inline]
pub fn logistic(x: f64) -> f64 {
    1.0 / (1.0 + libm::exp(-x))
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

/// Number of independent partial sums in [`dot`].
const LANES: usize = 8;

/// The dot product Σ w_i x_i over the common length of the two slices.
///
/// The summation order is fixed, so the result has the same bits everywhere: eight partial sums
/// s_k accumulate the products at indices ≡ k (mod 8) over the whole blocks of eight, they are
/// combined as ((s0 + s1) + (s2 + s3)) + ((s4 + s5) + (s6 + s7)), and the remaining (fewer than
/// eight) products are added one by one in index order. The independent partial sums let the
/// compiler use SIMD registers without reassociating anything (no relaxed floating-point flags). For fewer than
/// eight elements this is the plain left-to-right sum 0 + w0 x0 + w1 x1 + ….
#[inline]
pub fn dot(w: &[f64], x: &[f64]) -> f64 {
    let n = w.len().min(x.len());
    let (w, x) = (&w[..n], &x[..n]);
    let wc = w.chunks_exact(LANES);
    let xc = x.chunks_exact(LANES);
    let (wr, xr) = (wc.remainder(), xc.remainder());
    let mut acc = [0.0f64; LANES];
    for (a, b) in wc.zip(xc) {
        // Fixed-size arrays let the compiler drop the bounds checks and use SIMD registers.
        let a: &[f64; LANES] = a.try_into().expect("chunks_exact yields LANES elements");
        let b: &[f64; LANES] = b.try_into().expect("chunks_exact yields LANES elements");
        for k in 0..LANES {
            acc[k] += a[k] * b[k];
        }
    }
    let mut sum = ((acc[0] + acc[1]) + (acc[2] + acc[3])) + ((acc[4] + acc[5]) + (acc[6] + acc[7]));
    for (a, b) in wr.iter().zip(xr) {
        sum += a * b;
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dot_matches_documented_order() {
        let w: Vec<f64> = (1..=11).map(f64::from).collect();
        let x: Vec<f64> = (1..=11).map(|i| 1.0 / f64::from(i)).collect();
        let mut s = [0.0; 8];
        for k in 0..8 {
            s[k] += w[k] * x[k];
        }
        let mut expected = ((s[0] + s[1]) + (s[2] + s[3])) + ((s[4] + s[5]) + (s[6] + s[7]));
        for i in 8..11 {
            expected += w[i] * x[i];
        }
        assert_eq!(dot(&w, &x).to_bits(), expected.to_bits());
        assert_eq!(dot(&[2.0, 3.0], &[5.0, 7.0]), 31.0);
        assert_eq!(dot(&[], &[]), 0.0);
    }

    #[test]
    fn kernels_are_total() {
        assert_eq!(logistic(f64::INFINITY), 1.0);
        assert_eq!(logistic(f64::NEG_INFINITY), 0.0);
        assert_eq!(logistic(-1e6), 0.0);
        assert_eq!(relu(f64::NAN), 0.0);
        assert_eq!(relu(-0.0).to_bits(), 0.0f64.to_bits());
        assert_eq!(nan_to_zero(f64::NAN), 0.0);
        assert_eq!(nan_to_zero(-0.5), -0.5);
    }
}
