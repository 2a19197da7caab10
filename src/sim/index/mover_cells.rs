//! The creatures' moves and contacts: a grid over the fixed walls whose cells list the walls a
//! move starting in the cell may reach and the food and aversive objects a body ending in it
//! may touch (`MoverCells`), and per creature the cell its last contacts found it in
//! (`LastCell`), which its next move reuses when it starts where the last one ended.

use crate::geometry::BoxedSegment;
use crate::geometry::{Segment, Vec2};
use crate::sim::food::{Aversive, Food};
use crate::sim::index::cells::bucket_by_cell;
use crate::sim::index::static_grid::Scratch;

/// Where the world's `walls_near` put the walls of one move.
#[derive(Clone, Copy)]
pub(crate) enum NearWalls {
    /// The list of the cell of `mover_cells` with these lists.
    Cell(CellLists),
    /// `scratch.blocking`.
    Scratch,
}

impl NearWalls {
    /// The walls themselves.
    #[inline]
    pub(crate) fn walls<'a>(
        self,
        cells: &'a Option<MoverCells>,
        scratch: &'a Scratch,
    ) -> &'a [Segment] {
        match (self, cells) {
            (NearWalls::Cell(lists), Some(cells)) => cells.walls(lists),
            _ => &scratch.blocking,
        }
    }
}

/// Where a creature's last contacts phase found its body: its position and the cell of
/// `mover_cells` it was in. Its next move most often starts there (the cell is a function of
/// the position alone), and most often ends in the same cell.
#[derive(Debug, Clone, Copy)]
pub(crate) struct LastCell {
    /// The position; NaN (matching no position) until the first contacts in the grid.
    pub(crate) at: Vec2,
    /// A copy of its cell's `MoverCells::lists` record, which the move and the contacts
    /// read: no lookup (and no bounds check) in the grid's records.
    pub(crate) lists: CellLists,
    /// The cell's grid coordinates (see [`MoverCells::grid_coordinates`]): the points of
    /// the cell are those with coordinates in [lo, hi), hi = lo + 1. NaN (holding none)
    /// until then.
    pub(crate) lo: Vec2,
    pub(crate) hi: Vec2,
}

impl LastCell {
    pub(crate) const NONE: LastCell = LastCell {
        at: Vec2::NAN,
        lists: CellLists {
            walls: (0, 0),
            food: (0, 0),
            aversives: (0, 0),
        },
        lo: Vec2::NAN,
        hi: Vec2::NAN,
    };

    /// Do grid coordinates `f` lie in the cell? Then [`MoverCells::cell_at`] gives it: its
    /// conversions truncate each coordinate to `lo`'s (small integers, exact as floats).
    #[inline]
    pub(crate) fn holds(&self, f: Vec2) -> bool {
        (f.x >= self.lo.x) & (f.y >= self.lo.y) & (f.x < self.hi.x) & (f.y < self.hi.y)
    }

    /// A body at `at`, in the cell (of [`MoverCells::cell_at`]) with lists `lists`, at grid
    /// coordinates `f`.
    #[inline]
    pub(crate) fn new(at: Vec2, lists: CellLists, f: Vec2) -> LastCell {
        let lo = Vec2::new(f.x as u32 as f64, f.y as u32 as f64);
        LastCell {
            at,
            lists,
            lo,
            hi: lo + 1.0,
        }
    }
}

/// Most cells of [`MoverCells`] along each axis: finer cells list fewer walls per move but
/// cost more to build, once per trial world (figures in docs/performance.md).
const MOVER_CELLS: usize = 16;

/// Most fixed walls [`MoverCells`] lists.
const MOVER_WALLS: usize = 64;

/// For the creatures' moves: a grid over the fixed walls, each cell listing (in wall order)
/// the fixed walls whose box meets the cell's box grown by `travel + radius` and a margin, so
/// the walls a body of `radius` starting in the cell can reach when it moves at most `travel`
/// (a creature's largest move), without filtering on every move. The margin, 10⁻⁶ of the
/// coordinates' scale, covers every rounding: of the start's cell index, of the cell's box,
/// and of the end point and its box that `plan_move` computes (a few ε of the scale).
///
/// The lists hold more walls than [`StaticIndex::blocking_near`](crate::sim::index::StaticIndex::blocking_near) gives, which changes no
/// result: `plan_move`'s first verdict is `wall_blocks` over every listed wall, false for a
/// wall its box rejection rejects, and its shortlists (the single-wall loop, the prepared
/// search, the shortlist) keep only the walls `wall_may_block` keeps, so an extra wall,
/// which cannot be reached, is in none of them. Doors are not in the lists: while a door
/// stands, the grid filters as before.
///
/// What a move reads of it, the grid's placement and the lists' addresses, fits two cache
/// lines (boxed slices, aligned), for the same reason as the world's creature rules.
#[derive(Debug, Clone)]
#[repr(align(64))]
pub(crate) struct MoverCells {
    pub(crate) origin: Vec2,
    pub(crate) inv_cell: f64,
    pub(crate) nx: usize,
    /// `nx` and `ny` as floats, for the range test of [`MoverCells::cell_of`].
    pub(crate) nx_f: f64,
    pub(crate) ny_f: f64,
    /// The largest move the lists cover.
    pub(crate) travel: f64,
    /// Where each cell's lists lie in `walls`, `food` and `aversives`; cells are numbered row
    /// by row. One record per cell: a move and its contacts read one cache line and check
    /// one index for all three lists.
    pub(crate) lists: Box<[CellLists]>,
    walls: Box<[Segment]>,
    /// The food objects a body centred in the cell may touch (see
    /// [`MoverCells::with_contacts`]), in food order. Empty (no cell lists any) until
    /// `with_contacts`.
    food: Box<[u32]>,
    /// The same for aversive objects.
    aversives: Box<[u32]>,
}

/// Where one cell's lists of [`MoverCells`] lie: `walls[walls.0..walls.1]` and so on.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct CellLists {
    walls: (u32, u32),
    food: (u32, u32),
    aversives: (u32, u32),
}

impl MoverCells {
    /// The lists for `fixed` (every fixed wall with its box), moves of at most `travel` and
    /// bodies of `radius`. `None` (the grid filters every move) when there are no fixed
    /// walls or anything is not finite.
    pub(crate) fn build(fixed: &[BoxedSegment], travel: f64, radius: f64) -> Option<MoverCells> {
        // A NaN radius makes `plan_move` keep every wall (its box tests all fail), so the
        // lists must then be the grid's; a negative one reaches less than a radius of 0.
        let reach = travel + radius.max(0.0);
        if fixed.is_empty() || fixed.len() > MOVER_WALLS || radius.is_nan() || !reach.is_finite() {
            return None;
        }
        let mut lo = fixed[0].lo;
        let mut hi = fixed[0].hi;
        for w in fixed {
            lo = lo.min(w.lo);
            hi = hi.max(w.hi);
        }
        if !(lo.is_finite() && hi.is_finite()) {
            return None;
        }
        let scale = lo.abs().max(hi.abs()).max_element() + reach;
        let margin = 1e-6 * (1.0 + scale);
        let grow = reach + margin;
        // Starts farther than `grow` from every wall's box reach no wall; they fall outside
        // the grid and are filtered by the index.
        let origin = lo - grow;
        let extent = (hi + grow) - origin;
        let cell = (extent.max_element() / MOVER_CELLS as f64)
            .max(reach)
            .max(margin);
        let inv_cell = 1.0 / cell;
        let count = |e: f64| ((e * inv_cell).ceil() as usize).clamp(1, MOVER_CELLS);
        let (nx, ny) = (count(extent.x), count(extent.y));
        // Each wall is tested only against the cells around its box (two cells of slack on
        // every side cover the rounding of these index bounds), not against every cell: a
        // world has thousands of cells and a wall reaches few of them. The test itself is
        // the one every cell's list is defined by, and a stable counting sort by cell keeps
        // each list in wall order.
        let span = |lo: f64, hi: f64, o: f64, n: usize| {
            let first = ((lo - grow - o) * inv_cell).floor() - 2.0;
            let last = ((hi + grow - o) * inv_cell).floor() + 2.0;
            let clamp = |v: f64| v.clamp(0.0, (n - 1) as f64) as usize;
            clamp(first)..=clamp(last)
        };
        let mut pairs: Vec<(u32, u32)> = Vec::new();
        for (k, w) in fixed.iter().enumerate() {
            for y in span(w.lo.y, w.hi.y, origin.y, ny) {
                for x in span(w.lo.x, w.hi.x, origin.x, nx) {
                    let c_lo = origin + Vec2::new(x as f64, y as f64) * cell - grow;
                    let c_hi = origin + Vec2::new((x + 1) as f64, (y + 1) as f64) * cell + grow;
                    if w.may_meet(c_lo, c_hi) {
                        pairs.push(((y * nx + x) as u32, k as u32));
                    }
                }
            }
        }
        let (start, walls) = bucket_by_cell(nx * ny, &pairs, |k| fixed[k as usize].segment);
        let lists = start
            .windows(2)
            .map(|w| CellLists {
                walls: (w[0], w[1]),
                ..CellLists::default()
            })
            .collect();
        Some(MoverCells {
            origin,
            inv_cell,
            nx,
            nx_f: nx as f64,
            ny_f: ny as f64,
            travel,
            lists,
            walls: walls.into(),
            food: Box::default(),
            aversives: Box::default(),
        })
    }

    /// These cells, listing also the food and aversive objects a body of `radius` centred in
    /// each cell may touch, for the contacts phase: a body touching an object (as
    /// `circles_touch` tests it) lies within |radius + object radius| of its centre on each
    /// axis, up to a few ε of the coordinates' scale, so within the object's centre ±
    /// `grow`, the margin 10⁻⁶ of that scale far above the rounding. A start in the cell
    /// grid is in the cell `cell_of` computes with the same float steps (a difference, a
    /// product by `inv_cell`, then the floor), each monotone, so the cells of the range
    /// below, computed with those steps from the grown box's corners, hold every such start.
    /// `None` when an object or the radius is not finite (no world the specifications allow):
    /// the grid then answers every move and contact.
    pub(crate) fn with_contacts(
        self,
        radius: f64,
        food: &[Food],
        aversives: &[Aversive],
    ) -> Option<MoverCells> {
        let (food_start, food) =
            self.object_lists(radius, food.iter().map(|f| (f.position, f.radius)))?;
        let (aversive_start, aversives) =
            self.object_lists(radius, aversives.iter().map(|a| (a.position, a.radius)))?;
        let mut lists = self.lists;
        for (k, l) in lists.iter_mut().enumerate() {
            l.food = (food_start[k], food_start[k + 1]);
            l.aversives = (aversive_start[k], aversive_start[k + 1]);
        }
        Some(MoverCells {
            lists,
            food: food.into(),
            aversives: aversives.into(),
            ..self
        })
    }

    /// Per cell, in object order, the objects (centre, radius) a body of `radius` centred in
    /// the cell may touch, as `start` offsets and indices (see [`MoverCells::with_contacts`]).
    fn object_lists(
        &self,
        radius: f64,
        objects: impl Iterator<Item = (Vec2, f64)> + Clone,
    ) -> Option<(Vec<u32>, Vec<u32>)> {
        let ny = (self.ny_f as usize).max(1);
        let cells = self.nx * ny;
        let span = |lo: f64, o: f64, hi: f64, n: usize| {
            let clamp = |v: f64| v.clamp(0.0, (n - 1) as f64) as usize;
            clamp(((lo - o) * self.inv_cell).floor())..=clamp(((hi - o) * self.inv_cell).floor())
        };
        let mut pairs: Vec<(u32, u32)> = Vec::new();
        for (k, (centre, r)) in objects.enumerate() {
            // `circles_touch` compares with (radius + r)², so a negative sum reaches as far
            // as its magnitude.
            let reach = (radius + r).abs();
            let scale = centre.abs().max_element() + reach;
            if !(scale.is_finite() && self.origin.is_finite()) {
                return None;
            }
            let grow = reach + 1e-6 * (1.0 + scale + self.origin.abs().max_element());
            let (lo, hi) = (centre - grow, centre + grow);
            for y in span(lo.y, self.origin.y, hi.y, ny) {
                for x in span(lo.x, self.origin.x, hi.x, self.nx) {
                    pairs.push(((y * self.nx + x) as u32, k as u32));
                }
            }
        }
        Some(bucket_by_cell(cells, &pairs, |k| k))
    }

    /// The cell `p` lies in, `None` outside the grid (or not finite).
    #[inline]
    pub(crate) fn cell_of(&self, p: Vec2) -> Option<usize> {
        self.cell_at(self.grid_coordinates(p))
    }

    /// `p` in cell units from the grid's origin: cell (x, y) holds the points whose
    /// coordinates lie in [x, x + 1) × [y, y + 1).
    #[inline]
    pub(crate) fn grid_coordinates(&self, p: Vec2) -> Vec2 {
        Vec2::new(
            (p.x - self.origin.x) * self.inv_cell,
            (p.y - self.origin.y) * self.inv_cell,
        )
    }

    /// The cell at grid coordinates `f` ([`MoverCells::grid_coordinates`]), `None` outside
    /// the grid (or not finite).
    #[inline]
    pub(crate) fn cell_at(&self, f: Vec2) -> Option<usize> {
        let (fx, fy) = (f.x, f.y);
        if fx >= 0.0 && fy >= 0.0 && fx < self.nx_f && fy < self.ny_f {
            // Both are below MOVER_CELLS: the conversion to u32 truncates as the one to
            // usize would, in fewer instructions.
            Some(fy as u32 as usize * self.nx + fx as u32 as usize)
        } else {
            None
        }
    }

    /// The walls of the cell of `lists`.
    #[inline]
    pub(crate) fn walls(&self, lists: CellLists) -> &[Segment] {
        &self.walls[lists.walls.0 as usize..lists.walls.1 as usize]
    }

    /// The food objects a body centred in the cell of `lists` may touch, in food order.
    #[inline]
    pub(crate) fn food(&self, lists: CellLists) -> &[u32] {
        &self.food[lists.food.0 as usize..lists.food.1 as usize]
    }

    /// The aversive objects a body centred in the cell of `lists` may touch.
    #[inline]
    pub(crate) fn aversives(&self, lists: CellLists) -> &[u32] {
        &self.aversives[lists.aversives.0 as usize..lists.aversives.1 as usize]
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use rand::{Rng as _, SeedableRng};

    /// A float next to `x` (`d` = ±1 step of its bits, finite nonzero `x`); the world's
    /// motor-clamp test uses it too.
    pub(crate) fn step(x: f64, d: i64) -> f64 {
        let up = (x > 0.0) == (d > 0);
        let bits = x.to_bits();
        f64::from_bits(if up { bits + 1 } else { bits - 1 })
    }

    /// The range kept in [`LastCell`] agrees with [`MoverCells::cell_of`]: every point it
    /// holds is in its cell, on random points near and on the cells' edges (as computed),
    /// inside and outside the grid.
    #[test]
    fn last_cell_range_agrees_with_cell_of() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
        for _ in 0..50 {
            let mut walls = Vec::new();
            for _ in 0..rng.gen_range(1..8) {
                let p = |rng: &mut rand_chacha::ChaCha8Rng| {
                    Vec2::new(rng.gen_range(-50.0..350.0), rng.gen_range(-50.0..350.0))
                };
                walls.push(BoxedSegment::new(Segment::new(p(&mut rng), p(&mut rng))));
            }
            let travel = rng.gen_range(0.5..8.0);
            let radius = rng.gen_range(0.5..10.0);
            let cells = MoverCells::build(&walls, travel, radius).expect("finite walls");
            let cell = 1.0 / cells.inv_cell;
            let mut last = LastCell::NONE;
            assert!(!last.holds(Vec2::ZERO));
            for _ in 0..2_000 {
                // A point near a cell corner of the grid (or beyond it), or anywhere.
                let mut p = if rng.gen_bool(0.5) {
                    let cx = rng.gen_range(-2..cells.nx as i64 + 2) as f64;
                    let cy = rng.gen_range(-2..cells.ny_f as i64 + 2) as f64;
                    cells.origin + Vec2::new(cx, cy) * cell
                } else {
                    Vec2::new(rng.gen_range(-400.0..700.0), rng.gen_range(-400.0..700.0))
                };
                if rng.gen_bool(0.5) && p.x != 0.0 {
                    p.x = step(p.x, if rng.gen_bool(0.5) { 1 } else { -1 });
                }
                if rng.gen_bool(0.5) && p.y != 0.0 {
                    p.y = step(p.y, if rng.gen_bool(0.5) { 1 } else { -1 });
                }
                let f = cells.grid_coordinates(p);
                let k = cells.cell_of(p);
                assert_eq!(cells.cell_at(f), k);
                if last.holds(f) {
                    // The cell whose range it is: cells are numbered row by row.
                    let cell = last.lo.y as usize * cells.nx + last.lo.x as usize;
                    assert_eq!(k, Some(cell), "{p:?} held by the range of {last:?}");
                }
                if let Some(k) = k {
                    last = LastCell::new(p, cells.lists[k], f);
                    assert!(last.holds(f), "{p:?} not held by its own cell's range");
                    let cell = last.lo.y as usize * cells.nx + last.lo.x as usize;
                    assert_eq!(k, cell, "{p:?}: {last:?}");
                }
            }
        }
    }
}
