//! Record: all of the run's file I/O that must survive a crash and reproduce byte for byte:
//! atomic file replacement, checkpoints and the fitness CSV.

pub mod atomic;
pub mod checkpoint;
pub mod fitness_csv;
