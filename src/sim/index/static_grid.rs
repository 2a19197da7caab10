//! The spatial index of what never moves: a uniform grid over the arena that holds the food
//! objects, the aversive objects and the fixed walls (boundary and interior walls; doors open
//! and close, so they stay in short linear lists that the senses test after the grid's walls),
//! and the smell grid ([`crate::sim::index::smell_grid`]) with the smell sources each receptor
//! position may smell. Built once per world; a query allocates nothing (its scratch space is a [`Scratch`] the
//! world preallocates).
//!
//! It only narrows down *which* objects a sense tests; the tests themselves are the same
//! functions as before, so results do not change. Where order matters (eating, which adds
//! floats in object order), a query yields candidate indices in increasing index order: the
//! cells mark their objects in a bitset over object indices, and the bitset is read back word
//! by word (deduplicating walls that span several cells on the way).
//!
//! # Cell size
//! The widest query on this grid is the smell box (the opaque walls within the largest finite
//! θ of a pair of receptors, for the smell sources the smell grid does not list). A cell as
//! wide as that largest θ makes such a query cover 3 × 3 to 4 × 4 cells. Narrower cells trim the
//! square query's corners but add per-cell overhead to every query, whiskers' included
//! (figures in docs/performance.md). Wider cells would hand the range test objects far out of range. Cells are never narrower than
//! the body's contact and whisker reach (so a whisker query covers at most 2 × 2 cells), and
//! the grid never has more than [`MAX_CELLS`] cells (huge arenas with short ranges get wider
//! cells). Nor does it have more than [`CELLS_PER_ITEM`] cells per object and wall it
//! holds (at least [`MIN_CELLS`]): the grid is built anew for every trial world, at a few
//! instructions per cell, and a world without smell would otherwise get cells as narrow as
//! the whisker reach, and spend more building its grid than living its trial. Worlds with at most [`FEW_WALLS`] fixed walls
//! filter the wall list directly instead of visiting cells, which is cheaper at that size.

use crate::geometry::BoxedSegment;
use crate::geometry::{Segment, Vec2};
use crate::sim::food::{Aversive, Food};
use crate::sim::index::cells::{
    bucket_by_cell, Cells, Geometry, CELLS_PER_ITEM, MAX_CELLS, MIN_CELLS,
};
use crate::sim::index::smell_grid::{
    finite_sources, smell_grid, Odour, ShadedWall, SmellGrid, Source,
};
use crate::sim::index::whisker_cells::WhiskerCells;
use crate::sim::smell::{Shade, Smell};
use crate::sim::wall::Walls;

/// Up to this many fixed walls, a box query filters the whole wall list (a few comparisons
/// per wall) rather than visiting cells and deduplicating: cheaper for small worlds.
pub const FEW_WALLS: usize = 32;

/// Cells per largest finite smell range (see the module docs).
const CELLS_PER_RANGE: f64 = 1.0;

/// Which objects each cell holds, in compressed rows: the objects of cell k are
/// `items[start[k]..start[k + 1]]`, in increasing index order. Cells are numbered row by row,
/// so the cells `x0..=x1` of one row are one contiguous slice.
#[derive(Debug, Clone, PartialEq, Default)]
struct CellLists {
    start: Vec<u32>,
    items: Vec<u32>,
}

impl CellLists {
    /// Lists built from `(cell, object)` pairs pushed in increasing object order.
    fn build(cells: usize, pairs: Vec<(u32, u32)>) -> CellLists {
        // Stable: objects keep their increasing order within a cell.
        let (start, items) = bucket_by_cell(cells, &pairs, |k| k);
        CellLists { start, items }
    }

    /// The objects of cells `x0..=x1` in row `y` (a row holds `nx` cells).
    #[inline]
    fn row(&self, nx: usize, y: usize, x0: usize, x1: usize) -> &[u32] {
        let a = self.start[y * nx + x0] as usize;
        let b = self.start[y * nx + x1 + 1] as usize;
        &self.items[a..b]
    }
}

/// Scratch space for the queries that must yield candidates in index order, sized when the
/// world is built so that a tick allocates nothing.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Scratch {
    /// One bit per object (the largest of the food, aversive and fixed opaque wall lists);
    /// all zero between queries.
    bits: Vec<u64>,
    /// Food candidates of the last query, in increasing index order.
    pub food: Vec<u32>,
    /// The opaque walls (fixed and closed doors) that may meet the smell box of the last
    /// [`StaticIndex::near_opaque`] query.
    pub near: Vec<BoxedSegment>,
    /// Per receptor: `near` as that receptor sees it (see [`Shade`]).
    pub shades: [Vec<Shade>; 2],
    /// The walls (fixed and closed doors) that may block a move, see
    /// [`StaticIndex::blocking_near`].
    pub blocking: Vec<Segment>,
}

/// The box around a receptor inside which every source of finite range lies. The opaque walls
/// that may meet it decide the visibility of any source whose centre is in the box (the
/// segment to it lies in the box too).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SmellBox {
    /// Smallest corner.
    pub lo: Vec2,
    /// Largest corner.
    pub hi: Vec2,
}

/// The grid of one world (see the module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct StaticIndex {
    geometry: Geometry,
    food: CellLists,
    aversives: CellLists,
    /// Fixed walls (the first `fixed_felt` of the standing walls), in every cell they cross.
    felt: CellLists,
    /// Fixed opaque walls (the first `fixed_opaque` of the opaque walls).
    opaque: CellLists,
    fixed_felt: usize,
    fixed_opaque: usize,
    /// The smell sources of finite range, per cell of their own grid.
    pub(super) smell: SmellGrid,
    /// Smelly food and aversive objects of unlimited range, as [`Source`] ids, increasing.
    pub(super) smell_always: Vec<u32>,
    /// The largest finite smell range θ of the food and aversive objects (0 when none).
    smell_reach: f64,
    /// Largest food and aversive radius.
    food_radius: f64,
    aversive_radius: f64,
    /// Added to every query box, far above rounding errors, far below any object size.
    slack: f64,
    pub(super) food_count: usize,
    aversive_count: usize,
    /// The fixed felt walls and food objects each whisker query may touch, per cell.
    whisker: Option<WhiskerCells>,
}

/// The largest finite smell range of `smells`, with the indices of the smelly ones of
/// unlimited range.
fn ranges<'a>(smells: impl Iterator<Item = &'a Smell>) -> (f64, Vec<u32>) {
    let mut reach: f64 = 0.0;
    let mut always = Vec::new();
    for (k, s) in smells.enumerate() {
        if s.silent {
            continue;
        }
        if s.range_squared.is_finite() {
            reach = reach.max(s.range_squared.sqrt());
        } else {
            always.push(k as u32);
        }
    }
    (reach, always)
}

impl StaticIndex {
    /// Indexes `food`, `aversives` and the fixed walls of `walls` (its doors stay out).
    /// `reach` is the farthest a body's whiskers or contacts extend from its centre.
    pub fn build(
        arena: [f64; 2],
        reach: f64,
        food: &[Food],
        aversives: &[Aversive],
        walls: &Walls,
    ) -> StaticIndex {
        let (felt, fixed_felt) = (walls.felt(), walls.fixed_count());
        let (opaque, fixed_opaque) = (walls.opaque(), walls.fixed_opaque_count());
        let (food_reach, food_always) = ranges(food.iter().map(|f| &f.smell));
        let (aversive_reach, aversive_always) = ranges(aversives.iter().map(|a| &a.smell));
        let smell_reach = food_reach.max(aversive_reach);
        let radius = |r: f64, acc: f64| if r.is_finite() { acc.max(r) } else { acc };
        let food_radius = food.iter().fold(0.0, |acc, f| radius(f.radius, acc));
        let aversive_radius = aversives.iter().fold(0.0, |acc, a| radius(a.radius, acc));
        let (w, h) = (arena[0], arena[1]);
        // Validation makes the arena positive and finite; anything else gets a 1 x 1 grid.
        let (w, h) = if w.is_finite() && h.is_finite() && w > 0.0 && h > 0.0 {
            (w, h)
        } else {
            (1.0, 1.0)
        };
        let extent = w.max(h);
        let mut cell = (smell_reach / CELLS_PER_RANGE).max(reach);
        if !(cell.is_finite() && cell > 0.0) {
            cell = extent;
        }
        // A grid is built for every trial world, so its cells must not outnumber what it
        // holds by much: building costs a few instructions per cell, and a world without
        // smell (cells as narrow as the whisker reach) would otherwise spend more building
        // its grid than living its trial.
        let items = food.len() + aversives.len() + fixed_felt + fixed_opaque;
        let most = (CELLS_PER_ITEM * items).clamp(MIN_CELLS, MAX_CELLS);
        let geometry = Geometry::covering(w, h, cell, most);
        let slack = 1e-6 * (1.0 + extent + smell_reach + reach);
        let cells = geometry.nx * geometry.ny;
        let points = |positions: &mut dyn Iterator<Item = Vec2>| {
            let pairs = positions
                .enumerate()
                .map(|(k, p)| {
                    let cell = geometry.row(p.y) * geometry.nx + geometry.col(p.x);
                    (cell as u32, k as u32)
                })
                .collect();
            CellLists::build(cells, pairs)
        };
        let food_lists = points(&mut food.iter().map(|f| f.position));
        let aversive_lists = points(&mut aversives.iter().map(|a| a.position));
        let felt_lists = segment_lists(&geometry, &felt[..fixed_felt], slack);
        let opaque_lists = segment_lists(&geometry, &opaque[..fixed_opaque], slack);
        let food_count = food.len();
        let mut smell_always = food_always;
        smell_always.extend(aversive_always.iter().map(|&k| k + food_count as u32));
        let mut index = StaticIndex {
            geometry,
            food: food_lists,
            aversives: aversive_lists,
            felt: felt_lists,
            opaque: opaque_lists,
            fixed_felt,
            fixed_opaque,
            smell: SmellGrid::empty(extent),
            smell_always,
            smell_reach,
            food_radius,
            aversive_radius,
            slack,
            food_count,
            aversive_count: aversives.len(),
            whisker: WhiskerCells::build(arena, reach, &felt[..fixed_felt], food),
        };
        let (sources, odours) = finite_sources(food, aversives);
        let fixed = &opaque[..fixed_opaque];
        let mut bits = vec![0u64; fixed_opaque / 64 + 1];
        let smell = smell_grid(
            &sources,
            (w, h, extent, reach),
            fixed,
            slack,
            |lo, hi, out| {
                if fixed_opaque <= FEW_WALLS {
                    out.extend(
                        (0..fixed_opaque as u32).filter(|&k| fixed[k as usize].may_meet(lo, hi)),
                    );
                } else {
                    index.each_wall(&index.opaque, lo, hi, &mut bits, |k| {
                        if fixed[k].may_meet(lo, hi) {
                            out.push(k as u32);
                        }
                    });
                }
            },
        );
        index.smell = smell.with_odours(odours);
        index
    }

    /// Scratch space big enough for every query on this index; `opaque_total` counts every
    /// opaque wall, `walls_total` every wall, doors included.
    pub fn scratch(&self, opaque_total: usize, walls_total: usize) -> Scratch {
        let n = self
            .food_count
            .max(self.aversive_count)
            .max(self.fixed_opaque)
            .max(self.fixed_felt);
        Scratch {
            blocking: Vec::with_capacity(walls_total),
            bits: vec![0; n / 64 + 1],
            food: Vec::with_capacity(self.food_count),
            near: Vec::with_capacity(opaque_total),
            shades: [
                Vec::with_capacity(opaque_total),
                Vec::with_capacity(opaque_total),
            ],
        }
    }

    /// Side of a cell in LU.
    pub fn cell_size(&self) -> f64 {
        self.geometry.cell
    }

    /// Columns and rows of the grid.
    pub fn dimensions(&self) -> [usize; 2] {
        [self.geometry.nx, self.geometry.ny]
    }

    /// How many of the standing walls are fixed (the rest are closed doors).
    #[inline]
    pub fn fixed_felt(&self) -> usize {
        self.fixed_felt
    }

    /// How many of the opaque walls are fixed (the rest are closed opaque doors).
    #[inline]
    pub fn fixed_opaque(&self) -> usize {
        self.fixed_opaque
    }

    /// The per-cell lists of the fixed felt walls and food objects for the whiskers and food
    /// detectors (`None` when the world has none, see [`WhiskerCells::build`]).
    #[inline]
    pub fn whisker_cells(&self) -> Option<&WhiskerCells> {
        self.whisker.as_ref()
    }

    /// The largest finite smell range of the food and aversive objects (0 when none).
    pub fn smell_reach(&self) -> f64 {
        self.smell_reach
    }

    /// Does `hit` hold for any object of `lists` in the cells meeting `[lo, hi]`? Cells are
    /// visited in any order (for yes/no answers only).
    #[inline]
    fn any(
        &self,
        lists: &CellLists,
        lo: Vec2,
        hi: Vec2,
        mut hit: impl FnMut(usize) -> bool,
    ) -> bool {
        let g = &self.geometry;
        let c = g.cells(lo, hi);
        let mut y = c.y0;
        while y <= c.y1 {
            for &k in lists.row(g.nx, y, c.x0, c.x1) {
                if hit(k as usize) {
                    return true;
                }
            }
            y += 1;
        }
        false
    }

    /// Does `hit` hold for a fixed wall that may cross the box `[lo, hi]`? `hit` gets the
    /// wall's index among the standing walls.
    #[inline]
    pub fn any_fixed_wall(&self, lo: Vec2, hi: Vec2, hit: impl FnMut(usize) -> bool) -> bool {
        if self.fixed_felt <= FEW_WALLS {
            return (0..self.fixed_felt).any(hit);
        }
        let s = self.slack;
        self.any(&self.felt, lo - s, hi + s, hit)
    }

    /// Does `hit` hold for a food object whose body may meet the box `[lo, hi]`?
    #[inline]
    pub fn any_food(&self, lo: Vec2, hi: Vec2, hit: impl FnMut(usize) -> bool) -> bool {
        if self.food_count == 0 {
            return false;
        }
        let r = self.food_radius + self.slack;
        self.any(&self.food, lo - r, hi + r, hit)
    }

    /// Does `hit` hold for an aversive object whose body may meet the box `[lo, hi]`?
    #[inline]
    pub fn any_aversive(&self, lo: Vec2, hi: Vec2, hit: impl FnMut(usize) -> bool) -> bool {
        if self.aversive_count == 0 {
            return false;
        }
        let r = self.aversive_radius + self.slack;
        self.any(&self.aversives, lo - r, hi + r, hit)
    }

    /// Into `scratch.food`, in index order: the food objects whose body may meet the box
    /// `[lo, hi]` and for which `keep` holds. Few pass `keep` (a body touches one or two
    /// objects), so they are sorted directly rather than through the bitset.
    pub fn food_where(
        &self,
        lo: Vec2,
        hi: Vec2,
        scratch: &mut Scratch,
        mut keep: impl FnMut(usize) -> bool,
    ) {
        let out = &mut scratch.food;
        out.clear();
        self.any_food(lo, hi, |k| {
            if keep(k) {
                out.push(k as u32);
            }
            false
        });
        // Insertion sort: allocation-free, and the list is almost always 0 to 2 long.
        for n in 1..out.len() {
            let mut m = n;
            while m > 0 && out[m - 1] > out[m] {
                out.swap(m - 1, m);
                m -= 1;
            }
        }
    }

    /// The smell box of receptors in the box `[lo, hi]` (the largest finite range around it)
    /// and, into `scratch.near`, the opaque walls of `opaque` (fixed ones first, in order,
    /// then the closed opaque doors) that may meet it.
    pub fn near_opaque(
        &self,
        lo: Vec2,
        hi: Vec2,
        opaque: &[BoxedSegment],
        scratch: &mut Scratch,
    ) -> SmellBox {
        let r = self.smell_reach + self.slack;
        let (lo, hi) = (lo - r, hi + r);
        let Scratch { bits, near, .. } = scratch;
        near.clear();
        if self.fixed_opaque <= FEW_WALLS {
            near.extend(opaque.iter().filter(|w| w.may_meet(lo, hi)));
            return SmellBox { lo, hi };
        }
        self.each_wall(&self.opaque, lo, hi, bits, |k| {
            if opaque[k].may_meet(lo, hi) {
                near.push(opaque[k]);
            }
        });
        near.extend(
            opaque[self.fixed_opaque..]
                .iter()
                .filter(|d| d.may_meet(lo, hi)),
        );
        SmellBox { lo, hi }
    }

    /// Calls `f` once for each wall of `lists` in the cells meeting `[lo, hi]`, in index
    /// order (`bits` deduplicates walls spanning several cells and is left zero).
    #[inline]
    fn each_wall(
        &self,
        lists: &CellLists,
        lo: Vec2,
        hi: Vec2,
        bits: &mut [u64],
        mut f: impl FnMut(usize),
    ) {
        let g = &self.geometry;
        let c = g.cells(lo, hi);
        let (mut first, mut last) = (usize::MAX, 0);
        for y in c.y0..=c.y1 {
            for &k in lists.row(g.nx, y, c.x0, c.x1) {
                let w = (k >> 6) as usize;
                bits[w] |= 1u64 << (k & 63);
                first = first.min(w);
                last = last.max(w);
            }
        }
        if first > last {
            return;
        }
        for (w, word) in bits.iter_mut().enumerate().take(last + 1).skip(first) {
            let mut b = *word;
            *word = 0;
            while b != 0 {
                f(((w << 6) as u32 | b.trailing_zeros()) as usize);
                b &= b - 1;
            }
        }
    }

    /// Into `scratch.blocking`: the walls of `walls` (every standing wall, fixed ones first,
    /// as [`Walls::felt`] lists them) that may block a body of radius `radius` whose centre
    /// moves at most `travel` from `start`, i.e. whose box meets `start ± (travel + radius)`:
    /// a wall outside that box neither crosses the path nor touches the body at its end.
    /// Every wall when the box is not finite. Order is kept (fixed walls, then doors).
    pub fn blocking_near(
        &self,
        start: Vec2,
        travel: f64,
        radius: f64,
        walls: &[BoxedSegment],
        scratch: &mut Scratch,
    ) {
        let r = travel + radius + self.slack;
        let (lo, hi) = (start - r, start + r);
        let Scratch { bits, blocking, .. } = scratch;
        blocking.clear();
        if !(lo.is_finite() && hi.is_finite()) {
            blocking.extend(walls.iter().map(|w| w.segment));
            return;
        }
        if self.fixed_felt <= FEW_WALLS {
            blocking.extend(
                walls
                    .iter()
                    .filter(|w| w.may_meet(lo, hi))
                    .map(|w| w.segment),
            );
            return;
        }
        self.each_wall(&self.felt, lo, hi, bits, |k| {
            if walls[k].may_meet(lo, hi) {
                blocking.push(walls[k].segment);
            }
        });
        blocking.extend(
            walls[self.fixed_felt..]
                .iter()
                .filter(|d| d.may_meet(lo, hi))
                .map(|d| d.segment),
        );
    }
}

/// Cell lists of `segments`: each in every cell of its box that the segment may cross.
fn segment_lists(g: &Geometry, segments: &[BoxedSegment], slack: f64) -> CellLists {
    let mut pairs = Vec::new();
    for (k, s) in segments.iter().enumerate() {
        let c = g.cells(s.lo - slack, s.hi + slack);
        for y in c.y0..=c.y1 {
            for x in c.x0..=c.x1 {
                if may_cross_cell(g, x, y, c, s, slack) {
                    pairs.push(((y * g.nx + x) as u32, k as u32));
                }
            }
        }
    }
    CellLists::build(g.nx * g.ny, pairs)
}

/// Can segment `s` cross cell (x, y)? False only when the cell (widened by `slack`, and
/// unbounded on the grid's border sides, where outside points are clamped in) lies strictly
/// on one side of the segment's line. Border cells and cells of a single-cell box are
/// always kept.
fn may_cross_cell(
    g: &Geometry,
    x: usize,
    y: usize,
    c: Cells,
    s: &BoxedSegment,
    slack: f64,
) -> bool {
    let border = x == 0 || y == 0 || x + 1 == g.nx || y + 1 == g.ny;
    if border || (c.x0 == c.x1 && c.y0 == c.y1) {
        return true;
    }
    let x0 = g.origin.x + x as f64 * g.cell - slack;
    let y0 = g.origin.y + y as f64 * g.cell - slack;
    let (x1, y1) = (x0 + g.cell + 2.0 * slack, y0 + g.cell + 2.0 * slack);
    let (a, b) = (s.segment.a, s.segment.b);
    let d = b - a;
    let side = |px: f64, py: f64| d.x * (py - a.y) - d.y * (px - a.x);
    let tol = slack * (d.x.abs() + d.y.abs());
    let corners = [side(x0, y0), side(x1, y0), side(x0, y1), side(x1, y1)];
    let all_above = corners.iter().all(|&v| v > tol);
    let all_below = corners.iter().all(|&v| v < -tol);
    !(all_above || all_below)
}

/// The smell grid's queries, on the world's index that holds it.
impl StaticIndex {
    /// The cell of the smell grid holding a receptor at `p` (any point: outside points go to
    /// the nearest border cell, NaN to cell 0).
    #[inline]
    pub fn smell_cell(&self, p: Vec2) -> usize {
        let g = &self.smell.geometry;
        g.row(p.y) * g.nx + g.col(p.x)
    }

    /// The list of [`StaticIndex::smell_sources`] that serves both receptors `tips` of a
    /// creature at once, or `None` (then each receptor's own cell, [`StaticIndex::smell_cell`],
    /// serves it): the cell holding the tips' midpoint when both tips lie in its box as the
    /// grid was built for it, which is the cell widened by the whisker reach (see
    /// [`SmellGrid`]), so that one list holds every source that may reach either tip, with
    /// every wall that may hide it from either. The whisker tips are at most the whisker
    /// length from their midpoint, so only tips far from the arena or not finite miss.
    #[inline(never)]
    pub fn smell_pair_sources(&self, tips: [Vec2; 2]) -> Option<&[Source]> {
        self.smell_pair_sources_inlined(tips)
    }

    /// [`StaticIndex::smell_pair_sources`], always inlined: for the common case of a
    /// creature's smell, where a call would cost about a fifth of the lookup. The general
    /// smell keeps the call (out of line above): inlined there, it crowds that function's
    /// registers (more instructions in the eye world).
    #[inline(always)]
    pub fn smell_pair_sources_inlined(&self, tips: [Vec2; 2]) -> Option<&[Source]> {
        let s = &self.smell;
        let g = &s.geometry;
        let mid = (tips[0] + tips[1]) * 0.5;
        let c = &s.cells[g.row(mid.y) * g.nx + g.col(mid.x)];
        let (lo, hi) = (c.lo, c.hi);
        let within = |p: Vec2| (p.x >= lo.x) & (p.x <= hi.x) & (p.y >= lo.y) & (p.y <= hi.y);
        if within(tips[0]) & within(tips[1]) {
            Some(&s.sources[c.start as usize..c.end as usize])
        } else {
            None
        }
    }

    /// Every food or aversive object of finite range whose smell may reach a receptor in
    /// smell cell `cell` (a finite receptor strictly within the range of such an object is
    /// in a cell listing it), in increasing [`Source::id`] order.
    #[inline]
    pub fn smell_sources(&self, cell: usize) -> &[Source] {
        let s = &self.smell;
        &s.sources[s.start[cell] as usize..s.start[cell + 1] as usize]
    }

    /// The fixed opaque walls (indices among the first [`StaticIndex::fixed_opaque`] opaque
    /// walls) that may cross a segment from a point of the cell listing `source` to its
    /// centre: no other fixed wall can hide it from a receptor in that cell.
    #[inline]
    pub fn source_walls(&self, source: &Source) -> &[u32] {
        &self.smell.walls[source.w0 as usize..source.w1 as usize]
    }

    /// The emission of `source` (a copy of its object's [`Smell::emission`]) and whether its
    /// smell follows its amount.
    #[inline(always)]
    pub fn odour(&self, source: &Source) -> &Odour {
        &self.smell.odours[source.odour as usize]
    }

    /// Per wall of [`StaticIndex::source_walls`] of `source`, in the same order, what the
    /// occlusion test of a receptor's segment to the source's centre reads of it (a
    /// [`ShadedWall`]): one slice, so that the smell's loop over a source's walls walks one
    /// array with no index into the walls.
    #[inline]
    pub fn source_shaded_walls(&self, source: &Source) -> &[ShadedWall] {
        &self.smell.shaded[source.w0 as usize..source.w1 as usize]
    }

    /// The smelly food and aversive objects of unlimited range, as [`Source::id`]s in
    /// increasing order: every receptor may smell them.
    #[inline]
    pub fn smell_always(&self) -> &[u32] {
        &self.smell_always
    }

    /// How many food objects the index holds ([`Source::id`]s from it on are aversive).
    #[inline]
    pub fn food_count(&self) -> usize {
        self.food_count
    }

    /// Columns and rows of the smell grid, and the side of its cells.
    pub fn smell_dimensions(&self) -> ([usize; 2], f64) {
        let g = &self.smell.geometry;
        ([g.nx, g.ny], g.cell)
    }
}
