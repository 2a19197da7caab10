//! The workload estimate in words: what `inspect` prints, and the note (or, above an hour,
//! the warning) `run` prints on stderr before its first generation. The numbers come from
//! `berry_evolve::run::estimate`; this module only words them and decides when to warn.

use crate::cli::console::errln;
use berry_evolve::experiment::Experiment;
use berry_evolve::record::fitness_csv::FitnessRow;
use berry_evolve::run::estimate::{calibrate, Estimate, Workload, RUN_CALIBRATION_TARGET};
use berry_evolve::run::{JobHook, Progress};
use std::path::Path;
use std::time::Duration;

/// A run estimated longer than this many seconds (one hour) gets a warning before it starts.
pub const LONG_RUN_SECONDS: f64 = 3600.0;

/// A duration for people: "12 ms", "40 s", "12 min", "3 h 20 min", "4.5 days", "120 years".
pub fn duration(seconds: f64) -> String {
    const MINUTE: f64 = 60.0;
    const HOUR: f64 = 3600.0;
    const DAY: f64 = 86_400.0;
    const YEAR: f64 = 365.25 * DAY;
    if !seconds.is_finite() {
        return "forever".to_string();
    }
    if seconds < 0.1 {
        format!("{:.0} ms", (seconds * 1000.0).max(1.0))
    } else if seconds < 1.0 {
        format!("{seconds:.2} s")
    } else if seconds < 10.0 {
        format!("{seconds:.1} s")
    } else if seconds < 90.0 {
        format!("{seconds:.0} s")
    } else if seconds < HOUR {
        format!("{:.0} min", seconds / MINUTE)
    } else if seconds < 2.0 * DAY {
        let minutes = (seconds / MINUTE).round() as u64;
        format!("{} h {} min", minutes / 60, minutes % 60)
    } else if seconds < 2.0 * YEAR {
        format!("{:.1} days", seconds / DAY)
    } else {
        format!("{:.0} years", seconds / YEAR)
    }
}

/// A count with thousands separators: 256000 → "256,000".
pub fn count(n: u64) -> String {
    let digits = n.to_string();
    let mut out = String::with_capacity(digits.len() + digits.len() / 3);
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i) % 3 == 0 {
            out.push(',');
        }
        out.push(c);
    }
    out
}

/// The workload lines: per generation, validation (when on), and the whole run.
pub fn workload_lines(w: &Workload) -> Vec<String> {
    let world = match w.creatures_per_world {
        1 => String::new(),
        k => format!(", {k} creatures per world"),
    };
    let episodes = match w.episodes {
        1 => String::new(),
        k => format!(" × {k} episodes"),
    };
    let mut lines = vec![format!(
        "workload: {} individuals × {} trials{episodes} × {} ticks = {} creature-ticks per generation{world}",
        count(w.individuals),
        count(w.trials),
        count(w.ticks),
        count(w.creature_ticks_per_generation),
    )];
    if w.validations > 0 {
        lines.push(format!(
            "validation: {} rounds × up to {} candidates × {} worlds{episodes} × {} ticks = {} creature-ticks",
            count(w.validations),
            count(w.validation_candidates),
            count(w.validation_trials),
            count(w.ticks),
            count(w.validation_creature_ticks),
        ));
    }
    let plus = if w.validations > 0 {
        " + validation"
    } else {
        ""
    };
    lines.push(format!(
        "whole run: {} generations × {} creature-ticks{plus} = {} creature-ticks",
        count(w.generations),
        count(w.creature_ticks_per_generation),
        count(w.total_creature_ticks),
    ));
    lines
}

/// The estimate's time and what it is based on, in two lines.
pub fn time_lines(e: &Estimate) -> Vec<String> {
    let c = &e.calibration;
    let shortened = if c.ticks < e.workload.ticks {
        format!(" (lives shortened to {} ticks to time them)", c.ticks)
    } else {
        String::new()
    };
    let episodes = match e.workload.episodes {
        1 => String::new(),
        k => format!(" × {k} episodes"),
    };
    vec![
        format!(
            "estimated wall time: {} ({} per generation) on {} worker thread{}",
            duration(e.total_seconds),
            duration(e.seconds_per_generation),
            c.threads,
            if c.threads == 1 { "" } else { "s" }
        ),
        format!(
            "  based on {} creature-ticks per second measured just now on this machine: \
             generation 0's first {} individuals × {} trials{episodes} × {} ticks{shortened}, in {:.2} s; \
             evaluation only, and evolved creatures may live longer or shorter lives than \
             random ones",
            count(c.rate().round() as u64),
            count(c.individuals),
            count(c.trials),
            count(c.ticks),
            c.elapsed_seconds,
        ),
    ]
}

/// The one line `run` prints before it starts.
pub fn run_line(e: &Estimate) -> String {
    let c = &e.calibration;
    format!(
        "estimated wall time: {} for {} generations ({} each) on {} worker thread{}, from {} \
         creature-ticks per second measured just now (`berry-evolve inspect` says more; \
         --no-estimate skips it)",
        duration(e.total_seconds),
        count(e.workload.generations),
        duration(e.seconds_per_generation),
        c.threads,
        if c.threads == 1 { "" } else { "s" },
        count(c.rate().round() as u64),
    )
}

/// Calibrates for `experiment` on `jobs` threads and estimates `generations` of it; `None`
/// (after saying why on stderr) when the calibration cannot run, which the run itself will
/// then report.
pub fn estimate(
    experiment: &Experiment,
    jobs: usize,
    generations: std::ops::Range<u64>,
    target: Duration,
) -> Option<Estimate> {
    match calibrate(experiment, jobs, target) {
        Ok(c) => Some(Estimate::new(Workload::of(experiment, generations), c)),
        Err(e) => {
            errln!("note: no time estimate: {e}");
            None
        }
    }
}

/// The warning for a run estimated above [`LONG_RUN_SECONDS`], or `None`.
pub fn long_run_warning(e: &Estimate, what: &str) -> Option<String> {
    (e.total_seconds > LONG_RUN_SECONDS).then(|| {
        format!(
            "warning: {what} is estimated to take {} ({} per generation). It starts now; \
             Ctrl-C stops it after the current generation (with a checkpoint to resume \
             from). To make it shorter: --generations N, or in the experiment file fewer \
             evolution.population, evaluation.trials or evaluation.ticks (shorter \
             generations). --no-estimate skips this check.",
            duration(e.total_seconds),
            duration(e.seconds_per_generation)
        )
    })
}

/// A reporter that, when the run really starts (its folder locked and checked), calibrates,
/// prints the estimate for the generations still to run (unless quiet) and the long-run
/// warning (even when quiet: a run of hours should not start unannounced), then reports as
/// `inner` does.
pub struct Announced {
    /// The reporter that does the rest.
    pub inner: Box<dyn Progress>,
    /// The experiment being run (with its overrides).
    pub experiment: Experiment,
    /// `--jobs` (0: one per core).
    pub jobs: usize,
    /// `--quiet`: only the warning, not the estimate.
    pub quiet: bool,
}

impl Progress for Announced {
    fn begin(&mut self, first: u64, total: u64) {
        if let Some(e) = estimate(
            &self.experiment,
            self.jobs,
            first..total,
            RUN_CALIBRATION_TARGET,
        ) {
            if !self.quiet {
                errln!("{}", run_line(&e));
            }
            if let Some(w) = long_run_warning(&e, "this run") {
                errln!("{w}");
            }
        }
        self.inner.begin(first, total);
    }
    fn generation(&mut self, row: &FitnessRow) {
        self.inner.generation(row);
    }
    fn checkpoint(&mut self, path: &Path) {
        self.inner.checkpoint(path);
    }
    fn end(&mut self) {
        self.inner.end();
    }
    fn note(&mut self, message: &str) {
        self.inner.note(message);
    }
    fn within_generation(&mut self, jobs_per_generation: u64) -> Option<JobHook> {
        self.inner.within_generation(jobs_per_generation)
    }
}

#[cfg(test)]
mod tests {
    use super::{count, duration};

    #[test]
    fn durations_and_counts_in_words() {
        assert_eq!(duration(0.0123), "12 ms");
        assert_eq!(duration(0.0), "1 ms");
        assert_eq!(duration(0.145), "0.14 s");
        assert_eq!(duration(5.25), "5.2 s");
        assert_eq!(duration(42.4), "42 s");
        assert_eq!(duration(600.0), "10 min");
        assert_eq!(duration(3.0 * 3600.0 + 20.0 * 60.0), "3 h 20 min");
        assert_eq!(duration(4.5 * 86_400.0), "4.5 days");
        assert_eq!(duration(100.0 * 365.25 * 86_400.0), "100 years");
        assert_eq!(count(0), "0");
        assert_eq!(count(999), "999");
        assert_eq!(count(256_000), "256,000");
        assert_eq!(count(1_234_567), "1,234,567");
    }
}
