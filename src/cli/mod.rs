//! The command-line front end: one module per subcommand, each parsing its arguments and
//! calling the library. Only this layer turns typed errors into messages.

pub mod bench;
pub mod cluster;
pub mod compare;
pub mod completions;
pub mod console;
pub mod export;
pub mod inspect;
pub mod plot;
pub mod progress;
pub mod render;
pub mod replay;
pub mod resume;
pub mod run;
pub mod simulate;
pub mod summary;

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
    /// Evaluate one genome as evolution did and print its fitness and metabolic vector.
    Replay(replay::ReplayArgs),
    /// Run scripted creatures in an experiment's world and write a per-tick trace.
    Simulate(simulate::SimulateArgs),
    /// Show what an experiment file means: the observation layout, brain size and workload.
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
}

/// Runs the parsed command line; `ranks`: the other MPI ranks, when started by `mpirun` (see
/// [`cluster`]), which `run` and `resume` evaluate on.
pub fn dispatch(cli: Cli, ranks: Option<&cluster::Ranks>) -> anyhow::Result<()> {
    match (cli.command, cli.run) {
        (Some(Command::Run(args)), _) | (None, Some(args)) => run::run(args, ranks),
        (Some(Command::Resume(args)), _) => resume::run(args, ranks),
        (Some(Command::ExportCsv(args)), _) => export::run(args),
        (Some(Command::Replay(args)), _) => replay::run(args),
        (Some(Command::Simulate(args)), _) => simulate::run(args),
        (Some(Command::Inspect(args)), _) => inspect::run(args),
        (Some(Command::Bench(args)), _) => bench::run(args),
        (Some(Command::Compare(args)), _) => compare::run(args),
        (Some(Command::Plot(args)), _) => plot::run(args),
        (Some(Command::Render(args)), _) => render::run(args),
        (Some(Command::Summary(args)), _) => summary::run(args),
        (Some(Command::Completions(args)), _) => {
            completions::completions(args, <Cli as clap::CommandFactory>::command())
        }
        (Some(Command::Man), _) => completions::man(<Cli as clap::CommandFactory>::command()),
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
    let (distance, best) = names.iter().map(|n| (edit_distance(first, n), *n)).min()?;
    (distance <= 2.max(best.len() / 3)).then(|| {
        format!(
            "`{first}` is not a subcommand; did you mean `{best}`? (`berry-evolve FILE.toml` \
             runs an experiment file; `berry-evolve --help` lists the subcommands)"
        )
    })
}

/// Levenshtein distance between two short words (insertions, deletions, substitutions).
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let above = row[j + 1];
            row[j + 1] = (above + 1)
                .min(row[j] + 1)
                .min(diagonal + usize::from(ca != cb));
            diagonal = above;
        }
    }
    row[b.len()]
}

#[cfg(test)]
mod tests {
    use super::{edit_distance, mistyped_subcommand};

    #[test]
    fn edit_distance_of_hand_checked_pairs() {
        assert_eq!(edit_distance("inpsect", "inspect"), 2);
        assert_eq!(edit_distance("resme", "resume"), 1);
        assert_eq!(edit_distance("", "plot"), 4);
        assert_eq!(edit_distance("bench", "bench"), 0);
    }

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
