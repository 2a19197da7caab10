//! Geometry of the report's §6: contact between circles and segments, segment intersection,
//! and ray casts, as pure, total functions.
//!
//! A miss is `false` or `None`, never an error, and every function accepts degenerate input
//! (zero-radius circles, zero-length segments, parallel and collinear segments). Whiskers,
//! smell occlusion, motion and the eye all call these functions rather than repeating the math.
//!
//! Frame (SPEC-NOTES, §2–3): x grows to the right, y grows downwards; contact is inclusive
//! (touching counts).

use serde::{Deserialize, Serialize};

/// A point or direction in the plane, in LU. glam's `DVec2` is plain scalar f64 arithmetic,
/// so it gives the same bits on every CPU.
pub type Vec2 = glam::DVec2;

/// A line segment between two points (a wall, a whisker, a path). Zero length is legal.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Segment {
    /// First end point.
    pub a: Vec2,
    /// Second end point.
    pub b: Vec2,
}

impl Segment {
    /// The segment from `a` to `b`.
    pub const fn new(a: Vec2, b: Vec2) -> Self {
        Segment { a, b }
    }

    /// Length in LU.
    pub fn length(&self) -> f64 {
        (self.b - self.a).length()
    }

    /// Axis-aligned bounding box as (min corner, max corner).
    pub fn bounds(&self) -> (Vec2, Vec2) {
        (self.a.min(self.b), self.a.max(self.b))
    }
}

/// A circle (a body, a food item, a trigger region) in LU. Radius 0 is legal (a point).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Circle {
    /// Centre.
    pub centre: Vec2,
    /// Radius in LU (>= 0).
    pub radius: f64,
}

impl Circle {
    /// The circle of `radius` around `centre`.
    pub const fn new(centre: Vec2, radius: f64) -> Self {
        Circle { centre, radius }
    }
}

/// eq. 1: two circles are in contact when the distance between their centres is at most the
/// sum of their radii. Compared on squares, which is the same test without a square root.
#[inline]
pub fn circles_touch(c0: Vec2, r0: f64, c1: Vec2, r1: f64) -> bool {
    let r = r0 + r1;
    c0.distance_squared(c1) <= r * r
}

/// The point of `seg` closest to `p`.
#[inline]
pub fn closest_point_on_segment(p: Vec2, seg: &Segment) -> Vec2 {
    let ab = seg.b - seg.a;
    let len2 = ab.length_squared();
    if len2 == 0.0 {
        return seg.a;
    }
    let t = ((p - seg.a).dot(ab) / len2).clamp(0.0, 1.0);
    seg.a + ab * t
}

/// Squared exact distance from `p` to the segment (not to its infinite line; see SPEC-NOTES
/// on eq. 4).
#[inline]
pub fn point_segment_distance_squared(p: Vec2, seg: &Segment) -> f64 {
    p.distance_squared(closest_point_on_segment(p, seg))
}

/// §6.2: a circle of radius `r` at `c` is in contact with `seg` when the smallest distance
/// from `c` to the segment is at most `r`. The bounding-box test of eq. 2–3 rejects far
/// segments cheaply; the exact point-to-segment distance then replaces eq. 4, which measured
/// the distance to the infinite line and so reported false contacts past a segment's ends.
#[inline]
pub fn circle_touches_segment(c: Vec2, r: f64, seg: &Segment) -> bool {
    let (lo, hi) = seg.bounds();
    // eq. 2 and eq. 3.
    if c.x < lo.x - r || c.x > hi.x + r || c.y < lo.y - r || c.y > hi.y + r {
        return false;
    }
    point_segment_distance_squared(c, seg) <= r * r
}

/// Twice the signed area of the triangle (a, b, c), with its sign exact for the given f64
/// values: positive, negative or zero exactly as c lies on one side of the line a→b, the
/// other, or on it. (In the screen frame, positive means a→b→c turns clockwise on screen.)
///
/// A plain float determinant can get the sign wrong, or miss an exact zero, when c lies
/// within rounding error of the line; then T-junctions, shared corners and collinear walls
/// would depend on float accidents. This is Shewchuk's adaptive `orient2d`: the float
/// determinant is returned when its error bound proves the sign, and the rare remaining
/// cases are decided by exact expansion arithmetic (then the value is just -1, 0 or 1).
/// Exact unless a product underflows (coordinate differences below ~1e-150 LU).
#[inline]
fn orientation(a: Vec2, b: Vec2, c: Vec2) -> f64 {
    let detleft = (a.x - c.x) * (b.y - c.y);
    let detright = (a.y - c.y) * (b.x - c.x);
    let det = detleft - detright;
    let detsum = if detleft > 0.0 {
        if detright <= 0.0 {
            return det;
        }
        detleft + detright
    } else if detleft < 0.0 {
        if detright >= 0.0 {
            return det;
        }
        -detleft - detright
    } else {
        // A factor is exactly zero, so detleft is exact and det = -detright is exact in sign.
        return det;
    };
    // Shewchuk's ccwerrboundA = (3 + 16ε)ε with ε = 2^-53.
    const EPS: f64 = f64::EPSILON * 0.5;
    const ERRBOUND_A: f64 = (3.0 + 16.0 * EPS) * EPS;
    let errbound = ERRBOUND_A * detsum;
    if det >= errbound || -det >= errbound {
        return det;
    }
    orientation_exact(a, b, c)
}

/// The sign (-1, 0 or 1) of (a.x−c.x)(b.y−c.y) − (a.y−c.y)(b.x−c.x), computed exactly: every
/// difference and product is split into error-free float pairs and their sum is accumulated
/// as a non-overlapping expansion, whose largest component carries the sign.
#[cold]
fn orientation_exact(a: Vec2, b: Vec2, c: Vec2) -> f64 {
    let (acx, acxt) = two_diff(a.x, c.x);
    let (acy, acyt) = two_diff(a.y, c.y);
    let (bcx, bcxt) = two_diff(b.x, c.x);
    let (bcy, bcyt) = two_diff(b.y, c.y);
    let mut expansion = [0.0f64; 16];
    let mut len = 0usize;
    let products = [
        (acx, bcy),
        (acx, bcyt),
        (acxt, bcy),
        (acxt, bcyt),
        (-acy, bcx),
        (-acy, bcxt),
        (-acyt, bcx),
        (-acyt, bcxt),
    ];
    for (x, y) in products {
        let (p, e) = two_product(x, y);
        len = grow_expansion(&mut expansion, len, e);
        len = grow_expansion(&mut expansion, len, p);
    }
    // Non-overlapping components in increasing magnitude: the last non-zero one dominates.
    match expansion[..len].iter().rev().find(|&&x| x != 0.0) {
        Some(&x) if x > 0.0 => 1.0,
        Some(&x) if x < 0.0 => -1.0,
        Some(&x) => x, // NaN input stays NaN
        None => 0.0,
    }
}

/// Knuth's TwoSum: a + b = s + e exactly.
#[inline]
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bv = s - a;
    let av = s - bv;
    (s, (a - av) + (b - bv))
}

/// a − b = s + e exactly.
#[inline]
fn two_diff(a: f64, b: f64) -> (f64, f64) {
    two_sum(a, -b)
}

/// a · b = p + e exactly (barring underflow). `libm::fma` is correctly rounded on every
/// platform, unlike some system fma implementations.
#[inline]
fn two_product(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, libm::fma(a, b, -p))
}

/// Shewchuk's Grow-Expansion with zero elimination: adds `b` to the non-overlapping
/// expansion `e[..len]` (increasing magnitude) in place and returns the new length. The
/// length grows by at most one, so 16 additions fit in 16 slots.
fn grow_expansion(e: &mut [f64; 16], len: usize, b: f64) -> usize {
    let mut q = b;
    let mut out = 0usize;
    for i in 0..len {
        let (s, h) = two_sum(q, e[i]);
        q = s;
        if h != 0.0 {
            e[out] = h;
            out += 1;
        }
    }
    if q != 0.0 && out < e.len() {
        e[out] = q;
        out += 1;
    }
    out
}

/// Given that `p` is collinear with segment (a, b), does it lie within the segment's box?
#[inline]
fn within_box(a: Vec2, b: Vec2, p: Vec2) -> bool {
    p.x >= a.x.min(b.x) && p.x <= a.x.max(b.x) && p.y >= a.y.min(b.y) && p.y <= a.y.max(b.y)
}

/// §6.3: do the two segments share at least one point? End points touching and collinear
/// overlap count. The bounding-box rejection of eq. 5–8 comes first; the slope form of
/// eq. 9–24 is replaced by orientation tests (SPEC-NOTES), which answer the same question
/// without special cases for vertical, parallel or identical lines.
///
/// Out of line: inlined into every caller (whiskers, motion, the general smell), it would
/// crowd their loops.
#[inline(never)]
pub fn segments_intersect(s0: &Segment, s1: &Segment) -> bool {
    boxes_meet(s0, s1) && segments_meet(s0, s1, || orientation(s1.a, s1.b, s0.b))
}

/// The side of `p` from the line through `seg` (the orientation of `seg.a`, `seg.b`, `p`):
/// for `p` the second end of `s0`, the one orientation of [`segments_intersect`]`(s0, seg)`
/// that does not depend on the first end. A smell source's centre is the second end of
/// every occlusion test against a wall, so its side of each wall is settled once, when the
/// grid is built ([`segments_intersect_past_box`]).
#[inline]
pub fn side_of(seg: &Segment, p: Vec2) -> f64 {
    orientation(seg.a, seg.b, p)
}

/// [`segments_intersect`]`(s0, s1)` when the caller knows that the segments' boxes meet (the
/// rejection of eq. 5–8 would pass) and gives `o4 = `[`side_of`]`(s1, s0.b)`: the rest of the
/// same code, with that orientation read rather than computed. The smell's occlusion test
/// knows both: a wall's [`WallShade`](crate::sim::smell::WallShade) settled the box test for
/// the receptor, and the grid keeps the source's side of the wall. Out of line like
/// [`segments_intersect`]: inlined into the smell's loop over walls, its registers crowded
/// that loop into more spills than the call costs.
#[inline(never)]
pub fn segments_intersect_past_box(s0: &Segment, s1: &Segment, o4: f64) -> bool {
    segments_meet(s0, s1, || o4)
}

/// eq. 5–8: may the two segments meet, as far as their boxes tell?
#[inline(always)]
fn boxes_meet(s0: &Segment, s1: &Segment) -> bool {
    let (lo0, hi0) = s0.bounds();
    let (lo1, hi1) = s1.bounds();
    !(hi0.x < lo1.x || hi1.x < lo0.x || hi0.y < lo1.y || hi1.y < lo0.y)
}

/// The orientation tests of [`segments_intersect`] past the box test, which take the
/// orientation of `s1.a`, `s1.b`, `s0.b` from `o4` so that
/// [`segments_intersect_past_box`] shares them.
#[inline(always)]
fn segments_meet(s0: &Segment, s1: &Segment, o4: impl FnOnce() -> f64) -> bool {
    let (p, q, r, s) = (s0.a, s0.b, s1.a, s1.b);
    let o1 = orientation(p, q, r);
    let o2 = orientation(p, q, s);
    let o3 = orientation(r, s, p);
    let o4 = o4();
    // Proper crossing: each segment's ends lie strictly on opposite sides of the other.
    if ((o1 > 0.0 && o2 < 0.0) || (o1 < 0.0 && o2 > 0.0))
        && ((o3 > 0.0 && o4 < 0.0) || (o3 < 0.0 && o4 > 0.0))
    {
        return true;
    }
    // Touching and collinear cases: an end point lies on the other segment.
    (o1 == 0.0 && within_box(p, q, r))
        || (o2 == 0.0 && within_box(p, q, s))
        || (o3 == 0.0 && within_box(r, s, p))
        || (o4 == 0.0 && within_box(r, s, q))
}

/// Ray cast against a segment: the smallest `t >= 0` such that `origin + t * dir` lies on
/// `seg`, or `None`. `dir` need not be a unit vector; `t` is measured in multiples of it.
/// A ray running along a collinear segment hits it at the nearer end (or at t = 0 when it
/// starts on it). A zero `dir` hits only when the origin lies on the segment.
pub fn ray_segment(origin: Vec2, dir: Vec2, seg: &Segment) -> Option<f64> {
    let e = seg.b - seg.a;
    let denom = dir.perp_dot(e);
    let w = seg.a - origin;
    if denom != 0.0 {
        // origin + t dir = a + u e  =>  t = (w × e) / (dir × e), u = (w × dir) / (dir × e)
        let t = w.perp_dot(e) / denom;
        let u = w.perp_dot(dir) / denom;
        if t >= 0.0 && (0.0..=1.0).contains(&u) {
            return Some(t);
        }
        return None;
    }
    // Parallel, or a degenerate ray or segment.
    let dd = dir.length_squared();
    if dd == 0.0 {
        return (point_segment_distance_squared(origin, seg) == 0.0).then_some(0.0);
    }
    // A hit only if the segment lies on the ray's line.
    if w.perp_dot(dir) != 0.0 {
        return None;
    }
    // Collinear: parameters of both ends along the ray.
    let ta = (seg.a - origin).dot(dir) / dd;
    let tb = (seg.b - origin).dot(dir) / dd;
    let (lo, hi) = if ta <= tb { (ta, tb) } else { (tb, ta) };
    if hi < 0.0 {
        None
    } else {
        Some(lo.max(0.0))
    }
}

/// Ray cast against a circle: the smallest `t >= 0` such that `origin + t * dir` lies on or
/// in the circle, or `None`. An origin inside the circle hits at t = 0.
pub fn ray_circle(origin: Vec2, dir: Vec2, centre: Vec2, radius: f64) -> Option<f64> {
    let m = origin - centre;
    let c = m.length_squared() - radius * radius;
    if c <= 0.0 {
        return Some(0.0);
    }
    let a = dir.length_squared();
    if a == 0.0 {
        return None;
    }
    let b = m.dot(dir);
    if b > 0.0 {
        // Outside and pointing away.
        return None;
    }
    // The discriminant b² − ac equals a r² − (m × dir)² (Lagrange's identity); this form
    // measures the ray's distance from the centre directly instead of cancelling two large
    // squares, so a ray passing just beside a small circle is not counted as a hit.
    let cross = m.perp_dot(dir);
    let disc = a * (radius * radius) - cross * cross;
    if disc < 0.0 {
        return None;
    }
    // The nearer root (-b - √disc)/a, written as c/(√disc - b) (the product of the roots is
    // c/a) so that it does not cancel when the origin is close to the circle. b < 0 here
    // (b = 0 would make disc = -ac < 0), so the denominator is positive.
    Some(c / (disc.sqrt() - b))
}

/// Does the segment touch the circle (share at least one point with the disc)?
#[inline]
pub fn segment_touches_circle(seg: &Segment, centre: Vec2, radius: f64) -> bool {
    circle_touches_segment(centre, radius, seg)
}

/// A segment with its bounding box, so that the sensor loops can reject far walls with
/// four inline comparisons before calling the exact intersection test (eq. 5–8 done once per
/// wall instead of once per query).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BoxedSegment {
    /// The segment.
    pub segment: Segment,
    /// Smallest x and y of its end points.
    pub lo: Vec2,
    /// Largest x and y of its end points.
    pub hi: Vec2,
}

impl BoxedSegment {
    /// `segment` with its box.
    pub fn new(segment: Segment) -> BoxedSegment {
        let (lo, hi) = segment.bounds();
        BoxedSegment { segment, lo, hi }
    }

    /// Can this wall meet anything inside the box `[lo, hi]`? False only when the boxes are
    /// disjoint (touching boxes may meet).
    #[inline]
    pub fn may_meet(&self, lo: Vec2, hi: Vec2) -> bool {
        !(self.hi.x < lo.x || hi.x < self.lo.x || self.hi.y < lo.y || hi.y < self.lo.y)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: f64, y: f64) -> Vec2 {
        Vec2::new(x, y)
    }
    fn seg(ax: f64, ay: f64, bx: f64, by: f64) -> Segment {
        Segment::new(v(ax, ay), v(bx, by))
    }

    #[test]
    fn eq1_touching_counts() {
        assert!(circles_touch(v(0.0, 0.0), 3.0, v(6.0, 0.0), 3.0));
        assert!(!circles_touch(v(0.0, 0.0), 3.0, v(6.000001, 0.0), 3.0));
        assert!(circles_touch(v(1.0, 1.0), 0.0, v(1.0, 1.0), 0.0));
    }

    #[test]
    fn eq4_false_contact_past_segment_end_is_fixed() {
        // On the infinite line of the segment, 2 LU past its end, radius 1: eq. 4 would say
        // contact (distance to the line is 0); the exact distance is 2 > 1.
        let s = seg(0.0, 0.0, 10.0, 0.0);
        assert!(!circle_touches_segment(v(12.0, 0.5), 1.0, &s));
        // Within the box of eq. 2–3 but past the end diagonally.
        assert!(!circle_touches_segment(v(10.9, 0.9), 1.0, &s));
        assert!(circle_touches_segment(v(10.6, 0.6), 1.0, &s));
        assert!(circle_touches_segment(v(5.0, 1.0), 1.0, &s)); // tangent
    }

    /// segments_intersect_past_box given side_of(s1, s0.b) answers as segments_intersect on
    /// every pair of segments with meeting boxes, whose ends come from a small set of coordinates (so that
    /// touching, collinear, zero-length and identical segments are common) with signed
    /// zeros, a coordinate within rounding of another, infinities and NaN.
    #[test]
    fn intersect_past_box_matches_intersect() {
        let coords = [
            0.0,
            -0.0,
            1.0,
            2.0,
            3.0,
            0.1 + 0.2,
            0.3,
            1e-300,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
        ];
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut pick = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            // Mostly finite small coordinates, now and then a special one.
            let k = (state >> 32) as usize;
            if k % 4 == 0 {
                coords[k / 4 % coords.len()]
            } else {
                coords[k % 7]
            }
        };
        let (mut met, mut touched) = (0, 0);
        for _ in 0..200_000 {
            let mut p = || v(pick(), pick());
            let (s0, s1) = (Segment::new(p(), p()), Segment::new(p(), p()));
            let o4 = side_of(&s1, s0.b);
            let answer = segments_intersect(&s0, &s1);
            if boxes_meet(&s0, &s1) {
                let past = segments_intersect_past_box(&s0, &s1, o4);
                assert_eq!(past, answer, "{s0:?} {s1:?}");
            } else {
                assert!(!answer, "{s0:?} {s1:?}");
            }
            met += usize::from(answer);
            touched += usize::from(answer && o4 == 0.0);
        }
        assert!(
            met > 10_000 && touched > 1_000,
            "{met} met, {touched} touching"
        );
    }

    #[test]
    fn ray_hits() {
        let s = seg(5.0, -1.0, 5.0, 1.0);
        assert_eq!(ray_segment(v(0.0, 0.0), v(1.0, 0.0), &s), Some(5.0));
        assert_eq!(ray_segment(v(0.0, 0.0), v(-1.0, 0.0), &s), None);
        let c = seg(2.0, 0.0, 4.0, 0.0);
        assert_eq!(ray_segment(v(0.0, 0.0), v(2.0, 0.0), &c), Some(1.0));
        assert_eq!(ray_segment(v(3.0, 0.0), v(1.0, 0.0), &c), Some(0.0));
        assert_eq!(
            ray_circle(v(0.0, 0.0), v(1.0, 0.0), v(10.0, 0.0), 2.0),
            Some(8.0)
        );
        assert_eq!(
            ray_circle(v(0.0, 0.0), v(1.0, 0.0), v(10.0, 3.0), 2.0),
            None
        );
    }
}
