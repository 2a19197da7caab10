//! Brains: the neural-network controllers that genomes encode (MLP, Elman recurrent network,
//! CTRNN), the `[brain]` table that chooses one, and the controller that drives a creature.

pub mod activation;
pub mod genome;
pub mod spec;

pub use activation::Activation;
pub use genome::Genome;
pub use spec::{BrainKind, BrainSpec, Topology};
