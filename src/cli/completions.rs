//! `completions SHELL` and `man`: shell completions and a man page for the installed binary,
//! generated from the same command-line definition the program parses (clap_complete,
//! clap_mangen), so they cannot drift from it.

use super::console::outln;
use clap::Args;

/// Arguments of `completions`.
#[derive(Debug, Args)]
pub struct CompletionsArgs {
    /// The shell to complete for: bash, zsh, fish, elvish or powershell.
    pub shell: clap_complete::Shell,
}

/// Prints the completion script for one shell of the program's `command` on standard output.
pub fn completions(args: CompletionsArgs, mut command: clap::Command) -> anyhow::Result<()> {
    let mut script = Vec::new();
    clap_complete::generate(args.shell, &mut command, "berry-evolve", &mut script);
    print_text(&script)
}

/// Prints the man page (roff) of the program's `command` on standard output.
pub fn man(command: clap::Command) -> anyhow::Result<()> {
    let mut page = Vec::new();
    clap_mangen::Man::new(command).render(&mut page)?;
    print_text(&page)
}

/// Writes generated text through the console, which stops quietly on a closed pipe.
fn print_text(bytes: &[u8]) -> anyhow::Result<()> {
    let text = String::from_utf8_lossy(bytes);
    for line in text.lines() {
        outln!("{line}");
    }
    Ok(())
}
