//! Console output never panics: a closed or full stderr or stdout stops the printing and
//! nothing else. The run still stops gracefully on SIGINT, writes its checkpoint and exits
//! 130 when its stderr reader is gone; `replay` and `compare` on a full stdout fail with a
//! message (exit 1), and a reader that closes the pipe early is not an error.

use crate::cli_common::{bin, fixture, read, run_ok};
use std::fs::OpenOptions;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

fn dev_full() -> std::fs::File {
    OpenOptions::new().write(true).open("/dev/full").unwrap()
}

fn no_panic(stderr: &[u8]) {
    let s = String::from_utf8_lossy(stderr);
    assert!(!s.contains("panicked"), "{s}");
}

#[test]
fn a_run_with_stderr_on_a_full_device_completes_as_usual() {
    let tmp = tempfile::tempdir().unwrap();
    let (a, b) = (tmp.path().join("a"), tmp.path().join("b"));
    run_ok(&[
        "run",
        fixture("tiny.toml").to_str().unwrap(),
        "--quiet",
        "--out",
        a.to_str().unwrap(),
    ]);
    let status = bin()
        .args([
            "run",
            fixture("tiny.toml").to_str().unwrap(),
            "--out",
            b.to_str().unwrap(),
        ])
        .stderr(dev_full())
        .stdout(dev_full())
        .status()
        .unwrap();
    assert_eq!(status.code(), Some(0));
    assert!(read(&a.join("fitness.csv")) == read(&b.join("fitness.csv")));
}

#[test]
fn replay_and_compare_on_a_full_stdout_fail_with_a_message() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("run");
    run_ok(&[
        "run",
        fixture("tiny.toml").to_str().unwrap(),
        "--quiet",
        "--out",
        dir.to_str().unwrap(),
    ]);
    let best = dir.join("best.json");
    let exp = fixture("tiny.toml");
    for args in [
        vec![
            "replay",
            best.to_str().unwrap(),
            "--experiment",
            exp.to_str().unwrap(),
        ],
        vec![
            "compare",
            "--experiment",
            exp.to_str().unwrap(),
            best.to_str().unwrap(),
        ],
        vec!["export-csv", dir.to_str().unwrap()],
        vec!["inspect", exp.to_str().unwrap()],
    ] {
        let out = bin()
            .args(&args)
            .stdout(dev_full())
            .stderr(Stdio::piped())
            .output()
            .unwrap();
        no_panic(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{args:?}");
        assert!(
            String::from_utf8_lossy(&out.stderr).contains("standard output"),
            "{args:?}"
        );
        // A reader that takes one line and exits: not an error.
        let mut child = bin()
            .args(&args)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        drop(child.stdout.take());
        let out = child.wait_with_output().unwrap();
        no_panic(&out.stderr);
        assert_eq!(
            out.status.code(),
            Some(0),
            "{args:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let sh = Command::new("sh")
            .arg("-c")
            .arg(format!(
                "'{}' {} | head -1",
                env!("CARGO_BIN_EXE_berry-evolve"),
                args.iter()
                    .map(|a| format!("'{a}'"))
                    .collect::<Vec<_>>()
                    .join(" ")
            ))
            .stderr(Stdio::piped())
            .output()
            .unwrap();
        no_panic(&sh.stderr);
    }
}

#[test]
fn sigint_after_the_stderr_reader_died_still_stops_with_a_checkpoint_and_130() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("run");
    // `berry-evolve X 2>&1 | tee log`, and tee is killed by the Ctrl-C first.
    let mut child = bin()
        .args([
            "run",
            fixture("slow.toml").to_str().unwrap(),
            "--out",
            dir.to_str().unwrap(),
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let deadline = Instant::now() + Duration::from_secs(60);
    while std::fs::read_to_string(dir.join("fitness.csv")).map_or(0, |t| t.lines().count()) < 3 {
        assert!(Instant::now() < deadline);
        std::thread::sleep(Duration::from_millis(5));
    }
    drop(child.stderr.take());
    Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert_eq!(child.wait().unwrap().code(), Some(130));
    let checkpoints = std::fs::read_dir(dir.join("checkpoints")).unwrap().count();
    assert!(checkpoints > 0);
    run_ok(&["resume", dir.to_str().unwrap(), "--quiet"]);
}
