//! `berry-evolve summary`: the replicates of one experiment (the `seed-<s>/` run folders that
//! `run --seeds` makes) summed up: `summary.csv` (per generation, quartiles across seeds of
//! best, mean and validation fitness) and `held-out.csv` (each seed's best.json, random
//! genomes and baseline genomes on the held-out worlds `compare` uses; `--worlds validation`
//! writes `validation.csv` from the experiment's validation worlds instead, `--worlds
//! training --generation G` `training-G.csv` from generation G's training worlds).

use crate::cli::compare::{fitness_text, measures_in_order};
use crate::cli::console::outln;
use crate::cli::json::{self, Named};
use crate::cli::worlds::{warn_other_experiment, WorldSet, WorldSetArgs, WorldsChoice};

use anyhow::Context;
use berry_evolve::evo::door::{Evaluate, Worlds};
use berry_evolve::evo::evaluate::Evaluation;
use berry_evolve::evo::worlds::random_genomes;
use berry_evolve::experiment::Experiment;
use berry_evolve::record::genome_file::GenomeFile;
use berry_evolve::record::summary::{
    self, held_out_bytes, quartiles, read_seeds, seed_folders, summary_bytes, HeldOutRow,
    SummaryRow, HELD_OUT_FILE, SUMMARY_FILE,
};
use clap::Args;
use serde::Serialize;
use std::path::{Path, PathBuf};

/// Arguments of `summary`.
#[derive(Debug, Args)]
pub struct SummaryArgs {
    /// The experiment's folder holding `seed-<s>/` run folders, e.g. results/foraging/.
    pub folder: PathBuf,
    /// The experiment whose held-out worlds and fitness to use (default: the lowest seed's
    /// experiment.toml; every genome meets the same worlds).
    #[arg(long)]
    pub experiment: Option<PathBuf>,
    /// Held-out trials per genome (default: the experiment's; with `--worlds validation`, the
    /// first N validation worlds, default its [validation] trials).
    #[arg(long)]
    pub trials: Option<u64>,
    /// Whose worlds the genomes meet (default: held-out, written to held-out.csv;
    /// validation: validation.csv; training, those of --generation: training-G.csv).
    #[arg(long, value_enum, conflicts_with = "no_held_out")]
    pub worlds: Option<WorldsChoice>,
    /// With `--worlds training`: whose training worlds (default: 0).
    #[arg(long, conflicts_with = "no_held_out")]
    pub generation: Option<u64>,
    /// Random genomes (drawn as compare draws them) whose median and best go in held-out.csv.
    #[arg(long, default_value_t = 64)]
    pub random: u64,
    /// A baseline genome file (e.g. a hand-designed controller) to evaluate too; repeatable.
    #[arg(long)]
    pub baseline: Vec<PathBuf>,
    /// Write only summary.csv (no held-out evaluation).
    #[arg(long)]
    pub no_held_out: bool,
    /// Print one JSON document (schema `berry-evolve/summary/1`) instead of text: the seeds,
    /// summary.csv's last line, and every line of held-out.csv with its measures by name.
    #[arg(long)]
    pub json: bool,
}

/// Quartiles of a set of values.
#[derive(Debug, Serialize)]
pub struct Quartiles {
    /// First quartile.
    pub q1: f64,
    /// Median.
    pub median: f64,
    /// Third quartile.
    pub q3: f64,
}

/// One line of held-out.csv, as `summary --json` reports it.
#[derive(Debug, Serialize)]
pub struct HeldOutEntry {
    /// What it is: `seed`, `random_median`, `random_best`, `baseline`.
    pub who: String,
    /// The seed (for `seed` entries).
    pub seed: Option<u64>,
    /// The genome file, when there is one.
    pub genome: Option<String>,
    /// The held-out fitness (`null`: non-finite).
    pub fitness: Option<f64>,
    /// The behaviour measures, by name.
    pub measures: Named<f64>,
}

/// The held-out part of the summary.
#[derive(Debug, Serialize)]
pub struct HeldOutReport {
    /// The file written.
    pub held_out_csv: String,
    /// The named set when not the held-out worlds (`validation`, `training`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub worlds: Option<&'static str>,
    /// With `training`: the generation whose worlds.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub generation: Option<u64>,
    /// The set, resolved.
    #[serde(skip)]
    pub set: WorldSet,
    /// Held-out trials per genome.
    pub trials: u64,
    /// Seeds whose folder has no best.json yet (left out).
    pub without_best: Vec<u64>,
    /// Quartiles over the seeds of their best.json's held-out fitness (finite ones).
    pub seed_fitness: Option<Quartiles>,
    /// How many seeds' fitness the quartiles are over.
    pub seeds_with_fitness: usize,
    /// Every line of held-out.csv, in its order.
    pub rows: Vec<HeldOutEntry>,
}

/// What `summary` prints (as text, or as JSON with `--json`).
#[derive(Debug, Serialize)]
pub struct SummaryReport {
    /// `berry-evolve/summary/1`.
    pub schema: &'static str,
    /// The experiment's folder summed up.
    pub folder: String,
    /// The seeds found (`seed-<s>/` folders), in increasing order.
    pub seeds: Vec<u64>,
    /// Generations in summary.csv.
    pub generations: usize,
    /// The file written.
    pub summary_csv: String,
    /// summary.csv's last line (quartiles across seeds of the last generation).
    pub last_generation: Option<SummaryRow>,
    /// The held-out evaluation (absent with `--no-held-out`).
    pub held_out: Option<HeldOutReport>,
}

impl SummaryReport {
    /// Prints the report as the text lines `summary` has always printed.
    fn print_text(&self) {
        outln!(
            "{} seeds, {} generations: {}",
            self.seeds.len(),
            self.generations,
            self.summary_csv
        );
        if let Some(last) = &self.last_generation {
            outln!(
                "generation {}: best median {:.4} (quartiles {:.4}–{:.4}), mean median {:.4}",
                last.generation,
                last.best_median,
                last.best_q1,
                last.best_q3,
                last.mean_median
            );
        }
        let Some(h) = &self.held_out else {
            return;
        };
        for seed in &h.without_best {
            outln!("seed {seed}: no best.json yet (left out of held-out.csv)");
        }
        let which = match h.set {
            WorldSet::Training(g) => format!("generation {g}"),
            set => set.name().to_string(),
        };
        if let Some(q) = &h.seed_fitness {
            outln!(
                "{which} fitness over {} seeds ({} trials): median {:.4} (quartiles {:.4}–{:.4})",
                h.seeds_with_fitness,
                h.trials,
                q.median,
                q.q1,
                q.q3
            );
        }
        for r in h.rows.iter().filter(|r| r.who != "seed") {
            let f = fitness_text(r.fitness);
            let name = r.genome.as_deref().unwrap_or(&r.who);
            outln!("{name}: {which} fitness {f}");
        }
        outln!("{}", h.held_out_csv);
    }
}

/// Runs the subcommand.
pub fn run(args: SummaryArgs) -> anyhow::Result<()> {
    let report = summarize(&args)?;
    if args.json {
        json::print(&report)
    } else {
        report.print_text();
        Ok(())
    }
}

/// Writes summary.csv (and held-out.csv) and gathers what to report.
fn summarize(args: &SummaryArgs) -> anyhow::Result<SummaryReport> {
    let seeds = read_seeds(&args.folder)?;
    // The worlds and the experiment are checked before any file is written.
    let set = WorldSet::choose(args.worlds, args.generation, WorldsChoice::HeldOut, 0)?;
    let experiment = if args.no_held_out {
        None
    } else {
        Some(held_out_experiment(args, set)?)
    };
    let tables: Vec<_> = seeds.iter().map(|(_, t)| t.clone()).collect();
    let rows = summary::summarize(&tables);
    let path = args.folder.join(SUMMARY_FILE);
    summary::write(&path, &summary_bytes(&rows)?)?;
    let held_out = experiment
        .map(|(experiment_path, experiment)| held_out(args, set, &experiment_path, &experiment))
        .transpose()?;
    Ok(SummaryReport {
        schema: "berry-evolve/summary/1",
        folder: args.folder.display().to_string(),
        seeds: seeds.iter().map(|(s, _)| *s).collect(),
        generations: rows.len(),
        summary_csv: path.display().to_string(),
        last_generation: rows.last().copied(),
        held_out,
    })
}

/// The experiment whose worlds the genomes meet (`--experiment`, or the lowest seed's), with
/// `--trials` and common random numbers (every genome meets the same worlds, as in compare),
/// and its file; refuses a set it has not.
fn held_out_experiment(args: &SummaryArgs, set: WorldSet) -> anyhow::Result<(PathBuf, Experiment)> {
    let folders = seed_folders(&args.folder)?;
    let experiment_path = match &args.experiment {
        Some(p) => p.clone(),
        None => folders[0].1.join(berry_evolve::run::EXPERIMENT_FILE),
    };
    let mut experiment = Experiment::load(&experiment_path)?;
    set.check_file(&experiment, &experiment_path)?;
    if let Some(t) = args.trials {
        experiment = set.with_trials(&experiment, t)?;
    }
    let experiment = experiment
        .with_overrides()
        .common_random_numbers(true)
        .build()?;
    Ok((experiment_path, experiment))
}

/// Evaluates each seed's best.json, random genomes and the baselines on the held-out worlds
/// (or `set`'s) of `experiment` and writes held-out.csv (validation.csv, training-G.csv).
fn held_out(
    args: &SummaryArgs,
    set: WorldSet,
    experiment_path: &Path,
    experiment: &Experiment,
) -> anyhow::Result<HeldOutReport> {
    let folders = seed_folders(&args.folder)?;
    let generation = set.generation();
    // The worlds compare uses: the validation worlds, or group 0 of the generation, one
    // creature each.
    let worlds = set.build(experiment)?;
    let evaluate_file = |path: &PathBuf| -> anyhow::Result<Evaluation> {
        let file = GenomeFile::load(path)?;
        let topology = file.topology_for(experiment, path)?;
        warn_other_experiment(&file, path, experiment, experiment_path);
        let genome = [file.genome()];
        let request = Evaluate::new(experiment, &topology, &genome, Worlds::Built(&worlds));
        Ok(request.run()?.remove(0))
    };
    let mut out = Vec::new();
    let mut without_best = Vec::new();
    for (seed, dir) in &folders {
        let best = dir.join(berry_evolve::run::BEST_FILE);
        if !best.is_file() {
            without_best.push(*seed);
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
        let genomes = random_genomes(experiment, generation, args.random as usize);
        let evaluations =
            Evaluate::new(experiment, &topology, &genomes, Worlds::Built(&worlds)).run()?;
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
    let file = match set {
        WorldSet::HeldOut => HELD_OUT_FILE.to_string(),
        WorldSet::Validation => "validation.csv".to_string(),
        WorldSet::Design => "design.csv".to_string(),
        WorldSet::Training(g) => format!("training-{g}.csv"),
    };
    let path = args.folder.join(file);
    summary::write(&path, &held_out_bytes(&names, &out)?)?;
    Ok(HeldOutReport {
        held_out_csv: path.display().to_string(),
        worlds: (set != WorldSet::HeldOut).then(|| set.name()),
        generation: match set {
            WorldSet::Training(g) => Some(g),
            _ => None,
        },
        set,
        trials: worlds.worlds.len() as u64,
        without_best,
        seed_fitness: quartiles(&seed_fitness).map(|q| Quartiles {
            q1: q[0],
            median: q[1],
            q3: q[2],
        }),
        seeds_with_fitness: seed_fitness.len(),
        rows: out
            .into_iter()
            .map(|r| HeldOutEntry {
                measures: measures_in_order(experiment, &r.measures),
                who: r.who,
                seed: r.seed,
                genome: r.genome,
                fitness: r.fitness,
            })
            .collect(),
    })
}
