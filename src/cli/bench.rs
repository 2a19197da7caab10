//! `berry-evolve bench`: speed of the simulator (creature-ticks per second) and of whole
//! generations, with 1 and 2 threads. Timing lives here and in scripts, never in tests.

use crate::cli::console::outln;

use berry_evolve::brain::{Brain, BrainController};
use berry_evolve::evo::lockstep::{self, Lockstep};
use berry_evolve::evo::state::{evaluate, first_population, offspring};
use berry_evolve::experiment::Experiment;
use berry_evolve::seed::{stream, Generation, IndividualId, Purpose, TrialIndex};
use berry_evolve::sim::spec::WorldSpec;
use berry_evolve::sim::world::World;
use clap::Args;
use rayon::prelude::*;
use std::path::PathBuf;
use std::time::Instant;

/// Arguments of `bench`.
#[derive(Debug, Args)]
pub struct BenchArgs {
    /// Simulator benchmark world(s): experiment files whose [world], [creature] and [brain]
    /// are used, one creature per world driven by a random genome.
    #[arg(long, default_values_os_t = vec![
        PathBuf::from("experiments/bench/foraging-world.toml"),
        PathBuf::from("experiments/bench/eye-predators-world.toml"),
    ])]
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
    /// Evolution benchmark experiment.
    #[arg(long, default_value = "experiments/foraging.toml")]
    pub evolution: PathBuf,
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
    /// Base world of the scaling series.
    #[arg(long, default_value = "experiments/bench/foraging-world.toml")]
    pub scaling_world: PathBuf,
}

fn pool(threads: usize) -> anyhow::Result<rayon::ThreadPool> {
    Ok(rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()?)
}

/// Creature-ticks per second for `worlds` one-creature worlds of `spec` on `threads`
/// threads, all driven by one genome and run as evolution runs trials: in lockstep chunks
/// of [`lockstep::CHUNK_TRIALS`] worlds, one rayon job and one brain per chunk. Worlds and
/// brains are built before the clock starts: placement is not what is measured.
fn sim_rate(
    experiment: &Experiment,
    spec: &WorldSpec,
    worlds: u64,
    ticks: u64,
    threads: usize,
) -> anyhow::Result<f64> {
    let topology = experiment.topology();
    let mut rng = stream(
        experiment.seed(),
        Purpose::Baseline,
        Generation(0),
        IndividualId(0),
        TrialIndex(0),
    );
    let genome = berry_evolve::evo::init::initial_population(
        &experiment.evolution,
        topology.parameter_count(),
        &mut rng,
    )
    .swap_remove(0);
    anyhow::ensure!(
        lockstep::stateless(&topology),
        "the simulator benchmark runs worlds in lockstep and needs a stateless brain (an MLP)"
    );
    let pool = pool(threads)?;
    let mut jobs = Vec::new();
    for chunk in lockstep::chunks(worlds) {
        let brain = Brain::new(&topology, &genome.parameters)?;
        let controllers = [BrainController::new(
            brain,
            experiment.creature.max_rpt,
            experiment.creature.eats_by_action(),
        )];
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
                let width = worlds[0].layout().len();
                let mut lockstep = Lockstep::new(n, 1, width);
                let running = vec![true; n];
                let mut invalid = vec![false; n];
                for _ in 0..ticks {
                    lockstep.tick(worlds, &running, controllers, &mut invalid);
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

/// The scaling series' world `k`: `base` (a w × h arena) tiled k × k times into a kw × kh
/// arena at the same density of walls and food. Tile (i, j) holds a copy of every
/// `[[world.walls]]` entry and explicit object of `base`, shifted by (iw, jh); placement
/// rules place k² times as many objects over their region tiled the same way (a rule without
/// a region covers the whole larger arena). The arena's 4 boundary walls are shared, so
/// every tile but the first also gets 4 short free-standing wall pieces (two L-shaped pairs
/// in opposite corners) to replace the boundary walls it lacks: the tiled world has
/// exactly k² times `base`'s walls when `base` has boundary walls and 8 interior walls,
/// as the benchmark world does (12 → 1,200 walls for k = 10). `k = 1` is `base` itself.
pub fn tiled_world(base: &WorldSpec, k: u32) -> anyhow::Result<WorldSpec> {
    if k <= 1 {
        return Ok(base.clone());
    }
    anyhow::ensure!(
        base.doors.is_empty()
            && base.teleporters.is_empty()
            && base.predators.is_empty()
            && base.air_predators.is_empty()
            && base.wanderers.count == 0
            && base.areas.is_empty()
            && base.landmarks.is_empty(),
        "the scaling series tiles walls and food only; the base world has gadgets, areas or landmarks"
    );
    let [w, h] = base.arena;
    let mut spec = base.clone();
    spec.arena = [w * f64::from(k), h * f64::from(k)];
    spec.walls.clear();
    spec.objects.clear();
    // Corner pieces as fractions of the tile: (from, to).
    const PIECES: [([f64; 2], [f64; 2]); 4] = [
        ([0.05, 0.05], [0.2, 0.05]),
        ([0.05, 0.1], [0.05, 0.25]),
        ([0.8, 0.95], [0.95, 0.95]),
        ([0.95, 0.8], [0.95, 0.9]),
    ];
    for j in 0..k {
        for i in 0..k {
            let (dx, dy) = (w * f64::from(i), h * f64::from(j));
            let shift = |p: [f64; 2]| [p[0] + dx, p[1] + dy];
            for wall in &base.walls {
                let mut wall = wall.clone();
                wall.from = shift(wall.from);
                wall.to = shift(wall.to);
                spec.walls.push(wall);
            }
            if i + j > 0 && base.boundary_walls {
                for (from, to) in PIECES {
                    let mut wall =
                        base.walls.first().cloned().ok_or_else(|| {
                            anyhow::anyhow!("the base world has no interior walls")
                        })?;
                    wall.from = shift([from[0] * w, from[1] * h]);
                    wall.to = shift([to[0] * w, to[1] * h]);
                    wall.opaque = true;
                    spec.walls.push(wall);
                }
            }
            for object in &base.objects {
                let mut object = object.clone();
                object.position = shift(object.position);
                spec.objects.push(object);
            }
        }
    }
    spec.place.clear();
    for rule in &base.place {
        match rule.region {
            None => {
                let mut rule = rule.clone();
                rule.count *= u64::from(k) * u64::from(k);
                spec.place.push(rule);
            }
            Some([x0, y0, x1, y1]) => {
                for j in 0..k {
                    for i in 0..k {
                        let (dx, dy) = (w * f64::from(i), h * f64::from(j));
                        let mut rule = rule.clone();
                        rule.region = Some([x0 + dx, y0 + dy, x1 + dx, y1 + dy]);
                        spec.place.push(rule);
                    }
                }
            }
        }
    }
    if let Some([x0, y0, x1, y1]) = base.start.region {
        // One creature per world: it starts in the first tile's start region.
        spec.start.region = Some([x0, y0, x1, y1]);
    }
    Ok(spec)
}

/// Number of food and aversive objects a world spec will hold (explicit plus placed).
fn object_count(spec: &WorldSpec) -> u64 {
    spec.objects.len() as u64 + spec.place.iter().map(|p| p.count).sum::<u64>()
}

/// Number of walls of a world spec, boundary walls included.
fn wall_count(spec: &WorldSpec) -> usize {
    spec.walls.len() + if spec.boundary_walls { 4 } else { 0 }
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
    ga_seconds: f64,
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
    let mut population = first_population(experiment, &topology);
    let mut timing = EvolutionTiming {
        eval_seconds: 0.0,
        ga_seconds: 0.0,
        bests: Vec::new(),
    };
    for g in 0..generations {
        let t = Instant::now();
        let evaluated = pool.install(|| evaluate(experiment, &topology, g, population))?;
        timing.eval_seconds += t.elapsed().as_secs_f64();
        let t = Instant::now();
        let summary = evaluated.summary();
        timing.bests.push(summary.stats.best.to_bits());
        population = offspring(experiment, &evaluated);
        timing.ga_seconds += t.elapsed().as_secs_f64();
    }
    Ok(timing)
}

/// Runs the subcommand.
pub fn run(args: BenchArgs) -> anyhow::Result<()> {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let repeat = args.repeat.max(1);
    outln!(
        "berry-evolve {} bench; {cores} cores available; every figure is the median of {repeat} run(s), 1 and 2 threads measured in alternating rounds",
        env!("CARGO_PKG_VERSION")
    );
    for path in &args.world {
        let experiment = Experiment::load(path)?;
        let spec = &experiment.world;
        // Warm up caches and the allocator once.
        sim_rate(&experiment, spec, 2, args.ticks.min(500), 1)?;
        // Rounds of 1 thread then 2 threads back to back: a shared VM's speed drifts from
        // second to second, so the speed-up is the median of each round's own ratio, not the
        // ratio of medians measured minutes apart.
        // The reference loop runs just before and after each 1-thread run, on the same thread.
        let mut rounds = Vec::with_capacity(repeat as usize);
        let mut machine = Vec::with_capacity(repeat as usize);
        for _ in 0..repeat {
            let before = machine_speeds();
            let one = sim_rate(&experiment, spec, args.worlds, args.ticks, 1)?;
            let after = machine_speeds();
            machine.push([0.5 * (before[0] + after[0]), 0.5 * (before[1] + after[1])]);
            let two = sim_rate(&experiment, spec, args.worlds, args.ticks, 2)?;
            rounds.push((one, two));
        }
        let ones: Vec<f64> = rounds.iter().map(|r| r.0).collect();
        let (low, high) = spread(&ones);
        outln!(
            "simulator {}: {:.0} creature-ticks/s on 1 thread, {:.0} on 2 threads ({:.2}x); 1-thread runs {:.0}-{:.0}",
            path.display(),
            median(ones.clone()),
            median(rounds.iter().map(|r| r.1).collect()),
            median(rounds.iter().map(|r| r.1 / r.0).collect()),
            low,
            high
        );
        let throughput: Vec<f64> = machine.iter().map(|m| m[0]).collect();
        let (slowest, fastest) = spread(&throughput);
        let (latency_low, latency_high) = spread(&machine.iter().map(|m| m[1]).collect::<Vec<_>>());
        let quiet = quiet_rounds(&throughput, &ones);
        outln!(
            "  machine check around the 1-thread runs: a high-throughput arithmetic loop ran at {:.1}-{:.1}M steps/s ({:.2}x spread), a latency-bound one at {:.0}-{:.0}M ({:.2}x); 1 thread in the {} round(s) where the first ran within {:.0}% of its fastest: {:.0} creature-ticks/s",
            slowest / 1e6,
            fastest / 1e6,
            fastest / slowest,
            latency_low / 1e6,
            latency_high / 1e6,
            latency_high / latency_low,
            quiet.len(),
            100.0 * QUIET,
            median(quiet)
        );
    }
    if !args.scaling.iter().all(|&k| k == 0) {
        let experiment = Experiment::load(&args.scaling_world)?;
        let mut first = None;
        for &k in args.scaling.iter().filter(|&&k| k > 0) {
            let spec = tiled_world(&experiment.world, k)?;
            // One thread runs one chunk at a time, so one chunk's worth of (large) worlds
            // gives the same rate as more.
            let worlds = args.worlds.min(berry_evolve::evo::lockstep::CHUNK_TRIALS);
            let rate = median_of(repeat, || {
                sim_rate(&experiment, &spec, worlds, args.ticks, 1)
            })?;
            let base = *first.get_or_insert(rate);
            outln!(
                "scaling {} x{k}: {:.0} x {:.0} arena, {} walls, {} objects: {:.0} creature-ticks/s on 1 thread, cost per creature-tick {:.2}x the first",
                args.scaling_world.display(),
                spec.arena[0],
                spec.arena[1],
                wall_count(&spec),
                object_count(&spec),
                rate,
                base / rate
            );
        }
    }
    if args.generations > 0 {
        let experiment = Experiment::load(&args.evolution)?;
        let per_generation = experiment.evolution.population as f64
            * experiment.evaluation.trials as f64
            * experiment.evaluation.ticks as f64;
        let gens = args.generations as f64;
        // Rounds of 1 thread then 2 threads, as for the simulator.
        let mut timings: [Vec<EvolutionTiming>; 2] = [Vec::new(), Vec::new()];
        for _ in 0..repeat {
            for (threads, runs) in [1usize, 2].into_iter().zip(timings.iter_mut()) {
                runs.push(time_evolution(&experiment, args.generations, threads)?);
            }
        }
        let rate = |t: &EvolutionTiming| gens / (t.eval_seconds + t.ga_seconds);
        for (threads, runs) in [1usize, 2].into_iter().zip(&timings) {
            let ga_share = median(
                runs.iter()
                    .map(|t| 100.0 * t.ga_seconds / (t.eval_seconds + t.ga_seconds))
                    .collect(),
            );
            let rate = median(runs.iter().map(rate).collect());
            outln!(
                "evolution {} on {threads} thread(s): {:.3} generations/s, {:.0} creature-ticks/s (agent-steps/s), GA share {:.2}%",
                args.evolution.display(),
                rate,
                per_generation * rate,
                ga_share
            );
        }
        let speed_up = median(
            timings[0]
                .iter()
                .zip(&timings[1])
                .map(|(one, two)| rate(two) / rate(one))
                .collect(),
        );
        let mut bests = timings.iter().flatten().map(|t| &t.bests);
        let first = bests.next();
        outln!(
            "evolution speed-up 2 vs 1 thread: {:.2}x; best fitness per generation identical in every run: {}",
            speed_up,
            if bests.all(|b| Some(b) == first) {
                "yes"
            } else {
                "NO"
            }
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

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

    fn bench_world() -> Experiment {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        Experiment::load(&root.join("experiments/bench/foraging-world.toml")).unwrap()
    }

    #[test]
    fn tiling_keeps_the_density_of_walls_and_food() {
        let experiment = bench_world();
        let base = &experiment.world;
        assert_eq!(tiled_world(base, 1).unwrap(), *base);
        for k in [2u32, 5, 10] {
            let spec = tiled_world(base, k).unwrap();
            let k2 = u64::from(k * k);
            assert_eq!(spec.arena, [300.0 * f64::from(k), 300.0 * f64::from(k)]);
            assert_eq!(wall_count(&spec) as u64, 12 * k2, "k = {k}");
            assert_eq!(object_count(&spec), 40 * k2, "k = {k}");
            for wall in &spec.walls {
                for p in [wall.from, wall.to] {
                    assert!(p[0] >= 0.0 && p[0] <= spec.arena[0], "{p:?}");
                    assert!(p[1] >= 0.0 && p[1] <= spec.arena[1], "{p:?}");
                }
            }
        }
        // The largest world of the series can be built and run.
        let spec = tiled_world(base, 10).unwrap();
        let rng = stream(
            experiment.seed(),
            Purpose::Baseline,
            Generation(0),
            IndividualId(0),
            TrialIndex(0),
        );
        let world = World::new(&spec, &experiment.creature, 1, rng).unwrap();
        assert_eq!(world.creatures().len(), 1);
    }
}
