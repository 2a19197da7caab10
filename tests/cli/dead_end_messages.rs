//! Dead ends in messages: each gives a next step that works.

use crate::cli_common::{bin, fixture, run_err, run_ok};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

#[test]
fn a_run_stopped_before_its_first_checkpoint_points_to_force() {
    let tmp = tempfile::tempdir().unwrap();
    // Generations long enough (seconds, also on an idle fast machine) for two signals to
    // land within the first one.
    let text = String::from_utf8(std::fs::read(fixture("slow.toml")).unwrap())
        .unwrap()
        .replace("population = 12", "population = 3000")
        .replace("trials = 2", "trials = 8");
    let exp = tmp.path().join("long.toml");
    std::fs::write(&exp, text).unwrap();
    let dir = tmp.path().join("run");
    let child = bin()
        .args(["run", exp.to_str().unwrap(), "--out", dir.to_str().unwrap()])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let deadline = Instant::now() + Duration::from_secs(30);
    while !dir.join("fitness.csv").exists() {
        assert!(Instant::now() < deadline);
        std::thread::sleep(Duration::from_millis(2));
    }
    std::thread::sleep(Duration::from_millis(50));
    for _ in 0..2 {
        Command::new("kill")
            .args(["-INT", &child.id().to_string()])
            .status()
            .unwrap();
        std::thread::sleep(Duration::from_millis(50));
    }
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(130), "{stderr}");
    assert!(!stderr.contains("is intact"), "{stderr}");
    assert!(
        stderr.contains("nothing to resume") && stderr.contains("--force"),
        "{stderr}"
    );
    // resume says the same, with the command; that command works.
    let err = run_err(&["resume", dir.to_str().unwrap()]);
    assert!(
        err.contains("nothing to resume") && err.contains("--force"),
        "{err}"
    );
    let command = err
        .split("start it over with: ")
        .nth(1)
        .unwrap()
        .trim()
        .to_string();
    let mut args: Vec<&str> = command.split_whitespace().skip(1).collect();
    args.extend(["--generations", "1", "--quiet"]);
    run_ok(&args);
}

#[test]
fn a_dangling_symlink_as_out_and_a_tiny_disk_say_what_to_do() {
    let tmp = tempfile::tempdir().unwrap();
    let link = tmp.path().join("out");
    std::os::unix::fs::symlink(tmp.path().join("missing/dir"), &link).unwrap();
    let err = run_err(&[
        "run",
        fixture("tiny.toml").to_str().unwrap(),
        "--out",
        link.to_str().unwrap(),
    ]);
    assert!(
        err.contains("symbolic link") && err.contains("mkdir -p"),
        "{err}"
    );
    // No room for even the first file (a file size limit stands for a 4 KB disk).
    let dir = tmp.path().join("full");
    let out = Command::new("sh")
        .arg("-c")
        .arg(format!(
            "trap '' XFSZ; ulimit -f 1; exec '{}' run '{}' --out '{}'",
            env!("CARGO_BIN_EXE_berry-evolve"),
            fixture("tiny.toml").display(),
            dir.display()
        ))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("--force") && stderr.contains("disk space"),
        "{stderr}"
    );
}
