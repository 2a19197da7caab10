//! Smell (§4.2, §7.1, §7.2): what a smelly thing gives off, how it fades with distance
//! (eq. 25, cut off by the range θ of eq. 26), and how opaque walls hide it from a receptor.

use crate::geometry::{segments_intersect, Segment, Vec2};
use crate::sim::wall::BoxedSegment;
use serde::{Deserialize, Serialize};

/// What one smelly thing gives off, precomputed for the receptor loop.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Smell {
    /// i · o: the odour vector times the intensity at the centre (§4.2 "the smell leaving the
    /// object is given by I · o").
    pub emission: [f64; 8],
    /// θ², or +∞ when the range is unlimited (eq. 25). Squared so that the range test of
    /// §7.1, done before the costly occlusion test, needs no square root.
    pub range_squared: f64,
    /// True when every emission component is 0: such a thing is skipped outright.
    pub silent: bool,
}

impl Smell {
    /// The smell of a thing with odour `odour`, intensity `intensity` and optional range θ.
    pub fn new(odour: &[f64; 8], intensity: f64, range: Option<f64>) -> Smell {
        let emission = odour.map(|o| intensity * o);
        Smell {
            emission,
            range_squared: range.map_or(f64::INFINITY, |r| r * r),
            silent: emission.iter().all(|&e| e == 0.0),
        }
    }

    /// A thing that does not smell.
    pub const NONE: Smell = Smell {
        emission: [0.0; 8],
        range_squared: f64::INFINITY,
        silent: true,
    };
}

/// eq. 25/26 without the intensity: the factor 1 / (1 + c d²) at squared distance `d2`, or 0
/// when `d2` is not strictly inside the range (eq. 26 says "if d < θ").
#[inline]
pub fn falloff(d2: f64, c: f64, range_squared: f64) -> f64 {
    if d2 < range_squared {
        1.0 / (1.0 + c * d2)
    } else {
        0.0
    }
}

/// §7.1: a thing at `centre` is visible to a receptor at `receptor` when the segment between
/// them crosses no opaque wall (touching counts as crossing, as everywhere in §6).
#[inline]
pub fn visible(receptor: Vec2, centre: Vec2, opaque: &[BoxedSegment]) -> bool {
    let line = Segment::new(receptor, centre);
    let (lo, hi) = (receptor.min(centre), receptor.max(centre));
    !opaque
        .iter()
        .any(|wall| wall.may_meet(lo, hi) && segments_intersect(&line, &wall.segment))
}

/// Adds the smell of one thing at `centre` to a receptor's accumulator `acc`: `scale` · I(d) ·
/// o_k for each k, where `scale` is 1, or amount / capacity for food whose smell follows its
/// amount. The §7.1 order is kept: the range test first, the wall test only for things in
/// range, since the wall test is the expensive part.
#[inline]
pub fn accumulate(
    acc: &mut [f64; 8],
    receptor: Vec2,
    centre: Vec2,
    smell: &Smell,
    scale: f64,
    c: f64,
    opaque: &[BoxedSegment],
) {
    if smell.silent || scale == 0.0 {
        return;
    }
    let d2 = receptor.distance_squared(centre);
    let f = falloff(d2, c, smell.range_squared);
    if f == 0.0 || !visible(receptor, centre, opaque) {
        return;
    }
    let f = f * scale;
    for (a, e) in acc.iter_mut().zip(smell.emission.iter()) {
        *a += f * e;
    }
}

/// [`accumulate`] with the occluders chosen after the range test: `near` (the opaque walls
/// that may meet the box `[lo, hi]` around the receptor) for a thing whose centre lies in the
/// box, since the segment to it lies in the box too, else `all`. The same bits as
/// [`accumulate`] with `all`.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub fn accumulate_near(
    acc: &mut [f64; 8],
    receptor: Vec2,
    centre: Vec2,
    smell: &Smell,
    scale: f64,
    c: f64,
    (lo, hi, near): (Vec2, Vec2, &[BoxedSegment]),
    all: &[BoxedSegment],
) {
    if smell.silent || scale == 0.0 {
        return;
    }
    let d2 = receptor.distance_squared(centre);
    let f = falloff(d2, c, smell.range_squared);
    if f == 0.0 {
        return;
    }
    let inside = centre.x >= lo.x && centre.x <= hi.x && centre.y >= lo.y && centre.y <= hi.y;
    if !visible(receptor, centre, if inside { near } else { all }) {
        return;
    }
    let f = f * scale;
    for (a, e) in acc.iter_mut().zip(smell.emission.iter()) {
        *a += f * e;
    }
}

/// §7.1: a receptor saturates at 1.
#[inline]
pub fn saturate(acc: &mut [f64; 8]) {
    for a in acc.iter_mut() {
        *a = a.min(1.0);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn falloff_is_eq25_and_strict_at_range() {
        assert_eq!(falloff(0.0, 0.01, f64::INFINITY), 1.0);
        // d = 10, c = 0.01: 1 / (1 + 1) = 0.5.
        assert_eq!(falloff(100.0, 0.01, f64::INFINITY), 0.5);
        // d = θ = 10: eq. 26 gives 0 (d < θ is false).
        assert_eq!(falloff(100.0, 0.01, 100.0), 0.0);
        assert_eq!(falloff(99.0, 0.01, 100.0), 1.0 / 1.99);
    }

    #[test]
    fn silent_things_are_marked() {
        assert!(Smell::new(&[1.0; 8], 0.0, None).silent);
        assert!(!Smell::new(&[0.0, 0.5, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0], 2.0, None).silent);
        assert_eq!(Smell::new(&[1.0; 8], 2.0, Some(3.0)).range_squared, 9.0);
    }
}
