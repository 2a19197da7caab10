//! What the console says in plain words: generations numbered from 0 as in the files, the
//! end-of-run line rounds its numbers, and
//! `compare` names the worlds it scores on (the held-out set by default, a generation's
//! training worlds when asked), and a mistyped subcommand is answered with the one it resembles.

use crate::cli_common::{fixture, run_ok};

/// Runs tiny.toml for 2 generations into a fresh folder; returns the folder and stderr.
fn tiny_run() -> (tempfile::TempDir, String) {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("run");
    let out = run_ok(&[
        "run",
        fixture("tiny.toml").to_str().unwrap(),
        "--generations",
        "2",
        "--out",
        dir.to_str().unwrap(),
    ]);
    (tmp, String::from_utf8_lossy(&out.stderr).to_string())
}

#[test]
fn the_done_line_rounds_the_metabolism_to_four_decimals() {
    let (_tmp, stderr) = tiny_run();
    let line = stderr
        .lines()
        .find(|l| l.starts_with("done: "))
        .unwrap_or_else(|| panic!("no done: line in\n{stderr}"));
    let inside = line
        .split("metabolism [")
        .nth(1)
        .and_then(|s| s.strip_suffix(']'))
        .unwrap_or_else(|| panic!("no metabolism [..] in {line}"));
    let parts: Vec<&str> = inside.split(", ").collect();
    assert_eq!(parts.len(), 4, "{line}");
    for p in parts {
        let decimals = p.split('.').nth(1).unwrap_or("");
        assert_eq!(decimals.len(), 4, "{p} in {line}");
        assert!(p.parse::<f64>().is_ok(), "{p} in {line}");
    }
}

#[test]
fn compare_names_the_held_out_worlds_or_the_generation_asked_for() {
    let (tmp, _) = tiny_run();
    let best = tmp.path().join("run").join("best.json");
    let best = best.to_str().unwrap();
    let tiny = fixture("tiny.toml");
    let tiny = tiny.to_str().unwrap();
    // The first line of `compare` on tiny.toml for `best` with `extra` flags.
    let first_line = |extra: &[&str]| {
        let mut args = vec![
            "compare",
            "--experiment",
            tiny,
            best,
            "--trials",
            "2",
            "--random",
            "2",
        ];
        args.extend_from_slice(extra);
        let out = run_ok(&args);
        let text = String::from_utf8_lossy(&out.stdout).to_string();
        text.lines().next().unwrap_or("").to_string()
    };
    let held_out = first_line(&[]);
    assert!(
        held_out.contains("on the held-out worlds (never used in training or validation)"),
        "{held_out}"
    );
    assert!(!held_out.contains("1099511627776"), "{held_out}");
    let asked = first_line(&["--generation", "3"]);
    assert!(
        asked.contains("on generation 3's training worlds"),
        "{asked}"
    );
}

#[test]
fn a_mistyped_subcommand_is_answered_with_the_subcommand_it_resembles() {
    let err = crate::cli_common::run_err(&["inpsect", "experiments/foraging.toml"]);
    assert!(
        err.contains("`inpsect` is not a subcommand; did you mean `inspect`?"),
        "{err}"
    );
    assert!(!err.contains("cannot be used with"), "{err}");
}

#[test]
fn the_console_numbers_generations_from_0_as_the_files_do() {
    let (tmp, stderr) = tiny_run();
    assert!(stderr.contains("generation    0 (1/2 done): "), "{stderr}");
    assert!(stderr.contains("generation    1 (2/2 done): "), "{stderr}");
    // The last generation's line names the generation of the last checkpoint.
    assert!(tmp.path().join("run/checkpoints/gen-000001.json").exists());
}

#[test]
fn best_json_records_the_seed_and_replay_names_it_when_another_is_used() {
    let (tmp, _) = tiny_run();
    let best = tmp.path().join("run").join("best.json");
    let json: serde_json::Value = serde_json::from_slice(&crate::cli_common::read(&best)).unwrap();
    assert_eq!(json["origin"]["seed"], 5, "{json}");
    let tiny = fixture("tiny.toml");
    let out = run_ok(&[
        "replay",
        best.to_str().unwrap(),
        "--experiment",
        tiny.to_str().unwrap(),
        "--seed",
        "9",
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr
            .contains("was evolved with seed 5, this experiment has seed 9; replay with --seed 5"),
        "{stderr}"
    );
    let same = run_ok(&[
        "replay",
        best.to_str().unwrap(),
        "--experiment",
        tiny.to_str().unwrap(),
    ]);
    assert!(!String::from_utf8_lossy(&same.stderr).contains("evolved with seed"));
}
