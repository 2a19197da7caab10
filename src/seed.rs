//! Seed streams: one master seed becomes independent, reproducible random streams, and the
//! few samplers (uniform, bounded integer, Gaussian) the project draws from them.
//!
//! Every random draw in berry-evolve comes from a generator made by [`stream`] from
//! `(seed, purpose, generation, individual, trial)` and passed down as an explicit argument.
//! Nothing keeps a global or thread-local generator, so a value never depends on which
//! thread computed it or on what was computed before.
//!
//! The samplers are written here rather than taken from `rand::distributions`, whose values
//! have changed between `rand` releases; golden tests pin their first outputs so that a
//! dependency upgrade that changes any value fails loudly.

use rand_chacha::rand_core::{RngCore, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

/// The random generator used everywhere: ChaCha8 is portable (same bits on every platform)
/// and fast enough to draw trial worlds and mutations without showing in a profile.
pub type Rng = ChaCha8Rng;

/// The experiment's master seed. Kept below 2^63 because TOML integers are signed 64-bit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, Default)]
#[serde(transparent)]
pub struct Seed(pub u64);

/// A generation number, counted from 0 (the random initial population).
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize, Default,
)]
#[serde(transparent)]
pub struct Generation(pub u64);

/// The index of an individual within its generation's population.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize, Default,
)]
#[serde(transparent)]
pub struct IndividualId(pub u64);

/// The index of a trial (one world, one life) within an evaluation.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize, Default,
)]
#[serde(transparent)]
pub struct TrialIndex(pub u64);

/// What a stream is used for. The discriminants are part of the reproducibility contract:
/// changing one changes every run, so new purposes get new numbers. 4 is unassigned: it was
/// `TrialDynamics`, which nothing ever drew from (what is random while a trial runs, sensor
/// noise, wanderers, predators, draws on from the world's own [`Purpose::TrialWorld`]
/// stream), so removing it changed no stream; each discriminant is written out, so the others
/// kept their numbers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[repr(u64)]
pub enum Purpose {
    /// Drawing the initial population (generation 0).
    Initialisation = 1,
    /// Selection, crossover and mutation that make generation g + 1 from generation g.
    Variation = 2,
    /// Building a trial world (random placement of objects and creatures) and, from the
    /// world's own generator, everything random while its trial runs (sensor noise, wanderers,
    /// predators).
    TrialWorld = 3,
    /// Random genomes drawn as a baseline for comparisons (never used by evolution itself).
    Baseline = 5,
    /// The `simulate` demo command's worlds.
    Demo = 6,
    /// A distribution-based search (PGPE): the Gaussian noise that samples generation g
    /// around the centre (the GA uses `Initialisation` and `Variation` instead).
    Search = 7,
    /// The fixed validation worlds the champion is chosen on (`[validation]`): generation 0,
    /// individual 0, trial t for world t, the same worlds every time. Apart from the training
    /// worlds and from `compare`'s held-out worlds, which are both [`Purpose::TrialWorld`]
    /// streams.
    ValidationWorld = 8,
    /// Novelty search's probabilistic archive addition: one draw per individual of
    /// generation g, in index order (`[evolution.novelty] archive_probability`).
    Novelty = 9,
    /// A plastic brain's random initial weights (`brain.initial_weights = "random"`): one
    /// stream per life, keyed like the life's trial world but with the individual's own
    /// index (see [`crate::brain::plasticity::LifeKey`]).
    PlasticWeights = 10,
    /// A life's switch draws (`[evaluation.switch]`): whether its payoffs start exchanged and
    /// before which episodes they are exchanged again, from the coordinates of the life's
    /// first world's stream (its purpose absorbed as an extra coordinate, see
    /// [`sub_stream`]), so every life draws its own, the same every time. 12, leaving 10 and
    /// 11 to purposes being added on other branches.
    Switch = 12,
}

/// SplitMix64's output function: a bijective 64-bit mixer with full avalanche.
const fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

const GOLDEN_GAMMA: u64 = 0x9E37_79B9_7F4A_7C15;

/// The one function that derives every random stream of a run.
///
/// The five coordinates are absorbed one after another through SplitMix64's mixer (each step
/// `h = mix64(h ^ x + γ)`), and the resulting 64-bit state is stretched with SplitMix64 into the
/// 256-bit ChaCha8 key. Coordinates that do not apply to a purpose are passed as 0.
pub fn stream(
    seed: Seed,
    purpose: Purpose,
    generation: Generation,
    individual: IndividualId,
    trial: TrialIndex,
) -> Rng {
    sub_stream(seed, purpose, generation, individual, trial, &[])
}

/// [`stream`] with more coordinates absorbed after the five (the same way): a family of
/// streams below one stream, e.g. the worlds of episodes 2, 3, ... of a life whose first
/// world is `stream(...)`. With no extra coordinate it is [`stream`], bit for bit.
pub fn sub_stream(
    seed: Seed,
    purpose: Purpose,
    generation: Generation,
    individual: IndividualId,
    trial: TrialIndex,
    extra: &[u64],
) -> Rng {
    let mut h = mix64(seed.0.wrapping_add(GOLDEN_GAMMA));
    for &x in [purpose as u64, generation.0, individual.0, trial.0]
        .iter()
        .chain(extra)
    {
        h = mix64((h ^ x).wrapping_add(GOLDEN_GAMMA));
    }
    let mut key = [0u8; 32];
    for chunk in key.chunks_exact_mut(8) {
        h = h.wrapping_add(GOLDEN_GAMMA);
        chunk.copy_from_slice(&mix64(h).to_le_bytes());
    }
    ChaCha8Rng::from_seed(key)
}

/// A uniform draw from [0, 1) with 53 random bits (every representable multiple of 2^-53).
#[inline]
pub fn unit(rng: &mut impl RngCore) -> f64 {
    (rng.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

/// A uniform draw from [lo, hi) (or exactly `lo` when `lo == hi`).
#[inline]
pub fn uniform(rng: &mut impl RngCore, lo: f64, hi: f64) -> f64 {
    lo + (hi - lo) * unit(rng)
}

/// A uniform integer in `0..n` without modulo bias (Lemire's multiply-and-reject).
/// `n == 0` returns 0 so the function is total.
pub fn below(rng: &mut impl RngCore, n: u64) -> u64 {
    if n == 0 {
        return 0;
    }
    let threshold = n.wrapping_neg() % n;
    loop {
        let m = (rng.next_u64() as u128) * (n as u128);
        if (m as u64) >= threshold {
            return (m >> 64) as u64;
        }
    }
}

/// `true` with probability `p` (p <= 0 never, p >= 1 always).
#[inline]
pub fn chance(rng: &mut impl RngCore, p: f64) -> bool {
    unit(rng) < p
}

/// A standard normal draw (mean 0, standard deviation 1) by the Box–Muller transform, using
/// two uniform draws and `libm` so that the bits are the same on every platform.
pub fn gaussian(rng: &mut impl RngCore) -> f64 {
    let a = unit(rng);
    let b = unit(rng);
    gaussian_from(a, b)
}

/// The normal draw [`gaussian`] makes from its two `unit()` draws `a` then `b`: drawing is
/// split from transforming so that hot loops can draw the words in stream order and do the
/// costly `log`, `sqrt` and `cos` in parallel afterwards, with the same bits.
#[inline]
pub fn gaussian_from(a: f64, b: f64) -> f64 {
    // 1 - a is in (0, 1], so the logarithm is finite.
    let u1 = 1.0 - a;
    let u2 = b;
    libm::sqrt(-2.0 * libm::log(u1)) * libm::cos(std::f64::consts::TAU * u2)
}

/// A standard normal draw from one 64-bit word, by the inverse of the normal distribution
/// function: `[evolution] draw_order = 2`'s normal (see [`Normals`]). The word's top 53 bits
/// make p = (k + ½) / 2^53, strictly inside (0, 1), and the draw is [`inverse_normal_cdf`]
/// of p: one word per draw, always, so runs of draws can still be split over threads by
/// word position, and about a fifth of Box–Muller's cost (a `log` and a `sqrt` for the 15%
/// of draws in the tails, two short polynomials otherwise).
#[inline]
pub fn gaussian_icdf(rng: &mut impl RngCore) -> f64 {
    let p = ((rng.next_u64() >> 11) as f64 + 0.5) * (1.0 / (1u64 << 53) as f64);
    inverse_normal_cdf(p)
}

/// The standard normal quantile of `p` in (0, 1): Wichura's algorithm AS241 (PPND16, 1988;
/// relative error about 1e-16), the same rational approximations and coefficients as
/// Python's `statistics.NormalDist().inv_cdf`, evaluated in the same order with `libm`.
// The published coefficients digit for digit (as Python's `statistics` writes them), so that
// anyone can check them against AS241; some have more digits than an f64 holds.
#[allow(clippy::excessive_precision)]
pub fn inverse_normal_cdf(p: f64) -> f64 {
    let q = p - 0.5;
    if q.abs() <= 0.425 {
        let r = 0.180625 - q * q;
        let num = (((((((2.50908_09287_30122_6727e+3 * r + 3.34305_75583_58812_8105e+4) * r
            + 6.72657_70927_00870_0853e+4)
            * r
            + 4.59219_53931_54987_1457e+4)
            * r
            + 1.37316_93765_50946_1125e+4)
            * r
            + 1.97159_09503_06551_4427e+3)
            * r
            + 1.33141_66789_17843_7745e+2)
            * r
            + 3.38713_28727_96366_6080e+0)
            * q;
        let den = ((((((5.22649_52788_52854_5610e+3 * r + 2.87290_85735_72194_2674e+4) * r
            + 3.93078_95800_09271_0610e+4)
            * r
            + 2.12137_94301_58659_5867e+4)
            * r
            + 5.39419_60214_24751_1077e+3)
            * r
            + 6.87187_00749_20579_0830e+2)
            * r
            + 4.23133_30701_60091_1252e+1)
            * r
            + 1.0;
        return num / den;
    }
    let tail = if q <= 0.0 { p } else { 1.0 - p };
    let r = libm::sqrt(-libm::log(tail));
    let x = if r <= 5.0 {
        let r = r - 1.6;
        let num = ((((((7.74545_01427_83414_07640e-4 * r + 2.27238_44989_26918_45833e-2) * r
            + 2.41780_72517_74506_11770e-1)
            * r
            + 1.27045_82524_52368_38258e+0)
            * r
            + 3.64784_83247_63204_60504e+0)
            * r
            + 5.76949_72214_60691_40550e+0)
            * r
            + 4.63033_78461_56545_29590e+0)
            * r
            + 1.42343_71107_49683_57734e+0;
        let den = ((((((1.05075_00716_44416_84324e-9 * r + 5.47593_80849_95344_94600e-4) * r
            + 1.51986_66563_61645_71966e-2)
            * r
            + 1.48103_97642_74800_74590e-1)
            * r
            + 6.89767_33498_51000_04550e-1)
            * r
            + 1.67638_48301_83803_84940e+0)
            * r
            + 2.05319_16266_37758_82187e+0)
            * r
            + 1.0;
        num / den
    } else {
        let r = r - 5.0;
        let num = ((((((2.01033_43992_92288_13265e-7 * r + 2.71155_55687_43487_57815e-5) * r
            + 1.24266_09473_88078_43860e-3)
            * r
            + 2.65321_89526_57612_30930e-2)
            * r
            + 2.96560_57182_85048_91230e-1)
            * r
            + 1.78482_65399_17291_33580e+0)
            * r
            + 5.46378_49111_64114_36990e+0)
            * r
            + 6.65790_46435_01103_77720e+0;
        let den = ((((((2.04426_31033_89939_78564e-15 * r + 1.42151_17583_16445_88870e-7) * r
            + 1.84631_83175_10054_68180e-5)
            * r
            + 7.86869_13114_56132_59100e-4)
            * r
            + 1.48753_61290_85061_48525e-2)
            * r
            + 1.36929_88092_27358_05310e-1)
            * r
            + 5.99832_20655_58879_37690e-1)
            * r
            + 1.0;
        num / den
    };
    if q < 0.0 {
        -x
    } else {
        x
    }
}

/// How a search turns its stream's words into normal draws, set by `[evolution] draw_order`
/// (part of the reproducibility contract: the same words give other numbers under the
/// other).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Normals {
    /// [`gaussian`]: Box–Muller from two 64-bit words (draw order 1, every shipped file).
    BoxMuller,
    /// [`gaussian_icdf`]: the inverse distribution function of one 64-bit word (draw order 2).
    InverseCdf,
}

impl Normals {
    /// The stream's 32-bit words one draw uses, always.
    pub const fn words_per_draw(self) -> u128 {
        match self {
            Normals::BoxMuller => 4,
            Normals::InverseCdf => 2,
        }
    }

    /// One normal draw from `rng`.
    #[inline]
    pub fn draw(self, rng: &mut impl RngCore) -> f64 {
        match self {
            Normals::BoxMuller => gaussian(rng),
            Normals::InverseCdf => gaussian_icdf(rng),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn s(seed: u64, purpose: Purpose, g: u64, i: u64, t: u64) -> Rng {
        stream(
            Seed(seed),
            purpose,
            Generation(g),
            IndividualId(i),
            TrialIndex(t),
        )
    }

    #[test]
    fn stream_golden_values() {
        // Pinned: a change here changes every published run.
        let mut r = s(42, Purpose::TrialWorld, 3, 7, 1);
        let got: Vec<u64> = (0..3).map(|_| r.next_u64()).collect();
        assert_eq!(got, GOLDEN_STREAM, "stream() output changed");
    }

    const GOLDEN_STREAM: [u64; 3] = [
        980_894_188_289_985_386,
        8_277_159_072_362_293_349,
        17_059_733_452_536_483_452,
    ];

    #[test]
    fn streams_differ_in_every_coordinate() {
        let base = s(1, Purpose::Variation, 2, 3, 4).next_u64();
        for other in [
            s(2, Purpose::Variation, 2, 3, 4),
            s(1, Purpose::TrialWorld, 2, 3, 4),
            s(1, Purpose::Variation, 3, 3, 4),
            s(1, Purpose::Variation, 2, 4, 4),
            s(1, Purpose::Variation, 2, 3, 5),
        ] {
            let mut other = other;
            assert_ne!(base, other.next_u64());
        }
        // Swapping two coordinates must not give the same stream.
        assert_ne!(
            s(1, Purpose::Variation, 2, 3, 4).next_u64(),
            s(1, Purpose::Variation, 3, 2, 4).next_u64()
        );
    }

    #[test]
    fn sampler_golden_values() {
        let mut r = s(7, Purpose::Demo, 0, 0, 0);
        let u = unit(&mut r);
        let b = below(&mut r, 10);
        let g = gaussian(&mut r);
        assert_eq!(
            (u.to_bits(), b, g.to_bits()),
            GOLDEN_SAMPLERS,
            "sampler output changed: unit {u}, below {b}, gaussian {g}"
        );
    }

    // unit = 0.9424305837936606, below(10) = 4, gaussian = -1.573355375367113.
    const GOLDEN_SAMPLERS: (u64, u64, u64) =
        (4_606_663_879_597_267_794, 4, 13_833_136_618_709_647_417);

    #[test]
    fn unit_is_in_range_and_below_is_unbiased_enough() {
        let mut r = s(9, Purpose::Demo, 0, 0, 0);
        let mut counts = [0u32; 6];
        for _ in 0..60_000 {
            let u = unit(&mut r);
            assert!((0.0..1.0).contains(&u));
            counts[below(&mut r, 6) as usize] += 1;
        }
        for c in counts {
            assert!((9_400..10_600).contains(&c), "counts {counts:?}");
        }
        assert_eq!(below(&mut r, 0), 0);
        assert_eq!(below(&mut r, 1), 0);
    }

    #[test]
    fn gaussian_has_unit_moments() {
        let mut r = s(11, Purpose::Demo, 0, 0, 0);
        let n = 100_000;
        let xs: Vec<f64> = (0..n).map(|_| gaussian(&mut r)).collect();
        let mean = xs.iter().sum::<f64>() / n as f64;
        let var = xs.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / n as f64;
        assert!(mean.abs() < 0.01, "mean {mean}");
        assert!((var - 1.0).abs() < 0.02, "variance {var}");
        assert!(xs.iter().all(|x| x.is_finite()));
    }

    #[test]
    fn inverse_normal_cdf_agrees_with_published_as241_values() {
        // Python's statistics.NormalDist().inv_cdf (AS241) at each region's points and edges:
        // the centre (|p - 0.5| <= 0.425), the near tail (r <= 5) and the far tail.
        let cases = [
            (1e-300, -37.0470962993612),
            (1e-20, -9.262340089798405),
            (5.551115123125783e-17, -8.292361075813595),
            (1e-06, -4.753424308822899),
            (0.01, -2.3263478740408408),
            (0.07, -1.4757910281791702),
            (0.075, -1.4395314709384557),
            (0.3, -0.5244005127080407),
            (0.5, 0.0),
            (0.500000001, 2.506628203738712e-09),
            (0.8, 0.8416212335729144),
            (0.925, 1.439531470938456),
            (0.99, 2.3263478740408408),
            (0.9999999999999999, 8.209536151601386),
        ];
        for (p, want) in cases {
            let got = inverse_normal_cdf(p);
            assert!(
                (got - want).abs() <= 4.0 * f64::EPSILON * want.abs(),
                "p {p}: got {got}, AS241 gives {want}"
            );
        }
    }

    #[test]
    fn gaussian_icdf_uses_one_word_and_has_unit_moments() {
        let mut r = s(11, Purpose::Demo, 0, 0, 0);
        let n = 100_000;
        let xs: Vec<f64> = (0..n).map(|_| gaussian_icdf(&mut r)).collect();
        assert_eq!(r.get_word_pos(), 2 * n as u128, "one 64-bit word a draw");
        let mean = xs.iter().sum::<f64>() / n as f64;
        let var = xs.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / n as f64;
        assert!(mean.abs() < 0.01, "mean {mean}");
        assert!((var - 1.0).abs() < 0.02, "variance {var}");
        // The tails: P(|z| > 2) = 0.0455.
        let beyond = xs.iter().filter(|x| x.abs() > 2.0).count() as f64 / n as f64;
        assert!((beyond - 0.0455).abs() < 0.003, "share beyond 2: {beyond}");
        // Pinned: draw order 2's normals are part of the contract.
        let mut r = s(7, Purpose::Demo, 0, 0, 0);
        let first = gaussian_icdf(&mut r);
        assert_eq!(
            first.to_bits(),
            GOLDEN_ICDF,
            "gaussian_icdf output changed: {first}"
        );
        let mut r = s(7, Purpose::Demo, 0, 0, 0);
        assert_eq!(Normals::InverseCdf.draw(&mut r).to_bits(), GOLDEN_ICDF);
        let mut r = s(7, Purpose::Demo, 0, 0, 0);
        let _ = unit(&mut r);
        let _ = below(&mut r, 10);
        assert_eq!(
            Normals::BoxMuller.draw(&mut r).to_bits(),
            GOLDEN_SAMPLERS.2,
            "draw order 1's normal is gaussian()"
        );
    }

    // 1.5755097383456373: AS241 of the first word, which unit() reads as 0.9424305837936606.
    const GOLDEN_ICDF: u64 = 4_609_774_284_243_178_912;
}
