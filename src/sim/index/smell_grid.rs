//! The smell grid: the smell sources each receptor position may smell, with the walls that
//! may hide them, worked out when a world's [`StaticIndex`] is built.
//!
//! Smell, the widest and most frequent query, has a grid of its own, whose lists are worked
//! out when the index is built so that a pair of receptors' query is one slice read: each
//! cell lists, in increasing id order (food, then aversive objects, the order of the smell
//! sums), every smelly food or aversive object of finite range θ that may reach a receptor in
//! the cell (the cell's box, grown by the whisker reach (at most a quarter cell) plus a
//! rounding slack and unbounded on the grid's border sides where outside points are clamped
//! in, lies within θ of it), with its centre and θ² (so that the range test reads the list
//! alone), and with each object the fixed opaque walls that may meet the convex hull of the
//! cell's box and the object's centre: a segment from a receptor in the cell to the centre
//! lies in that hull, so no other fixed wall can hide the object from there (doors open and
//! close, so they are tested apart). Most lists of walls are empty, and an object that one
//! wall hides from the whole cell is left out. Since the box is grown by the whisker reach,
//! the cell holding the midpoint of a creature's two whisker tips serves both tips with one
//! list. Each listed wall carries its [`WallShade`] from the object's centre (the box test of
//! a segment from a receptor to the centre, settled when the grid is built; kept as a
//! [`FacedShade`], one vector comparison per receptor), the side of the centre from the
//! wall's line (the one orientation of that segment's occlusion test that no receptor
//! changes, see [`crate::geometry::side_of`]) and a copy of the wall ([`ShadedWall`], one
//! entry read in order rather than three arrays and the walls), and each object
//! its [`Odour`] (a copy of its emission), so that summing a listed smell reads the grid alone
//! unless the smell follows the food's amount. Its cells are half the largest finite θ wide
//! ([`SMELL_CELLS_PER_RANGE`]), and at most [`CELLS_PER_ITEM`] per listed object (at least
//! [`MIN_CELLS`]): each object is listed in about (2θ / cell + 1)² cells, so narrower cells
//! would hand a receptor fewer objects but cost more to build, and the grid is built for
//! every trial world. Objects of unlimited range are in a short list apart, merged into
//! every query in id order.

use crate::geometry::BoxedSegment;
use crate::geometry::{point_segment_distance_squared, side_of, Segment, Vec2};
use crate::sim::food::{Aversive, Food};
use crate::sim::index::cells::{bucket_by_cell, Geometry, CELLS_PER_ITEM, MAX_CELLS, MIN_CELLS};
use crate::sim::smell::{Smell, WallShade};

/// Cells of the smell grid per largest finite smell range (see the module docs).
const SMELL_CELLS_PER_RANGE: f64 = 2.0;

/// One smell source listed in a cell of the [`SmellGrid`]: `id` is the food object's index,
/// or the food count plus the aversive object's index (so that increasing ids are the order
/// of [`crate::sim::sensors::Surroundings::smell_at_all`]: food, then aversive objects), and
/// `walls[w0..w1]` of the grid are the fixed opaque walls that may cross a segment from a
/// point of the cell to the source's centre. The centre and θ² are copies of the object's
/// (food and aversive objects never move), so that the range test of a listed source, which
/// most sources fail, reads the list alone.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Source {
    /// The object's centre.
    pub centre: Vec2,
    /// The object's θ² ([`Smell::range_squared`], finite).
    pub range_squared: f64,
    /// Food index, or food count + aversive index.
    pub id: u32,
    pub(super) w0: u32,
    pub(super) w1: u32,
    /// Index of its [`Odour`] in the grid's.
    pub(super) odour: u32,
}

impl Source {
    const NONE: Source = Source {
        centre: Vec2::ZERO,
        range_squared: 0.0,
        id: 0,
        w0: 0,
        w1: 0,
        odour: 0,
    };

    /// Are there fixed opaque walls that may hide it from its cell
    /// ([`StaticIndex::source_walls`] is not empty)?
    #[inline(always)]
    pub fn has_walls(&self) -> bool {
        self.w1 > self.w0
    }
}

/// The emission of listed smell sources ([`Smell::emission`], copied when the index is built:
/// food and aversive objects never change their smell), its lone non-zero component if it
/// has one, and whether it is food whose smell follows its amount: so that summing a source's
/// smell reads the grid alone, unless its smell follows its amount.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Odour {
    /// i · o.
    pub emission: [f64; 8],
    /// The only component of `emission` that is not ±0.0, when there is exactly one. Then
    /// every other term `f · emission[k]` of a finite factor f is ±0.0, and adding ±0.0
    /// leaves a smell accumulator as it is (an accumulator starts at +0.0 and a sum of
    /// floats is −0.0 only when both terms are, so it is never −0.0, and x ± 0.0 is x for
    /// every other x, NaN included): adding this one term gives the bits of adding all eight.
    pub lone: Option<u8>,
    /// Food whose smell follows its amount (else [`Food::smell_scale`] is 1, or it is an
    /// aversive object).
    pub follows: bool,
}

impl Odour {
    fn new(emission: &[f64; 8], follows: bool) -> Odour {
        let mut nonzero = (0..8u8).filter(|&k| emission[k as usize] != 0.0);
        let lone = match (nonzero.next(), nonzero.next()) {
            (Some(k), None) => Some(k),
            _ => None,
        };
        Odour {
            emission: *emission,
            lone,
            follows,
        }
    }

    /// The same emission, to the bit, and the same scale?
    fn same(&self, other: &Odour) -> bool {
        self.follows == other.follows
            && self
                .emission
                .iter()
                .zip(other.emission.iter())
                .all(|(a, b)| a.to_bits() == b.to_bits())
    }
}

/// The smelly food and aversive objects of finite range, as [`Source`]s in id order (food,
/// then aversive objects), and their distinct emissions, which the sources reference.
pub(super) fn finite_sources(food: &[Food], aversives: &[Aversive]) -> (Vec<Source>, Vec<Odour>) {
    let food_count = food.len();
    // The smelly objects of finite range, in id order (food, then aversive objects), and
    // their distinct emissions.
    let mut odours: Vec<Odour> = Vec::new();
    let mut finite = |id: usize, p: Vec2, s: &Smell, follows: bool| {
        if s.silent || !s.range_squared.is_finite() {
            return None;
        }
        let odour = Odour::new(&s.emission, follows);
        let k = odours
            .iter()
            .position(|o| o.same(&odour))
            .unwrap_or_else(|| {
                odours.push(odour);
                odours.len() - 1
            });
        Some(Source {
            centre: p,
            range_squared: s.range_squared,
            id: id as u32,
            odour: k as u32,
            ..Source::NONE
        })
    };
    let mut sources: Vec<Source> = Vec::with_capacity(food.len() + aversives.len());
    for (k, f) in food.iter().enumerate() {
        sources.extend(finite(k, f.position, &f.smell, f.smell_follows_amount));
    }
    for (k, a) in aversives.iter().enumerate() {
        sources.extend(finite(food_count + k, a.position, &a.smell, false));
    }
    (sources, odours)
}

/// A [`WallShade`] as four lower bounds, `[x0, y0, −x1, −y1]`, for a receptor given as
/// `[x, y, −x, −y]` ([`FacedShade::key`]): its four tests are then the same comparison,
/// which the compiler makes one vector comparison. `x ≤ x1` is `−x ≥ −x1` exactly (a
/// negation is exact, and a NaN fails both), so the answers are those of
/// [`WallShade::holds`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FacedShade {
    /// `[x0, y0, −x1, −y1]`.
    pub low: [f64; 4],
}

impl FacedShade {
    /// `shade` as lower bounds.
    pub fn new(shade: WallShade) -> FacedShade {
        FacedShade {
            low: [shade.x0, shade.y0, -shade.x1, -shade.y1],
        }
    }

    /// A receptor at `r` as [`FacedShade::holds`] reads it.
    #[inline(always)]
    pub fn key(r: Vec2) -> [f64; 4] {
        [r.x, r.y, -r.x, -r.y]
    }

    /// [`WallShade::holds`] for the receptor of `key` ([`FacedShade::key`]).
    #[inline(always)]
    pub fn holds(&self, key: &[f64; 4], ask: bool) -> bool {
        let mut n = u8::from(ask);
        for (k, low) in key.iter().zip(&self.low) {
            n += u8::from(k >= low);
        }
        n == 5
    }
}

/// A fixed opaque wall listed with a smell source, as the occlusion test of a segment from a
/// receptor to the source's centre reads it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShadedWall {
    /// Its [`WallShade`] from the source's centre.
    pub shade: FacedShade,
    /// The wall (a copy of the opaque wall's segment).
    pub segment: Segment,
    /// The side of the source's centre from the wall's line ([`side_of`]), the orientation
    /// of the occlusion test that no receptor changes (see
    /// [`segments_intersect_past_box`](crate::geometry::segments_intersect_past_box)).
    pub side: f64,
}

/// Per cell, the food and aversive objects of finite range whose smell may reach a receptor
/// in the cell, in increasing id order, each with the fixed opaque walls that may hide it
/// from there (see the module docs). Each cell is taken as its box grown by `grow` (the
/// whisker reach, at most a quarter cell) on the sides facing other cells, plus the rounding
/// slack, so that the cell holding the midpoint of a creature's two whisker tips lists what
/// both tips may smell ([`StaticIndex::smell_pair_sources`]): one list for the pair instead
/// of a merge of two, at the cost of a slightly longer list.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct SmellGrid {
    pub(super) geometry: Geometry,
    /// The sources of cell k are `sources[start[k]..start[k + 1]]`.
    pub(super) start: Vec<u32>,
    pub(super) sources: Vec<Source>,
    /// The distinct emissions of the listed sources, referenced by [`Source::odour`].
    pub(super) odours: Vec<Odour>,
    /// Indices into the fixed opaque walls, referenced by [`Source`] ranges.
    pub(super) walls: Vec<u32>,
    /// Per entry of `walls`, its shade, segment and side of the source's centre.
    pub(super) shaded: Vec<ShadedWall>,
    /// The bounds of the columns' grown boxes (infinite on the border sides).
    pub(super) xs: Vec<(f64, f64)>,
    /// Per cell, its grown box and its range of `sources`, side by side for
    /// [`StaticIndex::smell_pair_sources`] (one read of one cache line or two).
    pub(super) cells: Vec<PairCell>,
    /// The bounds of the rows' grown boxes (infinite on the border sides).
    pub(super) ys: Vec<(f64, f64)>,
}

impl SmellGrid {
    /// This grid with its per-cell lists of sources from `(cell, source)` pairs pushed in id
    /// order (a stable counting sort, so each cell's sources keep their increasing id order),
    /// and each cell's grown box beside its range.
    fn with_sources(mut self, pairs: &[(u32, Source)]) -> SmellGrid {
        let (nx, ny) = (self.geometry.nx, self.geometry.ny);
        let (start, sources) = bucket_by_cell(nx * ny, pairs, |s| s);
        self.start = start;
        self.sources = sources;
        self.cells = (0..nx * ny)
            .map(|k| {
                let ((x0, x1), (y0, y1)) = (self.xs[k % nx], self.ys[k / nx]);
                PairCell {
                    lo: Vec2::new(x0, y0),
                    hi: Vec2::new(x1, y1),
                    start: self.start[k],
                    end: self.start[k + 1],
                }
            })
            .collect();
        self
    }

    /// This grid with `odours`, the distinct emissions its sources reference.
    pub(super) fn with_odours(self, odours: Vec<Odour>) -> SmellGrid {
        SmellGrid { odours, ..self }
    }

    /// An empty grid of one cell (no smelly object of finite range).
    pub(super) fn empty(extent: f64) -> SmellGrid {
        let all = vec![(f64::NEG_INFINITY, f64::INFINITY)];
        SmellGrid {
            geometry: Geometry {
                origin: Vec2::ZERO,
                inv_cell: 1.0 / extent,
                cell: extent,
                nx: 1,
                ny: 1,
                last_x: 0.0,
                last_y: 0.0,
            },
            start: vec![0, 0],
            sources: Vec::new(),
            odours: Vec::new(),
            walls: Vec::new(),
            shaded: Vec::new(),
            xs: all.clone(),
            ys: all,
            cells: vec![PairCell {
                lo: Vec2::NEG_INFINITY,
                hi: Vec2::INFINITY,
                start: 0,
                end: 0,
            }],
        }
    }

    /// The bounds of the cells' columns (or rows): cell k spans `[b[k], b[k + 1]]`, widened by
    /// `widen` (at least the slack, so that every point the map from coordinate to cell puts
    /// in it lies inside despite rounding), and unbounded on the grid's border sides, where
    /// points outside the grid are clamped in.
    fn bounds(&self, n: usize, origin: f64, widen: f64) -> Vec<(f64, f64)> {
        let cell = self.geometry.cell;
        (0..n)
            .map(|k| {
                let lo = if k == 0 {
                    f64::NEG_INFINITY
                } else {
                    origin + k as f64 * cell - widen
                };
                let hi = if k + 1 == n {
                    f64::INFINITY
                } else {
                    origin + (k + 1) as f64 * cell + widen
                };
                (lo, hi)
            })
            .collect()
    }
}

/// One cell of the [`SmellGrid`] as [`StaticIndex::smell_pair_sources`] reads it: its grown box
/// (the bounds of its column and row in `xs` and `ys`) and its range of sources.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct PairCell {
    pub(super) lo: Vec2,
    pub(super) hi: Vec2,
    pub(super) start: u32,
    pub(super) end: u32,
}

/// A fixed opaque wall as seen from a smell source's centre `p`, prepared for the test "can
/// the wall meet the convex hull of a cell's box and `p`?" (a segment from a point of the
/// cell to `p` lies in that hull, so a wall that cannot meet it does not cross the segment).
struct Hider {
    /// Index among the fixed opaque walls.
    k: u32,
    lo: Vec2,
    hi: Vec2,
    /// The wall's line: the side of a point q is `ax (q.x − a.x) + ay (q.y − a.y)`.
    a: Vec2,
    ax: f64,
    ay: f64,
    tol: f64,
    /// +1 or −1 when `p` is strictly on that side of the line by more than `tol`, else 0.
    p_side: i8,
    /// The wall's other end, and the source's centre.
    b: Vec2,
    p: Vec2,
}

impl Hider {
    /// `wall` seen from `p`, or `None` when it cannot cross a segment of length at most `r`
    /// ending at `p` (it is farther than `r` from `p`). `r` and `tol` include a slack far
    /// above rounding errors as long as `p` and the wall's ends lie within `bound` of the
    /// origin; otherwise only the box test is used.
    fn new(k: u32, wall: &BoxedSegment, p: Vec2, r: f64, slack: f64, bound: f64) -> Option<Hider> {
        let (a, b) = (wall.segment.a, wall.segment.b);
        let near = |v: Vec2| v.x.abs() <= bound && v.y.abs() <= bound;
        let bounded = near(a) && near(b) && near(p);
        if bounded && point_segment_distance_squared(p, &wall.segment) > r * r {
            return None;
        }
        let d = b - a;
        let (ax, ay) = (-d.y, d.x);
        let tol = slack * (d.x.abs() + d.y.abs());
        let at_p = term(ax, p.x, a.x) + term(ay, p.y, a.y);
        let p_side = if !bounded {
            0
        } else if at_p > tol {
            1
        } else if at_p < -tol {
            -1
        } else {
            0
        };
        Some(Hider {
            k,
            lo: wall.lo,
            hi: wall.hi,
            a,
            ax,
            ay,
            tol,
            p_side,
            b,
            p,
        })
    }

    /// Does the wall hide `p` from every point of the finite box `[lo, hi]`, so that a cell
    /// with that box need not list the source at all? Yes when the wall properly crosses the
    /// segment from each point t of the box to `p`: `p` and the box strictly on opposite
    /// sides of the wall's line, and the wall's ends strictly on opposite sides of the line
    /// through t and `p`, the same way for every t. The orientation of (t, `p`, e) for a
    /// fixed end e is (`p` − t) × (e − t) = `p` × e + (e − `p`) × t, affine in t, and so is
    /// the side of t of the wall's line, so their extremes over the box are at its
    /// corners. A margin of 1e-9 D² (D: the extent of the box, the wall and `p`) is far
    /// above the rounding of these few products, and the exact orientation tests of
    /// [`crate::geometry::segments_intersect`] then find every such segment crossing the
    /// wall (the boxes of crossing segments meet), so `visible` is false from anywhere in
    /// the box: the source adds nothing there.
    fn hides(&self, lo: Vec2, hi: Vec2) -> bool {
        let (a, b, p) = (self.a, self.b, self.p);
        let pts = [lo, hi, a, b, p];
        let span = |v: &dyn Fn(Vec2) -> f64| {
            let (mut l, mut h) = (f64::INFINITY, f64::NEG_INFINITY);
            for &q in &pts {
                l = l.min(v(q));
                h = h.max(v(q));
            }
            h - l
        };
        let d = span(&|q| q.x) + span(&|q| q.y);
        if !d.is_finite() {
            return false;
        }
        let m = 1e-9 * d * d;
        let cross =
            |o: Vec2, u: Vec2, v: Vec2| (u.x - o.x) * (v.y - o.y) - (u.y - o.y) * (v.x - o.x);
        let wp = cross(a, b, p);
        let side = if wp > m {
            1.0
        } else if wp < -m {
            -1.0
        } else {
            return false;
        };
        let corners = [lo, Vec2::new(hi.x, lo.y), Vec2::new(lo.x, hi.y), hi];
        let turn = cross(corners[0], p, a);
        let turn = if turn > m {
            1.0
        } else if turn < -m {
            -1.0
        } else {
            return false;
        };
        corners.iter().all(|&c| {
            side * cross(a, b, c) < -m && turn * cross(c, p, a) > m && turn * cross(c, p, b) < -m
        })
    }

    /// Can the wall meet the convex hull of the box `[lo, hi]` (bounds may be infinite) and
    /// `p`, whose box is `[hlo, hhi]`? False only when the wall's box misses the hull's box,
    /// or the box and `p` lie strictly on one side of the wall's line by more than `tol`.
    /// The side of a point is affine, so its least and greatest values over the box are at
    /// the corners picked by the signs of `ax` and `ay`.
    #[inline]
    fn may_meet(&self, lo: Vec2, hi: Vec2, hlo: Vec2, hhi: Vec2) -> bool {
        if self.hi.x < hlo.x || hhi.x < self.lo.x || self.hi.y < hlo.y || hhi.y < self.lo.y {
            return false;
        }
        let (ax, ay, a) = (self.ax, self.ay, self.a);
        match self.p_side {
            1 => {
                let least = term(ax, if ax > 0.0 { lo.x } else { hi.x }, a.x)
                    + term(ay, if ay > 0.0 { lo.y } else { hi.y }, a.y);
                let apart = least > self.tol;
                !apart
            }
            -1 => {
                let most = term(ax, if ax > 0.0 { hi.x } else { lo.x }, a.x)
                    + term(ay, if ay > 0.0 { hi.y } else { lo.y }, a.y);
                let apart = most < -self.tol;
                !apart
            }
            _ => true,
        }
    }
}

/// `f (v − o)`, or 0 when `f` is 0 (so that an unbounded side of a box along a wall's line
/// adds nothing rather than a NaN).
#[inline]
fn term(f: f64, v: f64, o: f64) -> f64 {
    if f == 0.0 {
        0.0
    } else {
        f * (v - o)
    }
}

/// Builds the [`SmellGrid`] of `sources` (id, centre, θ²; finite ranges only, in id order)
/// over an arena `w` × `h` whose largest side is `extent`, for whisker tips at most `reach`
/// from their midpoint. `near_walls` gives the fixed opaque walls (indices into `opaque`)
/// that may meet a box.
#[allow(clippy::needless_range_loop)] // indexing both bounds tables by cell is clearer
pub(super) fn smell_grid(
    sources: &[Source],
    (w, h, extent, reach): (f64, f64, f64, f64),
    opaque: &[BoxedSegment],
    slack: f64,
    mut near_walls: impl FnMut(Vec2, Vec2, &mut Vec<u32>),
) -> SmellGrid {
    let theta = sources
        .iter()
        .fold(0.0f64, |acc, s| acc.max(s.range_squared.sqrt()));
    if sources.is_empty() || !(theta.is_finite() && theta > 0.0) {
        return SmellGrid::empty(extent);
    }
    // Narrower cells hand each receptor fewer sources but cost more to build (each source
    // is listed in about (2θ / cell + 1)² cells, with its walls sorted out for each).
    let cell = theta / SMELL_CELLS_PER_RANGE;
    let most = (CELLS_PER_ITEM * sources.len()).clamp(MIN_CELLS, MAX_CELLS);
    let geometry = Geometry::covering(w, h, cell, most);
    let (nx, ny) = (geometry.nx, geometry.ny);
    // Grown by the whisker reach (a whisker tip is at most that far from the tips'
    // midpoint), but by at most a quarter cell, so that long whiskers and short ranges do
    // not lengthen every list much; pairs of tips farther apart take two lists.
    let grow = if reach > 0.0 {
        reach.min(geometry.cell / 4.0)
    } else {
        0.0
    };
    let mut grid = SmellGrid {
        geometry,
        start: vec![0; nx * ny + 1],
        sources: Vec::new(),
        odours: Vec::new(),
        walls: Vec::new(),
        shaded: Vec::new(),
        xs: Vec::new(),
        ys: Vec::new(),
        cells: Vec::new(),
    };
    let bound = 1e6 * (1.0 + extent + theta);
    grid.xs = grid.bounds(nx, grid.geometry.origin.x, slack + grow);
    grid.ys = grid.bounds(ny, grid.geometry.origin.y, slack + grow);
    let (xs, ys) = (&grid.xs, &grid.ys);
    // About (2θ / cell + 1)² cells per source, each listing a wall or two.
    let per = (2.0 * SMELL_CELLS_PER_RANGE + 2.0) as usize;
    let mut pairs: Vec<(u32, Source)> = Vec::with_capacity(sources.len() * per * per);
    let mut walls: Vec<u32> = Vec::with_capacity(2 * pairs.capacity());
    let mut shaded: Vec<ShadedWall> = Vec::with_capacity(walls.capacity());
    let mut near = Vec::new();
    let mut hiders: Vec<Hider> = Vec::new();
    for template in sources {
        let (p, range_squared) = (template.centre, template.range_squared);
        let r = range_squared.sqrt() + slack;
        let (lo, hi) = (p - r, p + r);
        near.clear();
        near_walls(lo, hi, &mut near);
        // Only walls within θ of p can cross a segment from a receptor in range to p.
        hiders.clear();
        hiders.extend(
            near.iter()
                .filter_map(|&k| Hider::new(k, &opaque[k as usize], p, r, slack, bound)),
        );
        // The cells whose grown boxes may come within r of p (one slack more, far above
        // the rounding of the map from coordinate to cell).
        let c = grid
            .geometry
            .cells(lo - (grow + slack), hi + (grow + slack));
        for y in c.y0..=c.y1 {
            let (ylo, yhi) = ys[y];
            // Distance from p to the cell's box (0 inside it), by axis.
            let dy = gap(ylo, yhi, p.y);
            for x in c.x0..=c.x1 {
                let (xlo, xhi) = xs[x];
                let dx = gap(xlo, xhi, p.x);
                let reaches = dx * dx + dy * dy <= r * r;
                if !reaches {
                    continue;
                }
                let (clo, chi) = (Vec2::new(xlo, ylo), Vec2::new(xhi, yhi));
                let w0 = walls.len() as u32;
                if !list_hiders(&hiders, (clo, chi), p, opaque, &mut walls, &mut shaded) {
                    continue;
                }
                let w1 = walls.len() as u32;
                let source = Source {
                    w0,
                    w1,
                    ..*template
                };
                pairs.push(((y * nx + x) as u32, source));
            }
        }
    }
    grid.walls = walls;
    grid.shaded = shaded;
    grid.with_sources(&pairs)
}

/// Distance from `v` to the span `[lo, hi]` (0 inside it). Plain comparisons rather than
/// f64::min/max (which handle NaN at a cost): only a finite source centre can be in range of
/// a receptor, and its lists are what matters.
fn gap(lo: f64, hi: f64, v: f64) -> f64 {
    if v < lo {
        lo - v
    } else if v > hi {
        v - hi
    } else {
        0.0
    }
}

/// The lesser of `a` and `b` (`a` when they compare equal or one is NaN).
fn low(a: f64, b: f64) -> f64 {
    if b < a {
        b
    } else {
        a
    }
}

/// The greater of `a` and `b` (`a` when they compare equal or one is NaN).
fn high(a: f64, b: f64) -> f64 {
    if b > a {
        b
    } else {
        a
    }
}

/// Onto `walls` and `shaded`: the walls of `hiders` that may hide the source at `p` from a
/// receptor in the cell's grown box `[clo, chi]`, with their shades. False (and nothing left
/// pushed) when one wall hides it from the whole cell: such a source is not listed there, it
/// would cost an occlusion test per receptor and add nothing.
fn list_hiders(
    hiders: &[Hider],
    (clo, chi): (Vec2, Vec2),
    p: Vec2,
    opaque: &[BoxedSegment],
    walls: &mut Vec<u32>,
    shaded: &mut Vec<ShadedWall>,
) -> bool {
    let w0 = walls.len();
    let hlo = Vec2::new(low(clo.x, p.x), low(clo.y, p.y));
    let hhi = Vec2::new(high(chi.x, p.x), high(chi.y, p.y));
    for h in hiders {
        if h.may_meet(clo, chi, hlo, hhi) {
            if h.hides(clo, chi) {
                walls.truncate(w0);
                shaded.truncate(w0);
                return false;
            }
            walls.push(h.k);
            let segment = opaque[h.k as usize].segment;
            shaded.push(ShadedWall {
                shade: FacedShade::new(WallShade::new(p, h.lo, h.hi)),
                segment,
                side: side_of(&segment, p),
            });
        }
    }
    true
}
