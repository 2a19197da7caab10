//! Smell (§4.2, §7.1, §7.2): what a smelly thing gives off, how it fades with distance
//! (eq. 25, cut off by the range θ of eq. 26), and how opaque walls hide it from a receptor.

use crate::geometry::BoxedSegment;
use crate::geometry::{segments_intersect, Segment, Vec2};
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

    /// Silences it (`quiet`) or gives it back its emission (silent again when that is all
    /// zeros): for a predator asleep or away between flights.
    pub fn set_quiet(&mut self, quiet: bool) {
        self.silent = quiet || self.emission.iter().all(|&e| e == 0.0);
    }

    /// A thing that does not smell.
    pub const NONE: Smell = Smell {
        emission: [0.0; 8],
        range_squared: f64::INFINITY,
        silent: true,
    };
}

/// Eq. 25 without the intensity, the one place it is written: the factor 1 / (1 + c d²) of
/// I(d) = i / (1 + c d²) at squared distance `d2`. Always inlined, so that each caller
/// compiles to the expression it wrote out before.
#[inline(always)]
pub fn diffusion(c: f64, d2: f64) -> f64 {
    1.0 / (1.0 + c * d2)
}

/// eq. 25/26 without the intensity: [`diffusion`] at squared distance `d2`, or 0 when `d2`
/// is not strictly inside the range (eq. 26 says "if d < θ").
#[inline]
pub fn falloff(d2: f64, c: f64, range_squared: f64) -> f64 {
    if d2 < range_squared {
        diffusion(c, d2)
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

/// An opaque wall as seen from one receptor: the box `[x0, x1] × [y0, y1]` (bounds may be
/// infinite) a source's centre must lie in for the segment from the receptor to it to meet
/// the wall's box. For a finite receptor and centre, "the centre is in the box" is exactly
/// [`BoxedSegment::may_meet`] of the segment's box (the receptor's side of the wall is
/// settled once per receptor instead of once per source), so [`visible_from`] gives the
/// answers of [`visible`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Shade {
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
    segment: Segment,
}

impl Shade {
    /// `wall` seen from `receptor`. The segment's box misses the wall's box on the low x side
    /// only when both ends are below `wall.lo.x`, which the receptor settles: if it is below,
    /// the centre must not be (x0 = lo.x), else nothing is required (x0 = −∞). Likewise for
    /// the other three sides. NaN bounds require nothing, as in `may_meet`.
    #[inline]
    pub fn new(receptor: Vec2, wall: &BoxedSegment) -> Shade {
        // The same box as a source's wall shade, seen from the receptor instead.
        let WallShade { x0, x1, y0, y1 } = WallShade::new(receptor, wall.lo, wall.hi);
        Shade {
            x0,
            x1,
            y0,
            y1,
            segment: wall.segment,
        }
    }
}

/// A wall as seen from a smell source's centre p: the box `[x0, x1] × [y0, y1]` (bounds may be
/// infinite) a receptor r must lie in for the box of the segment from r to p to meet the
/// wall's box. The segment's box misses the wall's box on the low x side only when both ends
/// are below the wall's `lo.x`, which p settles: if p is below, r must not be (x0 = lo.x),
/// else nothing is required (x0 = −∞); likewise for the other three sides. So for r and p not
/// NaN, "r is in the box" is exactly [`BoxedSegment::may_meet`] of the segment's box, the
/// first test of [`crate::sim::smell::visible_among`], settled per source and wall when the
/// index is built rather than per receptor (the same construction as
/// [`crate::sim::smell::Shade`], with the roles of the two ends swapped, which the box of a
/// segment does not see).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WallShade {
    /// Least x.
    pub x0: f64,
    /// Greatest x.
    pub x1: f64,
    /// Least y.
    pub y0: f64,
    /// Greatest y.
    pub y1: f64,
}

impl WallShade {
    /// The wall whose box is `[lo, hi]` seen from `p` (also the first part of a receptor's
    /// [`Shade`]).
    #[inline]
    pub(crate) fn new(p: Vec2, lo: Vec2, hi: Vec2) -> WallShade {
        let pick = |cut: bool, v: f64, none: f64| if cut { v } else { none };
        WallShade {
            x0: pick(p.x < lo.x, lo.x, f64::NEG_INFINITY),
            x1: pick(hi.x < p.x, hi.x, f64::INFINITY),
            y0: pick(p.y < lo.y, lo.y, f64::NEG_INFINITY),
            y1: pick(hi.y < p.y, hi.y, f64::INFINITY),
        }
    }

    /// Does the box of the segment from `r` to the source's centre meet the wall's box (`r`
    /// and the centre not NaN), and is `ask` true? One branch for the caller rather than one
    /// per side (the answers are as good as random): the tests are counted, which the
    /// compiler keeps free of branches where it turns `&` and `&&` alike into jumps.
    #[inline(always)]
    pub fn holds(&self, r: Vec2, ask: bool) -> bool {
        let n = u8::from(r.x >= self.x0)
            + u8::from(r.x <= self.x1)
            + u8::from(r.y >= self.y0)
            + u8::from(r.y <= self.y1)
            + u8::from(ask);
        n == 5
    }
}

/// [`visible`] for a finite `receptor` and `centre`, with the opaque walls given as the
/// receptor's [`Shade`]s: the same answers.
#[inline]
pub fn visible_from(receptor: Vec2, centre: Vec2, shades: &[Shade]) -> bool {
    let line = Segment::new(receptor, centre);
    !shades.iter().any(|s| {
        centre.x >= s.x0
            && centre.x <= s.x1
            && centre.y >= s.y0
            && centre.y <= s.y1
            && segments_intersect(&line, &s.segment)
    })
}

/// eq. 25/26 at both receptors of a creature for a thing at `centre`: `None` when the thing is
/// silent or out of range of both (then [`accumulate`] adds nothing for either).
#[inline(always)]
pub fn falloff_pair(receptors: [Vec2; 2], centre: Vec2, smell: &Smell, c: f64) -> Option<[f64; 2]> {
    if smell.silent {
        return None;
    }
    let f = receptors.map(|r| falloff(r.distance_squared(centre), c, smell.range_squared));
    if f[0] == 0.0 && f[1] == 0.0 {
        None
    } else {
        Some(f)
    }
}

/// The rest of [`accumulate`] at both receptors of a creature at once, into `acc[0]` and
/// `acc[1]`, given the falloffs `f` of [`falloff_pair`], with the occluders chosen per source:
/// `shades[i]` (the opaque walls that may meet the box `[lo, hi]`, which holds both
/// receptors, as receptor i sees them) for a thing whose centre lies in the box, since the
/// segment from either receptor to it lies in the box too, else `all`. Which walls are tested
/// does not change the yes/no answer of [`visible`] as long as every wall that may meet the
/// segment is among them, and each receptor's sum gets its terms in the caller's order, so
/// each receptor has the same bits as [`accumulate`] with `all`. The occlusion test runs only
/// for a finite squared distance inside the range, so with finite receptor and centre, as
/// [`visible_from`] needs. `scale` (a sum and a division for food whose smell follows its
/// amount) is only computed for a thing in range of a receptor: skipping a thing of scale 0
/// after the range tests rather than before adds nothing either way.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub fn add_pair(
    acc: &mut [[f64; 8]; 2],
    receptors: [Vec2; 2],
    centre: Vec2,
    smell: &Smell,
    (f, scale): ([f64; 2], f64),
    (lo, hi, shades): (Vec2, Vec2, [&[Shade]; 2]),
    all: &[BoxedSegment],
) {
    if scale == 0.0 {
        return;
    }
    let inside = centre.x >= lo.x && centre.x <= hi.x && centre.y >= lo.y && centre.y <= hi.y;
    for i in 0..2 {
        if f[i] == 0.0 {
            continue;
        }
        let receptor = receptors[i];
        let seen = if inside {
            visible_from(receptor, centre, shades[i])
        } else {
            visible(receptor, centre, all)
        };
        if seen {
            add(&mut acc[i], f[i] * scale, &smell.emission);
        }
    }
}

/// `acc += f · emission`, component by component.
#[inline(always)]
pub fn add(acc: &mut [f64; 8], f: f64, emission: &[f64; 8]) {
    for (a, e) in acc.iter_mut().zip(emission.iter()) {
        *a += f * e;
    }
}

/// [`visible`] from a receptor in a cell of the index's smell grid to a source that cell
/// lists: `walls` (indices into the fixed opaque walls `fixed`) are the only fixed walls that
/// may cross the segment, and `doors` are the closed opaque doors, so the yes/no answer is
/// that of every opaque wall.
#[inline(always)]
pub fn visible_among(
    receptor: Vec2,
    centre: Vec2,
    walls: &[u32],
    fixed: &[BoxedSegment],
    doors: &[BoxedSegment],
) -> bool {
    if walls.is_empty() && doors.is_empty() {
        return true;
    }
    let line = Segment::new(receptor, centre);
    let (lo, hi) = (receptor.min(centre), receptor.max(centre));
    let blocks = |w: &BoxedSegment| w.may_meet(lo, hi) && segments_intersect(&line, &w.segment);
    !(walls.iter().any(|&k| blocks(&fixed[k as usize])) || doors.iter().any(blocks))
}

/// The range test of eq. 26 at both receptors for a thing at `centre` of range θ² =
/// `range_squared`: the squared distances and whether each is strictly inside the range
/// (the test of [`falloff`]), for the caller to skip a thing out of range of both with one
/// branch.
#[inline(always)]
pub fn reach_pair(receptors: [Vec2; 2], centre: Vec2, range_squared: f64) -> ([f64; 2], [bool; 2]) {
    let d2 = [
        receptors[0].distance_squared(centre),
        receptors[1].distance_squared(centre),
    ];
    (d2, [d2[0] < range_squared, d2[1] < range_squared])
}

/// [`accumulate`] at both receptors for a food or aversive object that the smell cells of
/// the receptors list, given the squared distances `d2` and the range tests `reach` of
/// [`reach_pair`] (false also for a receptor whose cell does not list it, which proves it
/// out of range there): `walls[i]` are its walls in receptor i's cell (see
/// [`visible_among`]). The terms are those of [`accumulate`]: both falloffs are computed
/// without a branch and the one out of range dropped (a division whose result is dropped
/// changes nothing), and `scale` is only computed for an object in range, as in
/// [`add_pair`].
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub fn accumulate_listed(
    acc: &mut [[f64; 8]; 2],
    receptors: [Vec2; 2],
    centre: Vec2,
    (d2, reach): ([f64; 2], [bool; 2]),
    emission: &[f64; 8],
    scale: impl FnOnce() -> f64,
    c: f64,
    walls: [&[u32]; 2],
    (fixed, doors): (&[BoxedSegment], &[BoxedSegment]),
) {
    let q = [diffusion(c, d2[0]), diffusion(c, d2[1])];
    let f0 = if reach[0] { q[0] } else { 0.0 };
    let f1 = if reach[1] { q[1] } else { 0.0 };
    if f0 == 0.0 && f1 == 0.0 {
        return;
    }
    let scale = scale();
    if scale == 0.0 {
        return;
    }
    if f0 != 0.0 && visible_among(receptors[0], centre, walls[0], fixed, doors) {
        add(&mut acc[0], f0 * scale, emission);
    }
    if f1 != 0.0 && visible_among(receptors[1], centre, walls[1], fixed, doors) {
        add(&mut acc[1], f1 * scale, emission);
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
