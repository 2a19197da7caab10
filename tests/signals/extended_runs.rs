//! An extended run is the same run: a finished run extended with `resume --generations`
//! (3 → 6 → 12), and an extension killed (SIGKILL) or stopped (SIGTERM) and resumed, end with
//! `fitness.csv`, `best.json`, `champions.jsonl`, `experiment.toml` and every checkpoint
//! byte-identical to a run planned that long from the start, for every shipped experiment.
//!
//! The experiments are made small (population, trials, ticks) so that CI can afford them
//! all; validation is on in each (every 4 generations, so that a 3- and a 6-generation run end
//! on a generation validated only for being the last, and a 12-generation run on a scheduled
//! one), and checkpoints every 2 (a 3-generation run's last checkpoint is off the schedule,
//! a 6-generation run's on it).

use berry_evolve::experiment::Experiment;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_berry-evolve"))
}

fn run_ok(args: &[&str]) {
    let out = bin().args(args).output().unwrap();
    assert!(
        out.status.success(),
        "berry-evolve {}: {}",
        args.join(" "),
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Every experiment file under experiments/, sorted.
fn shipped_experiments() -> Vec<PathBuf> {
    fn walk(dir: &Path, found: &mut Vec<PathBuf>) {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                walk(&path, found);
            } else if path.extension().is_some_and(|e| e == "toml") {
                found.push(path);
            }
        }
    }
    let mut found = Vec::new();
    walk(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("experiments"),
        &mut found,
    );
    found.sort();
    found
}

/// `path` made small enough to run many times, with validation every 4 generations and a
/// checkpoint every 2, written into `into`. `size` scales its work (trials and ticks are
/// the file's own at the largest size).
fn small(path: &Path, into: &Path, size: Size) -> PathBuf {
    let experiment = Experiment::load(path).unwrap();
    let shrink = |population: usize| {
        experiment.with_overrides().edit(|c| {
            c.evolution.population = population;
            c.evolution.elitism = c.evolution.elitism.min(2);
            if let Size::Small = size {
                c.evaluation.trials = c.evaluation.trials.min(2);
                c.evaluation.ticks = c.evaluation.ticks.min(150);
            }
            c.validation.every = 4;
            c.validation.top = c.validation.top.clamp(1, 2);
            c.validation.trials = c.validation.trials.clamp(1, 3);
            c.output.checkpoint_every = 2;
            c.output.keep_checkpoints = 3;
        })
    };
    // A population of 12 where the file allows it (groups, PGPE's pairs), else its own.
    let experiment = shrink(12)
        .build()
        .or_else(|_| shrink(experiment.evolution.population).build())
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let name = path.file_name().unwrap();
    let out = into.join(name);
    std::fs::write(&out, experiment.to_toml()).unwrap();
    out
}

#[derive(Clone, Copy)]
enum Size {
    Small,
    Full,
}

fn run(experiment: &Path, dir: &Path, generations: u64) {
    run_ok(&[
        "run",
        experiment.to_str().unwrap(),
        "--out",
        dir.to_str().unwrap(),
        "--generations",
        &generations.to_string(),
        "--quiet",
        "--no-estimate",
    ]);
}

fn resume(dir: &Path, generations: Option<u64>) {
    let g = generations.map(|g| g.to_string());
    let mut args = vec!["resume", dir.to_str().unwrap(), "--quiet"];
    if let Some(g) = &g {
        args.extend(["--generations", g]);
    }
    run_ok(&args);
}

/// The run folder's files that must be byte-identical: the outputs and every checkpoint.
fn outputs(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut names: Vec<String> = [
        "fitness.csv",
        "best.json",
        "champions.jsonl",
        "experiment.toml",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    let mut cps: Vec<String> = std::fs::read_dir(dir.join("checkpoints"))
        .unwrap()
        .map(|e| format!("checkpoints/{}", e.unwrap().file_name().to_string_lossy()))
        .collect();
    cps.sort();
    names.extend(cps);
    names
        .into_iter()
        .map(|n| {
            let bytes = std::fs::read(dir.join(&n)).unwrap_or_default();
            (n, bytes)
        })
        .collect()
}

fn assert_same(reference: &Path, dir: &Path, what: &str) {
    let a = outputs(reference);
    let b = outputs(dir);
    let names = |v: &[(String, Vec<u8>)]| v.iter().map(|(n, _)| n.clone()).collect::<Vec<_>>();
    assert_eq!(names(&a), names(&b), "{what}: different files");
    for ((name, x), (_, y)) in a.iter().zip(&b) {
        assert!(x == y, "{what}: {name} differs");
    }
}

#[test]
fn extending_3_to_6_to_12_generations_equals_the_run_planned_that_long() {
    let tmp = tempfile::tempdir().unwrap();
    for path in shipped_experiments() {
        let name = path.file_stem().unwrap().to_string_lossy().to_string();
        let what = |w: &str| format!("{} {w}", path.display());
        let exp = small(&path, tmp.path(), Size::Small);
        let full6 = tmp.path().join(format!("{name}-6"));
        let full12 = tmp.path().join(format!("{name}-12"));
        let extended = tmp.path().join(format!("{name}-extended"));
        run(&exp, &full6, 6);
        run(&exp, &full12, 12);
        run(&exp, &extended, 3);
        resume(&extended, Some(6));
        assert_same(&full6, &extended, &what("3 -> 6"));
        resume(&extended, Some(12));
        assert_same(&full12, &extended, &what("6 -> 12"));
        // The plainer way to extend: edit the file's length and resume.
        let edited = tmp.path().join(format!("{name}-edited"));
        run(&exp, &edited, 6);
        let toml = std::fs::read_to_string(edited.join("experiment.toml")).unwrap();
        let toml = toml.replacen("generations = 6\n", "generations = 12\n", 1);
        std::fs::write(edited.join("experiment.toml"), toml).unwrap();
        resume(&edited, None);
        assert_same(
            &full12,
            &edited,
            &what("6 -> 12 by editing experiment.toml"),
        );
    }
}

/// The number of rows in the run's fitness.csv.
fn rows(dir: &Path) -> usize {
    std::fs::read_to_string(dir.join("fitness.csv"))
        .map(|s| s.lines().count().saturating_sub(1))
        .unwrap_or(0)
}

/// Starts `resume DIR --generations 12` and signals it (`kill -NAME`) once the extension has
/// written `rows` rows. Returns false when the resume finished before the signal could land.
fn signal_extension(dir: &Path, signal: &str, at_rows: usize) -> bool {
    let mut child: Child = bin()
        .args([
            "resume",
            dir.to_str().unwrap(),
            "--generations",
            "12",
            "--quiet",
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let deadline = Instant::now() + Duration::from_secs(120);
    while rows(dir) < at_rows {
        if child.try_wait().unwrap().is_some() || Instant::now() > deadline {
            let _ = child.wait();
            return false;
        }
        std::thread::sleep(Duration::from_millis(1));
    }
    if child.try_wait().unwrap().is_some() {
        return false;
    }
    let status = Command::new("kill")
        .arg(format!("-{signal}"))
        .arg(child.id().to_string())
        .status()
        .unwrap();
    assert!(status.success(), "kill -{signal} failed");
    let exit = child.wait().unwrap();
    !exit.success()
}

#[test]
fn an_extension_killed_or_stopped_and_resumed_equals_the_run_planned_that_long() {
    let tmp = tempfile::tempdir().unwrap();
    let validating: Vec<PathBuf> = shipped_experiments()
        .into_iter()
        .filter(|p| Experiment::load(p).unwrap().validation.enabled())
        .collect();
    assert!(validating.len() >= 6, "{validating:?}");
    let mut landed = 0;
    for (k, path) in validating.iter().enumerate() {
        let name = path.file_stem().unwrap().to_string_lossy().to_string();
        // The file's own trials and ticks, so that a generation lasts long enough to be hit.
        let exp = small(path, tmp.path(), Size::Full);
        let full12 = tmp.path().join(format!("{name}-12"));
        run(&exp, &full12, 12);
        // SIGKILL in most, SIGTERM (stop after the generation) in every third.
        let signal = if k % 3 == 2 { "TERM" } else { "KILL" };
        let dir = tmp.path().join(format!("{name}-{signal}"));
        run(&exp, &dir, 6);
        if signal_extension(&dir, signal, 8) {
            landed += 1;
        }
        resume(&dir, None);
        assert_same(
            &full12,
            &dir,
            &format!("{} extension 6 -> 12 after SIG{signal}", path.display()),
        );
    }
    assert!(
        landed * 2 >= validating.len(),
        "the signal landed during only {landed} of {} extensions",
        validating.len()
    );
}
