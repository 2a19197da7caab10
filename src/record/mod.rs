//! Record: the file I/O of a run, written so that it survives a crash and reproduces byte for
//! byte: atomic file replacement, checkpoints, the fitness CSV, a MAP-Elites archive, genome
//! files, the champions log, per-tick traces, and the tables plots are drawn from. The
//! pictures themselves are drawn in [`crate::view`].

pub mod archive;
pub mod atomic;
pub mod champions;
pub mod checkpoint;
pub mod fitness_csv;
pub mod genome_file;
pub mod plot;
pub mod summary;
pub mod trace;
