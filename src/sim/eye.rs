//! The eye (§7.4): a cyclopean eye at the body centre, `eye_height` above the ground, that
//! renders a `width × height` RGB retina by ray casting.
//!
//! Every wall is a vertical rectangle of its height and colour; food, aversive objects and
//! other living creatures are vertical cylinders of their own radius, height and colour
//! with a flat top (radius-0 objects are points and are never seen). Each pixel column casts
//! one horizontal ray ([`crate::geometry::ray_segment`], [`crate::geometry::ray_circle`]); a
//! surface met at distance d with height H covers the pixel rows whose elevation e satisfies
//! −eye_height ≤ d·tan e ≤ H − eye_height, and each row shows the nearest surface that covers
//! it, or the background. This gives the painter's image of the report (a tall far wall shows
//! above a low near one) without sorting. With a 1-row retina (e = 0) a surface is seen iff
//! H ≥ eye_height. On equal distance the first surface in the order walls, food, aversive
//! objects, creatures wins.
//!
//! A row looking down (e < 0) whose ray passes over the rim of a cylinder lower than the eye
//! (H < eye_height) meets its top disc where it has come down to height H, at distance
//! (H − eye_height) / tan e, if that is before the ray leaves the cylinder's circle: the row
//! shows the object there (SPEC-NOTES, Eye), so a multi-row retina sees low objects from
//! above. Walls have no thickness, so their top is a line a ray never meets: a row that
//! passes over a wall sees what lies beyond it. An eye whose rows all look level or up (every
//! 1-row retina) never meets a top and does not look for one.
//!
//! Cylinders are ray-tested only against the columns within their angular extent widened by
//! a small slack (two polynomial arctangents per object instead of a ray test per column),
//! and walls farther than the eye's range are not ray-tested at all; the exact ray test still decides, and a test checks
//! that culling never changes a pixel. Everything is allocated
//! when the eye is built; rendering allocates nothing.

use crate::geometry::{point_segment_distance_squared, ray_circle, ray_segment, Vec2};
use crate::sim::creature::Creature;
use crate::sim::food::{Aversive, Food};
use crate::sim::gadgets::Thing;
use crate::sim::spec::EyeSpec;
use crate::sim::wall::Wall;

/// Margin in radians added on each side of a cylinder's approximate angular extent. It must
/// dominate the error of the bearing and of the angular radius (each ≤ 1.2e-5 rad from
/// [`atan2_bound`], plus rounding far below that, even for an eye just outside the cylinder),
/// so that no column whose ray can meet the cylinder is left out. It is small against the
/// narrowest column (a 4,096-pixel retina over a full turn: 1.5e-3 rad), so it rarely adds
/// a column to be tested.
const ANGLE_SLACK: f64 = 1e-4;

/// atan2(y, x) in (−π, π] within 1.2e-5 rad, for the column range of a cylinder: the
/// 9th-degree polynomial of Abramowitz & Stegun 4.4.47 (error about 1e-5 on [0, 1]) after
/// reducing to the first octant; a test measures the bound over all directions. Both zero
/// gives NaN (0/0), which the caller treats as "no range known".
#[inline]
fn atan2_bound(y: f64, x: f64) -> f64 {
    let (ax, ay) = (x.abs(), y.abs());
    let t = ax.min(ay) / ax.max(ay);
    let t2 = t * t;
    let mut a = t
        * (0.999_866_0
            + t2 * (-0.330_299_5 + t2 * (0.180_141_0 + t2 * (-0.085_133_0 + t2 * 0.020_835_1))));
    if ay > ax {
        a = std::f64::consts::FRAC_PI_2 - a;
    }
    if x < 0.0 {
        a = std::f64::consts::PI - a;
    }
    if y < 0.0 {
        -a
    } else {
        a
    }
}

/// Where a ray from `origin` along `dir` that meets the circle (see
/// [`crate::geometry::ray_circle`]) leaves it: the far root of |origin + t·dir − centre| =
/// radius, written so that it does not cancel (as `ray_circle` does for the near root).
/// NaN for a zero `dir`, which then meets no top.
#[inline]
fn ray_circle_exit(origin: Vec2, dir: Vec2, centre: Vec2, radius: f64) -> f64 {
    let m = origin - centre;
    let a = dir.length_squared();
    let b = m.dot(dir);
    let c = m.length_squared() - radius * radius;
    let cross = m.perp_dot(dir);
    let root = (a * (radius * radius) - cross * cross).max(0.0).sqrt();
    if b <= 0.0 {
        (root - b) / a
    } else {
        // Inside the circle (c ≤ 0) and pointing away from the centre: the product of the
        // roots is c/a, and the near one (−b − root)/a is ≤ 0.
        c / (-b - root)
    }
}

/// What the eye can see.
pub struct Scene<'a> {
    /// Every wall.
    pub walls: &'a [Wall],
    /// Food objects.
    pub food: &'a [Food],
    /// Aversive objects.
    pub aversives: &'a [Aversive],
    /// Every creature (dead ones and the seeing one are skipped).
    pub creatures: &'a [Creature],
    /// Body radius of every creature in LU.
    pub creature_radius: f64,
    /// Body colour of every creature.
    pub creature_colour: [f64; 3],
    /// Body height of every creature in LU.
    pub creature_height: f64,
    /// Wanderers, predators and gadgets; those marked `seen` with radius > 0 are cylinders.
    pub things: &'a [Thing],
}

/// An eye with its precomputed ray directions and its scratch depth buffer.
#[derive(Debug, Clone, PartialEq)]
pub struct Eye {
    width: usize,
    height: usize,
    /// (cos, sin) of each column's angle from the heading, positive clockwise.
    columns: Vec<(f64, f64)>,
    /// tan of each row's elevation, top row first.
    row_tan: Vec<f64>,
    /// Some row looks down (tan e < 0), so it may see the top of a cylinder lower than the
    /// eye.
    looks_down: bool,
    eye_height: f64,
    background: [f64; 3],
    /// Largest distance seen, +∞ when unlimited.
    range: f64,
    /// Columns per radian (width / fov), the column index looking straight ahead
    /// (fov/2 / step − ½), and columns per full turn: they map a bearing to the (fractional)
    /// index of the column looking that way.
    columns_per_radian: f64,
    column_offset: f64,
    columns_per_turn: f64,
    /// Scratch: each column's ray direction for the current render.
    dirs: Vec<Vec2>,
    /// Scratch: distance of what each pixel shows, row-major.
    depth: Vec<f64>,
}

/// Where the eye is and whether to cull, for one render.
struct Look {
    position: Vec2,
    heading: Vec2,
    cull: bool,
}

impl Eye {
    /// The eye `spec` describes (angles in degrees, see [`EyeSpec`]).
    pub fn new(spec: &EyeSpec) -> Eye {
        let width = spec.width as usize;
        let height = spec.height as usize;
        let fov = spec.fov.to_radians();
        let columns = (0..width)
            .map(|i| {
                let a = -0.5 * fov + (i as f64 + 0.5) * fov / width as f64;
                (libm::cos(a), libm::sin(a))
            })
            .collect();
        let vfov = spec.vertical_fov.to_radians();
        let row_tan: Vec<f64> = (0..height)
            .map(|j| {
                if height == 1 {
                    0.0
                } else {
                    libm::tan(0.5 * vfov - (j as f64 + 0.5) * vfov / height as f64)
                }
            })
            .collect();
        let looks_down = row_tan.iter().any(|&t| t < 0.0);
        Eye {
            width,
            height,
            columns,
            row_tan,
            looks_down,
            eye_height: spec.eye_height,
            background: spec.background,
            range: spec.range.unwrap_or(f64::INFINITY),
            columns_per_radian: width as f64 / fov,
            column_offset: 0.5 * width as f64 - 0.5,
            columns_per_turn: std::f64::consts::TAU * width as f64 / fov,
            dirs: vec![Vec2::X; width],
            depth: vec![f64::INFINITY; width * height],
        }
    }

    /// Retina `[width, height]` in pixels.
    pub fn size(&self) -> [usize; 2] {
        [self.width, self.height]
    }

    /// Number of values a retina holds (3 per pixel).
    pub fn len(&self) -> usize {
        3 * self.width * self.height
    }

    /// Never true: a retina has at least one pixel.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Renders what an eye at `position` looking along unit `heading` sees into `out`
    /// (`len()` values: row-major, top row first, left column first, R, G, B per pixel).
    /// Creature `me` (the one seeing) is not seen; pass `usize::MAX` to see every creature.
    ///
    /// # Panics
    /// When `out` is shorter than `len()` (a programming error).
    pub fn render(
        &mut self,
        scene: &Scene<'_>,
        position: Vec2,
        heading: Vec2,
        me: usize,
        out: &mut [f64],
    ) {
        self.render_with(scene, position, heading, me, out, true);
    }

    /// [`Eye::render`]; `cull` tests each cylinder only against the columns near its
    /// angular extent (the exact ray test still decides), else against every column.
    fn render_with(
        &mut self,
        scene: &Scene<'_>,
        position: Vec2,
        heading: Vec2,
        me: usize,
        out: &mut [f64],
        cull: bool,
    ) {
        let w = self.width;
        for (i, &(c, s)) in self.columns.iter().enumerate() {
            // Rotation by +angle (clockwise on screen), as eq. 32.
            self.dirs[i] = Vec2::new(heading.x * c - heading.y * s, heading.x * s + heading.y * c);
        }
        self.depth.fill(f64::INFINITY);
        for pixel in out[..3 * w * self.height].chunks_exact_mut(3) {
            pixel.copy_from_slice(&self.background);
        }
        // With culling, a wall farther than the eye's range (plus a margin far above the
        // rounding of a ray's distance) is skipped: every ray would meet it beyond the range,
        // where `paint` shows nothing. In a large arena most walls are that far.
        let reach = self.range * (1.0 + 1e-9) + 1e-9;
        let reach_squared = reach * reach;
        for wall in scene.walls {
            if cull && point_segment_distance_squared(position, &wall.segment) > reach_squared {
                continue;
            }
            for i in 0..w {
                if let Some(t) = ray_segment(position, self.dirs[i], &wall.segment) {
                    self.paint(out, i, t, wall.height, &wall.colour);
                }
            }
        }
        let look = Look {
            position,
            heading,
            cull,
        };
        // Most objects of a large world are beyond the eye's range: reject them here with a
        // few inline comparisons instead of a call each.
        let range = self.range;
        let far = |centre: Vec2, radius: f64| {
            let reach = (range + radius) * (1.0 + 1e-9) + 1e-9;
            cull && (centre - position).length_squared() > reach * reach
        };
        for f in scene.food {
            if !far(f.position, f.radius) {
                self.cylinder(out, &look, f.position, f.radius, f.height, &f.colour);
            }
        }
        for a in scene.aversives {
            if !far(a.position, a.radius) {
                self.cylinder(out, &look, a.position, a.radius, a.height, &a.colour);
            }
        }
        for (k, other) in scene.creatures.iter().enumerate() {
            if k != me && other.alive {
                self.cylinder(
                    out,
                    &look,
                    other.pose.position,
                    scene.creature_radius,
                    scene.creature_height,
                    &scene.creature_colour,
                );
            }
        }
        for t in scene.things {
            if t.seen && t.radius > 0.0 {
                self.cylinder(out, &look, t.position, t.radius, t.height, &t.colour);
            }
        }
    }

    /// Paints a cylinder (radius > 0; points are never seen) into every column whose ray
    /// meets it. With culling, only the columns within ANGLE_SLACK of its angular extent
    /// (and of the same extent a full turn away, for wide fields of view) are ray-tested:
    /// the slack covers the error of the approximate angles, and `ray_circle` decides
    /// exactly.
    fn cylinder(
        &mut self,
        out: &mut [f64],
        look: &Look,
        centre: Vec2,
        radius: f64,
        height: f64,
        colour: &[f64; 3],
    ) {
        if radius <= 0.0 {
            return;
        }
        let m = centre - look.position;
        let d2 = m.length_squared();
        if !look.cull || d2 <= radius * radius {
            // No culling, or the eye is inside the cylinder: every column.
            self.columns_hit(
                out,
                look.position,
                0..self.width,
                centre,
                radius,
                height,
                colour,
            );
            return;
        }
        let d = d2.sqrt();
        if d - radius > self.range {
            return;
        }
        // The cylinder's bearing from the heading (positive clockwise) and angular radius
        // asin(radius / d), both from a polynomial arctangent whose error (≤ 1.2e-5 rad each)
        // is dominated by ANGLE_SLACK, so the column range below can only come out wider
        // than the exact one. libm's atan2 and asin cost several times as much.
        let alpha = atan2_bound(look.heading.perp_dot(m), look.heading.dot(m));
        let half = atan2_bound(radius, (d2 - radius * radius).sqrt());
        // In column units: column i looks at −fov/2 + (i + ½)·step, i.e. at u = i.
        let mid = alpha * self.columns_per_radian + self.column_offset;
        let spread = (half + ANGLE_SLACK) * self.columns_per_radian;
        let (lo, hi) = (mid - spread, mid + spread);
        if !(lo.is_finite() && hi.is_finite()) {
            // A zero or non-finite heading, or coordinates so large that squares overflow:
            // no range can be trusted, so every column decides by ray test.
            self.columns_hit(
                out,
                look.position,
                0..self.width,
                centre,
                radius,
                height,
                colour,
            );
            return;
        }
        let max = (self.width - 1) as f64;
        // The extent as seen, and the same extent a full turn to either side (it can reach
        // into a wide field of view from behind). The three never share a column, as the
        // extent is at most half a turn wide; a shared column would only be painted twice
        // with the same distance, which changes nothing.
        for shift in [0.0, -self.columns_per_turn, self.columns_per_turn] {
            let (a, b) = (lo + shift, hi + shift);
            if b < 0.0 || a > max {
                continue;
            }
            // First column i ≥ a and last i ≤ b, within the retina. Here a ≤ max and b ≥ 0,
            // so the truncating casts are floors of non-negative values in range.
            let first = if a <= 0.0 {
                0
            } else {
                let t = a as usize;
                t + usize::from((t as f64) < a)
            };
            let last = if b >= max { self.width - 1 } else { b as usize };
            if first <= last {
                self.columns_hit(
                    out,
                    look.position,
                    first..last + 1,
                    centre,
                    radius,
                    height,
                    colour,
                );
            }
        }
    }

    /// Ray-tests the cylinder against `columns` and paints where it is hit.
    #[allow(clippy::too_many_arguments)]
    #[inline]
    fn columns_hit(
        &mut self,
        out: &mut [f64],
        position: Vec2,
        columns: std::ops::Range<usize>,
        centre: Vec2,
        radius: f64,
        height: f64,
        colour: &[f64; 3],
    ) {
        if self.looks_down && height < self.eye_height {
            for i in columns {
                let dir = self.dirs[i];
                if let Some(t) = ray_circle(position, dir, centre, radius) {
                    self.paint(out, i, t, height, colour);
                    let exit = ray_circle_exit(position, dir, centre, radius);
                    self.paint_top(out, i, t, exit, height, colour);
                }
            }
            return;
        }
        for i in columns {
            if let Some(t) = ray_circle(position, self.dirs[i], centre, radius) {
                self.paint(out, i, t, height, colour);
            }
        }
    }

    /// The top disc, at height `height` below the eye, of a cylinder that column `i`'s ray
    /// enters at distance `t` and leaves at `exit`: each row looking down whose ray comes
    /// down to that height at a distance in [t, exit] (so passes over the rim and meets the
    /// disc) shows it there, where nothing nearer does. A row that met the side at t meets
    /// the height at or before t, so only at the rim (the same distance) do both hold.
    #[inline(never)]
    fn paint_top(
        &mut self,
        out: &mut [f64],
        i: usize,
        t: f64,
        exit: f64,
        height: f64,
        colour: &[f64; 3],
    ) {
        let top = height - self.eye_height;
        for j in 0..self.height {
            let tan = self.row_tan[j];
            if tan >= 0.0 {
                continue;
            }
            // top < 0 and tan < 0: the ray is at the top's height this far out.
            let d = top / tan;
            let q = j * self.width + i;
            if d >= t && d <= exit && d <= self.range && d < self.depth[q] {
                self.depth[q] = d;
                let p = 3 * q;
                out[p..p + 3].copy_from_slice(colour);
            }
        }
    }

    /// A surface of height `height` and colour `colour` met at distance `t` along column
    /// `i`'s ray: it shows in every row it covers where nothing nearer does.
    #[inline]
    fn paint(&mut self, out: &mut [f64], i: usize, t: f64, height: f64, colour: &[f64; 3]) {
        if t > self.range {
            return;
        }
        let top = height - self.eye_height;
        let bottom = -self.eye_height;
        for j in 0..self.height {
            let e = self.row_tan[j] * t;
            let q = j * self.width + i;
            if t < self.depth[q] && e <= top && e >= bottom {
                self.depth[q] = t;
                let p = 3 * q;
                out[p..p + 3].copy_from_slice(colour);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Segment;
    use crate::seed::{stream, uniform, Generation, IndividualId, Purpose, Seed, TrialIndex};
    use crate::sim::spec::{AversiveKind, FoodKind};

    /// `n` food objects of radius up to `max_radius` and height up to 12 at random places in
    /// a 100 × 100 square, alternately pure green and green-blue.
    fn random_food(rng: &mut crate::seed::Rng, n: usize, max_radius: f64) -> Vec<Food> {
        (0..n)
            .map(|k| {
                let kind = FoodKind {
                    radius: uniform(rng, 0.0, max_radius),
                    colour: Some([0.0, 1.0, (k % 2) as f64]),
                    height: Some(uniform(rng, 0.0, 12.0)),
                    ..FoodKind::default()
                };
                let p = Vec2::new(uniform(rng, 0.0, 100.0), uniform(rng, 0.0, 100.0));
                Food::new(0, &kind, p)
            })
            .collect()
    }

    /// Renders `scene` with and without culling: whether the retinas are the same, and how
    /// many pure green (food) pixels the culled one shows.
    fn render_both_ways(
        eye: &mut Eye,
        scene: &Scene<'_>,
        position: Vec2,
        heading: Vec2,
    ) -> (bool, usize) {
        let mut culled = vec![0.0; eye.len()];
        let mut full = vec![1.0; eye.len()];
        eye.render_with(scene, position, heading, usize::MAX, &mut culled, true);
        eye.render_with(scene, position, heading, usize::MAX, &mut full, false);
        let food = culled
            .chunks(3)
            .filter(|p| p[1] == 1.0 && p[0] == 0.0)
            .count();
        (culled == full, food)
    }

    /// Culling must never change a pixel: random scenes, poses and eyes (fields of view up to
    /// a full turn, objects around, beside and on top of the eye) render bit-identically with
    /// and without it.
    #[test]
    fn culling_changes_nothing() {
        let mut rng = stream(
            Seed(3),
            Purpose::TrialWorld,
            Generation(0),
            IndividualId(0),
            TrialIndex(0),
        );
        let mut differing = 0;
        let mut seen = 0;
        for trial in 0..200 {
            let spec = EyeSpec {
                fov: [30.0, 90.0, 179.0, 270.0, 360.0][trial % 5],
                width: 1 + (trial as u64 * 7) % 40,
                height: 1 + (trial as u64) % 4,
                range: (trial % 3 == 0).then_some(60.0),
                ..EyeSpec::default()
            };
            let mut eye = Eye::new(&spec);
            let walls: Vec<Wall> = (0..3)
                .map(|_| Wall {
                    segment: Segment::new(
                        Vec2::new(uniform(&mut rng, 0.0, 100.0), uniform(&mut rng, 0.0, 100.0)),
                        Vec2::new(uniform(&mut rng, 0.0, 100.0), uniform(&mut rng, 0.0, 100.0)),
                    ),
                    opaque: true,
                    colour: [0.5, 0.5, 0.5],
                    height: uniform(&mut rng, 0.0, 20.0),
                })
                .collect();
            let food = random_food(&mut rng, 30, 8.0);
            let aversives: Vec<Aversive> = (0..10)
                .map(|_| {
                    let kind = AversiveKind {
                        radius: uniform(&mut rng, 0.5, 4.0),
                        ..AversiveKind::default()
                    };
                    let p = Vec2::new(uniform(&mut rng, 0.0, 100.0), uniform(&mut rng, 0.0, 100.0));
                    Aversive::new(0, &kind, p)
                })
                .collect();
            let scene = Scene {
                walls: &walls,
                food: &food,
                aversives: &aversives,
                creatures: &[],
                things: &[],
                creature_radius: 3.0,
                creature_colour: [0.0, 0.0, 1.0],
                creature_height: 6.0,
            };
            let position = Vec2::new(uniform(&mut rng, 0.0, 100.0), uniform(&mut rng, 0.0, 100.0));
            let a = uniform(&mut rng, -4.0, 4.0);
            let heading = Vec2::new(libm::cos(a), libm::sin(a));
            let (same, food_pixels) = render_both_ways(&mut eye, &scene, position, heading);
            differing += usize::from(!same);
            seen += food_pixels;
        }
        assert_eq!(differing, 0);
        assert!(
            seen > 100,
            "too few food pixels ({seen}) for the test to mean much"
        );
    }

    /// The polynomial arctangent stays within the error that ANGLE_SLACK must dominate
    /// (twice: bearing and angular radius), over all octants, the axes and near them.
    #[test]
    fn atan2_bound_error_is_dominated_by_the_slack() {
        let mut worst: f64 = 0.0;
        let n = 200_000;
        for k in 0..n {
            let a = -std::f64::consts::PI + std::f64::consts::TAU * k as f64 / n as f64;
            for r in [1e-3, 1.0, 7.5, 1e6] {
                let (y, x) = (r * libm::sin(a), r * libm::cos(a));
                let err = (atan2_bound(y, x) - libm::atan2(y, x)).abs();
                // ±π are the same direction.
                let err = err.min((err - std::f64::consts::TAU).abs());
                worst = worst.max(err);
            }
        }
        for (y, x) in [(0.0, 1.0), (1.0, 0.0), (0.0, -1.0), (-1.0, 0.0), (1.0, 1.0)] {
            let err = (atan2_bound(y, x) - libm::atan2(y, x)).abs();
            worst = worst.max(err.min((err - std::f64::consts::TAU).abs()));
        }
        assert!(worst <= 1.2e-5, "atan2_bound error {worst}");
        assert!(4.0 * worst < ANGLE_SLACK);
        assert!(atan2_bound(0.0, 0.0).is_nan());
    }

    /// Culling changes nothing on wide retinas (up to 4,096 columns, whose columns are far
    /// narrower than the slack's worth of extra columns matters), full turns, 1-row and
    /// multi-row retinas, an eye inside or just outside a cylinder, and objects exactly at
    /// the eye's range.
    #[test]
    fn culling_changes_nothing_on_wide_retinas_and_edge_cases() {
        let mut rng = stream(
            Seed(11),
            Purpose::TrialWorld,
            Generation(0),
            IndividualId(0),
            TrialIndex(0),
        );
        let mut differing = 0;
        let mut seen = 0;
        for trial in 0..60 {
            let spec = EyeSpec {
                fov: [360.0, 359.0, 180.0, 1.0, 360.0, 90.0][trial % 6],
                width: [4096, 1000, 30, 1, 777, 2][trial % 5],
                height: [1, 3, 1, 2][trial % 4],
                range: (trial % 3 != 2).then_some(40.0),
                ..EyeSpec::default()
            };
            let mut eye = Eye::new(&spec);
            let position = Vec2::new(uniform(&mut rng, 20.0, 80.0), uniform(&mut rng, 20.0, 80.0));
            let a = uniform(&mut rng, -4.0, 4.0);
            let heading = Vec2::new(libm::cos(a), libm::sin(a));
            let mut food = random_food(&mut rng, 25, 6.0);
            // Around the eye: exactly at the range (centre at range + radius), the eye
            // inside, on the rim and just outside.
            for (k, (distance, radius)) in [
                (40.0 + 3.0, 3.0),
                (40.0 + 0.5, 0.5),
                (1.0, 4.0),
                (2.0, 2.0),
                (2.0 + 1e-12, 2.0),
                (5.0, 4.999_999),
            ]
            .into_iter()
            .enumerate()
            {
                let b = uniform(&mut rng, -4.0, 4.0);
                let kind = FoodKind {
                    radius,
                    colour: Some([0.0, 1.0, (k % 2) as f64]),
                    height: Some(10.0),
                    ..FoodKind::default()
                };
                let p = position + distance * Vec2::new(libm::cos(b), libm::sin(b));
                food.push(Food::new(0, &kind, p));
            }
            let aversives: Vec<Aversive> = (0..8)
                .map(|_| {
                    let kind = AversiveKind {
                        radius: uniform(&mut rng, 0.5, 4.0),
                        ..AversiveKind::default()
                    };
                    let p = Vec2::new(uniform(&mut rng, 0.0, 100.0), uniform(&mut rng, 0.0, 100.0));
                    Aversive::new(0, &kind, p)
                })
                .collect();
            let scene = Scene {
                walls: &[],
                food: &food,
                aversives: &aversives,
                creatures: &[],
                things: &[],
                creature_radius: 3.0,
                creature_colour: [0.0, 0.0, 1.0],
                creature_height: 6.0,
            };
            let (same, food_pixels) = render_both_ways(&mut eye, &scene, position, heading);
            differing += usize::from(!same);
            seen += food_pixels;
        }
        assert_eq!(differing, 0);
        assert!(
            seen > 1000,
            "too few food pixels ({seen}) for the test to mean much"
        );
    }
}
