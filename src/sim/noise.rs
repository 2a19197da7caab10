//! Sensor noise (§7.5, eq. 27): ŝ = N + (1 + M)·s, applied to the observation a controller
//! receives, per sensor group, with draws from the trial's own generator.
//!
//! # Draw order (fixed, so that noisy runs reproduce exactly)
//!
//! Noise is applied right after a creature's observation is written, in the observation's
//! order: the groups in [`SensorGroup::ORDER`] that the controller receives *and* that have a
//! `[creature.noise.<group>]` table, and within a group each input in turn. Each input takes
//! two standard normal draws from the world's generator: first the one behind N, then the one
//! behind M. Groups without a table take no draws, so a noise-free run never touches the
//! generator here.

use crate::seed::{gaussian, Rng};
use crate::sim::controller::{ObservationLayout, SensorGroup};
use crate::sim::spec::{NoiseChannel, NoiseSpec};
use std::ops::Range;

/// One noisy group: where it sits in the observation, its noise, and the range its values
/// are clipped to.
#[derive(Debug, Clone, PartialEq)]
struct NoisyGroup {
    range: Range<usize>,
    channel: NoiseChannel,
    lo: f64,
    hi: f64,
}

/// The noisy groups of one layout, resolved once per world.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Noise {
    groups: Vec<NoisyGroup>,
}

/// The range a sensor group's values live in, which noisy values are clipped back to.
pub fn sensor_range(group: SensorGroup) -> (f64, f64) {
    match group {
        SensorGroup::Metabolism => (0.0, f64::INFINITY),
        SensorGroup::Landmarks => (-1.0, 1.0),
        _ => (0.0, 1.0),
    }
}

impl Noise {
    /// The noise `spec` puts on the groups of `layout`.
    pub fn new(spec: &NoiseSpec, layout: &ObservationLayout) -> Noise {
        let groups = layout
            .groups()
            .iter()
            .filter_map(|(group, range)| {
                spec.channel(*group).map(|channel| {
                    let (lo, hi) = sensor_range(*group);
                    NoisyGroup {
                        range: range.clone(),
                        channel,
                        lo,
                        hi,
                    }
                })
            })
            .collect();
        Noise { groups }
    }

    /// True when no group is noisy.
    pub fn is_empty(&self) -> bool {
        self.groups.is_empty()
    }

    /// Applies eq. 27 to `observation` in place (see the module docs for the draw order).
    pub fn apply(&self, observation: &mut [f64], rng: &mut Rng) {
        for g in &self.groups {
            for x in &mut observation[g.range.clone()] {
                *x = noisy(*x, &g.channel, g.lo, g.hi, rng);
            }
        }
    }
}

/// eq. 27 for one value `s`: N = |normal(0, n_sigma)| clipped to [0, n], M = normal(0,
/// m_sigma) clipped to [−m, m], ŝ = N + (1 + M)·s clipped to [lo, hi]. Draws N first, then M.
#[inline]
pub fn noisy(s: f64, c: &NoiseChannel, lo: f64, hi: f64, rng: &mut Rng) -> f64 {
    let n = (gaussian(rng) * c.n_sigma).abs().min(c.n);
    let m = (gaussian(rng) * c.m_sigma).clamp(-c.m, c.m);
    (n + (1.0 + m) * s).clamp(lo, hi)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::seed::{stream, Generation, IndividualId, Purpose, Seed, TrialIndex};

    fn rng() -> Rng {
        stream(
            Seed(7),
            Purpose::TrialWorld,
            Generation(0),
            IndividualId(0),
            TrialIndex(0),
        )
    }

    fn mean_var(xs: &[f64]) -> (f64, f64) {
        let n = xs.len() as f64;
        let mean = xs.iter().sum::<f64>() / n;
        let var = xs.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / n;
        (mean, var)
    }

    #[test]
    fn additive_noise_is_half_normal_and_clipped() {
        // s = 0, M irrelevant: ŝ = N. With n large, N is |normal(0, σ)|: mean σ√(2/π),
        // variance σ²(1 − 2/π).
        let sigma = 0.1;
        let c = NoiseChannel {
            n: 10.0,
            n_sigma: sigma,
            m: 0.0,
            m_sigma: 0.0,
        };
        let mut r = rng();
        let xs: Vec<f64> = (0..200_000)
            .map(|_| noisy(0.0, &c, 0.0, f64::INFINITY, &mut r))
            .collect();
        let (mean, var) = mean_var(&xs);
        let pi = std::f64::consts::PI;
        let want_mean = sigma * (2.0 / pi).sqrt();
        let want_var = sigma * sigma * (1.0 - 2.0 / pi);
        assert!((mean - want_mean).abs() < 0.01 * want_mean, "mean {mean}");
        assert!((var - want_var).abs() < 0.02 * want_var, "var {var}");
        assert!(xs.iter().all(|&x| x >= 0.0));

        // Clipped to [0, n]: with n = σ/2 a large share of draws sits exactly at n.
        let c = NoiseChannel { n: 0.05, ..c };
        let xs: Vec<f64> = (0..10_000)
            .map(|_| noisy(0.0, &c, 0.0, f64::INFINITY, &mut r))
            .collect();
        assert!(xs.iter().all(|&x| (0.0..=0.05).contains(&x)));
        // P(|Z| > 0.5) ≈ 0.617.
        let at_cap = xs.iter().filter(|&&x| x == 0.05).count() as f64 / 1e4;
        assert!((at_cap - 0.617).abs() < 0.02, "share at the cap {at_cap}");
    }

    #[test]
    fn multiplicative_noise_is_normal_and_clipped() {
        // s = 1, N = 0: ŝ = 1 + M, M normal(0, σ).
        let sigma = 0.2;
        let c = NoiseChannel {
            n: 0.0,
            n_sigma: 0.5,
            m: 1.0,
            m_sigma: sigma,
        };
        let mut r = rng();
        let xs: Vec<f64> = (0..200_000)
            .map(|_| noisy(1.0, &c, f64::NEG_INFINITY, f64::INFINITY, &mut r) - 1.0)
            .collect();
        let (mean, var) = mean_var(&xs);
        assert!(mean.abs() < 0.003, "mean {mean}");
        assert!(
            (var - sigma * sigma).abs() < 0.02 * sigma * sigma,
            "var {var}"
        );

        let c = NoiseChannel { m: 0.1, ..c };
        let xs: Vec<f64> = (0..10_000)
            .map(|_| noisy(1.0, &c, f64::NEG_INFINITY, f64::INFINITY, &mut r) - 1.0)
            .collect();
        assert!(xs
            .iter()
            .all(|&m| (-0.1 - 1e-12..=0.1 + 1e-12).contains(&m)));
        assert!(xs.iter().any(|&m| m > 0.0999) && xs.iter().any(|&m| m < -0.0999));
    }

    #[test]
    fn result_is_clipped_to_the_sensor_range() {
        let c = NoiseChannel {
            n: 0.5,
            n_sigma: 1.0,
            m: 0.5,
            m_sigma: 1.0,
        };
        let mut r = rng();
        for s in [0.0, 0.5, 1.0] {
            for _ in 0..1000 {
                let x = noisy(s, &c, 0.0, 1.0, &mut r);
                assert!((0.0..=1.0).contains(&x));
                let y = noisy(s - 1.0, &c, -1.0, 1.0, &mut r);
                assert!((-1.0..=1.0).contains(&y));
            }
        }
    }

    #[test]
    fn zero_noise_is_the_identity() {
        let c = NoiseChannel::default();
        let mut r = rng();
        for s in [0.0, 0.123_456_789, 1.0, 0.999_999_999_9] {
            assert_eq!(noisy(s, &c, 0.0, 1.0, &mut r).to_bits(), s.to_bits());
        }
    }
}
