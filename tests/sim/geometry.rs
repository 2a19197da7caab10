//! Geometry of the report's §6: circle contact (eq. 1), circle–segment contact (eq. 2–4 with
//! the eq. 4 erratum), segment intersection (eq. 5–24, every degenerate case the report lists
//! and more), ray casts, and seeded randomized comparisons with references built another way.

use berry_evolve::geometry::{
    circle_touches_segment, circles_touch, closest_point_on_segment,
    point_segment_distance_squared, ray_circle, ray_segment, segment_touches_circle,
    segments_intersect, Circle, Segment, Vec2,
};
use berry_evolve::seed::{
    below, chance, stream, uniform, Generation, IndividualId, Purpose, Rng, Seed, TrialIndex,
};

fn v(x: f64, y: f64) -> Vec2 {
    Vec2::new(x, y)
}
fn seg(ax: f64, ay: f64, bx: f64, by: f64) -> Segment {
    Segment::new(v(ax, ay), v(bx, by))
}
/// Both argument orders and both end-point orders must agree.
#[track_caller]
fn intersect(s0: Segment, s1: Segment) -> bool {
    let r0 = Segment::new(s0.b, s0.a);
    let r1 = Segment::new(s1.b, s1.a);
    let all = [
        segments_intersect(&s0, &s1),
        segments_intersect(&s1, &s0),
        segments_intersect(&r0, &s1),
        segments_intersect(&s0, &r1),
        segments_intersect(&r1, &r0),
    ];
    assert!(
        all.iter().all(|&x| x == all[0]),
        "order-dependent: {s0:?} {s1:?}: {all:?}"
    );
    all[0]
}
fn rng(trial: u64) -> Rng {
    stream(
        Seed(31_415),
        Purpose::Baseline,
        Generation(1),
        IndividualId(0),
        TrialIndex(trial),
    )
}
#[track_caller]
fn close(a: f64, b: f64, tol: f64) {
    assert!((a - b).abs() <= tol, "{a} vs {b} (tol {tol})");
}

// ---------------------------------------------------------------- eq. 1

#[test]
fn eq1_circles_touching_is_inclusive() {
    assert!(circles_touch(v(0.0, 0.0), 3.0, v(6.0, 0.0), 3.0));
    assert!(!circles_touch(
        v(0.0, 0.0),
        3.0,
        v(6.000_000_000_001, 0.0),
        3.0
    ));
    // 3-4-5: centre distance 5 = 1 + 4 exactly.
    assert!(circles_touch(v(0.0, 0.0), 1.0, v(3.0, 4.0), 4.0));
    assert!(!circles_touch(v(0.0, 0.0), 1.0, v(3.0, 4.0), 3.999_999_999));
    // Zero radii: points touch only when equal.
    assert!(circles_touch(v(1.5, -2.0), 0.0, v(1.5, -2.0), 0.0));
    assert!(!circles_touch(v(1.5, -2.0), 0.0, v(1.5, -2.0 + 1e-12), 0.0));
    // A point inside a circle.
    assert!(circles_touch(v(0.0, 0.0), 0.0, v(0.5, 0.5), 1.0));
    let c = Circle::new(v(2.0, 3.0), 4.0);
    assert_eq!((c.centre, c.radius), (v(2.0, 3.0), 4.0));
}

// ---------------------------------------------------------------- §6.2, eq. 2–4

/// eq. 4 as printed: squared distance to the *infinite* line compared with r².
fn eq4_as_printed(p: Vec2, r: f64, s: &Segment) -> bool {
    let (x, y, x0, y0, x1, y1) = (p.x, p.y, s.a.x, s.a.y, s.b.x, s.b.y);
    let num = (x - x0) * (x0 - x1) + (y - y0) * (y0 - y1);
    (x - x0).powi(2) + (y - y0).powi(2) - r * r
        <= num * num / ((x0 - x1).powi(2) + (y0 - y1).powi(2))
}

#[test]
fn eq2_eq3_box_rejects_far_circles() {
    let s = seg(0.0, 0.0, 10.0, 0.0);
    // Outside the box widened by r, on each side.
    assert!(!circle_touches_segment(v(-3.5, 0.0), 3.0, &s));
    assert!(!circle_touches_segment(v(13.5, 0.0), 3.0, &s));
    assert!(!circle_touches_segment(v(5.0, 3.5), 3.0, &s));
    assert!(!circle_touches_segment(v(5.0, -3.5), 3.0, &s));
    // On the widened box's edge: touching counts (distance exactly r).
    assert!(circle_touches_segment(v(-3.0, 0.0), 3.0, &s));
    assert!(circle_touches_segment(v(13.0, 0.0), 3.0, &s));
    assert!(circle_touches_segment(v(5.0, 3.0), 3.0, &s));
    assert!(circle_touches_segment(v(5.0, -3.0), 3.0, &s));
    assert!(!circle_touches_segment(v(5.0, 3.0), 2.999_999_999, &s));
}

#[test]
fn eq4_misprint_past_segment_end_is_not_contact() {
    let s = seg(0.0, 0.0, 10.0, 0.0);
    // Inside the box of eq. 2–3 (x <= 11, y <= 1), 0.9 from the infinite line, but
    // √(0.9² + 0.9²) ≈ 1.27 from the segment's end: eq. 4 as printed says contact, the text's
    // "smallest distance from p to L" says no.
    let p = v(10.9, 0.9);
    assert!(eq4_as_printed(p, 1.0, &s));
    assert!(!circle_touches_segment(p, 1.0, &s));
    // On the infinite line, 2 past the end, radius 1.
    assert!(eq4_as_printed(v(12.0, 0.0), 2.5, &s));
    assert!(!circle_touches_segment(v(12.0, 0.0), 1.0, &s));
    // Where the nearest point is inside the segment, eq. 4 and the exact distance agree.
    assert!(eq4_as_printed(v(5.0, 1.0), 1.0, &s));
    assert!(circle_touches_segment(v(5.0, 1.0), 1.0, &s));
    // Just round the corner: √(0.6² + 0.6²) ≈ 0.85 < 1.
    assert!(circle_touches_segment(v(10.6, 0.6), 1.0, &s));
}

#[test]
fn circle_segment_exact_distance_on_slanted_segment() {
    // Segment (0,0)-(3,4) of length 5; (5.5, −1) is (4, −3) from its midpoint (1.5, 2), a
    // perpendicular offset of length 5.
    let s = seg(0.0, 0.0, 3.0, 4.0);
    let p = v(5.5, -1.0);
    assert_eq!(closest_point_on_segment(p, &s), v(1.5, 2.0));
    assert_eq!(point_segment_distance_squared(p, &s), 25.0);
    assert!(circle_touches_segment(p, 5.0, &s));
    assert!(!circle_touches_segment(p, 4.999_999, &s));
    assert!(segment_touches_circle(&s, p, 5.0));
    // Beyond either end the nearest point is the end.
    assert_eq!(closest_point_on_segment(v(-1.0, -1.0), &s), v(0.0, 0.0));
    assert_eq!(closest_point_on_segment(v(10.0, 10.0), &s), v(3.0, 4.0));
    assert_eq!(s.length(), 5.0);
    assert_eq!(s.bounds(), (v(0.0, 0.0), v(3.0, 4.0)));
}

#[test]
fn circle_segment_degenerate_inputs() {
    // Zero-length segment: a point.
    let p = seg(2.0, 2.0, 2.0, 2.0);
    assert!(circle_touches_segment(v(5.0, 6.0), 5.0, &p));
    assert!(!circle_touches_segment(v(5.0, 6.0), 4.999, &p));
    assert_eq!(closest_point_on_segment(v(9.0, 9.0), &p), v(2.0, 2.0));
    // Zero-radius circle: a point on or off the segment.
    let s = seg(0.0, 0.0, 10.0, 0.0);
    assert!(circle_touches_segment(v(3.0, 0.0), 0.0, &s));
    assert!(circle_touches_segment(v(10.0, 0.0), 0.0, &s));
    assert!(!circle_touches_segment(v(3.0, 1e-12), 0.0, &s));
    // Both degenerate.
    assert!(circle_touches_segment(v(2.0, 2.0), 0.0, &p));
    assert!(!circle_touches_segment(v(2.0, 2.000_001), 0.0, &p));
}

// ---------------------------------------------------------------- §6.3, eq. 5–24

#[test]
fn figure4_left_trivially_rejected_by_box_test() {
    // Boxes [0,1]x[0,1] and [2,3]x[0,1] are disjoint (eq. 5).
    assert!(!intersect(seg(0.0, 0.0, 1.0, 1.0), seg(2.0, 0.0, 3.0, 1.0)));
    // Disjoint in y only (eq. 7).
    assert!(!intersect(seg(0.0, 0.0, 3.0, 1.0), seg(0.0, 2.0, 3.0, 5.0)));
}

#[test]
fn figure4_middle_box_overlap_but_intersection_outside() {
    // y = x on [0,4] and y = 5 − x on x ∈ [3,4]: boxes overlap ([3,4]x[1,2]), the lines meet
    // at (2.5, 2.5), outside the second segment.
    assert!(!intersect(seg(0.0, 0.0, 4.0, 4.0), seg(4.0, 1.0, 3.0, 2.0)));
    // The same with the lines meeting outside the first segment.
    assert!(!intersect(seg(0.0, 0.0, 1.0, 1.0), seg(0.0, 5.0, 5.0, 0.0)));
}

#[test]
fn figure4_right_real_crossing() {
    assert!(intersect(seg(0.0, 0.0, 4.0, 4.0), seg(0.0, 4.0, 4.0, 0.0)));
    assert!(intersect(seg(0.0, 0.0, 4.0, 4.0), seg(4.0, 1.0, 2.0, 3.0)));
}

#[test]
fn identical_lines() {
    let s = seg(1.0, 2.0, 5.0, 7.0);
    assert!(intersect(s, s));
    assert!(intersect(s, Segment::new(s.b, s.a)));
    // On the same infinite line, overlapping in part.
    assert!(intersect(seg(0.0, 0.0, 2.0, 2.0), seg(1.0, 1.0, 3.0, 3.0)));
    // One inside the other.
    assert!(intersect(seg(0.0, 0.0, 4.0, 2.0), seg(1.0, 0.5, 3.0, 1.5)));
}

#[test]
fn parallel_lines_never_intersect() {
    assert!(!intersect(seg(0.0, 0.0, 2.0, 1.0), seg(0.0, 1.0, 2.0, 2.0)));
    // Boxes overlap a lot, still parallel and distinct.
    assert!(!intersect(seg(0.0, 0.0, 4.0, 2.0), seg(0.0, 1.0, 4.0, 3.0)));
    assert!(!intersect(
        seg(0.0, 0.0, 4.0, 0.0),
        seg(1.0, 1e-12, 3.0, 1e-12)
    ));
}

#[test]
fn vertical_lines() {
    // Vertical against horizontal, slanted, vertical parallel and vertical collinear.
    assert!(intersect(seg(2.0, -1.0, 2.0, 1.0), seg(0.0, 0.0, 4.0, 0.0)));
    assert!(intersect(
        seg(2.0, -5.0, 2.0, 5.0),
        seg(0.0, -3.0, 4.0, 1.0)
    ));
    assert!(!intersect(
        seg(2.0, -5.0, 2.0, 5.0),
        seg(3.0, -3.0, 6.0, 1.0)
    ));
    assert!(!intersect(seg(0.0, 0.0, 0.0, 2.0), seg(1.0, 0.0, 1.0, 2.0)));
    assert!(intersect(seg(0.0, 0.0, 0.0, 2.0), seg(0.0, 1.0, 0.0, 3.0)));
    assert!(!intersect(seg(0.0, 0.0, 0.0, 1.0), seg(0.0, 2.0, 0.0, 3.0)));
    assert!(intersect(seg(0.0, 0.0, 0.0, 1.0), seg(0.0, 1.0, 0.0, 3.0)));
    // Both vertical: the slope form has k = ∞ twice.
    assert!(intersect(seg(7.0, 0.0, 7.0, 9.0), seg(7.0, 9.0, 7.0, 4.0)));
    // Nearly vertical (slope 1e13) crossing a horizontal segment.
    assert!(intersect(
        seg(0.0, 0.0, 1e-12, 10.0),
        seg(-1.0, 5.0, 1.0, 5.0)
    ));
    assert!(!intersect(
        seg(0.0, 0.0, 1e-12, 10.0),
        seg(1e-9, 5.0, 1.0, 5.0)
    ));
}

#[test]
fn collinear_overlap_and_disjoint() {
    // Horizontal collinear: overlapping, touching end to end, disjoint.
    assert!(intersect(seg(0.0, 0.0, 2.0, 0.0), seg(1.0, 0.0, 3.0, 0.0)));
    assert!(intersect(seg(0.0, 0.0, 2.0, 0.0), seg(2.0, 0.0, 3.0, 0.0)));
    assert!(!intersect(seg(0.0, 0.0, 1.0, 0.0), seg(2.0, 0.0, 3.0, 0.0)));
    // Diagonal collinear disjoint and end to end.
    assert!(!intersect(seg(0.0, 0.0, 1.0, 1.0), seg(2.0, 2.0, 3.0, 3.0)));
    assert!(intersect(seg(0.0, 0.0, 1.0, 1.0), seg(1.0, 1.0, 3.0, 3.0)));
    assert!(!intersect(
        seg(0.0, 0.0, 1.0, 1.0),
        seg(1.000_000_000_001, 1.000_000_000_001, 3.0, 3.0)
    ));
}

#[test]
fn touching_at_an_end_point_and_t_junction() {
    // L corner.
    assert!(intersect(seg(0.0, 0.0, 2.0, 0.0), seg(2.0, 0.0, 2.0, 2.0)));
    // V: only the end points meet.
    assert!(intersect(seg(0.0, 0.0, 2.0, 1.0), seg(0.0, 0.0, 2.0, -1.0)));
    // T-junction: one end on the other's interior.
    assert!(intersect(seg(0.0, 0.0, 4.0, 0.0), seg(2.0, 0.0, 2.0, 3.0)));
    assert!(intersect(seg(0.0, 0.0, 4.0, 4.0), seg(1.0, 1.0, 0.0, 5.0)));
    // Almost a T: a gap of 1e-12.
    assert!(!intersect(
        seg(0.0, 0.0, 4.0, 0.0),
        seg(2.0, 1e-12, 2.0, 3.0)
    ));
    // A T-junction off the float grid of the decimal inputs: (0.3, 0.1)·k for k = 1, 3 are
    // both rounded, so whether (0.3, 0.1) lies exactly on the line from (0, 0) to (0.9, 0.3)
    // (as floats) is decided by exact arithmetic, consistently in every argument order.
    let a = seg(0.0, 0.0, 0.9, 0.3);
    let b = seg(0.3, 0.1, 0.3, 5.0);
    let _consistent = intersect(a, b);
}

#[test]
fn zero_length_segments() {
    let s = seg(0.0, 0.0, 2.0, 2.0);
    // Point on the interior, at an end, on the line's extension, just off the line.
    assert!(intersect(s, seg(1.0, 1.0, 1.0, 1.0)));
    assert!(intersect(s, seg(2.0, 2.0, 2.0, 2.0)));
    assert!(!intersect(s, seg(3.0, 3.0, 3.0, 3.0)));
    assert!(!intersect(
        s,
        seg(1.0, 1.000_000_000_001, 1.0, 1.000_000_000_001)
    ));
    // Two points: equal or not.
    assert!(intersect(seg(0.1, 0.2, 0.1, 0.2), seg(0.1, 0.2, 0.1, 0.2)));
    assert!(!intersect(seg(0.1, 0.2, 0.1, 0.2), seg(0.1, 0.3, 0.1, 0.3)));
    // A point on a vertical segment.
    assert!(intersect(seg(5.0, -1.0, 5.0, 1.0), seg(5.0, 0.5, 5.0, 0.5)));
    assert!(!intersect(
        seg(5.0, -1.0, 5.0, 1.0),
        seg(5.0, 1.5, 5.0, 1.5)
    ));
}

// ---------------------------------------------------------------- ray casts

#[test]
fn ray_segment_cases() {
    let o = v(0.0, 0.0);
    let x = v(1.0, 0.0);
    let wall = seg(5.0, -1.0, 5.0, 1.0);
    assert_eq!(ray_segment(o, x, &wall), Some(5.0));
    // t counts multiples of dir.
    assert_eq!(ray_segment(o, v(2.0, 0.0), &wall), Some(2.5));
    // Behind the origin, beside the segment, hitting an end point exactly.
    assert_eq!(ray_segment(o, -x, &wall), None);
    assert_eq!(ray_segment(v(0.0, 1.5), x, &wall), None);
    assert_eq!(ray_segment(v(0.0, 1.0), x, &wall), Some(5.0));
    // Oblique: from (0,0) along (1,1) the line x = 5 is reached at (5,5); a segment up to 4
    // misses, up to 6 hits.
    assert_eq!(ray_segment(o, v(1.0, 1.0), &seg(5.0, 0.0, 5.0, 4.0)), None);
    assert_eq!(
        ray_segment(o, v(1.0, 1.0), &seg(5.0, 0.0, 5.0, 6.0)),
        Some(5.0)
    );
    // Parallel, not collinear.
    assert_eq!(ray_segment(o, x, &seg(1.0, 1.0, 4.0, 1.0)), None);
    // Collinear: ahead (nearer end), origin inside, behind.
    let c = seg(4.0, 0.0, 2.0, 0.0);
    assert_eq!(ray_segment(o, x, &c), Some(2.0));
    assert_eq!(ray_segment(v(3.0, 0.0), x, &c), Some(0.0));
    assert_eq!(ray_segment(v(3.0, 0.0), -x, &c), Some(0.0));
    assert_eq!(ray_segment(v(5.0, 0.0), x, &c), None);
    assert_eq!(ray_segment(v(5.0, 0.0), -x, &c), Some(1.0));
    // Zero direction: a hit only when the origin lies on the segment.
    assert_eq!(ray_segment(v(5.0, 0.5), v(0.0, 0.0), &wall), Some(0.0));
    assert_eq!(ray_segment(v(5.5, 0.5), v(0.0, 0.0), &wall), None);
    // Zero-length segment on and off the ray.
    assert_eq!(ray_segment(o, x, &seg(3.0, 0.0, 3.0, 0.0)), Some(3.0));
    assert_eq!(ray_segment(o, x, &seg(3.0, 1.0, 3.0, 1.0)), None);
    assert_eq!(ray_segment(o, x, &seg(-3.0, 0.0, -3.0, 0.0)), None);
}

#[test]
fn ray_circle_cases() {
    let o = v(0.0, 0.0);
    let x = v(1.0, 0.0);
    assert_eq!(ray_circle(o, x, v(10.0, 0.0), 2.0), Some(8.0));
    assert_eq!(ray_circle(o, v(2.0, 0.0), v(10.0, 0.0), 2.0), Some(4.0));
    // 3-4-5: from (0,0) along (0.6, 0.8) to a circle of radius 5 at (6, 8) (distance 10).
    close(
        ray_circle(o, v(0.6, 0.8), v(6.0, 8.0), 5.0).unwrap(),
        5.0,
        1e-12,
    );
    // Miss, tangent (inclusive), pointing away.
    assert_eq!(ray_circle(o, x, v(10.0, 3.0), 2.0), None);
    assert_eq!(ray_circle(o, x, v(10.0, 2.0), 2.0), Some(10.0));
    assert_eq!(ray_circle(o, -x, v(10.0, 0.0), 2.0), None);
    // Origin inside or on the circle: t = 0, whatever the direction.
    assert_eq!(ray_circle(o, -x, v(1.0, 0.0), 2.0), Some(0.0));
    assert_eq!(ray_circle(o, x, v(2.0, 0.0), 2.0), Some(0.0));
    // Zero direction from outside, zero radius on and off the ray.
    assert_eq!(ray_circle(o, v(0.0, 0.0), v(10.0, 0.0), 2.0), None);
    assert_eq!(ray_circle(o, x, v(7.0, 0.0), 0.0), Some(7.0));
    assert_eq!(ray_circle(o, x, v(7.0, 1e-9), 0.0), None);
    // Starting a hair outside: t is tiny and accurate, not lost to cancellation.
    let t = ray_circle(v(0.6, 0.8) * (1.0 + 1e-9), -v(0.6, 0.8), o, 1.0).unwrap();
    close(t, 1e-9, 1e-15);
}

// ---------------------------------------------------------------- randomized references

/// Exact rational reference for "do the segments share a point", by solving the parametric
/// equations p + t r = q + u s in integers (a different method from the orientation tests).
fn reference_intersect(p0: [i128; 2], p1: [i128; 2], q0: [i128; 2], q1: [i128; 2]) -> bool {
    let cross = |a: [i128; 2], b: [i128; 2]| a[0] * b[1] - a[1] * b[0];
    let dot = |a: [i128; 2], b: [i128; 2]| a[0] * b[0] + a[1] * b[1];
    let sub = |a: [i128; 2], b: [i128; 2]| [a[0] - b[0], a[1] - b[1]];
    let r = sub(p1, p0);
    let s = sub(q1, q0);
    let qp = sub(q0, p0);
    let zero = [0, 0];
    // A point on a segment: collinear and within the parameter range.
    let on = |pt: [i128; 2], a: [i128; 2], d: [i128; 2]| {
        let w = sub(pt, a);
        if d == zero {
            return w == zero;
        }
        cross(w, d) == 0 && (0..=dot(d, d)).contains(&dot(w, d))
    };
    if r == zero {
        return on(p0, q0, s);
    }
    if s == zero {
        return on(q0, p0, r);
    }
    let denom = cross(r, s);
    if denom == 0 {
        if cross(qp, r) != 0 {
            return false; // parallel, distinct lines
        }
        // Collinear: project both ends of q onto r and overlap the intervals.
        let rr = dot(r, r);
        let t0 = dot(qp, r);
        let t1 = dot(sub(q1, p0), r);
        return t0.min(t1) <= rr && t0.max(t1) >= 0;
    }
    // t = (qp × s)/denom, u = (qp × r)/denom, both in [0, 1].
    let (tn, un, d) = if denom > 0 {
        (cross(qp, s), cross(qp, r), denom)
    } else {
        (-cross(qp, s), -cross(qp, r), -denom)
    };
    (0..=d).contains(&tn) && (0..=d).contains(&un)
}

fn to_f(p: [i128; 2], scale: f64) -> Vec2 {
    v(p[0] as f64 * scale, p[1] as f64 * scale)
}

#[test]
fn randomized_small_grid_against_exact_reference() {
    // Coordinates in -4..=4: identical, parallel, collinear, vertical, T and end-point cases
    // all occur thousands of times.
    let mut r = rng(1);
    let mut hits = 0usize;
    for _ in 0..200_000 {
        let mut pt = || [below(&mut r, 9) as i128 - 4, below(&mut r, 9) as i128 - 4];
        let (a, b, c, d) = (pt(), pt(), pt(), pt());
        let expected = reference_intersect(a, b, c, d);
        let got = segments_intersect(
            &Segment::new(to_f(a, 1.0), to_f(b, 1.0)),
            &Segment::new(to_f(c, 1.0), to_f(d, 1.0)),
        );
        assert_eq!(got, expected, "{a:?}-{b:?} vs {c:?}-{d:?}");
        hits += usize::from(expected);
    }
    assert!(hits > 20_000 && hits < 180_000, "{hits}");
}

/// Extended Euclid: (g, x, y) with a x + b y = g = gcd(a, b) >= 0.
fn ext_gcd(a: i128, b: i128) -> (i128, i128, i128) {
    if b == 0 {
        if a < 0 {
            (-a, -1, 0)
        } else {
            (a, 1, 0)
        }
    } else {
        let (g, x, y) = ext_gcd(b, a % b);
        (g, y, x - (a / b) * y)
    }
}

#[test]
fn randomized_near_degenerate_fixed_point_against_exact_reference() {
    // Grid points k / 2^20 LU (exact floats). A long primitive lattice direction `dir`
    // (components up to 2^28 grid steps) and a Bézout vector `e` with dir × e = 1 give
    // points a + k·dir + j·e whose orientation against the line a → a + n·dir is exactly
    // n·j grid units², while the products a float determinant forms reach 2^60: the plain
    // float test gets such signs and zeros wrong. End points sit on or a few lattice steps off
    // the other segment's line: T-junctions, corners, near-misses, collinear overlaps.
    let scale = 1.0 / f64::from(1u32 << 20);
    let mut r = rng(2);
    let mut hits = 0usize;
    let mut naive_wrong = 0usize;
    for i in 0..100_000 {
        let mut rnd = |lo: i128, hi: i128| lo + i128::from(below(&mut r, (hi - lo + 1) as u64));
        let a = [rnd(-1 << 30, 1 << 30), rnd(-1 << 30, 1 << 30)];
        let (dx, dy) = loop {
            let (dx, dy) = (rnd(-1 << 28, 1 << 28), rnd(-1 << 28, 1 << 28));
            let (g, _, _) = ext_gcd(dx, dy);
            if g != 0 {
                break (dx / g, dy / g);
            }
        };
        // dx·x + dy·y = 1, so dir × (−y, x) = dx·x + dy·y = 1.
        let (_, x, y) = ext_gcd(dx, dy);
        let e = [-y, x];
        assert_eq!(dx * e[1] - dy * e[0], 1);
        let at = |k: i128, j: i128| [a[0] + k * dx + j * e[0], a[1] + k * dy + j * e[1]];
        let n = rnd(1, 8);
        let b = at(n, 0);
        let k = rnd(-2, n + 2);
        let (c, d) = match i % 4 {
            0 => (at(k, rnd(-2, 2)), at(rnd(-2, n + 2), rnd(-2, 2))),
            1 => (at(k, 0), at(k, rnd(-3, 3))),
            2 => (at(k, 0), at(rnd(-2, n + 2), 0)),
            _ => (
                at(k, rnd(-1, 1)),
                [rnd(-1 << 30, 1 << 30), rnd(-1 << 30, 1 << 30)],
            ),
        };
        let expected = reference_intersect(a, b, c, d);
        let (fa, fb, fc, fd) = (
            to_f(a, scale),
            to_f(b, scale),
            to_f(c, scale),
            to_f(d, scale),
        );
        let got = segments_intersect(&Segment::new(fa, fb), &Segment::new(fc, fd));
        assert_eq!(got, expected, "{a:?}-{b:?} vs {c:?}-{d:?}");
        assert_eq!(
            segments_intersect(&Segment::new(fd, fc), &Segment::new(fa, fb)),
            expected
        );
        hits += usize::from(expected);
        naive_wrong += usize::from(naive_intersect(fa, fb, fc, fd) != expected);
    }
    eprintln!("hits {hits}, naive float predicate wrong {naive_wrong}");
    assert!(hits > 10_000 && hits < 90_000, "{hits}");
    // The cases are hard enough that plain float arithmetic fails on many of them.
    assert!(
        naive_wrong > 1_000,
        "test cases are too easy: {naive_wrong}"
    );
}

/// The textbook float predicate, for showing that the test above is not trivial.
fn naive_intersect(p: Vec2, q: Vec2, r: Vec2, s: Vec2) -> bool {
    let o = |a: Vec2, b: Vec2, c: Vec2| (b - a).perp_dot(c - a);
    let inb = |a: Vec2, b: Vec2, c: Vec2| {
        c.x >= a.x.min(b.x) && c.x <= a.x.max(b.x) && c.y >= a.y.min(b.y) && c.y <= a.y.max(b.y)
    };
    let (o1, o2, o3, o4) = (o(p, q, r), o(p, q, s), o(r, s, p), o(r, s, q));
    (o1 * o2 < 0.0 && o3 * o4 < 0.0)
        || (o1 == 0.0 && inb(p, q, r))
        || (o2 == 0.0 && inb(p, q, s))
        || (o3 == 0.0 && inb(r, s, p))
        || (o4 == 0.0 && inb(r, s, q))
}

#[test]
fn randomized_float_segments_against_parametric_solution() {
    // Generic float segments: solve p + t r = q + u s in floats and compare wherever t and u
    // are clearly inside or clearly outside [0, 1].
    let mut r = rng(3);
    let (mut inside, mut outside) = (0usize, 0usize);
    for _ in 0..100_000 {
        let mut pt = || v(uniform(&mut r, -50.0, 50.0), uniform(&mut r, -50.0, 50.0));
        let (p0, p1, q0, q1) = (pt(), pt(), pt(), pt());
        let (rv, sv, qp) = (p1 - p0, q1 - q0, q0 - p0);
        let denom = rv.perp_dot(sv);
        // Keep the float solution well conditioned (|denom| up to 1e4 here).
        if denom.abs() < 1.0 {
            continue;
        }
        let t = qp.perp_dot(sv) / denom;
        let u = qp.perp_dot(rv) / denom;
        let m = 1e-9;
        let got = segments_intersect(&Segment::new(p0, p1), &Segment::new(q0, q1));
        if t > m && t < 1.0 - m && u > m && u < 1.0 - m {
            assert!(got, "missed crossing at t={t}, u={u}");
            inside += 1;
        } else if t < -m || t > 1.0 + m || u < -m || u > 1.0 + m {
            assert!(!got, "false crossing at t={t}, u={u}");
            outside += 1;
        }
    }
    assert!(inside > 10_000 && outside > 10_000, "{inside} {outside}");
}

#[test]
fn randomized_circle_segment_against_dense_sampling() {
    // Sample the segment at n + 1 evenly spaced points: the sampled minimum distance ds is
    // at least the true distance d, and ds² <= d² + (h/2)² for spacing h. So ds <= r proves
    // contact and ds² − (h/2)² > r² proves none; in between the sample cannot tell.
    let mut r = rng(4);
    let (mut yes, mut no) = (0usize, 0usize);
    for i in 0..20_000 {
        let a = v(uniform(&mut r, -20.0, 20.0), uniform(&mut r, -20.0, 20.0));
        let b = match i % 5 {
            0 => a, // zero length
            1 => v(uniform(&mut r, -20.0, 20.0), a.y),
            2 => v(a.x, uniform(&mut r, -20.0, 20.0)),
            _ => v(uniform(&mut r, -20.0, 20.0), uniform(&mut r, -20.0, 20.0)),
        };
        let s = Segment::new(a, b);
        let c = v(uniform(&mut r, -30.0, 30.0), uniform(&mut r, -30.0, 30.0));
        let radius = if chance(&mut r, 0.1) {
            0.0
        } else {
            uniform(&mut r, 0.0, 15.0)
        };
        let n = 2000;
        let mut ds2 = f64::INFINITY;
        for k in 0..=n {
            let p = a + (b - a) * (f64::from(k) / f64::from(n));
            ds2 = ds2.min(p.distance_squared(c));
        }
        let h = s.length() / f64::from(n);
        let got = circle_touches_segment(c, radius, &s);
        let exact2 = point_segment_distance_squared(c, &s);
        assert!(
            exact2 <= ds2 * (1.0 + 1e-12) + 1e-12,
            "distance above a sample"
        );
        assert!(
            exact2 >= ds2 - (h / 2.0).powi(2) - 1e-9,
            "distance far below samples"
        );
        // The closest point lies on the segment and is at the reported distance.
        let cp = closest_point_on_segment(c, &s);
        close(cp.distance_squared(c), exact2, 1e-9);
        assert!(point_segment_distance_squared(cp, &s) <= 1e-18 * (1.0 + s.length()));
        if ds2.sqrt() <= radius * (1.0 - 1e-12) {
            assert!(got, "sample within r but no contact");
            yes += 1;
        } else if ds2 - (h / 2.0).powi(2) > radius * radius * (1.0 + 1e-12) {
            assert!(!got, "contact but every sample farther than r");
            no += 1;
        }
        assert_eq!(got, segment_touches_circle(&s, c, radius));
    }
    assert!(yes > 2_000 && no > 2_000, "{yes} {no}");
}

#[test]
fn randomized_ray_casts_against_bisection() {
    // Reference t for ray_circle: bisection on "is origin + t dir in the disc" between the
    // origin and the foot of the perpendicular from the centre (a different method from the
    // quadratic formula). Reference for ray_segment: the float parametric solution, compared
    // where it is clearly inside or outside.
    let mut r = rng(5);
    let mut circle_hits = 0usize;
    let mut segment_hits = 0usize;
    for _ in 0..20_000 {
        let o = v(uniform(&mut r, -20.0, 20.0), uniform(&mut r, -20.0, 20.0));
        let dir = v(uniform(&mut r, -2.0, 2.0), uniform(&mut r, -2.0, 2.0));
        let c = v(uniform(&mut r, -20.0, 20.0), uniform(&mut r, -20.0, 20.0));
        let radius = uniform(&mut r, 0.0, 8.0);
        let inside = |t: f64| (o + dir * t).distance_squared(c) <= radius * radius;
        let got = ray_circle(o, dir, c, radius);
        let aa = dir.length_squared();
        let foot = ((c - o).dot(dir) / aa).max(0.0);
        if inside(0.0) {
            assert_eq!(got, Some(0.0));
        } else if !inside(foot) {
            // The closest point of the ray is outside: a miss unless it is within rounding.
            let gap = (o + dir * foot).distance(c) - radius;
            if gap > 1e-9 {
                assert_eq!(got, None, "o {o:?} dir {dir:?} c {c:?} r {radius}");
            }
        } else {
            let (mut lo, mut hi) = (0.0, foot);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if inside(mid) {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            let t = got.expect("bisection found a hit");
            close(t, hi, 1e-9 * (1.0 + hi));
            circle_hits += 1;
        }

        let s = Segment::new(
            v(uniform(&mut r, -20.0, 20.0), uniform(&mut r, -20.0, 20.0)),
            v(uniform(&mut r, -20.0, 20.0), uniform(&mut r, -20.0, 20.0)),
        );
        let e = s.b - s.a;
        let denom = dir.perp_dot(e);
        if denom.abs() > 0.1 {
            let w = s.a - o;
            let t = w.perp_dot(e) / denom;
            let u = w.perp_dot(dir) / denom;
            let m = 1e-9;
            let got = ray_segment(o, dir, &s);
            if t > m && u > m && u < 1.0 - m {
                let gt = got.expect("missed a segment");
                close(gt, t, 1e-9 * (1.0 + t));
                segment_hits += 1;
            } else if t < -m || u < -m || u > 1.0 + m {
                assert_eq!(got, None);
            }
        }
    }
    assert!(circle_hits > 1_000 && segment_hits > 1_000);
}
