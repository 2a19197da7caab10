//! Evolution: the search that evolves brain genomes ([`search`]: the generational genetic
//! algorithm or PGPE behind one ask/tell trait) and the evaluation it asks for. This part holds
//! the random generation 0, selection, variation (crossover and mutation), trials and their
//! evaluation, and fitness statistics; the `[evolution]` table it reads is
//! [`crate::experiment::evolution`]. The trial code (worlds, lives, scores: [`trial`],
//! [`lockstep`], [`life`], [`episodes`], [`episode`], [`fitness`]) reads the experiment only
//! through a [`TrialPlan`] resolved once per request ([`trial_plan`]); the searches and the
//! named world sets read the whole experiment. Every random draw comes from a stream passed in,
//! in a documented order, so a run reproduces bit for bit from its seed.

pub mod choices;
pub mod door;
pub mod episode;
pub mod episodes;
pub mod evaluate;
pub mod fitness;
pub mod init;
pub mod life;
pub mod lineage;
pub mod lockstep;
pub mod operators;
#[cfg(feature = "mpi")]
pub mod ranks;
pub mod search;
pub mod select;
pub mod state;
pub mod stats;
pub mod trace;
pub mod trial;
pub mod trial_plan;
pub mod validation;
pub mod vary;
pub mod vary_streams;
pub mod worlds;

pub use init::initial_population;
/// PGPE, kept at its old path (`evo::pgpe`) for the code and tests that name it.
pub use search::pgpe;
pub use stats::FitnessStats;
pub use trial_plan::TrialPlan;
pub use vary::next_generation;
