//! `--json` (compare, replay, run, resume, summary): stdout is exactly one JSON document whose
//! first key is its schema, and it carries the same numbers as the text output of the same
//! command, read back from the text (each text number must equal the JSON value rounded to
//! the decimals the text shows).

use crate::cli_common::{bin, experiment, fixture, run_ok};
use serde_json::Value;
use std::path::Path;
use std::process::Stdio;
use std::time::{Duration, Instant};

/// Parses stdout as one JSON document (serde_json refuses anything after it) whose first key
/// is `schema` with `schema`'s value; returns it.
fn document(stdout: &[u8], schema: &str) -> Value {
    let text = std::str::from_utf8(stdout).expect("stdout is UTF-8");
    let first = format!("{{\n  \"schema\": \"{schema}\",\n");
    assert!(
        text.starts_with(&first),
        "stdout does not begin with the schema key {schema}:\n{text}"
    );
    assert!(
        text.ends_with("}\n"),
        "stdout holds more than the document:\n{text}"
    );
    serde_json::from_str(text)
        .unwrap_or_else(|e| panic!("stdout is not one JSON document: {e}\n{text}"))
}

/// The numbers of a text line, in order, each with the decimals it was printed with
/// (punctuation around them dropped: `[6.0000,` is 6 with 4 decimals, `1:` is 1; a range
/// `0.5–1.5` is two numbers).
fn numbers(line: &str) -> Vec<(f64, usize)> {
    line.split(|c: char| c.is_whitespace() || c == '–')
        .filter_map(|token| {
            let t = token.trim_matches(|c: char| "[](),:;".contains(c));
            let value: f64 = t.parse().ok()?;
            t.chars()
                .next()
                .filter(|c| c.is_ascii_digit() || *c == '-')?;
            Some((value, t.split('.').nth(1).map_or(0, str::len)))
        })
        .collect()
}

/// A JSON number.
fn num(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("{v} is not a number"))
}

/// Asserts that `line`'s numbers are `expected` (JSON values) as the text rounds them.
fn same_numbers(line: &str, expected: &[f64]) {
    let found = numbers(line);
    assert_eq!(
        found.len(),
        expected.len(),
        "numbers of `{line}`: {found:?}, JSON has {expected:?}"
    );
    for (&(text, decimals), &json) in found.iter().zip(expected) {
        assert_eq!(
            format!("{json:.decimals$}"),
            format!("{text:.decimals$}"),
            "`{line}`: the text says {text}, the JSON {json}"
        );
    }
}

/// The line of `text` that starts with `prefix`.
fn line<'a>(text: &'a str, prefix: &str) -> &'a str {
    text.lines()
        .find(|l| l.starts_with(prefix))
        .unwrap_or_else(|| panic!("no line starting with `{prefix}` in:\n{text}"))
}

fn stdout_of(args: &[&str]) -> String {
    String::from_utf8(run_ok(args).stdout).unwrap()
}

/// A genome's fitness, metabolism and measures (means), as the text line lists them.
fn genome_values(g: &Value) -> Vec<f64> {
    let mut v = vec![num(&g["fitness"])];
    v.extend(g["metabolism"].as_array().unwrap().iter().map(num));
    v.extend(g["measures"].as_object().unwrap().values().map(num));
    v
}

#[test]
fn compare_json_carries_the_numbers_of_the_text() {
    let foraging = experiment("foraging.toml");
    let hand = Path::new(env!("CARGO_MANIFEST_DIR")).join("genomes/braitenberg-forager.json");
    let champion =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("genomes/foraging-champion-seed2.json");
    let (hand, champion) = (hand.to_str().unwrap(), champion.to_str().unwrap());
    let args = [
        "compare",
        hand,
        champion,
        "--experiment",
        &foraging,
        "--trials",
        "3",
        "--random",
        "4",
    ];
    let text = stdout_of(&args);
    let out = run_ok(&[&args[..], &["--json"]].concat());
    let d = document(&out.stdout, "berry-evolve/compare/1");
    assert_eq!(d["experiment"], "foraging");
    assert_eq!(d["worlds"]["held_out"], true);
    assert_eq!(d["worlds"]["generation"], 1u64 << 40);
    same_numbers(
        line(&text, "experiment `foraging`"),
        &[num(&d["trials"]), num(&d["ticks"])],
    );
    let genomes = d["genomes"].as_array().unwrap();
    assert_eq!(genomes.len(), 2);
    for (g, path) in genomes.iter().zip([hand, champion]) {
        assert_eq!(g["path"], path);
        same_numbers(line(&text, &format!("{path}: fitness")), &genome_values(g));
        // Every trial is there, and the fitness is their mean (foraging aggregates by mean).
        let trials = g["trials"].as_array().unwrap();
        assert_eq!(trials.len(), 3);
        let scores: Vec<f64> = trials.iter().map(|t| num(&t["score"])).collect();
        let mean = scores.iter().sum::<f64>() / 3.0;
        assert_eq!(num(&g["fitness"]), mean);
        assert_eq!(num(&g["trial_scores"]["mean"]), mean);
        let best = scores.iter().copied().fold(f64::MIN, f64::max);
        assert_eq!(num(&g["trial_scores"]["best"]), best);
        assert_eq!(
            g["measures"]
                .as_object()
                .unwrap()
                .keys()
                .collect::<Vec<_>>(),
            ["distinct_food", "food_types"],
            "the experiment's measures, in its order"
        );
    }
    let r = &d["random"];
    assert_eq!(r["count"], 4);
    assert_eq!(r["genomes"].as_array().unwrap().len(), 4);
    let s = &r["fitness"];
    same_numbers(
        line(&text, "4 random genomes: fitness"),
        &[
            4.0,
            num(&s["mean"]),
            num(&s["std"]),
            num(&s["best"]),
            num(&s["median"]),
        ],
    );
    for name in ["distinct_food", "food_types"] {
        let m = &r["measures"][name];
        same_numbers(
            line(&text, &format!("4 random genomes: {name}")),
            &[4.0, num(&m["median"]), num(&m["best"])],
        );
    }
    // A generation's training worlds are named as such.
    let out = run_ok(
        &[
            &args[..7],
            &["--random", "0", "--generation", "3", "--json"],
        ]
        .concat(),
    );
    let d = document(&out.stdout, "berry-evolve/compare/1");
    assert_eq!(d["worlds"]["held_out"], false);
    assert_eq!(d["worlds"]["generation"], 3);
    assert_eq!(d["random"], Value::Null);
}

#[test]
fn replay_json_carries_the_numbers_of_the_text_and_names_the_trace() {
    let foraging = experiment("foraging.toml");
    let hand = Path::new(env!("CARGO_MANIFEST_DIR")).join("genomes/braitenberg-forager.json");
    let hand = hand.to_str().unwrap();
    let args = [
        "replay",
        hand,
        "--experiment",
        &foraging,
        "--generation",
        "2",
    ];
    let text = stdout_of(&args);
    let tmp = tempfile::tempdir().unwrap();
    let trace = tmp.path().join("t.csv");
    let out = run_ok(&[&args[..], &["--json", "--trace", trace.to_str().unwrap()]].concat());
    let d = document(&out.stdout, "berry-evolve/replay/1");
    assert_eq!(d["genome"], hand);
    assert_eq!(d["generation"], 2);
    assert_eq!(d["seed"], 1);
    let trials = d["trials"].as_array().unwrap();
    assert_eq!(trials.len(), 5, "foraging has 5 trials");
    for t in trials {
        let k = t["trial"].as_u64().unwrap();
        let mut v = vec![k as f64, num(&t["score"])];
        v.extend(t["metabolism"].as_array().unwrap().iter().map(num));
        v.push(num(&t["shocked_ticks"]));
        same_numbers(line(&text, &format!("trial {k}: score")), &v);
        let mut v = vec![k as f64];
        v.extend(t["measures"].as_object().unwrap().values().map(num));
        same_numbers(line(&text, &format!("trial {k}:  measures")), &v);
    }
    same_numbers(
        line(&text, "fitness "),
        &[num(&d["fitness"]), 5.0, num(&d["generation"])],
    );
    // `metabolism [..]` is printed at full precision: the very same values.
    same_numbers(
        line(&text, "metabolism "),
        &d["metabolism"]
            .as_array()
            .unwrap()
            .iter()
            .map(num)
            .collect::<Vec<_>>(),
    );
    same_numbers(
        line(&text, "measures (mean over trials)"),
        &d["measures"]
            .as_object()
            .unwrap()
            .values()
            .map(num)
            .collect::<Vec<_>>(),
    );
    // The trace's five files are named and written; the note about them went to stderr.
    let files = d["files"]["trace"].as_array().unwrap();
    assert_eq!(files.len(), 5);
    assert_eq!(files[0], trace.to_str().unwrap());
    for f in files {
        assert!(Path::new(f.as_str().unwrap()).is_file(), "{f} not written");
    }
    assert!(String::from_utf8_lossy(&out.stderr).contains("trace written to"));
}

/// `run` (or `resume`) with `args`, in text and with --json, each into its own copy of the
/// same folder state; returns (stderr of the text run, the JSON document, its folder).
fn text_and_json(
    tmp: &Path,
    args: impl Fn(&Path) -> Vec<String>,
) -> (String, Value, std::path::PathBuf) {
    let text_dir = tmp.join("text");
    let json_dir = tmp.join("json");
    let a = args(&text_dir);
    let a: Vec<&str> = a.iter().map(String::as_str).collect();
    let out = run_ok(&a);
    assert!(out.stdout.is_empty(), "text run printed on stdout");
    let stderr = String::from_utf8(out.stderr).unwrap();
    let a = args(&json_dir);
    let mut a: Vec<&str> = a.iter().map(String::as_str).collect();
    a.push("--json");
    let out = run_ok(&a);
    let d = document(&out.stdout, "berry-evolve/run/1");
    assert!(
        !String::from_utf8_lossy(&out.stderr).contains("done:"),
        "--json printed the text summary too"
    );
    (stderr, d, json_dir)
}

/// Checks the text summary's numbers against the JSON document of the same run.
fn same_summary(stderr: &str, d: &Value, dir: &Path) {
    let b = &d["best_ever"];
    let mut v = vec![
        num(&d["generations_done"]),
        num(&b["fitness"]),
        num(&b["generation"]),
        num(&b["individual"]),
    ];
    v.extend(b["metabolism"].as_array().unwrap().iter().map(num));
    same_numbers(line(stderr, "done: "), &v);
    assert_eq!(d["status"], "done");
    assert_eq!(d["run_dir"], dir.to_str().unwrap());
    assert_eq!(
        d["best_json"],
        dir.join("best.json").to_str().unwrap(),
        "best.json is named"
    );
    // The program as it was started (a path here, see src/invocation.rs), then the command.
    let resume = d["resume_command"].as_str().unwrap();
    assert!(
        resume.ends_with(&format!("berry-evolve resume {}", dir.display())),
        "{resume}"
    );
    let checkpoint = d["checkpoint"].as_str().unwrap();
    assert!(Path::new(checkpoint).is_file(), "{checkpoint}");
}

#[test]
fn run_and_resume_json_carry_the_numbers_of_the_text_summary() {
    let tmp = tempfile::tempdir().unwrap();
    // foraging validates after the last generation: the validation champion is reported.
    let foraging = experiment("foraging.toml");
    let (stderr, d, dir) = text_and_json(tmp.path(), |dir| {
        [
            "run",
            &foraging,
            "--generations",
            "2",
            "--out",
            dir.to_str().unwrap(),
        ]
        .map(String::from)
        .to_vec()
    });
    same_summary(&stderr, &d, &dir);
    assert_eq!(d["generations_done"], 2);
    let v = &d["validation"];
    same_numbers(
        line(&stderr, "validation champion"),
        &[
            num(&v["fitness"]),
            num(&v["generation"]),
            num(&v["individual"]),
        ],
    );
    // best.json holds the validation champion.
    let best: Value =
        serde_json::from_slice(&std::fs::read(dir.join("best.json")).unwrap()).unwrap();
    assert_eq!(best["origin"]["generation"], v["generation"]);
    // The same run's fitness.csv agrees on best ever (its last row's best_ever column).
    let csv = std::fs::read_to_string(dir.join("fitness.csv")).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let last: Vec<&str> = csv.lines().last().unwrap().split(',').collect();
    let column = header.iter().position(|h| *h == "best_ever").unwrap();
    assert_eq!(
        last[column].parse::<f64>().unwrap(),
        num(&d["best_ever"]["fitness"])
    );

    // resume extends both runs by one generation.
    let (stderr, d, dir) = text_and_json(tmp.path(), |dir| {
        ["resume", dir.to_str().unwrap(), "--generations", "3"]
            .map(String::from)
            .to_vec()
    });
    same_summary(&stderr, &d, &dir);
    assert_eq!(d["generations_done"], 3);
}

#[test]
fn run_json_of_an_interrupted_run_says_so_before_stopping() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("run");
    let mut child = bin()
        .args([
            "run",
            fixture("slow.toml").to_str().unwrap(),
            "--json",
            "--out",
        ])
        .arg(&dir)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("binary starts");
    let csv = dir.join("fitness.csv");
    let deadline = Instant::now() + Duration::from_secs(60);
    while std::fs::read_to_string(&csv).map_or(0, |t| t.lines().count()) < 2 {
        assert!(child.try_wait().unwrap().is_none(), "run ended too soon");
        assert!(Instant::now() < deadline, "no fitness row after 60 s");
        std::thread::sleep(Duration::from_millis(5));
    }
    let status = std::process::Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr).to_string();
    assert_eq!(out.status.code(), Some(130), "{stderr}");
    let d = document(&out.stdout, "berry-evolve/run/1");
    assert_eq!(d["status"], "interrupted");
    let stopped = line(&stderr, "stopped: interrupted after generation ");
    let generation = numbers(stopped)[0].0;
    assert_eq!(num(&d["generations_done"]), generation + 1.0, "{stopped}");
    assert!(
        stopped.contains(d["checkpoint"].as_str().unwrap()),
        "{stopped}"
    );
    // The program as it was started (a path here, see src/invocation.rs), then the command.
    let resume = d["resume_command"].as_str().unwrap();
    assert!(
        resume.ends_with(&format!("berry-evolve resume {}", dir.display())),
        "{resume}"
    );
    assert!(stopped.ends_with(d["resume_command"].as_str().unwrap()));
}

#[test]
fn run_seeds_and_summary_json_carry_the_numbers_of_the_text() {
    let tmp = tempfile::tempdir().unwrap();
    let tiny = fixture("tiny.toml");
    let tiny = tiny.to_str().unwrap();
    let batch = |name: &str| tmp.path().join(name).to_str().unwrap().to_string();
    let (text_batch, json_batch) = (batch("text"), batch("json"));
    let seeds = [
        "run",
        tiny,
        "--seeds",
        "1..2",
        "--generations",
        "2",
        "--quiet",
    ];
    let text = stdout_of(&[&seeds[..], &["--out", &text_batch]].concat());
    let out = run_ok(&[&seeds[..], &["--out", &json_batch, "--json"]].concat());
    let d = document(&out.stdout, "berry-evolve/run-seeds/1");
    let runs = d["runs"].as_array().unwrap();
    assert_eq!(runs.len(), 2);
    for r in runs {
        let seed = r["seed"].as_u64().unwrap();
        assert_eq!(r["continued"], false);
        let b = &r["best_ever"];
        same_numbers(
            line(&text, &format!("seed {seed}: ")),
            &[
                seed as f64,
                num(&r["generations_done"]),
                num(&b["fitness"]),
                num(&b["generation"]),
                num(&b["individual"]),
            ],
        );
    }

    let summary = ["summary", "--random", "3"];
    let text = stdout_of(&[&summary[..], &[text_batch.as_str()]].concat());
    let out = run_ok(&[&summary[..], &[json_batch.as_str(), "--json"]].concat());
    let d = document(&out.stdout, "berry-evolve/summary/1");
    assert_eq!(d["seeds"], serde_json::json!([1, 2]));
    same_numbers(line(&text, "2 seeds, 2 generations"), &[2.0, 2.0]);
    let last = &d["last_generation"];
    same_numbers(
        line(&text, "generation 1: "),
        &[
            num(&last["generation"]),
            num(&last["best_median"]),
            num(&last["best_q1"]),
            num(&last["best_q3"]),
            num(&last["mean_median"]),
        ],
    );
    let h = &d["held_out"];
    let q = &h["seed_fitness"];
    same_numbers(
        line(&text, "held-out fitness over"),
        &[
            num(&h["seeds_with_fitness"]),
            num(&h["trials"]),
            num(&q["median"]),
            num(&q["q1"]),
            num(&q["q3"]),
        ],
    );
    let rows = h["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 4, "two seeds, random median and best");
    for r in rows.iter().filter(|r| r["who"] != "seed") {
        let who = r["who"].as_str().unwrap();
        same_numbers(
            line(&text, &format!("{who}: held-out fitness")),
            &[num(&r["fitness"])],
        );
    }
    // The held-out.csv written beside it has the same fitness values.
    let csv = std::fs::read_to_string(h["held_out_csv"].as_str().unwrap()).unwrap();
    for (r, l) in rows.iter().zip(csv.lines().skip(1)) {
        let fitness: f64 = l.split(',').nth(3).unwrap().parse().unwrap();
        assert_eq!(fitness, num(&r["fitness"]), "{l}");
    }
}

#[test]
fn the_numbers_of_a_text_line_are_read_with_their_decimals() {
    assert_eq!(
        numbers("trial 1: score 36.000000  metabolism [6.0000, 18.5000]  shocked ticks 0"),
        vec![(1.0, 0), (36.0, 6), (6.0, 4), (18.5, 4), (0.0, 0)]
    );
    assert_eq!(
        numbers("genomes/seed2.json: fitness -1.25  (A 0.300, B inf) (quartiles 0.5–1.50)"),
        vec![(-1.25, 2), (0.3, 3), (0.5, 1), (1.5, 2)]
    );
}

/// `compare --measure` reports measures the experiment file does not name, after its own
/// (repeated or comma-separated; a name the file has keeps its place), without changing
/// fitness or the file's measures; an unknown name is refused with the list of names.
#[test]
fn compare_measure_adds_measures_beside_the_files_own() {
    let foraging = experiment("foraging.toml");
    let hand = Path::new(env!("CARGO_MANIFEST_DIR")).join("genomes/braitenberg-forager.json");
    let hand = hand.to_str().unwrap();
    let base = [
        "compare",
        hand,
        "--experiment",
        &foraging,
        "--trials",
        "2",
        "--random",
        "2",
        "--json",
    ];
    let plain = document(&run_ok(&base).stdout, "berry-evolve/compare/1");
    let extra = [
        &base[..],
        &["--measure", "eaten,food_types", "--measure", "still_share"],
    ]
    .concat();
    let more = document(&run_ok(&extra).stdout, "berry-evolve/compare/1");
    let (g0, g1) = (&plain["genomes"][0], &more["genomes"][0]);
    assert_eq!(
        g0["fitness"], g1["fitness"],
        "measures never change fitness"
    );
    let names: Vec<&String> = g1["measures"].as_object().unwrap().keys().collect();
    assert_eq!(
        names,
        ["distinct_food", "eaten", "food_types", "still_share"]
    );
    // The file's measures first, in its order, then the new ones (the text keeps the order).
    let text = [&extra[..8], &extra[9..]].concat();
    let text = stdout_of(&text);
    let at = |name: &str| text.find(&format!("{name} ")).unwrap_or(usize::MAX);
    assert!(
        at("distinct_food") < at("food_types")
            && at("food_types") < at("eaten")
            && at("eaten") < at("still_share")
            && at("still_share") < usize::MAX,
        "{text}"
    );
    for k in ["distinct_food", "food_types"] {
        assert_eq!(g0["measures"][k], g1["measures"][k], "{k}");
    }
    // Nothing decays in foraging: the substance eaten is the final metabolic vector's sum.
    let m: f64 = g1["metabolism"].as_array().unwrap().iter().map(num).sum();
    assert!((num(&g1["measures"]["eaten"]) - m).abs() < 1e-9, "{g1}");
    let still = num(&g1["measures"]["still_share"]);
    assert!((0.0..=1.0).contains(&still), "{still}");
    assert!(more["random"]["measures"]["still_share"]["median"].is_number());
    // Every trial carries them too.
    assert!(g1["trials"][1]["measures"]["eaten"].is_number());

    let problem = crate::cli_common::run_err(&[&base[..], &["--measure", "eatn"]].concat());
    assert!(
        problem.contains("eatn") && problem.contains("still_share"),
        "{problem}"
    );
    // An area measure needs [behaviour] area, which foraging has not: the file is named.
    let problem = crate::cli_common::run_err(&[&base[..], &["--measure", "area_reached"]].concat());
    assert!(
        problem.contains("foraging.toml") && problem.contains("behaviour.area"),
        "{problem}"
    );
}
