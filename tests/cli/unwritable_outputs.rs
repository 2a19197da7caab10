//! Output that cannot be written: the run stops with an error naming the path and exits
//! non-zero, the last good checkpoint stays intact, and once the folder is fixed `resume`
//! finishes the same run. (Failed writes inside the record layer, e.g. a full disk, are
//! simulated with `write_atomic_with` in tests/record/atomic_checkpoints_csv.rs.)

use berry_evolve::record::checkpoint;
use berry_evolve::run::CheckpointPayload;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_berry-evolve"))
}

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures")
        .join(name)
}

fn checkpoint_files(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
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

fn assert_clean_error(stderr: &str) {
    assert!(stderr.starts_with("error: "), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
}

#[test]
fn out_under_a_regular_file_is_refused_naming_the_path() {
    // A regular file as a parent: not writable even by root.
    let tmp = tempfile::tempdir().unwrap();
    let file = tmp.path().join("not-a-folder");
    std::fs::write(&file, b"x").unwrap();
    let out_dir = file.join("run");
    let out = bin()
        .args([
            "run",
            fixture("tiny.toml").to_str().unwrap(),
            "--quiet",
            "--out",
        ])
        .arg(&out_dir)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert_clean_error(&stderr);
    assert!(stderr.contains(out_dir.to_str().unwrap()), "{stderr}");
    assert!(stderr.contains("cannot create the run folder"), "{stderr}");
    assert_eq!(std::fs::read(&file).unwrap(), b"x", "the file was touched");
}

#[test]
fn a_checkpoint_folder_that_disappears_mid_run_stops_the_run_and_keeps_the_last_good_checkpoint() {
    let tmp = tempfile::tempdir().unwrap();
    let reference = tmp.path().join("reference");
    let out = bin()
        .args([
            "run",
            fixture("slow.toml").to_str().unwrap(),
            "--quiet",
            "--out",
        ])
        .arg(&reference)
        .output()
        .unwrap();
    assert!(out.status.success(), "{out:?}");

    let dir = tmp.path().join("run");
    let checkpoints = dir.join("checkpoints");
    let mut child = bin()
        .args([
            "run",
            fixture("slow.toml").to_str().unwrap(),
            "--quiet",
            "--out",
        ])
        .arg(&dir)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Once the first checkpoint exists, the folder is moved away and a file takes its name.
    let deadline = Instant::now() + Duration::from_secs(60);
    while !checkpoints.is_dir() || checkpoint_files(&checkpoints).is_empty() {
        assert!(child.try_wait().unwrap().is_none(), "run ended too early");
        assert!(Instant::now() < deadline, "no checkpoint after 60 s");
        std::thread::sleep(Duration::from_millis(2));
    }
    let saved = dir.join("checkpoints.saved");
    std::fs::rename(&checkpoints, &saved).unwrap();
    std::fs::write(&checkpoints, b"in the way").unwrap();
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert_clean_error(&stderr);
    assert!(stderr.contains(checkpoints.to_str().unwrap()), "{stderr}");
    assert!(stderr.contains("could not be written"), "{stderr}");

    // The checkpoints written before are intact.
    let kept = checkpoint_files(&saved);
    assert!(!kept.is_empty());
    for cp in &kept {
        checkpoint::load::<CheckpointPayload>(cp, None).expect("intact checkpoint");
    }
    // Put the folder back: the run resumes and finishes as if nothing had happened.
    std::fs::remove_file(&checkpoints).unwrap();
    std::fs::rename(&saved, &checkpoints).unwrap();
    let out = bin()
        .args(["resume", "--quiet"])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(out.status.success(), "{out:?}");
    for name in ["fitness.csv", "best.json", "experiment.toml"] {
        assert!(
            std::fs::read(reference.join(name)).unwrap() == std::fs::read(dir.join(name)).unwrap(),
            "{name} differs"
        );
    }
    let a = checkpoint_files(&reference.join("checkpoints"))
        .pop()
        .unwrap();
    let b = checkpoint_files(&checkpoints).pop().unwrap();
    assert_eq!(a.file_name(), b.file_name());
    assert!(std::fs::read(a).unwrap() == std::fs::read(b).unwrap());
}

#[test]
fn a_checkpoint_that_cannot_be_written_names_the_last_good_one_and_resume_continues() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("run");
    let checkpoints = dir.join("checkpoints");
    let mut child = bin()
        .args([
            "run",
            fixture("slow.toml").to_str().unwrap(),
            "--quiet",
            "--out",
        ])
        .arg(&dir)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let deadline = Instant::now() + Duration::from_secs(60);
    while !checkpoints.is_dir() || checkpoint_files(&checkpoints).is_empty() {
        assert!(child.try_wait().unwrap().is_none(), "run ended too early");
        assert!(Instant::now() < deadline, "no checkpoint after 60 s");
        std::thread::sleep(Duration::from_millis(2));
    }
    // Folders squat on the names of every later checkpoint: the next one cannot be renamed
    // into place (as with a full disk, the write fails after the older ones are safe).
    let first = checkpoint_files(&checkpoints)[0].clone();
    let squatters: Vec<PathBuf> = (3..60)
        .map(|g| checkpoints.join(checkpoint::checkpoint_file_name(g)))
        .collect();
    for s in &squatters {
        let _ = std::fs::create_dir(s);
    }
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert_clean_error(&stderr);
    assert!(stderr.contains("could not be written"), "{stderr}");
    assert!(
        stderr.contains(&format!("berry-evolve resume {}", dir.display())),
        "{stderr}"
    );
    // The checkpoint the message names is good, and so is every real checkpoint file.
    let named = checkpoint_files(&checkpoints)
        .into_iter()
        .rfind(|p| p.is_file())
        .expect("a good checkpoint");
    assert!(named >= first);
    assert!(stderr.contains(named.to_str().unwrap()), "{stderr}");
    checkpoint::load::<CheckpointPayload>(&named, None).expect("intact checkpoint");
    for s in &squatters {
        let _ = std::fs::remove_dir(s);
    }
    let out = bin()
        .args(["resume", "--quiet"])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(out.status.success(), "{out:?}");
}

#[test]
fn a_deleted_fitness_csv_is_rebuilt_from_the_checkpoint_on_resume() {
    let tmp = tempfile::tempdir().unwrap();
    let full = tmp.path().join("full");
    let short = tmp.path().join("short");
    let tiny = fixture("tiny.toml");
    for (dir, generations) in [(&full, "8"), (&short, "5")] {
        let out = bin()
            .args([
                "run",
                tiny.to_str().unwrap(),
                "--quiet",
                "--generations",
                generations,
            ])
            .arg("--out")
            .arg(dir)
            .output()
            .unwrap();
        assert!(out.status.success(), "{out:?}");
    }
    std::fs::remove_file(short.join("fitness.csv")).unwrap();
    let out = bin()
        .args(["resume", "--quiet", "--generations", "8"])
        .arg(&short)
        .output()
        .unwrap();
    assert!(out.status.success(), "{out:?}");
    for name in ["fitness.csv", "best.json"] {
        assert!(
            std::fs::read(full.join(name)).unwrap() == std::fs::read(short.join(name)).unwrap(),
            "{name} differs"
        );
    }
}
