//! Stopping a real run with SIGTERM or SIGINT (Ctrl-C): the run stops after the current
//! generation with a checkpoint of it, exits with 130 and says how to continue; `resume` then
//! finishes with the same bytes as a run that was never stopped. A second signal stops at
//! once and leaves the last checkpoint intact.

use berry_evolve::record::checkpoint;
use berry_evolve::run::CheckpointPayload;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::OnceLock;
use std::time::{Duration, Instant};

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_berry-evolve"))
}

fn slow() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/slow.toml")
}

fn read(path: &Path) -> Vec<u8> {
    std::fs::read(path).unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()))
}

fn checkpoints(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir.join("checkpoints"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    v.sort();
    v
}

/// The uninterrupted run of slow.toml, made once per test binary.
fn reference() -> &'static Path {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("interrupt-reference");
        let out = bin()
            .args([
                "run",
                slow().to_str().unwrap(),
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

/// fitness.csv, best.json, champions.jsonl, experiment.toml and the final checkpoint must be
/// byte-identical.
fn assert_same_as_reference(dir: &Path, what: &str) {
    let reference = reference();
    for name in [
        "fitness.csv",
        "best.json",
        "champions.jsonl",
        "experiment.toml",
    ] {
        assert!(
            read(&reference.join(name)) == read(&dir.join(name)),
            "{what}: {name} differs from the uninterrupted run"
        );
    }
    let a = checkpoints(reference).pop().unwrap();
    let b = checkpoints(dir).pop().unwrap();
    assert_eq!(a.file_name(), b.file_name(), "{what}: final checkpoint");
    assert!(read(&a) == read(&b), "{what}: final checkpoint differs");
}

fn start_slow(dir: &Path) -> Child {
    bin()
        .args(["run", slow().to_str().unwrap(), "--quiet", "--out"])
        .arg(dir)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("binary starts")
}

/// Waits until fitness.csv holds at least `rows` data rows.
fn wait_for_rows(dir: &Path, rows: usize, child: &mut Child) {
    let csv = dir.join("fitness.csv");
    let deadline = Instant::now() + Duration::from_secs(60);
    loop {
        let n = std::fs::read_to_string(&csv)
            .map(|t| t.lines().count().saturating_sub(1))
            .unwrap_or(0);
        if n >= rows {
            return;
        }
        assert!(
            child.try_wait().unwrap().is_none(),
            "run ended before writing {rows} rows"
        );
        assert!(Instant::now() < deadline, "no fitness rows after 60 s");
        std::thread::sleep(Duration::from_millis(5));
    }
}

fn signal(child: &Child, name: &str) {
    let status = Command::new("kill")
        .args([format!("-{name}"), child.id().to_string()])
        .status()
        .expect("kill runs");
    assert!(status.success(), "kill -{name} failed");
}

/// Stops a run with one `signal_name` and checks what the user is told and left with.
fn stop_and_resume(signal_name: &str) {
    reference();
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("run");
    let mut child = start_slow(&dir);
    wait_for_rows(&dir, 1, &mut child);
    signal(&child, signal_name);
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr).to_string();
    assert_eq!(out.status.code(), Some(130), "exit code; stderr:\n{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    // A deliberate stop is reported as such, not as an error.
    assert!(
        stderr.contains("stopped: interrupted after generation ") && !stderr.contains("error:"),
        "the stop is not reported as a stop:\n{stderr}"
    );
    assert!(
        stderr.contains(&format!("berry-evolve resume {}", dir.display())),
        "stderr does not say how to continue:\n{stderr}"
    );
    // "interrupted after generation G; the checkpoint .../gen-00000G.json holds it."
    let generation: u64 = stderr
        .split("interrupted after generation ")
        .nth(1)
        .and_then(|s| s.split(';').next())
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("no generation in:\n{stderr}"));
    let cp = dir
        .join("checkpoints")
        .join(checkpoint::checkpoint_file_name(generation));
    assert!(stderr.contains(&cp.display().to_string()), "{stderr}");
    let loaded = checkpoint::load::<CheckpointPayload>(&cp, None).expect("checkpoint is good");
    assert_eq!(loaded.payload.last.generation, generation);
    assert_eq!(
        checkpoints(&dir).pop().unwrap(),
        cp,
        "the stop checkpoint is the newest"
    );
    let rows = std::fs::read_to_string(dir.join("fitness.csv"))
        .unwrap()
        .lines()
        .count()
        - 1;
    assert_eq!(rows as u64, generation + 1, "fitness.csv rows at the stop");

    let out = bin()
        .args(["resume", "--quiet"])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(out.status.success(), "resume failed: {out:?}");
    assert_same_as_reference(&dir, &format!("stopped by SIG{signal_name}"));
}

#[test]
fn sigterm_stops_after_the_generation_and_resume_finishes_the_same_run() {
    stop_and_resume("TERM");
}

#[test]
fn sigint_stops_after_the_generation_and_resume_finishes_the_same_run() {
    stop_and_resume("INT");
}

#[test]
fn second_signal_stops_at_once_leaving_a_good_checkpoint() {
    reference();
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("run");
    let mut child = start_slow(&dir);
    // Wait for a scheduled checkpoint (every 3 generations) so one exists before the stop.
    wait_for_rows(&dir, 4, &mut child);
    signal(&child, "INT");
    signal(&child, "INT");
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr).to_string();
    assert_eq!(out.status.code(), Some(130), "exit code; stderr:\n{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    // Whichever way the stop went, the newest checkpoint reads back and resume completes.
    let newest = checkpoints(&dir)
        .into_iter()
        .rfind(|p| {
            p.file_name()
                .and_then(|n| n.to_str())
                .and_then(checkpoint::parse_checkpoint_file_name)
                .is_some()
        })
        .expect("a checkpoint");
    checkpoint::load::<CheckpointPayload>(&newest, None).expect("newest checkpoint is good");
    let out = bin()
        .args(["resume", "--quiet"])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(out.status.success(), "resume failed: {out:?}");
    assert_same_as_reference(&dir, "stopped by two SIGINTs");
}
