//! `berry-evolve simulate`: scripted creatures (the experiment's `[demo]` table) in the
//! experiment's world, with an optional per-tick trace CSV.

use crate::cli::console::{errln, outln};

use anyhow::Context;
use berry_evolve::experiment::Experiment;
use berry_evolve::record::trace::TraceWriter;
use berry_evolve::seed::{stream, Generation, IndividualId, Purpose, TrialIndex};
use berry_evolve::sim::world::World;
use clap::Args;
use std::path::PathBuf;

/// Arguments of `simulate`.
#[derive(Debug, Args)]
pub struct SimulateArgs {
    /// An experiment file; its [world], [creature] and [demo] tables are used.
    pub file: PathBuf,
    /// Ticks to simulate (fewer when every creature dies first: the simulation stops after
    /// the tick in which the last one died, as a scored trial and `replay --trace` do).
    #[arg(long, default_value_t = 1000)]
    pub ticks: u64,
    /// Write the per-tick trace CSV here: a row per creature per tick, dead ones included
    /// with alive = 0, up to the tick in which the last creature died.
    #[arg(long)]
    pub trace: Option<PathBuf>,
    /// Override the experiment's seed (the world is drawn from it).
    #[arg(long)]
    pub seed: Option<u64>,
}

/// Runs the subcommand.
pub fn run(args: SimulateArgs) -> anyhow::Result<()> {
    if let Some(trace) = &args.trace {
        berry_evolve::record::atomic::refuse_output_over_input("--trace", trace, &[&args.file])?;
    }
    let mut experiment = Experiment::load(&args.file)?;
    if let Some(seed) = args.seed {
        experiment = experiment
            .with_overrides()
            .seed(seed)
            .build()
            .with_context(|| format!("--seed {seed}"))?;
    }
    anyhow::ensure!(
        args.ticks <= berry_evolve::experiment::tables::MAX_TICKS,
        "--ticks {}: at most {} ticks",
        args.ticks,
        berry_evolve::experiment::tables::MAX_TICKS
    );
    let layout = experiment.layout();
    let demo = &experiment.demo;
    let mut controllers = (0..demo.creatures)
        .map(|_| demo.controller.build(&layout))
        .collect::<Result<Vec<_>, _>>()
        .with_context(|| format!("{}: [demo]", args.file.display()))?;
    let rng = stream(
        experiment.seed(),
        Purpose::Demo,
        Generation(0),
        IndividualId(0),
        TrialIndex(0),
    );
    let mut world = World::new(&experiment.world, &experiment.creature, demo.creatures, rng)
        .with_context(|| format!("{}: cannot build the world", args.file.display()))?;
    let mut trace = match &args.trace {
        // Atomic: until the trace is complete, an earlier trace file keeps its content.
        Some(path) => Some(TraceWriter::new(
            berry_evolve::record::atomic::AtomicFile::create(path)
                .with_context(|| format!("cannot create {}", path.display()))?,
        )),
        None => None,
    };
    let mut all_dead = false;
    for _ in 0..args.ticks {
        world.step(&mut controllers);
        if let Some(t) = &mut trace {
            t.write_tick(&world)?;
        }
        // The rule of a scored trial (`evo::trial::live`, which `replay --trace` records):
        // the life ends after the first tick no creature lived through, so both traces end
        // on the tick whose rows say alive = 0 for everyone.
        if !world.creatures().iter().any(|c| c.alive) {
            all_dead = true;
            break;
        }
    }
    if let (Some(t), Some(path)) = (trace, &args.trace) {
        t.into_inner()
            .map_err(anyhow::Error::from)
            .and_then(|f| f.commit().map_err(anyhow::Error::from))
            .with_context(|| format!("cannot write {}", path.display()))?;
    }
    for (i, c) in world.creatures().iter().enumerate() {
        outln!(
            "creature {i}: position ({:.2}, {:.2}), travelled {:.1} LU, eaten {:?}, metabolism {:?}{}",
            c.pose.position.x,
            c.pose.position.y,
            c.travelled,
            c.eaten,
            c.metabolism,
            if c.alive { "" } else { ", dead" }
        );
    }
    if all_dead {
        errln!(
            "every creature was dead after tick {} of {}: the simulation stopped there, as a scored trial does",
            world.tick(),
            args.ticks
        );
    }
    if let Some(path) = &args.trace {
        errln!("trace written to {}", path.display());
    }
    Ok(())
}
