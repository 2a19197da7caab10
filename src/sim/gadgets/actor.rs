//! Wanderers and ground predators (§4.7, §4.8): their running state and how they pick a
//! motor command (a held random one, a turn away from a touch, or steering to a target).

use crate::geometry::Vec2;
use crate::seed::{below, uniform, Rng};
use crate::sim::motion::Pose;
use crate::sim::spec::{Effect, Strategy};

/// What drives a ground actor.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Role {
    /// An irrelevant creature.
    Wanderer,
    /// A ground predator with its strategy and effect; `predator` indexes
    /// `[[world.predators]]` (for its waypoints).
    Predator {
        /// Index in `[[world.predators]]`.
        predator: usize,
        /// Its strategy.
        strategy: Strategy,
        /// Its effect.
        effect: Effect,
    },
}

/// A wanderer or ground predator while running.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Actor {
    /// Index of its body in the world's things.
    pub thing: usize,
    /// What drives it.
    pub role: Role,
    /// Its pose.
    pub pose: Pose,
    /// Its largest motor signal.
    pub max_rpt: f64,
    /// Hold range of random commands.
    pub hold_ticks: [u64; 2],
    /// The random command being held (left, right).
    pub held: (f64, f64),
    /// Ticks left on the held command.
    pub hold_left: u64,
    /// This tick's command is the held random one (not a turn away, a steer or a sleep):
    /// when it cannot move the body, the hold ends ([`Actor::moved_on`]).
    pub on_held: bool,
    /// Next waypoint of a patrol.
    pub waypoint: usize,
    /// How it turns away from a touch while wandering.
    pub turn_away: TurnAway,
    /// Ticks it still sleeps (a ground predator with `asleep`; 0 = awake).
    pub asleep: u64,
}

impl Actor {
    /// Is it awake? Asleep, a predator neither moves, smells, attacks nor counts as a threat.
    #[inline]
    pub fn awake(&self) -> bool {
        self.asleep == 0
    }
}

/// Which way a wanderer turns.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Turn {
    /// Anticlockwise on screen (towards its left).
    Left,
    /// Clockwise on screen (towards its right).
    Right,
}

/// A wanderer's turn away from what its whiskers touch (§4.8, SPEC-NOTES): a spin in place
/// by at most `turn_degrees` per tick, in one direction kept from the first touching tick
/// until neither whisker touches.
///
/// Why: a spin at ±max_rpt turns 720·max_rpt degrees in one tick (180° at the default 0.25,
/// 144° at 0.2); beside a wall that turn lands the other whisker on the wall, the next tick
/// spins straight back, and the wanderer flips between two headings for good (in 0.3.5 a
/// wanderer in an open arena froze 0.2 LU from a wall; in a 30 × 30 pen most froze within
/// 2,000 ticks). A bounded turn with a kept direction sweeps the headings one way, so it
/// reaches the free ones (next to a straight wall about 170° of them, in a right-angled
/// corner about 70°: the 30° default always lands in them). Where no heading is free (a
/// corridor narrower than the whisker span, or bodies all around), after a full circle
/// without freeing both whiskers it drives its held command for one tick and starts another
/// circle, so it still moves along the corridor instead of spinning forever. The whole rule,
/// in words: docs/simulator-decisions.md, "How wanderers move".
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TurnAway {
    /// Spin signal per wheel in RPT: `turn_degrees / 720`, at most `max_rpt`.
    pub rpt: f64,
    /// Ticks of turning that make a full circle: ⌈1 / (2·rpt)⌉ (`u32::MAX` when rpt is 0).
    pub full_circle: u32,
    /// The direction of the turn in progress, `None` while no whisker touches.
    pub turning: Option<Turn>,
    /// Ticks turned since the turn began or since the last full circle.
    pub turned: u32,
}

impl TurnAway {
    /// Largest turn per tick in degrees when `turn_degrees` is absent.
    pub const DEFAULT_DEGREES: f64 = 30.0;

    /// The turn of a body whose motor signals are at most `max_rpt` (≥ 0), turning at most
    /// `degrees` per tick (validated in (0, 180]; absent = [`TurnAway::DEFAULT_DEGREES`]).
    pub fn new(max_rpt: f64, degrees: Option<f64>) -> TurnAway {
        let rpt = (degrees.unwrap_or(Self::DEFAULT_DEGREES) / 720.0).min(max_rpt);
        let ticks = (1.0 / (2.0 * rpt)).ceil();
        TurnAway {
            rpt,
            // A float-to-integer cast saturates: rpt = 0 gives +∞, hence u32::MAX.
            full_circle: ticks as u32,
            turning: None,
            turned: 0,
        }
    }
}

impl Actor {
    /// The wanderer's command: a fresh random one when the held one ran out (draws: left,
    /// right, then the hold length), else the held one, except while a whisker touches:
    /// then it turns away ([`TurnAway`]), which does not replace the held command but uses
    /// up its ticks (the hold counts down on turning ticks too, and a fresh command is drawn
    /// on a turning tick when the hold ran out). A held command that could not move the body
    /// ends its hold ([`Actor::moved_on`]). The direction is chosen on the first touching tick: a left touch
    /// turns it right, a right touch left, both a direction drawn from `rng` (one draw, after
    /// those of a fresh command).
    pub fn wander(&mut self, whiskers: [bool; 2], rng: &mut Rng) -> (f64, f64) {
        if self.hold_left == 0 {
            let m = self.max_rpt;
            self.held = (uniform(rng, -m, m), uniform(rng, -m, m));
            let [lo, hi] = self.hold_ticks;
            self.hold_left = lo + below(rng, hi - lo + 1);
        }
        self.hold_left -= 1;
        let t = &mut self.turn_away;
        self.on_held = false;
        if whiskers == [false, false] {
            t.turning = None;
            t.turned = 0;
            self.on_held = true;
            return self.held;
        }
        let turn = *t.turning.get_or_insert_with(|| match whiskers {
            [true, false] => Turn::Right,
            [false, true] => Turn::Left,
            _ if below(rng, 2) == 0 => Turn::Left,
            _ => Turn::Right,
        });
        t.turned = t.turned.saturating_add(1);
        if t.turned > t.full_circle {
            // A full circle found no free heading: move on the held command for a tick.
            t.turned = 0;
            self.on_held = true;
            return self.held;
        }
        match turn {
            Turn::Right => (t.rpt, -t.rpt),
            Turn::Left => (-t.rpt, t.rpt),
        }
    }

    /// After this tick's move to `pose`: a held random command that left the body where it
    /// was (its move blocked before it travelled any distance: a wanderer backed into a wall,
    /// or driving into a body) ends its hold, so the next tick draws a fresh one from the
    /// same generator, in the same place in the tick order (left, right, hold length).
    ///
    /// Why: the report's wanderers have no rear sensor, and a command held for its drawn
    /// number of ticks kept a wanderer pressed against a wall; with fresh commands that
    /// pointed into the wall too it stood still for up to 170 ticks in a 30 × 30 pen (289
    /// with crowded-arena's 0.2 RPT held 5–40 ticks), while §4.8 wants wanderers to keep the
    /// world changing. A turn away (a spin) and a steer are not random commands and keep
    /// their rules.
    pub fn moved_on(&mut self, pose: Pose) {
        if self.on_held && pose.position == self.pose.position {
            self.hold_left = 0;
        }
        self.pose = pose;
    }

    /// Steers towards `target`: the wheel difference that turns the heading onto it in one
    /// tick (a spin turns by 2π(L − R) rad, eq. 28–33), limited to ±`max_rpt` per wheel,
    /// with the rest of the speed budget going forward.
    pub fn steer(&self, target: Vec2) -> (f64, f64) {
        let to = target - self.pose.position;
        let h = self.pose.heading;
        // y points down: a positive cross product means the target is clockwise (right).
        let angle = libm::atan2(h.x * to.y - h.y * to.x, h.x * to.x + h.y * to.y);
        let m = self.max_rpt;
        let half = (angle / (4.0 * std::f64::consts::PI)).clamp(-m, m);
        let ahead = m - half.abs();
        (ahead + half, ahead - half)
    }
}
