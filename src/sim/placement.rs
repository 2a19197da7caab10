//! Building a trial world's contents: explicit objects, then random placement rules
//! (uniform in a region, minimum spacing, optional grid, never touching a wall), then the
//! creatures' start poses. Every random draw comes from the world's generator, in a fixed
//! order, so a seed always gives the same world.

use crate::geometry::{circle_touches_segment, circles_touch, Segment, Vec2};
use crate::seed::{below, uniform, Rng};
use crate::sim::food::{Aversive, Food};
use crate::sim::motion::Pose;
use crate::sim::spec::{grid_span, KindSpec, PlaceSpec, Region, WorldSpec, MAX_CREATURES};
use crate::validate::InvalidValue;
use std::collections::BTreeMap;
use thiserror::Error;

/// Attempts per object or creature before placement gives up. Generous enough that a region
/// filled to a reasonable density always succeeds, small enough that an impossible rule fails
/// in well under a second.
pub const MAX_ATTEMPTS: u32 = 10_000;

/// Why a trial world could not be built.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum PlacementError {
    /// The world or creature specification failed validation.
    #[error("invalid specification: {0}")]
    Invalid(#[from] InvalidValue),
    /// A placement rule found no free spot for one of its objects.
    #[error(
        "cannot place object {number} of {count} of kind `{kind}` (`world.place[{rule}]`): \
         no position in the region at least {min_spacing} LU from every earlier object and \
         touching no wall found in {attempts} attempts; lower the count or min_spacing, or \
         enlarge the region"
    )]
    Object {
        /// Index of the rule in `[[world.place]]`.
        rule: usize,
        /// The kind being placed.
        kind: String,
        /// Which object of the rule failed, counted from 1.
        number: u64,
        /// How many the rule asked for.
        count: u64,
        /// The rule's minimum spacing in LU.
        min_spacing: f64,
        /// Attempts made for this object.
        attempts: u32,
    },
    /// No free start position for a creature.
    #[error(
        "cannot place creature {number} of {count} in `world.start.region`: no position \
         touching no wall, creature, food or aversive object found in {attempts} attempts"
    )]
    Creature {
        /// Which creature failed, counted from 1.
        number: usize,
        /// How many creatures were asked for.
        count: usize,
        /// Attempts made for this creature.
        attempts: u32,
    },
    /// No free start position for a wanderer or ground predator.
    #[error(
        "cannot place {what}: no position touching no wall, creature or wanderer found in \
         {attempts} attempts"
    )]
    Actor {
        /// Which one failed.
        what: String,
        /// Attempts made.
        attempts: u32,
    },
    /// More creatures than the simulator supports.
    #[error("cannot place {count} creatures: at most {max} creatures per world")]
    TooManyCreatures {
        /// How many were asked for.
        count: usize,
        /// The limit ([`MAX_CREATURES`]).
        max: usize,
    },
}

/// A uniform-grid bucket index over the arena for "is anything near this point" queries:
/// placement of thousands of objects with a minimum spacing would otherwise cost a scan of
/// every earlier object per attempt. Cells are at least `reach` wide, so every point within
/// `reach` of a query lies in the 3 x 3 cells around it. Buckets are singly linked lists in
/// two flat vectors (no allocation per cell).
struct NearIndex {
    cell: f64,
    nx: usize,
    ny: usize,
    /// First entry of each cell, or `NONE`.
    heads: Vec<u32>,
    /// Next entry in the same cell, or `NONE`, per entry.
    next: Vec<u32>,
    /// Each entry's position.
    points: Vec<Vec2>,
}

const NONE: u32 = u32::MAX;

impl NearIndex {
    /// An index over `[0, w] x [0, h]` for queries up to distance `reach`, sized for about
    /// `expected` entries (about one per cell when `reach` is small).
    fn new(arena: [f64; 2], reach: f64, expected: usize) -> NearIndex {
        let [w, h] = arena;
        let by_count = (w * h / expected.max(1) as f64).sqrt();
        let cell = reach.max(by_count).max(f64::MIN_POSITIVE);
        let nx = (w / cell) as usize + 1;
        let ny = (h / cell) as usize + 1;
        NearIndex {
            cell,
            nx,
            ny,
            heads: vec![NONE; nx * ny],
            next: Vec::with_capacity(expected),
            points: Vec::with_capacity(expected),
        }
    }

    fn cell_of(&self, p: Vec2) -> (usize, usize) {
        // Points are inside the arena; the clamp only guards the last row and column.
        let cx = ((p.x / self.cell).max(0.0) as usize).min(self.nx - 1);
        let cy = ((p.y / self.cell).max(0.0) as usize).min(self.ny - 1);
        (cx, cy)
    }

    fn insert(&mut self, p: Vec2) {
        let (cx, cy) = self.cell_of(p);
        let c = cy * self.nx + cx;
        self.next.push(self.heads[c]);
        self.heads[c] = self.points.len() as u32;
        self.points.push(p);
    }

    /// Does any entry within `reach` of `p` (the index's reach or less) satisfy `hit`?
    /// `hit` gets the entry number (insertion order) and its position.
    fn any_near(&self, p: Vec2, mut hit: impl FnMut(usize, Vec2) -> bool) -> bool {
        let (cx, cy) = self.cell_of(p);
        for y in cy.saturating_sub(1)..=(cy + 1).min(self.ny - 1) {
            for x in cx.saturating_sub(1)..=(cx + 1).min(self.nx - 1) {
                let mut e = self.heads[y * self.nx + x];
                while e != NONE {
                    if hit(e as usize, self.points[e as usize]) {
                        return true;
                    }
                    e = self.next[e as usize];
                }
            }
        }
        false
    }
}

/// Draws a point in `region`: uniform, or uniform among the grid points inside it.
/// x is drawn before y.
fn sample(rng: &mut Rng, region: Region, grid: Option<f64>) -> Vec2 {
    let [x0, y0, x1, y1] = region;
    match grid.and_then(|p| Some((p, grid_span(x0, x1, p)?, grid_span(y0, y1, p)?))) {
        Some((pitch, (ix0, ix1), (iy0, iy1))) => {
            let ix = ix0 + below(rng, (ix1 - ix0) as u64 + 1) as i64;
            let iy = iy0 + below(rng, (iy1 - iy0) as u64 + 1) as i64;
            Vec2::new(ix as f64 * pitch, iy as f64 * pitch)
        }
        None => Vec2::new(uniform(rng, x0, x1), uniform(rng, y0, y1)),
    }
}

fn touches_a_wall(p: Vec2, r: f64, walls: &[Segment]) -> bool {
    walls.iter().any(|w| circle_touches_segment(p, r, w))
}

/// The objects of a new world.
pub(crate) struct Objects {
    pub food: Vec<Food>,
    pub aversives: Vec<Aversive>,
}

/// Places the explicit objects (in file order, where they are asked to be), then each
/// placement rule in order. `walls` are the blocking segments.
pub(crate) fn place_objects(
    spec: &WorldSpec,
    walls: &[Segment],
    rng: &mut Rng,
) -> Result<Objects, PlacementError> {
    let index_of: BTreeMap<&str, usize> = spec
        .kinds
        .keys()
        .enumerate()
        .map(|(i, k)| (k.as_str(), i))
        .collect();
    let kinds: Vec<&KindSpec> = spec.kinds.values().collect();
    let total = spec.objects.len() + spec.place.iter().map(|r| r.count as usize).sum::<usize>();
    let mut objects = Objects {
        food: Vec::new(),
        aversives: Vec::new(),
    };
    // Centres of every object placed so far, for the spacing rule.
    let mut centres: Vec<Vec2> = Vec::with_capacity(total);

    let add = |objects: &mut Objects, kind: usize, p: Vec2| match kinds[kind] {
        KindSpec::Food(f) => objects.food.push(Food::new(kind, f, p)),
        KindSpec::Aversive(a) => objects.aversives.push(Aversive::new(kind, a, p)),
    };
    let lookup = |key: String, name: &str| {
        index_of
            .get(name)
            .copied()
            .ok_or_else(|| InvalidValue::new(key, format!("unknown kind `{name}`")))
    };

    for (i, object) in spec.objects.iter().enumerate() {
        let kind = lookup(format!("world.objects[{i}].kind"), &object.kind)?;
        let p = Vec2::from(object.position);
        add(&mut objects, kind, p);
        centres.push(p);
    }

    for (i, rule) in spec.place.iter().enumerate() {
        let kind = lookup(format!("world.place[{i}].kind"), &rule.kind)?;
        let radius = kinds[kind].radius();
        place_rule(spec, i, rule, radius, walls, rng, &mut centres, |p| {
            add(&mut objects, kind, p)
        })?;
    }
    Ok(objects)
}

/// One `[[world.place]]` rule: draws until each object finds a spot that keeps the spacing
/// and touches no wall, or fails after [`MAX_ATTEMPTS`] draws for one object.
#[allow(clippy::too_many_arguments)]
fn place_rule(
    spec: &WorldSpec,
    rule_index: usize,
    rule: &PlaceSpec,
    radius: f64,
    walls: &[Segment],
    rng: &mut Rng,
    centres: &mut Vec<Vec2>,
    mut add: impl FnMut(Vec2),
) -> Result<(), PlacementError> {
    let region = rule.region.unwrap_or(spec.arena_region());
    let spacing = rule.min_spacing;
    let spacing2 = spacing * spacing;
    // The spacing index is only worth building when there is a spacing to keep.
    let mut near = (spacing > 0.0).then(|| {
        let mut index = NearIndex::new(spec.arena, spacing, centres.len() + rule.count as usize);
        for &c in centres.iter() {
            index.insert(c);
        }
        index
    });
    for n in 0..rule.count {
        let mut found = None;
        for _ in 0..MAX_ATTEMPTS {
            let p = sample(rng, region, rule.grid);
            if touches_a_wall(p, radius, walls) {
                continue;
            }
            if let Some(index) = &near {
                if index.any_near(p, |_, q| p.distance_squared(q) < spacing2) {
                    continue;
                }
            }
            found = Some(p);
            break;
        }
        let Some(p) = found else {
            return Err(PlacementError::Object {
                rule: rule_index,
                kind: rule.kind.clone(),
                number: n + 1,
                count: rule.count,
                min_spacing: spacing,
                attempts: MAX_ATTEMPTS,
            });
        };
        if let Some(index) = &mut near {
            index.insert(p);
        }
        centres.push(p);
        add(p);
    }
    Ok(())
}

/// Start poses for `count` creatures of body radius `radius`: uniform in the start region
/// (or among its points of the start grid), the body touching no wall, no earlier creature
/// and no food or aversive object; heading
/// from `[world.start]` or uniform on the circle. Per creature, the position draws (x, then
/// y, repeated until a spot is free; grid indices with a grid) come before the heading draw.
pub(crate) fn place_creatures(
    spec: &WorldSpec,
    radius: f64,
    count: usize,
    walls: &[Segment],
    objects: &Objects,
    rng: &mut Rng,
) -> Result<Vec<Pose>, PlacementError> {
    if count > MAX_CREATURES {
        return Err(PlacementError::TooManyCreatures {
            count,
            max: MAX_CREATURES,
        });
    }
    let region = spec.start.region.unwrap_or(spec.arena_region());
    // Objects within reach of a body: radius plus the largest object radius.
    let things: Vec<(Vec2, f64)> = objects
        .food
        .iter()
        .map(|f| (f.position, f.radius))
        .chain(objects.aversives.iter().map(|a| (a.position, a.radius)))
        .collect();
    let largest = things.iter().map(|t| t.1).fold(0.0, f64::max);
    let mut near = NearIndex::new(spec.arena, radius + largest, things.len());
    for t in &things {
        near.insert(t.0);
    }
    let mut poses: Vec<Pose> = Vec::with_capacity(count);
    for n in 0..count {
        let mut found = None;
        for _ in 0..MAX_ATTEMPTS {
            let p = sample(rng, region, spec.start.grid);
            if touches_a_wall(p, radius, walls)
                || poses
                    .iter()
                    .any(|q| circles_touch(p, radius, q.position, radius))
                || near.any_near(p, |i, q| circles_touch(p, radius, q, things[i].1))
            {
                continue;
            }
            found = Some(p);
            break;
        }
        let Some(position) = found else {
            return Err(PlacementError::Creature {
                number: n + 1,
                count,
                attempts: MAX_ATTEMPTS,
            });
        };
        let angle = match spec.start.heading {
            Some(degrees) => degrees.to_radians(),
            None => uniform(rng, 0.0, std::f64::consts::TAU),
        };
        let heading = Vec2::new(libm::cos(angle), libm::sin(angle));
        poses.push(Pose { position, heading });
    }
    Ok(poses)
}
