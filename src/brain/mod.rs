//! Brains: the neural-network controllers that genomes encode.

pub mod genome;
