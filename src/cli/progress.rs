//! Progress reports on stderr: an indicatif bar on a terminal, plain log lines otherwise,
//! nothing under `--quiet`. Timings live here only, never in the run's files.

use crate::cli::console::errln;

use berry_evolve::record::fitness_csv::FitnessRow;
use berry_evolve::run::Progress;
use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;
use std::path::Path;
use std::time::Instant;

/// Chooses the reporter for this terminal and flags.
pub fn reporter(quiet: bool) -> Box<dyn Progress> {
    if quiet {
        Box::new(berry_evolve::run::Silent)
    } else if std::io::stderr().is_terminal() {
        Box::new(Bar { bar: None })
    } else {
        Box::new(Lines { started: None })
    }
}

struct Bar {
    bar: Option<ProgressBar>,
}

impl Progress for Bar {
    fn begin(&mut self, first: u64, total: u64) {
        let bar = ProgressBar::new(total);
        bar.set_position(first);
        bar.set_style(
            ProgressStyle::with_template(
                "{spinner} gen {pos}/{len} [{bar:30}] {msg} ({elapsed}, eta {eta})",
            )
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
        );
        bar.reset_eta();
        self.bar = Some(bar);
    }
    fn generation(&mut self, row: &FitnessRow) {
        if let Some(bar) = &self.bar {
            bar.set_message(format!(
                "best {:.3}  mean {:.3}  best ever {:.3}",
                row.best, row.mean, row.best_ever
            ));
            bar.set_position(row.generation + 1);
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
