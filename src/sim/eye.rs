//! The eye (§7.4): a cyclopean eye at the body centre, `eye_height` above the ground, that
//! renders a `width × height` RGB retina by ray casting.
//!
//! Every wall is a vertical rectangle of its height and colour; food, aversive objects and
//! other living creatures are vertical cylinders of their own radius, height and colour
//! (radius-0 objects are points and are never seen). Each pixel column casts one horizontal
//! ray ([`crate::geometry::ray_segment`], [`crate::geometry::ray_circle`]); a surface met at
//! distance d with height H covers the pixel rows whose elevation e satisfies
//! −eye_height ≤ d·tan e ≤ H − eye_height, and each row shows the nearest surface that covers
//! it, or the background. This gives the painter's image of the report (a tall far wall shows
//! above a low near one) without sorting. With a 1-row retina (e = 0) a surface is seen iff
//! H ≥ eye_height. On equal distance the first surface in the order walls, food, aversive
//! objects, creatures wins.
//!
//! Cylinders are ray-tested only against the columns near their angular extent (one atan2
//! and one asin per object instead of a ray test per column), and walls farther than the
//! eye's range are not ray-tested at all; the exact ray test still decides, and a test checks
//! that culling never changes a pixel. Everything is allocated
//! when the eye is built; rendering allocates nothing.

use crate::geometry::{point_segment_distance_squared, ray_circle, ray_segment, Vec2};
use crate::sim::food::{Aversive, Food};
use crate::sim::gadgets::Thing;
use crate::sim::spec::EyeSpec;
use crate::sim::wall::Wall;
use crate::sim::world::Creature;

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
    eye_height: f64,
    background: [f64; 3],
    /// Largest distance seen, +∞ when unlimited.
    range: f64,
    /// Half the horizontal field of view and the angle between columns, in radians.
    half_fov: f64,
    step: f64,
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
        let row_tan = (0..height)
            .map(|j| {
                if height == 1 {
                    0.0
                } else {
                    libm::tan(0.5 * vfov - (j as f64 + 0.5) * vfov / height as f64)
                }
            })
            .collect();
        Eye {
            width,
            height,
            columns,
            row_tan,
            eye_height: spec.eye_height,
            background: spec.background,
            range: spec.range.unwrap_or(f64::INFINITY),
            half_fov: 0.5 * fov,
            step: fov / width as f64,
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
    /// meets it. With culling, only the columns within one column of its angular extent
    /// (and of the same extent a full turn away, for wide fields of view) are ray-tested:
    /// the margin covers rounding in the angle, and `ray_circle` decides exactly.
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
        // The cylinder's bearing from the heading (positive clockwise) and angular radius.
        let alpha = libm::atan2(look.heading.perp_dot(m), look.heading.dot(m));
        let half = libm::asin((radius / d).min(1.0));
        let max = (self.width - 1) as f64;
        for shift in [0.0, -std::f64::consts::TAU, std::f64::consts::TAU] {
            let (lo, hi) = (alpha + shift - half, alpha + shift + half);
            if hi < -self.half_fov - self.step || lo > self.half_fov + self.step {
                continue;
            }
            // Column i looks at −fov/2 + (i + ½)·step; one column of margin on each side.
            let first = ((lo + self.half_fov) / self.step - 0.5).floor() - 1.0;
            let last = ((hi + self.half_fov) / self.step - 0.5).ceil() + 1.0;
            let columns = first.clamp(0.0, max) as usize..last.clamp(0.0, max) as usize + 1;
            self.columns_hit(out, look.position, columns, centre, radius, height, colour);
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
        for i in columns {
            if let Some(t) = ray_circle(position, self.dirs[i], centre, radius) {
                self.paint(out, i, t, height, colour);
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
            let food: Vec<Food> = (0..30)
                .map(|k| {
                    let kind = FoodKind {
                        radius: uniform(&mut rng, 0.0, 8.0),
                        colour: Some([0.0, 1.0, (k % 2) as f64]),
                        height: Some(uniform(&mut rng, 0.0, 12.0)),
                        ..FoodKind::default()
                    };
                    let p = Vec2::new(uniform(&mut rng, 0.0, 100.0), uniform(&mut rng, 0.0, 100.0));
                    Food::new(0, &kind, p)
                })
                .collect();
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
            let mut culled = vec![0.0; eye.len()];
            let mut full = vec![1.0; eye.len()];
            eye.render_with(&scene, position, heading, usize::MAX, &mut culled, true);
            eye.render_with(&scene, position, heading, usize::MAX, &mut full, false);
            if culled != full {
                differing += 1;
            }
            seen += culled
                .chunks(3)
                .filter(|p| p[1] == 1.0 && p[0] == 0.0)
                .count();
        }
        assert_eq!(differing, 0);
        assert!(
            seen > 100,
            "too few food pixels ({seen}) for the test to mean much"
        );
    }
}
