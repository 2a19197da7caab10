//! Where a run's evaluation runs: on this process's threads, or (a build with the `mpi`
//! feature, started by `mpirun`) across MPI ranks, rank 0 running the command. Without the
//! feature there are no ranks and nothing here costs anything.

use berry_evolve::evo::evaluate::Evaluator;
use std::sync::atomic::AtomicBool;

/// The other MPI ranks (the `mpi` feature's `berry_evolve::evo::ranks::Ranks`).
#[cfg(feature = "mpi")]
pub use berry_evolve::evo::ranks::Ranks;

/// No ranks in a build without the `mpi` feature (a type with no values).
#[cfg(not(feature = "mpi"))]
pub enum Ranks {}

/// The evaluator of one run over `ranks` (`None`: evaluate here), with `jobs` threads per
/// rank and the run's stop flag.
#[cfg(feature = "mpi")]
pub fn evaluator<'a>(
    ranks: Option<&'a Ranks>,
    jobs: usize,
    stop: &'a AtomicBool,
) -> anyhow::Result<Option<Box<dyn Evaluator + 'a>>> {
    let Some(ranks) = ranks else {
        return Ok(None);
    };
    let run = ranks
        .for_run(jobs, Some(stop))
        .map_err(|e| anyhow::anyhow!("cannot start {jobs} worker threads on rank 0: {e}"))?;
    Ok(Some(Box::new(run)))
}

/// The evaluator of one run: always this process's threads without the `mpi` feature.
#[cfg(not(feature = "mpi"))]
pub fn evaluator<'a>(
    ranks: Option<&'a Ranks>,
    _jobs: usize,
    _stop: &'a AtomicBool,
) -> anyhow::Result<Option<Box<dyn Evaluator + 'a>>> {
    match ranks {
        None => Ok(None),
        Some(never) => match *never {},
    }
}
