//! Walls (§4.1) as the running world holds them: segments with opacity, colour and height,
//! plus the precomputed segment lists the hot loops iterate over (all walls block movement
//! and whiskers; only opaque ones stop smells).

use crate::geometry::{BoxedSegment, Segment, Vec2};
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
    /// Boundary and interior walls, which never change.
    fixed: Vec<Wall>,
    /// Locked doors (§4.5.2), in file order, and whether each is open.
    doors: Vec<Wall>,
    open: Vec<bool>,
    /// The walls standing now: `fixed` then the closed doors. The lists below follow it; they
    /// are rebuilt (within their reserved capacity, so without allocating) only when a door
    /// opens or closes.
    walls: Vec<Wall>,
    /// Every wall's segment: what blocks motion.
    blocking: Vec<Segment>,
    /// The same with boxes: what whiskers feel.
    felt: Vec<BoxedSegment>,
    /// Opaque walls only: what occludes smell. Kept apart so that smell tests do not skip
    /// over transparent walls one by one.
    opaque: Vec<BoxedSegment>,
    /// How many of `opaque` are fixed walls (they come first; the closed opaque doors follow).
    fixed_opaque: usize,
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
        let doors: Vec<Wall> = spec
            .doors
            .iter()
            .map(|d| Wall {
                segment: Segment::new(Vec2::from(d.from), Vec2::from(d.to)),
                opaque: d.opaque,
                colour: d.colour,
                height: d.height,
            })
            .collect();
        let n = walls.len() + doors.len();
        let fixed_opaque = walls.iter().filter(|w| w.opaque).count();
        let mut built = Walls {
            fixed_opaque,
            open: vec![false; doors.len()],
            fixed: walls,
            doors,
            walls: Vec::with_capacity(n),
            blocking: Vec::with_capacity(n),
            felt: Vec::with_capacity(n),
            opaque: Vec::with_capacity(n),
        };
        built.refresh();
        built
    }

    /// Rebuilds the standing walls and their lists from `fixed`, `doors` and `open`.
    fn refresh(&mut self) {
        self.walls.clear();
        self.walls.extend_from_slice(&self.fixed);
        for (door, &open) in self.doors.iter().zip(&self.open) {
            if !open {
                self.walls.push(*door);
            }
        }
        self.blocking.clear();
        self.blocking.extend(self.walls.iter().map(|w| w.segment));
        self.felt.clear();
        self.felt
            .extend(self.blocking.iter().copied().map(BoxedSegment::new));
        self.opaque.clear();
        self.opaque.extend(
            self.walls
                .iter()
                .filter(|w| w.opaque)
                .map(|w| BoxedSegment::new(w.segment)),
        );
    }

    /// Opens or closes door `door` (index in `[[world.doors]]`).
    pub fn set_door_open(&mut self, door: usize, open: bool) {
        if self.open[door] != open {
            self.open[door] = open;
            self.refresh();
        }
    }

    /// Is door `door` open?
    pub fn door_open(&self, door: usize) -> bool {
        self.open[door]
    }

    /// Every wall standing now: boundary walls first, then interior walls, then closed doors.
    pub fn all(&self) -> &[Wall] {
        &self.walls
    }

    /// The boundary and interior walls (standing always), boundary walls first.
    pub fn fixed(&self) -> &[Wall] {
        &self.fixed
    }

    /// Every locked door's wall, open or closed, in file order.
    pub fn doors(&self) -> &[Wall] {
        &self.doors
    }

    /// Segments that block movement (every wall).
    pub fn blocking(&self) -> &[Segment] {
        &self.blocking
    }

    /// Segments whiskers feel (every wall), with boxes.
    pub fn felt(&self) -> &[BoxedSegment] {
        &self.felt
    }

    /// Segments that stop smells, with boxes.
    pub fn opaque(&self) -> &[BoxedSegment] {
        &self.opaque
    }

    /// How many walls can stand at once (fixed ones and every door).
    pub fn capacity(&self) -> usize {
        self.fixed.len() + self.doors.len()
    }

    /// How many opaque walls can stand at once (fixed ones and every opaque door).
    pub fn opaque_capacity(&self) -> usize {
        self.fixed_opaque + self.doors.iter().filter(|d| d.opaque).count()
    }

    /// How many of [`Walls::felt`] are fixed walls (boundary and interior, which never
    /// change): they come first, the closed doors follow.
    pub fn fixed_count(&self) -> usize {
        self.fixed.len()
    }

    /// How many of [`Walls::opaque`] are fixed walls: they come first, the closed opaque doors
    /// follow.
    pub fn fixed_opaque_count(&self) -> usize {
        self.fixed_opaque
    }
}
