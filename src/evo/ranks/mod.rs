//! Evaluation across MPI ranks (the `mpi` feature): the same bytes as one machine.
//!
//! Under `mpirun -np N`, every rank runs the same program. Rank 0 is the run: it alone owns
//! the run folder (lock, `fitness.csv`, checkpoints, progress, stdout) and does everything
//! serial (selection, variation, statistics, validation). Ranks 1..N are workers
//! ([`worker::serve`]): they never touch a file. Each generation, rank 0 sends every worker the
//! population (genomes as raw `f64` bits, [`wire`]) after the experiment when it changed (its
//! TOML, checked against its config hash), then hands out chunks of the generation's job
//! numbers ([`PopulationJobs`]) as ranks finish their previous chunk (guided self-scheduling:
//! large chunks first, smaller towards the end, never fewer jobs than the rank has threads),
//! evaluating chunks itself on its own threads meanwhile. Each rank runs a chunk's jobs with
//! its rayon threads and sends back their trial outcomes as raw bits; rank 0 puts them in
//! place by job number and reduces them serially in job order, as on one machine. A job's
//! result is a pure function of its number, so which rank ran it, in which chunk, on how many
//! threads, changes no bit: `fitness.csv`, `best.json` and the checkpoints are those of a
//! plain run, for any number of ranks, and a run resumes under any number of ranks (or none).
//!
//! Faults: a worker that cannot evaluate (its experiment or generation did not arrive whole,
//! a world cannot be built) answers with its error and rank 0 stops the run naming the rank.
//! A rank that dies makes `mpirun` end every rank; rank 0 then stops at its last good
//! checkpoint (the files are written atomically) and, if it was told to stop (the SIGTERM
//! mpirun sends) while a rank still owed it jobs, says which rank (see [`stop_grace`]). The waits poll with short
//! sleeps instead of MPI's busy-waiting receive, so an idle rank leaves its cores to others.

mod wire;
pub mod worker;

use crate::evo::evaluate::{Evaluator, JobLives, PopulationJobs};
use crate::evo::life::EvaluationError;
use crate::experiment::Experiment;
use mpi::environment::Universe;
use mpi::topology::SimpleCommunicator;
use mpi::traits::*;
use mpi::Tag;
use std::cell::RefCell;
use std::ops::Range;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Mutex;
use std::time::{Duration, Instant};
use thiserror::Error;
use wire::{Reader, Writer};

/// Message tags (the first word of the protocol is the tag, not the payload).
mod tag {
    use mpi::Tag;
    /// Worker → 0 at start: its program name and version, and its core count.
    pub const HELLO: Tag = 1;
    /// 0 → worker: threads per rank (0: one per core), config hash, experiment TOML.
    pub const EXPERIMENT: Tag = 2;
    /// 0 → worker: the generation number and its genomes.
    pub const GENERATION: Tag = 3;
    /// 0 → worker: a chunk of job numbers, start and end.
    pub const JOBS: Tag = 4;
    /// Worker → 0: a chunk's start and end and its jobs' outcomes.
    pub const LIVES: Tag = 5;
    /// Worker → 0: a chunk's start and end, and why it could not be evaluated.
    pub const FAILED: Tag = 6;
    /// 0 → worker: the program is done; exit.
    pub const STOP: Tag = 7;
}

/// The program's name and version, which every rank must share (another version may
/// compute other bits).
pub const PROGRAM: &str = concat!("berry-evolve ", env!("CARGO_PKG_VERSION"));

/// How long rank 0 waits for every worker's first message.
const HELLO_TIMEOUT: Duration = Duration::from_secs(120);

/// How long rank 0, told to stop, still waits for jobs a worker owes it before it stops
/// the run naming that rank. mpirun's SIGTERM to the ranks (after a rank died, or after its
/// own SIGINT/SIGTERM) is followed by SIGKILL `odls_base_sigkill_timeout` seconds later
/// (default 1; `mpirun --mca odls_base_sigkill_timeout 120` passes it to the ranks as
/// `OMPI_MCA_odls_base_sigkill_timeout`): rank 0 waits for all but half a second of it, so
/// that a slow but living rank can still finish the generation and a dead one is named.
fn stop_grace() -> Duration {
    let timeout = std::env::var("OMPI_MCA_odls_base_sigkill_timeout")
        .ok()
        .and_then(|t| t.trim().parse::<f64>().ok())
        .filter(|t| t.is_finite() && *t > 0.0)
        .unwrap_or(1.0);
    Duration::from_secs_f64((timeout - 0.5).max(0.3))
}

/// Why the ranks could not start.
#[derive(Debug, Error)]
pub enum RanksError {
    /// MPI could not be initialised.
    #[error("cannot initialise MPI (started by mpirun, but MPI_Init_thread failed or MPI was already initialised)")]
    Init,
    /// A worker did not say hello in time.
    #[error("rank {rank} did not start: no word from it within {} s", HELLO_TIMEOUT.as_secs())]
    Silent {
        /// The rank.
        rank: usize,
    },
    /// A worker runs another program version, or said something unexpected.
    #[error("rank {rank} cannot take part: {reason}")]
    Refused {
        /// The rank.
        rank: usize,
        /// Why.
        reason: String,
    },
}

/// Was this process started by `mpirun`/`srun` with MPI (Open MPI, MPICH or PMIx set these)?
/// A plain start initialises no MPI at all.
pub fn launched_by_mpi() -> bool {
    ["OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"]
        .iter()
        .any(|v| std::env::var_os(v).is_some())
}

/// What this process is in an MPI job.
pub enum Role {
    /// Rank 0: runs the command; its [`Ranks`] evaluates generations across all ranks.
    Coordinator(Ranks),
    /// Another rank: call [`worker::serve`] and exit with what it returns.
    Worker(Worker),
}

/// A worker rank's handle on MPI (see [`worker::serve`]).
pub struct Worker {
    universe: Universe,
}

/// Initialises MPI and learns this process's role. Rank 0 waits for every worker's hello
/// and checks it runs the same program version.
pub fn join() -> Result<Role, RanksError> {
    let (universe, _) =
        mpi::initialize_with_threading(mpi::Threading::Funneled).ok_or(RanksError::Init)?;
    let world = universe.world();
    if world.rank() != 0 {
        return Ok(Role::Worker(Worker { universe }));
    }
    let size = world.size() as usize;
    let mut cores = vec![0usize; size];
    cores[0] = rayon::current_num_threads();
    let deadline = Instant::now() + HELLO_TIMEOUT;
    for _ in 1..size {
        let (bytes, t, from) = receive(&world, None, Some(deadline), None).ok_or_else(|| {
            let rank = (1..size).find(|&r| cores[r] == 0).unwrap_or(1);
            RanksError::Silent { rank }
        })?;
        let refuse = |reason: String| RanksError::Refused { rank: from, reason };
        if t != tag::HELLO {
            return Err(refuse(format!("its first message had tag {t}, not hello")));
        }
        let mut r = Reader::new(&bytes);
        let program = r.text().map_err(|e| refuse(e.to_string()))?;
        let n = r.u64().map_err(|e| refuse(e.to_string()))?;
        if program != PROGRAM {
            return Err(refuse(format!(
                "it runs {program}, rank 0 runs {PROGRAM}; install the same version on every node"
            )));
        }
        cores[from] = (n as usize).max(1);
    }
    Ok(Role::Coordinator(Ranks {
        world,
        cores,
        sent: RefCell::new(None),
        _universe: universe,
    }))
}

/// Rank 0's view of the job: the other ranks and what they were last told.
pub struct Ranks {
    world: SimpleCommunicator,
    /// Each rank's cores (its threads when `--jobs` is not given).
    cores: Vec<usize>,
    /// (threads, config hash) of the experiment the workers hold.
    sent: RefCell<Option<(usize, String)>>,
    /// Finalises MPI when dropped, after `world`.
    _universe: Universe,
}

impl Ranks {
    /// The number of ranks, rank 0 included.
    pub fn size(&self) -> usize {
        self.cores.len()
    }

    /// The evaluator for one run: `jobs` threads per rank (0: one per core of each rank's
    /// machine); `stop` is the run's stop flag (see [`stop_grace`]).
    pub fn for_run<'a>(
        &'a self,
        jobs: usize,
        stop: Option<&'a AtomicBool>,
    ) -> Result<RanksRun<'a>, rayon::ThreadPoolBuildError> {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(jobs).build()?;
        Ok(RanksRun {
            ranks: self,
            jobs,
            stop,
            pool,
            done: Mutex::new(vec![0; self.size()]),
            traffic: std::cell::Cell::new(Traffic::default()),
        })
    }

    /// Tells every worker to exit (at the end of the program, whatever the command did).
    pub fn stop_workers(&self) {
        for r in 1..self.size() {
            send(&self.world, r, tag::STOP, &[]);
        }
    }

    /// Sends the experiment to every worker unless they hold it already; returns the bytes
    /// sent.
    fn share_experiment(&self, experiment: &Experiment, jobs: usize) -> Traffic {
        let hash = experiment.config_hash();
        let current = Some((jobs, hash.clone()));
        if *self.sent.borrow() == current {
            return Traffic::default();
        }
        let message = Writer::new()
            .u64(jobs as u64)
            .text(&hash)
            .text(&experiment.to_toml())
            .finish();
        let mut traffic = Traffic::default();
        for r in 1..self.size() {
            send(&self.world, r, tag::EXPERIMENT, &message);
            traffic.add(message.len());
        }
        *self.sent.borrow_mut() = current;
        traffic
    }
}

/// [`Ranks`] evaluating one run's generations (see the module docs).
pub struct RanksRun<'a> {
    ranks: &'a Ranks,
    jobs: usize,
    stop: Option<&'a AtomicBool>,
    /// Rank 0's own threads for its share.
    pool: rayon::ThreadPool,
    /// Jobs each rank has evaluated in this run.
    done: Mutex<Vec<u64>>,
    /// Messages and bytes to and from rank 0 in this run.
    traffic: std::cell::Cell<Traffic>,
}

/// Messages and bytes exchanged (rank 0's sends and receives: every message has rank 0 at
/// one end), and the generations they served.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Traffic {
    /// Generations evaluated.
    pub generations: u64,
    /// Messages sent or received by rank 0.
    pub messages: u64,
    /// Their payload bytes.
    pub bytes: u64,
}

impl Traffic {
    fn add(&mut self, bytes: usize) {
        self.messages += 1;
        self.bytes += bytes as u64;
    }
}

/// Hands out chunks of job numbers `0..total` in order (guided self-scheduling).
struct Chunks {
    next: usize,
    total: usize,
    ranks: usize,
    closed: bool,
}

impl Chunks {
    /// The next chunk for a rank with `threads` threads: a share of what is left (half of
    /// it split over the ranks), at least `threads` jobs; `None` when none is left.
    fn take(&mut self, threads: usize) -> Option<Range<usize>> {
        let left = self.total - self.next;
        if self.closed || left == 0 {
            return None;
        }
        let size = left.div_ceil(2 * self.ranks).max(threads).min(left);
        let chunk = self.next..self.next + size;
        self.next += size;
        Some(chunk)
    }
}

impl RanksRun<'_> {
    fn threads_of(&self, rank: usize) -> usize {
        if rank == 0 {
            self.pool.current_num_threads()
        } else if self.jobs > 0 {
            self.jobs
        } else {
            self.ranks.cores[rank]
        }
    }

    fn stop_requested(&self) -> bool {
        self.stop.is_some_and(|s| s.load(Ordering::SeqCst))
    }
}

impl Evaluator for RanksRun<'_> {
    fn report(&self) -> Option<String> {
        let done = self.jobs_per_rank();
        let list: Vec<String> = done.iter().map(u64::to_string).collect();
        let t = self.traffic();
        let per = |x: u64| x as f64 / t.generations.max(1) as f64;
        Some(format!(
            "evaluated on {} MPI ranks ({} generations; per generation {:.1} messages, {:.0} bytes); jobs per rank (rank 0 first): {}",
            done.len(),
            t.generations,
            per(t.messages),
            per(t.bytes),
            list.join(", ")
        ))
    }

    fn run_jobs(&self, jobs: &PopulationJobs<'_>) -> Result<Vec<JobLives>, EvaluationError> {
        let ranks = self.ranks;
        let world = &ranks.world;
        let size = ranks.size();
        let generation = jobs.generation().0;
        let mut start = self.traffic.get();
        start.generations += 1;
        let traffic = std::cell::Cell::new(start);
        let count = |bytes: usize| {
            let mut t = traffic.get();
            t.add(bytes);
            traffic.set(t);
        };
        if size > 1 {
            let shared = ranks.share_experiment(jobs.experiment(), self.jobs);
            let mut t = traffic.get();
            t.messages += shared.messages;
            t.bytes += shared.bytes;
            traffic.set(t);
            let message = Writer::new()
                .u64(generation)
                .genomes(jobs.population())
                .finish();
            for r in 1..size {
                send(world, r, tag::GENERATION, &message);
                count(message.len());
            }
        }
        let chunks = Mutex::new(Chunks {
            next: 0,
            total: jobs.len(),
            ranks: size,
            closed: false,
        });
        let results: Mutex<Vec<Option<JobLives>>> = Mutex::new(vec![None; jobs.len()]);
        let done = &self.done;
        let store = |rank: usize, range: Range<usize>, lives: Vec<JobLives>| {
            done.lock().expect("done")[rank] += range.len() as u64;
            if rank != 0 {
                // Rank 0's own jobs told the progress hook as they finished (run_range).
                jobs.jobs_done(range.len());
            }
            let mut results = results.lock().expect("results");
            for (slot, l) in results[range].iter_mut().zip(lives) {
                *slot = Some(l);
            }
        };
        let take = |threads: usize| chunks.lock().expect("chunks").take(threads);
        let close = || chunks.lock().expect("chunks").closed = true;
        let local_threads = self.threads_of(0);
        let pool = &self.pool;
        let mut owed: Vec<Option<Range<usize>>> = vec![None; size];
        let hand_out = |r: usize, owed: &mut Vec<Option<Range<usize>>>| {
            if let Some(range) = take(self.threads_of(r)) {
                let message = Writer::new()
                    .u64(range.start as u64)
                    .u64(range.end as u64)
                    .finish();
                send(world, r, tag::JOBS, &message);
                count(message.len());
                owed[r] = Some(range);
            }
        };
        // The workers' first chunks before rank 0 starts on its own, which could otherwise
        // take every job of a quick generation before the others hear of it.
        for r in 1..size {
            hand_out(r, &mut owed);
        }
        let (local, remote) = std::thread::scope(|s| {
            // Rank 0's own share, on its own threads, while this thread talks to the others
            // (only this thread calls MPI).
            let local = s.spawn(|| {
                pool.install(|| -> Result<(), EvaluationError> {
                    while let Some(range) = take(local_threads) {
                        match jobs.run_range(range.clone()) {
                            Ok(lives) => store(0, range, lives),
                            Err(e) => {
                                close();
                                return Err(e);
                            }
                        }
                    }
                    Ok(())
                })
            });
            let mut failure: Option<EvaluationError> = None;
            let mut stop_seen: Option<Instant> = None;
            while owed.iter().any(Option::is_some) {
                let grace = match (stop_seen, self.stop_requested()) {
                    (Some(t), _) => Some(t + stop_grace()),
                    (None, true) => {
                        stop_seen = Some(Instant::now());
                        stop_seen.map(|t| t + stop_grace())
                    }
                    (None, false) => None,
                };
                let stop_check = || self.stop_requested();
                let Some((bytes, t, from)) = receive(
                    world,
                    None,
                    grace,
                    (grace.is_none()).then_some(&stop_check as &dyn Fn() -> bool),
                ) else {
                    if stop_seen.is_none() {
                        continue; // the stop flag was set: wait on with a deadline
                    }
                    close();
                    let late: Vec<String> = owed
                        .iter()
                        .enumerate()
                        .filter_map(|(r, o)| {
                            o.as_ref()
                                .map(|c| format!("rank {r} (jobs {}..{})", c.start, c.end))
                        })
                        .collect();
                    let rank = owed.iter().position(Option::is_some).unwrap_or(1);
                    failure.get_or_insert(EvaluationError::Rank {
                        rank,
                        what: format!(
                            "did not return its jobs of generation {generation} after the stop signal: {} still owed (a rank that died makes mpirun stop them all)",
                            late.join(", ")
                        ),
                    });
                    break;
                };
                count(bytes.len());
                let Some(range) = owed.get(from).cloned().flatten() else {
                    failure.get_or_insert(EvaluationError::Rank {
                        rank: from,
                        what: format!("sent a message (tag {t}) while it owed no jobs"),
                    });
                    continue;
                };
                owed[from] = None;
                let answer = read_answer(t, &bytes, &range, jobs);
                match answer {
                    Ok(Ok(lives)) => {
                        store(from, range, lives);
                        if failure.is_none() {
                            hand_out(from, &mut owed);
                        }
                    }
                    Ok(Err(what)) => {
                        close();
                        failure.get_or_insert(EvaluationError::Rank { rank: from, what });
                    }
                    Err(e) => {
                        close();
                        failure.get_or_insert(EvaluationError::Rank {
                            rank: from,
                            what: format!(
                                "sent its jobs {}..{} garbled: {e}",
                                range.start, range.end
                            ),
                        });
                    }
                }
            }
            let local = match local.join() {
                Ok(result) => result,
                Err(panic) => std::panic::resume_unwind(panic),
            };
            (local, failure)
        });
        self.traffic.set(traffic.get());
        local?;
        if let Some(e) = remote {
            return Err(e);
        }
        Ok(results
            .into_inner()
            .expect("results")
            .into_iter()
            .map(|l| l.expect("every job was run"))
            .collect())
    }
}

impl RanksRun<'_> {
    /// Messages and bytes exchanged in this run.
    pub fn traffic(&self) -> Traffic {
        self.traffic.get()
    }

    /// Jobs each rank has evaluated in this run, rank 0 first.
    pub fn jobs_per_rank(&self) -> Vec<u64> {
        self.done.lock().expect("done").clone()
    }
}

/// A worker's answer to its chunk `range` of `jobs`: the outcomes, or what it said went wrong
/// (`Ok(Err(..))`), or why its message could not be read (`Err`).
fn read_answer(
    t: Tag,
    bytes: &[u8],
    range: &Range<usize>,
    jobs: &PopulationJobs<'_>,
) -> Result<Result<Vec<JobLives>, String>, wire::WireError> {
    let mut r = Reader::new(bytes);
    match t {
        tag::LIVES => {
            let (a, b) = (r.u64()? as usize, r.u64()? as usize);
            if (a, b) != (range.start, range.end) {
                return Ok(Err(format!(
                    "returned jobs {a}..{b}, it was given {}..{}",
                    range.start, range.end
                )));
            }
            let shapes: Vec<(usize, usize)> = range.clone().map(|j| jobs.shape(j)).collect();
            let lives = r.lives(&shapes)?;
            r.end()?;
            Ok(Ok(lives))
        }
        tag::FAILED => {
            let _ = (r.u64()?, r.u64()?);
            Ok(Err(format!(
                "could not evaluate jobs {}..{} of generation {}: {}",
                range.start,
                range.end,
                jobs.generation().0,
                r.text()?
            )))
        }
        other => Ok(Err(format!(
            "sent a message with tag {other}, not its jobs"
        ))),
    }
}

/// Sends `bytes` to rank `to` with `tag` (a blocking standard send).
fn send(world: &SimpleCommunicator, to: usize, tag: Tag, bytes: &[u8]) {
    world.process_at_rank(to as i32).send_with_tag(bytes, tag);
}

/// The next message (bytes, tag, source) from rank `from` (any rank when `None`), polling with
/// short sleeps; `None` at `deadline` or as soon as `give_up()` says so.
fn receive(
    world: &SimpleCommunicator,
    from: Option<usize>,
    deadline: Option<Instant>,
    give_up: Option<&dyn Fn() -> bool>,
) -> Option<(Vec<u8>, Tag, usize)> {
    let mut nap = Duration::from_micros(20);
    loop {
        let probed = match from {
            Some(r) => world.process_at_rank(r as i32).immediate_matched_probe(),
            None => world.any_process().immediate_matched_probe(),
        };
        if let Some(probed) = probed {
            let (bytes, status) = probed.matched_receive_vec::<u8>();
            return Some((bytes, status.tag(), status.source_rank() as usize));
        }
        if deadline.is_some_and(|d| Instant::now() >= d) || give_up.is_some_and(|g| g()) {
            return None;
        }
        std::thread::sleep(nap);
        nap = (nap * 2).min(Duration::from_micros(500));
    }
}
