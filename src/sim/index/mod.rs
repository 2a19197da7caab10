//! Everything in the world that exists only for speed: spatial indexes that hand the senses,
//! moves and contacts the objects near a creature instead of every object in the world.
//!
//! # The contract
//! An index hands a *superset* of the candidates a plain loop would test, *in index order*;
//! the caller then tests each candidate with the *same exact predicate* as the plain loop
//! (the model's code, in `sensors.rs`, `motion.rs`, `world.rs`). The answers are "or"s over
//! objects (whiskers, detectors, shock, a move's block), which extra candidates that fail the
//! test and the order of the tests cannot change, or sums in object order (smell, eating),
//! which the index order keeps. So an index changes no bit of any result; `World::set_brute_force`
//! runs the plain loops, and the tests compare the two.
//!
//! # Adding an object kind
//! 1. Decide which index lists it: [`static_grid`] (anything fixed the senses query by box),
//!    [`smell_grid`] (a fixed smell source of finite range), [`whisker_cells`] (fixed things
//!    a whisker or body may touch), [`mover_cells`] (fixed things a move or contact may meet);
//!    a kind that moves or changes (doors, creatures, gadgets) stays out of every index and
//!    is tested in a short linear list after the index's candidates.
//! 2. Write the plain loop first, in the model (`sensors.rs`, `world.rs`), with its report
//!    reference; the indexed pass then only changes where its candidates come from.
//! 3. Add a brute-force test that runs both (`World::set_brute_force`, or the index's query
//!    against a filter over every object) and compares the bits.
//!
//! # Layout
//! - [`cells`]: the cell layout of the static and smell grids, and the stable counting sort
//!   the static grid, the smell grid and the mover cells build their lists with. The whisker
//!   and mover cells keep their own cell lookups (a range test and a truncation tuned for
//!   the tick, which the static grid's clamping lookup would lengthen), and the whisker
//!   cells their own two-kind sort (a quarter cheaper to build than the shared one).
//! - [`static_grid`]: food, aversive objects and fixed walls by cell ([`StaticIndex`]).
//! - [`smell_grid`]: per cell, the smell sources that may reach it and the walls that may
//!   hide them.
//! - [`whisker_cells`]: per cell, the walls and food a body's whiskers and detectors may touch.
//! - [`mover_cells`]: per cell, the walls a move may reach and the objects a body may touch.
//! - [`senses`]: the senses' passes over these candidates (the plain loops stay in
//!   [`crate::sim::sensors`]).

pub mod cells;
pub mod mover_cells;
pub mod senses;
pub mod smell_grid;
pub mod static_grid;
pub mod whisker_cells;

use crate::sim::food::{Aversive, Food};
use crate::sim::wall::Walls;
use mover_cells::MoverCells;
pub use static_grid::{Scratch, StaticIndex};

/// The indexes of one world, built once when the world is: the static grid over `food`,
/// `aversives` and the fixed walls of `walls` for bodies whose whiskers or contacts reach
/// `reach` from the centre, its query scratch space, and the mover cells for bodies of
/// `radius` moving at most `travel` a tick.
pub(crate) fn build(
    arena: [f64; 2],
    reach: f64,
    radius: f64,
    travel: f64,
    food: &[Food],
    aversives: &[Aversive],
    walls: &Walls,
) -> (StaticIndex, Scratch, Option<MoverCells>) {
    let index = StaticIndex::build(arena, reach, food, aversives, walls);
    let scratch = index.scratch(walls.opaque_capacity(), walls.capacity());
    let mover_cells = MoverCells::build(&walls.felt()[..walls.fixed_count()], travel, radius)
        .and_then(|cells| cells.with_contacts(radius, food, aversives));
    (index, scratch, mover_cells)
}
