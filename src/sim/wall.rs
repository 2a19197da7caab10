//! Walls (§4.1) as the running world holds them: segments with opacity, colour and height,
//! plus the precomputed segment lists the hot loops iterate over (all walls block movement
//! and whiskers; only opaque ones stop smells).

use crate::geometry::{Segment, Vec2};
use crate::sim::spec::{WallSpec, WorldSpec, DEFAULT_WALL_COLOUR, DEFAULT_WALL_HEIGHT};
use serde::{Deserialize, Serialize};

/// One wall of a running world.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Wall {
    /// The wall's segment in LU.
    pub segment: Segment,
    /// Stops smells (every wall blocks movement and whiskers).
    pub opaque: bool,
    /// RGB in [0, 1].
    pub colour: [f64; 3],
    /// Height in LU (for the eye).
    pub height: f64,
}

impl Wall {
    /// The wall a `[[world.walls]]` entry describes.
    pub fn from_spec(spec: &WallSpec) -> Wall {
        Wall {
            segment: Segment::new(Vec2::from(spec.from), Vec2::from(spec.to)),
            opaque: spec.opaque,
            colour: spec.colour,
            height: spec.height,
        }
    }
}

/// The walls of a world and the lists the tick loop reads, built once per world.
#[derive(Debug, Clone, PartialEq)]
pub struct Walls {
    walls: Vec<Wall>,
    /// Every wall's segment: what blocks motion and what whiskers feel.
    blocking: Vec<Segment>,
    /// Opaque walls' segments only: what occludes smell. Kept apart so that smell tests do
    /// not skip over transparent walls one by one.
    opaque: Vec<Segment>,
}

impl Walls {
    /// The boundary walls (when `boundary_walls`, clockwise from the top-left corner) followed
    /// by `[[world.walls]]` in file order.
    pub fn build(spec: &WorldSpec) -> Walls {
        let [w, h] = spec.arena;
        let mut walls = Vec::with_capacity(spec.walls.len() + 4);
        if spec.boundary_walls {
            let corners = [
                Vec2::new(0.0, 0.0),
                Vec2::new(w, 0.0),
                Vec2::new(w, h),
                Vec2::new(0.0, h),
            ];
            for i in 0..4 {
                walls.push(Wall {
                    segment: Segment::new(corners[i], corners[(i + 1) % 4]),
                    opaque: true,
                    colour: DEFAULT_WALL_COLOUR,
                    height: DEFAULT_WALL_HEIGHT,
                });
            }
        }
        walls.extend(spec.walls.iter().map(Wall::from_spec));
        let blocking = walls.iter().map(|w| w.segment).collect();
        let opaque = walls
            .iter()
            .filter(|w| w.opaque)
            .map(|w| w.segment)
            .collect();
        Walls {
            walls,
            blocking,
            opaque,
        }
    }

    /// Every wall, boundary walls first.
    pub fn all(&self) -> &[Wall] {
        &self.walls
    }

    /// Segments that block movement and are felt by whiskers.
    pub fn blocking(&self) -> &[Segment] {
        &self.blocking
    }

    /// Segments that stop smells.
    pub fn opaque(&self) -> &[Segment] {
        &self.opaque
    }
}
