//! Everything berry-evolve writes to files: per-tick traces (and, from other modules, fitness
//! tables, checkpoints and genome files).

pub mod trace;
