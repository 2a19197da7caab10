//! `berry-evolve new NAME --from TEMPLATE`: write a new experiment file from one of the
//! experiments built into the program (`experiment::templates`), comments and all, so an
//! installed binary can start work in any folder.

use crate::cli::console::outln;

use anyhow::Context;
use berry_evolve::experiment::templates::{self, Template, TEMPLATES};
use berry_evolve::invocation::program;
use berry_evolve::record::atomic::write_atomic;
use clap::Args;
use std::path::{Path, PathBuf};

/// Arguments of `new`.
#[derive(Debug, Args)]
#[command(
    after_help = "Examples:\n  berry-evolve new --list\n  berry-evolve new my-foragers \
                        --from foraging\n  berry-evolve new maze --from t-maze -o runs/maze.toml"
)]
pub struct NewArgs {
    /// Name of the new experiment: its `name` key, the file NAME.toml and the run folder
    /// results/NAME/seed-<seed>/ (a plain folder name).
    #[arg(required_unless_present = "list")]
    pub name: Option<String>,
    /// The built-in experiment to start from (`--list` names them); the file is written as
    /// shipped in experiments/, comments included, with only its `name` changed.
    #[arg(long, default_value = "foraging")]
    pub from: String,
    /// Where to write it (default: NAME.toml in the current folder; a folder: NAME.toml in it).
    #[arg(long, short)]
    pub out: Option<PathBuf>,
    /// Replace an existing file.
    #[arg(long)]
    pub force: bool,
    /// List the built-in experiments with what each is for.
    #[arg(long, conflicts_with_all = ["name", "out", "force"])]
    pub list: bool,
}

/// Runs the subcommand.
pub fn run(args: NewArgs) -> anyhow::Result<()> {
    if args.list {
        list();
        return Ok(());
    }
    let name = args.name.as_deref().unwrap_or_default();
    let template = templates::find(&args.from).ok_or_else(|| unknown_template(&args.from))?;
    let path = match &args.out {
        Some(out) if out.is_dir() => out.join(format!("{name}.toml")),
        Some(out) => out.clone(),
        None => PathBuf::from(format!("{name}.toml")),
    };
    // symlink_metadata: a dangling link is an existing name too.
    if !args.force && std::fs::symlink_metadata(&path).is_ok() {
        anyhow::bail!(
            "{} already exists; choose another name or -o PATH, or replace it with --force",
            path.display()
        );
    }
    let text = template
        .with_name(name, &path)
        .with_context(|| format!("cannot name the experiment `{name}`"))?;
    write_atomic(&path, text.as_bytes())
        .with_context(|| format!("cannot write {}", path.display()))?;
    written(template, name, &path, &text)
}

/// Says what was written and what to do next.
fn written(template: &Template, name: &str, path: &Path, text: &str) -> anyhow::Result<()> {
    let experiment = berry_evolve::experiment::Experiment::from_toml(text, path)?;
    let file = berry_evolve::invocation::shell_word(&path.to_string_lossy());
    outln!(
        "wrote {file}: the built-in {} named `{name}`: {}",
        template.file,
        template.purpose()
    );
    outln!(
        "next: `{p} inspect {file}` shows its inputs and workload; `{p} {file}` runs it, \
         writing into {} (relative to the folder you run it in; --out to choose)",
        experiment.default_run_dir().display(),
        p = program()
    );
    Ok(())
}

/// `new --list`: one line per template, its name and its purpose.
fn list() {
    let width = TEMPLATES.iter().map(|t| t.name.len()).max().unwrap_or(0);
    for t in TEMPLATES {
        outln!("{:width$}  {}", t.name, t.purpose());
    }
}

/// The error for a `--from` that names no template, with the closest name when one is close.
fn unknown_template(asked: &str) -> anyhow::Error {
    let names = || TEMPLATES.iter().map(|t| t.name);
    // A unique prefix (`forag`) is as likely a meaning as a typo.
    let mut prefixed = names().filter(|n| n.starts_with(asked) && !asked.is_empty());
    let prefix = match (prefixed.next(), prefixed.next()) {
        (Some(only), None) => Some(only),
        _ => None,
    };
    let suggestion = prefix
        .or_else(|| berry_evolve::input::closest(asked, names()))
        .map_or(String::new(), |best| format!("did you mean `{best}`? "));
    anyhow::anyhow!(
        "there is no built-in experiment `{asked}`; {suggestion}`{} new --list` names them all",
        program()
    )
}
