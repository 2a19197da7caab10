//! Runs stopped by signals: SIGINT/SIGTERM stop and resume, and SIGKILL at random moments.
//!
//! Kept in their own test binary: every test here starts real runs of slow.toml (a second
//! each, many times over) and signals them at moments that must fall inside a generation or
//! before the end of the run. Beside the ~40 end-to-end tests of tests/cli they would share the
//! cores with those tests' own runs, so that where a signal lands would depend on what else
//! the binary runs at the time; alone, only their own tests compete.

mod extended_runs;
mod sigint_sigterm_stop;
mod sigkill_resume;
