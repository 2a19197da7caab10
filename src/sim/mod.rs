//! The BERRY III world (report §3–§9): walls, food, smells, creatures, sensors, motion and the
//! tick loop. Pure and deterministic: it knows nothing of networks, genomes, files or threads,
//! and every random draw comes from the generator a world is given.
//!
//! - [`spec`]: the `[world]` and `[creature]` tables and their validation.
//! - [`world`]: the running world and the tick loop of §9; [`creature`]: one creature.
//! - [`wall`], [`food`], [`smell`]: the things in the world.
//! - [`events`]: what happened in a tick, told by the world where it decides it.
//! - [`sensors`]: whiskers, smell sensors, food detectors, observation layout.
//! - [`index`]: what exists only for speed, the spatial indexes the senses, moves and contacts
//!   query (the static grid, the smell grid, whisker cells, mover cells).
//! - [`gadgets`]: doors, teleporters, wanderers and predators (§4.5.1, §4.5.2, §4.7, §4.8).
//! - [`area`]: areas and distal landmarks; [`eye`]: the retina; [`noise`]: sensor noise.
//! - [`motion`]: the body's movement (§8).
//! - [`metabolism`]: the metabolic vector m.
//! - [`placement`]: building a trial world from a seed.
//! - [`scripted`]: controllers without a brain, for tests and demos.

pub mod area;
pub mod controller;
pub mod creature;
pub mod events;
pub mod eye;
pub mod food;
pub mod gadgets;
pub mod index;
pub mod metabolism;
pub mod motion;
pub mod noise;
pub mod placement;
pub mod scripted;
pub mod sensors;
pub mod smell;
pub mod spec;
pub mod wall;
pub mod world;

pub use creature::Creature;
pub use placement::PlacementError;
pub use spec::{CreatureSpec, Eating, WorldSpec};
pub use world::World;
