//! `berry-evolve extract`: one individual of a checkpoint's population as a genome file, for
//! `replay`, `compare` and `render`.

use crate::cli::console::errln;

use anyhow::Context;
use berry_evolve::experiment::Experiment;
use berry_evolve::record::genome_file::{GenomeFile, Origin};
use berry_evolve::run::load_checkpoint;
use clap::Args;
use std::path::PathBuf;

/// Arguments of `extract`.
#[derive(Debug, Args)]
pub struct ExtractArgs {
    /// A checkpoint file (RUN/checkpoints/gen-NNNNNN.json) or a run folder (its newest good
    /// checkpoint).
    pub checkpoint: PathBuf,
    /// Which individual of the checkpoint's generation, from 0 (the `id` column of
    /// `export-csv --population`; for PGPE the last one is the centre).
    #[arg(long, value_name = "K")]
    pub individual: u64,
    /// The genome file to write (replaced atomically; never one of the run's own files).
    #[arg(short, long, value_name = "FILE")]
    pub output: PathBuf,
}

/// Runs the subcommand.
pub fn run(args: ExtractArgs) -> anyhow::Result<()> {
    let (dir, path, payload, _) = load_checkpoint(&args.checkpoint).with_context(|| {
        let genome = !args.checkpoint.is_dir()
            && GenomeFile::load(&args.checkpoint).is_ok();
        format!(
            "cannot extract from {}: {}; give a checkpoint (RUN/checkpoints/gen-NNNNNN.json) or \
             a run folder",
            args.checkpoint.display(),
            if genome {
                "it is a genome file, which holds one genome already (replay or compare it as it is)"
            } else {
                "it is not a readable checkpoint"
            }
        )
    })?;
    super::export::refuse_over_run_files(&args.output, &dir, &path)?;
    let generation = payload.last.generation;
    let count = payload.last.individuals.len();
    let individual = usize::try_from(args.individual)
        .ok()
        .and_then(|k| payload.last.individuals.get(k))
        .with_context(|| {
            format!(
                "--individual {}: {} holds generation {generation} with {count} individuals, \
                 numbered 0 to {}; choose one of those (export-csv --population lists them)",
                args.individual,
                path.display(),
                count.saturating_sub(1)
            )
        })?;
    // Validated when the checkpoint was loaded; a failure here names the checkpoint anyway.
    let experiment = Experiment::try_from(payload.experiment.clone())
        .map_err(|e| anyhow::anyhow!("{}: its experiment is not valid: {e}", path.display()))?;
    let born = individual.lineage.as_ref().map_or(String::new(), |l| {
        let parents: Vec<String> = l.parents.iter().map(u64::to_string).collect();
        if parents.is_empty() {
            format!(", born {}", l.birth.name())
        } else {
            format!(
                ", born {} of generation {}'s individual(s) {}",
                l.birth.name(),
                generation.saturating_sub(1),
                parents.join(" and ")
            )
        }
    });
    let origin = Origin {
        description: Some(format!(
            "individual {} of generation {generation}, extracted from checkpoint {}{born}",
            args.individual,
            path.file_name().unwrap_or_default().to_string_lossy()
        )),
        ..Origin::evolved(
            &experiment,
            generation,
            Some(args.individual),
            individual.evaluation.fitness,
            Some(individual.evaluation.metabolism),
        )
    };
    let file = GenomeFile::new(&experiment, &individual.genome, origin);
    file.save(&args.output)?;
    errln!(
        "wrote individual {} of generation {generation} ({}) to {}",
        args.individual,
        individual
            .evaluation
            .fitness
            .map_or("non-finite fitness".to_string(), |f| format!("fitness {f}")),
        args.output.display()
    );
    Ok(())
}
