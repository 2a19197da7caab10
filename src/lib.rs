//! berry-evolve: a deterministic re-creation of the BERRY III artificial-creature world
//! (Balkenius, Lund University) driven by a genetic algorithm that evolves neural-network
//! controllers, evaluating whole populations in parallel.
//!
//! # Layers (dependencies point one way)
//!
//! ```text
//! geometry, seed  <-  sim  <-  brain  <-  evo  <-  experiment  <-  record  <-  cli
//! ```
//!
//! - [`geometry`]: the report's §6, pure functions on circles, segments and rays.
//! - [`seed`]: the one function that derives every random stream from the master seed.
//! - `sim`: the world, creatures, sensors and motion (§3–§9); knows nothing of networks.
//! - `brain`: genomes and the controllers they encode (MLP, recurrent, CTRNN).
//! - `evo`: the genetic algorithm and parallel, deterministic evaluation (the only rayon user).
//! - `experiment`: TOML experiment files, strict parsing and validation.
//! - `record`: all file output: fitness CSV, checkpoints, genome files, traces.
//! - `cli`: the command-line front end (lives in the binary).
//!
//! # Glossary (one name per concept)
//! World, Arena, Wall, Door, Food, FoodType (A–D), Odour, Aversive, Teleporter, Landmark,
//! Area, Predator, Wanderer (irrelevant creature), Creature, Body, Pose, Whisker, SmellSensor,
//! Eye, Retina, Observation, MotorCommand, Metabolism (the vector m), Brain, Genome,
//! Individual, Population, Trial, Evaluation, Fitness, GenerationReport, Checkpoint,
//! Experiment, Run.

pub mod brain;
pub mod cpu;
pub mod evo;
pub mod experiment;
pub mod geometry;
pub mod input;
pub mod record;
pub mod run;
pub mod seed;
pub mod sim;
pub mod validate;
