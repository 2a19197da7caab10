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

/// A standard normal draw by the ziggurat method (Marsaglia & Tsang 2000, with Doornik's
/// 256 layers and 52-bit uniforms, as `rand_distr` draws it): draw order 2's normal (see
/// [`Normals`]). One 64-bit word almost always (98.8%): its low 8 bits choose a layer, its top
/// 52 a point in it; a point outside the layer's inner rectangle draws a `unit()` to test it
/// against the density (`libm::exp`), and the bottom layer's tail draws by Marsaglia's
/// method (`libm::log`). So the number of words varies: runs of these draws cannot be split
/// over threads by word position, and draw order 2 gives each individual its own stream.
#[inline]
pub fn gaussian_ziggurat(rng: &mut impl RngCore) -> f64 {
    let z = ziggurat();
    loop {
        let bits = rng.next_u64();
        let i = (bits & 0xFF) as usize;
        // 2 · [1, 2) − 3: in [−1, 1), from the 52 bits the layer index does not use.
        let u = 2.0 * f64::from_bits(bits >> 12 | 0x3FF0_0000_0000_0000) - 3.0;
        let x = u * z.x[i];
        if x.abs() < z.x[i + 1] {
            return x;
        }
        if i == 0 {
            return ziggurat_tail(rng, u);
        }
        if z.f[i + 1] + (z.f[i] - z.f[i + 1]) * unit(rng) < libm::exp(-0.5 * x * x) {
            return x;
        }
    }
}

/// The normal's tail beyond the ziggurat's R, on the side of `u`'s sign (Marsaglia 1964).
#[cold]
fn ziggurat_tail(rng: &mut impl RngCore, u: f64) -> f64 {
    loop {
        // 1 − unit() is in (0, 1], so both logarithms are finite.
        let x = -libm::log(1.0 - unit(rng)) / ZIGGURAT_R;
        let y = -libm::log(1.0 - unit(rng));
        if 2.0 * y > x * x {
            return if u < 0.0 {
                -(ZIGGURAT_R + x)
            } else {
                ZIGGURAT_R + x
            };
        }
    }
}

/// The 256-layer normal ziggurat's right edge of the bottom layer's rectangle part, R, and
/// the area V of every layer (under the unnormalised density exp(−x²/2)).
const ZIGGURAT_R: f64 = 3.654_152_885_361_009;
const ZIGGURAT_V: f64 = 0.004_928_673_233_99;

/// The ziggurat's layers: `x[i]` the right edge of layer i (x[0] = V / f(R) for the bottom
/// layer with its tail, x[1] = R, down to x[256] = 0), `f[i]` = exp(−x[i]²/2).
struct Ziggurat {
    x: [f64; 257],
    f: [f64; 257],
}

/// The tables, computed once with `libm` (so the same on every platform) by the recurrence
/// x[i + 1] = f⁻¹(V / x[i] + f(x[i])).
fn ziggurat() -> &'static Ziggurat {
    static TABLES: std::sync::OnceLock<Ziggurat> = std::sync::OnceLock::new();
    TABLES.get_or_init(|| {
        let f = |x: f64| libm::exp(-0.5 * x * x);
        let mut x = [0.0; 257];
        x[0] = ZIGGURAT_V / f(ZIGGURAT_R);
        x[1] = ZIGGURAT_R;
        for i in 1..255 {
            x[i + 1] = libm::sqrt(-2.0 * libm::log(ZIGGURAT_V / x[i] + f(x[i])));
        }
        x[256] = 0.0;
        let mut fx = [0.0; 257];
        for (fi, &xi) in fx.iter_mut().zip(&x) {
            *fi = f(xi);
        }
        Ziggurat { x, f: fx }
    })
}

/// How a search draws its normals, set by `[evolution] draw_order` (part of the
/// reproducibility contract: the same stream gives other numbers under the other).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Normals {
    /// [`gaussian`]: Box–Muller from exactly two 64-bit words (draw order 1, every shipped
    /// file), so a run of draws can be split over threads by word position.
    BoxMuller,
    /// [`gaussian_ziggurat`]: a varying number of words, about a sixth of Box–Muller's cost
    /// (draw order 2, where each individual draws from its own stream).
    Ziggurat,
}

impl Normals {
    /// One normal draw from `rng`.
    #[inline]
    pub fn draw(self, rng: &mut impl RngCore) -> f64 {
        match self {
            Normals::BoxMuller => gaussian(rng),
            Normals::Ziggurat => gaussian_ziggurat(rng),
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

    /// The standard normal distribution function, Φ(x) = erfc(−x/√2) / 2.
    fn phi(x: f64) -> f64 {
        0.5 * libm::erfc(-x / std::f64::consts::SQRT_2)
    }

    #[test]
    fn ziggurat_tables_close_at_zero() {
        // The recurrence from R and V must come down to the top layer: V / x[255] + f(x[255])
        // is 1 (x[256] = 0), which holds only for a consistent (R, V).
        let z = ziggurat();
        let top = ZIGGURAT_V / z.x[255] + libm::exp(-0.5 * z.x[255] * z.x[255]);
        assert!((top - 1.0).abs() < 1e-9, "{top}");
        assert!(z.x.windows(2).all(|w| w[0] > w[1]), "edges decrease");
        assert_eq!((z.x[1], z.f[256]), (ZIGGURAT_R, 1.0));
    }

    #[test]
    fn gaussian_ziggurat_is_standard_normal() {
        let mut r = s(11, Purpose::Demo, 0, 0, 0);
        let n = 400_000;
        let mut xs: Vec<f64> = (0..n).map(|_| gaussian_ziggurat(&mut r)).collect();
        let mean = xs.iter().sum::<f64>() / n as f64;
        let var = xs.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / n as f64;
        assert!(mean.abs() < 0.006, "mean {mean}");
        assert!((var - 1.0).abs() < 0.01, "variance {var}");
        // The tail beyond R (drawn by its own method): P(|z| > 3.654) = 2.58e-4, about 103.
        let tail = xs.iter().filter(|x| x.abs() > ZIGGURAT_R).count();
        assert!((60..=150).contains(&tail), "{tail} draws beyond R");
        // Kolmogorov–Smirnov against Φ: D = 0.0031 is the 0.1% critical value at this n.
        xs.sort_by(f64::total_cmp);
        let d = xs
            .iter()
            .enumerate()
            .map(|(i, &x)| {
                let p = phi(x);
                (p - i as f64 / n as f64)
                    .abs()
                    .max((i + 1) as f64 / n as f64 - p)
            })
            .fold(0.0, f64::max);
        assert!(d < 0.0031, "KS distance {d}");
        // Pinned: draw order 2's normals are part of the contract.
        let mut r = s(7, Purpose::Demo, 0, 0, 0);
        let first: Vec<u64> = (0..3)
            .map(|_| gaussian_ziggurat(&mut r).to_bits())
            .collect();
        assert_eq!(first, GOLDEN_ZIGGURAT, "gaussian_ziggurat output changed");
        let mut r = s(7, Purpose::Demo, 0, 0, 0);
        assert_eq!(Normals::Ziggurat.draw(&mut r).to_bits(), GOLDEN_ZIGGURAT[0]);
        let mut r = s(7, Purpose::Demo, 0, 0, 0);
        let _ = unit(&mut r);
        let _ = below(&mut r, 10);
        assert_eq!(
            Normals::BoxMuller.draw(&mut r).to_bits(),
            GOLDEN_SAMPLERS.2,
            "draw order 1's normal is gaussian()"
        );
    }

    const GOLDEN_ZIGGURAT: [u64; 3] = [
        4_609_638_919_596_108_256,
        13_811_047_066_491_985_322,
        4_605_415_330_405_330_905,
    ];
}
