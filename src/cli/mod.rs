//! The command-line front end: one module per subcommand, each parsing its arguments and
//! calling the library. Only this layer turns typed errors into messages.

pub mod bench;
pub mod check;
pub mod cluster;
pub mod compare;
pub mod completions;
pub mod config;
pub mod console;
pub mod estimate;
pub mod export;
pub mod extract;
pub mod inspect;
pub mod json;
pub mod new;
pub mod plot;
pub mod progress;
pub mod render;
pub mod replay;
pub mod resume;
pub mod run;
pub mod run_report;
pub mod simulate;
pub mod summary;
pub mod worlds;

use berry_evolve::input::closest;
use clap::{Parser, Subcommand};

/// berry-evolve: evolve neural-network creatures in the BERRY III world, reproducibly.
///
/// `berry-evolve EXPERIMENT.toml` is short for `berry-evolve run EXPERIMENT.toml`.
#[derive(Debug, Parser)]
#[command(name = "berry-evolve", version, args_conflicts_with_subcommands = true)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
    #[command(flatten)]
    pub run: Option<run::RunArgs>,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Evolve a population as an experiment file describes (the main job).
    Run(run::RunArgs),
    /// Continue a stopped or finished run from its newest good checkpoint.
    Resume(resume::ResumeArgs),
    /// Write the fitness curve (or the last population) of a checkpoint or run folder as CSV.
    ExportCsv(export::ExportArgs),
    /// Write individual K of a checkpoint's population as a genome file (for replay, compare).
    Extract(extract::ExtractArgs),
    /// Evaluate one genome as evolution did and print its fitness and metabolic vector.
    Replay(replay::ReplayArgs),
    /// Run scripted creatures in an experiment's world and write a per-tick trace.
    Simulate(simulate::SimulateArgs),
    /// Start a new experiment file from a built-in one (`new NAME --from foraging`; `new --list`).
    New(new::NewArgs),
    /// Show what an experiment file means in plain words: the observation layout, the brain,
    /// the workload of the whole run and its estimated wall time on this machine (--json).
    Inspect(inspect::InspectArgs),
    /// Evaluate genome files and random genomes on the same (held-out) trial worlds.
    Compare(compare::CompareArgs),
    /// Measure simulator and evolution speed (creature-ticks per second, 1 and 2 threads).
    Bench(bench::BenchArgs),
    /// Draw a run's fitness curves (or a summary's medians and quartiles) as SVG.
    Plot(plot::PlotArgs),
    /// Draw one trial of a genome: the arena to scale, its objects and the creature's path.
    Render(render::RenderArgs),
    /// Sum up replicates (`run --seeds`): summary.csv (quartiles across seeds per generation)
    /// and held-out.csv (each seed's best.json, random and baseline genomes held out).
    Summary(summary::SummaryArgs),
    /// Print a completion script for a shell (bash: `berry-evolve completions bash >
    /// ~/.local/share/bash-completion/completions/berry-evolve`).
    Completions(completions::CompletionsArgs),
    /// Print the man page (`berry-evolve man > berry-evolve.1; man -l berry-evolve.1`).
    Man,
    /// Describe the experiment file: `--schema` (JSON Schema for editors), `--reference`
    /// (every key: type, unit, default, range, report section) or `--defaults` (a complete
    /// commented file of defaults).
    Config(config::ConfigArgs),
}

/// Runs the parsed command line; `ranks`: the other MPI ranks, when started by `mpirun` (see
/// [`cluster`]), which `run` and `resume` evaluate on.
pub fn dispatch(cli: Cli, ranks: Option<&cluster::Ranks>) -> anyhow::Result<()> {
    match (cli.command, cli.run) {
        (Some(Command::Run(args)), _) | (None, Some(args)) => run::run(args, ranks),
        (Some(Command::Resume(args)), _) => resume::run(args, ranks),
        (Some(Command::ExportCsv(args)), _) => export::run(args),
        (Some(Command::Extract(args)), _) => extract::run(args),
        (Some(Command::Replay(args)), _) => replay::run(args),
        (Some(Command::Simulate(args)), _) => simulate::run(args),
        (Some(Command::Inspect(args)), _) => inspect::run(args),
        (Some(Command::New(args)), _) => new::run(args),
        (Some(Command::Bench(args)), _) => bench::run(args),
        (Some(Command::Compare(args)), _) => compare::run(args),
        (Some(Command::Plot(args)), _) => plot::run(args),
        (Some(Command::Render(args)), _) => render::run(args),
        (Some(Command::Summary(args)), _) => summary::run(args),
        (Some(Command::Completions(args)), _) => {
            completions::completions(args, <Cli as clap::CommandFactory>::command())
        }
        (Some(Command::Man), _) => completions::man(<Cli as clap::CommandFactory>::command()),
        (Some(Command::Config(args)), _) => config::run(args),
        (None, None) => {
            use clap::CommandFactory;
            Cli::command().print_help()?;
            anyhow::bail!("no experiment given: try `berry-evolve experiments/foraging.toml`")
        }
    }
}

/// A message for a first argument that looks like a mistyped subcommand (`inpsect x.toml`),
/// which the `berry-evolve FILE` shortcut would otherwise take for an experiment file and clap
/// would answer with a confusing conflict: None when it names a subcommand, looks like a path
/// (has a `.` or a `/`), is an existing file, or is close to no subcommand.
pub fn mistyped_subcommand(first: &str) -> Option<String> {
    use clap::CommandFactory;
    if first.starts_with('-') || first.contains(['.', '/']) || std::path::Path::new(first).exists()
    {
        return None;
    }
    let command = Cli::command();
    let names: Vec<&str> = command.get_subcommands().map(|s| s.get_name()).collect();
    if names.contains(&first) {
        return None;
    }
    closest(first, names.iter().copied()).map(|best| {
        format!(
            "`{first}` is not a subcommand; did you mean `{best}`? (`berry-evolve FILE.toml` \
             runs an experiment file; `berry-evolve --help` lists the subcommands)"
        )
    })
}

#[cfg(test)]
mod tests {
    use super::mistyped_subcommand;

    #[test]
    fn a_mistyped_subcommand_gets_a_suggestion_and_a_file_does_not() {
        let m = mistyped_subcommand("inpsect").expect("a suggestion");
        assert!(m.contains("did you mean `inspect`"), "{m}");
        assert!(mistyped_subcommand("export-cvs")
            .unwrap()
            .contains("`export-csv`"));
        assert_eq!(mistyped_subcommand("inspect"), None);
        assert_eq!(mistyped_subcommand("experiments/foraging.toml"), None);
        assert_eq!(mistyped_subcommand("zzzzzzzzzz"), None);
    }
}
