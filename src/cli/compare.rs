//! `berry-evolve compare`: evaluate several genomes, and random genomes as a baseline, on the
//! same trial worlds of an experiment, so evolved and hand-designed controllers can be compared
//! fairly. By default the worlds are a held-out set that evolution never saw.

use crate::cli::console::outln;

use berry_evolve::brain::genome::Genome;
use berry_evolve::brain::spec::Topology;
use berry_evolve::evo::evaluate::{aggregate, run_trial, Evaluation};
use berry_evolve::evo::init::initial_population;
use berry_evolve::evo::stats::FitnessStats;
use berry_evolve::experiment::Experiment;
use berry_evolve::record::genome_file::GenomeFile;
use berry_evolve::seed::{stream, Generation, IndividualId, Purpose, TrialIndex};
use clap::Args;
use rayon::prelude::*;
use std::path::PathBuf;

/// Generation number whose trial worlds serve as the held-out test set: far beyond any run's
/// length, so no individual was ever selected on them.
pub const HELD_OUT_GENERATION: u64 = 1 << 40;

/// Arguments of `compare`.
#[derive(Debug, Args)]
pub struct CompareArgs {
    /// Genome files to evaluate.
    pub genomes: Vec<PathBuf>,
    /// The experiment whose worlds and fitness to use.
    #[arg(long)]
    pub experiment: PathBuf,
    /// Use this generation's trial worlds (default: a held-out set evolution never saw).
    #[arg(long)]
    pub generation: Option<u64>,
    /// Trials per genome (default: the experiment's).
    #[arg(long)]
    pub trials: Option<u64>,
    /// Random genomes (drawn as the initial population is) to evaluate as a baseline.
    #[arg(long, default_value_t = 32)]
    pub random: u64,
}

fn evaluate(
    experiment: &Experiment,
    topology: &Topology,
    genome: &Genome,
    generation: Generation,
) -> anyhow::Result<Evaluation> {
    let outcomes = (0..experiment.evaluation.trials)
        .map(|t| {
            run_trial(
                experiment,
                topology,
                std::slice::from_ref(genome),
                generation,
                0,
                TrialIndex(t),
            )
            .map(|o| o[0])
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(aggregate(experiment, &outcomes))
}

fn fmt(experiment: &Experiment, e: &Evaluation) -> String {
    let f = e
        .fitness
        .map_or("non-finite".to_string(), |f| format!("{f:.4}"));
    format!(
        "{f}  (A {:.3}, B {:.3}, C {:.3}, D {:.3}){}",
        e.metabolism[0],
        e.metabolism[1],
        e.metabolism[2],
        e.metabolism[3],
        measures_text(experiment, &e.measures)
    )
}

/// A trial's measures (all [`berry_evolve::experiment::MEASURES`] values) as
/// `  measures: distinct_food 3, ticks_alive 500` for the experiment's behaviour measures, or
/// an empty string.
pub fn measure_values_text(experiment: &Experiment, all: &[f64]) -> String {
    let values: Vec<f64> = experiment
        .behaviour
        .measures
        .iter()
        .map(|m| all[m.index()])
        .collect();
    let text = measures_text(experiment, &values);
    if text.is_empty() {
        text
    } else {
        format!("  measures:{text}")
    }
}

/// `  distinct_food 3.5, ticks_alive 500` for the experiment's behaviour measures (mean over
/// trials), or nothing when it names none.
pub fn measures_text(experiment: &Experiment, values: &[f64]) -> String {
    let parts: Vec<String> = experiment
        .behaviour
        .measures
        .iter()
        .zip(values)
        .map(|(m, v)| format!("{} {v:.4}", m.name()))
        .collect();
    if parts.is_empty() {
        String::new()
    } else {
        format!("  {}", parts.join(", "))
    }
}

/// Runs the subcommand.
pub fn run(args: CompareArgs) -> anyhow::Result<()> {
    let mut overrides = Experiment::load(&args.experiment)?.with_overrides();
    if let Some(t) = args.trials {
        overrides = overrides.trials(t);
    }
    // Every genome meets the same worlds: common random numbers, group 0.
    let experiment = overrides.common_random_numbers(true).build()?;
    let generation = Generation(args.generation.unwrap_or(HELD_OUT_GENERATION));
    let worlds = match args.generation {
        None => "the held-out worlds (never used in training or validation)".to_string(),
        Some(g) => format!("generation {g}'s training worlds"),
    };
    outln!(
        "experiment `{}`: {} trials x {} ticks on {worlds}",
        experiment.name,
        experiment.evaluation.trials,
        experiment.evaluation.ticks,
    );
    for path in &args.genomes {
        let file = GenomeFile::load(path)?;
        let topology = file.topology_for(&experiment, path)?;
        let e = evaluate(&experiment, &topology, &file.genome(), generation)?;
        outln!("{}: fitness {}", path.display(), fmt(&experiment, &e));
    }
    if args.random > 0 {
        let topology = experiment.topology();
        let mut rng = stream(
            experiment.seed(),
            Purpose::Baseline,
            generation,
            IndividualId(0),
            TrialIndex(0),
        );
        let mut spec = experiment.evolution.clone();
        spec.population = args.random as usize;
        let genomes = initial_population(&spec, topology.parameter_count(), &mut rng);
        let evaluations = genomes
            .par_iter()
            .map(|g| evaluate(&experiment, &topology, g, generation))
            .collect::<anyhow::Result<Vec<_>>>()?;
        let fitness: Vec<f64> = evaluations.iter().filter_map(|e| e.fitness).collect();
        let stats = FitnessStats::of(&fitness);
        outln!(
            "{} random genomes: fitness mean {:.4}, std {:.4}, best {:.4}, median {:.4}",
            args.random,
            stats.mean,
            stats.std,
            stats.best,
            stats.median
        );
        // Per measure, the random genomes' median and best (largest) value.
        for (k, m) in experiment.behaviour.measures.iter().enumerate() {
            let values: Vec<f64> = evaluations.iter().map(|e| e.measures[k]).collect();
            let s = FitnessStats::of(&values);
            outln!(
                "{} random genomes: {} median {:.4}, best {:.4}",
                args.random,
                m.name(),
                s.median,
                s.best
            );
        }
    }
    Ok(())
}
