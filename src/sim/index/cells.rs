//! The cell layout the grids share: square cells over the arena (`Geometry`; points outside
//! map to the nearest border cell), and the stable counting sort that turns `(cell, item)`
//! pairs pushed in item order into per-cell lists that keep item order (`bucket_by_cell`).

use crate::geometry::Vec2;

/// Most cells a grid may have (memory per world stays below a few hundred KiB).
pub const MAX_CELLS: usize = 1 << 16;

/// Cells per indexed object or wall at most (see [`crate::sim::index::static_grid`]); never
/// fewer than [`MIN_CELLS`] in all.
pub(super) const CELLS_PER_ITEM: usize = 4;

/// Cells a grid may always have, however little it holds.
pub(super) const MIN_CELLS: usize = 64;

/// An inclusive range of cells, columns `x0..=x1` and rows `y0..=y1`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Cells {
    pub(super) x0: usize,
    pub(super) x1: usize,
    pub(super) y0: usize,
    pub(super) y1: usize,
}

/// The uniform grid's geometry: `nx` × `ny` square cells of side `cell` from `origin`.
/// Points outside the grid map to the nearest border cell; the map from coordinate to cell
/// is monotone, so a box query finds every point inside the box.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Geometry {
    pub(super) origin: Vec2,
    pub(super) inv_cell: f64,
    pub(super) cell: f64,
    pub(super) nx: usize,
    pub(super) ny: usize,
    /// `nx − 1` and `ny − 1` as floats, converted once (an unsigned-to-float conversion is a
    /// dozen instructions on x86-64, and every query clamps four coordinates).
    pub(super) last_x: f64,
    pub(super) last_y: f64,
}

impl Geometry {
    /// Square cells of side `cell` from the origin over a `w` × `h` arena, the side doubled
    /// until there are at most `most` cells.
    pub(super) fn covering(w: f64, h: f64, mut cell: f64, most: usize) -> Geometry {
        let side = |len: f64, cell: f64| ((len / cell).ceil() as usize).max(1);
        while side(w, cell) * side(h, cell) > most {
            cell *= 2.0;
        }
        let (nx, ny) = (side(w, cell), side(h, cell));
        Geometry {
            origin: Vec2::ZERO,
            inv_cell: 1.0 / cell,
            cell,
            nx,
            ny,
            last_x: (nx - 1) as f64,
            last_y: (ny - 1) as f64,
        }
    }

    /// Column (or row) of coordinate `t` measured from the origin, clamped to `0..n`. NaN maps
    /// to 0 (queries with NaN bounds take every cell, see [`Geometry::cells`]). Truncation is
    /// the floor here since negative values map to 0 anyway (and `floor` is a library call
    /// on baseline x86-64). `last` is `n − 1` as a float. Below it, `k` is under
    /// [`MAX_CELLS`], so the conversion through `u32` (one instruction, where one to `usize`
    /// takes several) gives the same column.
    #[inline]
    fn index(t: f64, inv_cell: f64, n: usize, last: f64) -> usize {
        let k = t * inv_cell;
        if k >= last {
            n - 1
        } else if k > 0.0 {
            k as u32 as usize
        } else {
            0
        }
    }

    #[inline]
    pub(super) fn col(&self, x: f64) -> usize {
        Self::index(x - self.origin.x, self.inv_cell, self.nx, self.last_x)
    }

    #[inline]
    pub(super) fn row(&self, y: f64) -> usize {
        Self::index(y - self.origin.y, self.inv_cell, self.ny, self.last_y)
    }

    /// The cells meeting the box `[lo, hi]`; every cell when a bound is NaN.
    #[inline]
    pub(super) fn cells(&self, lo: Vec2, hi: Vec2) -> Cells {
        if lo.is_nan() || hi.is_nan() {
            return Cells {
                x0: 0,
                x1: self.nx - 1,
                y0: 0,
                y1: self.ny - 1,
            };
        }
        Cells {
            x0: self.col(lo.x),
            x1: self.col(hi.x),
            y0: self.row(lo.y),
            y1: self.row(hi.y),
        }
    }
}

/// Per-cell lists from `(cell, k)` pairs: cell c's items are `items[start[c]..start[c + 1]]`,
/// `item(k)` for each of its pairs in the order the pairs come (a stable counting sort, so
/// lists built from pairs in object order stay in object order). The counting sort of the
/// static grid, the smell grid and the mover cells.
pub(crate) fn bucket_by_cell<K: Copy, T: Copy>(
    cells: usize,
    pairs: &[(u32, K)],
    item: impl Fn(K) -> T,
) -> (Vec<u32>, Vec<T>) {
    let mut start = vec![0u32; cells + 1];
    for &(c, _) in pairs {
        start[c as usize + 1] += 1;
    }
    for c in 0..cells {
        start[c + 1] += start[c];
    }
    let mut next = start.clone();
    let mut items = Vec::with_capacity(pairs.len());
    if let Some(&(_, k)) = pairs.first() {
        items.resize(pairs.len(), item(k));
    }
    for &(c, k) in pairs {
        let slot = &mut next[c as usize];
        items[*slot as usize] = item(k);
        *slot += 1;
    }
    (start, items)
}
