//! `config`: the experiment file described from the code. `--schema` prints its JSON Schema
//! (for editors: taplo, Even Better TOML), `--reference` the page of every key with type,
//! unit, default, range and report section (`docs/experiment-reference.md`), `--defaults` a
//! complete commented experiment file with every key at its default.

use super::console::outln;
use berry_evolve::experiment::reference;
use clap::Args;

/// Arguments of `config`: exactly one of the three outputs.
#[derive(Debug, Args)]
#[group(required = true, multiple = false)]
pub struct ConfigArgs {
    /// Print the JSON Schema of the experiment file (as docs/experiment.schema.json); for
    /// taplo or Even Better TOML, put `#:schema PATH` on an experiment file's first line.
    #[arg(long)]
    pub schema: bool,
    /// Print the reference of every key as Markdown (as docs/experiment-reference.md).
    #[arg(long)]
    pub reference: bool,
    /// Print a complete experiment file with every key at its default, each commented with
    /// its meaning, unit, range and report section; it runs as it stands
    /// (`berry-evolve config --defaults > mine.toml`).
    #[arg(long)]
    pub defaults: bool,
}

/// Prints the chosen description on standard output.
pub fn run(args: ConfigArgs) -> anyhow::Result<()> {
    let text = if args.schema {
        format!("{}\n", serde_json::to_string_pretty(&reference::schema())?)
    } else if args.reference {
        reference::reference_markdown()
    } else {
        reference::defaults_toml()
    };
    for line in text.lines() {
        outln!("{line}");
    }
    Ok(())
}
