//! A worker rank (1..N): receives the experiment and each generation's genomes from rank 0,
//! evaluates the chunks of jobs it is handed on its own threads, and sends back their trial
//! outcomes, until rank 0 says stop. It never touches a file; anything it cannot do it
//! reports to rank 0, which stops the run naming this rank.

use super::wire::{Reader, Writer};
use super::{receive, send, tag, Worker, PROGRAM};
use crate::brain::genome::Genome;
use crate::brain::spec::Topology;
use crate::evo::evaluate::PopulationJobs;
use crate::experiment::Experiment;
use crate::seed::Generation;
use mpi::Tag;
use std::path::Path;

/// What the worker holds between messages: the experiment (or why it could not be read) and
/// its threads.
struct Held {
    experiment: Result<(Experiment, Topology), String>,
    pool: Option<(usize, rayon::ThreadPool)>,
}

/// Serves rank 0 until it sends stop; then finalises MPI. Signals (mpirun's SIGTERM after a
/// Ctrl-C) are left to rank 0, which finishes the generation and then sends stop.
pub fn serve(worker: Worker) {
    let world = worker.universe.world();
    // Rank 0 decides when to stop; a worker that died at mpirun's SIGTERM would leave rank 0
    // waiting for its jobs. (mpirun's later SIGKILL still ends it.)
    let _ = ctrlc::set_handler(|| {});
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    send(
        &world,
        0,
        tag::HELLO,
        &Writer::new().text(PROGRAM).u64(cores as u64).finish(),
    );
    let mut held = Held {
        experiment: Err("no experiment arrived before the jobs".to_string()),
        pool: None,
    };
    let mut pending: Option<(Vec<u8>, Tag)> = None;
    loop {
        let (bytes, t) = match pending.take() {
            Some(message) => message,
            None => match receive(&world, Some(0), None, None) {
                Some((bytes, t, _)) => (bytes, t),
                None => continue,
            },
        };
        match t {
            tag::STOP => break,
            tag::EXPERIMENT => held.take_experiment(&bytes),
            tag::GENERATION => {
                let mut r = Reader::new(&bytes);
                let population = r
                    .u64()
                    .and_then(|g| Ok((g, r.genomes()?)))
                    .and_then(|p| r.end().map(|()| p))
                    .map_err(|e| format!("its generation did not arrive whole: {e}"));
                pending = Some(held.serve_generation(&world, population));
            }
            tag::JOBS => {
                // Jobs before any generation: nothing to evaluate them on.
                let mut r = Reader::new(&bytes);
                let (a, b) = (r.u64().unwrap_or(0), r.u64().unwrap_or(0));
                failed(&world, a, b, "it was sent jobs before their generation");
            }
            _ => {}
        }
    }
    drop(world);
    drop(worker);
}

/// Reports that jobs `a..b` could not be evaluated.
fn failed(world: &mpi::topology::SimpleCommunicator, a: u64, b: u64, why: &str) {
    send(
        world,
        0,
        tag::FAILED,
        &Writer::new().u64(a).u64(b).text(why).finish(),
    );
}

impl Held {
    /// Reads the experiment rank 0 sent: threads per rank, config hash, TOML.
    fn take_experiment(&mut self, bytes: &[u8]) {
        let mut r = Reader::new(bytes);
        let read =
            (|| Ok::<_, super::wire::WireError>((r.u64()?, r.text()?, r.text()?, r.end()?)))();
        self.experiment = match read {
            Err(e) => Err(format!("its experiment did not arrive whole: {e}")),
            Ok((jobs, hash, text, ())) => {
                let jobs = jobs as usize;
                if self.pool.as_ref().is_none_or(|(j, _)| *j != jobs) {
                    self.pool = rayon::ThreadPoolBuilder::new()
                        .num_threads(jobs)
                        .build()
                        .ok()
                        .map(|p| (jobs, p));
                }
                match Experiment::from_toml(&text, Path::new("rank 0's experiment")) {
                    Err(e) => Err(format!("cannot read rank 0's experiment: {e}")),
                    Ok(e) if e.config_hash() != hash => Err(format!(
                        "rank 0's experiment reads back with config hash {} instead of {hash}",
                        e.config_hash()
                    )),
                    Ok(e) => {
                        let topology = e.topology();
                        Ok((e, topology))
                    }
                }
            }
        };
    }

    /// Evaluates the chunks of jobs rank 0 hands out for one generation; returns the first
    /// message that is not a chunk (the next generation, experiment or stop).
    fn serve_generation(
        &self,
        world: &mpi::topology::SimpleCommunicator,
        population: Result<(u64, Vec<Genome>), String>,
    ) -> (Vec<u8>, Tag) {
        let jobs = match (&self.experiment, &population, &self.pool) {
            (Err(why), _, _) | (_, Err(why), _) => Err(why.clone()),
            (_, _, None) => Err("cannot start its worker threads".to_string()),
            (Ok((experiment, topology)), Ok((generation, genomes)), Some(_)) => {
                PopulationJobs::new(experiment, topology, genomes, Generation(*generation))
                    .map_err(|e| e.to_string())
            }
        };
        loop {
            let Some((bytes, t, _)) = receive(world, Some(0), None, None) else {
                continue;
            };
            if t != tag::JOBS {
                return (bytes, t);
            }
            let mut r = Reader::new(&bytes);
            let (a, b) = match (r.u64(), r.u64()) {
                (Ok(a), Ok(b)) => (a, b),
                _ => {
                    failed(world, 0, 0, "its chunk of jobs did not arrive whole");
                    continue;
                }
            };
            let jobs = match &jobs {
                Err(why) => {
                    failed(world, a, b, why);
                    continue;
                }
                Ok(jobs) if a > b || b as usize > jobs.len() => {
                    failed(
                        world,
                        a,
                        b,
                        &format!("jobs {a}..{b} do not exist ({} jobs)", jobs.len()),
                    );
                    continue;
                }
                Ok(jobs) => jobs,
            };
            let pool = &self.pool.as_ref().expect("checked above").1;
            match pool.install(|| jobs.run_range(a as usize..b as usize)) {
                Ok(lives) => send(
                    world,
                    0,
                    tag::LIVES,
                    &Writer::new().u64(a).u64(b).lives(&lives).finish(),
                ),
                Err(e) => failed(world, a, b, &e.to_string()),
            }
        }
    }
}
