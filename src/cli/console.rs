//! Console output that never panics: `outln!` (stdout) and `errln!` (stderr) write a line and
//! ignore failure, because a closed pipe (`| head`, a `tee` killed by Ctrl-C) or a full device
//! must stop the printing, not the run (which still stops gracefully and writes its checkpoint).
//! After the first failed write to a stream, nothing more is written to it.
//!
//! For the commands whose product is their standard output (`replay`, `compare`, `inspect`,
//! `export-csv`), `main` asks [`stdout_error`] at the end: a full device is an error (exit 1,
//! said on stderr), a reader that closed the pipe (`| head`) is not. The progress bar
//! (indicatif) ignores failed draws itself.

use std::io::Write;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::OnceLock;

static STDOUT_GONE: AtomicBool = AtomicBool::new(false);
static STDERR_GONE: AtomicBool = AtomicBool::new(false);
static STDOUT_ERROR: OnceLock<std::io::Error> = OnceLock::new();

/// The first failed write to stdout, if any, as an error to report (a closed pipe is none).
pub fn stdout_error() -> Option<&'static std::io::Error> {
    STDOUT_ERROR
        .get()
        .filter(|e| e.kind() != std::io::ErrorKind::BrokenPipe)
}

/// Writes one formatted line to stdout unless an earlier write to it failed.
pub fn out(args: std::fmt::Arguments<'_>) {
    if let Some(e) = write_line(&mut std::io::stdout().lock(), &STDOUT_GONE, args) {
        let _ = STDOUT_ERROR.set(e);
    }
}

/// Writes one formatted line to stderr unless an earlier write to it failed.
pub fn err(args: std::fmt::Arguments<'_>) {
    let _ = write_line(&mut std::io::stderr().lock(), &STDERR_GONE, args);
}

fn write_line(
    w: &mut impl Write,
    gone: &AtomicBool,
    args: std::fmt::Arguments<'_>,
) -> Option<std::io::Error> {
    if gone.load(Ordering::Relaxed) {
        return None;
    }
    match w
        .write_fmt(args)
        .and_then(|()| w.write_all(b"\n"))
        .and_then(|()| w.flush())
    {
        Ok(()) => None,
        Err(e) => {
            gone.store(true, Ordering::Relaxed);
            Some(e)
        }
    }
}

/// The standard stdout line macro, but one that never panics (see the module doc).
macro_rules! outln {
    () => { $crate::cli::console::out(format_args!("")) };
    ($($arg:tt)*) => { $crate::cli::console::out(format_args!($($arg)*)) };
}

/// The standard stderr line macro, but one that never panics (see the module doc).
macro_rules! errln {
    () => { $crate::cli::console::err(format_args!("")) };
    ($($arg:tt)*) => { $crate::cli::console::err(format_args!($($arg)*)) };
}

pub(crate) use {errln, outln};
