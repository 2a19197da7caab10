//! The BERRY III world (report §3–§9): walls, food, smells, creatures, sensors, motion and the
//! tick loop. Pure and deterministic: it knows nothing of networks, genomes, files or threads,
//! and every random draw comes from the generator a world is given.

pub mod controller;
pub mod motion;
