//! `berry-evolve plot`: fitness curves of a run (best, mean, median, worst, and
//! `validation_best` where the run has it) or, for a `summary.csv` across seeds, median
//! lines with quartile bands, as an SVG file (see [`berry_evolve::record::plot`]).

use crate::cli::console::errln;
use crate::cli::replay::refuse_overwriting_inputs;

use berry_evolve::record::plot::{run_plot, summary_plot, write_svg, Table};
use clap::Args;
use std::path::{Path, PathBuf};

/// Arguments of `plot`.
#[derive(Debug, Args)]
pub struct PlotArgs {
    /// A run folder (its fitness.csv is plotted), a fitness.csv, or a summary.csv.
    pub input: PathBuf,
    /// The SVG file to write (default: fitness.svg in the run folder, or the CSV's name with
    /// .svg).
    #[arg(short, long)]
    pub output: Option<PathBuf>,
}

/// The experiment's name from `experiment.toml` beside `csv`, else the folder's name.
fn title_for(csv: &Path) -> String {
    let dir = csv.parent().unwrap_or(Path::new("."));
    let name = std::fs::read_to_string(dir.join("experiment.toml"))
        .ok()
        .and_then(|text| text.parse::<toml::Table>().ok())
        .and_then(|t| t.get("name").and_then(|n| n.as_str()).map(str::to_string));
    let seed = std::fs::read_to_string(dir.join("experiment.toml"))
        .ok()
        .and_then(|text| text.parse::<toml::Table>().ok())
        .and_then(|t| t.get("seed").and_then(|n| n.as_integer()));
    match (name, seed) {
        (Some(n), Some(s)) => format!("{n} (seed {s})"),
        (Some(n), None) => n,
        _ => dir
            .canonicalize()
            .ok()
            .and_then(|d| d.file_name().map(|n| n.to_string_lossy().to_string()))
            .unwrap_or_else(|| csv.display().to_string()),
    }
}

/// Runs the subcommand.
pub fn run(args: PlotArgs) -> anyhow::Result<()> {
    let (csv, default_out) = if args.input.is_dir() {
        let csv = args.input.join("fitness.csv");
        anyhow::ensure!(
            csv.is_file(),
            "{}: no fitness.csv in this folder; give a run folder, a fitness.csv or a summary.csv",
            args.input.display()
        );
        (csv, args.input.join("fitness.svg"))
    } else {
        anyhow::ensure!(
            args.input.is_file(),
            "{}: no such file or folder; give a run folder, a fitness.csv or a summary.csv",
            args.input.display()
        );
        (args.input.clone(), args.input.with_extension("svg"))
    };
    let output = args.output.unwrap_or(default_out);
    refuse_overwriting_inputs("-o", &output, &[csv.as_path()])?;
    let table = Table::load(&csv)?;
    let summary =
        table.column("best").is_none() && table.header.iter().any(|h| h.ends_with("_median"));
    let title = title_for(&csv);
    let svg = if summary {
        summary_plot(&table, &format!("{title}: across seeds"))?
    } else {
        run_plot(&table, &format!("{title}: fitness"))?
    };
    write_svg(&output, &svg)?;
    errln!("plot written to {}", output.display());
    Ok(())
}
