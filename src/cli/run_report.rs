//! The end-of-run summary of `run` and `resume`: where the results are, the best individual,
//! the validation champion, the held-out check (did it work?, `cli::check`), how to look at
//! the champion and how to go on, printed as text on stderr or, with `--json`, as one JSON
//! document on stdout (also when the run was interrupted, before the `stopped:` line). Both
//! forms are printed from [`RunOutcome`], so they carry the same numbers.

use crate::cli::check::{self, CheckReport};
use crate::cli::compare::fitness_text;
use crate::cli::console::{errln, outln};
use crate::cli::json;
use berry_evolve::invocation::{program, shell_word};
use std::path::PathBuf;

use berry_evolve::run::{RunError, RunSummary, BEST_FILE};
use serde::Serialize;

/// How a run ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Status {
    /// All its generations are done.
    Done,
    /// Stopped by Ctrl-C or SIGTERM after a checkpoint; `resume` continues it.
    Interrupted,
}

/// The best individual of training (the `best_ever` column of fitness.csv).
#[derive(Debug, Serialize)]
pub struct BestReport {
    /// Its fitness in the generation it was evaluated in.
    pub fitness: f64,
    /// That generation (from 0).
    pub generation: u64,
    /// Its index in that generation.
    pub individual: u64,
    /// Its mean final metabolic vector over that generation's trials (A, B, C, D).
    pub metabolism: [f64; 4],
}

/// The best individual on the validation worlds (`[validation]` on): the one best.json holds.
#[derive(Debug, Serialize)]
pub struct ValidationReport {
    /// Its fitness on the validation worlds (`null` when not finite).
    pub fitness: Option<f64>,
    /// The generation it was validated after.
    pub generation: u64,
    /// Its index in that generation (`null`: not a population member, e.g. PGPE's centre).
    pub individual: Option<u64>,
    /// Its training fitness in that generation, when it has one.
    pub training_fitness: Option<f64>,
}

/// Where one run stands at its end.
#[derive(Debug, Serialize)]
pub struct RunOutcome {
    /// Done or interrupted.
    pub status: Status,
    /// The run folder.
    pub run_dir: String,
    /// Generations completed in total (the rows of fitness.csv).
    pub generations_done: u64,
    /// The best individual of training, if any had a finite fitness.
    pub best_ever: Option<BestReport>,
    /// The validation champion, when the experiment validates.
    pub validation: Option<ValidationReport>,
    /// The best genome's file, when written.
    pub best_json: Option<String>,
    /// The last checkpoint written.
    pub checkpoint: Option<String>,
    /// The command that continues the run (add `--generations N` to extend a finished one).
    pub resume_command: String,
    /// The held-out check of a finished run (`run` and `resume`; absent with --no-check, for
    /// an interrupted run, without best.json, and for the seeds of `run --seeds`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub check: Option<CheckReport>,
    /// Why a check that was asked for could not be made, when it could not.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub check_failed: Option<String>,
    /// Commands that show the champion: a picture of one trial (`render`) and an animated
    /// page (`replay --html`), with the run folder's real paths (`run` and `resume`).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub look: Vec<String>,
}

impl RunOutcome {
    /// The outcome that `summary` describes.
    pub fn new(status: Status, summary: &RunSummary) -> RunOutcome {
        let best = summary.dir.join(BEST_FILE);
        RunOutcome {
            status,
            run_dir: summary.dir.display().to_string(),
            generations_done: summary.generations,
            best_ever: summary.best_ever.as_ref().map(|c| BestReport {
                fitness: c.fitness,
                generation: c.generation,
                individual: c.individual,
                metabolism: c.metabolism,
            }),
            validation: summary.validated_best.as_ref().map(|v| ValidationReport {
                fitness: v.validation.fitness,
                generation: v.generation,
                individual: v.individual,
                training_fitness: v.training_fitness,
            }),
            best_json: best.is_file().then(|| best.display().to_string()),
            checkpoint: summary.checkpoint.as_ref().map(|p| p.display().to_string()),
            resume_command: format!(
                "{} resume {}",
                berry_evolve::invocation::program(),
                summary.dir.display()
            ),
            check: None,
            check_failed: None,
            look: Vec::new(),
        }
    }

    /// The commands that show best.json, when the run has one.
    fn look_commands(&self) -> Vec<String> {
        let Some(best) = &self.best_json else {
            return Vec::new();
        };
        let dir = std::path::Path::new(&self.run_dir);
        let word = |p: &std::path::Path| shell_word(&p.display().to_string());
        let (best, experiment) = (
            word(std::path::Path::new(best)),
            word(&dir.join(berry_evolve::run::EXPERIMENT_FILE)),
        );
        vec![
            format!("{} render {best} --experiment {experiment}", program()),
            format!(
                "{} replay {best} --experiment {experiment} --trial 0 --html {}",
                program(),
                word(&dir.join("best.html"))
            ),
        ]
    }

    /// Prints the text summary on stderr (the run's product is its folder, not stdout).
    pub fn print_text(&self) {
        if let Some(best) = &self.best_ever {
            errln!(
                "done: {} generations; best ever {:.4} (generation {}, individual {}), metabolism [{}]",
                self.generations_done,
                best.fitness,
                best.generation,
                best.individual,
                best.metabolism.map(|m| format!("{m:.4}")).join(", ")
            );
        }
        if let Some(v) = &self.validation {
            let fitness = fitness_text(v.fitness);
            errln!(
                "validation champion (best.json): fitness {fitness} on the validation worlds \
                 (generation {}{})",
                v.generation,
                v.individual
                    .map_or(String::new(), |i| format!(", individual {i}"))
            );
        }
        if let Some(c) = &self.check {
            for line in c.lines() {
                errln!("{line}");
            }
        }
        if let Some(why) = &self.check_failed {
            errln!("held-out check not made: {why}");
        }
        // A MAP-Elites run also has its archive (only then, so other runs' words stay).
        let archive = std::path::Path::new(&self.run_dir)
            .join("archive.csv")
            .is_file();
        errln!(
            "results in {}: fitness.csv, best.json, checkpoints/{}",
            self.run_dir,
            if archive {
                ", archive.csv (plot draws it; extract --cell I,J takes an elite)"
            } else {
                ""
            }
        );
        if let [render, replay] = self.look.as_slice() {
            errln!(
                "look at the champion: {render}  (draws its path in trial 0 as best-trial-0.svg)"
            );
            errln!("  or watch it move: {replay}  (open best.html in a browser)");
        }
    }

    /// The one-line text of a replicate (`run --seeds`) on stdout.
    fn seed_line(&self, seed: u64, continued: bool) -> String {
        let how = if continued { " (continued)" } else { "" };
        match &self.best_ever {
            Some(best) => format!(
                "seed {seed}{how}: {} generations, best ever {:.4} (generation {}, individual {}); results in {}",
                self.generations_done, best.fitness, best.generation, best.individual, self.run_dir
            ),
            None => format!(
                "seed {seed}{how}: {} generations, no finite fitness; results in {}",
                self.generations_done, self.run_dir
            ),
        }
    }
}

/// `run --json` / `resume --json`: one run.
#[derive(Debug, Serialize)]
struct RunDocument<'a> {
    /// `berry-evolve/run/1` (`resume` reports the same shape).
    schema: &'static str,
    #[serde(flatten)]
    run: &'a RunOutcome,
}

/// Whether and how a finished run is checked on held-out worlds (`cli::check`).
#[derive(Debug, Clone)]
pub struct CheckRequest {
    /// False with `--no-check`.
    pub enabled: bool,
    /// Worker threads (0: one per core), as the run's.
    pub jobs: usize,
    /// The baseline genome resolved from the experiment file the run was started from
    /// (`run`; `resume` finds the run folder's copy).
    pub baseline: Option<PathBuf>,
}

/// Reports the end of a run: as text on stderr (unless `quiet`), or as JSON on stdout. A
/// finished run is first checked on held-out worlds as `check` says (not when its result
/// would not be shown: `--quiet` without `--json`). An interrupted run is reported as JSON
/// too, then its error is returned so that `main` says `stopped:` and exits 130; other
/// errors are returned untouched.
pub fn finish(
    result: Result<RunSummary, RunError>,
    json_output: bool,
    quiet: bool,
    check: CheckRequest,
) -> anyhow::Result<()> {
    let (status, summary) = match &result {
        Ok(summary) => (Status::Done, summary),
        Err(RunError::Interrupted { summary, .. }) if json_output => {
            (Status::Interrupted, summary.as_ref())
        }
        Err(_) => return Ok(result.map(drop)?),
    };
    let mut outcome = RunOutcome::new(status, summary);
    outcome.look = outcome.look_commands();
    if status == Status::Done && check.enabled && (json_output || !quiet) {
        // The run is done and its files are written: a failed check is said, not an error.
        match check::held_out_check(summary, check.jobs, check.baseline.as_deref()) {
            Ok(report) => outcome.check = report,
            Err(e) => outcome.check_failed = Some(format!("{e:#}")),
        }
    }
    if json_output {
        json::print(&RunDocument {
            schema: "berry-evolve/run/1",
            run: &outcome,
        })?;
    } else if !quiet {
        outcome.print_text();
    }
    Ok(result.map(drop)?)
}

/// One replicate of `run --seeds`.
#[derive(Debug, Serialize)]
pub struct SeedRun {
    /// Its seed.
    pub seed: u64,
    /// True when an earlier run in its folder was continued rather than started.
    pub continued: bool,
    /// Where it stands.
    #[serde(flatten)]
    pub run: RunOutcome,
}

/// The replicates of `run --seeds`, reported one line each as they finish or, with `--json`,
/// as one document at the end.
pub struct SeedsReport {
    json_output: bool,
    runs: Vec<SeedRun>,
}

/// `run --seeds --json`.
#[derive(Debug, Serialize)]
struct SeedsDocument<'a> {
    /// `berry-evolve/run-seeds/1`.
    schema: &'static str,
    /// Each seed's run, in the order run.
    runs: &'a [SeedRun],
}

impl SeedsReport {
    /// An empty report.
    pub fn new(json_output: bool) -> SeedsReport {
        SeedsReport {
            json_output,
            runs: Vec::new(),
        }
    }

    /// Records seed `seed`'s result: prints its line (text) or keeps it (JSON). An
    /// interrupted replicate ends the batch: with `--json` the document is printed with it;
    /// then its error is returned, as any other.
    pub fn add(
        &mut self,
        seed: u64,
        continued: bool,
        result: Result<RunSummary, RunError>,
    ) -> anyhow::Result<()> {
        let run = match &result {
            Ok(summary) => RunOutcome::new(Status::Done, summary),
            Err(RunError::Interrupted { summary, .. }) if self.json_output => {
                RunOutcome::new(Status::Interrupted, summary)
            }
            Err(_) => return Ok(result.map(drop)?),
        };
        if !self.json_output {
            outln!("{}", run.seed_line(seed, continued));
        }
        let interrupted = run.status == Status::Interrupted;
        self.runs.push(SeedRun {
            seed,
            continued,
            run,
        });
        if interrupted {
            self.print()?;
        }
        Ok(result.map(drop)?)
    }

    /// Prints the JSON document (nothing in text mode, whose lines are already out).
    pub fn print(&self) -> anyhow::Result<()> {
        if self.json_output {
            json::print(&SeedsDocument {
                schema: "berry-evolve/run-seeds/1",
                runs: &self.runs,
            })?;
        }
        Ok(())
    }
}
