//! Air predators in flight (§4.7): straight flights across the arena, one after another.

use crate::geometry::Vec2;
use crate::seed::{below, Rng};
use crate::sim::spec::Effect;

/// An air predator in flight.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Flyer {
    /// Index of its smell in the world's things.
    pub thing: usize,
    /// Ground position in LU.
    pub position: Vec2,
    /// Displacement per tick in LU.
    pub velocity: Vec2,
    /// Speed in LU per tick.
    pub speed: f64,
    /// Attack radius in LU.
    pub strike_radius: f64,
    /// Its effect.
    pub effect: Effect,
    /// Ticks away between flights, `[min, max]` (`[0, 0]`: none).
    pub pause: [u64; 2],
    /// Ticks still to wait before the next flight begins (0 = in flight).
    pub away: u64,
    /// Where the next flight begins, while away.
    pub entry: Vec2,
}

impl Flyer {
    /// A new flight across an arena of size `arena`: draws the side (0 top, 1 right, 2
    /// bottom, 3 left), the entry point along it, then the exit point along the opposite side.
    pub fn enter(&mut self, arena: [f64; 2], rng: &mut Rng) {
        let [w, h] = arena;
        let side = below(rng, 4);
        let a = crate::seed::unit(rng);
        let b = crate::seed::unit(rng);
        let (from, to) = match side {
            0 => (Vec2::new(a * w, 0.0), Vec2::new(b * w, h)),
            1 => (Vec2::new(w, a * h), Vec2::new(0.0, b * h)),
            2 => (Vec2::new(a * w, h), Vec2::new(b * w, 0.0)),
            _ => (Vec2::new(0.0, a * h), Vec2::new(w, b * h)),
        };
        self.position = from;
        self.velocity = (to - from).normalize_or(Vec2::X) * self.speed;
        self.entry = from;
        if self.pause[1] > 0 {
            self.away = self.pause[0] + below(rng, self.pause[1] - self.pause[0] + 1);
            if self.away > 0 {
                // Waiting outside, beyond its strike radius from the entry point (drawn
                // there, never striking: `in_flight` is false).
                let back = self.velocity.normalize_or(Vec2::X) * (self.strike_radius + 1.0);
                self.position = from - back;
            }
        }
    }

    /// Is it over the arena (not away between two flights)? Only then does it strike, smell
    /// and count as a threat.
    #[inline]
    pub fn in_flight(&self) -> bool {
        self.away == 0
    }

    /// Flies one tick; enters anew when it left the arena (after its pause, when it has one).
    pub fn fly(&mut self, arena: [f64; 2], rng: &mut Rng) {
        if self.away > 0 {
            self.away -= 1;
            if self.away == 0 {
                self.position = self.entry;
            }
            return;
        }
        self.position += self.velocity;
        let p = self.position;
        if p.x < 0.0 || p.y < 0.0 || p.x > arena[0] || p.y > arena[1] {
            self.enter(arena, rng);
        }
    }
}
