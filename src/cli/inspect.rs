//! `berry-evolve inspect`: what an experiment file means, so a user can see which input is
//! which before running it.

use berry_evolve::experiment::Experiment;
use clap::Args;
use std::path::PathBuf;

/// Arguments of `inspect`.
#[derive(Debug, Args)]
pub struct InspectArgs {
    /// The experiment file.
    pub file: PathBuf,
}

/// Runs the subcommand.
pub fn run(args: InspectArgs) -> anyhow::Result<()> {
    let experiment = Experiment::load(&args.file)?;
    let layout = experiment.layout();
    let topology = experiment.topology();
    println!("experiment `{}`, seed {}", experiment.name, experiment.seed);
    println!("config hash {}", experiment.config_hash());
    println!("observation: {} inputs", layout.len());
    for (group, range) in layout.groups() {
        println!("  {group:?}: inputs {}..{}", range.start, range.end);
        for i in range.clone() {
            println!("    [{i:>3}] {}", layout.names()[i]);
        }
    }
    println!("outputs: {}", experiment.output_names().join(", "));
    println!(
        "brain: {:?}, {} parameters",
        experiment.brain,
        topology.parameter_count()
    );
    let e = &experiment.evaluation;
    let per_generation = experiment.evolution.population as u64 * e.trials * e.ticks;
    println!(
        "workload: {} generations x {} individuals x {} trials x {} ticks = {} creature-ticks per generation",
        experiment.evolution.generations,
        experiment.evolution.population,
        e.trials,
        e.ticks,
        per_generation
    );
    Ok(())
}
