//! Fitness of one life: the `[fitness]` table applied to a creature's metabolic history
//! (report §5.3 leaves the function open; SPEC-NOTES lists the choices offered here), and the
//! `[behaviour]` measures taken over the same life.
//!
//! What a trial must watch is decided once per trial ([`LifePlan`]): with only the
//! metabolic gain and the shock penalty (every shipped experiment before the new keys), a
//! tick costs what it always did, and a world query is made only for a term or measure that
//! needs it; the world's event log is switched on only for a measure that reads it.
//!
//! One job per file:
//! - `gain`: the pure terms (the balanced metabolic gain, the goal term and its distances);
//! - `plan`: [`LifePlan`], the `[fitness]` and `[behaviour]` tables resolved in a trial world;
//! - `score`: [`LifeScore`], the accumulation tick by tick;
//! - `finish`: the score and the measures at the end of a life;
//! - `trackers`: the measures that follow a creature (air predator passes, the T-maze side,
//!   aversive contacts, doors), and which of them read the world's events.

mod finish;
mod gain;
mod plan;
mod score;
mod trackers;

use crate::experiment::MEASURES;

pub use gain::{balanced_gain, distance_to_area, goal_nearness, goal_term, weighted, Goal};
pub use plan::LifePlan;
pub use score::LifeScore;

/// How many behaviour measures there are ([`MEASURES`]); a trial's measure values are an
/// array of this length, in that order.
pub const MEASURE_COUNT: usize = MEASURES.len();
