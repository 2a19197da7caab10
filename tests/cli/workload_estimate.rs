//! The workload estimate: `inspect` prints the whole run's creature-ticks and an estimated
//! wall time in plain words (and as JSON with the same numbers); `run` prints it before the
//! first generation, warns above an hour and starts anyway; `--no-estimate` silences both;
//! the calibration changes no output file.

use crate::cli_common::{bin, experiment, fixture, read, run_ok};
use std::io::{BufRead, BufReader};
use std::path::Path;
use std::process::{Command, Stdio};
use std::sync::mpsc;
use std::time::Duration;

/// 256000 → "256,000", as the text prints counts.
fn grouped(n: u64) -> String {
    let digits = n.to_string();
    let mut out = String::new();
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i) % 3 == 0 {
            out.push(',');
        }
        out.push(c);
    }
    out
}

fn stdout_of(args: &[&str]) -> String {
    String::from_utf8(run_ok(args).stdout).unwrap()
}

#[test]
fn inspect_prints_the_brain_the_workload_and_an_estimate_in_plain_words() {
    let text = stdout_of(&["inspect", &experiment("foraging.toml")]);
    for rust in ["BrainSpec", "Some(", "None", "..", "Smell:"] {
        assert!(!text.contains(rust), "Rust Debug output `{rust}`:\n{text}");
    }
    for line in [
        "brain: MLP 24 → 2 (no hidden layer), tanh outputs, f64 sums, 50 parameters",
        "  smell sensors (8 receptors left, 8 right): inputs 0 to 15",
        "  shock sensor: input 22",
        "fitness: A + B + C + D of the metabolism at the end of life, + 0.005 × LU driven forward",
        "behaviour measures: distinct_food, food_types",
        "champion: the best on 10 validation worlds of each generation's top 3, every 10 \
         generations and after the last",
        "evolution: genetic algorithm, 200 generations of 64 individuals",
        "workload: 64 individuals × 5 trials × 800 ticks = 256,000 creature-ticks per generation",
        // [validation] every 10 generations, top 3, 10 worlds.
        "validation: 20 rounds × up to 3 candidates × 10 worlds × 800 ticks = 480,000 creature-ticks",
        "whole run: 200 generations × 256,000 creature-ticks + validation = 51,680,000 creature-ticks",
    ] {
        assert!(text.lines().any(|l| l == line), "no line `{line}`:\n{text}");
    }
    let time = text
        .lines()
        .find(|l| l.starts_with("estimated wall time: "))
        .unwrap_or_else(|| panic!("no estimate:\n{text}"));
    assert!(time.contains("per generation) on "), "{time}");
    assert!(
        text.contains("creature-ticks per second measured just now on this machine"),
        "the estimate does not say what it is based on:\n{text}"
    );

    let skipped = stdout_of(&["inspect", &experiment("foraging.toml"), "--no-estimate"]);
    assert!(
        skipped.contains("estimated wall time: not measured (--no-estimate)"),
        "{skipped}"
    );
    assert!(skipped.contains("51,680,000 creature-ticks"), "{skipped}");
}

#[test]
fn inspect_json_carries_the_numbers_of_the_text() {
    let file = experiment("foraging.toml");
    let text = stdout_of(&["inspect", &file, "--jobs", "1"]);
    let json_text = stdout_of(&["inspect", &file, "--jobs", "1", "--json"]);
    assert!(
        json_text.starts_with("{\n  \"schema\": \"berry-evolve/inspect/1\","),
        "{json_text}"
    );
    let json: serde_json::Value = serde_json::from_str(&json_text).unwrap();
    let w = &json["workload"];
    for key in [
        "individuals",
        "trials",
        "ticks",
        "creature_ticks_per_generation",
        "validations",
        "validation_creature_ticks",
        "total_creature_ticks",
        "generations",
    ] {
        let n = w[key].as_u64().unwrap_or_else(|| panic!("workload.{key}"));
        assert!(
            text.contains(&grouped(n)),
            "{key} = {n} not in the text:\n{text}"
        );
    }
    assert_eq!(w["total_creature_ticks"], 51_680_000);
    assert_eq!(json["brain"]["parameters"], 50);
    assert_eq!(json["brain"]["kind"], "mlp");
    assert_eq!(json["brain"]["hidden"], serde_json::json!([]));
    assert!(text.contains(json["brain"]["description"].as_str().unwrap()));
    for key in ["fitness", "champion"] {
        let line = json[key].as_str().unwrap_or_else(|| panic!("{key}"));
        assert!(text.contains(&format!("{key}: {line}\n")), "{key}: {line}");
    }
    assert_eq!(
        json["behaviour_measures"],
        serde_json::json!(["distinct_food", "food_types"])
    );
    assert_eq!(json["inputs"], 24);
    assert_eq!(json["observation"][0]["group"], "smell");
    assert_eq!(json["observation"][0]["end"], 16);
    assert_eq!(json["config_hash"].as_str().map(str::len), Some(64));
    assert!(text.contains(json["config_hash"].as_str().unwrap()));
    // The estimate: on the threads asked for, and consistent with itself.
    let e = &json["estimate"];
    assert_eq!(e["calibration"]["threads"], 1);
    assert!(text.contains("on 1 worker thread\n") || text.contains("on 1 worker thread"));
    let per_generation = e["seconds_per_generation"].as_f64().unwrap();
    let total = e["total_seconds"].as_f64().unwrap();
    let validation = e["validation_seconds"].as_f64().unwrap();
    assert!(per_generation > 0.0 && validation > 0.0, "{e}");
    assert!(
        (total - (200.0 * per_generation + validation)).abs() <= 1e-9 * total,
        "{e}"
    );
    assert!(
        e["calibration"]["elapsed_seconds"].as_f64().unwrap() < 1.0,
        "{e}"
    );

    let skipped = stdout_of(&["inspect", &file, "--json", "--no-estimate"]);
    let skipped: serde_json::Value = serde_json::from_str(&skipped).unwrap();
    assert!(skipped["estimate"].is_null());
    assert_eq!(skipped["workload"], json["workload"]);
}

#[test]
fn inspect_says_every_fitness_term_and_how_the_champion_is_chosen() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("terms.toml");
    let tiny = String::from_utf8(read(&fixture("tiny.toml"))).unwrap();
    std::fs::write(
        &file,
        format!(
            "{tiny}\n[[world.areas]]\nname = \"nest\"\nregion = [0.0, 0.0, 20.0, 20.0]\n\
             kind = \"safe\"\n\
             [fitness]\nweights = [2.0, 0.0, 1.0, 0.0]\nbalance = \"min\"\nmode = \"integrated\"\n\
             imbalance_penalty = 0.5\nalive_bonus = 0.25\narea = \"nest\"\narea_bonus = 1.5\n\
             goal_point = [10.0, 10.0]\ngoal_bonus = 3.0\ngoal_at = \"closest\"\n\
             distinct_food_bonus = 0.5\nforward_bonus = 0.01\nshock_penalty = 2.0\n\
             death_penalty = 100.0\n[behaviour]\nmeasures = [\"ticks_alive\", \"time_in_area\"]\n\
             area = \"nest\"\n"
        ),
    )
    .unwrap();
    let text = stdout_of(&["inspect", file.to_str().unwrap(), "--no-estimate"]);
    for line in [
        "fitness: the smallest of 2 × A, C of the metabolism summed over every tick of life, \
         − 0.5 × (largest − smallest), + 0.25 × tick alive, + 1.5 × tick in area `nest`, \
         + 3 × nearness to [10, 10] at its closest, + 0.5 × distinct food object eaten, \
         + 0.01 × LU driven forward, − 2 × shocked tick, − 100 if killed",
        "behaviour measures: ticks_alive, time_in_area",
        "champion: the best training evaluation of the run (no [validation]: the luckiest, not \
         necessarily the best on new worlds)",
    ] {
        assert!(text.lines().any(|l| l == line), "no line `{line}`:\n{text}");
    }
    let plain = stdout_of(&[
        "inspect",
        fixture("tiny.toml").to_str().unwrap(),
        "--no-estimate",
    ]);
    assert!(
        plain.contains("behaviour measures: none ([behaviour] measures)\n"),
        "{plain}"
    );
}

/// Starts `berry-evolve run tiny.toml --generations 1000000000 --out dir extra...` (estimated
/// at days), reads stderr until `until` matches a line, stops the run with SIGINT and returns
/// everything it wrote on stderr.
fn start_long_run_and_stop(dir: &Path, extra: &[&str], until: &str) -> String {
    let tiny = fixture("tiny.toml");
    let mut args = vec![
        "run",
        tiny.to_str().unwrap(),
        "--generations",
        "1000000000",
        "--out",
        dir.to_str().unwrap(),
    ];
    args.extend(extra);
    let mut child = bin()
        .args(&args)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let (tx, rx) = mpsc::channel();
    let stderr = child.stderr.take().unwrap();
    let reader = std::thread::spawn(move || {
        for line in BufReader::new(stderr).lines() {
            let line = line.unwrap();
            let _ = tx.send(line);
        }
    });
    let mut seen = Vec::new();
    loop {
        let line = rx
            .recv_timeout(Duration::from_secs(60))
            .unwrap_or_else(|_| panic!("no `{until}` line; stderr so far:\n{}", seen.join("\n")));
        let found = line.contains(until);
        seen.push(line);
        if found {
            break;
        }
    }
    Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    let status = child.wait().unwrap();
    reader.join().unwrap();
    seen.extend(rx.try_iter());
    let stderr = seen.join("\n");
    assert!(!status.success(), "a stopped run reports it:\n{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    stderr
}

#[test]
fn a_run_estimated_above_an_hour_warns_and_starts_and_ctrl_c_stops_it() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("run");
    let stderr = start_long_run_and_stop(&dir, &[], "warning:");
    let warning = stderr.lines().find(|l| l.starts_with("warning:")).unwrap();
    for words in [
        "this run is estimated to take",
        "per generation",
        "Ctrl-C stops it after the current generation",
        "--generations N",
        "evaluation.ticks",
        "--no-estimate",
    ] {
        assert!(warning.contains(words), "`{words}` missing: {warning}");
    }
    // Estimated at days or years, not minutes.
    assert!(
        warning.contains(" days (") || warning.contains(" years ("),
        "{warning}"
    );
    let estimate = stderr
        .find("estimated wall time:")
        .expect("the estimate line");
    assert!(estimate < stderr.find("warning:").unwrap(), "{stderr}");
    // The warning comes before any generation is reported, and the stop left a checkpoint.
    assert!(
        !stderr[..stderr.find("warning:").unwrap()].contains("generation    0"),
        "{stderr}"
    );
    assert!(
        stderr.contains("stopping after this generation"),
        "{stderr}"
    );
    assert!(dir.join("checkpoints").read_dir().unwrap().next().is_some());
}

#[test]
fn no_estimate_skips_the_estimate_and_the_warning() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("run");
    let stderr = start_long_run_and_stop(&dir, &["--no-estimate"], "generation    0");
    assert!(!stderr.contains("warning"), "{stderr}");
    assert!(!stderr.contains("estimated"), "{stderr}");
}

#[test]
fn quiet_keeps_the_warning_but_not_the_estimate_line() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("run");
    let stderr = start_long_run_and_stop(&dir, &["--quiet"], "warning:");
    assert!(!stderr.contains("estimated wall time"), "{stderr}");
}

#[test]
fn the_calibration_changes_no_output_file() {
    let tmp = tempfile::tempdir().unwrap();
    let tiny = fixture("tiny.toml");
    let dirs: Vec<_> = [&[][..], &["--no-estimate"][..]]
        .iter()
        .enumerate()
        .map(|(i, extra)| {
            let dir = tmp.path().join(format!("run-{i}"));
            let mut args = vec![
                "run",
                tiny.to_str().unwrap(),
                "--out",
                dir.to_str().unwrap(),
            ];
            args.extend(*extra);
            let out = run_ok(&args);
            let stderr = String::from_utf8_lossy(&out.stderr).to_string();
            assert_eq!(
                stderr.contains("estimated wall time: "),
                extra.is_empty(),
                "{stderr}"
            );
            dir
        })
        .collect();
    for file in [
        "fitness.csv",
        "best.json",
        "experiment.toml",
        "checkpoints/gen-000007.json",
    ] {
        assert!(
            read(&dirs[0].join(file)) == read(&dirs[1].join(file)),
            "{file} differs with the calibration"
        );
    }
}

/// A life of several episodes lives `ticks` in each: the workload counts every episode (a
/// t-maze-switch life is 10 episodes of 180 ticks), in the text and in the JSON.
#[test]
fn the_workload_counts_every_episode_of_a_life() {
    let file = experiment("t-maze-switch.toml");
    let text = stdout_of(&["inspect", &file, "--no-estimate"]);
    assert!(
        text.contains("workload: 128 individuals × 4 trials × 10 episodes × 180 ticks = 921,600 creature-ticks per generation"),
        "{text}"
    );
    let json: serde_json::Value =
        serde_json::from_str(&stdout_of(&["inspect", &file, "--json", "--no-estimate"])).unwrap();
    assert_eq!(json["workload"]["episodes"], 10, "{json}");
    assert_eq!(
        json["workload"]["creature_ticks_per_generation"], 921_600,
        "{json}"
    );
}

#[test]
fn inspect_points_a_large_brain_in_draw_order_1_to_draw_order_2() {
    let dir = tempfile::tempdir().unwrap();
    let tiny = String::from_utf8(read(&fixture("tiny.toml"))).unwrap();
    // 24 inputs (tiny's senses) → 100 → 2 is about 2,700 parameters, over the 2,000 noted.
    let large = tiny.replace("hidden = [4]", "hidden = [100]");
    assert_ne!(large, tiny);
    for (name, text, noted) in [
        ("small.toml", tiny.clone(), false),
        ("large.toml", large.clone(), true),
        (
            "large-order-2.toml",
            large.replacen("\n[evolution]\n", "\n[evolution]\ndraw_order = 2\n", 1),
            false,
        ),
    ] {
        let file = dir.path().join(name);
        std::fs::write(&file, text).unwrap();
        let out = stdout_of(&["inspect", file.to_str().unwrap(), "--no-estimate"]);
        assert_eq!(
            out.contains("`[evolution] draw_order = 2`"),
            noted,
            "{name}:\n{out}"
        );
        let json = stdout_of(&["inspect", file.to_str().unwrap(), "--no-estimate", "--json"]);
        assert_eq!(json.contains("draw_order = 2"), noted, "{name} (JSON)");
        if name == "large-order-2.toml" {
            assert!(
                out.contains(", draw order 2 (offspring in parallel"),
                "{out}"
            );
        }
    }
}
