//! `berry-evolve extract`: one individual of a checkpoint's population, or one elite of a
//! MAP-Elites archive (`--cell`), as a genome file, for `replay`, `compare` and `render`.

use crate::cli::console::errln;

use anyhow::Context;
use berry_evolve::evo::search::factory;
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
    #[arg(
        long,
        value_name = "K",
        required_unless_present = "cell",
        conflicts_with = "cell"
    )]
    pub individual: Option<u64>,
    /// For a MAP-Elites run: the elite of this archive cell, one bin index per descriptor
    /// from 0, comma-separated (`3,1`; the `cell_*` columns of archive.csv), in the archive as
    /// it was after the checkpoint's generation.
    #[arg(long, value_name = "I,J")]
    pub cell: Option<String>,
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
    if let Some(cell) = &args.cell {
        return extract_cell(cell, &path, &payload, &args.output);
    }
    // clap requires one of --individual and --cell.
    let chosen = args.individual.unwrap_or_default();
    let generation = payload.last.generation;
    let count = payload.last.individuals.len();
    let individual = usize::try_from(chosen)
        .ok()
        .and_then(|k| payload.last.individuals.get(k))
        .with_context(|| {
            format!(
                "--individual {}: {} holds generation {generation} with {count} individuals, \
                 numbered 0 to {}; choose one of those (export-csv --population lists them)",
                chosen,
                path.display(),
                count.saturating_sub(1)
            )
        })?;
    // Validated when the checkpoint was loaded; a failure here names the checkpoint anyway.
    let experiment = Experiment::try_from(payload.experiment.clone())
        .map_err(|e| anyhow::anyhow!("{}: its experiment is not valid: {e}", path.display()))?;
    let born = individual.lineage.as_ref().map_or(String::new(), |l| {
        let parents: Vec<String> = l.parents.iter().map(u64::to_string).collect();
        if !l.elites.is_empty() {
            // MAP-Elites: parents are archive elites of any earlier generation.
            let elites: Vec<String> = l.elites.iter().map(|e| e.to_string()).collect();
            format!(
                ", born {} of the elites {}",
                l.birth.name(),
                elites.join(" and ")
            )
        } else if parents.is_empty() {
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
            chosen,
            path.file_name().unwrap_or_default().to_string_lossy()
        )),
        ..Origin::evolved(
            &experiment,
            generation,
            Some(chosen),
            individual.evaluation.fitness,
            Some(individual.evaluation.metabolism),
        )
    };
    let file = GenomeFile::new(&experiment, &individual.genome, origin);
    file.save(&args.output)?;
    errln!(
        "wrote individual {} of generation {generation} ({}) to {}",
        chosen,
        individual
            .evaluation
            .fitness
            .map_or("non-finite fitness".to_string(), |f| format!("fitness {f}")),
        args.output.display()
    );
    Ok(())
}

/// `--cell`: the elite of a cell of the checkpoint's MAP-Elites archive (after its
/// generation), written as a genome file at `output`.
fn extract_cell(
    cell: &str,
    path: &std::path::Path,
    payload: &berry_evolve::run::CheckpointPayload,
    output: &std::path::Path,
) -> anyhow::Result<()> {
    let experiment = Experiment::try_from(payload.experiment.clone())
        .map_err(|e| anyhow::anyhow!("{}: its experiment is not valid: {e}", path.display()))?;
    let mut search = factory::of(&experiment, &experiment.topology());
    search.restore(payload.search.as_ref(), payload.last.generation);
    let Some(archive) = search.archive(&payload.last) else {
        anyhow::bail!(
            "--cell {cell}: {} is a run of algorithm = \"{}\", which keeps no archive of \
             elites; --cell is for map-elites runs (use --individual K for this one)",
            path.display(),
            search.name()
        );
    };
    let bins: Vec<String> = archive
        .dimensions
        .iter()
        .map(|d| format!("{} bins of {}", d.bins, d.measure))
        .collect();
    let shape = format!(
        "its grid has {} (each index from 0 to bins − 1)",
        bins.join(" × ")
    );
    let parsed: Option<Vec<usize>> = cell
        .split(',')
        .map(|x| x.trim().parse::<usize>().ok())
        .collect();
    let Some(index) = parsed else {
        anyhow::bail!(
            "--cell {cell}: not a cell; write one bin index per descriptor, from 0, separated by \
             commas (e.g. --cell 3,1); {shape}"
        );
    };
    if index.len() != archive.dimensions.len() {
        anyhow::bail!(
            "--cell {cell}: gives {} bin indices, but the archive of {} has {} dimensions: {shape}",
            index.len(),
            path.display(),
            archive.dimensions.len()
        );
    }
    if index
        .iter()
        .zip(&archive.dimensions)
        .any(|(&i, d)| i >= d.bins)
    {
        anyhow::bail!(
            "--cell {cell}: outside the archive of {}: {shape}",
            path.display()
        );
    }
    let Some(elite) = archive.get(&index) else {
        anyhow::bail!(
            "--cell {cell}: that cell of the archive of {} is empty (after generation {}, {} of \
             {} cells hold an elite); archive.csv in the run folder lists the filled cells",
            path.display(),
            payload.last.generation,
            archive.elites.len(),
            archive.cells()
        );
    };
    let origin = Origin {
        description: Some(format!(
            "the elite of MAP-Elites cell {cell} ({}) after generation {}, extracted from \
             checkpoint {}",
            archive
                .dimensions
                .iter()
                .zip(&elite.measures)
                .map(|(d, m)| format!("{} = {m}", d.measure))
                .collect::<Vec<_>>()
                .join(", "),
            payload.last.generation,
            path.file_name().unwrap_or_default().to_string_lossy()
        )),
        ..Origin::evolved(
            &experiment,
            elite.id.generation,
            Some(elite.id.individual),
            Some(elite.fitness),
            None,
        )
    };
    GenomeFile::new(&experiment, elite.genome, origin).save(output)?;
    errln!(
        "wrote the elite of cell {cell} ({}, fitness {}) to {}",
        elite.id,
        elite.fitness,
        output.display()
    );
    Ok(())
}
