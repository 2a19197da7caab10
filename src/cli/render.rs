//! `berry-evolve render`: one trial of a genome drawn as an SVG picture, the arena to scale
//! with its walls, doors, gadgets, food and predators and the creature's path (see
//! [`berry_evolve::view::render`]). The trial is lived on the one trial path, so the
//! picture shows the life evaluation scored.

use crate::cli::console::errln;
use crate::cli::replay::{refuse_overwriting_inputs, Replay};
use crate::cli::worlds::{experiment_file, WorldsChoice};

use anyhow::Context;
use berry_evolve::record::atomic::write_atomic;
use berry_evolve::view::render::{render_svg, Caption};
use clap::Args;
use std::path::PathBuf;

/// Arguments of `render`.
#[derive(Debug, Args)]
pub struct RenderArgs {
    /// The genome file (JSON), e.g. a run's best.json or one under genomes/.
    pub genome: PathBuf,
    /// The experiment whose worlds to use (default: the experiment.toml beside the genome
    /// file, as in a run folder).
    #[arg(long)]
    pub experiment: Option<PathBuf>,
    /// Which trial to draw.
    #[arg(long, default_value_t = 0)]
    pub trial: u64,
    /// Whose worlds (default: training, those of --generation).
    #[arg(long, value_enum)]
    pub worlds: Option<WorldsChoice>,
    /// Whose training worlds: this generation's (default: the genome's own generation, or 0).
    #[arg(long)]
    pub generation: Option<u64>,
    /// Override the experiment's seed.
    #[arg(long)]
    pub seed: Option<u64>,
    /// The SVG file to write (default: the genome's name with -trial-K.svg).
    #[arg(short, long)]
    pub output: Option<PathBuf>,
}

/// Runs the subcommand.
pub fn run(args: RenderArgs) -> anyhow::Result<()> {
    let output = args.output.clone().unwrap_or_else(|| {
        let stem = args.genome.with_extension("");
        let mut name = stem.file_name().unwrap_or_default().to_os_string();
        name.push(format!("-trial-{}.svg", args.trial));
        stem.with_file_name(name)
    });
    let experiment_path = experiment_file(
        args.experiment.as_deref(),
        std::slice::from_ref(&args.genome),
    )?;
    refuse_overwriting_inputs(
        "-o",
        &output,
        &[args.genome.as_path(), experiment_path.as_path()],
    )?;
    let replay = Replay::prepare(
        &args.genome,
        &experiment_path,
        args.seed,
        args.worlds,
        args.generation,
        Some(args.trial),
    )?;
    let traces = replay.record()?;
    let trace = traces.first().context("no trial was lived")?;
    let e = &replay.experiment;
    let caption = Caption {
        title: replay.title(args.trial),
        lines: vec![
            format!(
                "genome {}",
                args.genome
                    .file_name()
                    .map_or(args.genome.display().to_string(), |n| n
                        .to_string_lossy()
                        .to_string())
            ),
            format!("seed {}, {} ticks per trial", e.seed, e.evaluation.ticks),
        ],
    };
    let svg = render_svg(trace, &caption);
    write_atomic(&output, svg.as_bytes())
        .with_context(|| format!("cannot write {}", output.display()))?;
    errln!("picture written to {}", output.display());
    Ok(())
}
