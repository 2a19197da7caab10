//! Seeing learning (issue 31): `replay --trace` of a plastic brain records per tick the
//! modulatory signal m, its gate g, ‖Δw‖ and the weights of a few followed synapses, across the
//! episodes of a life (continuous weights), with each episode and switch marked; the replay page
//! of a plastic brain's life has a strip of those weights, a fixed brain's none; and a fixed
//! brain's trace of a life of one episode is byte for byte what it was before.
//!
//! The plastic genome is a fixture: 5 generations of `experiments/t-maze-switch.toml` with
//! `plasticity = "neuromodulated"`, `granularity = "network"`, modulators food A–C and one
//! modulatory neuron (tests/fixtures/plastic-t-maze.toml, the run folder's experiment file);
//! the fixed one, generation 0 of the shipped file (t-maze-switch-mlp-best.json).

use crate::cli_common::{experiment, fixture, read, run_err, run_ok};
use berry_evolve::brain::activation::tanh;
use berry_evolve::experiment::Experiment;
use serde_json::Value;
use sha2::{Digest, Sha256};
use std::collections::BTreeMap;
use std::path::Path;

/// The JSON lines of `path`.
fn lines(path: &Path) -> Vec<Value> {
    String::from_utf8(read(path))
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect()
}

/// Replays `genome` (trial 0 of the fixture experiment) into `dir`, with `extra` arguments;
/// returns the JSON lines.
fn replay(genome: &Path, dir: &Path, extra: &[&str]) -> Vec<Value> {
    let exp = fixture("plastic-t-maze.toml");
    let (csv, jsonl) = (dir.join("t.csv"), dir.join("t.jsonl"));
    let mut args = vec![
        "replay",
        genome.to_str().unwrap(),
        "--experiment",
        exp.to_str().unwrap(),
        "--trial",
        "0",
        "--trace",
        csv.to_str().unwrap(),
        "--trace-jsonl",
        jsonl.to_str().unwrap(),
    ];
    args.extend(extra);
    run_ok(&args);
    lines(&jsonl)
}

/// Per episode (in order): the learning line's first creature, and its tick rows.
fn episodes(trace: &[Value]) -> Vec<(Value, Vec<Value>)> {
    let mut out: Vec<(Value, Vec<Value>)> = Vec::new();
    for r in trace {
        match r["type"].as_str().unwrap() {
            "learning" => out.push((r["creatures"][0].clone(), Vec::new())),
            "tick" => {
                let row = r["learning"][0].clone();
                assert!(!row.is_null(), "a plastic brain's tick has learning: {r}");
                out.last_mut().unwrap().1.push(row);
            }
            _ => {}
        }
    }
    out
}

fn numbers(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

#[test]
fn a_plastic_trace_holds_m_g_the_norm_and_the_followed_weights_continuous_over_the_life() {
    let dir = tempfile::tempdir().unwrap();
    let genome = fixture("plastic-t-maze-best.json");
    let trace = replay(&genome, dir.path(), &[]);
    let eps = episodes(&trace);
    assert_eq!(eps.len(), 10, "one learning line per episode of the life");
    let (first, _) = &eps[0];
    assert_eq!(first["chosen"], "moved_most");
    let synapses = first["synapses"].as_array().unwrap();
    assert_eq!(synapses.len(), 6, "the 6 that moved most by default");
    // Tick 0 of the life: the genome's own weights, bit for bit.
    let e = Experiment::load(&fixture("plastic-t-maze.toml")).unwrap();
    let names = e.topology().parameter_names();
    let file: Value = serde_json::from_slice(&read(&genome)).unwrap();
    let parameters = numbers(&file["parameters"]);
    for (s, w) in synapses.iter().zip(numbers(&first["start"])) {
        let name = s["name"].as_str().unwrap();
        let k = names.iter().position(|n| n == name).unwrap();
        assert_eq!(w.to_bits(), parameters[k].to_bits(), "{name} at tick 0");
    }
    let mut all_m = Vec::new();
    let mut previous: Option<Vec<f64>> = None;
    let mut moved = 0;
    for (info, rows) in &eps {
        assert_eq!(
            info["synapses"], first["synapses"],
            "the same synapses all life"
        );
        // Each episode starts where the one before ended: the brain kept its weights.
        let start = numbers(&info["start"]);
        if let Some(p) = &previous {
            assert_eq!(&start, p, "weights carry over the episode boundary");
        }
        let mut before = start;
        for r in rows {
            let m = r["m"].as_f64().unwrap();
            let g = r["g"].as_f64().unwrap();
            assert_eq!(g.to_bits(), tanh(m * 0.5).to_bits(), "g = tanh(m/2): {r}");
            all_m.push(m);
            let w = numbers(&r["weights"]);
            let norm = r["dw_norm"].as_f64().unwrap();
            // ‖Δw‖ over all weights is at least each followed weight's change.
            for (a, b) in w.iter().zip(&before) {
                assert!(
                    norm >= (a - b).abs(),
                    "‖Δw‖ {norm} below a change {}",
                    a - b
                );
            }
            if w != before {
                moved += 1;
            }
            before = w;
        }
        previous = Some(before);
    }
    assert!(
        moved > 10,
        "the followed weights change over the life ({moved} ticks)"
    );
    all_m.sort_by(f64::total_cmp);
    all_m.dedup();
    assert!(all_m.len() > 10, "m changes over ticks");
    // The CSV files say the same: learning rows per tick, synapse rows from tick 0.
    let learning = String::from_utf8(read(&dir.path().join("t-learning.csv"))).unwrap();
    assert!(learning.starts_with("trial,episode,tick,creature,m,g,dw_norm\n"));
    let ticks: usize = eps.iter().map(|(_, rows)| rows.len()).sum();
    assert_eq!(learning.lines().count(), 1 + ticks);
    let synapses_csv = String::from_utf8(read(&dir.path().join("t-synapses.csv"))).unwrap();
    assert_eq!(synapses_csv.lines().count(), 1 + 6 * (ticks + eps.len()));
}

#[test]
fn the_followed_synapses_are_those_that_moved_most_or_those_named() {
    let dir = tempfile::tempdir().unwrap();
    let genome = fixture("plastic-t-maze-best.json");
    let e = Experiment::load(&fixture("plastic-t-maze.toml")).unwrap();
    // Every synapse of the 25 → 8 → 2 network, named.
    let inputs = e.topology().inputs;
    let mut every = Vec::new();
    for from in 0..inputs {
        for to in 0..8 {
            every.push(format!("h0:{from}:{to}"));
        }
    }
    for from in 0..8 {
        for to in 0..2 {
            every.push(format!("out:{from}:{to}"));
        }
    }
    let all = replay(&genome, dir.path(), &["--synapses", &every.join(",")]);
    let eps = episodes(&all);
    assert_eq!(eps[0].0["chosen"], "named");
    let names: Vec<String> = eps[0].0["synapses"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["name"].as_str().unwrap().to_string())
        .collect();
    assert_eq!(names.len(), every.len());
    let start = numbers(&eps[0].0["start"]);
    let end = numbers(&eps.last().unwrap().1.last().unwrap()["weights"]);
    // The JSON lines round nothing: the largest |w_end − w_start|, ties to the lower index
    // (the live weights are input-major: h0 from input i to unit j is 8·i + j, then out).
    let index = |n: &str| {
        every.iter().position(|x| {
            let p: Vec<&str> = x.split(':').collect();
            let l = if p[0] == "h0" { "h0" } else { "out" };
            format!("w_{l}[{}][{}]", p[2], p[1]) == n
        })
    };
    let mut order: Vec<usize> = (0..names.len()).collect();
    order.sort_by(|&a, &b| {
        let (ma, mb) = ((end[a] - start[a]).abs(), (end[b] - start[b]).abs());
        mb.total_cmp(&ma)
            .then(index(&names[a]).cmp(&index(&names[b])))
    });
    let want: Vec<&str> = order[..6].iter().map(|&k| names[k].as_str()).collect();
    let dir2 = tempfile::tempdir().unwrap();
    let default = replay(&genome, dir2.path(), &[]);
    let got: Vec<String> = episodes(&default)[0].0["synapses"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["name"].as_str().unwrap().to_string())
        .collect();
    assert_eq!(got, want, "the default follows the 6 that moved most");
    // A name out of range is a clear error naming the flag.
    let out = crate::cli_common::bin()
        .args([
            "replay",
            genome.to_str().unwrap(),
            "--experiment",
            fixture("plastic-t-maze.toml").to_str().unwrap(),
            "--trial",
            "0",
            "--trace-jsonl",
            dir.path().join("x.jsonl").to_str().unwrap(),
            "--synapses",
            "out:9:0",
        ])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(
        stderr.contains("--synapses out:9:0") && stderr.contains("layer out has inputs 0..8"),
        "{stderr}"
    );
}

#[test]
fn with_eta_zero_the_norm_is_zero_and_the_weights_stay_the_genomes() {
    let dir = tempfile::tempdir().unwrap();
    let e = Experiment::load(&fixture("plastic-t-maze.toml")).unwrap();
    let names = e.topology().parameter_names();
    let eta = names.iter().position(|n| n == "rule_eta").unwrap();
    let mut file: Value =
        serde_json::from_slice(&read(&fixture("plastic-t-maze-best.json"))).unwrap();
    file["parameters"][eta] = Value::from(0.0);
    let genome = dir.path().join("eta0.json");
    std::fs::write(&genome, serde_json::to_vec(&file).unwrap()).unwrap();
    let trace = replay(&genome, dir.path(), &["--synapses", "h0:0:0,out:3:1"]);
    let eps = episodes(&trace);
    let start = numbers(&eps[0].0["start"]);
    let parameters = numbers(&file["parameters"]);
    for (name, w) in ["w_h0[0][0]", "w_out[1][3]"].iter().zip(&start) {
        let k = names.iter().position(|n| n == name).unwrap();
        assert_eq!(w.to_bits(), parameters[k].to_bits(), "{name}");
    }
    for (_, rows) in &eps {
        for r in rows {
            assert_eq!(r["dw_norm"].as_f64(), Some(0.0), "{r}");
            assert_eq!(numbers(&r["weights"]), start, "{r}");
        }
    }
}

#[test]
fn a_life_of_several_episodes_marks_each_episode_and_its_switch() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("t.csv");
    // The shipped (fixed MLP) experiment and a genome of its first generation: no learning
    // files, but the episodes are marked.
    run_ok(&[
        "replay",
        fixture("t-maze-switch-mlp-best.json").to_str().unwrap(),
        "--experiment",
        &experiment("t-maze-switch.toml"),
        "--trial",
        "1",
        "--trace",
        csv.to_str().unwrap(),
    ]);
    assert!(!dir.path().join("t-learning.csv").exists());
    let worlds = lines(&dir.path().join("t-world.jsonl"));
    assert_eq!(worlds.len(), 10);
    let mut switched = Vec::new();
    let mut exchanged = Vec::new();
    for (k, w) in worlds.iter().enumerate() {
        let ep = &w["episode"];
        assert_eq!(ep["episode"], k as u64 + 1);
        assert_eq!(ep["episodes"], 10);
        assert_eq!(
            ep["switch_kinds"],
            serde_json::json!(["left_goal", "right_goal"])
        );
        switched.push(ep["switched"].as_bool().unwrap());
        exchanged.push(ep["exchanged"].as_bool().unwrap());
    }
    // One switch, before an episode in 4..=7, where the exchange flips and only there.
    let at: Vec<usize> = (0..10).filter(|&k| switched[k]).collect();
    assert_eq!(at.len(), 1, "{switched:?}");
    assert!((3..=6).contains(&at[0]), "{at:?}");
    for k in 1..10 {
        assert_eq!(
            exchanged[k] != exchanged[k - 1],
            switched[k],
            "{exchanged:?}"
        );
    }
    // The CSV files say which episode a row belongs to.
    let text = String::from_utf8(read(&csv)).unwrap();
    assert!(text.starts_with("trial,episode,tick,creature,"));
    let episodes: Vec<&str> = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(1).unwrap())
        .collect();
    assert_eq!(episodes.first(), Some(&"1"));
    assert_eq!(episodes.last(), Some(&"10"));
}

#[test]
fn a_fixed_brains_trace_of_one_episode_is_byte_for_byte_as_before() {
    // sha-256 of the files the binary wrote before traces learned about plasticity and
    // episodes (commit 0598c40): foraging, champion of seed 2, trial 1.
    let dir = tempfile::tempdir().unwrap();
    let (csv, jsonl) = (dir.path().join("t.csv"), dir.path().join("t.jsonl"));
    let genome = Path::new(env!("CARGO_MANIFEST_DIR")).join("genomes/foraging-champion-seed2.json");
    run_ok(&[
        "replay",
        genome.to_str().unwrap(),
        "--experiment",
        &experiment("foraging.toml"),
        "--trial",
        "1",
        "--trace",
        csv.to_str().unwrap(),
        "--trace-jsonl",
        jsonl.to_str().unwrap(),
    ]);
    let want = BTreeMap::from([
        (
            "t.csv",
            "181150a8632d7993032151a842d646504428155812404dfb00f6a0a18c154de6",
        ),
        (
            "t-actors.csv",
            "34ec8a879fee232336b1590772aa16d8b8788b2f3984c142495af1f3213fc06f",
        ),
        (
            "t-objects.csv",
            "568af97e3699a601d50935e1ac844a0e591decd49286a54ccb93600ede28861f",
        ),
        (
            "t-events.csv",
            "91dc112e141cbffe6677aa74707eb7e5e43fe365b91162f4125ecc60896d0587",
        ),
        (
            "t-world.jsonl",
            "2c0aa2d8705c7a66efeff1fb9e04a953baab91cbb2f1ebed4451d61c2d7db6c9",
        ),
        (
            "t.jsonl",
            "1a027ddea8def19dc82841d73b303df1a0c71bae2bb0594d8b9b8a14c49d2ef0",
        ),
    ]);
    for (name, hash) in want {
        let digest = Sha256::digest(read(&dir.path().join(name)));
        let got: String = digest.iter().map(|b| format!("{b:02x}")).collect();
        assert_eq!(got, hash, "{name} changed");
    }
    assert!(!dir.path().join("t-learning.csv").exists());
    assert!(!dir.path().join("t-synapses.csv").exists());
}

/// The replay page (`replay GENOME --experiment EXPERIMENT --trial 0 --html`) as text.
fn replay_page(genome: &Path, experiment: &str) -> String {
    let dir = tempfile::tempdir().unwrap();
    let page = dir.path().join("page.html");
    run_ok(&[
        "replay",
        genome.to_str().unwrap(),
        "--experiment",
        experiment,
        "--trial",
        "0",
        "--html",
        page.to_str().unwrap(),
    ]);
    String::from_utf8(read(&page)).unwrap()
}

#[test]
fn the_replay_page_has_the_strip_for_a_plastic_brain_and_none_for_a_fixed_one() {
    let page = replay_page(
        &fixture("plastic-t-maze-best.json"),
        fixture("plastic-t-maze.toml").to_str().unwrap(),
    );
    assert!(
        page.contains("<canvas id=\"strip\""),
        "a strip under the arena"
    );
    let html = &page[..page.find("<script").unwrap()];
    assert_eq!(html.matches("data-kind=\"synapse\"").count(), 6, "6 keys");
    assert!(
        html.contains("data-kind=\"switch\""),
        "the switch is marked"
    );
    assert!(
        html.contains("data-kind=\"episode\""),
        "the episodes are marked"
    );
    // The whole life is on the page: ten world lines.
    assert_eq!(page.matches("\"type\":\"world\"").count(), 10);
    let genome = Path::new(env!("CARGO_MANIFEST_DIR")).join("genomes/t-maze-baseline.json");
    let page = replay_page(&genome, &experiment("t-maze.toml"));
    assert!(!page.contains("id=\"strip\"") && !page.contains("\"type\":\"learning\""));
}

/// The brain replayed is the genome file's: the hand-designed learner (a plastic MLP 24 → 3
/// → 2) replayed in experiments/t-maze-switch.toml, whose own brain is a fixed MLP, still has
/// its plastic weights followed and drawn.
#[test]
fn a_plastic_genome_in_a_fixed_brains_experiment_still_gets_its_strip() {
    let genome = Path::new(env!("CARGO_MANIFEST_DIR")).join("genomes/t-maze-switch-baseline.json");
    let page = replay_page(&genome, &experiment("t-maze-switch.toml"));
    assert!(
        page.contains("<canvas id=\"strip\""),
        "a strip under the arena"
    );
    let html = &page[..page.find("<script").unwrap()];
    // Its one plastic synapse (the memory's bias weight) moves; the page names it first.
    assert!(
        html.contains("w_h0[2][23]"),
        "the memory synapse is followed"
    );
}

#[test]
fn synapses_that_the_brain_lacks_are_refused_naming_the_flag() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("x.jsonl");
    let plastic = [
        fixture("plastic-t-maze-best.json"),
        fixture("plastic-t-maze.toml"),
    ];
    let baseline = Path::new(env!("CARGO_MANIFEST_DIR")).join("genomes/t-maze-baseline.json");
    for (genome, exp, synapses, says) in [
        (
            &plastic[0],
            plastic[1].clone(),
            "h3:1:1",
            "weight layers h0, out (0 to 1)",
        ),
        (
            &plastic[0],
            plastic[1].clone(),
            "h0:1",
            "is not layer:from:to",
        ),
        (
            &plastic[0],
            plastic[1].clone(),
            "h0:24:0",
            "layer h0 has inputs 0..24",
        ),
        (
            &baseline,
            experiment("t-maze.toml").into(),
            "out:0:0",
            "the brain is not plastic",
        ),
    ] {
        let stderr = run_err(&[
            "replay",
            genome.to_str().unwrap(),
            "--experiment",
            exp.to_str().unwrap(),
            "--trial",
            "0",
            "--trace-jsonl",
            out.to_str().unwrap(),
            "--synapses",
            synapses,
        ]);
        assert!(
            stderr.contains(&format!("--synapses {synapses}")) && stderr.contains(says),
            "{stderr}"
        );
    }
}
