//! Every output is written atomically: a SIGKILL, `ulimit -f` or a write error during
//! `export-csv -o` or a `--trace` leaves the earlier complete file as it was; and no output
//! path may name one of the command's inputs.

use crate::cli_common::{bin, fixture, read, run_err, run_ok};
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

fn tiny_run(dir: &Path) {
    run_ok(&[
        "run",
        fixture("tiny.toml").to_str().unwrap(),
        "--quiet",
        "--generations",
        "30",
        "--out",
        dir.to_str().unwrap(),
    ]);
}

fn exe() -> String {
    env!("CARGO_BIN_EXE_berry-evolve").to_string()
}

/// Runs the binary under `sh` with a file size limit of `blocks` (512-byte blocks in dash,
/// 1024 in bash: either is far below the outputs).
fn under_file_limit(blocks: u32, ignore_signal: bool, args: &[&str]) -> std::process::Output {
    let quoted: Vec<String> = args.iter().map(|a| format!("'{a}'")).collect();
    let trap = if ignore_signal { "trap '' XFSZ; " } else { "" };
    Command::new("sh")
        .arg("-c")
        .arg(format!(
            "{trap}ulimit -f {blocks}; exec '{}' {}",
            exe(),
            quoted.join(" ")
        ))
        .output()
        .unwrap()
}

fn no_temp_files(dir: &Path) {
    for e in std::fs::read_dir(dir).unwrap() {
        let name = e.unwrap().file_name().to_string_lossy().to_string();
        assert!(
            !name.contains(".tmp-"),
            "temporary file {name} left in {}",
            dir.display()
        );
    }
}

#[test]
fn export_csv_o_cut_short_by_a_file_size_limit_leaves_the_earlier_export_whole() {
    let tmp = tempfile::tempdir().unwrap();
    let run = tmp.path().join("run");
    tiny_run(&run);
    let out = tmp.path().join("curve.csv");
    run_ok(&[
        "export-csv",
        run.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    let earlier = read(&out);
    assert!(
        earlier.len() > 1024,
        "export too small for the test: {}",
        earlier.len()
    );
    // Killed by SIGXFSZ, and with the signal ignored (the write fails with EFBIG).
    for ignore in [false, true] {
        let o = under_file_limit(
            1,
            ignore,
            &[
                "export-csv",
                run.to_str().unwrap(),
                "-o",
                out.to_str().unwrap(),
            ],
        );
        assert!(!o.status.success(), "the limit did not stop the export");
        assert!(!String::from_utf8_lossy(&o.stderr).contains("panicked"));
        assert!(
            read(&out) == earlier,
            "the earlier export was damaged (ignore {ignore})"
        );
    }
}

#[test]
fn a_trace_killed_midway_leaves_the_earlier_trace_whole() {
    let tmp = tempfile::tempdir().unwrap();
    let trace = tmp.path().join("trace.csv");
    let exp = fixture("tiny.toml");
    run_ok(&[
        "simulate",
        exp.to_str().unwrap(),
        "--ticks",
        "50",
        "--trace",
        trace.to_str().unwrap(),
    ]);
    let earlier = read(&trace);
    // SIGKILL while a long trace is being written.
    let mut child = bin()
        .args([
            "simulate",
            exp.to_str().unwrap(),
            "--ticks",
            "10000000",
            "--trace",
            trace.to_str().unwrap(),
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let deadline = Instant::now() + Duration::from_secs(60);
    loop {
        let temp_size: u64 = std::fs::read_dir(tmp.path())
            .unwrap()
            .map(|e| e.unwrap())
            .filter(|e| e.file_name().to_string_lossy().contains(".tmp-"))
            .map(|e| e.metadata().unwrap().len())
            .sum();
        if temp_size > 1 << 20 {
            break;
        }
        assert!(Instant::now() < deadline, "no trace being written");
        std::thread::sleep(Duration::from_millis(5));
    }
    child.kill().unwrap();
    child.wait().unwrap();
    assert!(read(&trace) == earlier, "SIGKILL damaged the earlier trace");
    // A file size limit during replay --trace and simulate --trace.
    let run = tmp.path().join("run");
    tiny_run(&run);
    let best = run.join("best.json");
    for ignore in [false, true] {
        let o = under_file_limit(
            2,
            ignore,
            &[
                "replay",
                best.to_str().unwrap(),
                "--experiment",
                exp.to_str().unwrap(),
                "--trace",
                trace.to_str().unwrap(),
            ],
        );
        assert!(!o.status.success());
        assert!(
            read(&trace) == earlier,
            "replay --trace damaged the earlier trace"
        );
        let o = under_file_limit(
            2,
            ignore,
            &[
                "simulate",
                exp.to_str().unwrap(),
                "--ticks",
                "5000",
                "--trace",
                trace.to_str().unwrap(),
            ],
        );
        assert!(!o.status.success());
        assert!(
            read(&trace) == earlier,
            "simulate --trace damaged the earlier trace"
        );
    }
    // With the signal ignored the program itself saw the error and removed its temporary file.
    let _ = under_file_limit(
        2,
        true,
        &[
            "simulate",
            exp.to_str().unwrap(),
            "--ticks",
            "5000",
            "--trace",
            trace.to_str().unwrap(),
        ],
    );
    no_temp_files(tmp.path());
}

#[test]
fn an_output_that_names_an_input_is_refused_and_the_input_kept() {
    let tmp = tempfile::tempdir().unwrap();
    let run = tmp.path().join("run");
    tiny_run(&run);
    let best = run.join("best.json");
    let exp = fixture("tiny.toml");
    let before = read(&best);
    let err = run_err(&[
        "replay",
        best.to_str().unwrap(),
        "--experiment",
        exp.to_str().unwrap(),
        "--trace",
        best.to_str().unwrap(),
    ]);
    assert!(
        err.contains("--trace") && err.contains("an input of this command"),
        "{err}"
    );
    // Through a symbolic link too.
    let link = tmp.path().join("link.csv");
    std::os::unix::fs::symlink(&best, &link).unwrap();
    let err = run_err(&[
        "replay",
        best.to_str().unwrap(),
        "--experiment",
        exp.to_str().unwrap(),
        "--trace",
        link.to_str().unwrap(),
    ]);
    // replay resolves links before comparing (its message), the shared check compares
    // device and inode (its message): either way the input is refused and kept.
    assert!(
        err.contains("the same file as") || err.contains("an input of this command"),
        "{err}"
    );
    assert!(read(&best) == before);

    let copy = tmp.path().join("exp.toml");
    std::fs::copy(&exp, &copy).unwrap();
    let err = run_err(&[
        "simulate",
        copy.to_str().unwrap(),
        "--trace",
        copy.to_str().unwrap(),
    ]);
    assert!(err.contains("an input of this command"), "{err}");
    assert!(read(&copy) == read(&exp));

    let cps: Vec<_> = std::fs::read_dir(run.join("checkpoints"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    let oldest = cps.iter().min().unwrap().clone();
    let before = read(&oldest);
    let err = run_err(&[
        "export-csv",
        run.to_str().unwrap(),
        "-o",
        oldest.to_str().unwrap(),
    ]);
    assert!(err.contains("checkpoint"), "{err}");
    assert!(read(&oldest) == before);
    let fitness = run.join("fitness.csv");
    let before = read(&fitness);
    let err = run_err(&[
        "export-csv",
        run.to_str().unwrap(),
        "-o",
        fitness.to_str().unwrap(),
    ]);
    assert!(err.contains("an input of this command"), "{err}");
    assert!(read(&fitness) == before);
}
