//! The `berry-evolve` command: parses the command line, runs it, and prints errors as a cause
//! chain with a non-zero exit code (never a panic or a backtrace for bad input).

use cli::console::errln;

mod cli;

use clap::Parser;

fn main() {
    // First, before any code that may use them: does this CPU have the extensions this
    // build was compiled for (.cargo/config.toml)?
    if !berry_evolve::cpu::runs_here() {
        cpu_exit();
    }
    berry_evolve::invocation::init();
    if let Some(message) = std::env::args()
        .nth(1)
        .and_then(|a| cli::mistyped_subcommand(&a))
    {
        errln!("error: {message}");
        std::process::exit(2);
    }
    let cli = cli::Cli::parse();
    // Under mpirun (a build with the `mpi` feature): ranks other than 0 serve rank 0's
    // evaluation jobs until it is done and exit here; rank 0 runs the command. (Every rank
    // parses the command line first, so a mistyped one stops them all alike.)
    #[cfg(feature = "mpi")]
    let ranks = mpi_role();
    #[cfg(feature = "mpi")]
    let joined = ranks.as_ref();
    #[cfg(not(feature = "mpi"))]
    let joined = None;
    let result = cli::dispatch(cli, joined).and_then(|()| match cli::console::stdout_error() {
        Some(e) => Err(anyhow::anyhow!("cannot write to standard output: {e}")),
        None => Ok(()),
    });
    let code = exit_code(result);
    #[cfg(feature = "mpi")]
    if let Some(ranks) = ranks {
        // Whatever the command did (finished, failed, was stopped), after its message:
        // release the workers, then finalise MPI.
        ranks.stop_workers();
        drop(ranks);
    }
    if code != 0 {
        std::process::exit(code);
    }
}

/// The longest word (a path, a quoted value) an error message shows whole.
const MAX_QUOTED: usize = 300;

/// Prints a failed command's error as a cause chain and returns the exit code.
fn exit_code(result: anyhow::Result<()>) -> i32 {
    let Err(error) = result else {
        return 0;
    };
    // A reader that closed the pipe (`berry-evolve inspect x.toml | head`) is not an error.
    if error.chain().any(|c| {
        c.downcast_ref::<std::io::Error>()
            .is_some_and(|e| e.kind() == std::io::ErrorKind::BrokenPipe)
    }) {
        return 0;
    }
    // A deliberate Ctrl-C (or SIGTERM) that stopped the run after a checkpoint is not an
    // error: say what happened and how to go on, and exit 130 as shells expect.
    let interrupted = error
        .downcast_ref::<berry_evolve::run::RunError>()
        .is_some_and(|e| matches!(e, berry_evolve::run::RunError::Interrupted { .. }));
    // Messages quote what the user gave (names, paths, values): a huge one is cut, never
    // echoed whole.
    let short = |text: String| berry_evolve::input::cut_long_words(&text, MAX_QUOTED);
    if interrupted {
        errln!("stopped: {}", short(error.to_string()));
        return 130;
    }
    errln!("error: {}", short(error.to_string()));
    for cause in error.chain().skip(1) {
        errln!("  caused by: {}", short(cause.to_string()));
    }
    1
}

/// Joins the MPI job when started by mpirun: a worker rank serves and exits; rank 0 gets the
/// other ranks (`None` when not started by mpirun). A job whose ranks cannot all start is
/// stopped here with a message naming the rank.
#[cfg(feature = "mpi")]
fn mpi_role() -> Option<berry_evolve::evo::ranks::Ranks> {
    use berry_evolve::evo::ranks::{self, Role};
    if !ranks::launched_by_mpi() {
        return None;
    }
    match ranks::join() {
        Ok(Role::Coordinator(ranks)) => Some(ranks),
        Ok(Role::Worker(worker)) => {
            ranks::worker::serve(worker);
            std::process::exit(0);
        }
        Err(error) => {
            errln!("error: {error}");
            std::process::exit(1);
        }
    }
}

/// Says that this CPU lacks extensions the build uses, and exits. Nothing computed: this
/// code runs on such a CPU (see `berry_evolve::cpu::runs_here`).
#[cold]
#[inline(never)]
fn cpu_exit() -> ! {
    use std::io::Write;
    let _ = std::io::stderr().write_all(berry_evolve::cpu::MESSAGE.as_bytes());
    std::process::exit(1);
}
