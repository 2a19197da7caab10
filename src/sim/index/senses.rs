//! The fast passes of the senses (§5.2, §7.1–7.3): the same exact tests as the plain loops of
//! [`crate::sim::sensors`] (`*_all`), run only on the candidates the world's indexes hand
//! out, both whiskers and both smell receptors in one pass. What the tick loop uses; the
//! tests compare them with the plain loops (see the contract in [`crate::sim::index`]).

use crate::geometry::BoxedSegment;
use crate::geometry::{
    circles_touch, segment_touches_circle, segments_intersect, segments_intersect_past_box,
    Segment, Vec2,
};
use crate::sim::food::Food;
use crate::sim::index::smell_grid::{FacedShade, Source};
use crate::sim::index::static_grid::{Scratch, SmellBox};
use crate::sim::sensors::{Body, Senses, Surroundings};
use crate::sim::smell::{
    accumulate_listed, add, add_pair, diffusion, falloff_pair, reach_pair, saturate, Shade, Smell,
};

/// The indexed senses of [`Surroundings`].
impl Surroundings<'_> {
    /// [`Surroundings::whisker_touches_all`] on the walls, food and aversive objects the grid
    /// finds around the whisker (the closed doors, creatures and things are few: all of them).
    pub fn whisker_touches(&self, me: usize, body: &Body, from: Vec2, tip: Vec2) -> bool {
        let whisker = Segment::new(from, tip);
        let (lo, hi) = (from.min(tip), from.max(tip));
        let index = self.index;
        let wall =
            |w: &BoxedSegment| w.may_meet(lo, hi) && segments_intersect(&whisker, &w.segment);
        index.any_fixed_wall(lo, hi, |k| wall(&self.walls[k]))
            || self.walls[index.fixed_felt()..].iter().any(wall)
            || self.creatures.iter().enumerate().any(|(j, c)| {
                j != me && c.alive && segment_touches_circle(&whisker, c.pose.position, body.radius)
            })
            || index.any_aversive(lo, hi, |k| {
                let a = &self.aversives[k];
                a.radius > 0.0 && segment_touches_circle(&whisker, a.position, a.radius)
            })
            || index.any_food(lo, hi, |k| {
                let f = &self.food[k];
                f.radius > 0.0 && segment_touches_circle(&whisker, f.position, f.radius)
            })
            || self.things.iter().enumerate().any(|(k, t)| {
                k != self.skip_thing
                    && t.felt
                    && t.radius > 0.0
                    && segment_touches_circle(&whisker, t.position, t.radius)
            })
    }

    /// [`Surroundings::whisker_touches`] for both whiskers from `from` (the body's centre) to
    /// `tips`, and [`Surroundings::food_detectors_all`] for the body of radius `radius` there, in
    /// one pass. One grid query over the box of both whiskers and the body hands out the food
    /// candidates of both senses (a superset of each one's own: a yes/no answer, or an "or"
    /// over the detected types, does not depend on extra candidates or their order). Each
    /// candidate is tested against each whisker not yet touching; the other kinds of things
    /// only matter to the whiskers and are skipped once both touch. The fixed walls and food
    /// objects come from the body's cell of the
    /// [`WhiskerCells`](crate::sim::index::whisker_cells::WhiskerCells) when the query passes their
    /// guard (again a superset, see that module), else from the grid.
    ///
    /// Every answer is an "or" of exact tests that do not depend on one another, so the
    /// order of the passes is free: the fixed walls and food come first, then, only while a
    /// whisker is free and the world has any, the doors, the other creatures, aversive
    /// objects and things ([`Surroundings::whiskers_rest`]). A food object far from both
    /// whiskers is rejected by one box test on the box of both (see [`Whiskers::misses`]).
    #[inline]
    pub fn whiskers_and_food(
        &self,
        me: usize,
        body: &Body,
        from: Vec2,
        tips: [Vec2; 2],
    ) -> ([bool; 2], [bool; 4]) {
        let pair = Whiskers::new(from, tips);
        let index = self.index;
        let (position, radius) = (from, body.radius);
        let mut touch = [false; 2];
        let mut detected = [false; 4];
        // The detectors: an "or" over the substances of the food objects the body touches.
        let detect = |detected: &mut [bool; 4], f: &Food| {
            if circles_touch(position, radius, f.position, f.radius) {
                for (t, d) in detected.iter_mut().enumerate() {
                    *d |= f.holds(t);
                }
            }
        };
        // The cell's shortlists when the query passes their guard, else the index's.
        match index
            .whisker_cells()
            .and_then(|c| c.lists(position, pair.ulo, pair.uhi, radius))
        {
            Some((walls, listed)) => {
                for &k in walls {
                    if pair.wall(&mut touch, &self.walls[k as usize]) {
                        break;
                    }
                }
                let finite = pair.finite();
                for &k in listed {
                    let f = &self.food[k as usize];
                    if f.radius > 0.0
                        && !(touch[0] && touch[1])
                        && !(finite && pair.misses(f.position, f.radius))
                    {
                        pair.circle(&mut touch, f.position, f.radius);
                    }
                    detect(&mut detected, f);
                }
            }
            None => self.walls_and_food_indexed(&pair, radius, &mut touch, &mut detected),
        }
        if !(touch[0] && touch[1])
            && (self.walls.len() > index.fixed_felt()
                || self.creatures.len() > 1
                || !self.aversives.is_empty()
                || !self.things.is_empty())
        {
            self.whiskers_rest(me, body, &pair, &mut touch);
        }
        (touch, detected)
    }

    /// The fixed walls and food objects of [`Surroundings::whiskers_and_food`] when the query
    /// fails the lists' guard: from the grid, for the box of both whiskers (and the body's box
    /// for the food). Out of line, so that the common path keeps its registers.
    #[inline(never)]
    fn walls_and_food_indexed(
        &self,
        pair: &Whiskers,
        radius: f64,
        touch: &mut [bool; 2],
        detected: &mut [bool; 4],
    ) {
        let (index, position) = (self.index, pair.pair.from);
        let (ulo, uhi) = (pair.ulo, pair.uhi);
        let _ = index.any_fixed_wall(ulo, uhi, |k| pair.wall(touch, &self.walls[k]));
        let (lo, hi) = (ulo.min(position - radius), uhi.max(position + radius));
        index.any_food(lo, hi, |k| {
            let f = &self.food[k];
            if f.radius > 0.0 && !(touch[0] && touch[1]) {
                pair.circle(touch, f.position, f.radius);
            }
            if circles_touch(position, radius, f.position, f.radius) {
                for (t, d) in detected.iter_mut().enumerate() {
                    *d |= f.holds(t);
                }
            }
            false
        });
    }

    /// The whisker tests of [`Surroundings::whiskers_and_food`] on what the world has besides
    /// fixed walls and food: doors, the other living creatures, aversive objects (from the
    /// grid) and things, for each whisker not yet touching (`touch`).
    #[inline(never)]
    fn whiskers_rest(&self, me: usize, body: &Body, pair: &Whiskers, touch: &mut [bool; 2]) {
        let index = self.index;
        let _ = self.walls[index.fixed_felt()..]
            .iter()
            .any(|w| pair.wall(touch, w))
            || self.creatures.iter().enumerate().any(|(j, c)| {
                j != me && c.alive && pair.circle(touch, c.pose.position, body.radius)
            })
            || index.any_aversive(pair.ulo, pair.uhi, |k| {
                let a = &self.aversives[k];
                a.radius > 0.0 && pair.circle(touch, a.position, a.radius)
            })
            || self.things.iter().enumerate().any(|(k, t)| {
                k != self.skip_thing
                    && t.felt
                    && t.radius > 0.0
                    && pair.circle(touch, t.position, t.radius)
            });
    }

    /// [`Surroundings::smell_at_all`] at both receptors `tips`. The food and aversive objects
    /// of finite range come from the index's smell grid: a cell lists, in index order, the
    /// objects that may reach a receptor in it, each with its centre and range (so that an
    /// object out of range of both receptors costs a few instructions) and the fixed opaque
    /// walls that may hide it from there, so such an object is tested for occlusion against
    /// those walls and the closed doors only. Mostly one cell serves both receptors
    /// ([`StaticIndex::smell_pair_sources`](crate::sim::index::StaticIndex::smell_pair_sources)); otherwise each receptor's cell serves it, in a
    /// merge of both lists. The objects of unlimited range, the areas, things and creatures
    /// are tested against the opaque walls that meet the smell box of the pair (the largest
    /// finite range around both receptors) when their centre lies in it, else against every
    /// opaque wall; those walls are only gathered when such a source is in range. One pass
    /// over the sources serves both receptors; each receptor still adds its terms in the
    /// order of [`Surroundings::smell_at_all`].
    ///
    /// In the common case, a world whose only smells are food and aversive objects of
    /// finite range with no closed opaque door, and receptors served by one list,
    /// [`Surroundings::smell_listed`] does the same sums in a small function of its own.
    ///
    /// The sums are added into `out`, left and right sensor, which must hold zeros (the
    /// caller's fresh sensors), and saturated there: the caller copies them on from `out`
    /// rather than from a returned value's copy of the function's own accumulators.
    #[inline]
    pub fn smell_pair(
        &self,
        me: usize,
        body: &Body,
        tips: [Vec2; 2],
        scratch: &mut Scratch,
        out: &mut [[f64; 8]; 2],
    ) {
        debug_assert!(out.iter().flatten().all(|&v| v.to_bits() == 0));
        let index = self.index;
        let others_smell = !body.smell.silent && self.creatures.len() > 1;
        if index.smell_always().is_empty()
            && self.areas.is_empty()
            && self.things.is_empty()
            && !others_smell
            && self.opaque.len() == index.fixed_opaque()
        {
            if let Some(list) = index.smell_pair_sources_inlined(tips) {
                return self.smell_listed(list, tips, out);
            }
        }
        self.smell_general(me, body, tips, scratch, out);
    }

    /// [`Surroundings::smell_pair`] when only `list`, the food and aversive objects of finite
    /// range listed for both receptors, may be smelled, and only the fixed opaque walls hide
    /// them: the terms of [`accumulate_listed`] in list order, into accumulators local to this
    /// small function. What a term needs beyond the list comes from the grid too: the
    /// source's [`Odour`](crate::sim::index::smell_grid::Odour) (its emission, one term instead of eight
    /// when only one component is not 0, and whether its amount scales it, the only case that
    /// reads the food object), and for a source with walls, each wall's
    /// [`WallShade`](crate::sim::smell::WallShade), which settles the box test of
    /// [`visible_among`](crate::sim::smell::visible_among) for both receptors without a branch
    /// per side, and each wall's side of the source's centre, one of the four orientations
    /// of the occlusion test, with a copy of the wall
    /// ([`StaticIndex::source_shaded_walls`]).
    #[inline(never)]
    fn smell_listed(&self, list: &[Source], tips: [Vec2; 2], out: &mut [[f64; 8]; 2]) {
        let index = self.index;
        let c = self.smell_c;
        let [acc0, acc1] = out;
        // The receptors as the walls' shades read them.
        let keys = tips.map(FacedShade::key);
        for s in list {
            let (d2, reach) = reach_pair(tips, s.centre, s.range_squared);
            if !(reach[0] | reach[1]) {
                continue;
            }
            let q = [diffusion(c, d2[0]), diffusion(c, d2[1])];
            let f0 = if reach[0] { q[0] } else { 0.0 };
            let f1 = if reach[1] { q[1] } else { 0.0 };
            // accumulate_listed skips a source whose falloffs are both 0 before its scale:
            // here that scale (pure) is read anyway, and neither receptor adds it.
            let odour = index.odour(s);
            let scale = if odour.follows {
                self.food[s.id as usize].smell_scale()
            } else {
                1.0
            };
            if scale == 0.0 {
                continue;
            }
            let mut seen = [f0 != 0.0, f1 != 0.0];
            if s.has_walls() {
                // visible_among without doors, both receptors per wall, with the box test
                // of each settled by the wall's shade: it holds only for a tip not NaN, and
                // the centre of a source in reach is not NaN either, so the box test that
                // segments_intersect would begin with passes; the rest of it takes the
                // source's side of the wall from the grid.
                for w in index.source_shaded_walls(s) {
                    for (i, &tip) in tips.iter().enumerate() {
                        if w.shade.holds(&keys[i], seen[i])
                            && segments_intersect_past_box(
                                &Segment::new(tip, s.centre),
                                &w.segment,
                                w.side,
                            )
                        {
                            seen[i] = false;
                        }
                    }
                }
            }
            let g = [f0 * scale, f1 * scale];
            match odour.lone {
                // One term instead of eight (see Odour::lone), when its factors are finite.
                Some(k) if g[0].is_finite() & g[1].is_finite() => {
                    // k < 8 (Odour::lone): the mask only spares the bounds checks.
                    let k = usize::from(k) & 7;
                    let e = odour.emission[k];
                    if seen[0] {
                        acc0[k] += g[0] * e;
                    }
                    if seen[1] {
                        acc1[k] += g[1] * e;
                    }
                }
                _ => {
                    if seen[0] {
                        add(acc0, g[0], &odour.emission);
                    }
                    if seen[1] {
                        add(acc1, g[1], &odour.emission);
                    }
                }
            }
        }
        saturate(acc0);
        saturate(acc1);
    }

    /// [`Surroundings::smell_pair`] for any world, into `out`.
    #[inline(never)]
    fn smell_general(
        &self,
        me: usize,
        body: &Body,
        tips: [Vec2; 2],
        scratch: &mut Scratch,
        out: &mut [[f64; 8]; 2],
    ) {
        let index = self.index;
        // Local accumulators: summing through `out` costs more in this large function.
        let acc = &mut [[0.0; 8]; 2];
        let all = self.opaque;
        let walls = all.split_at(index.fixed_opaque());
        let always = index.smell_always();
        let mut near = Near::new(tips);
        let pair = index.smell_pair_sources(tips);
        match pair {
            Some(list) if always.is_empty() => {
                for s in list {
                    let (d2, reach) = reach_pair(tips, s.centre, s.range_squared);
                    if reach[0] | reach[1] {
                        let w = index.source_walls(s);
                        self.listed(acc, tips, s, (d2, reach), [w, w], walls);
                    }
                }
            }
            _ => self.smell_merged(pair, always, tips, walls, &mut near, acc, scratch),
        }
        self.smell_moving(me, body, &mut near, acc, scratch);
        saturate(&mut acc[0]);
        saturate(&mut acc[1]);
        *out = *acc;
    }

    /// The listed sources of [`Surroundings::smell_general`] when the pair's list does not
    /// serve alone: a three-way merge of both receptors' lists (`pair` for both when it
    /// serves them) and the unlimited-range objects `always`, in increasing id order.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn smell_merged(
        &self,
        pair: Option<&[Source]>,
        always: &[u32],
        tips: [Vec2; 2],
        walls: (&[BoxedSegment], &[BoxedSegment]),
        near: &mut Near,
        acc: &mut [[f64; 8]; 2],
        scratch: &mut Scratch,
    ) {
        let index = self.index;
        let food_count = index.food_count();
        // A three-way merge of both receptors' lists (the same one when it serves
        // both) and the unlimited-range objects, in increasing id order (an id is
        // either listed or of unlimited range).
        let lists = pair.map_or_else(
            || {
                let cells = [index.smell_cell(tips[0]), index.smell_cell(tips[1])];
                [index.smell_sources(cells[0]), index.smell_sources(cells[1])]
            },
            |l| [l, l],
        );
        let (mut i, mut j, mut k) = (0, 0, 0);
        let id = |l: &[Source], i: usize| l.get(i).map_or(u32::MAX, |s| s.id);
        loop {
            let a = id(lists[0], i);
            let b = id(lists[1], j);
            let u = always.get(k).copied().unwrap_or(u32::MAX);
            let m = a.min(b).min(u);
            if m == u32::MAX {
                break;
            }
            if m == u {
                k += 1;
                let x = m as usize;
                if x < food_count {
                    let f = &self.food[x];
                    near.source(self, acc, f.position, &f.smell, || f.smell_scale(), scratch);
                } else {
                    let a = &self.aversives[x - food_count];
                    near.source(self, acc, a.position, &a.smell, || 1.0, scratch);
                }
                continue;
            }
            let (sa, sb) = (
                (a == m).then(|| &lists[0][i]),
                (b == m).then(|| &lists[1][j]),
            );
            i += usize::from(a == m);
            j += usize::from(b == m);
            // Both entries are copies of the object's centre and range.
            let Some(s) = sa.or(sb) else { continue };
            let (d2, reach) = reach_pair(tips, s.centre, s.range_squared);
            let reach = [reach[0] && sa.is_some(), reach[1] && sb.is_some()];
            if reach[0] | reach[1] {
                let w = |e: Option<&Source>| e.map_or(&[][..], |e| index.source_walls(e));
                self.listed(acc, tips, s, (d2, reach), [w(sa), w(sb)], walls);
            }
        }
    }

    /// The sources of [`Surroundings::smell_general`] that no index lists: areas, things and
    /// the other living creatures (when the body smells), in that order.
    #[inline(always)]
    fn smell_moving(
        &self,
        me: usize,
        body: &Body,
        near: &mut Near,
        acc: &mut [[f64; 8]; 2],
        scratch: &mut Scratch,
    ) {
        for a in self.areas {
            near.source(self, acc, a.centre(), &a.smell, || 1.0, scratch);
        }
        for (k, t) in self.things.iter().enumerate() {
            if k != self.skip_thing && !t.smell.silent {
                near.source(self, acc, t.position, &t.smell, || 1.0, scratch);
            }
        }
        if !body.smell.silent {
            for (j, other) in self.creatures.iter().enumerate() {
                if j != me && other.alive {
                    let p = other.pose.position;
                    near.source(self, acc, p, &other.body_smell, || 1.0, scratch);
                }
            }
        }
    }

    /// [`accumulate_listed`] for the food or aversive object of `source` (food first, as in
    /// [`Source::id`]), in range of at least one receptor.
    #[inline(always)]
    fn listed(
        &self,
        acc: &mut [[f64; 8]; 2],
        tips: [Vec2; 2],
        source: &Source,
        range: ([f64; 2], [bool; 2]),
        w: [&[u32]; 2],
        walls: (&[BoxedSegment], &[BoxedSegment]),
    ) {
        let (k, c, centre) = (source.id as usize, self.smell_c, source.centre);
        let food_count = self.index.food_count();
        if k < food_count {
            let f = &self.food[k];
            let scale = || f.smell_scale();
            accumulate_listed(
                acc,
                tips,
                centre,
                range,
                &f.smell.emission,
                scale,
                c,
                w,
                walls,
            );
        } else {
            let e = &self.aversives[k - food_count].smell.emission;
            accumulate_listed(acc, tips, centre, range, e, || 1.0, c, w, walls);
        }
    }

    /// Everything creature `me` senses now (the grid's version of
    /// [`Surroundings::sense_all`], with the same answers). Smell is computed only when
    /// `smell` is true (the controller receives it, or a trace wants it), and not at all while
    /// a whisker touches under `inhibit_smell_on_whisker` (§7.3).
    #[inline]
    pub fn sense(
        &self,
        me: usize,
        body: &Body,
        smell: bool,
        inhibit_smell: bool,
        scratch: &mut Scratch,
    ) -> Senses {
        let pose = self.creatures[me].pose;
        let tips = body.whisker_tips(pose.position, pose.heading);
        let (whiskers, food) = self.whiskers_and_food(me, body, pose.position, tips);
        let inhibited = inhibit_smell && (whiskers[0] || whiskers[1]);
        let mut out = [[0.0; 8]; 2];
        if smell && !inhibited {
            self.smell_pair(me, body, tips, scratch, &mut out);
        }
        let smell = out;
        Senses {
            whiskers,
            smell,
            food,
        }
    }
}

/// A creature's two whiskers in one tick: from the body's centre `from` to each of `tips`.
struct WhiskerPair {
    from: Vec2,
    tips: [Vec2; 2],
}

impl WhiskerPair {
    /// Whisker `i` and its box.
    #[inline(always)]
    fn whisker(&self, i: usize) -> (Segment, Vec2, Vec2) {
        let (from, tip) = (self.from, self.tips[i]);
        (Segment::new(from, tip), from.min(tip), from.max(tip))
    }

    /// [`Whiskers::wall`] past the box of both whiskers.
    #[inline(never)]
    fn wall_near(&self, touch: &mut [bool; 2], w: &BoxedSegment) -> bool {
        for (i, touch) in touch.iter_mut().enumerate() {
            let (whisker, lo, hi) = self.whisker(i);
            if !*touch && w.may_meet(lo, hi) && segments_intersect(&whisker, &w.segment) {
                *touch = true;
            }
        }
        touch[0] && touch[1]
    }

    /// The whisker test of a circle of radius `radius` at `centre` for each whisker not yet
    /// touching (`touch`); true when both touch.
    #[inline(never)]
    fn circle(&self, touch: &mut [bool; 2], centre: Vec2, radius: f64) -> bool {
        for (i, touch) in touch.iter_mut().enumerate() {
            let (whisker, _, _) = self.whisker(i);
            if !*touch && segment_touches_circle(&whisker, centre, radius) {
                *touch = true;
            }
        }
        touch[0] && touch[1]
    }
}

/// A creature's two whiskers with the box of both, which rejects most walls and food
/// objects for both whiskers at once.
struct Whiskers {
    pair: WhiskerPair,
    /// The box of both whiskers: the `min` (`max`) of each whisker's box corner, as
    /// `Segment::bounds` computes them.
    ulo: Vec2,
    uhi: Vec2,
}

impl Whiskers {
    #[inline(always)]
    fn new(from: Vec2, tips: [Vec2; 2]) -> Whiskers {
        let lo = [from.min(tips[0]), from.min(tips[1])];
        let hi = [from.max(tips[0]), from.max(tips[1])];
        Whiskers {
            pair: WhiskerPair { from, tips },
            ulo: lo[0].min(lo[1]),
            uhi: hi[0].max(hi[1]),
        }
    }

    /// Are the centre and both tips finite? Then each whisker's box lies in the box of both
    /// (no NaN to drop out of a `min` or `max`).
    #[inline(always)]
    #[allow(clippy::eq_op)] // x − x is the finiteness test, on purpose
    fn finite(&self) -> bool {
        let WhiskerPair { from, tips } = self.pair;
        // x − x is 0 for a finite x and NaN otherwise, and a NaN term makes the sum NaN.
        let d = |v: Vec2| (v.x - v.x) + (v.y - v.y);
        d(from) + d(tips[0]) + d(tips[1]) == 0.0
    }

    /// The rejection of `circle_touches_segment` (eq. 2–3) for a circle of radius `r` at
    /// `c`, against the box of both whiskers: when it holds, each whisker's own box, inside
    /// that box when [`Whiskers::finite`], rejects the circle too (`lo − r` and `hi + r` are
    /// monotone in `lo` and `hi`), so neither whisker touches it.
    #[inline(always)]
    fn misses(&self, c: Vec2, r: f64) -> bool {
        (c.x < self.ulo.x - r)
            | (c.x > self.uhi.x + r)
            | (c.y < self.ulo.y - r)
            | (c.y > self.uhi.y + r)
    }

    /// The whisker test of wall `w` for each whisker not yet touching (`touch`); true when
    /// both touch. Most walls miss the box of both whiskers: one box test rejects them.
    #[inline(always)]
    fn wall(&self, touch: &mut [bool; 2], w: &BoxedSegment) -> bool {
        w.may_meet(self.ulo, self.uhi) && self.pair.wall_near(touch, w)
    }

    /// [`WhiskerPair::circle`].
    #[inline(always)]
    fn circle(&self, touch: &mut [bool; 2], centre: Vec2, radius: f64) -> bool {
        self.pair.circle(touch, centre, radius)
    }
}

/// The occluders of the smell sources that the smell grid does not list (objects of
/// unlimited range, areas, things, creatures): the opaque walls meeting the smell box of both
/// receptors, as each receptor sees them, gathered into the scratch space at the first such
/// source in range of a receptor.
struct Near {
    tips: [Vec2; 2],
    /// The smell box, once the walls are gathered.
    bx: Option<SmellBox>,
}

impl Near {
    fn new(tips: [Vec2; 2]) -> Near {
        Near { tips, bx: None }
    }

    /// [`accumulate`](crate::sim::smell::accumulate) at both receptors for a thing at `centre`.
    #[inline(always)]
    fn source(
        &mut self,
        s: &Surroundings<'_>,
        acc: &mut [[f64; 8]; 2],
        centre: Vec2,
        smell: &Smell,
        scale: impl FnOnce() -> f64,
        scratch: &mut Scratch,
    ) {
        let tips = self.tips;
        let Some(f) = falloff_pair(tips, centre, smell, s.smell_c) else {
            return;
        };
        let scale = scale();
        if scale == 0.0 {
            return;
        }
        let bx = match self.bx {
            Some(bx) => bx,
            None => {
                let (lo, hi) = (tips[0].min(tips[1]), tips[0].max(tips[1]));
                let bx = s.index.near_opaque(lo, hi, s.opaque, scratch);
                let Scratch { near, shades, .. } = &mut *scratch;
                for (shades, &tip) in shades.iter_mut().zip(tips.iter()) {
                    shades.clear();
                    shades.extend(near.iter().map(|w| Shade::new(tip, w)));
                }
                self.bx = Some(bx);
                bx
            }
        };
        let shades = [&scratch.shades[0][..], &scratch.shades[1][..]];
        add_pair(
            acc,
            tips,
            centre,
            smell,
            (f, scale),
            (bx.lo, bx.hi, shades),
            s.opaque,
        );
    }
}
