//! Motion of the report's §8: differential drive (eq. 28–36), admissible paths and the binary
//! search of §8.2, and the no-deeper rule for bodies that start inside a blocker.
//!
//! Expected values are worked out by hand in the comments (w = 2 unless stated), not copied
//! from the implementation's output.

use std::f64::consts::{FRAC_1_SQRT_2, FRAC_PI_2, FRAC_PI_4, PI, SQRT_2, TAU};

use berry_evolve::geometry::{
    circle_touches_segment, circles_touch, point_segment_distance_squared, segments_intersect,
    Circle, Segment, Vec2,
};
use berry_evolve::seed::{
    below, chance, stream, uniform, Generation, IndividualId, Purpose, Rng, Seed, TrialIndex,
};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

use berry_evolve::sim::motion::{
    admissible, drive, plan_clamped_move, plan_move, reference, rotate, Blockers, MotionParams,
    MoveOutcome, Pose,
};

const R: f64 = 3.0; // body radius (report default d = 6)

fn v(x: f64, y: f64) -> Vec2 {
    Vec2::new(x, y)
}
fn seg(ax: f64, ay: f64, bx: f64, by: f64) -> Segment {
    Segment::new(v(ax, ay), v(bx, by))
}
fn pose(x: f64, y: f64, hx: f64, hy: f64) -> Pose {
    Pose {
        position: v(x, y),
        heading: v(hx, hy),
    }
}
fn params() -> MotionParams {
    MotionParams {
        wheel: 2.0,
        max_rpt: 1.0,
        search_steps: 20,
        slippery_walls: false,
    }
}
fn walls(segments: &[Segment]) -> Blockers<'_> {
    Blockers {
        segments,
        circles: &[],
    }
}
fn mv(p: Pose, l: f64, r: f64, b: &Blockers) -> MoveOutcome {
    plan_move(p, l, r, R, &params(), b)
}

#[track_caller]
fn close(a: f64, b: f64, tol: f64) {
    assert!((a - b).abs() <= tol, "{a} vs {b} (tol {tol})");
}
#[track_caller]
fn close_v(a: Vec2, b: Vec2, tol: f64) {
    assert!(
        (a.x - b.x).abs() <= tol && (a.y - b.y).abs() <= tol,
        "{a:?} vs {b:?} (tol {tol})"
    );
}

/// Binary search tolerance: the chord length over 2^steps, plus float slack.
fn search_tol(chord: f64, steps: u32) -> f64 {
    chord.abs() / f64::from(1u32 << steps) * (1.0 + 1e-6) + 1e-12
}

// ---------------------------------------------------------------- drive and free motion

#[test]
fn rotate_positive_turns_clockwise_on_screen() {
    // Facing right (east), a quarter turn to the creature's right faces down the screen (+y).
    close_v(rotate(v(1.0, 0.0), FRAC_PI_2), v(0.0, 1.0), 1e-15);
    close_v(rotate(v(0.0, 1.0), FRAC_PI_2), v(-1.0, 0.0), 1e-15);
    close_v(rotate(v(1.0, 0.0), -FRAC_PI_2), v(0.0, -1.0), 1e-15);
    close_v(
        rotate(v(1.0, 0.0), FRAC_PI_4),
        v(FRAC_1_SQRT_2, FRAC_1_SQRT_2),
        1e-15,
    );
    assert_eq!(rotate(v(0.6, 0.8), 0.0), v(0.6, 0.8));
}

#[test]
fn drive_matches_eq28_to_eq33() {
    // L = 0.5, R = 0.25, w = 2: d_L = 2π·2·0.5 = 2π, d_R = π, φ = (2π − π)/2 = π/2,
    // M = 2 · (3π/π) · sin(π/4) = 3√2.
    let d = drive(2.0, 0.5, 0.25);
    close(d.d_left, TAU, 1e-14);
    close(d.d_right, PI, 1e-14);
    close(d.phi, FRAC_PI_2, 1e-14);
    close(d.chord, 3.0 * SQRT_2, 1e-13);
    // Straight: M = d_L exactly.
    let d = drive(2.0, 0.5, 0.5);
    assert_eq!(d.phi, 0.0);
    assert_eq!(d.chord, d.d_left);
    // Spin: M = 0 exactly.
    let d = drive(2.0, 0.3, -0.3);
    assert_eq!(d.chord, 0.0);
    // One wheel still, one full turn: φ = 2π, the body pivots back to its start (sin π = 0).
    let d = drive(2.0, 1.0, 0.0);
    close(d.phi, TAU, 1e-14);
    close(d.chord, 0.0, 1e-14);
    // A zero wheel does nothing.
    let d = drive(0.0, 1.0, -0.5);
    assert_eq!((d.phi, d.chord), (0.0, 0.0));
}

#[test]
fn chord_is_continuous_near_equal_wheels() {
    // Compare with eq. 30 evaluated literally from the same d_L, d_R: where the literal form
    // divides by a tiny d_L − d_R the two must still agree to rounding, and M must approach
    // (d_L + d_R)/2 smoothly through the switch to the series inside sinc.
    let w = 2.0;
    let base = 0.4;
    let mut previous = drive(w, base, base).chord;
    for k in 0..=120 {
        let eps = 1e-12 * libm::pow(10.0, f64::from(k) / 10.0); // 1e-12 .. 1
        let d = drive(w, base + eps, base);
        let delta = d.d_left - d.d_right;
        let literal = w * (d.d_left + d.d_right) / delta * libm::sin(delta / (2.0 * w));
        close(d.chord, literal, 1e-13 * literal.abs());
        // Increasing the left wheel a little lengthens the chord a little (no jump).
        let straight = 0.5 * (d.d_left + d.d_right);
        assert!(
            d.chord <= straight + 1e-15,
            "chord exceeds straight distance"
        );
        if eps < 1e-3 {
            close(d.chord, previous, 1e-3 * 2.0 * TAU);
        }
        previous = d.chord;
    }
}

#[test]
fn straight_move_travels_two_pi_w_l_along_heading() {
    // L = R = 0.5, w = 2: 2π·2·0.5 = 2π LU along the heading, heading unchanged.
    let o = mv(pose(100.0, 100.0, 1.0, 0.0), 0.5, 0.5, &Blockers::NONE);
    close_v(o.pose.position, v(100.0 + TAU, 100.0), 1e-12);
    assert_eq!(o.pose.heading, v(1.0, 0.0));
    close(o.travelled, TAU, 1e-12);
    assert!(!o.blocked && !o.blocked_by_wall);
    // Along a 3-4-5 heading.
    let o = mv(pose(50.0, 60.0, 0.6, 0.8), 0.5, 0.5, &Blockers::NONE);
    close_v(
        o.pose.position,
        v(50.0 + 0.6 * TAU, 60.0 + 0.8 * TAU),
        1e-12,
    );
    close_v(o.pose.heading, v(0.6, 0.8), 1e-15);
}

#[test]
fn spin_in_place_keeps_centre_and_turns_by_phi() {
    // L = 0.125, R = -0.125: d_L = π/2, d_R = −π/2, φ = π/2: a quarter turn to the right.
    let start = pose(100.0, 100.0, 1.0, 0.0);
    let o = mv(start, 0.125, -0.125, &Blockers::NONE);
    assert_eq!(o.pose.position, start.position);
    close_v(o.pose.heading, v(0.0, 1.0), 1e-15);
    assert_eq!(o.travelled, 0.0);
    // L = −0.25, R = 0.25: φ = −π, a half turn.
    let o = mv(start, -0.25, 0.25, &Blockers::NONE);
    assert_eq!(o.pose.position, start.position);
    close_v(o.pose.heading, v(-1.0, 0.0), 1e-15);
}

#[test]
fn turning_move_ends_on_the_chord() {
    // L = 0.5, R = 0.25: φ = π/2, M = 3√2, chord direction = heading turned by π/4, so the end
    // is (3, 3) from the start. Check by the arc: mean wheel distance 1.5π over φ = π/2 is a
    // radius-3 quarter circle turning right, which ends 3 ahead and 3 to the right (down).
    let o = mv(pose(100.0, 100.0, 1.0, 0.0), 0.5, 0.25, &Blockers::NONE);
    close_v(o.pose.position, v(103.0, 103.0), 1e-12);
    close_v(o.pose.heading, v(0.0, 1.0), 1e-15);
    close(o.travelled, 3.0 * SQRT_2, 1e-12);
    close(o.pose.heading.length(), 1.0, 1e-15);
    // Mirror: R faster turns left (up the screen).
    let o = mv(pose(100.0, 100.0, 1.0, 0.0), 0.25, 0.5, &Blockers::NONE);
    close_v(o.pose.position, v(103.0, 97.0), 1e-12);
    close_v(o.pose.heading, v(0.0, -1.0), 1e-15);
}

#[test]
fn negative_chord_moves_backwards() {
    // L = R = −0.5: 2π backwards, heading kept.
    let o = mv(pose(100.0, 100.0, 1.0, 0.0), -0.5, -0.5, &Blockers::NONE);
    close_v(o.pose.position, v(100.0 - TAU, 100.0), 1e-12);
    assert_eq!(o.pose.heading, v(1.0, 0.0));
    close(o.travelled, TAU, 1e-12);
    // L = −0.5, R = −0.25: d_L = −2π, d_R = −π, φ = −π/2, M = 2·3·sin(−π/4) = −3√2. Chord
    // direction = heading turned by −π/4 = (1, −1)/√2; end = start − 3√2·(1, −1)/√2 = (−3, +3).
    // (Reversing on the radius-3 circle centred 3 below the start; ends facing up.)
    let d = drive(2.0, -0.5, -0.25);
    assert!(d.chord < 0.0);
    let o = mv(pose(100.0, 100.0, 1.0, 0.0), -0.5, -0.25, &Blockers::NONE);
    close_v(o.pose.position, v(97.0, 103.0), 1e-12);
    close_v(o.pose.heading, v(0.0, -1.0), 1e-15);
    close(o.travelled, 3.0 * SQRT_2, 1e-12);
}

#[test]
fn motor_signals_are_clamped_to_max_rpt() {
    // max_rpt = 1: L = R = 5 acts as 1, i.e. 2π·2·1 = 4π.
    let o = mv(pose(100.0, 100.0, 1.0, 0.0), 5.0, 5.0, &Blockers::NONE);
    close_v(o.pose.position, v(100.0 + 2.0 * TAU, 100.0), 1e-12);
    // L = −7, R = 7 acts as a spin of −1, 1: φ = (−4π − 4π)/2 = −4π, two full turns left.
    let o = mv(pose(100.0, 100.0, 1.0, 0.0), -7.0, 7.0, &Blockers::NONE);
    assert_eq!(o.pose.position, v(100.0, 100.0));
    close_v(o.pose.heading, v(1.0, 0.0), 1e-14);
    // Infinite signals clamp too; NaN counts as 0.
    let o = mv(
        pose(100.0, 100.0, 1.0, 0.0),
        f64::INFINITY,
        1.0,
        &Blockers::NONE,
    );
    close_v(o.pose.position, v(100.0 + 2.0 * TAU, 100.0), 1e-12);
    let o = mv(
        pose(100.0, 100.0, 1.0, 0.0),
        f64::NAN,
        f64::NAN,
        &Blockers::NONE,
    );
    assert_eq!(o.pose, pose(100.0, 100.0, 1.0, 0.0));
    let o = mv(
        pose(100.0, 100.0, 1.0, 0.0),
        f64::NAN,
        -0.5,
        &Blockers::NONE,
    );
    assert!(o.pose.position.is_finite() && o.pose.heading.is_finite());
}

// ---------------------------------------------------------------- collisions

#[test]
fn straight_into_wall_stops_at_body_radius() {
    // Wall at x = 110; body radius 3 from x = 100, moving 4π ≈ 12.57 to the right. The body
    // may not touch (contact inclusive), so it ends just short of x = 107, within the search
    // tolerance 4π / 2^20 ≈ 1.2e-5.
    let wall = [seg(110.0, 50.0, 110.0, 150.0)];
    let o = mv(pose(100.0, 100.0, 1.0, 0.0), 1.0, 1.0, &walls(&wall));
    let x = o.pose.position.x;
    assert!(x < 107.0, "touches the wall: {x}");
    assert!(107.0 - x <= search_tol(2.0 * TAU, 20), "stopped early: {x}");
    assert_eq!(o.pose.position.y, 100.0);
    assert!(!circle_touches_segment(o.pose.position, R, &wall[0]));
    assert!(o.blocked && o.blocked_by_wall);
    close(o.travelled, x - 100.0, 1e-12);
    assert_eq!(o.pose.heading, v(1.0, 0.0));
    // The same against a wall the end point lands beyond only partly: ending at x = 112.57
    // would be 2.57 past a wall at x = 110 (centre through the wall).
    let wall = [seg(104.0, 50.0, 104.0, 150.0)];
    let o = mv(pose(100.0, 100.0, 1.0, 0.0), 1.0, 1.0, &walls(&wall));
    assert!(o.pose.position.x < 101.0 && 101.0 - o.pose.position.x <= search_tol(4.0 * PI, 20));
}

#[test]
fn search_steps_set_the_tolerance() {
    // 5 halvings: the end is within 4π/32 ≈ 0.39 of x = 107 and still clear of the wall.
    let wall = [seg(110.0, 50.0, 110.0, 150.0)];
    let p = MotionParams {
        search_steps: 5,
        ..params()
    };
    let o = plan_move(pose(100.0, 100.0, 1.0, 0.0), 1.0, 1.0, R, &p, &walls(&wall));
    let x = o.pose.position.x;
    assert!(x < 107.0 && 107.0 - x <= search_tol(4.0 * PI, 5), "{x}");
    // 0 halvings: a blocked move is cancelled.
    let p = MotionParams {
        search_steps: 0,
        ..params()
    };
    let o = plan_move(pose(100.0, 100.0, 1.0, 0.0), 1.0, 1.0, R, &p, &walls(&wall));
    assert_eq!(o.pose.position, v(100.0, 100.0));
    assert_eq!(o.travelled, 0.0);
    assert!(o.blocked && o.blocked_by_wall);
}

#[test]
fn blocked_turn_turns_by_travelled_fraction() {
    // L = 0.5, R = 0.25 from (100, 100) facing right: chord 3√2 along (1, 1)/√2, φ = π/2.
    // A horizontal wall at y = 104.5 lets the centre go down to y < 101.5, i.e. d_I ≈ 1.5√2,
    // half the chord, so φ' = d_I φ / |M| = π/4 and the heading ends at (1, 1)/√2.
    let wall = [seg(0.0, 104.5, 200.0, 104.5)];
    let o = mv(pose(100.0, 100.0, 1.0, 0.0), 0.5, 0.25, &walls(&wall));
    let tol = search_tol(3.0 * SQRT_2, 20);
    assert!(o.blocked && o.blocked_by_wall);
    close(o.travelled, 1.5 * SQRT_2, tol);
    close_v(o.pose.position, v(101.5, 101.5), tol);
    assert!(o.pose.position.y < 101.5);
    let angle = FRAC_PI_4 * o.travelled / (1.5 * SQRT_2);
    close_v(o.pose.heading, v(libm::cos(angle), libm::sin(angle)), 1e-12);
    close_v(o.pose.heading, v(FRAC_1_SQRT_2, FRAC_1_SQRT_2), 1e-5);
    close(o.pose.heading.length(), 1.0, 1e-15);
}

#[test]
fn slippery_walls_turn_the_full_phi() {
    let wall = [seg(0.0, 104.5, 200.0, 104.5)];
    let p = MotionParams {
        slippery_walls: true,
        ..params()
    };
    let o = plan_move(
        pose(100.0, 100.0, 1.0, 0.0),
        0.5,
        0.25,
        R,
        &p,
        &walls(&wall),
    );
    assert!(o.blocked);
    close_v(
        o.pose.position,
        v(101.5, 101.5),
        search_tol(3.0 * SQRT_2, 20),
    );
    close_v(o.pose.heading, v(0.0, 1.0), 1e-15);
    // Sticky walls on the same move: only π/4.
    let o = mv(pose(100.0, 100.0, 1.0, 0.0), 0.5, 0.25, &walls(&wall));
    close_v(o.pose.heading, v(FRAC_1_SQRT_2, FRAC_1_SQRT_2), 1e-5);
}

#[test]
fn backwards_blocked_turn_keeps_the_sign_of_phi() {
    // L = −0.5, R = −0.25 reverses towards (−3, +3) with φ = −π/2 (see negative_chord_...).
    // A wall at y = 104.5 cuts it halfway: φ' = d_I φ / |M| = −π/4 (with M, not |M|, the
    // creature would turn the wrong way).
    let wall = [seg(0.0, 104.5, 200.0, 104.5)];
    let o = mv(pose(100.0, 100.0, 1.0, 0.0), -0.5, -0.25, &walls(&wall));
    assert!(o.blocked);
    close_v(
        o.pose.position,
        v(98.5, 101.5),
        search_tol(3.0 * SQRT_2, 20),
    );
    close_v(o.pose.heading, v(FRAC_1_SQRT_2, -FRAC_1_SQRT_2), 1e-5);
}

#[test]
fn move_blocked_by_another_body() {
    // Another body of radius 3 at (110, 100): the bodies may not touch, so the centre stops
    // short of x = 104 (centre distance 6). Only the end position is tested against bodies.
    let other = [Circle::new(v(110.0, 100.0), 3.0)];
    let b = Blockers {
        segments: &[],
        circles: &other,
    };
    let o = mv(pose(100.0, 100.0, 1.0, 0.0), 1.0, 1.0, &b);
    let x = o.pose.position.x;
    assert!(x < 104.0 && 104.0 - x <= search_tol(4.0 * PI, 20), "{x}");
    assert!(!circles_touch(o.pose.position, R, other[0].centre, 3.0));
    assert!(o.blocked && !o.blocked_by_wall);
    // A body off to the side does not block.
    let other = [Circle::new(v(110.0, 107.0), 3.0)];
    let b = Blockers {
        segments: &[],
        circles: &other,
    };
    assert!(!mv(pose(100.0, 100.0, 1.0, 0.0), 1.0, 1.0, &b).blocked);
}

#[test]
fn blocked_by_wall_names_the_nearer_cause() {
    // Body (radius 1) at (108, 100) cuts at x = 104; wall at x = 110 would cut at 107.
    let wall = [seg(110.0, 50.0, 110.0, 150.0)];
    let body = [Circle::new(v(108.0, 100.0), 1.0)];
    let b = Blockers {
        segments: &wall,
        circles: &body,
    };
    let o = mv(pose(100.0, 100.0, 1.0, 0.0), 1.0, 1.0, &b);
    assert!(o.blocked && !o.blocked_by_wall);
    assert!(o.pose.position.x < 104.0 && o.pose.position.x > 103.99);
    // Wall at x = 106 cuts at 103; body at (112, 100) would cut at 108.
    let wall = [seg(106.0, 50.0, 106.0, 150.0)];
    let body = [Circle::new(v(112.0, 100.0), 1.0)];
    let b = Blockers {
        segments: &wall,
        circles: &body,
    };
    let o = mv(pose(100.0, 100.0, 1.0, 0.0), 1.0, 1.0, &b);
    assert!(o.blocked && o.blocked_by_wall);
    assert!(o.pose.position.x < 103.0 && o.pose.position.x > 102.99);
}

#[test]
fn admissible_follows_section_8_2() {
    let wall = [seg(110.0, 50.0, 110.0, 150.0)];
    let b = walls(&wall);
    // Path crosses the wall although the end is clear of it.
    assert!(!admissible(v(100.0, 100.0), v(120.0, 100.0), R, &b));
    // End touching the wall exactly (distance 3 = r): inadmissible, contact is inclusive.
    assert!(!admissible(v(100.0, 100.0), v(107.0, 100.0), R, &b));
    assert!(admissible(v(100.0, 100.0), v(106.5, 100.0), R, &b));
    // Past the wall's end (distance from (112, 40) to (110, 50) is √104 > 3).
    assert!(admissible(v(100.0, 40.0), v(120.0, 40.0), R, &b));
    // Bodies: only the end circle counts, touching inclusive.
    let body = [Circle::new(v(110.0, 100.0), 2.0)];
    let b = Blockers {
        segments: &[],
        circles: &body,
    };
    assert!(!admissible(v(100.0, 100.0), v(105.0, 100.0), R, &b));
    assert!(admissible(v(100.0, 100.0), v(104.5, 100.0), R, &b));
    // Nothing blocks: always admissible.
    assert!(admissible(v(0.0, 0.0), v(1e6, -1e6), R, &Blockers::NONE));
}

#[test]
fn spinning_needs_no_path_test() {
    // Wedged between two walls closer than the body radius, a spin still turns the body and
    // leaves its centre where it was.
    let wall = [seg(98.0, 0.0, 98.0, 200.0), seg(102.0, 0.0, 102.0, 200.0)];
    let o = mv(pose(100.0, 100.0, 1.0, 0.0), 0.125, -0.125, &walls(&wall));
    assert_eq!(o.pose.position, v(100.0, 100.0));
    close_v(o.pose.heading, v(0.0, 1.0), 1e-15);
    assert!(!o.blocked);
}

// ---------------------------------------------------------------- starting inside a blocker

#[test]
fn starting_overlapped_wall_cannot_go_deeper() {
    // Centre 1 LU from a wall at x = 101 (body radius 3): overlapping, e.g. a door closed on it.
    let wall = [seg(101.0, 0.0, 101.0, 200.0)];
    let b = walls(&wall);
    let start = pose(100.0, 100.0, 1.0, 0.0);
    // Towards the wall: every end point is deeper, so it stays.
    let o = mv(start, 0.5, 0.5, &b);
    assert_eq!(o.pose.position, start.position);
    assert!(o.blocked && o.blocked_by_wall);
    // Away from the wall: free.
    let o = mv(pose(100.0, 100.0, -1.0, 0.0), 0.5, 0.5, &b);
    close_v(o.pose.position, v(100.0 - TAU, 100.0), 1e-12);
    assert!(!o.blocked);
    // Along the wall at the same distance: allowed (no clearance lost).
    let o = mv(pose(100.0, 100.0, 0.0, -1.0), 0.5, 0.5, &b);
    close_v(o.pose.position, v(100.0, 100.0 - TAU), 1e-12);
    assert!(!o.blocked);
    // Diagonally towards it: stays.
    let o = mv(pose(100.0, 100.0, 0.6, 0.8), 0.5, 0.5, &b);
    assert_eq!(o.pose.position, start.position);
    // Diagonally away: free.
    let o = mv(pose(100.0, 100.0, -0.6, 0.8), 0.5, 0.5, &b);
    assert!(!o.blocked);
}

#[test]
fn starting_overlapped_cannot_pass_through_the_wall() {
    // Centre 1 LU left of a wall at x = 101: jumping to 1.5 LU right of it would increase the
    // clearance but cross the wall: the centre must stay on its side.
    let wall = [seg(101.0, 0.0, 101.0, 200.0)];
    let b = walls(&wall);
    assert!(!admissible(v(100.0, 100.0), v(102.5, 100.0), R, &b));
    assert!(!admissible(v(100.0, 100.0), v(110.0, 100.0), R, &b));
    let o = mv(pose(100.0, 100.0, 1.0, 0.0), 1.0, 1.0, &b);
    assert!(o.pose.position.x <= 100.0);
}

#[test]
fn starting_centred_on_a_wall_may_leave_either_side() {
    let wall = [seg(100.0, 0.0, 100.0, 200.0)];
    let b = walls(&wall);
    let o = mv(pose(100.0, 100.0, 1.0, 0.0), 1.0, 1.0, &b);
    close_v(o.pose.position, v(100.0 + 2.0 * TAU, 100.0), 1e-12);
    let o = mv(pose(100.0, 100.0, -1.0, 0.0), 1.0, 1.0, &b);
    close_v(o.pose.position, v(100.0 - 2.0 * TAU, 100.0), 1e-12);
}

#[test]
fn starting_overlapped_body_cannot_come_closer() {
    // Other body radius 3 at (104, 100): centres 4 apart, overlapping by 2.
    let body = [Circle::new(v(104.0, 100.0), 3.0)];
    let b = Blockers {
        segments: &[],
        circles: &body,
    };
    let o = mv(pose(100.0, 100.0, 1.0, 0.0), 0.5, 0.5, &b);
    assert_eq!(o.pose.position, v(100.0, 100.0));
    assert!(o.blocked && !o.blocked_by_wall);
    let o = mv(pose(100.0, 100.0, -1.0, 0.0), 0.5, 0.5, &b);
    assert!(!o.blocked);
    close_v(o.pose.position, v(100.0 - TAU, 100.0), 1e-12);
}

#[test]
fn starting_overlapped_still_respects_other_walls() {
    // Overlapping wall A at x = 101; moving away from it into wall B at x = 92 (not touched
    // at the start): B blocks as usual, at centre x > 95.
    let wall = [seg(101.0, 0.0, 101.0, 200.0), seg(92.0, 0.0, 92.0, 200.0)];
    let o = mv(pose(100.0, 100.0, -1.0, 0.0), 1.0, 1.0, &walls(&wall));
    let x = o.pose.position.x;
    assert!(x > 95.0 && x - 95.0 <= search_tol(4.0 * PI, 20), "{x}");
    assert!(o.blocked_by_wall);
}

// ---------------------------------------------------------------- regressions

#[test]
fn creature_tunnels_through_wall_corner() {
    // Inside the corner of a box at (0, 0), moving fast straight at the corner: the chord
    // passes exactly through the corner point and ends 4.9 LU outside, clear of both walls.
    // The path test must catch the crossing (the corner is an end point of both walls).
    let box_walls = [seg(0.0, 0.0, 300.0, 0.0), seg(0.0, 0.0, 0.0, 300.0)];
    let b = walls(&box_walls);
    let h = -FRAC_1_SQRT_2;
    let o = mv(pose(4.0, 4.0, h, h), 1.0, 1.0, &b);
    assert!(o.blocked && o.blocked_by_wall);
    let p = o.pose.position;
    assert!(p.x > 3.0 && p.y > 3.0, "{p:?}");
    // Slightly off the diagonal, the path crosses one of the two walls next to the corner.
    for k in 1..50 {
        let a = 1e-9 * f64::from(k) * if k % 2 == 0 { 1.0 } else { -1.0 };
        let hd = rotate(v(h, h), a);
        let o = mv(pose(4.0, 4.0, hd.x, hd.y), 1.0, 1.0, &b);
        let p = o.pose.position;
        assert!(p.x > 3.0 && p.y > 3.0, "escaped the corner: {p:?}");
    }
    // A corner made of two separate walls meeting at a point that is not on a float grid.
    let c = v(0.1, 0.3);
    let corner = [
        Segment::new(c, c + v(100.0, 0.0)),
        Segment::new(c, c + v(0.0, 100.0)),
    ];
    let b = walls(&corner);
    let start = c + v(4.0, 4.0);
    let o = mv(pose(start.x, start.y, h, h), 1.0, 1.0, &b);
    let p = o.pose.position;
    assert!(
        p.x > c.x + 3.0 && p.y > c.y + 3.0,
        "escaped the corner: {p:?}"
    );
}

#[test]
fn creature_tunnels_through_thin_wall() {
    // A short thin wall across the path, far from both ends of the chord: the chord test
    // alone must stop the body, on the near side.
    let wall = [seg(105.0, 99.0, 105.0, 101.0)];
    let o = mv(pose(99.0, 100.0, 1.0, 0.0), 1.0, 1.0, &walls(&wall));
    assert!(o.blocked && o.pose.position.x < 102.0);
    // A zero-length wall (a post) on the path blocks too.
    let post = [seg(105.0, 100.0, 105.0, 100.0)];
    let o = mv(pose(99.0, 100.0, 1.0, 0.0), 1.0, 1.0, &walls(&post));
    assert!(o.blocked && o.pose.position.x < 102.0);
    // A turning move across a thin diagonal wall (x + y = 206, 4.2 LU from the start):
    // L = 1, R = 0.6 gives φ = 0.8π and a chord of 8 sin(0.4π) ≈ 7.6 at 72° below the
    // heading, ending at about (102.4, 107.2), past the wall.
    let wall = [seg(108.0, 98.0, 98.0, 108.0)];
    assert!(!circle_touches_segment(v(100.0, 100.0), R, &wall[0]));
    let o = mv(pose(100.0, 100.0, 1.0, 0.0), 1.0, 0.6, &walls(&wall));
    assert!(o.blocked);
    assert!(!segments_intersect(
        &Segment::new(v(100.0, 100.0), o.pose.position),
        &wall[0]
    ));
}

#[test]
fn creature_sticks_to_wall_when_sliding() {
    // Sticky walls: pushing diagonally into a wall the body already nearly touches travels
    // (almost) nothing and so turns (almost) nothing; with slippery walls it turns fully.
    let wall = [seg(0.0, 103.001, 200.0, 103.001)];
    let start = pose(100.0, 100.0, 1.0, 0.0);
    let o = mv(start, 0.5, 0.25, &walls(&wall));
    assert!(o.travelled < 0.01);
    assert!(o.pose.heading.x > 0.99);
}

// ---------------------------------------------------------------- randomized

fn rng(trial: u64) -> Rng {
    stream(
        Seed(20_240_611),
        Purpose::Baseline,
        Generation(0),
        IndividualId(0),
        TrialIndex(trial),
    )
}

/// A 300 × 300 box with `n` random interior walls (some zero-length, some axis-aligned).
fn random_world(r: &mut Rng, n: usize) -> Vec<Segment> {
    let mut w = vec![
        seg(0.0, 0.0, 300.0, 0.0),
        seg(300.0, 0.0, 300.0, 300.0),
        seg(300.0, 300.0, 0.0, 300.0),
        seg(0.0, 300.0, 0.0, 0.0),
    ];
    for _ in 0..n {
        let a = v(uniform(r, 0.0, 300.0), uniform(r, 0.0, 300.0));
        let b = match below(r, 4) {
            0 => a,
            1 => v(uniform(r, 0.0, 300.0), a.y),
            2 => v(a.x, uniform(r, 0.0, 300.0)),
            _ => a + v(uniform(r, -60.0, 60.0), uniform(r, -60.0, 60.0)),
        };
        w.push(Segment::new(a, b));
    }
    w
}

fn clear_of(p: Vec2, radius: f64, walls: &[Segment], bodies: &[Circle]) -> bool {
    walls.iter().all(|s| !circle_touches_segment(p, radius, s))
        && bodies
            .iter()
            .all(|c| !circles_touch(p, radius, c.centre, c.radius))
}

fn random_heading(r: &mut Rng) -> Vec2 {
    let a = uniform(r, -PI, PI);
    v(libm::cos(a), libm::sin(a))
}

#[test]
fn randomized_clear_start_always_ends_clear() {
    let mut moves = 0usize;
    let mut blocked = 0usize;
    for world in 0..60u64 {
        let mut r = rng(world);
        let walls_v = random_world(&mut r, 12);
        let mut bodies = Vec::new();
        for _ in 0..6 {
            bodies.push(Circle::new(
                v(uniform(&mut r, 0.0, 300.0), uniform(&mut r, 0.0, 300.0)),
                uniform(&mut r, 0.0, 6.0),
            ));
        }
        let b = Blockers {
            segments: &walls_v,
            circles: &bodies,
        };
        let p = MotionParams {
            wheel: 2.0,
            max_rpt: uniform(&mut r, 0.2, 4.0),
            search_steps: 1 + below(&mut r, 25) as u32,
            slippery_walls: chance(&mut r, 0.5),
        };
        for _creature in 0..20 {
            let radius = uniform(&mut r, 0.5, 6.0);
            let mut pos;
            loop {
                pos = v(uniform(&mut r, 0.0, 300.0), uniform(&mut r, 0.0, 300.0));
                if clear_of(pos, radius, &walls_v, &bodies) {
                    break;
                }
            }
            let mut ps = Pose {
                position: pos,
                heading: random_heading(&mut r),
            };
            for _tick in 0..60 {
                let (l, rr) = if chance(&mut r, 0.3) {
                    // Full speed: the fastest tunnelling attempts.
                    let s = if chance(&mut r, 0.5) { 1.0 } else { -1.0 };
                    (
                        s * p.max_rpt * 2.0,
                        s * p.max_rpt * uniform(&mut r, 0.5, 2.0),
                    )
                } else {
                    (
                        uniform(&mut r, -p.max_rpt, p.max_rpt),
                        uniform(&mut r, -p.max_rpt, p.max_rpt),
                    )
                };
                let o = plan_move(ps, l, rr, radius, &p, &b);
                let q = o.pose.position;
                moves += 1;
                blocked += usize::from(o.blocked);
                assert!(
                    clear_of(q, radius, &walls_v, &bodies),
                    "world {world}: ended touching at {q:?} from {ps:?}"
                );
                assert!(q.x > 0.0 && q.x < 300.0 && q.y > 0.0 && q.y < 300.0);
                let path = Segment::new(ps.position, q);
                assert!(
                    walls_v.iter().all(|s| !segments_intersect(&path, s)),
                    "world {world}: centre crossed a wall from {ps:?} to {q:?}"
                );
                assert!(o.travelled >= 0.0);
                close(o.travelled, ps.position.distance(q), 1e-9);
                close(o.pose.heading.length(), 1.0, 1e-12);
                assert!(o.blocked || !o.blocked_by_wall);
                ps = o.pose;
            }
        }
    }
    // The walls must actually get in the way for the test to mean anything.
    eprintln!("blocked {blocked} of {moves}");
    assert!(
        blocked > moves / 20,
        "only {blocked} of {moves} moves blocked"
    );
}

#[test]
fn randomized_overlapped_start_never_goes_deeper() {
    // Bodies dropped onto walls and other bodies: after any move, no blocker is closer than
    // at the start, and the centre never crosses a wall.
    let mut moves = 0usize;
    let mut moved = 0usize;
    for world in 0..40u64 {
        let mut r = rng(1000 + world);
        let walls_v = random_world(&mut r, 15);
        let bodies: Vec<Circle> = (0..6)
            .map(|_| {
                Circle::new(
                    v(uniform(&mut r, 0.0, 300.0), uniform(&mut r, 0.0, 300.0)),
                    uniform(&mut r, 0.0, 6.0),
                )
            })
            .collect();
        let b = Blockers {
            segments: &walls_v,
            circles: &bodies,
        };
        let p = MotionParams {
            max_rpt: uniform(&mut r, 0.2, 2.0),
            ..params()
        };
        for _ in 0..300 {
            let radius = uniform(&mut r, 1.0, 6.0);
            // Start near a random wall point or body, usually overlapping it.
            let start = if chance(&mut r, 0.7) {
                let s = walls_v[below(&mut r, walls_v.len() as u64) as usize];
                let t = uniform(&mut r, 0.0, 1.0);
                s.a + (s.b - s.a) * t + random_heading(&mut r) * uniform(&mut r, 0.0, radius)
            } else {
                let c = bodies[below(&mut r, bodies.len() as u64) as usize];
                c.centre + random_heading(&mut r) * uniform(&mut r, 0.0, radius + c.radius)
            };
            let ps = Pose {
                position: start,
                heading: random_heading(&mut r),
            };
            let o = plan_move(
                ps,
                uniform(&mut r, -p.max_rpt, p.max_rpt),
                uniform(&mut r, -p.max_rpt, p.max_rpt),
                radius,
                &p,
                &b,
            );
            let q = o.pose.position;
            moves += 1;
            moved += usize::from(q != start);
            for s in &walls_v {
                let d0 = point_segment_distance_squared(start, s);
                let d1 = point_segment_distance_squared(q, s);
                if circle_touches_segment(q, radius, s) {
                    assert!(d1 >= d0, "went deeper into {s:?}: {start:?} -> {q:?}");
                }
                if d0 > 0.0 && q != start {
                    assert!(
                        !segments_intersect(&Segment::new(start, q), s),
                        "crossed {s:?}: {start:?} -> {q:?}"
                    );
                }
            }
            for c in &bodies {
                if circles_touch(q, radius, c.centre, c.radius) {
                    assert!(q.distance_squared(c.centre) >= start.distance_squared(c.centre));
                }
            }
        }
    }
    eprintln!("moved {moved} of {moves}");
    // Overlapped bodies must still be able to get free most of the time.
    assert!(
        moved > moves / 3,
        "only {moved} of {moves} overlapped bodies moved"
    );
}

#[test]
fn randomized_free_moves_match_the_arc() {
    // Without blockers the end point lies on the circular arc of radius (mean wheel
    // distance)/φ that eq. 30 approximates by its chord: check it against an independent
    // construction from the arc's centre.
    let mut r = rng(77);
    for _ in 0..5000 {
        let l = uniform(&mut r, -1.0, 1.0);
        let rr = uniform(&mut r, -1.0, 1.0);
        let h = random_heading(&mut r);
        let start = v(uniform(&mut r, -50.0, 50.0), uniform(&mut r, -50.0, 50.0));
        let o = plan_move(
            Pose {
                position: start,
                heading: h,
            },
            l,
            rr,
            R,
            &params(),
            &Blockers::NONE,
        );
        let (dl, dr) = (TAU * 2.0 * l, TAU * 2.0 * rr);
        let phi = (dl - dr) / 2.0;
        let mean = 0.5 * (dl + dr);
        if phi.abs() < 1e-3 {
            continue;
        }
        // Turning right (φ > 0) around the centre on the right side: start + ρ·right, where
        // right = h turned by +π/2 = (−h.y, h.x) and ρ = mean/φ (signed).
        let rho = mean / phi;
        let right = v(-h.y, h.x);
        let centre = start + right * rho;
        let expected = centre + rotate(start - centre, phi);
        close_v(o.pose.position, expected, 1e-9);
        close_v(o.pose.heading, rotate(h, phi), 1e-12);
    }
}

/// Moves a body of radius `rad` from `pose` for `ticks` ticks with the signals `signals()`
/// gives, by `plan_move` and by the reference, asserting the same bits at every tick (case
/// `case`); returns how many moves were blocked.
fn replay(
    case: usize,
    mut pose: Pose,
    (rad, params, b): (f64, &MotionParams, &Blockers),
    ticks: usize,
    mut signals: impl FnMut() -> (f64, f64),
) -> usize {
    let mut blocked = 0;
    for tick in 0..ticks {
        let (left, right) = signals();
        let got = plan_move(pose, left, right, rad, params, b);
        let want = reference::plan_move(pose, left, right, rad, params, b);
        assert!(
            same_bits(&got, &want),
            "case {case} tick {tick}: {got:?} vs reference {want:?}"
        );
        blocked += usize::from(want.blocked);
        pose = want.pose;
    }
    blocked
}

fn same_bits(a: &MoveOutcome, b: &MoveOutcome) -> bool {
    let bits = |o: &MoveOutcome| {
        [
            o.pose.position.x.to_bits(),
            o.pose.position.y.to_bits(),
            o.pose.heading.x.to_bits(),
            o.pose.heading.y.to_bits(),
            o.travelled.to_bits(),
        ]
    };
    bits(a) == bits(b) && a.blocked == b.blocked && a.blocked_by_wall == b.blocked_by_wall
}

/// A random point within `spread` of `c`.
fn near(r: &mut ChaCha8Rng, c: Vec2, spread: f64) -> Vec2 {
    c + v(uniform(r, -spread, spread), uniform(r, -spread, spread))
}

/// A random wall of one of several kinds around the start `p` of a body of radius `rad`.
fn random_wall(r: &mut ChaCha8Rng, p: Vec2, rad: f64) -> Segment {
    match below(r, 9) {
        // Near: within a few move lengths.
        0 | 1 => {
            let a = near(r, p, 20.0);
            Segment::new(a, near(r, a, 15.0))
        }
        // Far away.
        2 => {
            let a = near(r, p, 300.0);
            Segment::new(a, near(r, a, 40.0))
        }
        // Zero length, near.
        3 => {
            let a = near(r, p, 12.0);
            Segment::new(a, a)
        }
        // Through the start centre.
        4 => {
            let d = random_heading(r) * uniform(r, 0.0, 10.0);
            Segment::new(p - d * uniform(r, 0.0, 1.0), p + d)
        }
        // Touching the body at the start: passing through a point at distance <= rad.
        5 => {
            let q = p + random_heading(r) * uniform(r, 0.0, rad);
            let d = random_heading(r) * uniform(r, 0.0, 8.0);
            Segment::new(q - d * uniform(r, 0.0, 1.0), q + d)
        }
        // Exactly tangent to the body at the start, axis-aligned.
        6 => {
            let y = p.y + if chance(r, 0.5) { rad } else { -rad };
            Segment::new(v(p.x - 10.0, y), v(p.x + uniform(r, -5.0, 10.0), y))
        }
        // Long axis-aligned walls (arena borders).
        7 => {
            let off = uniform(r, -15.0, 15.0);
            if chance(r, 0.5) {
                Segment::new(v(p.x - 500.0, p.y + off), v(p.x + 500.0, p.y + off))
            } else {
                Segment::new(v(p.x + off, p.y - 500.0), v(p.x + off, p.y + 500.0))
            }
        }
        // An end point on the start circle.
        _ => {
            let q = p + random_heading(r) * rad;
            Segment::new(q, near(r, q, 10.0))
        }
    }
}

/// A random body around the start `p` of a body of radius `rad`.
fn random_body(r: &mut ChaCha8Rng, p: Vec2, rad: f64) -> Circle {
    let radius = match below(r, 4) {
        0 => 0.0,
        1 => rad,
        _ => uniform(r, 0.0, 8.0),
    };
    let centre = match below(r, 4) {
        0 => near(r, p, 200.0),
        // Exactly touching at the start.
        1 => p + random_heading(r) * (rad + radius),
        // Overlapping at the start.
        2 => p + random_heading(r) * uniform(r, 0.0, rad + radius),
        _ => near(r, p, 20.0),
    };
    Circle::new(centre, radius)
}

#[test]
fn prefiltered_search_matches_the_reference_bit_for_bit() {
    let mut r = ChaCha8Rng::seed_from_u64(0x8e55_2024);
    let (mut blocked, mut by_wall, mut by_body) = (0, 0, 0);
    for case in 0..12_000 {
        let rad = match below(&mut r, 40) {
            0..=7 => 0.0,
            8..=15 => uniform(&mut r, 0.5, 6.0),
            // Not a body radius, but the shortlist must not assume r >= 0.
            16 => -uniform(&mut r, 0.5, 3.0),
            17 => f64::NAN,
            _ => R,
        };
        // Mostly moderate coordinates; some huge ones (the search falls back to every blocker).
        let scale = match below(&mut r, 40) {
            0 => 1e301,
            1 => 1e-300,
            _ => 1.0,
        };
        let start = near(&mut r, v(0.0, 0.0), 400.0) * scale;
        let mut walls = Vec::new();
        // Sometimes more candidates than the shortlist holds.
        let n_walls = if case % 25 == 0 {
            40 + below(&mut r, 20)
        } else {
            below(&mut r, 14)
        };
        for _ in 0..n_walls {
            walls.push(random_wall(&mut r, start, rad));
        }
        let n_bodies = if case % 31 == 0 {
            40 + below(&mut r, 10)
        } else {
            below(&mut r, 6)
        };
        let bodies: Vec<Circle> = (0..n_bodies)
            .map(|_| random_body(&mut r, start, rad))
            .collect();
        let signal = |r: &mut ChaCha8Rng| match below(r, 12) {
            0 => 1.0,
            1 => -1.0,
            2 => 0.0,
            3 => f64::NAN,
            4 => uniform(r, -3.0, 3.0),
            _ => uniform(r, -1.0, 1.0),
        };
        let (left, right) = (signal(&mut r), signal(&mut r));
        let params = MotionParams {
            wheel: if chance(&mut r, 0.9) {
                2.0
            } else {
                uniform(&mut r, 0.0, 6.0)
            },
            max_rpt: if chance(&mut r, 0.8) { 1.0 } else { 2.5 },
            search_steps: if chance(&mut r, 0.8) {
                20
            } else {
                below(&mut r, 40) as u32
            },
            slippery_walls: chance(&mut r, 0.5),
        };
        let p = Pose {
            position: start,
            heading: random_heading(&mut r),
        };
        let b = Blockers {
            segments: &walls,
            circles: &bodies,
        };
        let got = plan_move(p, left, right, rad, &params, &b);
        let want = reference::plan_move(p, left, right, rad, &params, &b);
        assert!(
            same_bits(&got, &want),
            "case {case}: {got:?} vs reference {want:?}"
        );
        blocked += usize::from(want.blocked);
        by_wall += usize::from(want.blocked_by_wall);
        by_body += usize::from(want.blocked && !want.blocked_by_wall);
    }
    // The situations exercise the search, both causes.
    assert!(blocked > 3000, "{blocked}");
    assert!(by_wall > 1500, "{by_wall}");
    assert!(by_body > 300, "{by_body}");
}

/// A body about to push: its radius (mostly R, else uniform from `min_radius` to 6), its
/// start within 140 of (150, 150) and its heading, drawn in that order.
fn pusher(r: &mut ChaCha8Rng, min_radius: f64) -> (f64, Vec2, Vec2) {
    let rad = if chance(r, 0.8) {
        R
    } else {
        uniform(r, min_radius, 6.0)
    };
    let start = near(r, v(150.0, 150.0), 140.0);
    (rad, start, random_heading(r))
}

/// A body pushing against walls tick after tick (the search's commonest case: one wall, every
/// midpoint blocked, or a few walls near a corner), each tick starting where the last ended,
/// matches the reference bit for bit. Straight moves (φ = ±0) are frequent here.
#[test]
fn pushing_against_walls_matches_the_reference_bit_for_bit() {
    let mut r = ChaCha8Rng::seed_from_u64(0x9a5e_2026);
    let mut blocked = 0;
    for case in 0..600 {
        // One wall ahead (sometimes a second one: a corner), and sometimes a body.
        let (rad, start, heading) = pusher(&mut r, 0.0);
        let ahead = start + heading * (rad + uniform(&mut r, 0.0, 8.0));
        let across = v(-heading.y, heading.x) * uniform(&mut r, 1.0, 300.0);
        let mut walls = vec![Segment::new(ahead - across, ahead + across)];
        if chance(&mut r, 0.3) {
            walls.push(random_wall(&mut r, start, rad));
        }
        if chance(&mut r, 0.2) {
            walls.push(Segment::new(
                ahead,
                ahead - heading * uniform(&mut r, 0.0, 20.0),
            ));
        }
        let bodies: Vec<Circle> = if chance(&mut r, 0.2) {
            vec![random_body(&mut r, start, rad)]
        } else {
            Vec::new()
        };
        let b = Blockers {
            segments: &walls,
            circles: &bodies,
        };
        let params = MotionParams {
            slippery_walls: chance(&mut r, 0.3),
            ..MotionParams::default()
        };
        let p = Pose {
            position: start,
            heading,
        };
        blocked += replay(case, p, (rad, &params, &b), 12, || match below(&mut r, 4) {
            0 => (1.0, 1.0),
            1 => (-0.0, 0.0),
            2 => {
                let x = uniform(&mut r, 0.05, 1.0);
                (x, x)
            }
            _ => (uniform(&mut r, 0.0, 1.0), uniform(&mut r, 0.0, 1.0)),
        });
    }
    assert!(blocked > 2000, "{blocked}");
}

/// The pushing search reuses the first test's contact at the start for the one wall it
/// lists, found by its index among all the walls given: far walls listed before and after
/// the pushed wall (so its index is not 0), bodies resting just clear of it, touching it or
/// overlapping it, against the reference bit for bit.
#[test]
fn pushing_with_far_walls_listed_first_matches_the_reference_bit_for_bit() {
    let mut r = ChaCha8Rng::seed_from_u64(0xfa11_2026);
    let (mut blocked, mut touching) = (0, 0);
    for case in 0..1_500 {
        let (rad, start, heading) = pusher(&mut r, 0.1);
        // From overlapping the wall (gap < 0) to resting just clear of it.
        let gap = match below(&mut r, 3) {
            0 => uniform(&mut r, -rad, 0.0),
            1 => uniform(&mut r, 0.0, 1e-9),
            _ => uniform(&mut r, 0.0, 4.0),
        };
        let ahead = start + heading * (rad + gap);
        let across = v(-heading.y, heading.x) * uniform(&mut r, 1.0, 300.0);
        let pushed = Segment::new(ahead - across, ahead + across);
        // Far walls: beyond any move's reach (at most 2π·2 LU plus the radius).
        let far = |r: &mut ChaCha8Rng| {
            let c = start + random_heading(r) * uniform(r, 40.0, 200.0);
            Segment::new(c, c + random_heading(r) * uniform(r, 0.0, 30.0) * 0.1)
        };
        let before = below(&mut r, 4) as usize;
        let after = below(&mut r, 3) as usize;
        let mut walls: Vec<Segment> = (0..before).map(|_| far(&mut r)).collect();
        walls.push(pushed);
        walls.extend((0..after).map(|_| far(&mut r)));
        let b = Blockers {
            segments: &walls,
            circles: &[],
        };
        let params = MotionParams {
            slippery_walls: chance(&mut r, 0.3),
            ..MotionParams::default()
        };
        let p = Pose {
            position: start,
            heading,
        };
        touching += usize::from(gap <= 0.0);
        blocked += replay(case, p, (rad, &params, &b), 8, || match below(&mut r, 3) {
            0 => (1.0, 1.0),
            1 => {
                let x = uniform(&mut r, 0.01, 1.0);
                (x, x)
            }
            _ => (uniform(&mut r, 0.0, 1.0), uniform(&mut r, 0.0, 1.0)),
        });
    }
    assert!(blocked > 4_000 && touching > 300, "{blocked} {touching}");
}

/// A body pushing against a wall with an infinite, NaN or huge coordinate at its far end
/// (the pushing proof refuses such walls by their magnitude or by NaN distances), against
/// the reference bit for bit.
#[test]
fn pushing_against_non_finite_walls_matches_the_reference_bit_for_bit() {
    let mut r = ChaCha8Rng::seed_from_u64(0x1f1f_2026);
    let odd = [
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NAN,
        1e200,
        -1e101,
        1e99,
    ];
    for case in 0..2_000 {
        let start = near(&mut r, v(150.0, 150.0), 140.0);
        let heading = random_heading(&mut r);
        let ahead = start + heading * (R + uniform(&mut r, 0.0, 1e-6));
        let across = v(-heading.y, heading.x) * uniform(&mut r, 1.0, 50.0);
        let mut far = ahead + across;
        let x = odd[below(&mut r, odd.len() as u64) as usize];
        match below(&mut r, 3) {
            0 => far.x = x,
            1 => far.y = x,
            _ => far = v(x, x),
        }
        let walls = if chance(&mut r, 0.5) {
            vec![Segment::new(ahead - across, far)]
        } else {
            vec![Segment::new(far, ahead - across)]
        };
        let b = Blockers {
            segments: &walls,
            circles: &[],
        };
        let params = MotionParams::default();
        let p = Pose {
            position: start,
            heading,
        };
        replay(case, p, (R, &params, &b), 4, || {
            if chance(&mut r, 0.5) {
                (1.0, 1.0)
            } else {
                (uniform(&mut r, 0.0, 1.0), uniform(&mut r, 0.0, 1.0))
            }
        });
    }
}

/// The shortcut for a body pushing against a wall (every midpoint touching, proved once) at
/// its edges, against the reference bit for bit: bodies resting within rounding of the
/// contact distance after a blocked move and pushing again at every angle, moves so short
/// that the last midpoints barely reach (or just miss) the wall, pushes past a wall's end
/// and against zero-length walls, corners and nearby bodies, tiny and huge radii,
/// coordinates far from the origin, and 0 to 40 halvings.
#[test]
fn pushing_against_a_wall_at_the_edges_matches_the_reference_bit_for_bit() {
    let mut r = ChaCha8Rng::seed_from_u64(0x5e1f_2026);
    let (mut blocked, mut stayed, mut crept) = (0, 0, 0);
    for case in 0..4_000 {
        let rad = match below(&mut r, 10) {
            0 => uniform(&mut r, 1e-9, 1e-3),
            1 => uniform(&mut r, 1e3, 1e6),
            2 => 0.0,
            _ => uniform(&mut r, 0.5, 6.0),
        };
        let scale = match below(&mut r, 6) {
            0 => 1e6,
            1 => 1e12,
            _ => 1.0,
        };
        let start = near(&mut r, v(0.0, 0.0), 300.0) * scale;
        // The wall: long, short, or a point; ahead of the start at about the radius.
        let normal = random_heading(&mut r);
        let gap = match below(&mut r, 5) {
            0 => 0.0,
            1 => uniform(&mut r, 0.0, 1e-12) * (scale + rad),
            2 => uniform(&mut r, 0.0, 1e-6) * (1.0 + rad),
            _ => uniform(&mut r, 0.0, 3.0),
        };
        let foot = start + normal * (rad + gap);
        let along = v(-normal.y, normal.x);
        let wall = match below(&mut r, 4) {
            0 => Segment::new(foot, foot),
            // The foot near one end: pushes pass the end.
            1 => Segment::new(
                foot - along * uniform(&mut r, -2.0, 2.0),
                foot + along * uniform(&mut r, 0.0, 30.0),
            ),
            _ => Segment::new(
                foot - along * uniform(&mut r, 0.0, 300.0),
                foot + along * uniform(&mut r, 0.0, 300.0),
            ),
        };
        // Sometimes a corner: a second wall through the foot, or another wall nearby, and
        // sometimes a body.
        let mut list = vec![wall];
        match below(&mut r, 6) {
            0 => {
                let d = random_heading(&mut r) * uniform(&mut r, 0.0, 20.0);
                list.insert(below(&mut r, 2) as usize, Segment::new(foot, foot + d));
            }
            1 => list.push(random_wall(&mut r, start, rad)),
            _ => {}
        }
        let bodies: Vec<Circle> = if chance(&mut r, 0.15) {
            vec![random_body(&mut r, start, rad)]
        } else {
            Vec::new()
        };
        let b = Blockers {
            segments: &list,
            circles: &bodies,
        };
        let params = MotionParams {
            wheel: match below(&mut r, 5) {
                0 => uniform(&mut r, 1e-9, 1e-4),
                1 => uniform(&mut r, 10.0, 1e4),
                _ => 2.0,
            },
            search_steps: match below(&mut r, 4) {
                0 => below(&mut r, 41) as u32,
                _ => 20,
            },
            slippery_walls: chance(&mut r, 0.3),
            ..MotionParams::default()
        };
        // Facing the wall, or at a slant, or along it.
        let heading = match below(&mut r, 3) {
            0 => normal,
            1 => along * if chance(&mut r, 0.5) { 1.0 } else { -1.0 },
            _ => random_heading(&mut r),
        };
        let mut p = Pose {
            position: start,
            heading,
        };
        for tick in 0..8 {
            let (left, right) = match below(&mut r, 4) {
                0 => (1.0, 1.0),
                1 => {
                    let x = uniform(&mut r, 1e-7, 1.0);
                    (x, x)
                }
                2 => {
                    let x = uniform(&mut r, 0.0, 1.0);
                    (x, x + uniform(&mut r, -1e-3, 1e-3))
                }
                _ => (uniform(&mut r, -1.0, 1.0), uniform(&mut r, -1.0, 1.0)),
            };
            let got = plan_move(p, left, right, rad, &params, &b);
            let want = reference::plan_move(p, left, right, rad, &params, &b);
            assert!(
                same_bits(&got, &want),
                "case {case} tick {tick}: {got:?} vs reference {want:?}"
            );
            blocked += usize::from(want.blocked);
            stayed += usize::from(want.blocked && want.travelled == 0.0);
            crept += usize::from(want.blocked && want.travelled > 0.0);
            p = want.pose;
        }
    }
    // Both ends of the shortcut: searches that end at the start and searches that move.
    assert!(stayed > 5000, "{stayed} of {blocked}");
    assert!(crept > 2000, "{crept} of {blocked}");
}

/// `plan_move` takes sine and cosine from one `libm::sincos` call from |x| = 2⁻²⁶ on: its bits
/// are those of `libm::sin` and `libm::cos` there, at the kernel thresholds (2⁻²⁶, π/4), the
/// quadrant boundaries of the argument reduction, huge arguments and ±∞, NaN.
#[test]
fn sincos_gives_the_bits_of_sin_and_cos_from_two_to_the_minus_26() {
    let mut r = ChaCha8Rng::seed_from_u64(0x51c0_5026);
    let same = |x: f64| {
        let (s, c) = libm::sincos(x);
        (s.to_bits(), c.to_bits()) == (libm::sin(x).to_bits(), libm::cos(x).to_bits())
            || (s.is_nan() && c.is_nan() && libm::sin(x).is_nan() && libm::cos(x).is_nan())
    };
    let from: f64 = 1.0 / 67_108_864.0;
    let mut special = vec![
        from,
        f64::from_bits(from.to_bits() + 1),
        FRAC_PI_4,
        f64::from_bits(FRAC_PI_4.to_bits() - 1),
        f64::from_bits(FRAC_PI_4.to_bits() + 1),
        f64::from_bits(0x3fe9_21fb_ffff_ffff),
        f64::from_bits(0x3fe9_21fc_0000_0000),
        1e-4,
        f64::INFINITY,
        f64::NAN,
        f64::MAX,
        1e300,
    ];
    for k in 1..200 {
        let q = f64::from(k) * FRAC_PI_2;
        special.extend([
            q,
            f64::from_bits(q.to_bits() - 1),
            f64::from_bits(q.to_bits() + 1),
        ]);
    }
    for x in special {
        assert!(same(x) && same(-x), "{x:e}");
    }
    for _ in 0..200_000 {
        // Log-uniform magnitudes from 2⁻²⁶ to 2⁴⁰, both signs.
        let x = from * libm::pow(2.0, uniform(&mut r, 0.0, 66.0));
        let x = if chance(&mut r, 0.5) { -x } else { x };
        assert!(same(x), "{x:e}");
    }
}

/// Turning angles around the thresholds of the shortcuts (sinc's 1e-4 for φ/2, sincos's 2⁻²⁶
/// for φ/2 and for the blocked move's φ'), free and blocked, match the reference bit for bit.
#[test]
fn small_turns_match_the_reference_bit_for_bit() {
    let mut r = ChaCha8Rng::seed_from_u64(0x5a11_7041);
    let params = MotionParams::default();
    let wall = [seg(-50.0, 20.0, 50.0, 20.0)];
    let mut blocked = 0;
    for case in 0..40_000 {
        // φ = 2π(L − R) for w = 2, so φ/2 = π(L − R): aim L − R around each threshold.
        let half_target = match below(&mut r, 3) {
            0 => 1e-4,
            1 => 1.0 / 67_108_864.0,
            _ => 2.0 / 67_108_864.0,
        };
        let diff = half_target / PI * uniform(&mut r, 0.25, 4.0);
        let right = uniform(&mut r, -1.0, 1.0);
        let left = right + if chance(&mut r, 0.5) { diff } else { -diff };
        let gap = uniform(&mut r, 0.0, 15.0);
        let start = near(&mut r, v(0.0, 20.0 - R - gap), 5.0);
        let p = Pose {
            position: start,
            heading: random_heading_chacha(&mut r),
        };
        let b = if case % 2 == 0 {
            Blockers {
                segments: &wall,
                circles: &[],
            }
        } else {
            Blockers::NONE
        };
        let got = plan_move(p, left, right, R, &params, &b);
        let want = reference::plan_move(p, left, right, R, &params, &b);
        assert!(
            same_bits(&got, &want),
            "case {case}: {got:?} vs reference {want:?}"
        );
        blocked += usize::from(want.blocked);
    }
    assert!(blocked > 2000, "{blocked}");
}

fn random_heading_chacha(r: &mut ChaCha8Rng) -> Vec2 {
    let a = uniform(r, -PI, PI);
    v(libm::cos(a), libm::sin(a))
}

/// `rotate` skips libm for tiny angles (sin x = x below 2⁻²⁶, cos x = 1 below 2⁻²⁷·√2) and
/// takes `sincos` from 2⁻²⁶ on: the same bits as `libm::sin` and `libm::cos` everywhere,
/// around both thresholds, for ±0, subnormals, infinities and NaN.
#[test]
fn rotate_gives_libms_bits_for_tiny_and_threshold_angles() {
    let plain = |u: Vec2, x: f64| {
        let (s, c) = (libm::sin(x), libm::cos(x));
        Vec2::new(u.x * c - u.y * s, u.x * s + u.y * c)
    };
    let mut angles = vec![
        0.0,
        -0.0,
        f64::MIN_POSITIVE,
        5e-324,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NAN,
        1e-4,
        0.3,
        3.0,
        100.0,
    ];
    for threshold in [2f64.powi(-26), 2f64.powi(-27) * 2f64.sqrt(), 2f64.powi(-27)] {
        let mut x = threshold;
        for _ in 0..40 {
            angles.push(x);
            x = f64::from_bits(x.to_bits() + 1);
        }
        let mut x = threshold;
        for _ in 0..40 {
            angles.push(x);
            x = f64::from_bits(x.to_bits() - 1);
        }
    }
    let mut x = 1e-300;
    while x < 1.0 {
        angles.push(x);
        x *= 1.37;
    }
    let u = v(0.6, -0.8);
    for a in angles {
        for x in [a, -a] {
            let (got, want) = (rotate(u, x), plain(u, x));
            assert_eq!(
                (got.x.to_bits(), got.y.to_bits()),
                (want.x.to_bits(), want.y.to_bits()),
                "angle {x:e}"
            );
        }
    }
}

/// The world clamps every command and then calls `plan_clamped_move` (for a positive
/// max_rpt): the same bits as `plan_move` clamping the raw signals, at and near the bounds,
/// for signed zeros, and against walls.
#[test]
fn plan_clamped_move_is_plan_move_for_clamped_signals() {
    let walls = [seg(10.0, -30.0, 10.0, 30.0), seg(-20.0, 12.0, 25.0, 9.0)];
    let blockers = Blockers {
        segments: &walls,
        circles: &[],
    };
    let mut x = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = move || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x >> 11) as f64 / (1u64 << 53) as f64
    };
    for max_rpt in [1.0, 0.37, 2.5, 1e-9, f64::INFINITY] {
        let params = MotionParams {
            max_rpt,
            ..params()
        };
        let clamp = |s: f64| {
            if s.is_nan() {
                0.0
            } else {
                s.clamp(-max_rpt, max_rpt)
            }
        };
        for k in 0..3000 {
            let signal = |n: f64| match k % 7 {
                0 => [0.0, -0.0, max_rpt, -max_rpt][(n * 4.0) as usize],
                1 => f64::NAN,
                2 => 3.0 * (n - 0.5) * max_rpt.min(4.0),
                _ => (2.0 * n - 1.0) * max_rpt.min(4.0),
            };
            let (l, r) = (signal(next()), signal(next()));
            let h = 2.0 * std::f64::consts::PI * next();
            let p = pose(
                -5.0 + 20.0 * next(),
                -5.0 + 20.0 * next(),
                libm::cos(h),
                libm::sin(h),
            );
            let want = plan_move(p, l, r, 3.0, &params, &blockers);
            let got = plan_clamped_move(p, clamp(l), clamp(r), 3.0, &params, &blockers);
            let bits = |o: &MoveOutcome| {
                (
                    [
                        o.pose.position.x,
                        o.pose.position.y,
                        o.pose.heading.x,
                        o.pose.heading.y,
                        o.travelled,
                    ]
                    .map(f64::to_bits),
                    o.blocked,
                    o.blocked_by_wall,
                )
            };
            assert_eq!(bits(&got), bits(&want), "max_rpt {max_rpt}, {l} {r}, {p:?}");
        }
    }
}

/// The pushing shortcut runs before any shortlist is built, so it must agree with every
/// search the shortlists would have run: a wall pushed against among many walls and bodies
/// near the start (more than the 8 prepared candidates of a kind, sometimes more than the
/// 32 of a shortlist), with any number of halvings (0 and 1 included), walls and bodies
/// exactly touching the body at the start, and very short moves; against the reference bit
/// for bit.
#[test]
fn pushing_among_many_blockers_matches_the_reference_bit_for_bit() {
    let mut r = ChaCha8Rng::seed_from_u64(0x5ca1_ab1e);
    let mut blocked = 0;
    for case in 0..800 {
        let (rad, start, heading) = pusher(&mut r, 0.0);
        let gap = match below(&mut r, 3) {
            0 => 0.0,
            1 => uniform(&mut r, 0.0, 1e-9),
            _ => uniform(&mut r, 0.0, 4.0),
        };
        let ahead = start + heading * (rad + gap);
        let across = v(-heading.y, heading.x) * uniform(&mut r, 0.5, 300.0);
        let mut walls = vec![Segment::new(ahead - across, ahead + across)];
        let crowd = match below(&mut r, 3) {
            0 => below(&mut r, 8) as usize,
            1 => 8 + below(&mut r, 20) as usize,
            _ => 33 + below(&mut r, 10) as usize,
        };
        for _ in 0..crowd {
            walls.push(random_wall(&mut r, start, rad));
        }
        // The pushed wall anywhere in the list.
        let at = below(&mut r, walls.len() as u64) as usize;
        walls.swap(0, at);
        let bodies: Vec<Circle> = (0..below(&mut r, 40))
            .map(|_| random_body(&mut r, start, rad))
            .collect();
        let b = Blockers {
            segments: &walls,
            circles: &bodies,
        };
        let params = MotionParams {
            slippery_walls: chance(&mut r, 0.3),
            search_steps: match below(&mut r, 4) {
                0 => 0,
                1 => 1,
                2 => below(&mut r, 60) as u32,
                _ => 20,
            },
            ..MotionParams::default()
        };
        let p = Pose {
            position: start,
            heading,
        };
        blocked += replay(case, p, (rad, &params, &b), 10, || match below(&mut r, 4) {
            0 => (1.0, 1.0),
            1 => {
                let x = uniform(&mut r, 1e-9, 1e-3);
                (x, x)
            }
            2 => (uniform(&mut r, 0.5, 1.0), uniform(&mut r, 0.5, 1.0)),
            _ => (uniform(&mut r, -1.0, 1.0), uniform(&mut r, -1.0, 1.0)),
        });
    }
    assert!(blocked > 2000, "{blocked}");
}
