//! `berry-evolve summary`: the replicates of one experiment (the `seed-<s>/` run folders that
//! `run --seeds` makes) summed up: `summary.csv` (per generation, quartiles across seeds of
//! best, mean and validation fitness) and `held-out.csv` (each seed's best.json, random
//! genomes and baseline genomes on the held-out worlds `compare` uses).

use crate::cli::compare::HELD_OUT_GENERATION;
use crate::cli::console::outln;

use anyhow::Context;
use berry_evolve::brain::genome::Genome;
use berry_evolve::evo::evaluate::{evaluate_in_worlds, worlds_from, Evaluation};
use berry_evolve::evo::init::initial_population;
use berry_evolve::evo::life::trial_stream;
use berry_evolve::experiment::Experiment;
use berry_evolve::record::genome_file::GenomeFile;
use berry_evolve::record::summary::{
    self, held_out_bytes, quartiles, read_seeds, seed_folders, summary_bytes, HeldOutRow,
    HELD_OUT_FILE, SUMMARY_FILE,
};
use berry_evolve::seed::{stream, Generation, IndividualId, Purpose, TrialIndex};
use clap::Args;
use std::path::PathBuf;

/// Arguments of `summary`.
#[derive(Debug, Args)]
pub struct SummaryArgs {
    /// The experiment's folder holding `seed-<s>/` run folders, e.g. results/foraging/.
    pub folder: PathBuf,
    /// The experiment whose held-out worlds and fitness to use (default: the lowest seed's
    /// experiment.toml; every genome meets the same worlds).
    #[arg(long)]
    pub experiment: Option<PathBuf>,
    /// Held-out trials per genome (default: the experiment's).
    #[arg(long)]
    pub trials: Option<u64>,
    /// Random genomes (drawn as compare draws them) whose median and best go in held-out.csv.
    #[arg(long, default_value_t = 64)]
    pub random: u64,
    /// A baseline genome file (e.g. a hand-designed controller) to evaluate too; repeatable.
    #[arg(long)]
    pub baseline: Vec<PathBuf>,
    /// Write only summary.csv (no held-out evaluation).
    #[arg(long)]
    pub no_held_out: bool,
}

/// Runs the subcommand.
pub fn run(args: SummaryArgs) -> anyhow::Result<()> {
    let seeds = read_seeds(&args.folder)?;
    let tables: Vec<_> = seeds.iter().map(|(_, t)| t.clone()).collect();
    let rows = summary::summarize(&tables);
    let path = args.folder.join(SUMMARY_FILE);
    summary::write(&path, &summary_bytes(&rows)?)?;
    outln!(
        "{} seeds, {} generations: {}",
        seeds.len(),
        rows.len(),
        path.display()
    );
    if let Some(last) = rows.last() {
        outln!(
            "generation {}: best median {:.4} (quartiles {:.4}–{:.4}), mean median {:.4}",
            last.generation,
            last.best_median,
            last.best_q1,
            last.best_q3,
            last.mean_median
        );
    }
    if args.no_held_out {
        return Ok(());
    }
    let folders = seed_folders(&args.folder)?;
    let experiment_path = match &args.experiment {
        Some(p) => p.clone(),
        None => folders[0].1.join(berry_evolve::run::EXPERIMENT_FILE),
    };
    let mut overrides = Experiment::load(&experiment_path)?.with_overrides();
    if let Some(t) = args.trials {
        overrides = overrides.trials(t);
    }
    // Every genome meets the same worlds, as in compare.
    let experiment = overrides.common_random_numbers(true).build()?;
    let generation = Generation(HELD_OUT_GENERATION);
    // The worlds compare uses: group 0 of the held-out generation, one creature each.
    let worlds = worlds_from(&experiment, experiment.evaluation.trials, generation, |t| {
        trial_stream(&experiment, generation, 0, t)
    })?;
    let evaluate_file = |path: &PathBuf| -> anyhow::Result<Evaluation> {
        let file = GenomeFile::load(path)?;
        let topology = file.topology_for(&experiment, path)?;
        Ok(evaluate_in_worlds(&experiment, &topology, &[file.genome()], &worlds)?.remove(0))
    };
    let mut out = Vec::new();
    for (seed, dir) in &folders {
        let best = dir.join(berry_evolve::run::BEST_FILE);
        if !best.is_file() {
            outln!("seed {seed}: no best.json yet (left out of held-out.csv)");
            continue;
        }
        let e = evaluate_file(&best).with_context(|| format!("seed {seed}"))?;
        out.push(HeldOutRow {
            who: "seed".into(),
            seed: Some(*seed),
            genome: Some(best.display().to_string()),
            fitness: e.fitness,
            measures: e.measures,
        });
    }
    let seed_fitness: Vec<f64> = out.iter().filter_map(|r| r.fitness).collect();
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
        let genomes: Vec<Genome> = initial_population(&spec, topology.parameter_count(), &mut rng);
        let evaluations = evaluate_in_worlds(&experiment, &topology, &genomes, &worlds)?;
        let fitness: Vec<f64> = evaluations.iter().filter_map(|e| e.fitness).collect();
        let measure =
            |k: usize| -> Vec<f64> { evaluations.iter().map(|e| e.measures[k]).collect() };
        let count = experiment.behaviour.measures.len();
        let median = |v: &[f64]| quartiles(v).map(|q| q[1]);
        let best = |v: &[f64]| v.iter().copied().reduce(f64::max);
        out.push(HeldOutRow {
            who: "random_median".into(),
            seed: None,
            genome: None,
            fitness: median(&fitness),
            measures: (0..count)
                .map(|k| median(&measure(k)).unwrap_or(0.0))
                .collect(),
        });
        out.push(HeldOutRow {
            who: "random_best".into(),
            seed: None,
            genome: None,
            fitness: best(&fitness),
            measures: (0..count)
                .map(|k| best(&measure(k)).unwrap_or(0.0))
                .collect(),
        });
    }
    for path in &args.baseline {
        let e = evaluate_file(path).with_context(|| format!("baseline {}", path.display()))?;
        out.push(HeldOutRow {
            who: "baseline".into(),
            seed: None,
            genome: Some(path.display().to_string()),
            fitness: e.fitness,
            measures: e.measures,
        });
    }
    let names: Vec<String> = experiment
        .behaviour
        .measures
        .iter()
        .map(|m| m.name().to_string())
        .collect();
    let path = args.folder.join(HELD_OUT_FILE);
    summary::write(&path, &held_out_bytes(&names, &out)?)?;
    if let Some(q) = quartiles(&seed_fitness) {
        outln!(
            "held-out fitness over {} seeds ({} trials): median {:.4} (quartiles {:.4}–{:.4})",
            seed_fitness.len(),
            experiment.evaluation.trials,
            q[1],
            q[0],
            q[2]
        );
    }
    for r in out.iter().filter(|r| r.who != "seed") {
        let f = r
            .fitness
            .map_or("non-finite".to_string(), |f| format!("{f:.4}"));
        let name = r.genome.as_deref().unwrap_or(&r.who);
        outln!("{name}: held-out fitness {f}");
    }
    outln!("{}", path.display());
    Ok(())
}
