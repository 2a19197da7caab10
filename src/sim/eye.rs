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
//! Everything is allocated when the eye is built; rendering allocates nothing.

use crate::geometry::{ray_circle, ray_segment, Vec2};
use crate::sim::food::{Aversive, Food};
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
    /// Distance of what each row of the current column shows.
    depth: Vec<f64>,
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
            depth: vec![f64::INFINITY; height],
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
        let w = self.width;
        for i in 0..w {
            let (c, s) = self.columns[i];
            // Rotation by +angle (clockwise on screen), as eq. 32.
            let dir = Vec2::new(heading.x * c - heading.y * s, heading.x * s + heading.y * c);
            self.depth.fill(f64::INFINITY);
            for j in 0..self.height {
                let p = 3 * (j * w + i);
                out[p..p + 3].copy_from_slice(&self.background);
            }
            for wall in scene.walls {
                if let Some(t) = ray_segment(position, dir, &wall.segment) {
                    self.paint(out, i, t, wall.height, &wall.colour);
                }
            }
            for f in scene.food {
                if f.radius > 0.0 {
                    if let Some(t) = ray_circle(position, dir, f.position, f.radius) {
                        self.paint(out, i, t, f.height, &f.colour);
                    }
                }
            }
            for a in scene.aversives {
                if a.radius > 0.0 {
                    if let Some(t) = ray_circle(position, dir, a.position, a.radius) {
                        self.paint(out, i, t, a.height, &a.colour);
                    }
                }
            }
            if scene.creature_radius > 0.0 {
                for (k, other) in scene.creatures.iter().enumerate() {
                    if k != me && other.alive {
                        if let Some(t) =
                            ray_circle(position, dir, other.pose.position, scene.creature_radius)
                        {
                            self.paint(out, i, t, scene.creature_height, &scene.creature_colour);
                        }
                    }
                }
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
            if t < self.depth[j] && e <= top && e >= bottom {
                self.depth[j] = t;
                let p = 3 * (j * self.width + i);
                out[p..p + 3].copy_from_slice(colour);
            }
        }
    }
}
