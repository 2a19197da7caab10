//! Progress reports on stderr: an indicatif bar on a terminal, plain log lines otherwise,
//! nothing under `--quiet`. Timings live here only, never in the run's files.
//!
//! The bar counts evaluation jobs, not generations, so that it (and its eta) moves within a
//! long generation: each finished job advances it by one ([`Progress::within_generation`]),
//! and the text shows the generations done and the jobs done in the current one. The log
//! lines count nothing within a generation, so without a terminal there is no cost at all.

use crate::cli::console::errln;

use berry_evolve::record::fitness_csv::FitnessRow;
use berry_evolve::run::{JobHook, Progress};
use indicatif::{ProgressBar, ProgressState, ProgressStyle};
use std::io::IsTerminal;
use std::path::Path;
use std::sync::Arc;
use std::time::{Duration, Instant};

/// Chooses the reporter for this terminal and flags.
pub fn reporter(quiet: bool) -> Box<dyn Progress> {
    if quiet {
        Box::new(berry_evolve::run::Silent)
    } else if std::io::stderr().is_terminal() {
        Box::new(Bar { bar: None, jobs: 1 })
    } else {
        Box::new(Lines { started: None })
    }
}

struct Bar {
    bar: Option<ProgressBar>,
    /// Evaluation jobs per generation: the bar's unit is one job.
    jobs: u64,
}

impl Bar {
    /// The bar: made hidden by whichever of `within_generation` and `begin` comes first
    /// (the job hook needs it before the first generation starts), drawn from `begin` on.
    fn bar(&mut self) -> &ProgressBar {
        self.bar.get_or_insert_with(ProgressBar::hidden)
    }
}

impl Progress for Bar {
    fn within_generation(&mut self, jobs_per_generation: u64) -> Option<JobHook> {
        self.jobs = jobs_per_generation.max(1);
        let bar = self.bar().clone();
        // ProgressBar::inc is an atomic add (drawing is rate-limited), so worker threads may
        // call it; the count never reaches the evaluation's results.
        Some(Arc::new(move || bar.inc(1)))
    }
    fn begin(&mut self, first: u64, total: u64) {
        let jobs = self.jobs;
        let bar = self.bar().clone();
        bar.set_style(
            ProgressStyle::with_template(
                "{spinner} gen {gen}/{gens} [{bar:30}] {within}{msg} ({elapsed}, eta {eta})",
            )
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .with_key(
                "gen",
                move |s: &ProgressState, w: &mut dyn std::fmt::Write| {
                    let _ = write!(w, "{}", s.pos() / jobs);
                },
            )
            .with_key(
                "gens",
                move |s: &ProgressState, w: &mut dyn std::fmt::Write| {
                    let _ = write!(w, "{}", s.len().unwrap_or(0) / jobs);
                },
            )
            .with_key(
                "within",
                move |s: &ProgressState, w: &mut dyn std::fmt::Write| {
                    // Within a generation of several jobs: how many are done.
                    if jobs > 1 && s.pos() < s.len().unwrap_or(0) {
                        let _ = write!(w, "job {}/{jobs}  ", s.pos() % jobs);
                    }
                },
            )
            .progress_chars("=> "),
        );
        bar.set_length(total.saturating_mul(jobs));
        bar.set_position(first.saturating_mul(jobs));
        bar.reset_eta();
        // Redraw (elapsed, spinner) when jobs are minutes long.
        bar.set_draw_target(indicatif::ProgressDrawTarget::stderr());
        bar.enable_steady_tick(Duration::from_millis(500));
    }
    fn generation(&mut self, row: &FitnessRow) {
        if let Some(bar) = &self.bar {
            bar.set_message(format!(
                "best {:.3}  mean {:.3}  best ever {:.3}",
                row.best, row.mean, row.best_ever
            ));
            bar.set_position((row.generation + 1).saturating_mul(self.jobs));
        }
    }
    fn checkpoint(&mut self, _: &Path) {}
    fn end(&mut self) {
        if let Some(bar) = self.bar.take() {
            bar.finish();
        }
    }
    fn note(&mut self, message: &str) {
        match &self.bar {
            Some(bar) => bar.println(format!("note: {message}")),
            None => errln!("note: {message}"),
        }
    }
}

struct Lines {
    started: Option<(Instant, u64, u64)>,
}

impl Progress for Lines {
    fn begin(&mut self, first: u64, total: u64) {
        self.started = Some((Instant::now(), first, total));
    }
    fn generation(&mut self, row: &FitnessRow) {
        let (elapsed, total) = self
            .started
            .map_or((0.0, 0), |(t, _, total)| (t.elapsed().as_secs_f64(), total));
        errln!(
            // The generation as the files number it (from 0, the CSV row and the checkpoint
            // name), then how many of the run's generations are done.
            "generation {:>4} ({}/{total} done): best {:.4} mean {:.4} median {:.4} best ever {:.4} ({elapsed:.1} s)",
            row.generation,
            row.generation + 1,
            row.best,
            row.mean,
            row.median,
            row.best_ever
        );
    }
    fn checkpoint(&mut self, path: &Path) {
        errln!("checkpoint {}", path.display());
    }
    fn end(&mut self) {}
    fn note(&mut self, message: &str) {
        errln!("note: {message}");
    }
}
