//! The held-out check at the end of `run` and `resume`: "did it work?" in one line. The
//! champion (best.json) meets a few random genomes and, when the experiment names one
//! (`[output] baseline`), its hand-designed baseline on a few held-out worlds that evolution
//! never saw (the first trials of `compare`'s held-out set, generation 2^40), evaluated by
//! `compare` itself, so the numbers are those `compare --trials N --random 5` prints.
//!
//! The number of worlds is chosen so that the check costs at most [`CHECK_SHARE`] of the
//! run's creature-ticks (at least one world, at most [`MAX_CHECK_WORLDS`]): a function of the
//! experiment and the generations done, never of the machine, so the verdict is reproducible.

use crate::cli::compare::{self, CompareArgs, CompareReport};
use crate::cli::worlds::WorldsChoice;
use anyhow::Context;
use berry_evolve::experiment::Experiment;
use berry_evolve::record::genome_file::GenomeFile;
use berry_evolve::run::estimate::Workload;
use berry_evolve::run::{RunSummary, BASELINE_FILE, BEST_FILE, EXPERIMENT_FILE};
use serde::Serialize;
use std::path::{Path, PathBuf};

/// Random genomes the champion meets (drawn as `compare --random` draws them).
pub const CHECK_RANDOM: u64 = 5;
/// The most held-out worlds the check uses; enough to tell a working champion from a random
/// genome, and for a long run far below its cost.
pub const MAX_CHECK_WORLDS: u64 = 10;
/// The largest share of the run's creature-ticks the check may cost (a short run still gets
/// one world, a few milliseconds).
pub const CHECK_SHARE: f64 = 0.03;

/// One genome file's result in the check.
#[derive(Debug, Serialize)]
pub struct CheckedGenome {
    /// The genome file.
    pub path: String,
    /// What it is called: the file name the experiment names, without `.json`.
    pub name: String,
    /// Its fitness over the check's worlds (`null` when not finite).
    pub fitness: Option<f64>,
}

/// The random genomes' results in the check.
#[derive(Debug, Serialize)]
pub struct RandomCheck {
    /// How many were drawn.
    pub count: u64,
    /// How many got a finite fitness (the median and best are over those).
    pub finite: usize,
    /// Their median fitness (`null` when none was finite).
    pub median: Option<f64>,
    /// Their best fitness (`null` when none was finite).
    pub best: Option<f64>,
}

/// The held-out check, as `run --json` carries it (field `check`).
#[derive(Debug, Serialize)]
pub struct CheckReport {
    /// Held-out worlds each genome lived in.
    pub worlds: u64,
    /// Whose worlds: `compare`'s held-out generation (2^40), never used in training or
    /// validation.
    pub generation: u64,
    /// The champion, best.json.
    pub champion: CheckedGenome,
    /// The random genomes.
    pub random: RandomCheck,
    /// The experiment's baseline genome (`[output] baseline`), when it names one that could
    /// be evaluated.
    pub baseline: Option<CheckedGenome>,
    /// Why the baseline the experiment names is left out (no such file, another brain).
    pub baseline_left_out: Option<String>,
    /// The verdict in words, e.g. "the champion beats every random genome, but not the
    /// baseline".
    pub verdict: String,
}

impl CheckReport {
    /// The text lines: the verdict line, and a line on a baseline left out.
    pub fn lines(&self) -> Vec<String> {
        let f = |x: Option<f64>| compare::fitness_text(x);
        let mut line = format!(
            "held-out check ({} world{} evolution never saw): champion {}, {} random genomes \
             median {} (best {})",
            self.worlds,
            if self.worlds == 1 { "" } else { "s" },
            f(self.champion.fitness),
            self.random.count,
            f(self.random.median),
            f(self.random.best),
        );
        if let Some(b) = &self.baseline {
            line.push_str(&format!(", baseline {} {}", b.name, f(b.fitness)));
        }
        line.push_str(&format!(": {}", self.verdict));
        let mut lines = vec![line];
        if let Some(why) = &self.baseline_left_out {
            lines.push(format!("  (baseline left out: {why})"));
        }
        lines
    }
}

/// `braitenberg-forager` for `../genomes/braitenberg-forager.json`.
fn genome_name(path: &Path) -> String {
    path.file_stem().map_or_else(
        || path.display().to_string(),
        |s| s.to_string_lossy().into_owned(),
    )
}

/// How many held-out worlds the check of a run of `experiment` with `generations_done`
/// generations uses: as many as fit in [`CHECK_SHARE`] of the run's creature-ticks with the
/// champion, [`CHECK_RANDOM`] random genomes and a baseline each living one life per world,
/// from 1 to [`MAX_CHECK_WORLDS`].
pub fn world_count(experiment: &Experiment, generations_done: u64) -> u64 {
    let run = Workload::of(experiment, 0..generations_done).total_creature_ticks;
    let per_world = (CHECK_RANDOM + 2).saturating_mul(experiment.evaluation.ticks.max(1));
    let worlds = (CHECK_SHARE * run as f64 / per_world as f64).floor() as u64;
    worlds.clamp(1, MAX_CHECK_WORLDS)
}

/// The verdict: how the champion's fitness `champion` compares with the random genomes'
/// median and best and, when there is one, the baseline's. A fitness that is not finite
/// (`None`) beats nothing and is beaten by everything finite.
pub fn verdict(
    champion: Option<f64>,
    median: Option<f64>,
    best: Option<f64>,
    baseline: Option<Option<f64>>,
) -> String {
    let Some(c) = champion else {
        return "the champion's fitness is not finite on these worlds (its brain produced \
                NaN or infinity): it did not work"
            .to_string();
    };
    let beats = |other: Option<f64>| other.is_none_or(|o| c > o);
    // Three grades against the random genomes.
    let (random, good) = if beats(best) {
        ("beats every random genome", true)
    } else if beats(median) {
        (
            "beats the median random genome but not the best one (more generations, or a \
             larger population, may help)",
            true,
        )
    } else {
        (
            "does no better than a typical random genome (their median): evolution found \
             little so far",
            false,
        )
    };
    match baseline {
        None => format!("the champion {random}"),
        Some(b) => match (good, beats(b)) {
            (true, true) if beats(best) => {
                "the champion beats every random genome and the baseline".to_string()
            }
            (true, true) => format!("the champion {random}; it beats the baseline"),
            (true, false) if beats(best) => {
                "the champion beats every random genome, but not the baseline".to_string()
            }
            (true, false) => format!("the champion {random}; it does not beat the baseline"),
            (false, true) => format!("the champion {random}, but it beats the baseline"),
            (false, false) => format!("the champion {random}, nor does it beat the baseline"),
        },
    }
}

/// The baseline genome file `experiment` names, resolved against `folder` (the folder of
/// the experiment file that names it), when it names one.
pub fn baseline_file(experiment: &Experiment, folder: &Path) -> Option<PathBuf> {
    let folder = if folder.as_os_str().is_empty() {
        Path::new(".")
    } else {
        folder
    };
    experiment.output.baseline_in(folder)
}

/// The baseline genome file that `experiment`, read from `file`, names (`[output] baseline`,
/// relative to `file`'s folder), with a note when it cannot be read (the check will leave it
/// out). The run folder's experiment.toml keeps the key as written, so that runs of the same
/// file have the same bytes wherever they are made; the check copies the file into the run
/// folder ([`BASELINE_FILE`]) for a later `resume`.
pub fn resolve_baseline(experiment: &Experiment, file: &Path) -> (Option<PathBuf>, Option<String>) {
    let Some(named) = baseline_file(experiment, file.parent().unwrap_or(Path::new(""))) else {
        return (None, None);
    };
    match std::fs::metadata(&named) {
        Ok(m) if m.is_file() => (Some(named), None),
        Ok(_) | Err(_) => (
            None,
            Some(format!(
                "note: the baseline genome {} that {} names ([output] baseline) cannot be \
                 read; the held-out check at the end leaves it out. Point `baseline` at a \
                 genome file of this experiment's brain (relative to the experiment file), \
                 or remove the key",
                named.display(),
                file.display()
            )),
        ),
    }
}

/// The baseline genome for the check of the run in `dir`: the run folder's copy, else
/// `source` (resolved from the experiment file the run was started from, copied into the
/// folder for later), else the key resolved against the run folder.
fn baseline_for(experiment: &Experiment, dir: &Path, source: Option<&Path>) -> Option<PathBuf> {
    let copy = dir.join(BASELINE_FILE);
    if copy.is_file() {
        return Some(copy);
    }
    if let Some(source) = source {
        if let Ok(bytes) =
            berry_evolve::input::read_regular(source, berry_evolve::input::MAX_GENOME_BYTES)
        {
            if berry_evolve::record::atomic::write_atomic(&copy, &bytes).is_ok() {
                return Some(copy);
            }
            return Some(source.to_path_buf());
        }
    }
    baseline_file(experiment, dir).filter(|p| p.is_file())
}

/// Runs the check on the run folder of `summary` on `jobs` threads (0: one per core).
/// `Ok(None)` when there is no best.json to check (no individual had a finite fitness).
pub fn held_out_check(
    summary: &RunSummary,
    jobs: usize,
    source_baseline: Option<&Path>,
) -> anyhow::Result<Option<CheckReport>> {
    let dir = &summary.dir;
    let best = dir.join(BEST_FILE);
    if !best.is_file() {
        return Ok(None);
    }
    let experiment_file = dir.join(EXPERIMENT_FILE);
    let experiment = Experiment::load(&experiment_file)?;
    let worlds = world_count(&experiment, summary.generations);
    let mut genomes = vec![best.clone()];
    let mut baseline_left_out = None;
    match baseline_for(&experiment, dir, source_baseline) {
        Some(path) => match GenomeFile::load(&path)
            .map_err(anyhow::Error::from)
            .and_then(|g| Ok(g.topology_for(&experiment, &path)?))
        {
            Ok(_) => genomes.push(path),
            Err(e) => baseline_left_out = Some(format!("{e:#}")),
        },
        None => {
            if let Some(key) = &experiment.output.baseline {
                baseline_left_out = Some(format!(
                    "{key} ([output] baseline) is not there, relative to the experiment \
                     file, and {} holds no {BASELINE_FILE}",
                    dir.display()
                ));
            }
        }
    }
    let has_baseline = genomes.len() == 2;
    let args = CompareArgs {
        genomes,
        experiment: Some(experiment_file),
        worlds: Some(WorldsChoice::HeldOut),
        generation: None,
        trials: Some(worlds),
        random: CHECK_RANDOM,
        json: false,
        measures: Vec::new(),
        ablate: Vec::new(),
        episode_curve: None,
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(jobs)
        .build()
        .context("cannot start the held-out check's worker threads")?;
    let report: CompareReport = pool.install(|| compare::compare(&args))?;
    let fitness_of = |k: usize| report.genomes.get(k).and_then(|g| g.fitness);
    let champion = fitness_of(0);
    let random = report.random.as_ref().map_or(
        RandomCheck {
            count: 0,
            finite: 0,
            median: None,
            best: None,
        },
        |r| RandomCheck {
            count: r.count,
            finite: r.finite,
            median: (r.finite > 0).then_some(r.fitness.median),
            best: (r.finite > 0).then_some(r.fitness.best),
        },
    );
    let baseline = has_baseline.then(|| CheckedGenome {
        path: args.genomes[1].display().to_string(),
        name: experiment.output.baseline.as_deref().map_or_else(
            || genome_name(&args.genomes[1]),
            |b| genome_name(Path::new(b)),
        ),
        fitness: fitness_of(1),
    });
    let verdict = verdict(
        champion,
        random.median,
        random.best,
        baseline.as_ref().map(|b| b.fitness),
    );
    Ok(Some(CheckReport {
        worlds,
        generation: report.worlds.generation,
        champion: CheckedGenome {
            path: best.display().to_string(),
            name: "champion".to_string(),
            fitness: champion,
        },
        random,
        baseline,
        baseline_left_out,
        verdict,
    }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use berry_evolve::experiment::templates::TEMPLATES;

    #[test]
    fn the_check_costs_at_most_its_share_of_every_shipped_run() {
        for t in TEMPLATES {
            let e = t.experiment().unwrap();
            let generations = e.evolution.generations;
            let worlds = world_count(&e, generations);
            let run = Workload::of(&e, 0..generations).total_creature_ticks as f64;
            let check = (worlds * (CHECK_RANDOM + 2) * e.evaluation.ticks) as f64;
            assert!(
                worlds == 1 || check <= CHECK_SHARE * run,
                "{}: {worlds} worlds cost {check} of {run} creature-ticks",
                t.name
            );
        }
        // The main job gets the most worlds, far below its share.
        let foraging = berry_evolve::experiment::templates::find("foraging")
            .unwrap()
            .experiment()
            .unwrap();
        assert_eq!(world_count(&foraging, 200), MAX_CHECK_WORLDS);
        // A run of one generation still gets a world.
        assert_eq!(world_count(&foraging, 1), 1);
    }

    #[test]
    fn the_verdict_says_whom_the_champion_beats() {
        let v = |c, m, b, base| verdict(c, m, b, base);
        assert_eq!(
            v(Some(10.0), Some(1.0), Some(5.0), None),
            "the champion beats every random genome"
        );
        assert_eq!(
            v(Some(10.0), Some(1.0), Some(5.0), Some(Some(20.0))),
            "the champion beats every random genome, but not the baseline"
        );
        assert_eq!(
            v(Some(10.0), Some(1.0), Some(5.0), Some(Some(2.0))),
            "the champion beats every random genome and the baseline"
        );
        assert!(v(Some(3.0), Some(1.0), Some(5.0), None)
            .starts_with("the champion beats the median random genome but not the best one"));
        assert!(v(Some(1.0), Some(1.0), Some(5.0), Some(Some(2.0)))
            .contains("does no better than a typical random genome"));
        assert!(v(Some(1.0), Some(1.0), Some(5.0), Some(Some(2.0)))
            .ends_with("nor does it beat the baseline"));
        // A baseline that is not finite is beaten; a champion that is not finite beats nothing.
        assert_eq!(
            v(Some(10.0), Some(1.0), Some(5.0), Some(None)),
            "the champion beats every random genome and the baseline"
        );
        assert!(v(None, Some(1.0), Some(5.0), None).contains("not finite"));
        // No random genome with a finite fitness: the champion beats them all.
        assert_eq!(
            v(Some(0.0), None, None, None),
            "the champion beats every random genome"
        );
    }
}
