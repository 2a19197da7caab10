//! `berry-evolve replay`: evaluate one genome in an experiment's trial worlds, exactly as
//! evolution evaluated it, and print its fitness and metabolic vector.

use crate::cli::console::{errln, outln};

use anyhow::Context;
use berry_evolve::evo::evaluate::aggregate;
use berry_evolve::evo::trial::{self, NoObserver, TickObserver};
use berry_evolve::experiment::Experiment;
use berry_evolve::record::genome_file::GenomeFile;
use berry_evolve::record::trace::TraceWriter;
use berry_evolve::seed::{Generation, TrialIndex};
use berry_evolve::sim::world::World;
use clap::Args;
use std::path::PathBuf;

/// Arguments of `replay`.
#[derive(Debug, Args)]
pub struct ReplayArgs {
    /// The genome file (JSON), e.g. a run's best.json or one under genomes/.
    pub genome: PathBuf,
    /// The experiment whose worlds to use.
    #[arg(long)]
    pub experiment: PathBuf,
    /// Whose trial worlds: this generation's (default: the genome's own generation, or 0).
    #[arg(long)]
    pub generation: Option<u64>,
    /// Replay only this trial (default: all of the experiment's trials).
    #[arg(long)]
    pub trial: Option<u64>,
    /// Override the experiment's seed (use the seed the genome was evolved with).
    #[arg(long)]
    pub seed: Option<u64>,
    /// Write the per-tick trace of the replayed trial(s) to this CSV file.
    #[arg(long)]
    pub trace: Option<PathBuf>,
}

/// Runs the subcommand.
pub fn run(args: ReplayArgs) -> anyhow::Result<()> {
    let mut experiment = Experiment::load(&args.experiment)?;
    if let Some(seed) = args.seed {
        experiment.seed = seed;
        experiment.validate()?;
    }
    let file = GenomeFile::load(&args.genome)?;
    let topology = file.topology_for(&experiment, &args.genome)?;
    if let Some(recorded) = &file.origin.config_hash {
        let here = experiment.config_hash();
        if *recorded != here {
            errln!(
                "note: {} was evolved under config hash {}, this experiment's is {} (another seed \
                 or other settings), so its worlds and fitness differ from the recorded ones; \
                 replay with the run folder's experiment.toml (or the right --seed) to reproduce them",
                args.genome.display(),
                &recorded[..recorded.len().min(12)],
                &here[..12]
            );
        }
    }
    let genome = file.genome();
    let generation = Generation(args.generation.or(file.origin.generation).unwrap_or(0));
    // Without common random numbers the worlds depend on the individual's index too.
    let group = if experiment.evaluation.common_random_numbers {
        0
    } else {
        file.origin.individual.unwrap_or(0)
    };
    let trials: Vec<u64> = match args.trial {
        Some(t) => {
            anyhow::ensure!(
                t < experiment.evaluation.trials,
                "--trial {t}: the experiment has trials 0..{}",
                experiment.evaluation.trials
            );
            vec![t]
        }
        None => (0..experiment.evaluation.trials).collect(),
    };
    let mut trace = match &args.trace {
        Some(path) => Some(TraceObserver {
            writer: TraceWriter::new(std::io::BufWriter::new(
                std::fs::File::create(path)
                    .with_context(|| format!("cannot create {}", path.display()))?,
            )),
            error: None,
        }),
        None => None,
    };
    let mut outcomes = Vec::new();
    for &t in &trials {
        // The one trial path evaluation takes: the traced life is the scored one.
        let outcome = match &mut trace {
            Some(observer) => trial::run_trial(
                &experiment,
                &topology,
                std::slice::from_ref(&genome),
                generation,
                group,
                TrialIndex(t),
                observer,
            )?,
            None => trial::run_trial(
                &experiment,
                &topology,
                std::slice::from_ref(&genome),
                generation,
                group,
                TrialIndex(t),
                NoObserver,
            )?,
        };
        let o = outcome[0];
        outln!(
            "trial {t}: score {:.6}  metabolism [{:.4}, {:.4}, {:.4}, {:.4}]  shocked ticks {}{}",
            o.score,
            o.metabolism[0],
            o.metabolism[1],
            o.metabolism[2],
            o.metabolism[3],
            o.shocked_ticks,
            if o.non_finite {
                "  (brain produced NaN)"
            } else {
                ""
            }
        );
        outcomes.push(o);
    }
    let evaluation = aggregate(&experiment, &outcomes);
    match evaluation.fitness {
        Some(f) => outln!(
            "fitness {f:.6} ({:?} over {} trial(s) of generation {})",
            experiment.evaluation.aggregate,
            trials.len(),
            generation.0
        ),
        None => outln!("fitness: none (the brain produced a non-finite output)"),
    }
    outln!("metabolism {:?}", evaluation.metabolism);
    if let (Some(observer), Some(path)) = (trace, &args.trace) {
        if let Some(e) = observer.error {
            return Err(e).with_context(|| format!("cannot write {}", path.display()));
        }
        let mut writer = observer.writer;
        writer
            .flush()
            .with_context(|| format!("cannot write {}", path.display()))?;
        errln!("trace written to {}", path.display());
    }
    Ok(())
}

/// Writes each tick of the replayed trial(s) to the trace CSV, keeping the first error.
struct TraceObserver<W: std::io::Write> {
    writer: TraceWriter<W>,
    error: Option<csv::Error>,
}

impl<W: std::io::Write> TickObserver for TraceObserver<W> {
    fn tick(&mut self, world: &World, _tick: u64) {
        if self.error.is_none() {
            if let Err(e) = self.writer.write_tick(world) {
                self.error = Some(e);
            }
        }
    }
}
