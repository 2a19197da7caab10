//! `berry-evolve bench`: speed of the simulator (creature-ticks per second) and of whole
//! generations, with 1 and 2 threads. Timing lives here and in scripts, never in tests.

use berry_evolve::brain::{Brain, BrainController};
use berry_evolve::evo::state::{evaluate, first_population, offspring};
use berry_evolve::experiment::Experiment;
use berry_evolve::seed::{stream, Generation, IndividualId, Purpose, TrialIndex};
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
    /// Worlds per simulator measurement.
    #[arg(long, default_value_t = 16)]
    pub worlds: u64,
    /// Ticks per world.
    #[arg(long, default_value_t = 5000)]
    pub ticks: u64,
    /// Evolution benchmark experiment.
    #[arg(long, default_value = "experiments/foraging.toml")]
    pub evolution: PathBuf,
    /// Generations for the evolution benchmark (0 skips it).
    #[arg(long, default_value_t = 3)]
    pub generations: u64,
}

fn pool(threads: usize) -> anyhow::Result<rayon::ThreadPool> {
    Ok(rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()?)
}

/// Creature-ticks per second for `worlds` one-creature worlds on `threads` threads.
fn sim_rate(
    experiment: &Experiment,
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
    let pool = pool(threads)?;
    let start = Instant::now();
    let results: Vec<anyhow::Result<f64>> = pool.install(|| {
        (0..worlds)
            .into_par_iter()
            .map(|w| {
                let brain = Brain::new(&topology, &genome.parameters)?;
                let mut controllers = [BrainController::new(
                    brain,
                    experiment.creature.max_rpt,
                    experiment.creature.eats_by_action(),
                )];
                let rng = stream(
                    experiment.seed(),
                    Purpose::Baseline,
                    Generation(1),
                    IndividualId(w),
                    TrialIndex(0),
                );
                let mut world = World::new(&experiment.world, &experiment.creature, 1, rng)?;
                for _ in 0..ticks {
                    world.step(&mut controllers);
                }
                Ok(world.creatures()[0].travelled)
            })
            .collect()
    });
    let elapsed = start.elapsed().as_secs_f64();
    for r in results {
        r?;
    }
    Ok((worlds * ticks) as f64 / elapsed)
}

/// Runs the subcommand.
pub fn run(args: BenchArgs) -> anyhow::Result<()> {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    println!(
        "berry-evolve {} bench; {cores} cores available",
        env!("CARGO_PKG_VERSION")
    );
    for path in &args.world {
        let experiment = Experiment::load(path)?;
        // Warm up caches and the allocator once.
        sim_rate(&experiment, 2, args.ticks.min(500), 1)?;
        let one = sim_rate(&experiment, args.worlds, args.ticks, 1)?;
        let two = sim_rate(&experiment, args.worlds, args.ticks, 2)?;
        println!(
            "simulator {}: {:.0} creature-ticks/s on 1 thread, {:.0} on 2 threads ({:.2}x)",
            path.display(),
            one,
            two,
            two / one
        );
    }
    if args.generations > 0 {
        let experiment = Experiment::load(&args.evolution)?;
        let topology = experiment.topology();
        let per_generation = experiment.evolution.population as f64
            * experiment.evaluation.trials as f64
            * experiment.evaluation.ticks as f64;
        let mut rates = Vec::new();
        for threads in [1usize, 2] {
            let pool = pool(threads)?;
            let mut population = first_population(&experiment, &topology);
            let (mut eval_time, mut ga_time) = (0.0, 0.0);
            let mut bests = Vec::new();
            for g in 0..args.generations {
                let t = Instant::now();
                let evaluated = pool.install(|| evaluate(&experiment, &topology, g, population))?;
                eval_time += t.elapsed().as_secs_f64();
                let t = Instant::now();
                let summary = evaluated.summary();
                bests.push(summary.stats.best.to_bits());
                population = offspring(&experiment, &evaluated);
                ga_time += t.elapsed().as_secs_f64();
            }
            let total = eval_time + ga_time;
            let gens = args.generations as f64;
            println!(
                "evolution {} on {threads} thread(s): {:.3} generations/s, {:.0} creature-ticks/s, GA share {:.2}%",
                args.evolution.display(),
                gens / total,
                per_generation * gens / total,
                100.0 * ga_time / total
            );
            rates.push((gens / total, bests));
        }
        println!(
            "evolution speed-up 2 vs 1 thread: {:.2}x; best fitness per generation identical: {}",
            rates[1].0 / rates[0].0,
            if rates[0].1 == rates[1].1 {
                "yes"
            } else {
                "NO"
            }
        );
    }
    Ok(())
}
