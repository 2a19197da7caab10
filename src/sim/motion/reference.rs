//! The plain §8.2 move that the fast search of [`super::plan_move`] is checked against, bit
//! for bit (the algorithm before the search was pre-filtered): every path test runs over
//! every wall and every body, with the same float operations in the same order, and no
//! shortlist, prepared blocker or shortcut. Only tests call it.

use super::{Blockers, MotionParams, MoveOutcome, Pose};
use crate::geometry::{
    circle_touches_segment, circles_touch, point_segment_distance_squared, segments_intersect,
    Circle, Segment, Vec2,
};

#[derive(Clone, Copy, PartialEq)]
enum Verdict {
    Free,
    Wall,
    Body,
}

fn rotate_sc(v: Vec2, sin: f64, cos: f64) -> Vec2 {
    Vec2::new(v.x * cos - v.y * sin, v.x * sin + v.y * cos)
}

fn normalise(v: Vec2) -> Vec2 {
    let len = v.length();
    if len > 0.0 {
        v / len
    } else {
        v
    }
}

fn sinc(x: f64) -> f64 {
    if x.abs() < 1e-4 {
        1.0 - x * x / 6.0
    } else {
        libm::sin(x) / x
    }
}

fn clamp_rpt(x: f64, max: f64) -> f64 {
    if x.is_nan() {
        0.0
    } else {
        let m = max.abs();
        x.min(m).max(-m)
    }
}

fn wall_blocks(p0: Vec2, p1: Vec2, r: f64, wall: &Segment) -> bool {
    let path = Segment::new(p0, p1);
    let crosses = segments_intersect(&path, wall);
    if !crosses && !circle_touches_segment(p1, r, wall) {
        return false;
    }
    if !circle_touches_segment(p0, r, wall) {
        return true;
    }
    let d0 = point_segment_distance_squared(p0, wall);
    let d1 = point_segment_distance_squared(p1, wall);
    d1 < d0 || (crosses && d0 > 0.0)
}

fn circle_blocks(p0: Vec2, p1: Vec2, r: f64, body: &Circle) -> bool {
    if !circles_touch(p1, r, body.centre, body.radius) {
        return false;
    }
    if !circles_touch(p0, r, body.centre, body.radius) {
        return true;
    }
    p1.distance_squared(body.centre) < p0.distance_squared(body.centre)
}

fn verdict(p0: Vec2, p1: Vec2, r: f64, b: &Blockers) -> Verdict {
    if b.segments.iter().any(|w| wall_blocks(p0, p1, r, w)) {
        Verdict::Wall
    } else if b.circles.iter().any(|c| circle_blocks(p0, p1, r, c)) {
        Verdict::Body
    } else {
        Verdict::Free
    }
}

/// [`super::plan_move`] the plain way: the same drive, clamping and heading, the path tested
/// over every blocker, then the binary search of eq. 37 over every blocker at each midpoint.
pub fn plan_move(
    pose: Pose,
    left_rpt: f64,
    right_rpt: f64,
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
    let left = clamp_rpt(left_rpt, params.max_rpt);
    let right = clamp_rpt(right_rpt, params.max_rpt);
    let w = params.wheel;
    let d_left = std::f64::consts::TAU * w * left;
    let d_right = std::f64::consts::TAU * w * right;
    let (phi, chord) = if w == 0.0 {
        (0.0, 0.0)
    } else {
        let phi = (d_left - d_right) / w;
        (phi, 0.5 * (d_left + d_right) * sinc(0.5 * phi))
    };
    if !phi.is_finite() || !chord.is_finite() {
        return stay;
    }
    let half = 0.5 * phi;
    let (s, c) = (libm::sin(half), libm::cos(half));
    let chord_dir = normalise(rotate_sc(pose.heading, s, c));
    let free_heading = normalise(rotate_sc(chord_dir, s, c));
    let start = pose.position;
    if chord == 0.0 {
        return MoveOutcome {
            pose: Pose {
                position: start,
                heading: free_heading,
            },
            ..stay
        };
    }
    let target = start + chord_dir * chord;
    let mut cause = verdict(start, target, radius, blockers);
    if cause == Verdict::Free {
        return MoveOutcome {
            pose: Pose {
                position: target,
                heading: free_heading,
            },
            travelled: chord.abs(),
            ..stay
        };
    }
    let mut lo = start;
    let mut hi = target;
    for _ in 0..params.search_steps {
        let mid = (lo + hi) * 0.5;
        match verdict(start, mid, radius, blockers) {
            Verdict::Free => lo = mid,
            v => {
                hi = mid;
                cause = v;
            }
        }
    }
    let travelled = start.distance(lo);
    let heading = if params.slippery_walls {
        free_heading
    } else {
        let fraction = (travelled / chord.abs()).min(1.0);
        let angle = fraction * phi;
        normalise(rotate_sc(pose.heading, libm::sin(angle), libm::cos(angle)))
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
