//! A creature's senses (§5.2, §7.1–7.3): whiskers, the two smell sensors at the whisker tips,
//! the four food detectors and the shock sensor, and how they are written into the
//! controller's observation vector.
//!
//! Each sense comes twice: the plain loops over every object (`*_all`, the reference the
//! tests compare against) and the same tests run only on the candidates the world's
//! [`StaticIndex`] yields (what the tick loop uses), for both whiskers and both smell
//! receptors in one pass. Candidates come in index order, and the tests are the same
//! functions or give provably the same answers (a yes/no test does not depend on extra
//! candidates; see [`crate::sim::smell::Shade`]), so both give the same bits.

use crate::geometry::{
    circles_touch, segment_touches_circle, segments_intersect, segments_intersect_past_box,
    Segment, Vec2,
};
use crate::sim::area::Area;
use crate::sim::controller::{ObservationLayout, SensorGroup};
use crate::sim::creature::Creature;
use crate::sim::food::{Aversive, Food};
use crate::sim::gadgets::Thing;
use crate::sim::index::smell_grid::{FacedShade, Source};
use crate::sim::index::static_grid::{Scratch, SmellBox, StaticIndex};
use crate::sim::smell::{
    accumulate, accumulate_listed, add, add_pair, diffusion, falloff_pair, reach_pair, saturate,
    Shade, Smell,
};
use crate::sim::wall::BoxedSegment;

/// The body geometry the senses need, precomputed from the creature spec once per world.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Body {
    /// Body radius d/2 in LU.
    pub radius: f64,
    /// Whisker length s in LU.
    pub whisker_length: f64,
    /// cos φ and sin φ of the whisker angle, so that no sine is computed per tick.
    pub whisker_cos: f64,
    /// See `whisker_cos`.
    pub whisker_sin: f64,
    /// The creatures' body smell when all share one (`[creature] odour`); with `odours`,
    /// the largest of theirs, component by component. The senses read only whether it is
    /// silent (then no creature's body smells, and the other creatures are skipped); each
    /// creature gives off its own [`Creature::body_smell`].
    pub smell: Smell,
}

impl Body {
    /// The left and right whisker tips of a body at `position` heading `heading` (unit).
    /// Left is the heading rotated by −φ, right by +φ, with the rotation of eq. 32 (positive =
    /// clockwise on screen, y down), the same convention as `motion::rotate`.
    #[inline]
    pub fn whisker_tips(&self, position: Vec2, heading: Vec2) -> [Vec2; 2] {
        let (c, s) = (self.whisker_cos, self.whisker_sin);
        let left = Vec2::new(heading.x * c + heading.y * s, heading.y * c - heading.x * s);
        let right = Vec2::new(heading.x * c - heading.y * s, heading.x * s + heading.y * c);
        [
            position + left * self.whisker_length,
            position + right * self.whisker_length,
        ]
    }
}

/// Everything around a creature that its senses read: the world as left by the objects that
/// moved before it this tick.
pub struct Surroundings<'a> {
    /// Every wall (what whiskers feel).
    pub walls: &'a [BoxedSegment],
    /// Opaque walls (what hides smells).
    pub opaque: &'a [BoxedSegment],
    /// Food objects.
    pub food: &'a [Food],
    /// Aversive objects.
    pub aversives: &'a [Aversive],
    /// Areas (only their smell matters here).
    pub areas: &'a [Area],
    /// Every creature, the sensing one included (skipped by index).
    pub creatures: &'a [Creature],
    /// Door triggers, teleporter entries, wanderers, predators and smelly landmarks.
    pub things: &'a [Thing],
    /// Index in `things` of the sensing body itself when it is a wanderer or predator
    /// (`usize::MAX` for a creature).
    pub skip_thing: usize,
    /// The constant c of eq. 25.
    pub smell_c: f64,
    /// The grid over `food`, `aversives` and the fixed walls (the first
    /// [`StaticIndex::fixed_felt`] of `walls` and [`StaticIndex::fixed_opaque`] of `opaque`).
    pub index: &'a StaticIndex,
}

/// What one creature senses in one tick (before the shock sensor, which it carries over from
/// its previous tick).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Senses {
    /// Left and right whisker touching something.
    pub whiskers: [bool; 2],
    /// Left and right smell sensors, 8 receptors each, in [0, 1].
    pub smell: [[f64; 8]; 2],
    /// Food detectors A–D.
    pub food: [bool; 4],
}

impl Surroundings<'_> {
    /// §7.3: does a whisker from `from` to `tip` touch a wall, or a circle of radius > 0 other
    /// than creature `me`'s own body? Point objects (radius 0) are not felt (SPEC-NOTES).
    pub fn whisker_touches_all(&self, me: usize, body: &Body, from: Vec2, tip: Vec2) -> bool {
        let whisker = Segment::new(from, tip);
        let (lo, hi) = (from.min(tip), from.max(tip));
        self.walls
            .iter()
            .any(|w| w.may_meet(lo, hi) && segments_intersect(&whisker, &w.segment))
            || self.creatures.iter().enumerate().any(|(j, c)| {
                j != me && c.alive && segment_touches_circle(&whisker, c.pose.position, body.radius)
            })
            || self
                .aversives
                .iter()
                .any(|a| a.radius > 0.0 && segment_touches_circle(&whisker, a.position, a.radius))
            || self
                .food
                .iter()
                .any(|f| f.radius > 0.0 && segment_touches_circle(&whisker, f.position, f.radius))
            || self.things.iter().enumerate().any(|(k, t)| {
                k != self.skip_thing
                    && t.felt
                    && t.radius > 0.0
                    && segment_touches_circle(&whisker, t.position, t.radius)
            })
    }

    /// §7.1: one smell sensor at `receptor`: receptor k = min(1, Σ I(d) o_k) over the smelly
    /// things it can see: food, aversive objects, areas (from their centre, §4.6), gadgets,
    /// wanderers, predators and every other living creature.
    pub fn smell_at_all(&self, me: usize, body: &Body, receptor: Vec2) -> [f64; 8] {
        let mut acc = [0.0; 8];
        let (c, opaque) = (self.smell_c, self.opaque);
        for f in self.food {
            accumulate(
                &mut acc,
                receptor,
                f.position,
                &f.smell,
                f.smell_scale(),
                c,
                opaque,
            );
        }
        for a in self.aversives {
            accumulate(&mut acc, receptor, a.position, &a.smell, 1.0, c, opaque);
        }
        for a in self.areas {
            accumulate(&mut acc, receptor, a.centre(), &a.smell, 1.0, c, opaque);
        }
        for (k, t) in self.things.iter().enumerate() {
            if k != self.skip_thing && !t.smell.silent {
                accumulate(&mut acc, receptor, t.position, &t.smell, 1.0, c, opaque);
            }
        }
        if !body.smell.silent {
            for (j, other) in self.creatures.iter().enumerate() {
                if j != me && other.alive {
                    accumulate(
                        &mut acc,
                        receptor,
                        other.pose.position,
                        &other.body_smell,
                        1.0,
                        c,
                        opaque,
                    );
                }
            }
        }
        saturate(&mut acc);
        acc
    }

    /// §5.2: food detector X reads 1 while the body (radius `radius` at `position`) is in
    /// contact (eq. 1) with a food object holding substance X > 0.
    pub fn food_detectors_all(&self, position: Vec2, radius: f64) -> [bool; 4] {
        let mut detected = [false; 4];
        for f in self.food {
            if circles_touch(position, radius, f.position, f.radius) {
                for (t, d) in detected.iter_mut().enumerate() {
                    *d |= f.holds(t);
                }
            }
        }
        detected
    }

    /// Everything creature `me` senses now, by the plain loops (the reference for
    /// [`Surroundings::sense`]). Smell is computed only when `smell` is true
    /// (the controller receives it, or a trace wants it), and not at all while a whisker
    /// touches under `inhibit_smell_on_whisker` (§7.3).
    pub fn sense_all(&self, me: usize, body: &Body, smell: bool, inhibit_smell: bool) -> Senses {
        let pose = self.creatures[me].pose;
        let tips = body.whisker_tips(pose.position, pose.heading);
        let whiskers = [
            self.whisker_touches_all(me, body, pose.position, tips[0]),
            self.whisker_touches_all(me, body, pose.position, tips[1]),
        ];
        let inhibited = inhibit_smell && (whiskers[0] || whiskers[1]);
        let smell = if smell && !inhibited {
            [
                self.smell_at_all(me, body, tips[0]),
                self.smell_at_all(me, body, tips[1]),
            ]
        } else {
            [[0.0; 8]; 2]
        };
        Senses {
            whiskers,
            smell,
            food: self.food_detectors_all(pose.position, body.radius),
        }
    }

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
    /// ([`StaticIndex::smell_pair_sources`]); otherwise each receptor's cell serves it, in a
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
    /// source's [`Odour`](crate::sim::index::static_grid::Odour) (its emission, one term instead of eight
    /// when only one component is not 0, and whether its amount scales it, the only case that
    /// reads the food object), and for a source with walls, each wall's
    /// [`WallShade`](crate::sim::index::static_grid::WallShade), which settles the box test of
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
        let food_count = index.food_count();
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
            _ => {
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
                            near.source(
                                self,
                                acc,
                                f.position,
                                &f.smell,
                                || f.smell_scale(),
                                scratch,
                            );
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
        }
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
        saturate(&mut acc[0]);
        saturate(&mut acc[1]);
        *out = *acc;
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

    /// [`accumulate`] at both receptors for a thing at `centre`.
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

/// Where each sensor group starts in the observation vector (`None` = switched off),
/// resolved once so that the per-tick write is a handful of indexed stores.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Offsets {
    smell: Option<usize>,
    whiskers: Option<usize>,
    food: Option<usize>,
    shock: Option<usize>,
    metabolism: Option<usize>,
    /// Start of the landmark bearings.
    pub landmarks: Option<usize>,
    /// Start of the area flags.
    pub areas: Option<usize>,
    /// Start of the retina.
    pub eye: Option<usize>,
    /// Does the controller receive landmarks, areas or the eye (the groups the world writes
    /// itself)? One test skips all three in the common case.
    pub world_groups: bool,
    bias: Option<usize>,
    /// Start of smell, whiskers, food detectors and shock when the controller receives all
    /// four ([`REPORT_WIDTH`] values back to back, as the layout always places them):
    /// [`Offsets::write`] then writes them as one block, with one bounds check instead of
    /// one per group.
    report: Option<usize>,
}

/// Smell (16), whiskers (2), food detectors (4) and shock (1).
const REPORT_WIDTH: usize = 23;

impl Offsets {
    /// The offsets of `layout`.
    pub fn new(layout: &ObservationLayout) -> Offsets {
        let at = |g| layout.range(g).map(|r| r.start);
        Offsets {
            smell: at(SensorGroup::Smell),
            whiskers: at(SensorGroup::Whiskers),
            food: at(SensorGroup::Food),
            shock: at(SensorGroup::Shock),
            metabolism: at(SensorGroup::Metabolism),
            landmarks: at(SensorGroup::Landmarks),
            areas: at(SensorGroup::Areas),
            eye: at(SensorGroup::Eye),
            world_groups: [SensorGroup::Landmarks, SensorGroup::Areas, SensorGroup::Eye]
                .into_iter()
                .any(|g| at(g).is_some()),
            bias: at(SensorGroup::Bias),
            report: match (
                at(SensorGroup::Smell),
                at(SensorGroup::Whiskers),
                at(SensorGroup::Food),
                at(SensorGroup::Shock),
            ) {
                (Some(o), Some(w), Some(f), Some(s))
                    if w == o + 16 && f == o + 18 && s == o + 22 =>
                {
                    Some(o)
                }
                _ => None,
            },
        }
    }

    /// Does the controller receive smell?
    pub fn has_smell(&self) -> bool {
        self.smell.is_some()
    }

    /// Writes one observation's report groups (smell to metabolism, and the bias) in the
    /// layout's order. `shock` is the shock sensor, `metabolism` the raw vector m. Landmarks,
    /// areas and the eye are written by the world, which holds what they read.
    #[inline]
    pub fn write(&self, out: &mut [f64], senses: &Senses, shock: bool, metabolism: &[f64; 4]) {
        let Senses {
            whiskers,
            smell,
            food,
        } = senses;
        self.write_senses(out, *whiskers, smell, *food, shock, metabolism);
    }

    /// [`Offsets::write`] for senses held apart: `whiskers`, `smell` and `food` as in
    /// [`Senses`].
    #[inline(always)]
    pub fn write_senses(
        &self,
        out: &mut [f64],
        whiskers: [bool; 2],
        smell: &[[f64; 8]; 2],
        food: [bool; 4],
        shock: bool,
        metabolism: &[f64; 4],
    ) {
        // 0.0 or 1.0 without a branch (a sensor's state is as good as random).
        let bit = |b: bool| f64::from(u8::from(b));
        if let Some(o) = self.report {
            let block: &mut [f64; REPORT_WIDTH] = (&mut out[o..o + REPORT_WIDTH])
                .try_into()
                .expect("a block of REPORT_WIDTH values");
            block[..8].copy_from_slice(&smell[0]);
            block[8..16].copy_from_slice(&smell[1]);
            block[16] = bit(whiskers[0]);
            block[17] = bit(whiskers[1]);
            for t in 0..4 {
                block[18 + t] = bit(food[t]);
            }
            block[22] = bit(shock);
        } else {
            self.write_groups(out, whiskers, smell, food, shock);
        }
        if let Some(o) = self.metabolism {
            out[o..o + 4].copy_from_slice(metabolism);
        }
        if let Some(o) = self.bias {
            out[o] = 1.0;
        }
    }

    /// Smell, whiskers, food detectors and shock of [`Offsets::write`], group by group.
    fn write_groups(
        &self,
        out: &mut [f64],
        whiskers: [bool; 2],
        smell: &[[f64; 8]; 2],
        food: [bool; 4],
        shock: bool,
    ) {
        let bit = |b: bool| f64::from(u8::from(b));
        if let Some(o) = self.smell {
            out[o..o + 8].copy_from_slice(&smell[0]);
            out[o + 8..o + 16].copy_from_slice(&smell[1]);
        }
        if let Some(o) = self.whiskers {
            out[o] = bit(whiskers[0]);
            out[o + 1] = bit(whiskers[1]);
        }
        if let Some(o) = self.food {
            for t in 0..4 {
                out[o + t] = bit(food[t]);
            }
        }
        if let Some(o) = self.shock {
            out[o] = bit(shock);
        }
    }
}
