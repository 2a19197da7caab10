//! `berry-evolve compare`: evaluate several genomes, and random genomes as a baseline, on the
//! same trial worlds of an experiment, so evolved and hand-designed controllers can be compared
//! fairly. By default the worlds are a held-out set that evolution never saw; `--worlds`
//! names another set (the experiment's validation worlds, or a generation's training worlds).

use crate::cli::console::outln;
use crate::cli::json::{self, finite, Named};
use crate::cli::worlds::{
    experiment_file, warn_other_experiment, WorldSet, WorldSetArgs, WorldsChoice,
};

use anyhow::Context;
use berry_evolve::evo::door::{self, Evaluate};
use berry_evolve::evo::evaluate::aggregate;
use berry_evolve::evo::life::TrialOutcome;
use berry_evolve::evo::stats::FitnessStats;
use berry_evolve::evo::worlds::{self, alone};
use berry_evolve::experiment::{Aggregate, Experiment, Measure, MEASURES};
use berry_evolve::record::genome_file::GenomeFile;
use clap::Args;
use serde::Serialize;
use std::path::PathBuf;

/// Arguments of `compare`.
#[derive(Debug, Args)]
pub struct CompareArgs {
    /// Genome files to evaluate.
    pub genomes: Vec<PathBuf>,
    /// The experiment whose worlds and fitness to use (default: the experiment.toml beside
    /// the genome files, as in a run folder).
    #[arg(long)]
    pub experiment: Option<PathBuf>,
    /// Whose worlds (default: held-out; training: those of --generation, default 0).
    #[arg(long, value_enum)]
    pub worlds: Option<WorldsChoice>,
    /// Use this generation's training worlds (as `--worlds training --generation G`).
    #[arg(long)]
    pub generation: Option<u64>,
    /// Trials per genome (default: the experiment's; with `--worlds validation`, the first N
    /// validation worlds, default its [validation] trials).
    #[arg(long)]
    pub trials: Option<u64>,
    /// Random genomes (drawn as the initial population is) to evaluate as a baseline.
    #[arg(long, default_value_t = 32)]
    pub random: u64,
    /// Print one JSON document (schema `berry-evolve/compare/1`) instead of text: per genome
    /// the fitness, metabolism, behaviour measures, trial-score statistics and every trial;
    /// for the random genomes their statistics and each genome.
    #[arg(long)]
    pub json: bool,
    /// Also report this behaviour measure, beside the experiment's own `[behaviour]`
    /// measures (repeat it or separate names with commas; e.g. `--measure eaten,still_share`).
    /// Measures never change fitness, so the experiment file need not change.
    #[arg(long = "measure", value_name = "NAME", value_delimiter = ',', value_parser = measure_name)]
    pub measures: Vec<Measure>,
}

/// A `--measure` name, or a message listing the names there are.
fn measure_name(name: &str) -> Result<Measure, String> {
    MEASURES
        .iter()
        .copied()
        .find(|m| m.name() == name.trim())
        .ok_or_else(|| {
            let names: Vec<&str> = MEASURES.iter().map(|m| m.name()).collect();
            format!(
                "no behaviour measure is named `{name}`; the measures are {}",
                names.join(", ")
            )
        })
}

/// The experiment's behaviour measures, by name, taken from a trial's full measure array
/// (all [`berry_evolve::experiment::MEASURES`] values).
pub fn named_measures(experiment: &Experiment, all: &[f64]) -> Named<f64> {
    Named(
        experiment
            .behaviour
            .measures
            .iter()
            .map(|m| (m.name(), all[m.index()]))
            .collect(),
    )
}

/// The experiment's behaviour measures, by name, from values in its order (an
/// [`Evaluation`]'s means over trials).
pub fn measures_in_order(experiment: &Experiment, values: &[f64]) -> Named<f64> {
    Named(
        experiment
            .behaviour
            .measures
            .iter()
            .zip(values)
            .map(|(m, &v)| (m.name(), v))
            .collect(),
    )
}

/// `  distinct_food 3.5000, ticks_alive 500.0000` for the behaviour measures, or nothing when
/// the experiment names none.
pub fn measures_text(measures: &Named<f64>) -> String {
    if measures.is_empty() {
        return String::new();
    }
    let parts: Vec<String> = measures
        .0
        .iter()
        .map(|(name, v)| format!("{name} {v:.4}"))
        .collect();
    format!("  {}", parts.join(", "))
}

/// A fitness as the text output shows it: 4 decimals, or `non-finite`.
pub fn fitness_text(fitness: Option<f64>) -> String {
    fitness.map_or("non-finite".to_string(), |f| format!("{f:.4}"))
}

/// One life in one trial world, as `compare --json` and `replay --json` report it.
#[derive(Debug, Serialize)]
pub struct TrialReport {
    /// The trial's index (its world).
    pub trial: u64,
    /// Its score under `[fitness]` (`null` when not finite).
    pub score: Option<f64>,
    /// The metabolic vector at the end of life (A, B, C, D).
    pub metabolism: [f64; 4],
    /// Ticks on which the shock sensor was on.
    pub shocked_ticks: u64,
    /// True when the brain produced a NaN or infinite output and the life was stopped.
    pub non_finite: bool,
    /// The experiment's behaviour measures in this trial.
    pub measures: Named<f64>,
    /// With lives of several episodes (`compare --json` of a genome file): the life's
    /// episodes, for a curve of the correct-choice share per episode.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub episodes: Option<EpisodesReport>,
}

/// One life's episodes (`[evaluation] episodes_per_life` > 1), each list in episode order.
#[derive(Debug, Serialize)]
pub struct EpisodesReport {
    /// The episodes (numbered from 1) a switch came before.
    pub switches: Vec<u64>,
    /// Per episode: were the switch kinds' payoffs exchanged (relative to `[world.kinds]`)?
    pub exchanged: Vec<bool>,
    /// Per episode: was its first bite of a switch kind of the kind that paid then (false
    /// when it bit neither)? Empty without `[evaluation.switch]`.
    pub correct_first_choice: Vec<bool>,
}

impl TrialReport {
    /// The report of trial `trial`'s outcome.
    pub fn new(experiment: &Experiment, trial: u64, o: &TrialOutcome) -> TrialReport {
        TrialReport {
            trial,
            score: finite(o.score),
            metabolism: o.metabolism,
            shocked_ticks: o.shocked_ticks,
            non_finite: o.non_finite,
            measures: named_measures(experiment, &o.measures),
            episodes: None,
        }
    }
}

/// One genome's evaluation over the trials: the fitness selection would see, its parts, the
/// statistics of the trial scores and every trial.
#[derive(Debug, Serialize)]
pub struct GenomeReport {
    /// The genome file (absent for a random genome).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub path: Option<String>,
    /// The fitness: the trials' scores aggregated as the experiment says (`null` when a
    /// trial was not finite).
    pub fitness: Option<f64>,
    /// Mean over trials of the final metabolic vector.
    pub metabolism: [f64; 4],
    /// Mean over trials of each behaviour measure.
    pub measures: Named<f64>,
    /// Statistics over the trials' finite scores.
    pub trial_scores: FitnessStats,
    /// Every trial.
    pub trials: Vec<TrialReport>,
}

impl GenomeReport {
    fn new(
        experiment: &Experiment,
        path: Option<String>,
        outcomes: &[TrialOutcome],
    ) -> GenomeReport {
        let e = aggregate(experiment, outcomes);
        let scores: Vec<f64> = outcomes
            .iter()
            .map(|o| o.score)
            .filter(|s| s.is_finite())
            .collect();
        GenomeReport {
            path,
            fitness: e.fitness,
            metabolism: e.metabolism,
            measures: measures_in_order(experiment, &e.measures),
            trial_scores: FitnessStats::of(&scores),
            trials: outcomes
                .iter()
                .zip(0..)
                .map(|(o, t)| TrialReport::new(experiment, t, o))
                .collect(),
        }
    }

    /// `correct first choice by episode: 0.50 0.70 ...`: per episode, the share of lives whose
    /// first choice was correct (None without per-episode choices).
    fn choices_text(&self) -> Option<String> {
        let lives: Vec<&Vec<bool>> = self
            .trials
            .iter()
            .filter_map(|t| t.episodes.as_ref())
            .map(|e| &e.correct_first_choice)
            .filter(|c| !c.is_empty())
            .collect();
        let k = lives.first()?.len();
        let shares: Vec<String> = (0..k)
            .map(|e| {
                let right = lives.iter().filter(|c| c[e]).count();
                format!("{:.2}", right as f64 / lives.len() as f64)
            })
            .collect();
        Some(format!(
            "correct first choice by episode ({} lives): {}",
            lives.len(),
            shares.join(" ")
        ))
    }

    /// `46.0000  (A 22.000, B 10.000, C 8.000, D 6.000)  distinct_food 7.6667`.
    fn text(&self) -> String {
        let f = fitness_text(self.fitness);
        let m = self.metabolism;
        format!(
            "{f}  (A {:.3}, B {:.3}, C {:.3}, D {:.3}){}",
            m[0],
            m[1],
            m[2],
            m[3],
            measures_text(&self.measures)
        )
    }
}

/// Whose trial worlds the genomes met.
#[derive(Debug, Serialize)]
pub struct Worlds {
    /// True for the held-out set (never used in training or validation).
    pub held_out: bool,
    /// True for the experiment's validation worlds (absent otherwise).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub validation: bool,
    /// The generation number whose worlds these are (for the held-out set,
    /// [`berry_evolve::evo::worlds::HELD_OUT_GENERATION`]; 0 for the validation worlds, whose
    /// streams are of their own purpose).
    pub generation: u64,
    /// The set, resolved.
    #[serde(skip)]
    pub set: WorldSet,
}

impl Worlds {
    /// The worlds of `set`.
    pub fn of(set: WorldSet) -> Worlds {
        Worlds {
            held_out: set == WorldSet::HeldOut,
            validation: set == WorldSet::Validation,
            generation: set.generation().0,
            set,
        }
    }

    /// `the held-out worlds (...)`, `the validation worlds (...)` or `generation G's
    /// training worlds`.
    pub fn text(&self) -> String {
        self.set.description()
    }
}

/// The random genomes' results: statistics over the genomes and each genome.
#[derive(Debug, Serialize)]
pub struct RandomReport {
    /// How many random genomes were drawn.
    pub count: u64,
    /// How many of them got a finite fitness (the statistics are over those).
    pub finite: usize,
    /// Statistics of their finite fitness values.
    pub fitness: FitnessStats,
    /// Per behaviour measure, statistics of the genomes' values (means over trials).
    pub measures: Named<FitnessStats>,
    /// Every random genome, in the order drawn.
    pub genomes: Vec<GenomeReport>,
}

fn is_one(x: &u64) -> bool {
    *x == 1
}

/// What `compare` prints (as text, or as JSON with `--json`).
#[derive(Debug, Serialize)]
pub struct CompareReport {
    /// `berry-evolve/compare/1`.
    pub schema: &'static str,
    /// The experiment's name.
    pub experiment: String,
    /// The experiment file given.
    pub experiment_file: String,
    /// Its seed (the worlds derive from it).
    pub seed: u64,
    /// Trials per genome.
    pub trials: u64,
    /// Ticks per trial (per episode with lives of several).
    pub ticks: u64,
    /// Episodes per life (absent when 1).
    #[serde(skip_serializing_if = "is_one")]
    pub episodes_per_life: u64,
    /// How a genome's trial scores become its fitness.
    pub aggregate: Aggregate,
    /// Whose worlds.
    pub worlds: Worlds,
    /// The genome files, in the order given.
    pub genomes: Vec<GenomeReport>,
    /// The random genomes (absent with `--random 0`).
    pub random: Option<RandomReport>,
}

impl CompareReport {
    /// Prints the report as the text lines `compare` has always printed.
    fn print_text(&self) {
        let episodes = if self.episodes_per_life > 1 {
            format!(" x {} episodes", self.episodes_per_life)
        } else {
            String::new()
        };
        outln!(
            "experiment `{}`: {} trials{episodes} x {} ticks on {}",
            self.experiment,
            self.trials,
            self.ticks,
            self.worlds.text()
        );
        for g in &self.genomes {
            outln!("{}: fitness {}", g.path.as_deref().unwrap_or("?"), g.text());
            if let Some(line) = g.choices_text() {
                outln!("  {line}");
            }
        }
        if let Some(r) = &self.random {
            let s = &r.fitness;
            outln!(
                "{} random genomes: fitness mean {:.4}, std {:.4}, best {:.4}, median {:.4}",
                r.count,
                s.mean,
                s.std,
                s.best,
                s.median
            );
            // Per measure, the random genomes' median and best (largest) value.
            for (name, s) in &r.measures.0 {
                outln!(
                    "{} random genomes: {name} median {:.4}, best {:.4}",
                    r.count,
                    s.median,
                    s.best
                );
            }
        }
    }
}

/// Runs the subcommand.
pub fn run(args: CompareArgs) -> anyhow::Result<()> {
    let report = compare(&args)?;
    if args.json {
        json::print(&report)
    } else {
        report.print_text();
        Ok(())
    }
}

/// Evaluates what `args` names and gathers the report (also the end-of-run held-out check's
/// evaluation, `cli::check`).
pub(crate) fn compare(args: &CompareArgs) -> anyhow::Result<CompareReport> {
    let set = WorldSet::choose(args.worlds, args.generation, WorldsChoice::HeldOut, 0)?;
    let experiment_path = experiment_file(args.experiment.as_deref(), &args.genomes)?;
    let mut experiment = Experiment::load(&experiment_path)?;
    set.check_file(&experiment, &experiment_path)?;
    if let Some(t) = args.trials {
        experiment = set.with_trials(&experiment, t)?;
    }
    // Every genome meets the same worlds: common random numbers, group 0.
    let mut experiment = alone(&experiment)?;
    if !args.measures.is_empty() {
        experiment = with_measures(&experiment, &args.measures)
            .with_context(|| format!("{}: with --measure", experiment_path.display()))?;
    }
    let mut genomes = Vec::new();
    for path in &args.genomes {
        let file = GenomeFile::load(path)?;
        let topology = file.topology_for(&experiment, path)?;
        warn_other_experiment(&file, path, &experiment, &experiment_path);
        let path = Some(path.display().to_string());
        let genome = [file.genome()];
        let request = Evaluate::new(&experiment, &topology, &genome, door::Worlds::Alone(set));
        if experiment.evaluation.episodes_per_life > 1 {
            let lived = request.lives_by_episode()?.swap_remove(0);
            let o: Vec<TrialOutcome> = lived.iter().map(|(o, _)| *o).collect();
            let mut report = GenomeReport::new(&experiment, path, &o);
            let switch = experiment.evaluation.switch.is_some();
            for (trial, (_, c)) in report.trials.iter_mut().zip(lived) {
                trial.episodes = Some(EpisodesReport {
                    switches: c.switches,
                    exchanged: c.exchanged,
                    correct_first_choice: if switch {
                        c.correct_first_choice
                    } else {
                        Vec::new()
                    },
                });
            }
            genomes.push(report);
            continue;
        }
        let o = request.lives()?.swap_remove(0);
        genomes.push(GenomeReport::new(&experiment, path, &o));
    }
    let random = (args.random > 0)
        .then(|| random_genomes(&experiment, set, args.random))
        .transpose()?;
    Ok(CompareReport {
        schema: "berry-evolve/compare/1",
        experiment: experiment.name.clone(),
        experiment_file: experiment_path.display().to_string(),
        seed: experiment.seed,
        trials: set.trials(&experiment),
        ticks: experiment.evaluation.ticks,
        episodes_per_life: experiment.evaluation.episodes_per_life,
        aggregate: experiment.evaluation.aggregate,
        worlds: Worlds::of(set),
        genomes,
        random,
    })
}

/// `experiment` reporting `extra` measures after its own `[behaviour]` ones (those it names
/// already keep their place), validated as if the file named them (an area measure needs
/// `[behaviour] area`).
fn with_measures(
    experiment: &Experiment,
    extra: &[Measure],
) -> Result<Experiment, berry_evolve::validate::InvalidValue> {
    experiment
        .with_overrides()
        .edit(|c| {
            for &m in extra {
                if !c.behaviour.measures.contains(&m) {
                    c.behaviour.measures.push(m);
                }
            }
        })
        .build()
}

/// `count` random genomes, drawn as the initial population is, evaluated in parallel
/// (collected in draw order).
fn random_genomes(
    experiment: &Experiment,
    set: WorldSet,
    count: u64,
) -> anyhow::Result<RandomReport> {
    let topology = experiment.topology();
    let drawn = worlds::random_genomes(experiment, set.generation(), count as usize);
    let lives = Evaluate::new(experiment, &topology, &drawn, door::Worlds::Alone(set)).lives()?;
    let genomes: Vec<GenomeReport> = lives
        .iter()
        .map(|o| GenomeReport::new(experiment, None, o))
        .collect();
    let fitness: Vec<f64> = genomes.iter().filter_map(|g| g.fitness).collect();
    let measures = experiment
        .behaviour
        .measures
        .iter()
        .enumerate()
        .map(|(k, m)| {
            let values: Vec<f64> = genomes.iter().map(|g| g.measures.0[k].1).collect();
            (m.name(), FitnessStats::of(&values))
        })
        .collect();
    Ok(RandomReport {
        count,
        finite: fitness.len(),
        fitness: FitnessStats::of(&fitness),
        measures: Named(measures),
        genomes,
    })
}
