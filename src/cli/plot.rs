//! `berry-evolve plot`: fitness curves of a run (best, mean, median, worst, and
//! `validation_best` where the run has it) or, for a `summary.csv` across seeds, median
//! lines with quartile bands, as an SVG file (see [`berry_evolve::view::plot`]). For a
//! MAP-Elites run (an `archive.csv` beside its fitness.csv) also the archive as a heat map
//! and its QD score and coverage over generations, each in its own SVG.

use crate::cli::console::errln;
use crate::cli::replay::refuse_overwriting_inputs;

use anyhow::Context;
use berry_evolve::evo::search::grid::Dimension;
use berry_evolve::experiment::Experiment;
use berry_evolve::record::archive::ARCHIVE_FILE;
use berry_evolve::record::plot::{write_svg, Table};
use berry_evolve::view::heat_map::heat_map;
use berry_evolve::view::plot::{qd_plot, run_plot, summary_plot};
use clap::Args;
use std::path::{Path, PathBuf};

/// Arguments of `plot`.
#[derive(Debug, Args)]
pub struct PlotArgs {
    /// A run folder (its fitness.csv is plotted), a fitness.csv, or a summary.csv.
    pub input: PathBuf,
    /// The SVG file to write (default: fitness.svg in the run folder, or the CSV's name with
    /// .svg). For a MAP-Elites run also archive.svg and qd.svg in the run folder (with `-o
    /// X.svg`: X-archive.svg and X-qd.svg beside it).
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
    let explicit = args.output.is_some();
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
    let dir = csv.parent().unwrap_or(Path::new("."));
    if !summary && dir.join(ARCHIVE_FILE).is_file() {
        let (archive_out, qd_out) = if explicit {
            let stem = output.with_extension("");
            let stem = stem.display();
            (
                PathBuf::from(format!("{stem}-archive.svg")),
                PathBuf::from(format!("{stem}-qd.svg")),
            )
        } else {
            (dir.join("archive.svg"), dir.join("qd.svg"))
        };
        plot_archive(dir, &title, &archive_out)?;
        refuse_overwriting_inputs("-o", &qd_out, &[csv.as_path()])?;
        write_svg(
            &qd_out,
            &qd_plot(&table, &format!("{title}: quality diversity"))?,
        )?;
        errln!("QD score and coverage written to {}", qd_out.display());
    }
    Ok(())
}

/// The heat map of `dir`'s archive.csv, its grid read from `dir`'s experiment.toml, written
/// to `output`.
fn plot_archive(dir: &Path, title: &str, output: &Path) -> anyhow::Result<()> {
    let archive = dir.join(ARCHIVE_FILE);
    let experiment_file = dir.join("experiment.toml");
    let experiment = Experiment::load(&experiment_file).with_context(|| {
        format!(
            "{} needs the run's experiment.toml beside it for the grid's bins and ranges",
            archive.display()
        )
    })?;
    let Some(settings) = experiment.evolution.map_elites_settings() else {
        anyhow::bail!(
            "{}: its experiment ({}) does not use algorithm = \"map-elites\", so this archive.csv \
             is not its run's; remove it or plot the run it belongs to",
            archive.display(),
            experiment_file.display()
        );
    };
    let dimensions: Vec<Dimension> = settings.descriptors.iter().map(Dimension::from).collect();
    let table = Table::load(&archive)?;
    let columns: Vec<usize> = dimensions
        .iter()
        .map(|d| format!("cell_{}", d.measure))
        .chain(["fitness".to_string()])
        .map(|c| {
            table.column(&c).with_context(|| {
                format!(
                    "{}: no column `{c}` (its header: {}); it is not the archive of this run's grid",
                    archive.display(),
                    table.header.join(",")
                )
            })
        })
        .collect::<anyhow::Result<_>>()?;
    let (fitness, cells) = columns
        .split_last()
        .expect("the fitness column is chained last");
    let elites: Vec<(Vec<usize>, f64)> = table
        .rows
        .iter()
        .filter_map(|r| {
            let cell = cells
                .iter()
                .map(|&c| r.get(c).copied().flatten().map(|x| x as usize))
                .collect::<Option<Vec<usize>>>()?;
            Some((cell, r.get(*fitness).copied().flatten()?))
        })
        .collect();
    refuse_overwriting_inputs("-o", output, &[archive.as_path()])?;
    write_svg(
        output,
        &heat_map(&dimensions, &elites, &format!("{title}: archive")),
    )?;
    errln!("archive heat map written to {}", output.display());
    Ok(())
}
