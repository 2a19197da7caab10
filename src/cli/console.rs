//! Console output that never panics: `outln!` (stdout) and `errln!` (stderr) write a line and
//! ignore failure, because a closed pipe (`| head`, a `tee` killed by Ctrl-C) or a full device
//! must stop the printing, not the run (which still stops gracefully and writes its checkpoint).
//! After the first failed write to a stream, nothing more is written to it.

use std::io::Write;
use std::sync::atomic::{AtomicBool, Ordering};

static STDOUT_GONE: AtomicBool = AtomicBool::new(false);
static STDERR_GONE: AtomicBool = AtomicBool::new(false);

/// Writes one formatted line to stdout unless an earlier write to it failed.
pub fn out(args: std::fmt::Arguments<'_>) {
    write_line(&mut std::io::stdout().lock(), &STDOUT_GONE, args);
}

/// Writes one formatted line to stderr unless an earlier write to it failed.
pub fn err(args: std::fmt::Arguments<'_>) {
    write_line(&mut std::io::stderr().lock(), &STDERR_GONE, args);
}

fn write_line(w: &mut impl Write, gone: &AtomicBool, args: std::fmt::Arguments<'_>) {
    if gone.load(Ordering::Relaxed) {
        return;
    }
    if w.write_fmt(args)
        .and_then(|()| w.write_all(b"\n"))
        .and_then(|()| w.flush())
        .is_err()
    {
        gone.store(true, Ordering::Relaxed);
    }
}

/// `println!` that never panics (see the module doc).
macro_rules! outln {
    () => { $crate::cli::console::out(format_args!("")) };
    ($($arg:tt)*) => { $crate::cli::console::out(format_args!($($arg)*)) };
}

/// `eprintln!` that never panics (see the module doc).
macro_rules! errln {
    () => { $crate::cli::console::err(format_args!("")) };
    ($($arg:tt)*) => { $crate::cli::console::err(format_args!($($arg)*)) };
}

pub(crate) use {errln, outln};
