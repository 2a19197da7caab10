//! `berry-evolve export-csv`: the fitness curve (or the last population) held in a checkpoint.

use anyhow::Context;
use berry_evolve::record::atomic::{refuse_output_over_input, write_atomic};
use berry_evolve::record::checkpoint::{list_checkpoints, parse_checkpoint_file_name};
use berry_evolve::record::fitness_csv::{extra_columns, to_bytes_with};
use berry_evolve::run::load_checkpoint;
use clap::Args;
use std::io::Write;
use std::path::{Path, PathBuf};

/// Arguments of `export-csv`.
#[derive(Debug, Args)]
pub struct ExportArgs {
    /// A checkpoint file or a run folder (its newest good checkpoint).
    pub target: PathBuf,
    /// Output file (default: standard output).
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// Write the last generation's individuals instead of the fitness curve: id, fitness,
    /// metabolic components, and lineage: `birth` (random, elite, mutated, crossover,
    /// pgpe_sample, pgpe_centre) and `parent_a`, `parent_b` (indices into the previous
    /// generation; empty when there is none, and all three empty for checkpoints written
    /// before lineage was recorded).
    #[arg(long)]
    pub population: bool,
}

/// Runs the subcommand.
pub fn run(args: ExportArgs) -> anyhow::Result<()> {
    let (dir, path, payload, _) = load_checkpoint(&args.target)?;
    if let Some(out) = &args.output {
        refuse_over_run_files(out, &dir, &path)?;
    }
    let mut bytes = Vec::new();
    if args.population {
        let mut w = csv::Writer::from_writer(&mut bytes);
        w.write_record([
            "id", "fitness", "food_a", "food_b", "food_c", "food_d", "birth", "parent_a",
            "parent_b",
        ])?;
        for (id, individual) in payload.last.individuals.iter().enumerate() {
            let e = &individual.evaluation;
            let fitness = e
                .fitness
                .map_or(String::from("non_finite"), |f| f.to_string());
            let mut record = vec![id.to_string(), fitness];
            record.extend(e.metabolism.iter().map(|m| m.to_string()));
            let lineage = individual.lineage.as_ref();
            record.push(lineage.map_or(String::new(), |l| l.birth.name().to_string()));
            for k in 0..2 {
                record.push(
                    lineage
                        .and_then(|l| l.parents.get(k))
                        .map_or(String::new(), u64::to_string),
                );
            }
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
        // Atomic: a kill, `ulimit -f` or a full disk leaves the earlier export whole.
        Some(out) => {
            write_atomic(out, &bytes).with_context(|| format!("cannot write {}", out.display()))?
        }
        None => {
            let mut stdout = std::io::stdout().lock();
            stdout
                .write_all(&bytes)
                .and_then(|()| stdout.flush())
                .context("cannot write the CSV to standard output")?
        }
    }
    Ok(())
}

/// `-o` must not name the checkpoint read, nor any file of its run folder that resume reads
/// (other checkpoints, fitness.csv, best.json, champions.jsonl, experiment.toml), nor look
/// like a checkpoint. `extract` uses it too.
pub(crate) fn refuse_over_run_files(
    out: &Path,
    dir: &Path,
    checkpoint: &Path,
) -> anyhow::Result<()> {
    use berry_evolve::run::{
        BEST_FILE, CHAMPIONS_FILE, CHECKPOINT_DIR, EXPERIMENT_FILE, FITNESS_FILE,
    };
    if out
        .file_name()
        .and_then(|n| n.to_str())
        .and_then(parse_checkpoint_file_name)
        .is_some()
    {
        anyhow::bail!(
            "-o {}: a gen-NNNNNN.json name is a checkpoint's, and another file there would pass \
             for a damaged checkpoint; choose another output file name",
            out.display()
        );
    }
    let mut inputs: Vec<PathBuf> = vec![checkpoint.to_path_buf()];
    for f in [FITNESS_FILE, BEST_FILE, CHAMPIONS_FILE, EXPERIMENT_FILE] {
        inputs.push(dir.join(f));
    }
    for d in [
        dir.join(CHECKPOINT_DIR),
        checkpoint.parent().unwrap_or(Path::new(".")).to_path_buf(),
    ] {
        inputs.extend(
            list_checkpoints(&d)
                .unwrap_or_default()
                .into_iter()
                .map(|(_, p)| p),
        );
    }
    let inputs: Vec<&Path> = inputs.iter().map(PathBuf::as_path).collect();
    refuse_output_over_input("-o", out, &inputs)?;
    Ok(())
}
