//! `berry-evolve bench`: speed of the simulator (creature-ticks per second) and of whole
//! generations, with 1 and 2 threads. Timing lives here and in scripts, never in tests.

use crate::cli::console::{errln, outln};

use berry_evolve::brain::{Brain, BrainController};
use berry_evolve::evo::lockstep::{self, Lanes, Lockstep, WorldBrains};
use berry_evolve::evo::search;
use berry_evolve::evo::state::evaluate;
use berry_evolve::evo::worlds::random_genomes;
use berry_evolve::experiment::templates::{Template, BENCH_WORLDS};
use berry_evolve::experiment::tiled::{object_count, tiled_world, wall_count};
use berry_evolve::experiment::Experiment;
use berry_evolve::seed::{stream, Generation, IndividualId, Purpose, TrialIndex};
use berry_evolve::sim::spec::WorldSpec;
use berry_evolve::sim::world::World;
use clap::Args;
use rayon::prelude::*;
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Arguments of `bench`.
#[derive(Debug, Args)]
#[command(
    after_help = "Rates are creature-ticks per second (one creature's tick, senses, \
                        brain and move); the reference loops' in steps per second. With --json, \
                        stdout holds one JSON document (schema berry-evolve/bench/1) with the \
                        same figures at full precision, and the text goes to stderr."
)]
pub struct BenchArgs {
    /// Simulator benchmark world(s): experiment files whose [world], [creature] and [brain]
    /// are used, one creature per world driven by a random genome (default: the built-in
    /// experiments/bench/foraging-world.toml and eye-predators-world.toml, as shipped with
    /// this version, so `bench` works from any folder; name the files to measure edited ones).
    #[arg(long)]
    pub world: Vec<PathBuf>,
    /// Worlds per simulator measurement. They run in lockstep chunks of 16 worlds, one
    /// rayon job per chunk, as evolution runs trials. Chunks differ in cost (their creatures
    /// take different paths), so with few chunks the 2-thread figure measures how evenly 4
    /// jobs split; 256 give the threads 16 jobs to share, as a generation's 64 or more do.
    #[arg(long, default_value_t = 256)]
    pub worlds: u64,
    /// Ticks per world: 256 × 2,500 = 640,000 creature-ticks per measurement (about a
    /// quarter of a second on the standard world).
    #[arg(long, default_value_t = 2500)]
    pub ticks: u64,
    /// Evolution benchmark experiment (default: the built-in experiments/foraging.toml).
    #[arg(long)]
    pub evolution: Option<PathBuf>,
    /// Generations for the evolution benchmark (0 skips it).
    #[arg(long, default_value_t = 10)]
    pub generations: u64,
    /// Tiling factors k of the scaling series: the scaling world tiled k × k times at the
    /// same density (comma-separated; 0 alone skips the series).
    #[arg(long, value_delimiter = ',', default_values_t = vec![1u32, 2, 5, 10])]
    pub scaling: Vec<u32>,
    /// Runs of every measurement; each figure printed is their median.
    #[arg(long, default_value_t = 1)]
    pub repeat: u32,
    /// Base world of the scaling series (default: the built-in
    /// experiments/bench/foraging-world.toml).
    #[arg(long)]
    pub scaling_world: Option<PathBuf>,
    /// Print one JSON document on stdout (schema `berry-evolve/bench/1`: every figure at full
    /// precision) and the text on stderr.
    #[arg(long)]
    pub json: bool,
}

/// An experiment to measure and how the output names it.
struct Source {
    /// The file as given, or the built-in file's path in the repository.
    label: String,
    /// Whether it is the copy built into the program.
    built_in: bool,
    experiment: Experiment,
}

impl Source {
    /// The file at `path`, or the built-in `template` when no path is given.
    fn file_or(path: Option<&Path>, template: &Template) -> anyhow::Result<Source> {
        match path {
            Some(path) => Source::file(path),
            None => Source::built_in(template),
        }
    }

    /// An experiment file named on the command line.
    fn file(path: &Path) -> anyhow::Result<Source> {
        Ok(Source {
            label: path.display().to_string(),
            built_in: false,
            experiment: Experiment::load(path)?,
        })
    }

    /// The copy of a shipped file built into the program, labelled with its repository path.
    fn built_in(template: &Template) -> anyhow::Result<Source> {
        Ok(Source {
            label: template.file.to_string(),
            built_in: true,
            experiment: template.experiment()?,
        })
    }
}

/// What `bench --json` prints: every figure of the text output, at full precision. Rates are
/// creature-ticks per second, the reference loops' steps per second.
#[derive(Debug, Serialize)]
struct BenchReport {
    schema: &'static str,
    version: &'static str,
    cores: usize,
    /// Runs of every measurement; each figure is their median.
    repeat: u32,
    /// Worlds and ticks per world of each simulator measurement.
    worlds: u64,
    ticks: u64,
    simulator: Vec<SimulatorFigures>,
    scaling: Vec<ScalingFigures>,
    /// None when `--generations 0` skipped it.
    evolution: Option<EvolutionFigures>,
}

/// One simulator world, 1 and 2 threads.
#[derive(Debug, Serialize)]
struct SimulatorFigures {
    world: String,
    built_in: bool,
    one_thread: f64,
    two_threads: f64,
    /// Median of each round's own 2-thread / 1-thread ratio.
    speed_up: f64,
    one_thread_low: f64,
    one_thread_high: f64,
    machine: MachineCheck,
}

/// The reference loops timed around the 1-thread runs (see [`machine_speeds`]).
#[derive(Debug, Serialize)]
struct MachineCheck {
    throughput_low: f64,
    throughput_high: f64,
    /// high / low.
    throughput_spread: f64,
    latency_low: f64,
    latency_high: f64,
    latency_spread: f64,
    /// Rounds whose throughput loop ran within `quiet_within` of its fastest.
    quiet_rounds: usize,
    quiet_within: f64,
    /// Median 1-thread rate of those rounds.
    one_thread_quiet: f64,
}

/// One world of the scaling series, 1 thread.
#[derive(Debug, Serialize)]
struct ScalingFigures {
    world: String,
    built_in: bool,
    k: u32,
    arena: [f64; 2],
    walls: usize,
    objects: u64,
    one_thread: f64,
    /// Cost per creature-tick relative to the series' first world.
    cost_relative: f64,
}

/// Whole generations of an experiment.
#[derive(Debug, Serialize)]
struct EvolutionFigures {
    experiment: String,
    built_in: bool,
    /// The experiment's search algorithm as `[evolution] algorithm` names it (`ga`, `pgpe`):
    /// the one timed.
    algorithm: &'static str,
    generations: u64,
    /// Individuals evaluated per generation × trials × ticks.
    creature_ticks_per_generation: f64,
    threads: Vec<EvolutionRate>,
    /// Median of each round's own 2-thread / 1-thread ratio.
    speed_up: f64,
    /// Whether every run (both thread counts, every repeat) found the same best fitness in
    /// every generation, bit for bit.
    identical_bests: bool,
}

/// Whole generations on one thread count.
#[derive(Debug, Serialize)]
struct EvolutionRate {
    threads: usize,
    generations_per_second: f64,
    creature_ticks_per_second: f64,
    /// The search's share of a generation's wall time (its ask and tell, and the
    /// generation's summary), in percent.
    search_share_percent: f64,
}

fn pool(threads: usize) -> anyhow::Result<rayon::ThreadPool> {
    Ok(rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()?)
}

/// Creature-ticks per second for `worlds` one-creature worlds of `spec` on `threads`
/// threads, all driven by one genome and run as evolution runs trials: in lockstep chunks
/// of [`lockstep::CHUNK_TRIALS`] worlds, one rayon job and one brain per chunk (a plastic
/// MLP gets one brain per world in the lockstep, [`lockstep::WorldBrains`]; a recurrent
/// brain one per world, each world stepped alone, as evolution's single-trial path does).
/// Worlds and brains are built before the clock starts: placement is not what is measured.
fn sim_rate(
    experiment: &Experiment,
    spec: &WorldSpec,
    worlds: u64,
    ticks: u64,
    threads: usize,
) -> anyhow::Result<f64> {
    let topology = experiment.topology();
    let genome = random_genomes(experiment, Generation(0), 1).swap_remove(0);
    // A brain that keeps state cannot serve several worlds: each world gets its own.
    let lanes = lockstep::lanes(&topology);
    let stateless = lanes == Some(Lanes::Shared);
    let pool = pool(threads)?;
    let mut jobs = Vec::new();
    for chunk in lanes.map_or_else(
        || lockstep::chunks(worlds),
        |l| lockstep::chunks_for(l, worlds),
    ) {
        let brains = if stateless {
            1
        } else {
            chunk.end - chunk.start
        };
        let controllers = (0..brains)
            .map(|_| {
                let brain = Brain::new(&topology, &genome.parameters)?;
                Ok(BrainController::new(
                    brain,
                    experiment.creature.max_rpt,
                    experiment.creature.eats_by_action(),
                ))
            })
            .collect::<anyhow::Result<Vec<_>>>()?;
        let mut chunk_worlds = Vec::with_capacity((chunk.end - chunk.start) as usize);
        for w in chunk {
            let rng = stream(
                experiment.seed(),
                Purpose::Baseline,
                Generation(1),
                IndividualId(w),
                TrialIndex(0),
            );
            chunk_worlds.push(World::new(spec, &experiment.creature, 1, rng)?);
        }
        jobs.push((chunk_worlds, controllers));
    }
    let start = Instant::now();
    let travelled: Vec<f64> = pool.install(|| {
        jobs.par_iter_mut()
            .with_max_len(berry_evolve::evo::evaluate::JOBS_APART)
            .flat_map_iter(|(worlds, controllers)| {
                let n = worlds.len();
                if let Some(lanes) = lanes {
                    let width = worlds[0].layout().len();
                    let mut lockstep = Lockstep::new(n, 1, width);
                    let running = vec![true; n];
                    let mut invalid = vec![false; n];
                    if lanes == Lanes::Shared {
                        for _ in 0..ticks {
                            lockstep.tick(worlds, &running, controllers, &mut invalid);
                        }
                    } else {
                        let mut brains = [WorldBrains::new(std::mem::take(controllers))];
                        for _ in 0..ticks {
                            lockstep.tick(worlds, &running, &mut brains, &mut invalid);
                        }
                    }
                } else {
                    for (world, controller) in worlds.iter_mut().zip(controllers.iter_mut()) {
                        for _ in 0..ticks {
                            world.step(std::slice::from_mut(controller));
                        }
                    }
                }
                worlds.iter().map(|w| w.creatures()[0].travelled)
            })
            .collect()
    });
    let elapsed = start.elapsed().as_secs_f64();
    // Keep the result observable so that no tick can be optimised away.
    std::hint::black_box(travelled);
    Ok((worlds * ticks) as f64 / elapsed)
}

/// The median of `values` (the mean of the middle two for an even count).
fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    let n = values.len();
    if n == 0 {
        f64::NAN
    } else if n % 2 == 1 {
        values[n / 2]
    } else {
        0.5 * (values[n / 2 - 1] + values[n / 2])
    }
}

/// Steps per second of two fixed arithmetic loops that touch no memory beyond the stack:
/// `[throughput, latency]`. The first keeps the core's floating-point units as busy as the
/// simulator does (16 independent 4-lane multiply-add chains, vectorised; about 15 ms); the
/// second is one chain of dependent multiply-adds, which waits on each result and leaves the
/// units mostly idle (about 5 ms).
///
/// # Why
/// On a shared host a virtual CPU is often one hardware thread of a core whose other thread
/// runs another tenant's work. While that thread is busy, code that issues several
/// instructions per cycle, as the simulator does, runs up to twice as slowly, while
/// latency-bound code barely notices. Timing both loops next to every 1-thread run tells a
/// slow machine from a slow program (figures in docs/performance.md).
fn machine_speeds() -> [f64; 2] {
    const STEPS: u32 = 500_000;
    let start = Instant::now();
    let mut chains = [[1.0f64; 4]; 16];
    for _ in 0..STEPS {
        for (j, chain) in chains.iter_mut().enumerate() {
            for (l, x) in chain.iter_mut().enumerate() {
                *x = *x * 0.999_999_9 + (j + l) as f64 * 1e-12;
            }
        }
        // Keeps the compiler from folding the loop.
        chains = std::hint::black_box(chains);
    }
    let throughput = f64::from(STEPS) / start.elapsed().as_secs_f64();
    const CHAIN: u32 = 4 * STEPS;
    let start = Instant::now();
    let mut x = std::hint::black_box(1.0f64);
    for _ in 0..CHAIN {
        x = x * 0.999_999_9 + 1e-12;
    }
    std::hint::black_box(x);
    [throughput, f64::from(CHAIN) / start.elapsed().as_secs_f64()]
}

/// How far below its fastest run the reference loop may be for a round to count as quiet.
const QUIET: f64 = 0.1;

/// The 1-thread rates (`ones`) of the rounds whose reference loop speed (`machine`, same
/// order) is within [`QUIET`] of the fastest.
fn quiet_rounds(machine: &[f64], ones: &[f64]) -> Vec<f64> {
    let fastest = machine.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    machine
        .iter()
        .zip(ones)
        .filter(|(&m, _)| m >= (1.0 - QUIET) * fastest)
        .map(|(_, &one)| one)
        .collect()
}

/// The smallest and largest of `values` (NaN for none).
fn spread(values: &[f64]) -> (f64, f64) {
    let low = values.iter().copied().reduce(f64::min).unwrap_or(f64::NAN);
    let high = values.iter().copied().reduce(f64::max).unwrap_or(f64::NAN);
    (low, high)
}

/// `measure` run `repeat` times; the median.
fn median_of(repeat: u32, mut measure: impl FnMut() -> anyhow::Result<f64>) -> anyhow::Result<f64> {
    let mut values = Vec::with_capacity(repeat as usize);
    for _ in 0..repeat.max(1) {
        values.push(measure()?);
    }
    Ok(median(values))
}

/// One timed evolution: `generations` generations of `experiment` on `threads` threads.
struct EvolutionTiming {
    eval_seconds: f64,
    /// The search's ask and tell, and the generation's summary.
    search_seconds: f64,
    /// Best fitness of each generation, as bits (to compare thread counts).
    bests: Vec<u64>,
}

fn time_evolution(
    experiment: &Experiment,
    generations: u64,
    threads: usize,
) -> anyhow::Result<EvolutionTiming> {
    let topology = experiment.topology();
    let pool = pool(threads)?;
    // The experiment's own search, as a run drives it: ask, evaluate, tell.
    let t = Instant::now();
    let mut search = search::factory::of(experiment, &topology);
    let mut population = pool.install(|| search.ask());
    let mut timing = EvolutionTiming {
        eval_seconds: 0.0,
        search_seconds: t.elapsed().as_secs_f64(),
        bests: Vec::new(),
    };
    for g in 0..generations {
        let t = Instant::now();
        let evaluated = pool.install(|| evaluate(experiment, &topology, g, population.genomes))?;
        timing.eval_seconds += t.elapsed().as_secs_f64();
        let t = Instant::now();
        let summary = evaluated.summary();
        timing.bests.push(summary.stats.best.to_bits());
        population = pool.install(|| {
            search.tell(&evaluated);
            search.ask()
        });
        timing.search_seconds += t.elapsed().as_secs_f64();
    }
    Ok(timing)
}

/// Prints a line of the text output: on stdout, or on stderr when stdout holds the JSON.
fn say(json: bool, line: std::fmt::Arguments<'_>) {
    if json {
        errln!("{line}");
    } else {
        outln!("{line}");
    }
}

/// Runs the subcommand.
pub fn run(args: BenchArgs) -> anyhow::Result<()> {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let repeat = args.repeat.max(1);
    let json = args.json;
    let mut report = BenchReport {
        schema: "berry-evolve/bench/1",
        version: env!("CARGO_PKG_VERSION"),
        cores,
        repeat,
        worlds: args.worlds,
        ticks: args.ticks,
        simulator: Vec::new(),
        scaling: Vec::new(),
        evolution: None,
    };
    say(json, format_args!(
        "berry-evolve {} bench; {cores} cores available; every figure is the median of {repeat} run(s), 1 and 2 threads measured in alternating rounds",
        report.version
    ));
    let worlds: Vec<Source> = if args.world.is_empty() {
        BENCH_WORLDS
            .iter()
            .map(Source::built_in)
            .collect::<anyhow::Result<_>>()?
    } else {
        args.world
            .iter()
            .map(|p| Source::file(p))
            .collect::<anyhow::Result<_>>()?
    };
    for source in &worlds {
        let figures = simulator(source, &args, repeat)?;
        say(json, format_args!(
            "simulator {}: {:.0} creature-ticks/s on 1 thread, {:.0} on 2 threads ({:.2}x); 1-thread runs {:.0}-{:.0}",
            figures.world,
            figures.one_thread,
            figures.two_threads,
            figures.speed_up,
            figures.one_thread_low,
            figures.one_thread_high
        ));
        let m = &figures.machine;
        say(json, format_args!(
            "  machine check around the 1-thread runs: a high-throughput arithmetic loop ran at {:.1}-{:.1}M steps/s ({:.2}x spread), a latency-bound one at {:.0}-{:.0}M ({:.2}x); 1 thread in the {} round(s) where the first ran within {:.0}% of its fastest: {:.0} creature-ticks/s",
            m.throughput_low / 1e6,
            m.throughput_high / 1e6,
            m.throughput_spread,
            m.latency_low / 1e6,
            m.latency_high / 1e6,
            m.latency_spread,
            m.quiet_rounds,
            100.0 * m.quiet_within,
            m.one_thread_quiet
        ));
        report.simulator.push(figures);
    }
    if !args.scaling.iter().all(|&k| k == 0) {
        let source = Source::file_or(args.scaling_world.as_deref(), &BENCH_WORLDS[0])?;
        let experiment = &source.experiment;
        let mut first = None;
        for &k in args.scaling.iter().filter(|&&k| k > 0) {
            let spec = tiled_world(&experiment.world, k)?;
            // One thread runs one chunk at a time, so one chunk's worth of (large) worlds
            // gives the same rate as more.
            let worlds = args.worlds.min(berry_evolve::evo::lockstep::CHUNK_TRIALS);
            let rate = median_of(repeat, || {
                sim_rate(experiment, &spec, worlds, args.ticks, 1)
            })?;
            let base = *first.get_or_insert(rate);
            let figures = ScalingFigures {
                world: source.label.clone(),
                built_in: source.built_in,
                k,
                arena: spec.arena,
                walls: wall_count(&spec),
                objects: object_count(&spec),
                one_thread: rate,
                cost_relative: base / rate,
            };
            say(json, format_args!(
                "scaling {} x{k}: {:.0} x {:.0} arena, {} walls, {} objects: {:.0} creature-ticks/s on 1 thread, cost per creature-tick {:.2}x the first",
                figures.world,
                figures.arena[0],
                figures.arena[1],
                figures.walls,
                figures.objects,
                figures.one_thread,
                figures.cost_relative
            ));
            report.scaling.push(figures);
        }
    }
    if args.generations > 0 {
        let foraging = berry_evolve::experiment::templates::find("foraging")
            .expect("experiments/foraging.toml is built in");
        let source = Source::file_or(args.evolution.as_deref(), foraging)?;
        let figures = evolution(&source, args.generations, repeat)?;
        for rate in &figures.threads {
            say(json, format_args!(
                "evolution {} (algorithm {}) on {} thread(s): {:.3} generations/s, {:.0} creature-ticks/s (agent-steps/s), search share {:.2}% (ask, tell and the generation's summary)",
                figures.experiment,
                figures.algorithm,
                rate.threads,
                rate.generations_per_second,
                rate.creature_ticks_per_second,
                rate.search_share_percent
            ));
        }
        say(json, format_args!(
            "evolution speed-up 2 vs 1 thread: {:.2}x; best fitness per generation identical in every run: {}",
            figures.speed_up,
            if figures.identical_bests { "yes" } else { "NO" }
        ));
        report.evolution = Some(figures);
    }
    if json {
        outln!("{}", serde_json::to_string_pretty(&report)?);
    }
    Ok(())
}

/// The simulator figures of one world: `repeat` rounds of 1 thread then 2 threads.
fn simulator(source: &Source, args: &BenchArgs, repeat: u32) -> anyhow::Result<SimulatorFigures> {
    let experiment = &source.experiment;
    let spec = &experiment.world;
    // Warm up caches and the allocator once.
    sim_rate(experiment, spec, 2, args.ticks.min(500), 1)?;
    // Rounds of 1 thread then 2 threads back to back: a shared VM's speed drifts from
    // second to second, so the speed-up is the median of each round's own ratio, not the
    // ratio of medians measured minutes apart.
    // The reference loop runs just before and after each 1-thread run, on the same thread.
    let mut rounds = Vec::with_capacity(repeat as usize);
    let mut machine = Vec::with_capacity(repeat as usize);
    for _ in 0..repeat {
        let before = machine_speeds();
        let one = sim_rate(experiment, spec, args.worlds, args.ticks, 1)?;
        let after = machine_speeds();
        machine.push([0.5 * (before[0] + after[0]), 0.5 * (before[1] + after[1])]);
        let two = sim_rate(experiment, spec, args.worlds, args.ticks, 2)?;
        rounds.push((one, two));
    }
    let ones: Vec<f64> = rounds.iter().map(|r| r.0).collect();
    let (one_thread_low, one_thread_high) = spread(&ones);
    let throughput: Vec<f64> = machine.iter().map(|m| m[0]).collect();
    let (throughput_low, throughput_high) = spread(&throughput);
    let (latency_low, latency_high) = spread(&machine.iter().map(|m| m[1]).collect::<Vec<_>>());
    let quiet = quiet_rounds(&throughput, &ones);
    Ok(SimulatorFigures {
        world: source.label.clone(),
        built_in: source.built_in,
        one_thread: median(ones),
        two_threads: median(rounds.iter().map(|r| r.1).collect()),
        speed_up: median(rounds.iter().map(|r| r.1 / r.0).collect()),
        one_thread_low,
        one_thread_high,
        machine: MachineCheck {
            throughput_low,
            throughput_high,
            throughput_spread: throughput_high / throughput_low,
            latency_low,
            latency_high,
            latency_spread: latency_high / latency_low,
            quiet_rounds: quiet.len(),
            quiet_within: QUIET,
            one_thread_quiet: median(quiet),
        },
    })
}

/// The evolution figures: `repeat` rounds of `generations` generations on 1 then 2 threads.
fn evolution(source: &Source, generations: u64, repeat: u32) -> anyhow::Result<EvolutionFigures> {
    let experiment = &source.experiment;
    let search = search::factory::of(experiment, &experiment.topology());
    let per_generation = search.evaluated_per_generation() as f64
        * experiment.evaluation.trials as f64
        * experiment.evaluation.ticks as f64
        * experiment.evaluation.episodes_per_life as f64;
    let gens = generations as f64;
    // Rounds of 1 thread then 2 threads, as for the simulator.
    let mut timings: [Vec<EvolutionTiming>; 2] = [Vec::new(), Vec::new()];
    for _ in 0..repeat {
        for (threads, runs) in [1usize, 2].into_iter().zip(timings.iter_mut()) {
            runs.push(time_evolution(experiment, generations, threads)?);
        }
    }
    let rate = |t: &EvolutionTiming| gens / (t.eval_seconds + t.search_seconds);
    let threads = [1usize, 2]
        .into_iter()
        .zip(&timings)
        .map(|(threads, runs)| {
            let generations_per_second = median(runs.iter().map(rate).collect());
            EvolutionRate {
                threads,
                generations_per_second,
                creature_ticks_per_second: per_generation * generations_per_second,
                search_share_percent: median(
                    runs.iter()
                        .map(|t| 100.0 * t.search_seconds / (t.eval_seconds + t.search_seconds))
                        .collect(),
                ),
            }
        })
        .collect();
    let speed_up = median(
        timings[0]
            .iter()
            .zip(&timings[1])
            .map(|(one, two)| rate(two) / rate(one))
            .collect(),
    );
    let mut bests = timings.iter().flatten().map(|t| &t.bests);
    let first = bests.next();
    Ok(EvolutionFigures {
        experiment: source.label.clone(),
        built_in: source.built_in,
        algorithm: search.name(),
        generations,
        creature_ticks_per_generation: per_generation,
        threads,
        speed_up,
        identical_bests: bests.all(|b| Some(b) == first),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quiet_rounds_are_those_near_the_fastest_reference_loop() {
        let machine = [30.0, 40.0, 37.0, 35.9, 22.0];
        let ones = [2.0, 3.0, 2.8, 2.6, 1.6];
        // 36 = 90% of 40: 37 counts, 35.9 does not.
        assert_eq!(quiet_rounds(&machine, &ones), vec![3.0, 2.8]);
        assert!(quiet_rounds(&[], &[]).is_empty());
    }

    #[test]
    fn the_machine_loops_report_finite_speeds() {
        for speed in machine_speeds() {
            assert!(speed.is_finite() && speed > 0.0, "{speed}");
        }
    }
}
