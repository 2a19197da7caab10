//! `berry-evolve replay`: evaluate one genome in an experiment's trial worlds, exactly as
//! evolution evaluated it (the one trial path, [`berry_evolve::evo::trial`]), print its
//! fitness and metabolic vector, and on request write the trace of the whole world (CSV and
//! JSON lines) and an animated replay page (HTML) of those very lives. The worlds are a
//! generation's training worlds (by default the genome's own generation), or a named set
//! (`--worlds held-out|validation`, see [`crate::cli::worlds`]).

use crate::cli::compare::{measures_in_order, measures_text, TrialReport};
use crate::cli::console::{errln, outln};
use crate::cli::json::{self, Named};
use crate::cli::worlds::{
    experiment_file, warn_other_experiment, WorldSet, WorldSetArgs, WorldsChoice,
};

use anyhow::Context;
use berry_evolve::brain::genome::Genome;
use berry_evolve::brain::spec::Topology;
use berry_evolve::evo::episodes::LifeOrigin;
use berry_evolve::evo::evaluate::aggregate;
use berry_evolve::evo::life::TrialOutcome;
use berry_evolve::evo::trace::{parse_synapses, TraceRecorder, TrialTrace};
use berry_evolve::evo::trial::{self, NoObserver, TickObserver, TrialId};
use berry_evolve::evo::TrialPlan;
use berry_evolve::experiment::{Aggregate, Experiment};
use berry_evolve::record::genome_file::GenomeFile;
use berry_evolve::record::trace::files::{
    csv_paths, learning_paths, write_csv_files, write_jsonl, written_paths,
};
use berry_evolve::seed::{Generation, TrialIndex};
use berry_evolve::sim::world::World;
use berry_evolve::view::replay_html;
use clap::Args;
use serde::Serialize;
use std::path::{Path, PathBuf};

/// Arguments of `replay`.
#[derive(Debug, Args)]
pub struct ReplayArgs {
    /// The genome file (JSON), e.g. a run's best.json or one under genomes/.
    pub genome: PathBuf,
    /// The experiment whose worlds to use (default: the experiment.toml beside the genome
    /// file, as in a run folder).
    #[arg(long)]
    pub experiment: Option<PathBuf>,
    /// Whose worlds (default: training, those of --generation).
    #[arg(long, value_enum)]
    pub worlds: Option<WorldsChoice>,
    /// Whose training worlds: this generation's (default: the genome's own generation, or 0).
    #[arg(long)]
    pub generation: Option<u64>,
    /// Replay only this trial (default: all of the set's trials).
    #[arg(long)]
    pub trial: Option<u64>,
    /// Override the experiment's seed (use the seed the genome was evolved with).
    #[arg(long)]
    pub seed: Option<u64>,
    /// Write the trace of the whole world to this CSV file (creatures), with
    /// STEM-actors.csv, STEM-objects.csv, STEM-events.csv and STEM-world.jsonl beside it.
    /// It ends with the scored life: on the tick in which the last creature died, as
    /// `simulate --trace` does.
    #[arg(long)]
    pub trace: Option<PathBuf>,
    /// Write the same trace as JSON lines to this file.
    #[arg(long)]
    pub trace_jsonl: Option<PathBuf>,
    /// A plastic brain's synapses to follow in the trace and on the page, as
    /// layer:from:to,... (layer h0, h1, ..., out, or its number from 0; e.g. h0:3:5,out:7:1).
    /// Default: the 6 whose weight moved most over the life.
    #[arg(long, value_name = "LAYER:FROM:TO,...")]
    pub synapses: Option<String>,
    /// Write a self-contained page that animates the replayed trial (the first one replayed,
    /// every episode of its life) to this HTML file; a plastic brain's page adds a strip of
    /// its weights over the life.
    #[arg(long)]
    pub html: Option<PathBuf>,
    /// Print one JSON document (schema `berry-evolve/replay/1`) instead of text: fitness,
    /// metabolic vector, behaviour measures, every trial, seed, generation and the files
    /// written.
    #[arg(long)]
    pub json: bool,
}

/// What a replay needs, checked: the experiment (seed overridden), the genome and its
/// topology, whose worlds, and which trials.
pub(crate) struct Replay {
    pub experiment: Experiment,
    pub topology: Topology,
    pub genome: Genome,
    /// The named set, or the training worlds of a generation.
    pub worlds: WorldSet,
    /// The generation whose streams build the worlds.
    pub generation: Generation,
    pub group: u64,
    pub trials: Vec<u64>,
    /// The validation worlds, built once (None for the other sets, built trial by trial).
    built: Option<Vec<World>>,
}

impl Replay {
    /// Loads and checks the inputs; errors name the file or the flag.
    pub fn prepare(
        genome_path: &Path,
        experiment_path: &Path,
        seed: Option<u64>,
        worlds: Option<WorldsChoice>,
        generation: Option<u64>,
        trial: Option<u64>,
    ) -> anyhow::Result<Replay> {
        let mut experiment = Experiment::load(experiment_path)?;
        if let Some(seed) = seed {
            experiment = experiment
                .with_overrides()
                .seed(seed)
                .build()
                .with_context(|| format!("--seed {seed}"))?;
        }
        let file = GenomeFile::load(genome_path)?;
        let topology = file.topology_for(&experiment, genome_path)?;
        // Another experiment's genome: its seed and config hash differ as a matter of course,
        // and the warning says more than the notes below would.
        let other = warn_other_experiment(&file, genome_path, &experiment, experiment_path);
        if let Some(evolved) = file.origin.seed.filter(|&s| s != experiment.seed && !other) {
            errln!(
                "note: {} was evolved with seed {evolved}, this experiment has seed {}; replay \
                 with --seed {evolved} to meet the worlds it was evaluated on",
                genome_path.display(),
                experiment.seed
            );
        }
        if let Some(recorded) = file.origin.config_hash.as_ref().filter(|_| !other) {
            let here = experiment.config_hash();
            if *recorded != here {
                errln!(
                    "note: {} was evolved under config hash {}, this experiment's is {} (another seed \
                     or other settings), so its worlds and fitness differ from the recorded ones; \
                     replay with the run folder's experiment.toml (or the right --seed) to reproduce them",
                    genome_path.display(),
                    &recorded[..recorded.len().min(12)],
                    &here[..12]
                );
            }
        }
        let genome = file.genome();
        let worlds = WorldSet::choose(
            worlds,
            generation,
            WorldsChoice::Training,
            file.origin.generation.unwrap_or(0),
        )?;
        worlds.check_file(&experiment, experiment_path)?;
        // Without common random numbers a generation's worlds depend on the individual's
        // index too; the held-out worlds are compare's, one set for every genome (group 0).
        let group = match worlds {
            WorldSet::Training(_) if !experiment.evaluation.common_random_numbers => {
                file.origin.individual.unwrap_or(0)
            }
            _ => 0,
        };
        let count = worlds.trials(&experiment);
        let trials: Vec<u64> = match trial {
            Some(t) => {
                let what = match worlds {
                    WorldSet::Validation => "validation worlds",
                    _ => "trials",
                };
                anyhow::ensure!(
                    t < count,
                    "--trial {t}: experiment {} has {what} 0..{count} (0 to {}); choose one of \
                     those",
                    experiment_path.display(),
                    count.saturating_sub(1)
                );
                vec![t]
            }
            None => (0..count).collect(),
        };
        let built = worlds.built_worlds(&experiment)?;
        Ok(Replay {
            experiment,
            topology,
            genome,
            worlds,
            generation: worlds.generation(),
            group,
            trials,
            built,
        })
    }

    /// The title of trial `t`: `foraging: held-out world 2`, `foraging: trial 2 of
    /// generation 5`.
    pub fn title(&self, t: u64) -> String {
        format!("{}: {}", self.experiment.name, self.worlds.trial_title(t))
    }

    /// Lives trial `t`, recording it when `recorder` is given.
    pub fn run(
        &self,
        t: u64,
        recorder: Option<&mut TraceRecorder>,
    ) -> anyhow::Result<TrialOutcome> {
        let outcomes = match recorder {
            Some(r) => self.live(t, r)?,
            None => self.live(t, NoObserver)?,
        };
        Ok(outcomes[0])
    }

    /// Lives trial `t` on the one trial path evaluation takes (the traced life is the scored
    /// one), in the validation world built beforehand or in the world its stream builds.
    fn live<O: TickObserver>(&self, t: u64, observer: O) -> anyhow::Result<Vec<TrialOutcome>> {
        let genomes = std::slice::from_ref(&self.genome);
        let (plan, topology) = (&TrialPlan::new(&self.experiment), &self.topology);
        let (generation, group, trial) = (self.generation, self.group, TrialIndex(t));
        Ok(match &self.built {
            Some(worlds) => {
                let world = usize::try_from(t)
                    .ok()
                    .and_then(|k| worlds.get(k))
                    .context("no such validation world")?
                    .clone();
                let id = TrialId {
                    generation,
                    group,
                    trial,
                };
                // Built worlds are the validation worlds (`WorldSet::built_worlds`).
                let origin = LifeOrigin::validation(trial);
                trial::run_trial_in_world(plan, topology, genomes, id, origin, world, observer)?
            }
            None => trial::run_trial(plan, topology, genomes, generation, group, trial, observer)?,
        })
    }

    /// Lives every selected trial, recording them.
    pub fn record(&self) -> anyhow::Result<Vec<TrialTrace>> {
        let mut recorder = TraceRecorder::new(&self.experiment).for_brain(&self.topology);
        for &t in &self.trials {
            self.run(t, Some(&mut recorder))?;
        }
        Ok(recorder.into_trials())
    }

    /// The recorder of this replay's trials, following the synapses `--synapses` names.
    pub fn recorder(&self, synapses: Option<&str>) -> anyhow::Result<TraceRecorder> {
        let recorder = TraceRecorder::new(&self.experiment).for_brain(&self.topology);
        Ok(match synapses {
            Some(text) => recorder.with_synapses(
                parse_synapses(text, &self.topology)
                    .with_context(|| format!("--synapses {text}"))?,
            ),
            None => recorder,
        })
    }
}

/// Refuses an output path that is one of the inputs (compared as canonical paths; an output
/// that does not exist yet is compared through its canonical parent folder).
pub(crate) fn refuse_overwriting_inputs(
    flag: &str,
    output: &Path,
    inputs: &[&Path],
) -> anyhow::Result<()> {
    let canonical = |p: &Path| -> Option<PathBuf> {
        if let Ok(c) = p.canonicalize() {
            return Some(c);
        }
        let parent = match p.parent() {
            Some(d) if !d.as_os_str().is_empty() => d,
            _ => Path::new("."),
        };
        Some(parent.canonicalize().ok()?.join(p.file_name()?))
    };
    let Some(out) = canonical(output) else {
        return Ok(());
    };
    for input in inputs {
        if canonical(input).is_some_and(|i| i == out) {
            anyhow::bail!(
                "{flag} {}: that is an input of this command ({}); choose another output file",
                output.display(),
                input.display()
            );
        }
    }
    Ok(())
}

/// The files a replay wrote, as `replay --json` reports them.
#[derive(Debug, Default, Serialize)]
pub struct ReplayFiles {
    /// `--trace`: the creatures' CSV first, then its -actors.csv, -objects.csv, -events.csv
    /// and -world.jsonl, and a plastic brain's -learning.csv and -synapses.csv (empty
    /// without `--trace`).
    pub trace: Vec<String>,
    /// `--trace-jsonl`.
    pub trace_jsonl: Option<String>,
    /// `--html`.
    pub html: Option<String>,
}

/// What `replay` prints (as text, or as JSON with `--json`).
#[derive(Debug, Serialize)]
pub struct ReplayReport {
    /// `berry-evolve/replay/1`.
    pub schema: &'static str,
    /// The genome file.
    pub genome: String,
    /// The experiment's name.
    pub experiment: String,
    /// The experiment file used (given, or the one beside the genome).
    pub experiment_file: String,
    /// The seed the worlds derive from (the experiment's, or `--seed`).
    pub seed: u64,
    /// Whose trial worlds: this generation's.
    pub generation: u64,
    /// The individual index whose worlds these are (0 under common random numbers).
    pub group: u64,
    /// The named set (`held-out`, `validation`; absent for a generation's training worlds).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub worlds: Option<&'static str>,
    /// The set, resolved.
    #[serde(skip)]
    pub set: WorldSet,
    /// How the trials' scores become the fitness.
    pub aggregate: Aggregate,
    /// The fitness over the trials replayed (`null` when the brain produced a non-finite
    /// output).
    pub fitness: Option<f64>,
    /// Mean over the trials of the final metabolic vector (A, B, C, D).
    pub metabolism: [f64; 4],
    /// Mean over the trials of each behaviour measure the experiment names.
    pub measures: Named<f64>,
    /// Every trial replayed.
    pub trials: Vec<TrialReport>,
    /// The files written.
    pub files: ReplayFiles,
}

impl ReplayReport {
    /// Prints the report as the text lines `replay` has always printed.
    fn print_text(&self) {
        for t in &self.trials {
            let m = t.metabolism;
            let label = self.set.trial_label(t.trial);
            outln!(
                "{label}: score {:.6}  metabolism [{:.4}, {:.4}, {:.4}, {:.4}]  shocked ticks {}{}",
                t.score.unwrap_or(f64::NAN),
                m[0],
                m[1],
                m[2],
                m[3],
                t.shocked_ticks,
                if t.non_finite {
                    "  (brain produced NaN)"
                } else {
                    ""
                }
            );
            if !t.measures.is_empty() {
                outln!("{label}:  measures:{}", measures_text(&t.measures));
            }
        }
        match self.fitness {
            Some(f) => outln!(
                "fitness {f:.6} ({:?} over {})",
                self.aggregate,
                self.set.count_text(self.trials.len())
            ),
            None => outln!("fitness: none (the brain produced a non-finite output)"),
        }
        outln!("metabolism {:?}", self.metabolism);
        if !self.measures.is_empty() {
            outln!(
                "measures (mean over trials):{}",
                measures_text(&self.measures)
            );
        }
    }
}

/// Runs the subcommand.
pub fn run(args: ReplayArgs) -> anyhow::Result<()> {
    let experiment_path = experiment_file(
        args.experiment.as_deref(),
        std::slice::from_ref(&args.genome),
    )?;
    let inputs = [args.genome.as_path(), experiment_path.as_path()];
    if let Some(path) = &args.trace {
        for p in csv_paths(path).iter().chain(&learning_paths(path)) {
            refuse_overwriting_inputs("--trace", p, &inputs)?;
        }
    }
    if let Some(path) = &args.trace_jsonl {
        refuse_overwriting_inputs("--trace-jsonl", path, &inputs)?;
    }
    if let Some(path) = &args.html {
        refuse_overwriting_inputs("--html", path, &inputs)?;
    }
    let replay = Replay::prepare(
        &args.genome,
        &experiment_path,
        args.seed,
        args.worlds,
        args.generation,
        args.trial,
    )?;
    let experiment = &replay.experiment;
    let recording = args.trace.is_some() || args.trace_jsonl.is_some() || args.html.is_some();
    if args.synapses.is_some() && !recording {
        errln!("note: --synapses applies to --trace, --trace-jsonl and --html; none was given");
    }
    let mut recorder = match recording {
        true => Some(replay.recorder(args.synapses.as_deref())?),
        false => None,
    };
    let mut outcomes = Vec::new();
    let mut trials = Vec::new();
    for &t in &replay.trials {
        let o = replay.run(t, recorder.as_mut())?;
        trials.push(TrialReport::new(experiment, t, &o));
        outcomes.push(o);
    }
    let evaluation = aggregate(&TrialPlan::new(experiment), &outcomes);
    let traces = recorder.map(|r| r.into_trials()).unwrap_or_default();
    let mut files = ReplayFiles::default();
    if let Some(path) = &args.trace {
        write_csv_files(&traces, path)?;
        let written = written_paths(&traces, path);
        errln!(
            "trace written to {} (and its -actors.csv, -objects.csv, -events.csv, -world.jsonl{})",
            path.display(),
            if written.len() > 5 {
                ", -learning.csv, -synapses.csv"
            } else {
                ""
            }
        );
        files.trace = written.iter().map(|p| p.display().to_string()).collect();
    }
    if let Some(path) = &args.trace_jsonl {
        write_jsonl(&traces, path)?;
        errln!("trace written to {}", path.display());
        files.trace_jsonl = Some(path.display().to_string());
    }
    if let Some(path) = &args.html {
        let first = traces
            .first()
            .context("no trial was replayed, so there is no page to write")?;
        // The first life replayed, all its episodes.
        replay_html::write_life(
            replay_html::life_of(&traces),
            &replay.title(first.world.trial),
            &experiment.output_names(),
            path,
        )?;
        errln!("replay page written to {}", path.display());
        files.html = Some(path.display().to_string());
    }
    let report = ReplayReport {
        schema: "berry-evolve/replay/1",
        genome: args.genome.display().to_string(),
        experiment: experiment.name.clone(),
        experiment_file: experiment_path.display().to_string(),
        seed: experiment.seed,
        generation: replay.generation.0,
        group: replay.group,
        worlds: (!matches!(replay.worlds, WorldSet::Training(_))).then(|| replay.worlds.name()),
        set: replay.worlds,
        aggregate: experiment.evaluation.aggregate,
        fitness: evaluation.fitness,
        metabolism: evaluation.metabolism,
        measures: measures_in_order(experiment, &evaluation.measures),
        trials,
        files,
    };
    if args.json {
        json::print(&report)
    } else {
        report.print_text();
        Ok(())
    }
}
