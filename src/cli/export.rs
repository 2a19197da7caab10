//! `berry-evolve export-csv`: the fitness curve (or the last population) held in a checkpoint.

use anyhow::Context;
use berry_evolve::record::fitness_csv::{extra_columns, to_bytes_with};
use berry_evolve::run::load_checkpoint;
use clap::Args;
use std::io::Write;
use std::path::PathBuf;

/// Arguments of `export-csv`.
#[derive(Debug, Args)]
pub struct ExportArgs {
    /// A checkpoint file or a run folder (its newest good checkpoint).
    pub target: PathBuf,
    /// Output file (default: standard output).
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// Write the last generation's individuals (id, fitness, metabolic components) instead
    /// of the fitness curve.
    #[arg(long)]
    pub population: bool,
}

/// Runs the subcommand.
pub fn run(args: ExportArgs) -> anyhow::Result<()> {
    let (_, path, payload, _) = load_checkpoint(&args.target)?;
    let mut bytes = Vec::new();
    if args.population {
        let mut w = csv::Writer::from_writer(&mut bytes);
        w.write_record(["id", "fitness", "food_a", "food_b", "food_c", "food_d"])?;
        for (id, individual) in payload.last.individuals.iter().enumerate() {
            let e = &individual.evaluation;
            let fitness = e
                .fitness
                .map_or(String::from("non_finite"), |f| f.to_string());
            let mut record = vec![id.to_string(), fitness];
            record.extend(e.metabolism.iter().map(|m| m.to_string()));
            w.write_record(&record)?;
        }
        w.flush()?;
        drop(w);
    } else {
        let columns = extra_columns(&payload.experiment);
        bytes = to_bytes_with(&columns, &payload.history, &payload.history_extra)
            .with_context(|| format!("formatting the history of {}", path.display()))?;
    }
    match &args.output {
        Some(out) => std::fs::write(out, &bytes)
            .with_context(|| format!("cannot write {}", out.display()))?,
        None => std::io::stdout().write_all(&bytes)?,
    }
    Ok(())
}
