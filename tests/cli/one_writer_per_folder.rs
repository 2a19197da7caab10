//! One run folder, one writer: two writers started together (two `resume`s, two `run`s)
//! leave one refused ("is in use by process N") and the run byte-identical to an
//! uninterrupted one; `export-csv` readers in a loop beside a live run neither disturb it nor
//! see a broken state; a refused writer touches nothing.

use crate::cli_common::{bin, fixture, read};
use std::path::{Path, PathBuf};
use std::process::{Child, Output, Stdio};
use std::sync::OnceLock;
use std::time::{Duration, Instant};

/// The uninterrupted run of slow.toml, made once per test binary.
fn reference() -> &'static Path {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("reliability-concurrency-ref");
        let out = bin()
            .args([
                "run",
                fixture("slow.toml").to_str().unwrap(),
                "--quiet",
                "--force",
                "--out",
            ])
            .arg(&dir)
            .output()
            .unwrap();
        assert!(out.status.success(), "{out:?}");
        dir
    })
}

fn newest_checkpoint(dir: &Path) -> PathBuf {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir.join("checkpoints"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .collect();
    v.sort();
    v.pop().expect("a checkpoint")
}

fn assert_same_as_reference(dir: &Path, what: &str) {
    let r = reference();
    for name in ["fitness.csv", "best.json", "experiment.toml"] {
        assert!(
            read(&r.join(name)) == read(&dir.join(name)),
            "{what}: {name} differs from the uninterrupted run"
        );
    }
    let (a, b) = (newest_checkpoint(r), newest_checkpoint(dir));
    assert_eq!(a.file_name(), b.file_name(), "{what}");
    assert!(read(&a) == read(&b), "{what}: final checkpoint differs");
}

fn spawn(args: &[&str], dir: &Path) -> Child {
    bin()
        .args(args)
        .arg(dir)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap()
}

/// Of two writers, exactly one succeeds and the other says the folder is in use.
fn one_refused(a: Output, b: Output, what: &str) {
    let ok = [&a, &b].iter().filter(|o| o.status.success()).count();
    let refused: Vec<String> = [&a, &b]
        .iter()
        .filter(|o| !o.status.success())
        .map(|o| String::from_utf8_lossy(&o.stderr).to_string())
        .collect();
    assert_eq!(ok, 1, "{what}: {a:?} {b:?}");
    assert!(
        refused[0].contains("is in use by process") && !refused[0].contains("panicked"),
        "{what}: {}",
        refused[0]
    );
}

/// A run of slow.toml stopped (SIGTERM) after a few generations, ready to resume.
fn stopped_run(dir: &Path) {
    let mut child = spawn(
        &[
            "run",
            fixture("slow.toml").to_str().unwrap(),
            "--quiet",
            "--out",
        ],
        dir,
    );
    let deadline = Instant::now() + Duration::from_secs(60);
    while std::fs::read_to_string(dir.join("fitness.csv")).map_or(0, |t| t.lines().count()) < 5 {
        assert!(Instant::now() < deadline && child.try_wait().unwrap().is_none());
        std::thread::sleep(Duration::from_millis(5));
    }
    std::process::Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .unwrap();
    assert_eq!(child.wait().unwrap().code(), Some(130));
}

#[test]
fn two_resumes_started_together_one_refuses_and_the_run_is_the_uninterrupted_one() {
    reference();
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("r");
    stopped_run(&dir);
    let a = spawn(&["resume", "--quiet"], &dir);
    let b = spawn(&["resume", "--quiet"], &dir);
    let (a, b) = (a.wait_with_output().unwrap(), b.wait_with_output().unwrap());
    one_refused(a, b, "resume & resume");
    assert_same_as_reference(&dir, "resume & resume");
}

#[test]
fn two_runs_started_together_one_refuses_and_the_run_is_the_uninterrupted_one() {
    reference();
    let tmp = tempfile::tempdir().unwrap();
    for force in [false, true] {
        let dir = tmp.path().join(format!("r-{force}"));
        if force {
            // Both with --force over a finished run: still one writer.
            std::fs::create_dir_all(&dir).unwrap();
            let out = bin()
                .args([
                    "run",
                    fixture("tiny.toml").to_str().unwrap(),
                    "--quiet",
                    "--out",
                ])
                .arg(&dir)
                .output()
                .unwrap();
            assert!(out.status.success());
        }
        let slow = fixture("slow.toml");
        let mut args = vec!["run", slow.to_str().unwrap(), "--quiet"];
        if force {
            args.push("--force");
        }
        args.push("--out");
        let a = spawn(&args, &dir);
        let b = spawn(&args, &dir);
        let (a, b) = (a.wait_with_output().unwrap(), b.wait_with_output().unwrap());
        one_refused(a, b, &format!("run & run (force {force})"));
        assert_same_as_reference(&dir, &format!("run & run (force {force})"));
    }
}

#[test]
fn export_csv_in_a_loop_beside_a_live_run_neither_disturbs_it_nor_fails() {
    reference();
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("live");
    let mut writer = spawn(
        &[
            "run",
            fixture("slow.toml").to_str().unwrap(),
            "--quiet",
            "--out",
        ],
        &dir,
    );
    let mut exports = 0;
    while writer.try_wait().unwrap().is_none() {
        if dir.join("checkpoints").is_dir() {
            let out = bin().args(["export-csv"]).arg(&dir).output().unwrap();
            let stderr = String::from_utf8_lossy(&out.stderr);
            // Before the first checkpoint there is nothing to export; after it, always a
            // consistent curve (a header and whole rows), never another error.
            if out.status.success() {
                let text = String::from_utf8(out.stdout).unwrap();
                assert!(
                    text.starts_with("generation,") && text.ends_with('\n'),
                    "{text}"
                );
                exports += 1;
            } else {
                assert!(stderr.contains("no checkpoint"), "{stderr}");
            }
            // A refused writer beside the live run touches nothing either.
            let refused = bin()
                .args(["resume", "--quiet"])
                .arg(&dir)
                .output()
                .unwrap();
            if writer.try_wait().unwrap().is_none() {
                assert!(!refused.status.success());
            }
        }
    }
    assert!(writer.wait().unwrap().success(), "the live run failed");
    let stderr = String::from_utf8_lossy(&writer.wait_with_output().unwrap().stderr).to_string();
    assert!(stderr.is_empty(), "{stderr}");
    assert!(exports > 3, "only {exports} exports during the run");
    assert_same_as_reference(&dir, "run beside export-csv readers");
}

#[test]
fn a_refused_writer_touches_nothing() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("live");
    let mut writer = spawn(
        &[
            "run",
            fixture("slow.toml").to_str().unwrap(),
            "--quiet",
            "--out",
        ],
        &dir,
    );
    while !dir.join("checkpoints").is_dir() {
        std::thread::sleep(Duration::from_millis(2));
    }
    // A planted temporary file of the live writer must survive the refused commands.
    let planted = dir.join(".fitness.csv.tmp-1-1");
    std::fs::write(&planted, b"live").unwrap();
    for args in [
        vec!["resume".to_string(), dir.display().to_string()],
        vec![
            "run".to_string(),
            fixture("slow.toml").display().to_string(),
            "--force".to_string(),
            "--out".to_string(),
            dir.display().to_string(),
        ],
        vec!["export-csv".to_string(), dir.display().to_string()],
    ] {
        let out = bin().args(&args).output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        if args[0] != "export-csv" {
            assert!(
                stderr.contains("is in use by process"),
                "{args:?}: {stderr}"
            );
            assert!(stderr.contains(&writer.id().to_string()), "{stderr}");
        }
        assert!(planted.exists(), "{args:?} removed a live temporary file");
    }
    let status = writer.wait().unwrap();
    assert!(status.success());
}
