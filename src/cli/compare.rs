//! `berry-evolve compare`: evaluate several genomes, and random genomes as a baseline, on the
//! same trial worlds of an experiment, so evolved and hand-designed controllers can be compared
//! fairly. By default the worlds are a held-out set that evolution never saw; `--worlds`
//! names another set (the experiment's validation worlds, or a generation's training worlds).
//! `--ablate` adds the controls of a plastic genome (frozen, ungated) as rows of their own;
//! `--episode-curve` draws every row's correct first choices per episode (docs/learning.md,
//! "Controls and the episode curve").

use crate::cli::console::{errln, outln};
use crate::cli::json::{self, finite, Named};
use crate::cli::worlds::{
    experiment_file, warn_other_experiment, WorldSet, WorldSetArgs, WorldsChoice,
};

use anyhow::{bail, Context};
use berry_evolve::brain::ablation::{ablate, Ablation, AblationError};
use berry_evolve::evo::door::{self, Evaluate, LifeChoices};
use berry_evolve::evo::evaluate::aggregate;
use berry_evolve::evo::life::TrialOutcome;
use berry_evolve::evo::stats::FitnessStats;
use berry_evolve::evo::worlds::{self, alone};
use berry_evolve::evo::TrialPlan;
use berry_evolve::experiment::{Aggregate, Experiment, Measure, MEASURES};
use berry_evolve::record::atomic::{refuse_output_over_input, write_atomic};
use berry_evolve::record::genome_file::GenomeFile;
use berry_evolve::record::plot::write_svg;
use berry_evolve::view::episode_curve::{CurveRow, EpisodeCurve, LifeEpisodes};
use clap::{Args, ValueEnum};
use serde::Serialize;
use std::path::{Path, PathBuf};

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
    /// Also evaluate each plastic genome file ablated, as extra rows labelled
    /// `FILE (frozen)` and `FILE (ungated)`: `frozen`, plasticity off (the weights a life
    /// starts with never change: the fixed MLP of the genome's weights); `ungated`, the
    /// modulators cut (the neuromodulated rule run with g = 1 on every tick, as "hebbian").
    /// `--ablate` alone gives both; `--ablate=frozen` one. See docs/learning.md, "Controls
    /// and the episode curve".
    #[arg(
        long,
        value_enum,
        value_name = "ABLATION",
        num_args = 0..,
        require_equals = true,
        value_delimiter = ',',
        default_missing_values = ["frozen", "ungated"]
    )]
    pub ablate: Vec<AblationChoice>,
    /// Draw every row's share of correct first choices per episode of the life, and per
    /// episode since the last switch, to this SVG file, with the numbers in a CSV of the same
    /// name beside it (`FILE.csv`). Needs lives of several episodes with a switch
    /// (`[evaluation] episodes_per_life` > 1 and `[evaluation.switch]`); the random genomes'
    /// lives are then reported per episode too.
    #[arg(long, value_name = "FILE.svg")]
    pub episode_curve: Option<PathBuf>,
}

/// An `--ablate` value (see [`berry_evolve::brain::ablation`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum AblationChoice {
    /// Plasticity off: the weights never change.
    Frozen,
    /// The modulatory signal cut: the rule runs ungated (g = 1), as "hebbian".
    Ungated,
}

impl AblationChoice {
    fn ablation(self) -> Ablation {
        match self {
            AblationChoice::Frozen => Ablation::Frozen,
            AblationChoice::Ungated => Ablation::Ungated,
        }
    }
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
    /// With `--ablate`: the control this row is of the genome file `path` (`frozen` or
    /// `ungated`); absent for the genome as it is.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ablation: Option<&'static str>,
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
        let e = aggregate(&TrialPlan::new(experiment), outcomes);
        let scores: Vec<f64> = outcomes
            .iter()
            .map(|o| o.score)
            .filter(|s| s.is_finite())
            .collect();
        GenomeReport {
            path,
            ablation: None,
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

    /// The row's name: the genome file, with its ablation in brackets.
    fn label(&self) -> String {
        let path = self.path.as_deref().unwrap_or("?");
        match self.ablation {
            Some(a) => format!("{path} ({a})"),
            None => path.to_string(),
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
            outln!("{}: fitness {}", g.label(), g.text());
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
    if let Some(path) = &args.episode_curve {
        write_episode_curve(&report, path)?;
    }
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
    if let Some(path) = &args.episode_curve {
        check_episode_curve(&experiment, &experiment_path, path, &args.genomes)?;
    }
    let mut genomes = Vec::new();
    for path in &args.genomes {
        let file = GenomeFile::load(path)?;
        let topology = file.topology_for(&experiment, path)?;
        warn_other_experiment(&file, path, &experiment, &experiment_path);
        let path = Some(path.display().to_string());
        genomes.push(row_report(
            &experiment,
            &topology,
            &file.genome(),
            path,
            set,
        )?);
    }
    if !args.ablate.is_empty() {
        genomes = with_ablations(&experiment, args, set, genomes)?;
    }
    let mut random = (args.random > 0)
        .then(|| random_genomes(&experiment, set, args.random))
        .transpose()?;
    if let (Some(r), Some(_)) = (&mut random, &args.episode_curve) {
        random_episodes(&experiment, set, r)?;
    }
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

/// The episodes of one life as `compare --json` reports them; the first choices only with a
/// switch (without one no choice is right or wrong).
fn episodes_report(experiment: &Experiment, c: LifeChoices) -> EpisodesReport {
    let switch = experiment.evaluation.switch.is_some();
    EpisodesReport {
        switches: c.switches,
        exchanged: c.exchanged,
        correct_first_choice: if switch {
            c.correct_first_choice
        } else {
            Vec::new()
        },
    }
}

/// One row: `genome` of `topology` evaluated on the worlds, with its episodes when lives have
/// several.
fn row_report(
    experiment: &Experiment,
    topology: &berry_evolve::brain::Topology,
    genome: &berry_evolve::brain::Genome,
    path: Option<String>,
    set: WorldSet,
) -> anyhow::Result<GenomeReport> {
    let genomes = [genome.clone()];
    let request = Evaluate::new(experiment, topology, &genomes, door::Worlds::Alone(set));
    if experiment.evaluation.episodes_per_life == 1 {
        let o = request.lives()?.swap_remove(0);
        return Ok(GenomeReport::new(experiment, path, &o));
    }
    let lived = request.lives_by_episode()?.swap_remove(0);
    let o: Vec<TrialOutcome> = lived.iter().map(|(o, _)| *o).collect();
    let mut report = GenomeReport::new(experiment, path, &o);
    for (trial, (_, c)) in report.trials.iter_mut().zip(lived) {
        trial.episodes = Some(episodes_report(experiment, c));
    }
    Ok(report)
}

/// `genomes` (the files' rows, in `args.genomes` order) with each plastic file's ablations
/// after its row. A file whose brain is not plastic gets a note and no rows; when no file
/// is plastic, `--ablate` is refused (it would add nothing).
fn with_ablations(
    experiment: &Experiment,
    args: &CompareArgs,
    set: WorldSet,
    genomes: Vec<GenomeReport>,
) -> anyhow::Result<Vec<GenomeReport>> {
    let mut rows = Vec::new();
    let mut plastic = 0;
    for (path, row) in args.genomes.iter().zip(genomes) {
        rows.push(row);
        let file = GenomeFile::load(path)?;
        let topology = file.topology_for(experiment, path)?;
        if topology.spec.plastic_settings().is_none() {
            continue;
        }
        plastic += 1;
        for choice in &args.ablate {
            let ablation = choice.ablation();
            let (t, g) = match ablate(&topology, &file.genome(), ablation) {
                Ok(ablated) => ablated,
                Err(AblationError::NoGate) => {
                    errln!(
                        "note: {}: no `{}` row: {}",
                        path.display(),
                        ablation.name(),
                        AblationError::NoGate
                    );
                    continue;
                }
                Err(e) => return Err(e).with_context(|| format!("{}: --ablate", path.display())),
            };
            let mut row = row_report(experiment, &t, &g, Some(path.display().to_string()), set)?;
            row.ablation = Some(ablation.name());
            rows.push(row);
        }
    }
    if plastic == 0 {
        let names: Vec<String> = args
            .genomes
            .iter()
            .map(|p| p.display().to_string())
            .collect();
        bail!(
            "--ablate: no genome file given has a plastic brain ({}); ablations take learning \
             away from a genome whose `[brain] plasticity` is \"hebbian\" or \"neuromodulated\" \
             (see docs/learning.md, \"Controls and the episode curve\"), so give such a file or drop --ablate",
            if names.is_empty() {
                "none given".to_string()
            } else {
                format!("`brain.plasticity` is \"none\" in {}", names.join(", "))
            }
        );
    }
    Ok(rows)
}

/// Refuses `--episode-curve` where it cannot draw anything (lives of one episode, or no
/// switch, so no first choice is right or wrong) or would write over an input file, before
/// anything is evaluated.
fn check_episode_curve(
    experiment: &Experiment,
    experiment_path: &Path,
    path: &Path,
    genomes: &[PathBuf],
) -> anyhow::Result<()> {
    let k = experiment.evaluation.episodes_per_life;
    if k < 2 {
        bail!(
            "--episode-curve draws the correct first choices per episode of a life, but \
             experiment `{}` ({}) lives one episode per life (`[evaluation] \
             episodes_per_life` = {k}); use an experiment with lives of several episodes and \
             a switch, e.g. experiments/t-maze-switch.toml",
            experiment.name,
            experiment_path.display()
        );
    }
    if experiment.evaluation.switch.is_none() {
        bail!(
            "--episode-curve draws the share of correct first choices, but experiment `{}` \
             ({}) has no `[evaluation.switch]`, so no choice is right or wrong; add one \
             (docs/learning.md, \"Switches\")",
            experiment.name,
            experiment_path.display()
        );
    }
    if path.extension().and_then(|e| e.to_str()) != Some("svg") {
        bail!(
            "--episode-curve {}: give a file name ending in .svg (the numbers go beside it, \
             in the same name ending in .csv)",
            path.display()
        );
    }
    let mut inputs: Vec<&Path> = genomes.iter().map(PathBuf::as_path).collect();
    inputs.push(experiment_path);
    refuse_output_over_input("--episode-curve", path, &inputs)?;
    refuse_output_over_input("--episode-curve", &path.with_extension("csv"), &inputs)?;
    Ok(())
}

/// Adds each random genome's episodes to its trials (`--episode-curve`), evaluating the
/// genomes again per episode (the same lives: the outcomes are those already reported).
fn random_episodes(
    experiment: &Experiment,
    set: WorldSet,
    random: &mut RandomReport,
) -> anyhow::Result<()> {
    let topology = experiment.topology();
    let drawn = worlds::random_genomes(experiment, set.generation(), random.count as usize);
    let lived = Evaluate::new(experiment, &topology, &drawn, door::Worlds::Alone(set))
        .lives_by_episode()?;
    for (report, lives) in random.genomes.iter_mut().zip(lived) {
        for (trial, (_, c)) in report.trials.iter_mut().zip(lives) {
            trial.episodes = Some(episodes_report(experiment, c));
        }
    }
    Ok(())
}

/// A row's lives for the curve (those with per-episode first choices).
fn curve_lives(report: &GenomeReport) -> Vec<LifeEpisodes<'_>> {
    report
        .trials
        .iter()
        .filter_map(|t| t.episodes.as_ref())
        .map(|e| LifeEpisodes {
            switches: &e.switches,
            correct: &e.correct_first_choice,
        })
        .collect()
}

/// Writes `--episode-curve`: the SVG at `path`, the CSV beside it.
fn write_episode_curve(report: &CompareReport, path: &Path) -> anyhow::Result<()> {
    let episodes = report.episodes_per_life as usize;
    let mut rows = Vec::new();
    for g in &report.genomes {
        rows.push(CurveRow::new(g.label(), &curve_lives(g), episodes, false)?);
    }
    let mut first = report.genomes.first().map(curve_lives);
    if let Some(r) = &report.random {
        let pooled: Vec<LifeEpisodes<'_>> = r.genomes.iter().flat_map(curve_lives).collect();
        let label = format!("{} random genomes", r.count);
        rows.push(CurveRow::new(label, &pooled, episodes, true)?);
        if first.is_none() {
            first = r.genomes.first().map(curve_lives);
        }
    }
    let first = first.unwrap_or_default();
    let title = format!(
        "{}: correct first choice per episode, {} lives ({})",
        report.experiment,
        first.len(),
        report.worlds.set.name()
    );
    let curve = EpisodeCurve::new(title, episodes, &first, rows).with_context(|| {
        format!(
            "--episode-curve {}: give genome files or --random N",
            path.display()
        )
    })?;
    write_svg(path, &curve.svg()?)?;
    let csv = path.with_extension("csv");
    write_atomic(&csv, curve.csv().as_bytes())
        .with_context(|| format!("cannot write {}", csv.display()))?;
    Ok(())
}
