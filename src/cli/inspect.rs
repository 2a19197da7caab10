//! `berry-evolve inspect`: what an experiment file means, in plain words, so a user can see
//! which input is which, how big the brain is and how long a run will take before running
//! it; `--json` gives the same numbers as one JSON document.

use crate::cli::estimate::{self, count};
use anyhow::Context;
use berry_evolve::brain::summary::BrainSummary;
use berry_evolve::evo::search;
use berry_evolve::experiment::tables::{Balance, FitnessMode, FitnessSpec};
use berry_evolve::experiment::terms::{Sign, TERMS};
use berry_evolve::experiment::{Experiment, ExperimentError};
use berry_evolve::run::estimate::{Estimate, Workload};
use berry_evolve::validate::InvalidValue;
use clap::Args;
use serde::Serialize;
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::PathBuf;

/// Arguments of `inspect`.
#[derive(Debug, Args)]
pub struct InspectArgs {
    /// The experiment file.
    pub file: PathBuf,
    /// Worker threads to estimate the wall time for, 1 to 1024 (default: one per core, as
    /// `run` uses).
    #[arg(long, value_parser = super::run::parse_jobs)]
    pub jobs: Option<usize>,
    /// Skip the timing calibration (a fraction of a second) and the estimated wall time;
    /// the workload is still counted.
    #[arg(long)]
    pub no_estimate: bool,
    /// Print one JSON document (`"schema": "berry-evolve/inspect/1"`) with the same numbers
    /// on stdout instead of the text.
    #[arg(long)]
    pub json: bool,
}

/// `inspect --json`: everything the text says, as numbers.
#[derive(Debug, Serialize)]
struct Report<'a> {
    schema: &'static str,
    file: String,
    experiment: &'a str,
    seed: u64,
    config_hash: String,
    algorithm: &'static str,
    observation: Vec<Group>,
    inputs: usize,
    outputs: Vec<String>,
    brain: BrainJson,
    /// `[fitness]` in plain words, as the text's `fitness:` line.
    fitness: String,
    /// `[behaviour] measures`, by name.
    behaviour_measures: Vec<&'static str>,
    /// How `best.json` is chosen, as the text's `champion:` line.
    champion: String,
    /// What would make a run a dead end (e.g. nothing in the world can change the
    /// fitness), as the text's `warning:` lines; empty when nothing does.
    warnings: Vec<String>,
    workload: Workload,
    /// `null` with `--no-estimate`, or when the calibration could not run.
    estimate: Option<EstimateJson>,
}

/// One sensor group of the observation.
#[derive(Debug, Serialize)]
struct Group {
    group: serde_json::Value,
    label: &'static str,
    /// First input index.
    first: usize,
    /// One past the last input index.
    end: usize,
    names: Vec<String>,
}

/// The brain's numbers and its line of text.
#[derive(Debug, Serialize)]
struct BrainJson {
    #[serde(flatten)]
    summary: BrainSummary,
    description: String,
}

/// The estimate without the workload (given beside it).
#[derive(Debug, Serialize)]
struct EstimateJson {
    total_seconds: f64,
    seconds_per_generation: f64,
    validation_seconds: f64,
    creature_ticks_per_second: f64,
    calibration: berry_evolve::run::estimate::Calibration,
}

/// Runs the subcommand.
pub fn run(args: InspectArgs) -> anyhow::Result<()> {
    let experiment = Experiment::load(&args.file)?;
    // A world that cannot be built would stop `run` before it starts: say so here.
    berry_evolve::run::check_worlds(&experiment).map_err(|error| ExperimentError::Invalid {
        path: args.file.clone(),
        error: InvalidValue::new(
            "world",
            format!("{error}; `run` refuses this file until it is fixed"),
        ),
    })?;
    let workload = Workload::of(&experiment, 0..experiment.evolution.generations);
    let estimate = if args.no_estimate {
        None
    } else {
        estimate::estimate(
            &experiment,
            args.jobs.unwrap_or(0),
            0..experiment.evolution.generations,
            berry_evolve::run::estimate::CALIBRATION_TARGET,
        )
    };
    let out = if args.json {
        let mut text =
            serde_json::to_string_pretty(&report(&args, &experiment, workload, estimate.as_ref()))?;
        text.push('\n');
        text
    } else {
        text(&experiment, &workload, estimate.as_ref(), args.no_estimate)?
    };
    // One write, so a closed pipe (`| head`) is a single error that main treats as done.
    std::io::stdout()
        .write_all(out.as_bytes())
        .context("cannot write to standard output")?;
    Ok(())
}

/// The algorithm in words.
fn algorithm(experiment: &Experiment) -> &'static str {
    search::factory::of(experiment, &experiment.topology()).describe()
}

/// The text output.
fn text(
    experiment: &Experiment,
    workload: &Workload,
    estimate: Option<&Estimate>,
    skipped: bool,
) -> anyhow::Result<String> {
    let layout = experiment.layout();
    let mut out = String::new();
    writeln!(
        out,
        "experiment `{}`, seed {}, config hash {}",
        experiment.name,
        experiment.seed,
        experiment.config_hash()
    )?;
    writeln!(out, "observation: {} inputs", layout.len())?;
    for (group, range) in layout.groups() {
        let inputs = match range.len() {
            1 => format!("input {}", range.start),
            _ => format!("inputs {} to {}", range.start, range.end - 1),
        };
        writeln!(out, "  {}: {inputs}", group.label())?;
        for i in range.clone() {
            writeln!(out, "    [{i:>3}] {}", layout.names()[i])?;
        }
    }
    writeln!(out, "outputs: {}", experiment.output_names().join(", "))?;
    writeln!(out, "brain: {}", experiment.topology().summary())?;
    writeln!(out, "fitness: {}", fitness_words(&experiment.fitness))?;
    for warning in warnings(experiment) {
        writeln!(out, "  {warning}")?;
    }
    writeln!(
        out,
        "behaviour measures: {}",
        match measure_names(experiment).as_slice() {
            [] => "none ([behaviour] measures)".to_string(),
            names => names.join(", "),
        }
    )?;
    writeln!(out, "champion: {}", champion_words(experiment))?;
    writeln!(
        out,
        "evolution: {}, {} generations of {} individuals{}",
        algorithm(experiment),
        count(experiment.evolution.generations),
        count(experiment.evolution.population as u64),
        if experiment.evolution.draw_order == 1 {
            ""
        } else {
            ", draw order 2 (offspring in parallel, fewer draws per gene)"
        }
    )?;
    if let Some(hint) = draw_order_hint(experiment) {
        writeln!(out, "  {hint}")?;
    }
    for line in estimate::workload_lines(workload) {
        writeln!(out, "{line}")?;
    }
    match estimate {
        Some(e) => {
            for line in estimate::time_lines(e) {
                writeln!(out, "{line}")?;
            }
            if e.total_seconds > estimate::LONG_RUN_SECONDS {
                writeln!(
                    out,
                    "  above an hour: `run` will warn before it starts; --generations N, or \
                     fewer evolution.population, evaluation.trials or evaluation.ticks, make \
                     it shorter"
                )?;
            }
        }
        None if skipped => writeln!(out, "estimated wall time: not measured (--no-estimate)")?,
        None => writeln!(
            out,
            "estimated wall time: not measured (see the note on stderr)"
        )?,
    }
    Ok(out)
}

/// The `--json` document.
fn report<'a>(
    args: &InspectArgs,
    experiment: &'a Experiment,
    workload: Workload,
    estimate: Option<&Estimate>,
) -> Report<'a> {
    let layout = experiment.layout();
    let summary = experiment.topology().summary();
    Report {
        schema: "berry-evolve/inspect/1",
        file: args.file.display().to_string(),
        experiment: &experiment.name,
        seed: experiment.seed,
        config_hash: experiment.config_hash(),
        algorithm: search::factory::of(experiment, &experiment.topology()).name(),
        observation: layout
            .groups()
            .iter()
            .map(|(group, range)| Group {
                group: serde_json::to_value(group).unwrap_or_default(),
                label: group.label(),
                first: range.start,
                end: range.end,
                names: layout.names()[range.clone()].to_vec(),
            })
            .collect(),
        inputs: layout.len(),
        outputs: experiment.output_names(),
        brain: BrainJson {
            description: summary.to_string(),
            summary,
        },
        fitness: fitness_words(&experiment.fitness),
        behaviour_measures: measure_names(experiment),
        champion: champion_words(experiment),
        warnings: warnings(experiment)
            .into_iter()
            .chain(draw_order_hint(experiment))
            .collect(),
        workload,
        estimate: estimate.map(|e| EstimateJson {
            total_seconds: e.total_seconds,
            seconds_per_generation: e.seconds_per_generation,
            validation_seconds: e.validation_seconds,
            creature_ticks_per_second: e.calibration.rate(),
            calibration: e.calibration,
        }),
    }
}

/// `[fitness]` in plain words: the metabolic gain, then every term that is not zero, e.g.
/// `A + B of the metabolism summed over every tick of life, + 0.005 × LU driven forward`.
fn fitness_words(f: &FitnessSpec) -> String {
    let parts: Vec<String> = f
        .weights
        .iter()
        .zip(["A", "B", "C", "D"])
        .filter(|(w, _)| **w != 0.0)
        .map(|(w, name)| match *w {
            1.0 => name.to_string(),
            _ => format!("{w} × {name}"),
        })
        .collect();
    let components = match (parts.is_empty(), f.balance) {
        (true, _) => "0".to_string(),
        (false, Balance::Sum) => parts.join(" + "),
        (false, Balance::Min) => format!("the smallest of {}", parts.join(", ")),
    };
    let mut words = format!(
        "{components} of the metabolism {}",
        match f.mode {
            FitnessMode::Final => "at the end of life",
            FitnessMode::Integrated => "summed over every tick of life",
        }
    );
    if f.imbalance_penalty != 0.0 {
        write!(words, ", − {} × (largest − smallest)", f.imbalance_penalty).ok();
    }
    for term in TERMS.iter().filter(|t| t.sign == Sign::Add) {
        let weight = (term.weight)(f);
        if weight != 0.0 {
            write!(words, ", + {weight} {}", (term.words)(f)).ok();
        }
    }
    if f.shock_penalty != 0.0 {
        write!(words, ", − {} × shocked tick", f.shock_penalty).ok();
    }
    for term in TERMS.iter().filter(|t| t.sign == Sign::Subtract) {
        let weight = (term.weight)(f);
        if weight != 0.0 {
            write!(words, ", − {weight} {}", (term.words)(f)).ok();
        }
    }
    words
}

/// The dead ends a run of `experiment` would meet (`run` warns of them as it starts).
fn warnings(experiment: &Experiment) -> Vec<String> {
    super::run::constant_fitness_warning(experiment)
        .into_iter()
        .collect()
}

/// Brains this large make draw order 1's search a few percent of a generation.
const LARGE_BRAIN_PARAMETERS: usize = 2_000;

/// For a large brain in draw order 1: that draw order 2 makes the search cheaper.
fn draw_order_hint(experiment: &Experiment) -> Option<String> {
    let parameters = experiment.topology().parameter_count();
    (experiment.evolution.draw_order == 1 && parameters >= LARGE_BRAIN_PARAMETERS).then(|| {
        format!(
            "note: a brain of {} parameters; in draw order 1 the search draws its numbers \
             one after another from one stream (3-6% of a generation at 15,000 parameters); \
             `[evolution] draw_order = 2` draws fewer per gene and each individual in \
             parallel (about 1.5%), a different run from the same seed (docs/search.md, \
             \"Draw order 2\")",
            count(parameters as u64)
        )
    })
}

/// The behaviour measures' names.
fn measure_names(experiment: &Experiment) -> Vec<&'static str> {
    experiment
        .behaviour
        .measures
        .iter()
        .map(|m| m.name())
        .collect()
}

/// How `best.json` is chosen.
fn champion_words(experiment: &Experiment) -> String {
    let v = &experiment.validation;
    if v.enabled() {
        format!(
            "the best on {} validation worlds of each generation's top {}, every {} \
             generations and after the last",
            v.trials, v.top, v.every
        )
    } else {
        "the best training evaluation of the run (no [validation]: the luckiest, not \
         necessarily the best on new worlds)"
            .to_string()
    }
}
