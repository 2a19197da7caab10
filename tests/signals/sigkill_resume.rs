//! SIGKILL at random moments: a real run of slow.toml is killed again and again (at seeded
//! random delays after each start), resumed each time (started over with --force while no
//! checkpoint has been written yet), and must finish with fitness.csv, best.json,
//! champions.jsonl, experiment.toml and the final checkpoint byte-identical to an
//! uninterrupted run.
//!
//! After every kill, every `gen-*.json` in the folder must read back intact, and once a
//! checkpoint has been written there must always be one. When a round finishes, no temporary
//! file may be left anywhere in the run folder.
//!
//! CI runs 8 kills. `BERRY_KILLS=200 cargo test --release --test signals sigkill_resume:: --
//! --nocapture` (or scripts/kill-harness.sh) runs more; `BERRY_KILL_SEED` changes the delays.

use berry_evolve::record::atomic::is_temp_name;
use berry_evolve::record::checkpoint;
use berry_evolve::run::CheckpointPayload;
use berry_evolve::seed::{below, Rng};
use rand::SeedableRng;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_berry-evolve"))
}

fn slow() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/slow.toml")
}

fn env_number(name: &str, default: u64) -> u64 {
    match std::env::var(name) {
        Ok(v) => v
            .parse()
            .unwrap_or_else(|_| panic!("{name}={v} is not a number")),
        Err(_) => default,
    }
}

fn read(path: &Path) -> Vec<u8> {
    std::fs::read(path).unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()))
}

/// The `gen-NNNNNN.json` files of the run folder, oldest first.
fn checkpoint_files(dir: &Path) -> Vec<PathBuf> {
    let Ok(entries) = std::fs::read_dir(dir.join("checkpoints")) else {
        return Vec::new();
    };
    let mut v: Vec<PathBuf> = entries
        .map(|e| e.unwrap().path())
        .filter(|p| {
            p.file_name()
                .and_then(|n| n.to_str())
                .and_then(checkpoint::parse_checkpoint_file_name)
                .is_some()
        })
        .collect();
    v.sort();
    v
}

/// Temporary files left in the run folder or its checkpoint folder.
fn temp_files(dir: &Path) -> Vec<PathBuf> {
    [dir.to_path_buf(), dir.join("checkpoints")]
        .iter()
        .filter_map(|d| std::fs::read_dir(d).ok())
        .flatten()
        .map(|e| e.unwrap().path())
        .filter(|p| {
            p.file_name()
                .and_then(|n| n.to_str())
                .is_some_and(is_temp_name)
        })
        .collect()
}

fn outputs(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let last = checkpoint_files(dir).pop().expect("a final checkpoint");
    let mut v: Vec<(String, Vec<u8>)> = [
        "fitness.csv",
        "best.json",
        "champions.jsonl",
        "experiment.toml",
    ]
    .iter()
    .map(|n| (n.to_string(), read(&dir.join(n))))
    .collect();
    v.push((
        last.file_name().unwrap().to_string_lossy().to_string(),
        read(&last),
    ));
    v
}

fn spawn(dir: &Path, resume: bool) -> Child {
    let mut cmd = bin();
    if resume {
        cmd.args(["resume", "--quiet"]).arg(dir);
    } else {
        cmd.args([
            "run",
            slow().to_str().unwrap(),
            "--quiet",
            "--force",
            "--out",
        ])
        .arg(dir);
    }
    cmd.stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("binary starts")
}

/// Waits up to `delay` for the child to end by itself; true if it did.
fn ended_within(child: &mut Child, delay: Duration) -> bool {
    let until = Instant::now() + delay;
    loop {
        if child.try_wait().unwrap().is_some() {
            return true;
        }
        let now = Instant::now();
        if now >= until {
            return false;
        }
        std::thread::sleep((until - now).min(Duration::from_millis(2)));
    }
}

#[test]
fn runs_killed_at_random_moments_resume_to_the_same_bytes() {
    let kills = env_number("BERRY_KILLS", 8);
    let seed = env_number("BERRY_KILL_SEED", 2026);
    // Long enough to get past start-up and a checkpoint, short enough that a run of slow.toml
    // (about a second) is killed several times before it finishes.
    let max_delay_ms = env_number("BERRY_KILL_MAX_DELAY_MS", 150);
    let mut rng = Rng::seed_from_u64(seed);

    let tmp = tempfile::tempdir().unwrap();
    let reference = tmp.path().join("reference");
    let out = bin()
        .args(["run", slow().to_str().unwrap(), "--quiet", "--out"])
        .arg(&reference)
        .output()
        .unwrap();
    assert!(out.status.success(), "{out:?}");
    let expected = outputs(&reference);

    let mut survived = 0u64;
    let mut rounds = 0u64;
    let mut resumes = 0u64;
    let mut restarts = 0u64;
    while survived < kills {
        let dir = tmp.path().join(format!("round-{rounds}"));
        let mut checkpoint_seen = false;
        loop {
            let resume = !checkpoint_files(&dir).is_empty();
            if resume {
                resumes += 1;
            } else {
                restarts += 1;
            }
            let mut child = spawn(&dir, resume);
            let delay = Duration::from_millis(below(&mut rng, max_delay_ms + 1));
            let done = survived >= kills || ended_within(&mut child, delay);
            if !done {
                child.kill().expect("SIGKILL");
            }
            let out = child.wait_with_output().unwrap();
            let stderr = String::from_utf8_lossy(&out.stderr);
            if done {
                assert!(
                    out.status.success(),
                    "round {rounds}: {} failed after {survived} kills:\n{stderr}",
                    if resume { "resume" } else { "run" }
                );
                break;
            }
            survived += 1;
            // What a kill leaves: every checkpoint reads back, and one is always there once
            // one has been written.
            let files = checkpoint_files(&dir);
            for f in &files {
                if let Err(e) = checkpoint::load::<CheckpointPayload>(f, None) {
                    panic!("after kill {survived} (delay {delay:?}): damaged checkpoint: {e}");
                }
            }
            assert!(
                !checkpoint_seen || !files.is_empty(),
                "after kill {survived} (delay {delay:?}): all checkpoints are gone"
            );
            checkpoint_seen |= !files.is_empty();
        }
        let left = temp_files(&dir);
        assert!(
            left.is_empty(),
            "round {rounds}: temporary files left: {left:?}"
        );
        let got = outputs(&dir);
        for ((name_a, a), (name_b, b)) in expected.iter().zip(&got) {
            assert_eq!(name_a, name_b, "round {rounds}: final checkpoint");
            assert!(
                a == b,
                "round {rounds}: {name_a} differs from the uninterrupted run"
            );
        }
        rounds += 1;
    }
    println!(
        "survived {survived} SIGKILLs in {rounds} killed runs ({resumes} resumes, {restarts} \
         starts; seed {seed}, delays 0..={max_delay_ms} ms); every run finished byte-identical"
    );
}

#[test]
fn a_new_start_removes_temporary_files_a_killed_run_left() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("run");
    std::fs::create_dir_all(dir.join("checkpoints")).unwrap();
    std::fs::write(dir.join(".best.json.tmp-999-0"), b"half").unwrap();
    std::fs::write(dir.join("checkpoints/.gen-000002.json.tmp-999-1"), b"half").unwrap();
    let exp = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/tiny.toml");
    let out = bin()
        .args(["run", exp.to_str().unwrap(), "--quiet", "--force", "--out"])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(out.status.success(), "{out:?}");
    assert_eq!(temp_files(&dir), Vec::<PathBuf>::new());
}
