//! `berry-evolve inspect`: what an experiment file means, so a user can see which input is
//! which before running it.

use anyhow::Context;
use berry_evolve::experiment::Experiment;
use clap::Args;
use std::fmt::Write as _;
use std::io::Write as _;
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
    let mut out = String::new();
    writeln!(
        out,
        "experiment `{}`, seed {}",
        experiment.name, experiment.seed
    )?;
    writeln!(out, "config hash {}", experiment.config_hash())?;
    writeln!(out, "observation: {} inputs", layout.len())?;
    for (group, range) in layout.groups() {
        writeln!(out, "  {group:?}: inputs {}..{}", range.start, range.end)?;
        for i in range.clone() {
            writeln!(out, "    [{i:>3}] {}", layout.names()[i])?;
        }
    }
    writeln!(out, "outputs: {}", experiment.output_names().join(", "))?;
    writeln!(
        out,
        "brain: {:?}, {} parameters",
        experiment.brain,
        topology.parameter_count()
    )?;
    let e = &experiment.evaluation;
    let per_generation = experiment.evolution.population as u64 * e.trials * e.ticks;
    writeln!(out,
        "workload: {} generations x {} individuals x {} trials x {} ticks = {} creature-ticks per generation",
        experiment.evolution.generations,
        experiment.evolution.population,
        e.trials,
        e.ticks,
        per_generation
    )?;
    // One write, so a closed pipe (`| head`) is a single error that main treats as done.
    std::io::stdout()
        .write_all(out.as_bytes())
        .context("cannot write to standard output")?;
    Ok(())
}
