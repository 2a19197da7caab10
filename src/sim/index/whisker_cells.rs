//! Per-cell shortlists for the whiskers and the food detectors (§5.2, §7.3): a coarse grid
//! over the arena whose cells list, in index order, the fixed felt walls and the food objects
//! that a body whose centre lies in the cell can feel with a whisker or touch with its body.
//! Built once per world; a creature's query is one cell lookup and two slice reads, where the
//! [`crate::sim::index::static_grid::StaticIndex`] filtered every fixed wall (small worlds) or visited and
//! clamped a box of cells.
//!
//! # Why a longer list changes no verdict
//! The whisker and detector answers are "or"s over objects: a whisker touches when any wall
//! or circle passes its exact test, a detector reads 1 when any touching food object holds
//! its substance. Neither depends on the order of the objects tested or on extra objects that
//! fail the test, so testing a superset of the objects that can pass, with the same exact
//! tests, gives the same bits. A cell's list is such a superset for any query that passes
//! [`WhiskerCells::lists`]' guard (the guard is checked at every query; a query that fails
//! it uses the index as before):
//!
//! - The guard: both whisker boxes lie within `reach` of the centre `p` on each axis
//!   (measured on the boxes the caller computed, whatever their rounding or NaN), and
//!   `0 ≤ radius ≤ reach` for the body.
//! - A wall passes the whisker test only if its box meets the whisker's box (the test starts
//!   with that box test), so it meets `[p − reach, p + reach]`.
//! - A circle of radius r at c touches a whisker only if c lies in the whisker's box widened
//!   by r (the eq. 2–3 rejection of `circle_touches_segment`), so in `p ± (reach + r)`.
//! - The body (radius `radius` ≤ `reach`) touches a food object of radius r ≥ 0 only if
//!   `|c − p|² ≤ (radius + r)²`, so c lies in `p ± (reach + r)` too.
//! - `p` maps to cell (x, y) only if it lies in that cell's box up to the rounding of the
//!   map. A cell lists every wall whose box meets its box grown by `reach + margin`, and
//!   every food object whose centre lies in its box grown by `reach + r + margin`, where the
//!   margin, 10⁻⁶ of the coordinates' scale, is far above the few ε of every rounding above
//!   (the map to the cell, the cell's box, the guard's and the tests' differences).
//!
//! Doors open and close and stay out of the lists; so do the aversive objects, creatures and
//! things, which the caller tests as before. A world with a non-finite or negative size,
//! reach, wall or food object gets no lists (every query goes to the index).

use crate::geometry::BoxedSegment;
use crate::geometry::Vec2;
use crate::sim::food::Food;

/// Most cells along each side (cells are never narrower than the reach): finer cells hand a
/// query fewer walls and food but cost more to build (figures in docs/performance.md).
const CELLS_PER_SIDE: usize = 32;

/// 2⁵²: adding it to an integer in [0, 2⁵²) is exact and leaves the integer in the low bits
/// of the sum's representation (see [`WhiskerCells::lists`]).
const TWO_52: f64 = 4_503_599_627_370_496.0;

/// The shortlists of one world (see the module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct WhiskerCells {
    cell: f64,
    inv_cell: f64,
    nx: usize,
    /// `nx` and `ny` as floats, for the range test of the cell lookup.
    nx_f: f64,
    ny_f: f64,
    /// How far whiskers and body may extend from the centre for the lists to hold.
    reach: f64,
    /// Cell k lists the walls `items[a..b]` then the food objects `items[b..c]`, where
    /// `[a, b, c] = cells[k]`; cells are numbered row by row.
    cells: Vec<[u32; 3]>,
    items: Vec<u32>,
}

impl WhiskerCells {
    /// The lists over an `arena` (from the origin) for the fixed felt walls `walls` and the
    /// food objects `food`, for whiskers and bodies reaching at most `reach` from the centre.
    /// `None` when anything is not finite, or a size or radius is negative.
    pub fn build(
        arena: [f64; 2],
        reach: f64,
        walls: &[BoxedSegment],
        food: &[Food],
    ) -> Option<WhiskerCells> {
        let [w, h] = arena;
        let sane = |v: f64| v.is_finite() && v >= 0.0;
        if !(sane(w) && sane(h) && w > 0.0 && h > 0.0 && sane(reach)) {
            return None;
        }
        let mut scale = w.max(h);
        for wall in walls {
            if !(wall.lo.is_finite() && wall.hi.is_finite()) {
                return None;
            }
            scale = scale.max(wall.lo.abs().max(wall.hi.abs()).max_element());
        }
        let mut food_radius: f64 = 0.0;
        for f in food {
            if !(f.position.is_finite() && sane(f.radius)) {
                return None;
            }
            scale = scale.max(f.position.abs().max_element());
            food_radius = food_radius.max(f.radius);
        }
        let margin = 1e-6 * (1.0 + scale + reach + food_radius);
        let cell = (w.max(h) / CELLS_PER_SIDE as f64).max(reach).max(margin);
        let inv_cell = 1.0 / cell;
        let count = |e: f64| ((e * inv_cell).ceil() as usize).clamp(1, CELLS_PER_SIDE);
        let (nx, ny) = (count(w), count(h));
        let n = nx * ny;
        // An object's box meets a cell's box grown by `g` when their spans meet on both
        // axes, so its cells are a column range times a row range. Along an axis the cells
        // that meet form one run (the cells' bounds grow with their index), whose ends are
        // found exactly by stepping from the estimates, with the test that defines the lists.
        let axis = |lo: f64, hi: f64, g: f64, n: usize| {
            let meets = |k: usize| hi >= k as f64 * cell - g && (k + 1) as f64 * cell + g >= lo;
            // Truncation is the floor here: negative values clamp to 0 anyway.
            let index = |v: f64| if v > 0.0 { (v as usize).min(n - 1) } else { 0 };
            let mut a = index((lo - g) * inv_cell);
            if meets(a) {
                while a > 0 && meets(a - 1) {
                    a -= 1;
                }
            } else {
                while a < n && !meets(a) {
                    a += 1;
                }
                if a == n {
                    return (1, 0);
                }
            }
            let mut b = index((hi + g) * inv_cell).max(a);
            if meets(b) {
                while b + 1 < n && meets(b + 1) {
                    b += 1;
                }
            } else {
                while !meets(b) {
                    b -= 1;
                }
            }
            (a, b)
        };
        // Each object's cells, walls first: `[x0, x1, y0, y1]`, inclusive (empty off the grid).
        let g = reach + margin;
        let rects: Vec<[usize; 4]> = walls
            .iter()
            .map(|w| (w.lo, w.hi, g))
            .chain(food.iter().map(|f| (f.position, f.position, g + f.radius)))
            .map(|(lo, hi, g)| {
                let (x0, x1) = axis(lo.x, hi.x, g, nx);
                let (y0, y1) = axis(lo.y, hi.y, g, ny);
                [x0, x1, y0, y1]
            })
            .collect();
        // A counting sort by cell and kind (walls, then food), filled in object order so
        // that each list keeps the increasing index order. Its own rather than
        // `cells::bucket_by_cell`: two passes over the objects' cell ranges without a list of
        // pairs, where the shared sort cost a quarter more of this build (callgrind).
        let each = |f: &mut dyn FnMut(usize, usize)| {
            for (j, &[x0, x1, y0, y1]) in rects.iter().enumerate() {
                let (kind, k) = if j < walls.len() {
                    (0, j)
                } else {
                    (1, j - walls.len())
                };
                for y in y0..=y1 {
                    for x in x0..=x1 {
                        f(2 * (y * nx + x) + kind, k);
                    }
                }
            }
        };
        // First each cell's counts of walls and food, then their slots: cell k gets
        // `[a, b, c]`, and `next[k]` is the next free slot of its walls and of its food.
        let mut cells = vec![[0u32; 3]; n];
        each(&mut |slot, _| cells[slot / 2][1 + slot % 2] += 1);
        let mut next = vec![[0u32; 2]; n];
        let mut at = 0u32;
        for (cell, next) in cells.iter_mut().zip(next.iter_mut()) {
            let [_, walls_in, food_in] = *cell;
            let (b, c) = (at + walls_in, at + walls_in + food_in);
            *cell = [at, b, c];
            *next = [at, b];
            at = c;
        }
        let mut items = vec![0u32; at as usize];
        each(&mut |slot, k| {
            let free = &mut next[slot / 2][slot % 2];
            items[*free as usize] = k as u32;
            *free += 1;
        });
        Some(WhiskerCells {
            cell,
            inv_cell,
            nx,
            nx_f: nx as f64,
            ny_f: ny as f64,
            reach,
            cells,
            items,
        })
    }

    /// The fixed felt walls (indices among the standing walls) and food objects that a body
    /// of radius `radius` at `p` may feel with whiskers whose boxes lie in `[lo, hi]`, or
    /// touch (a superset, in index order), or `None` when the query fails the guard of the
    /// module docs or `p` lies outside the grid.
    #[inline]
    pub fn lists(&self, p: Vec2, lo: Vec2, hi: Vec2, radius: f64) -> Option<(&[u32], &[u32])> {
        let r = self.reach;
        let fx = p.x * self.inv_cell;
        let fy = p.y * self.inv_cell;
        // `&` rather than `&&`: one well-predicted branch instead of a chain.
        let inside = (fx >= 0.0) & (fy >= 0.0) & (fx < self.nx_f) & (fy < self.ny_f);
        // `p − lo ≤ r` as `lo − p ≥ −r` (negation is exact, NaN fails both), so that the
        // four differences are one vector subtraction.
        let d = [lo.x - p.x, lo.y - p.y, hi.x - p.x, hi.y - p.y];
        let short = (d[0] >= -r) & (d[1] >= -r) & (d[2] <= r) & (d[3] <= r);
        let body = (radius >= 0.0) & (radius <= r);
        if !(inside & short & body) {
            return None;
        }
        // Both lie in [0, `CELLS_PER_SIDE`) here, so their floors are small integers that
        // 2⁵² adds exactly, leaving the integer in the low bits: three instructions each,
        // where the saturating `as` conversion takes five.
        let cell = |f: f64| (f.floor() + TWO_52).to_bits() as u32 as usize;
        let k = cell(fy) * self.nx + cell(fx);
        // Three bounds checks (c ≤ len, b ≤ c, a ≤ b) without the differences of a range.
        let [a, b, c] = self.cells[k].map(|v| v as usize);
        let (walls, food) = self.items[..c].split_at(b);
        Some((&walls[a..], food))
    }

    /// Columns and rows of the grid, and the side of its cells.
    pub fn dimensions(&self) -> ([usize; 2], f64) {
        let ny = self.cells.len() / self.nx;
        ([self.nx, ny], self.cell)
    }
}
