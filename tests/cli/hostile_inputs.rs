//! Hostile inputs finish within seconds and bounded memory: a FIFO or `/dev/zero` (or a link
//! to it) as experiment, genome or checkpoint is refused before it is read; oversized files
//! are refused by size; 10^6 walls are refused before parsing; a checkpoint of small numbers
//! is decoded without a tree 17 times its size; long values are cut in messages; `--jobs`
//! and `name` are bounded.

use crate::cli_common::{bin, fixture, run_err, run_ok};
use std::path::Path;
use std::process::{Command, Output};
use std::time::{Duration, Instant};

/// Runs the binary with at most `mb` MB of address space and a 20 s deadline.
fn bounded(mb: u64, args: &[&str]) -> Output {
    let quoted: Vec<String> = args.iter().map(|a| format!("'{a}'")).collect();
    let started = Instant::now();
    let out = Command::new("timeout")
        .arg("20")
        .arg("sh")
        .arg("-c")
        .arg(format!(
            "ulimit -v {}; exec '{}' {}",
            mb * 1024,
            env!("CARGO_BIN_EXE_berry-evolve"),
            quoted.join(" ")
        ))
        .output()
        .unwrap();
    assert!(
        started.elapsed() < Duration::from_secs(15),
        "{args:?} took {:?}",
        started.elapsed()
    );
    out
}

fn refused(out: &Output, needle: &str) -> String {
    let stderr = String::from_utf8_lossy(&out.stderr).to_string();
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.starts_with("error: ") && !stderr.contains("panicked"),
        "{stderr}"
    );
    assert!(stderr.contains(needle), "expected `{needle}` in:\n{stderr}");
    stderr
}

fn mkfifo(path: &Path) {
    assert!(Command::new("mkfifo").arg(path).status().unwrap().success());
}

#[test]
fn fifos_and_devices_are_refused_at_once() {
    let tmp = tempfile::tempdir().unwrap();
    let fifo = tmp.path().join("fifo.toml");
    mkfifo(&fifo);
    let zero = tmp.path().join("zero.json");
    std::os::unix::fs::symlink("/dev/zero", &zero).unwrap();
    let tiny = fixture("tiny.toml");
    for input in [fifo.to_str().unwrap(), "/dev/zero", zero.to_str().unwrap()] {
        refused(&bounded(400, &["inspect", input]), "not a regular file");
        refused(
            &bounded(
                400,
                &["replay", input, "--experiment", tiny.to_str().unwrap()],
            ),
            "not a regular file",
        );
        refused(&bounded(400, &["export-csv", input]), "not a regular file");
    }
    // A FIFO among a run's checkpoints, and as its experiment.toml.
    let dir = tmp.path().join("run");
    run_ok(&[
        "run",
        tiny.to_str().unwrap(),
        "--quiet",
        "--generations",
        "2",
        "--out",
        dir.to_str().unwrap(),
    ]);
    let planted = dir.join("checkpoints/gen-000009.json");
    mkfifo(&planted);
    refused(&bounded(400, &["resume", dir.to_str().unwrap()]), "FIFO");
    refused(
        &bounded(400, &["export-csv", dir.to_str().unwrap()]),
        "FIFO",
    );
    std::fs::remove_file(&planted).unwrap();
    std::fs::remove_file(dir.join("experiment.toml")).unwrap();
    mkfifo(&dir.join("experiment.toml"));
    refused(
        &bounded(
            400,
            &["resume", dir.to_str().unwrap(), "--generations", "3"],
        ),
        "FIFO",
    );
}

#[test]
fn oversized_and_absurd_files_are_refused_quickly_in_bounded_memory() {
    let tmp = tempfile::tempdir().unwrap();
    let base = String::from_utf8(std::fs::read(fixture("tiny.toml")).unwrap()).unwrap();
    // 10^6 walls, compact (23 MB) and spread over lines.
    let walls: String = (0..1_000_000)
        .map(|i| format!("{{from=[{}.5,1],to=[{}.5,3]}},\n", i % 100, i % 100))
        .collect();
    let text = base.replace(
        "arena = [120.0, 120.0]\n",
        &format!("arena = [120.0, 120.0]\nwalls = [\n{walls}]\n"),
    );
    let big = tmp.path().join("walls.toml");
    std::fs::write(&big, &text).unwrap();
    refused(&bounded(400, &["inspect", big.to_str().unwrap()]), "limit");
    // 300,000 walls fit under the size cap: refused before parsing, by the count.
    let walls: String = (0..300_000)
        .map(|i| format!("{{from=[{}.5,1],to=[{}.5,3]}},", i % 100, i % 100))
        .collect();
    let text = base.replace(
        "arena = [120.0, 120.0]\n",
        &format!("arena = [120.0, 120.0]\nwalls = [{walls}]\n"),
    );
    std::fs::write(&big, &text).unwrap();
    refused(
        &bounded(400, &["inspect", big.to_str().unwrap()]),
        "world.walls",
    );

    // A checkpoint of small numbers, correctly signed: decoded in a small multiple of its
    // size (a tree of its 15 million numbers alone would take 480 MB).
    use sha2::{Digest, Sha256};
    let payload = format!("[{}0]", "0,".repeat(15_000_000));
    let program = format!("berry-evolve {}", env!("CARGO_PKG_VERSION"));
    let signed = format!("{{\"format\":1,\"program\":\"{program}\",\"config_hash\":\"ab\",\"generation\":0,\"payload\":{payload}}}");
    let hex: String = Sha256::digest(signed.as_bytes())
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect();
    let file = format!("{{\"format\":1,\"program\":\"{program}\",\"config_hash\":\"ab\",\"generation\":0,\"checksum\":\"sha256:{hex}\",\"payload\":{payload}}}\n");
    let cp = tmp.path().join("small-numbers.json");
    std::fs::write(&cp, file).unwrap();
    refused(
        &bounded(250, &["export-csv", cp.to_str().unwrap()]),
        "expected shape",
    );

    // The size cap, and the variable that raises it.
    let out = bin()
        .args(["inspect", fixture("tiny.toml").to_str().unwrap()])
        .env("BERRY_MAX_INPUT_BYTES", "100")
        .output()
        .unwrap();
    refused(&out, "BERRY_MAX_INPUT_BYTES");
}

#[test]
fn plot_reads_its_tables_under_the_size_cap() {
    let tmp = tempfile::tempdir().unwrap();
    let csv = tmp.path().join("fitness.csv");
    std::fs::write(&csv, "generation,best,mean\n0,1.5,1\n1,2.5,1.5\n").unwrap();
    let svg = tmp.path().join("fitness.svg");
    let args = ["plot", csv.to_str().unwrap(), "-o", svg.to_str().unwrap()];
    // Under a cap smaller than the file: refused by size, naming the file and the variable.
    let out = bin()
        .args(args)
        .env("BERRY_MAX_INPUT_BYTES", "20")
        .output()
        .unwrap();
    let err = refused(&out, "BERRY_MAX_INPUT_BYTES");
    assert!(err.contains("fitness.csv"), "{err}");
    assert!(!svg.exists());
    // Under the default cap the same table is drawn.
    let out = bin().args(args).output().unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(svg.is_file());
}

#[test]
fn long_values_are_cut_in_messages_and_counts_and_names_are_bounded() {
    let tmp = tempfile::tempdir().unwrap();
    let base = String::from_utf8(std::fs::read(fixture("tiny.toml")).unwrap()).unwrap();
    let long = "x".repeat(1 << 20);
    for text in [
        base.replace("name = \"tiny\"", &format!("name = \"{long}\" junk")),
        base.replace("name = \"tiny\"", &format!("name = \"{long}/\"")),
        base.replace("seed = 5", &format!("seed = 5\n{long} = 1")),
    ] {
        let p = tmp.path().join("long.toml");
        std::fs::write(&p, text).unwrap();
        let err = run_err(&["inspect", p.to_str().unwrap()]);
        assert!(err.len() < 4000, "a {}-byte message", err.len());
        let err = run_err(&[
            "run",
            p.to_str().unwrap(),
            "--out",
            tmp.path().join("o").to_str().unwrap(),
        ]);
        assert!(err.len() < 4000, "a {}-byte message", err.len());
    }
    // A valid but huge name (it would name the run folder) is refused, not echoed.
    let p = tmp.path().join("long-name.toml");
    std::fs::write(
        &p,
        base.replace("name = \"tiny\"", &format!("name = \"{long}\"")),
    )
    .unwrap();
    for args in [
        vec!["run", p.to_str().unwrap()],
        vec!["inspect", p.to_str().unwrap()],
    ] {
        let err = run_err(&args);
        assert!(err.len() < 4000, "{args:?}: a {}-byte message", err.len());
        assert!(err.contains("at most 100"), "{err}");
    }
    // A huge path is cut in whatever message quotes it.
    let deep = tmp
        .path()
        .join("d".repeat(200))
        .join("e".repeat(20_000))
        .join("f");
    let err = run_err(&[
        "run",
        fixture("tiny.toml").to_str().unwrap(),
        "--out",
        deep.to_str().unwrap(),
    ]);
    assert!(err.len() < 4000, "a {}-byte message: {err}", err.len());
    assert!(err.contains("more characters"), "{err}");
    for name in ["..", ".", "a/b", ""] {
        let p = tmp.path().join("name.toml");
        std::fs::write(
            &p,
            base.replace("name = \"tiny\"", &format!("name = \"{name}\"")),
        )
        .unwrap();
        let err = run_err(&["run", p.to_str().unwrap(), "--generations", "1"]);
        assert!(err.contains("`name`"), "{name}: {err}");
    }
    let started = Instant::now();
    let out = bin()
        .args([
            "run",
            fixture("tiny.toml").to_str().unwrap(),
            "--jobs",
            "100000",
            "--out",
            tmp.path().join("j").to_str().unwrap(),
        ])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success() && stderr.contains("between 1 and 1024"),
        "{stderr}"
    );
    assert!(started.elapsed() < Duration::from_secs(2));
    assert!(!tmp.path().join("j").exists());
    let out = bin()
        .args(["resume", tmp.path().to_str().unwrap(), "--jobs", "0"])
        .output()
        .unwrap();
    assert!(String::from_utf8_lossy(&out.stderr).contains("between 1 and 1024"));
}
