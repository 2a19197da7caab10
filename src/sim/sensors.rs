//! A creature's senses (§5.2, §7.1–7.3): whiskers, the two smell sensors at the whisker tips,
//! the four food detectors and the shock sensor, and how they are written into the
//! controller's observation vector.
//!
//! Each sense comes twice: here the plain loops over every object (`*_all`, the model as the
//! report writes it, and the reference the tests compare against), and in
//! [`crate::sim::index::senses`] the same tests run only on the candidates the world's
//! [`StaticIndex`] yields (what the tick loop uses), for both whiskers and both smell
//! receptors in one pass. Candidates come in index order, and the tests are the same
//! functions or give provably the same answers (a yes/no test does not depend on extra
//! candidates; see [`crate::sim::smell::Shade`]), so both give the same bits.

use crate::geometry::BoxedSegment;
use crate::geometry::{circles_touch, segment_touches_circle, segments_intersect, Segment, Vec2};
use crate::sim::area::Area;
use crate::sim::controller::{ObservationLayout, SensorGroup};
use crate::sim::creature::Creature;
use crate::sim::food::{Aversive, Food};
use crate::sim::gadgets::Thing;
use crate::sim::index::static_grid::StaticIndex;
use crate::sim::smell::{accumulate, saturate, Smell};

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
