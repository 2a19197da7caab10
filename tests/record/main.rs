//! The record layer (`berry_evolve::record`): atomic writes, checkpoints, the fitness CSV, the
//! champions log, the world trace, and fuzzed loaders.

#[path = "../sim_common/mod.rs"]
mod sim_common;

mod atomic_checkpoints_csv;
mod champions_log;
mod loader_fuzz;
mod world_trace;
