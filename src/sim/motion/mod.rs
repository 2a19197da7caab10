//! Motion of a creature's body (report §8): differential drive (eq. 28–36) and admissible paths (§8.2).
//!
//! # One move
//!
//! 1. The motor signals L and R (rotations per tick) are clamped to `±max_rpt`; a NaN signal
//!    (a broken controller) counts as 0 so that the world state stays finite.
//! 2. [`drive`] turns them into wheel distances d_L, d_R (eq. 28–29), the turning angle φ
//!    (eq. 33) and the chord M from the start to the end of the circular arc (eq. 30).
//! 3. The heading is turned by φ/2 (eq. 32): the chord's direction. The planned end point is
//!    `start + M · chord direction` (eq. 31). M < 0 moves backwards.
//! 4. If the path start → end is admissible (§8.2, [`admissible`]) the body ends there and the
//!    heading is turned by another φ/2. Otherwise a fixed number of halvings (eq. 37) finds the
//!    last admissible point along the chord; the body ends there, having travelled d_I (eq. 38),
//!    and the *starting* heading is turned by φ' = d_I φ / |M| (eq. 34–35; `slippery_walls`:
//!    φ' = φ). Every rotation is followed by re-normalisation (eq. 36).
//! 5. Spinning in place (M = 0) needs no path test: a circular body occupies the same place.
//!
//! # A cheaper search, same results
//!
//! The planned path start → target is tested against every blocker given (most moves are
//! free and end there). Only a blocked move searches. Every path the search tests runs from
//! the start to a point in the box of start → target (a float midpoint of two points of a box
//! lies in the box), so the walls and bodies are first shortlisted: a blocker is left out only
//! when the very box and distance rejections that `wall_blocks` / `circle_blocks` begin with,
//! evaluated with the same float expressions, reject it for every path and end point within
//! that box. Left out, it could not have blocked any tested path (the target's included), so
//! no verdict, end point or cause changes. The few shortlisted blockers (at most 8 of each
//! kind) are then prepared once per search (their boxes, squared lengths, contact at the
//! start and on which sides of the wall's box the start lies), and each step repeats
//! `wall_blocks` / `circle_blocks` with the same float operations on those stored values.
//! Walls are still tested before bodies. A single wall and no body, a body pushing against a
//! wall, has its own loop. A box that is not finite or reaches beyond ±1e300 (where a
//! midpoint could overflow), or more than 8 candidates of a kind, falls back to the
//! shortlists (more than 32: every blocker); nothing is allocated.
//!
//! `wall_blocks` for a wall the body does not touch at the start is `crosses || touches at
//! the end`, two pure tests: the end test runs first, since it alone decides a body pushed
//! against the wall, which would otherwise repeat the path test on every step. sin(φ/2) is
//! computed once for the chord and the heading, and sin and cos of angles below 2⁻²⁶ (±0 for
//! a straight move or a blocked move that travelled 0, and the tiny turns of an almost
//! straight one) are not computed: libm returns x itself for the sine there, and exactly 1
//! for the cosine below 2⁻²⁷·√2 (above, `libm::cos` is called). The world clamps the motor
//! signals before it moves a body, so it calls [`plan_clamped_move`], which does not clamp
//! them again (clamping a clamped signal changes no bit when the bound is positive).
//! When sinc needs sin(φ/2) (|φ/2| ≥ 1e-4), sine and cosine come from one `libm::sincos`
//! call, which shares the argument reduction: for |x| ≥ 2⁻²⁶ it runs the very kernels
//! `libm::sin` and `libm::cos` run (`k_sin(x, 0, 0)` and `k_cos(x, 0)` up to π/4, else the
//! same `rem_pio2` and the same kernel and sign for each quadrant; x − x for ±∞ and NaN), so
//! the bits are theirs. (Only below 2⁻²⁶ do the three differ in their shortcut thresholds.)
//! For 2⁻²⁷·√2 ≤ |x| ≲ π/4 (almost every turn of one tick) those two kernels are copied here
//! with the same operations in the same order and inlined, sparing the call.
//! The tests compare all of this with [`reference`](mod@reference), the plain §8.2 move, bit for bit.
//!
//! The world moves a creature every tick: the free move is inlined into its caller
//! ([`plan_clamped_move`] is a wrapper), and a blocked move's search is a function of its own.
//!
//! # A body pushing against a wall
//!
//! The commonest search by far: a body resting just clear of one wall (where its last blocked
//! move left it) pushes into it again, every midpoint touches the wall and the search ends at
//! the start. That is proved once instead of testing all midpoints, and only when it is
//! certain; otherwise the search runs as usual. The midpoints the search tests, if each is
//! blocked, are m₁ = (s + t)·0.5 and mₖ = (s + mₖ₋₁)·0.5 up to mₙ, n = `search_steps`. The
//! shortcut is taken when the wall's float distance, computed as the search computes it, is
//! at most r − δ at m₁ (computed as the search does) and at pₙ = s + (t − s)·2⁻ⁿ (the power
//! of two exact, n ≤ 1000), with δ = 10⁻¹²·(1 + scale + r), scale being the largest
//! coordinate magnitude of s, t and the wall (at most 10¹⁰⁰, so nothing overflows; r > 2δ).
//! Every midpoint then touches:
//!
//! - The float distance of p is its distance to a computed point within 10ε·scale (ε = 2⁻⁵³)
//!   of a point a + (b − a)·t̂ of the wall (t̂ ∈ [0, 1]), with a few ε of relative rounding:
//!   the true distance D to the wall is at most r − δ + 20ε·(scale + r) at m₁ and pₙ.
//! - Each float midpoint mₖ, and pₙ, lies within 5ε·scale of the exact point eₖ = s +
//!   (t − s)/2ᵏ (mₖ: one rounded addition per halving, its error halved by the next; pₙ:
//!   two rounded operations), and e₂ … eₙ₋₁ lie on the segment from e₁ to eₙ. D is convex
//!   along a segment and 1-Lipschitz, so D ≤ r − δ + 30ε·(scale + r) at every midpoint.
//! - A point with D ≤ r − δ + 30ε·(scale + r) lies inside the wall's box grown by r as
//!   computed, and its float distance is within 60ε·(scale + r) of D (the projection t̂ errs
//!   by a few ε·|p − a|/|b − a|, the closest point by a few ε·scale), so the search finds it
//!   touching (at most r·r as computed): 90ε < 10⁻¹⁴ is far below δ.
//!
//! The proof needs only the wall's ends and whether the body touches it at the start, which
//! the first test of the move (over every blocker) has found already for the wall that
//! blocked it. So the proof is tried for that wall first, before any shortlist is built
//! (that wall always passes the shortlists' test, so every search would meet it): when it
//! holds, the move ends at the start, its heading turned by 0·φ. Otherwise, with one wall
//! listed and no body, the search reuses that contact and prepares the wall.
//!
//! A midpoint that touches blocks in the single-wall search whatever the path test would say,
//! with a wall as its verdict, so the result is the start and a wall, as the search gives.
//! With several walls and bodies (a corner) the same holds when one wall not touched at the
//! start is touched at every midpoint: walls are tested before bodies, so every verdict is
//! a wall, whichever wall answers first.
//!
//! # M near d_L = d_R
//!
//! eq. 30 divides by d_L − d_R. It is rewritten as M = (d_L + d_R)/2 · sinc(φ/2), with
//! sinc(x) = sin(x)/x, which is the same expression (since φ/2 = (d_L − d_R)/(2w)) without the
//! division. sinc is evaluated as `1 − x²/6` for |x| < 1e-4, where the dropped term x⁴/120 is
//! below 1e-18 (under half an ulp of 1), so M is continuous and exactly (d_L + d_R)/2 = d_L for
//! a straight move.
//!
//! # Starting inside a blocker
//!
//! Placement, teleports and doors closing on a creature can leave a body overlapping a blocker
//! at the start of a move. §8.2 alone would then reject every nearby end point and freeze the
//! creature. Instead each blocker is judged relative to the start:
//!
//! - A blocker the body does not touch at the start blocks as in §8.2.
//! - A blocking circle touched at the start blocks an end point that is closer to its centre
//!   than the start was (the body may move away or keep its distance, never go deeper).
//! - A wall touched at the start blocks an end point that is closer to the wall than the start
//!   was, and any path that touches the wall unless the start centre lies exactly on it (the
//!   centre may never pass to the wall's other side).
//!
//! A creature that starts clear of everything is judged by plain §8.2, so it always ends clear.
//!
//! # What §8.2 does not catch
//!
//! As in the report, bodies are tested only at the end point, and the body is tested only at
//! the end point: within one tick the body may sweep over a wall corner, and a creature moving
//! farther in one tick than the combined diameters can pass another body. Walls cannot be
//! crossed: the centre's path is tested against them exactly (see `geometry`).

use crate::geometry::{
    circle_touches_segment, circles_touch, point_segment_distance_squared, segments_intersect,
    Circle, Segment, Vec2,
};

pub mod reference;

/// Where a body is and which way it faces.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose {
    /// Centre of the body in LU.
    pub position: Vec2,
    /// Facing direction, unit length. Screen frame: (1, 0) faces right, (0, 1) faces down.
    pub heading: Vec2,
}

/// The mechanical constants of a body's motion.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MotionParams {
    /// Wheel diameter w in LU (report default: 2). It is also the report's axle length (eq. 33).
    pub wheel: f64,
    /// Largest motor signal magnitude in rotations per tick; L and R are clamped to ±max_rpt.
    pub max_rpt: f64,
    /// Number of halvings of the binary search of §8.2 (default: 20).
    pub search_steps: u32,
    /// §8.1 "slippery walls": a blocked move still turns by the full φ.
    pub slippery_walls: bool,
}

impl Default for MotionParams {
    /// The report's defaults: w = 2, at most 1 RPT, 20 halvings, sticky walls.
    fn default() -> Self {
        MotionParams {
            wheel: 2.0,
            max_rpt: 1.0,
            search_steps: 20,
            slippery_walls: false,
        }
    }
}

/// What can block a moving body. The caller leaves the mover's own body out of `circles`.
#[derive(Debug, Clone, Copy)]
pub struct Blockers<'a> {
    /// Walls and closed doors.
    pub segments: &'a [Segment],
    /// Other bodies: creatures, predators, irrelevant creatures.
    pub circles: &'a [Circle],
}

impl Blockers<'_> {
    /// Nothing blocks.
    pub const NONE: Blockers<'static> = Blockers {
        segments: &[],
        circles: &[],
    };
}

/// The result of [`plan_move`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MoveOutcome {
    /// Where the body ends and which way it faces.
    pub pose: Pose,
    /// d_I: distance actually travelled in LU (>= 0; eq. 38).
    pub travelled: f64,
    /// The planned path was not admissible and the move was cut short (or cancelled).
    pub blocked: bool,
    /// The cut was caused by a wall: a blocking segment rejected the tightest inadmissible
    /// candidate of the search.
    pub blocked_by_wall: bool,
}

/// Rotates `v` by `angle` radians with the standard rotation matrix (eq. 32, 35). In the screen
/// frame (y down) a positive angle turns clockwise on screen, towards the creature's right.
#[inline]
pub fn rotate(v: Vec2, angle: f64) -> Vec2 {
    let (s, c) = sin_cos(angle);
    rotate_sc(v, s, c)
}

/// `(libm::sin(x), libm::cos(x))`. From |x| = 2⁻²⁶ on, one `libm::sincos` call gives the
/// same bits (see the module docs). Below, the calls are not made: libm's `sin` returns x
/// itself for |x| < 2⁻²⁶ (its high word below 0x3e500000), and its `cos` returns exactly 1
/// for |x| < 2⁻²⁷·√2 (high word below 0x3e46a09e), so a straight move (x = ±0) and the
/// tiny turns of an almost straight one cost a comparison. NaN takes neither shortcut.
#[inline]
fn sin_cos(x: f64) -> (f64, f64) {
    let a = x.abs();
    if a >= SINCOS_FROM {
        sincos(x)
    } else if a < SINCOS_FROM {
        let high = (x.to_bits() >> 32) as u32 & 0x7fff_ffff;
        let cos = if high < COS_ONE_BELOW {
            1.0
        } else {
            libm::cos(x)
        };
        (x, cos)
    } else {
        (libm::sin(x), libm::cos(x))
    }
}

/// `libm::sincos(x)`, the same bits: for 2⁻²⁷·√2 ≤ |x| ≲ π/4 (libm's high-word tests, which
/// hold for nearly every turn of one tick) libm returns `(k_sin(x, 0, 0), k_cos(x, 0))`, and
/// these are its kernels ([`k_sin0`], [`k_cos0`]), copied with the same float operations in
/// the same order, inlined here to spare the call; other arguments go to libm.
#[inline(always)]
fn sincos(x: f64) -> (f64, f64) {
    let high = (x.to_bits() >> 32) as u32 & 0x7fff_ffff;
    if (COS_ONE_BELOW..=PIO4_HIGH).contains(&high) {
        (k_sin0(x), k_cos0(x))
    } else {
        libm::sincos(x)
    }
}

/// The high word (sign cleared) up to which libm's sincos takes |x| as at most π/4.
const PIO4_HIGH: u32 = 0x3fe9_21fb;

// k_sin0 and k_cos0 are libm 0.2.16's k_sin(x, 0.0, 0) and k_cos(x, 0.0), from FreeBSD's
// /usr/src/lib/msun/src/k_sin.c and k_cos.c, under this notice:
//
// Copyright (C) 1993 by Sun Microsystems, Inc. All rights reserved.
//
// Developed at SunPro, a Sun Microsystems, Inc. business.
// Permission to use, copy, modify, and distribute this
// software is freely granted, provided that this notice
// is preserved.

/// libm's `k_sin(x, 0.0, 0)`: the sine on [-π/4, π/4].
#[inline(always)]
fn k_sin0(x: f64) -> f64 {
    const S1: f64 = f64::from_bits(0xBFC55555_55555549); // -1.66666666666666324348e-1
    const S2: f64 = f64::from_bits(0x3F811111_1110F8A6); // 8.33333333332248946124e-3
    const S3: f64 = f64::from_bits(0xBF2A01A0_19C161D5); // -1.98412698298579493134e-4
    const S4: f64 = f64::from_bits(0x3EC71DE3_57B1FE7D); // 2.75573137070700676789e-6
    const S5: f64 = f64::from_bits(0xBE5AE5E6_8A2B9CEB); // -2.50507602534068634195e-8
    const S6: f64 = f64::from_bits(0x3DE5D93A_5ACFD57C); // 1.58969099521155010221e-10
    let z = x * x;
    let w = z * z;
    let r = S2 + z * (S3 + z * S4) + z * w * (S5 + z * S6);
    let v = z * x;
    x + v * (S1 + z * r)
}

/// libm's `k_cos(x, 0.0)`: the cosine on [-π/4, π/4].
#[inline(always)]
fn k_cos0(x: f64) -> f64 {
    const C1: f64 = f64::from_bits(0x3FA55555_5555554C); // 4.16666666666666019037e-2
    const C2: f64 = f64::from_bits(0xBF56C16C_16C15177); // -1.38888888888741095749e-3
    const C3: f64 = f64::from_bits(0x3EFA01A0_19CB1590); // 2.48015872894767294178e-5
    const C4: f64 = f64::from_bits(0xBE927E4F_809C52AD); // -2.75573143513906633035e-7
    const C5: f64 = f64::from_bits(0x3E21EE9E_BDB4B1C4); // 2.08757232129817482790e-9
    const C6: f64 = f64::from_bits(0xBDA8FAE9_BE8838D4); // -1.13596475577881948265e-11
    let z = x * x;
    let w = z * z;
    let r = z * (C1 + z * (C2 + z * C3)) + w * w * (C4 + z * (C5 + z * C6));
    let hz = 0.5 * z;
    let w = 1.0 - hz;
    // libm subtracts x·y with the tail y = 0: ±0, which leaves z·r as it is unless z·r is
    // -0. Here 2⁻²⁷·√2 ≤ |x| ≤ π/4, so z ≥ 2⁻⁵³ and r ≈ C1·z are positive normal numbers,
    // and so is z·r: the term is left out (LLVM, keeping IEEE semantics, cannot).
    w + (((1.0 - w) - hz) + z * r)
}

/// 2⁻²⁶: from here on `libm::sincos` and `libm::sin`, `libm::cos` run the same code, and
/// below it `libm::sin(x)` is x.
const SINCOS_FROM: f64 = 1.0 / 67_108_864.0;

/// The high word (sign cleared) of 2⁻²⁷·√2, below which `libm::cos` returns 1.
const COS_ONE_BELOW: u32 = 0x3e46_a09e;

/// Rotation by an angle given by its sine and cosine.
#[inline]
fn rotate_sc(v: Vec2, sin: f64, cos: f64) -> Vec2 {
    Vec2::new(v.x * cos - v.y * sin, v.x * sin + v.y * cos)
}

/// eq. 36: scale to unit length. The zero vector stays zero (no NaN).
#[inline]
fn normalise(v: Vec2) -> Vec2 {
    let len = v.length();
    if len > 0.0 {
        v / len
    } else {
        unscaled(v)
    }
}

/// `normalise` of a vector of length 0 (or NaN): itself. Out of line and cold, so that the
/// length test stays a branch, which never misses on a heading, instead of a select that
/// costs a mask built from the comparison on every rotation.
#[cold]
#[inline(never)]
fn unscaled(v: Vec2) -> Vec2 {
    v
}

/// sin(x)/x, continuous through 0 (see the module docs), and libm's sin(x) and cos(x) when sin
/// was computed. `libm::sincos` gives the bits of `libm::sin` and `libm::cos` for |x| ≥ 2⁻²⁶
/// (see the module docs), and sin is computed only for |x| ≥ 1e-4.
#[inline]
fn sinc(x: f64) -> (f64, Option<(f64, f64)>) {
    if x.abs() < 1e-4 {
        (1.0 - x * x / 6.0, None)
    } else {
        let (sin, cos) = sincos(x);
        (sin / x, Some((sin, cos)))
    }
}

/// The wheel distances, turning angle and chord of one tick's motor signals (§8.1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Drive {
    /// eq. 28: distance travelled by the left wheel, d_L = 2πwL (LU).
    pub d_left: f64,
    /// eq. 29: distance travelled by the right wheel, d_R = 2πwR (LU).
    pub d_right: f64,
    /// eq. 33: turning angle φ = (d_L − d_R)/w (radians; positive turns right).
    pub phi: f64,
    /// eq. 30: the signed chord M from start to end position (LU; negative = backwards).
    pub chord: f64,
}

/// eq. 28–30 and 33 for wheel diameter `wheel` and motor signals (already clamped) in RPT.
/// A wheel of diameter 0 does not move or turn.
pub fn drive(wheel: f64, left_rpt: f64, right_rpt: f64) -> Drive {
    drive_and_sin(wheel, left_rpt, right_rpt).0
}

/// [`drive`], and libm's sin(φ/2) and cos(φ/2) when the chord needed the sine (`plan_move`
/// needs both).
#[inline]
fn drive_and_sin(wheel: f64, left_rpt: f64, right_rpt: f64) -> (Drive, Option<(f64, f64)>) {
    let d_left = std::f64::consts::TAU * wheel * left_rpt;
    let d_right = std::f64::consts::TAU * wheel * right_rpt;
    if wheel == 0.0 {
        let d = Drive {
            d_left,
            d_right,
            phi: 0.0,
            chord: 0.0,
        };
        return (d, None);
    }
    let phi = (d_left - d_right) / wheel;
    // eq. 30 with the division folded into sinc: w·sin(δ/2w)/δ = sinc(φ/2)/2.
    let (sinc_half, sin_half) = sinc(0.5 * phi);
    let chord = 0.5 * (d_left + d_right) * sinc_half;
    let d = Drive {
        d_left,
        d_right,
        phi,
        chord,
    };
    (d, sin_half)
}

/// Clamp a motor signal to ±max; NaN counts as 0.
#[inline]
pub(crate) fn clamp_rpt(x: f64, max: f64) -> f64 {
    if x.is_nan() {
        0.0
    } else {
        let m = max.abs();
        x.min(m).max(-m)
    }
}

/// Why a path is not admissible (or that it is).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Verdict {
    Free,
    Wall,
    Body,
}

/// Does `wall` block the path p0 → p1 of a body of radius `r`? (See the module docs for the
/// rule when the body touches the wall at p0.)
#[inline]
fn wall_blocks(
    p0: Vec2,
    p1: Vec2,
    path: &Segment,
    path_box: (Vec2, Vec2),
    r: f64,
    wall: &Segment,
) -> bool {
    wall_block(p0, p1, path, path_box, r, wall).is_some()
}

/// [`wall_blocks`], and when the wall blocks, whether the body touches it at p0
/// (`circle_touches_segment(p0, r, wall)`, which the test computes anyway): `None` when it
/// does not block. Inlined: the first test of every move runs it over the walls near the
/// start, and a call would store the path and its box for each wall.
#[inline(always)]
fn wall_block(
    p0: Vec2,
    p1: Vec2,
    path: &Segment,
    path_box: (Vec2, Vec2),
    r: f64,
    wall: &Segment,
) -> Option<bool> {
    let (lo, hi) = wall.bounds();
    let (plo, phh) = path_box;
    // The same box rejections segments_intersect (eq. 5–8) and circle_touches_segment
    // (eq. 2–3) start with, combined: most walls are far away. Pure comparisons, so they are
    // all evaluated (`|`, `&`) without a branch each: which side a wall lies on is not
    // predictable.
    let path_misses = (phh.x < lo.x) | (hi.x < plo.x) | (phh.y < lo.y) | (hi.y < plo.y);
    let end_misses = (p1.x < lo.x - r) | (p1.x > hi.x + r) | (p1.y < lo.y - r) | (p1.y > hi.y + r);
    if path_misses & end_misses {
        return None;
    }
    let touching = circle_touches_segment(p0, r, wall);
    if !touching {
        // Plain §8.2: `crosses || touches at p1`, both pure; the cheaper end test first.
        let blocks = circle_touches_segment(p1, r, wall) || segments_intersect(path, wall);
        return blocks.then_some(false);
    }
    let crosses = segments_intersect(path, wall);
    if !crosses && !circle_touches_segment(p1, r, wall) {
        return None;
    }
    // Already touching at the start: no deeper, and never through.
    let d0 = point_segment_distance_squared(p0, wall);
    let d1 = point_segment_distance_squared(p1, wall);
    (d1 < d0 || (crosses && d0 > 0.0)).then_some(true)
}

/// Does `body` block a body of radius `r` moving p0 → p1?
#[inline]
fn circle_blocks(p0: Vec2, p1: Vec2, r: f64, body: &Circle) -> bool {
    if !circles_touch(p1, r, body.centre, body.radius) {
        return false;
    }
    if !circles_touch(p0, r, body.centre, body.radius) {
        return true;
    }
    // Already touching at the start: may not come closer.
    p1.distance_squared(body.centre) < p0.distance_squared(body.centre)
}

/// §8.2 with walls tested first, so a path blocked by both reports a wall.
#[inline]
fn verdict(p0: Vec2, p1: Vec2, radius: f64, blockers: &Blockers) -> Verdict {
    verdict_over(
        p0,
        p1,
        radius,
        blockers.segments.iter(),
        blockers.circles.iter(),
    )
}

/// [`verdict`] over every blocker, and for a wall verdict, which wall answered (its index
/// in `blockers.segments`) and whether the body touches it at p0: the first test of a move,
/// whose search can then skip that wall's start test. Inlined into the move: called, it
/// would set up a frame and take the blockers and its answer through memory.
#[inline(always)]
fn first_verdict(
    p0: Vec2,
    p1: Vec2,
    radius: f64,
    blockers: &Blockers,
) -> (Verdict, Option<FirstWall>) {
    let path = Segment::new(p0, p1);
    let path_box = path.bounds();
    for (index, w) in blockers.segments.iter().enumerate() {
        if let Some(touching) = wall_block(p0, p1, &path, path_box, radius, w) {
            return (Verdict::Wall, Some(FirstWall { index, touching }));
        }
    }
    if blockers
        .circles
        .iter()
        .any(|c| circle_blocks(p0, p1, radius, c))
    {
        return (Verdict::Body, None);
    }
    (Verdict::Free, None)
}

/// The wall that blocked a move's planned path (see [`first_verdict`]).
#[derive(Clone, Copy)]
struct FirstWall {
    /// Its index in `Blockers::segments`.
    index: usize,
    /// `circle_touches_segment(start, r, wall)`.
    touching: bool,
}

/// [`verdict`] over the given walls and bodies (all of them, or a shortlist).
#[inline]
fn verdict_over<'w, 'c>(
    p0: Vec2,
    p1: Vec2,
    radius: f64,
    mut walls: impl Iterator<Item = &'w Segment>,
    mut circles: impl Iterator<Item = &'c Circle>,
) -> Verdict {
    let path = Segment::new(p0, p1);
    let path_box = path.bounds();
    if walls.any(|w| wall_blocks(p0, p1, &path, path_box, radius, w)) {
        return Verdict::Wall;
    }
    if circles.any(|c| circle_blocks(p0, p1, radius, c)) {
        return Verdict::Body;
    }
    Verdict::Free
}

/// Most blockers a [`Shortlist`] holds; with more candidates the full list is used.
const SHORTLIST_LEN: usize = 32;

/// The blockers of one kind that may block some path of one move's search (see
/// [`plan_move`]): their indices into `all` in the original order, or all of them when there
/// are more than [`SHORTLIST_LEN`] (or the move's box is not safe to reason about). Lives on
/// the stack: `plan_move` does not allocate.
struct Shortlist<'a, T> {
    all: &'a [T],
    index: [u32; SHORTLIST_LEN],
    /// `None`: use `all`.
    len: Option<usize>,
}

impl<'a, T> Shortlist<'a, T> {
    /// Every item of `all` for which `may_block` holds (or all of them, see above).
    #[inline]
    fn new(all: &'a [T], use_all: bool, may_block: impl Fn(&T) -> bool) -> Self {
        let mut list = Shortlist {
            all,
            index: [0; SHORTLIST_LEN],
            len: None,
        };
        if use_all || all.len() > u32::MAX as usize {
            return list;
        }
        let mut len = 0;
        for (i, item) in all.iter().enumerate() {
            if may_block(item) {
                if len == SHORTLIST_LEN {
                    return list;
                }
                list.index[len] = i as u32;
                len += 1;
            }
        }
        list.len = Some(len);
        list
    }

    /// The listed items in their original order.
    #[inline]
    fn iter(&self) -> ShortlistIter<'_, 'a, T> {
        match self.len {
            Some(n) => ShortlistIter::Listed(self.all, self.index[..n].iter()),
            None => ShortlistIter::All(self.all.iter()),
        }
    }
}

/// Iterator over a [`Shortlist`].
enum ShortlistIter<'s, 'a, T> {
    Listed(&'a [T], std::slice::Iter<'s, u32>),
    All(std::slice::Iter<'a, T>),
}

impl<'a, T> Iterator for ShortlistIter<'_, 'a, T> {
    type Item = &'a T;

    #[inline]
    fn next(&mut self) -> Option<&'a T> {
        match self {
            ShortlistIter::Listed(all, idx) => idx.next().map(|&i| &all[i as usize]),
            ShortlistIter::All(it) => it.next(),
        }
    }
}

/// Can `wall` block any path p0 → p1 of a body of radius `r` whose box and end point p1 lie
/// in the box (`lo`, `hi`)? `false` only when [`wall_blocks`]'s own first rejection holds for
/// every such path: its box misses the wall's box (the path box lies inside (`lo`, `hi`)) and
/// p1 is outside the wall's box grown by `r`, compared with the same float expressions.
#[inline]
fn wall_may_block(lo: Vec2, hi: Vec2, r: f64, wall: &Segment) -> bool {
    let (wlo, whi) = wall.bounds();
    let end_misses = hi.x < wlo.x - r || lo.x > whi.x + r || hi.y < wlo.y - r || lo.y > whi.y + r;
    if !end_misses {
        return true;
    }
    // For r >= 0 the grown box contains the wall's box (wlo.x - r <= wlo.x in floats too), so
    // `end_misses` already implies that the box misses.
    let box_misses = r >= 0.0 || hi.x < wlo.x || whi.x < lo.x || hi.y < wlo.y || whi.y < lo.y;
    !box_misses
}

/// Can `body` block a body of radius `r` ending anywhere in the box (`lo`, `hi`)? `false` only
/// when the body at the box's point nearest to the centre does not touch it: every float step
/// of [`circles_touch`] (difference, square, sum) is monotone in the coordinate distances, so
/// no point of the box is computed closer than that one.
#[inline]
fn circle_may_block(lo: Vec2, hi: Vec2, r: f64, body: &Circle) -> bool {
    let nearest = Vec2::new(
        body.centre.x.max(lo.x).min(hi.x),
        body.centre.y.max(lo.y).min(hi.y),
    );
    circles_touch(nearest, r, body.centre, body.radius)
}

/// Most walls, and separately most bodies, the search prepares (see [`PreparedWall`]); with
/// more candidates it tests the shortlists.
const PREPARED_LEN: usize = 8;

/// A shortlisted wall with what [`wall_blocks`] computes the same way on every step of one
/// move's search: its box, the box grown by the body radius, its direction and squared
/// length, and how the body touches it at the start. [`PreparedWall::blocks`] repeats
/// `wall_blocks` with the same float operations on the same values, so it gives the same
/// answer.
#[derive(Clone, Copy)]
struct PreparedWall {
    wall: Segment,
    lo: Vec2,
    hi: Vec2,
    /// `lo - r`, `hi + r`: the box of eq. 2–3 in `circle_touches_segment`.
    grown_lo: Vec2,
    grown_hi: Vec2,
    ab: Vec2,
    len2: f64,
    /// `circle_touches_segment(start, r, wall)`.
    touching: bool,
    /// `point_segment_distance_squared(start, wall)` when `touching` (else unused).
    d0: f64,
    /// Where the start lies against the box: `start.x < lo.x`, `hi.x < start.x`,
    /// `start.y < lo.y`, `hi.y < start.y`. The box of start → p1 misses the wall's box on a
    /// side exactly when the start and p1 both lie beyond it (max(s, p) < l ⟺ s < l ∧ p < l
    /// for numbers), so each step compares p1 alone.
    start_lo_x: bool,
    start_hi_x: bool,
    start_lo_y: bool,
    start_hi_y: bool,
}

impl PreparedWall {
    const EMPTY: PreparedWall = PreparedWall {
        wall: Segment::new(Vec2::ZERO, Vec2::ZERO),
        lo: Vec2::ZERO,
        hi: Vec2::ZERO,
        grown_lo: Vec2::ZERO,
        grown_hi: Vec2::ZERO,
        ab: Vec2::ZERO,
        len2: 0.0,
        touching: false,
        d0: 0.0,
        start_lo_x: false,
        start_hi_x: false,
        start_lo_y: false,
        start_hi_y: false,
    };

    #[inline]
    fn new(wall: &Segment, start: Vec2, r: f64) -> Self {
        let (lo, hi) = wall.bounds();
        let ab = wall.b - wall.a;
        let touching = circle_touches_segment(start, r, wall);
        PreparedWall {
            wall: *wall,
            lo,
            hi,
            grown_lo: Vec2::new(lo.x - r, lo.y - r),
            grown_hi: Vec2::new(hi.x + r, hi.y + r),
            ab,
            len2: ab.length_squared(),
            touching,
            d0: if touching {
                point_segment_distance_squared(start, wall)
            } else {
                0.0
            },
            start_lo_x: start.x < lo.x,
            start_hi_x: hi.x < start.x,
            start_lo_y: start.y < lo.y,
            start_hi_y: hi.y < start.y,
        }
    }

    /// `point_segment_distance_squared(p, wall)`, step by step.
    #[inline(always)]
    fn distance_squared(&self, p: Vec2) -> f64 {
        wall_distance_squared(self.wall.a, self.ab, self.len2, p)
    }

    /// [`every_midpoint_touches`] for this wall.
    #[inline]
    fn every_midpoint_touches(&self, start: Vec2, target: Vec2, r: f64, steps: u32) -> bool {
        every_midpoint_touches(&self.wall, start, target, r, steps)
    }

    /// `wall_blocks`'s box rejection of the path start → p1 (see `start_lo_x`).
    #[inline(always)]
    fn path_misses(&self, p1: Vec2) -> bool {
        (self.start_lo_x && p1.x < self.lo.x)
            || (self.start_hi_x && self.hi.x < p1.x)
            || (self.start_lo_y && p1.y < self.lo.y)
            || (self.start_hi_y && self.hi.y < p1.y)
    }

    /// `wall_blocks(start, p1, start → p1, its box, r, wall)` for the `start` the wall was
    /// prepared with (p1 finite), where `r2` is `r * r`.
    #[inline(always)]
    fn blocks(&self, start: Vec2, p1: Vec2, r2: f64) -> bool {
        if !self.touching {
            // Then `wall_blocks` is `crosses || touches_end`, both pure: the end test first,
            // which decides a body pushing against the wall without the path test.
            let end_misses = (p1.x < self.grown_lo.x)
                | (p1.x > self.grown_hi.x)
                | (p1.y < self.grown_lo.y)
                | (p1.y > self.grown_hi.y);
            if !end_misses && self.distance_squared(p1) <= r2 {
                return true;
            }
            return !self.path_misses(p1)
                && segments_intersect(&Segment::new(start, p1), &self.wall);
        }
        let path_misses = self.path_misses(p1);
        // segments_intersect begins with exactly the `path_misses` rejection (eq. 5–8), and
        // circle_touches_segment with the `end_misses` one (eq. 2–3); `wall_blocks` returns
        // false when both hold, which the two tests below do too.
        let crosses = !path_misses && segments_intersect(&Segment::new(start, p1), &self.wall);
        let mut d1 = f64::NAN;
        if !crosses {
            let end_misses = p1.x < self.grown_lo.x
                || p1.x > self.grown_hi.x
                || p1.y < self.grown_lo.y
                || p1.y > self.grown_hi.y;
            if end_misses {
                return false;
            }
            d1 = self.distance_squared(p1);
            let touches_end = d1 <= r2;
            if !touches_end {
                return false;
            }
        }
        if !self.touching {
            return true;
        }
        if crosses {
            d1 = self.distance_squared(p1);
        }
        d1 < self.d0 || (crosses && self.d0 > 0.0)
    }
}

/// `point_segment_distance_squared(p, wall)`, step by step, for the wall from `a` with
/// `ab = b - a` and `len2 = ab.length_squared()`.
#[inline(always)]
fn wall_distance_squared(a: Vec2, ab: Vec2, len2: f64, p: Vec2) -> f64 {
    let closest = if len2 == 0.0 {
        a
    } else {
        let t = ((p - a).dot(ab) / len2).clamp(0.0, 1.0);
        a + ab * t
    };
    p.distance_squared(closest)
}

/// Larger of two numbers that are not NaN: one `maxsd`, without `f64::max`'s NaN handling.
#[inline(always)]
fn max_number(x: f64, y: f64) -> f64 {
    if x > y {
        x
    } else {
        y
    }
}

/// Does a body of radius `r` touch `wall` at every midpoint the search of start → target
/// tests when each one is blocked (`(start + target) * 0.5`, then `(start + previous) * 0.5`,
/// `steps` of them)? `true` only when it is certain: see "A body pushing against a wall" in
/// the module docs for the argument and its margins. For a wall the body does not touch at
/// the start, a `true` means `PreparedWall::blocks` holds for every one of those midpoints,
/// so the search would end at the start. `start` and `target` must be finite (the search's
/// box lies within ±1e300); a wall that is not is refused.
#[inline]
fn every_midpoint_touches(wall: &Segment, start: Vec2, target: Vec2, r: f64, steps: u32) -> bool {
    debug_assert!(start.is_finite() && target.is_finite());
    let (a, b) = (wall.a, wall.b);
    // The largest coordinate magnitude. The coordinates of a finite wall and of the finite
    // start and target are numbers, so the plain maximum is exact. An infinite wall
    // coordinate makes it ∞ (or NaN), which fails `scale <= 1e100` below; a NaN one, if the
    // maximum drops it, makes both distances below NaN, which fails their comparisons.
    let scale = max_number(
        max_number(
            max_number(start.x.abs(), start.y.abs()),
            max_number(target.x.abs(), target.y.abs()),
        ),
        max_number(
            max_number(a.x.abs(), a.y.abs()),
            max_number(b.x.abs(), b.y.abs()),
        ),
    );
    let ab = b - a;
    let len2 = ab.length_squared();
    // Far above every rounding error of the argument (each below 100 ε (scale + r)).
    let margin = 1e-12 * (1.0 + scale + r);
    // Keeps every square below overflow and the margin meaningful, and 2^-steps a
    // normal float; NaN fails too.
    if !(scale <= 1e100 && r <= 1e100 && r > 2.0 * margin && steps <= 1000) {
        return false;
    }
    let reach = r - margin;
    let reach2 = reach * reach;
    let first = (start + target) * 0.5;
    // The first, then (only when it touches) a point within rounding of the last:
    // start + (target − start)·2^-steps, the power of two built exactly. NaN fails both.
    wall_distance_squared(a, ab, len2, first) <= reach2 && {
        let last_scale = f64::from_bits((1023 - u64::from(steps)) << 52);
        let last = start + (target - start) * last_scale;
        wall_distance_squared(a, ab, len2, last) <= reach2
    }
}

/// A shortlisted body with what [`circle_blocks`] computes the same way on every step.
#[derive(Clone, Copy)]
struct PreparedCircle {
    centre: Vec2,
    /// `(r + radius)²` as `circles_touch` computes it.
    reach2: f64,
    /// `circles_touch(start, r, centre, radius)`.
    touching: bool,
    /// `start.distance_squared(centre)`.
    d0: f64,
}

impl PreparedCircle {
    const EMPTY: PreparedCircle = PreparedCircle {
        centre: Vec2::ZERO,
        reach2: 0.0,
        touching: false,
        d0: 0.0,
    };

    #[inline]
    fn new(body: &Circle, start: Vec2, r: f64) -> Self {
        let reach = r + body.radius;
        PreparedCircle {
            centre: body.centre,
            reach2: reach * reach,
            touching: circles_touch(start, r, body.centre, body.radius),
            d0: start.distance_squared(body.centre),
        }
    }

    /// `circle_blocks(start, p1, r, body)` for the start the body was prepared with.
    #[inline]
    fn blocks(&self, p1: Vec2) -> bool {
        let d1 = p1.distance_squared(self.centre);
        let touches_end = d1 <= self.reach2;
        touches_end && (!self.touching || d1 < self.d0)
    }
}

/// The binary search of eq. 37 from `start` towards `target`, always testing the path from the
/// start, so the end point is one that was itself tested admissible (or the start). `test`
/// judges the path start → p1 and `cause` is the verdict of start → target. Returns the end
/// point and the verdict of the tightest inadmissible candidate.
#[inline]
fn search(
    start: Vec2,
    target: Vec2,
    steps: u32,
    mut cause: Verdict,
    mut test: impl FnMut(Vec2) -> Verdict,
) -> (Vec2, Verdict) {
    let mut lo = start;
    let mut hi = target;
    for _ in 0..steps {
        let mid = (lo + hi) * 0.5;
        match test(mid) {
            Verdict::Free => lo = mid,
            v => {
                hi = mid;
                cause = v;
            }
        }
    }
    (lo, cause)
}

/// The search of [`plan_move`] over prepared shortlists: the walls and bodies that may block
/// a path within the box (`lo`, `hi`) of start → target (finite, within ±1e300), prepared
/// for `start`. `None` (nothing searched) when there are more than [`PREPARED_LEN`] of a kind.
#[allow(clippy::too_many_arguments)]
#[inline]
fn prepared_search(
    start: Vec2,
    target: Vec2,
    radius: f64,
    lo: Vec2,
    hi: Vec2,
    steps: u32,
    cause: Verdict,
    first_wall: Option<FirstWall>,
    blockers: &Blockers,
) -> Option<(Vec2, Verdict)> {
    let r2 = radius * radius;
    // The common search, a body pushing against one wall: a loop over that wall alone.
    let mut near = blockers
        .segments
        .iter()
        .enumerate()
        .filter(|(_, w)| wall_may_block(lo, hi, radius, w));
    if let (Some((index, only)), None) = (near.next(), near.next()) {
        if !blockers
            .circles
            .iter()
            .any(|c| circle_may_block(lo, hi, radius, c))
        {
            // The first test already found whether the body touches the wall that blocked
            // the planned path (with one wall listed and no body, that is this wall).
            let touching = match first_wall {
                Some(f) if f.index == index => f.touching,
                _ => circle_touches_segment(start, radius, only),
            };
            if steps > 0 && !touching && every_midpoint_touches(only, start, target, radius, steps)
            {
                // Every midpoint blocked: `search` would end at the start, each midpoint's
                // verdict a wall. The wall needs no further preparation.
                return Some((start, Verdict::Wall));
            }
            let w = PreparedWall::new(only, start, radius);
            return Some(search(start, target, steps, cause, |p1| {
                if w.blocks(start, p1, r2) {
                    Verdict::Wall
                } else {
                    Verdict::Free
                }
            }));
        }
    }
    prepared_search_many(start, target, radius, lo, hi, steps, cause, blockers)
}

/// [`prepared_search`] with several walls or bodies (a corner, a crowd): its own function,
/// so that the common single-wall search does not set up these arrays.
#[allow(clippy::too_many_arguments)]
#[inline(never)]
fn prepared_search_many(
    start: Vec2,
    target: Vec2,
    radius: f64,
    lo: Vec2,
    hi: Vec2,
    steps: u32,
    cause: Verdict,
    blockers: &Blockers,
) -> Option<(Vec2, Verdict)> {
    let r2 = radius * radius;
    let mut pw = [PreparedWall::EMPTY; PREPARED_LEN];
    let mut nw = 0;
    for w in blockers.segments {
        if wall_may_block(lo, hi, radius, w) {
            if nw == PREPARED_LEN {
                return None;
            }
            pw[nw] = PreparedWall::new(w, start, radius);
            nw += 1;
        }
    }
    let mut pc = [PreparedCircle::EMPTY; PREPARED_LEN];
    let mut nc = 0;
    for c in blockers.circles {
        if circle_may_block(lo, hi, radius, c) {
            if nc == PREPARED_LEN {
                return None;
            }
            pc[nc] = PreparedCircle::new(c, start, radius);
            nc += 1;
        }
    }
    let (pw, pc) = (&pw[..nw], &pc[..nc]);
    // A body pushing into a corner: one wall every midpoint touches blocks them all (walls
    // are tested first, so each verdict is a wall whichever wall answers first).
    if steps > 0
        && pw
            .iter()
            .any(|w| !w.touching && w.every_midpoint_touches(start, target, radius, steps))
    {
        return Some((start, Verdict::Wall));
    }
    Some(search(start, target, steps, cause, |p1| {
        if pw.iter().any(|w| w.blocks(start, p1, r2)) {
            Verdict::Wall
        } else if pc.iter().any(|c| c.blocks(p1)) {
            Verdict::Body
        } else {
            Verdict::Free
        }
    }))
}

/// §8.2: may a body of `radius` move along the straight path `p0 → p1`? Yes when the segment
/// p0 → p1 touches no blocking segment and the body placed at p1 touches no blocking segment
/// or circle (contact inclusive). Blockers the body already touches at `p0` follow the
/// no-deeper rule of the module docs; for a body that starts clear this is exactly §8.2.
pub fn admissible(p0: Vec2, p1: Vec2, radius: f64, blockers: &Blockers) -> bool {
    verdict(p0, p1, radius, blockers) == Verdict::Free
}

/// One tick of motion (§8.1–8.2) for a body of `radius` at `pose` with motor signals
/// `left_rpt`, `right_rpt` (clamped here to ±`params.max_rpt`). Pure: the caller applies the
/// outcome. Does not allocate.
#[inline]
pub fn plan_move(
    pose: Pose,
    left_rpt: f64,
    right_rpt: f64,
    radius: f64,
    params: &MotionParams,
    blockers: &Blockers,
) -> MoveOutcome {
    let left = clamp_rpt(left_rpt, params.max_rpt);
    let right = clamp_rpt(right_rpt, params.max_rpt);
    plan_clamped_move(pose, left, right, radius, params, blockers)
}

/// [`plan_move`] for motor signals a caller has clamped already: `left` and `right` not NaN
/// and within ±`params.max_rpt`, with `max_rpt` > 0. Clamping them again would change no
/// bit (the minimum of a number and a bound above it is the number, and so is the maximum
/// with a bound below it; the bounds being nonzero, a signed zero meets no equal bound), so
/// the world, which clamps every command it records, skips the second clamping here.
pub fn plan_clamped_move(
    pose: Pose,
    left: f64,
    right: f64,
    radius: f64,
    params: &MotionParams,
    blockers: &Blockers,
) -> MoveOutcome {
    plan_clamped_move_inline(pose, left, right, radius, params, blockers)
}

/// [`plan_clamped_move`], inlined into its caller: the world moves a creature every tick, and
/// most moves are free, so the free move is computed in the caller's registers (no call, no
/// outcome through memory) while a blocked move's search stays out of line
/// ([`blocked_move`]).
#[inline(always)]
pub(crate) fn plan_clamped_move_inline(
    pose: Pose,
    left: f64,
    right: f64,
    radius: f64,
    params: &MotionParams,
    blockers: &Blockers,
) -> MoveOutcome {
    let stay = MoveOutcome {
        pose,
        travelled: 0.0,
        blocked: false,
        blocked_by_wall: false,
    };
    let (d, sin_half) = drive_and_sin(params.wheel, left, right);
    if !d.phi.is_finite() || !d.chord.is_finite() {
        // Only a non-finite wheel gets here; keep the world finite.
        return stay;
    }
    // eq. 32 twice, with the half angle's sine and cosine computed once.
    let half = 0.5 * d.phi;
    // sinc computed libm's sine and cosine of the same 0.5 * φ (unless it was tiny).
    let (s, c) = match sin_half {
        Some(sc) => sc,
        None => sin_cos(half),
    };
    let chord_dir = normalise(rotate_sc(pose.heading, s, c));
    let free_heading = normalise(rotate_sc(chord_dir, s, c));
    let start = pose.position;
    if d.chord == 0.0 {
        // Spinning in place (or standing still): the body covers the same disc.
        return MoveOutcome {
            pose: Pose {
                position: start,
                heading: free_heading,
            },
            ..stay
        };
    }
    // eq. 31.
    let target = start + chord_dir * d.chord;
    let free = MoveOutcome {
        pose: Pose {
            position: target,
            heading: free_heading,
        },
        travelled: d.chord.abs(),
        ..stay
    };
    // Nothing listed near the start (the commonest move): free, as the first test would find,
    // without setting up its path and box.
    if blockers.segments.is_empty() && blockers.circles.is_empty() {
        return free;
    }
    // The first test goes over every blocker given: the shortlists below would give the same
    // verdict (they leave out only blockers that cannot block any path of the search), and
    // most moves are free, so they are built only for a search.
    let (cause, first_wall) = first_verdict(start, target, radius, blockers);
    if cause == Verdict::Free {
        return free;
    }
    if pushes_against_first_wall(
        start,
        target,
        radius,
        params.search_steps,
        first_wall,
        blockers,
    ) {
        return stopped_at_wall(pose, d.phi, free_heading, params);
    }
    searched_move(
        start,
        pose.heading,
        target,
        d,
        free_heading,
        radius,
        params,
        blockers,
        cause,
        first_wall,
    )
}

/// The commonest blocked move, a body pushing against the wall that blocked its planned
/// path (`first_wall`), not touching it at the start: does every midpoint of the search touch
/// that wall? Then the search ends at the start with a wall as its verdict, whichever
/// shortlist it runs over (see "A body pushing against a wall" in the module docs). That wall
/// passes `wall_may_block` (it blocked a path of the box), so `prepared_search` would take
/// this very test, or run a search whose every verdict is a wall, and give the same.
#[inline(always)]
fn pushes_against_first_wall(
    start: Vec2,
    target: Vec2,
    radius: f64,
    steps: u32,
    first_wall: Option<FirstWall>,
    blockers: &Blockers,
) -> bool {
    first_wall.is_some_and(|f| {
        steps > 0
            && !f.touching
            && box_is_safe(start, target)
            && every_midpoint_touches(&blockers.segments[f.index], start, target, radius, steps)
    })
}

/// The outcome of a move from `pose` that [`pushes_against_first_wall`] stopped at the start:
/// eq. 38 gives d_I = |start − start| = +0 (the start is finite: its box is safe), the
/// fraction of eq. 34 is 0/|M| = +0 (M finite, not 0), and its turn 0·φ = ±0, whose sine
/// `sin_cos` returns as the angle itself and whose cosine as 1 (`free_heading` with slippery
/// walls).
#[inline(always)]
fn stopped_at_wall(pose: Pose, phi: f64, free_heading: Vec2, params: &MotionParams) -> MoveOutcome {
    let heading = if params.slippery_walls {
        free_heading
    } else {
        normalise(rotate_sc(pose.heading, 0.0 * phi, 1.0))
    };
    MoveOutcome {
        pose: Pose {
            position: pose.position,
            heading,
        },
        travelled: 0.0,
        blocked: true,
        blocked_by_wall: true,
    }
}

/// A blocked move's search ([`blocked_move`], out of line) for the drive `d`, its outcome
/// rebuilt here.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn searched_move(
    start: Vec2,
    heading: Vec2,
    target: Vec2,
    d: Drive,
    free_heading: Vec2,
    radius: f64,
    params: &MotionParams,
    blockers: &Blockers,
    cause: Verdict,
    first_wall: Option<FirstWall>,
) -> MoveOutcome {
    let searched = blocked_move(
        start,
        heading,
        target,
        d.phi,
        d.chord,
        free_heading,
        radius,
        params,
        *blockers,
        cause,
        first_wall,
    );
    // Rebuilt (a blocked move is blocked): returned whole, the search's outcome would be
    // written straight into the caller's, which would then live in memory on every path,
    // the free move's too.
    debug_assert!(searched.blocked);
    MoveOutcome {
        blocked: true,
        ..searched
    }
}

/// The search's box test of [`blocked_move`]: the box of start → target lies within ±1e300
/// (so both are finite and no midpoint overflows).
#[inline(always)]
fn box_is_safe(start: Vec2, target: Vec2) -> bool {
    let (lo, hi) = Segment::new(start, target).bounds();
    lo.x >= -SAFE && lo.y >= -SAFE && hi.x <= SAFE && hi.y <= SAFE
}

/// Coordinates beyond which the search's midpoints could overflow.
const SAFE: f64 = 1e300;

/// The rest of [`plan_clamped_move`] for a move from `start`, facing `heading`, whose planned
/// path to `target` is not admissible (`cause`, and `first_wall` from [`first_verdict`]): the
/// search of eq. 37 and the heading of eq. 34–35 for the drive's turn `phi` and chord `chord`
/// (`free_heading` with slippery walls). The pose and drive come as vectors and numbers,
/// which the call passes in registers: as structs they would be copied to memory on every
/// move, blocked or not.
#[allow(clippy::too_many_arguments)]
#[inline(never)]
fn blocked_move(
    start: Vec2,
    heading: Vec2,
    target: Vec2,
    phi: f64,
    chord: f64,
    free_heading: Vec2,
    radius: f64,
    params: &MotionParams,
    blockers: Blockers<'_>,
    cause: Verdict,
    first_wall: Option<FirstWall>,
) -> MoveOutcome {
    // Taken by value: a move that is not blocked then keeps its blockers in registers.
    let blockers = &blockers;
    // Every path the search tests runs from `start` to a point of the box of start → target
    // (a midpoint of two points of the box is in the box), so a blocker that cannot block
    // any path within that box is left out of every test. The box must be finite and far from
    // overflow for the midpoints to stay inside it; otherwise every blocker is tested.
    let (lo, hi) = Segment::new(start, target).bounds();
    let use_all = !box_is_safe(start, target);
    // Binary search (eq. 37), with the few candidates prepared when there are few.
    let prepared = if use_all {
        None
    } else {
        prepared_search(
            start,
            target,
            radius,
            lo,
            hi,
            params.search_steps,
            cause,
            first_wall,
            blockers,
        )
    };
    let (lo, cause) = match prepared {
        Some(found) => found,
        None => {
            let walls = Shortlist::new(blockers.segments, use_all, |w| {
                wall_may_block(lo, hi, radius, w)
            });
            let circles = Shortlist::new(blockers.circles, use_all, |c| {
                circle_may_block(lo, hi, radius, c)
            });
            search(start, target, params.search_steps, cause, |p1| {
                verdict_over(start, p1, radius, walls.iter(), circles.iter())
            })
        }
    };
    // eq. 38.
    let travelled = start.distance(lo);
    let heading = if params.slippery_walls {
        free_heading
    } else {
        // eq. 34 with |M| (d_I is a distance), then eq. 35–36.
        let fraction = (travelled / chord.abs()).min(1.0);
        normalise(rotate(heading, fraction * phi))
    };
    MoveOutcome {
        pose: Pose {
            position: lo,
            heading,
        },
        travelled,
        blocked: true,
        blocked_by_wall: cause == Verdict::Wall,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    /// `normalise` (its zero-length case out of line) gives the plain select's bits: zero
    /// and NaN vectors unchanged, every other one divided by its length.
    #[test]
    fn normalise_is_the_plain_select() {
        let plain = |v: Vec2| {
            let len = v.length();
            if len > 0.0 {
                v / len
            } else {
                v
            }
        };
        let same =
            |a: Vec2, b: Vec2| a.x.to_bits() == b.x.to_bits() && a.y.to_bits() == b.y.to_bits();
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
        let mut vs = vec![
            Vec2::ZERO,
            Vec2::new(-0.0, 0.0),
            Vec2::new(0.0, -0.0),
            Vec2::NAN,
            Vec2::new(f64::NAN, 1.0),
            Vec2::new(f64::INFINITY, 1.0),
            Vec2::new(5e-324, 0.0),
            Vec2::new(1e300, 1e300),
        ];
        for _ in 0..10_000 {
            vs.push(Vec2::new(
                rng.gen_range(-2.0..2.0),
                rng.gen_range(-2.0..2.0),
            ));
            vs.push(Vec2::new(
                f64::from_bits(rng.gen::<u64>()),
                f64::from_bits(rng.gen::<u64>()),
            ));
        }
        for v in vs {
            assert!(same(normalise(v), plain(v)), "{v:?}");
        }
    }

    /// The inlined kernels give `libm::sincos`'s bits, and `libm::sin`'s and `libm::cos`'s,
    /// on random arguments of every magnitude a turn can have, at the thresholds of the
    /// shortcut (2⁻²⁷·√2 and π/4, as libm's high words see them) and on special values.
    #[test]
    fn sincos_is_libms() {
        let check = |x: f64| {
            let (s, c) = sincos(x);
            let (ls, lc) = libm::sincos(x);
            assert_eq!(s.to_bits(), ls.to_bits(), "sin {x:e}");
            assert_eq!(c.to_bits(), lc.to_bits(), "cos {x:e}");
            if x.abs() >= SINCOS_FROM || x.is_nan() {
                assert_eq!(s.to_bits(), libm::sin(x).to_bits(), "sin {x:e}");
                assert_eq!(c.to_bits(), libm::cos(x).to_bits(), "cos {x:e}");
            }
        };
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        for _ in 0..200_000 {
            let x: f64 = rng.gen_range(-4.0..4.0);
            check(x);
            check(x * 1e-3);
            check(x * 1e-6);
            check(f64::from_bits(rng.gen::<u64>()));
        }
        for high in [COS_ONE_BELOW, PIO4_HIGH] {
            for h in [high - 1, high, high + 1] {
                for low in [0, 1, 0x5444_2d18, 0x8000_0000, u32::MAX] {
                    let x = f64::from_bits((u64::from(h) << 32) | u64::from(low));
                    check(x);
                    check(-x);
                }
            }
        }
        for x in [
            0.0,
            -0.0,
            std::f64::consts::FRAC_PI_4,
            -std::f64::consts::FRAC_PI_4,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            f64::MIN_POSITIVE,
            5e-324,
        ] {
            check(x);
        }
    }
}
