//! `berry-evolve replay`: evaluate one genome in an experiment's trial worlds, exactly as
//! evolution evaluated it, and print its fitness and metabolic vector.

use crate::cli::console::{errln, outln};

use anyhow::Context;
use berry_evolve::brain::{Brain, BrainController};
use berry_evolve::evo::evaluate::{aggregate, run_trial, trial_stream};
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
    let mut outcomes = Vec::new();
    for &t in &trials {
        let outcome = run_trial(
            &experiment,
            &topology,
            std::slice::from_ref(&genome),
            generation,
            group,
            TrialIndex(t),
        )?;
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
        let measures = crate::cli::compare::measure_values_text(&experiment, &o.measures);
        if !measures.is_empty() {
            outln!("trial {t}:{measures}");
        }
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
    if !experiment.behaviour.measures.is_empty() {
        outln!(
            "measures (mean over trials):{}",
            crate::cli::compare::measures_text(&experiment, &evaluation.measures)
        );
    }
    if let Some(trace_path) = &args.trace {
        let file_out = std::fs::File::create(trace_path)
            .with_context(|| format!("cannot create {}", trace_path.display()))?;
        let mut trace = TraceWriter::new(std::io::BufWriter::new(file_out));
        for &t in &trials {
            let brain = Brain::new(&topology, &genome.parameters)?;
            let mut controllers = [BrainController::new(
                brain,
                experiment.creature.max_rpt,
                experiment.creature.eats_by_action(),
            )];
            let rng = trial_stream(&experiment, generation, group, TrialIndex(t));
            let mut world = World::new(&experiment.world, &experiment.creature, 1, rng)?;
            for _ in 0..experiment.evaluation.ticks {
                world.step(&mut controllers);
                trace.write_tick(&world)?;
                if !world.creatures()[0].alive {
                    break;
                }
            }
        }
        trace.flush()?;
        errln!("trace written to {}", trace_path.display());
    }
    Ok(())
}
