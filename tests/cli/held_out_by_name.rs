//! Worlds by name (`--worlds held-out|validation|training`) for replay, render, compare and
//! summary: the held-out worlds are the old `--generation 1099511627776` ones to the byte and
//! are titled "held-out world K"; the validation worlds reproduce a run's validation fitness
//! exactly; `summary --trials N` evaluates on N worlds; `--experiment` is found beside a run
//! folder's genome; a genome replayed in another experiment than its own is warned about.

use crate::cli_common::{experiment, run_err, run_ok};
use serde_json::Value;
use std::path::{Path, PathBuf};

const HELD_OUT: &str = "1099511627776";

fn champion() -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("genomes/foraging-champion-seed2.json")
        .to_str()
        .unwrap()
        .to_string()
}

fn json(args: &[&str]) -> Value {
    let out = run_ok(args);
    serde_json::from_slice(&out.stdout).unwrap_or_else(|e| panic!("{args:?}: not JSON: {e}"))
}

fn stdout(args: &[&str]) -> String {
    String::from_utf8(run_ok(args).stdout).unwrap()
}

fn stderr(args: &[&str]) -> String {
    String::from_utf8(run_ok(args).stderr).unwrap()
}

/// A temporary folder that holds a run of tests/fixtures/tiny.toml with `[validation]` on
/// and a fitness with a continuous part (so that validation fitness values are not round
/// numbers that any nearby world would also give), as `run --seeds 5` makes it: RUN/seed-5/.
fn validated_run() -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let tiny = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/tiny.toml"),
    )
    .unwrap();
    let text = format!(
        "{tiny}\n[fitness]\nforward_bonus = 0.005\n\n[behaviour]\nmeasures = [\"distinct_food\"]\n\n\
         [validation]\nevery = 2\ntop = 3\ntrials = 3\n"
    );
    let file = dir.path().join("validated.toml");
    std::fs::write(&file, text).unwrap();
    let runs = dir.path().join("runs");
    run_ok(&[
        "run",
        file.to_str().unwrap(),
        "--seeds",
        "5",
        "--quiet",
        "--out",
        runs.to_str().unwrap(),
    ]);
    (dir, runs)
}

#[test]
fn named_held_out_worlds_are_the_old_generation_form_to_the_byte() {
    let (g, e) = (champion(), experiment("foraging.toml"));
    let replay = |extra: &[&'static str]| {
        let mut args = vec![
            "replay",
            g.as_str(),
            "--experiment",
            e.as_str(),
            "--trial",
            "1",
        ];
        args.extend_from_slice(extra);
        args
    };
    let old = run_ok(&replay(&["--generation", HELD_OUT, "--json"])).stdout;
    let named = run_ok(&replay(&["--worlds", "held-out", "--json"])).stdout;
    assert_eq!(
        String::from_utf8_lossy(&old),
        String::from_utf8_lossy(&named),
        "replay --json: --worlds held-out is --generation {HELD_OUT}"
    );
    let d: Value = serde_json::from_slice(&named).unwrap();
    assert_eq!(d["worlds"], "held-out");
    assert_eq!(d["generation"].as_u64(), Some(1 << 40));
    // Not the training worlds of the genome's own generation.
    let own = json(&replay(&["--json"]));
    assert_ne!(own["fitness"], d["fitness"]);
    assert_eq!(
        own.get("worlds"),
        None,
        "no `worlds` key for training worlds"
    );
    // The text names the worlds, not the generation number.
    let text = stdout(&replay(&["--worlds", "held-out"]));
    assert!(text.starts_with("held-out world 1: score "), "{text}");
    assert!(text.contains("over 1 held-out world(s))"), "{text}");
    assert!(!text.contains(HELD_OUT), "{text}");

    // compare: the default, the old form and the name agree to the byte.
    let compare = |extra: &[&str]| {
        let mut args = vec![
            "compare",
            g.as_str(),
            "--experiment",
            e.as_str(),
            "--trials",
            "2",
            "--random",
            "2",
        ];
        args.extend_from_slice(extra);
        run_ok(&args).stdout
    };
    let default = compare(&["--json"]);
    assert_eq!(default, compare(&["--json", "--worlds", "held-out"]));
    assert_eq!(default, compare(&["--json", "--generation", HELD_OUT]));
    assert_eq!(compare(&[]), compare(&["--generation", HELD_OUT]));
    // ... and replay meets the very worlds compare does.
    let c: Value = serde_json::from_slice(&default).unwrap();
    let trial_1 = &c["genomes"][0]["trials"][1];
    assert_eq!(trial_1["score"], d["trials"][0]["score"]);
    // Training worlds by name are --generation's.
    assert_eq!(
        compare(&["--json", "--worlds", "training", "--generation", "3"]),
        compare(&["--json", "--generation", "3"])
    );
    // A generation with another set is refused, not ignored.
    let err = run_err(&[
        "compare",
        &g,
        "--experiment",
        &e,
        "--worlds",
        "held-out",
        "--generation",
        "3",
    ]);
    assert!(err.contains("--worlds training --generation 3"), "{err}");
}

#[test]
fn pictures_and_pages_are_titled_by_the_worlds() {
    let (g, e) = (champion(), experiment("foraging.toml"));
    let dir = tempfile::tempdir().unwrap();
    let svg = dir.path().join("t.svg");
    let html = dir.path().join("t.html");
    let (svg_s, html_s) = (svg.to_str().unwrap(), html.to_str().unwrap());
    for (extra, title) in [
        (
            &["--generation", HELD_OUT][..],
            "foraging: held-out world 1",
        ),
        (&["--worlds", "held-out"][..], "foraging: held-out world 1"),
        (
            &["--worlds", "validation"][..],
            "foraging: validation world 1",
        ),
        (
            &["--generation", "5"][..],
            "foraging: trial 1 of generation 5",
        ),
    ] {
        let mut args = vec![
            "render",
            &g,
            "--experiment",
            &e,
            "--trial",
            "1",
            "-o",
            svg_s,
        ];
        args.extend_from_slice(extra);
        run_ok(&args);
        let picture = std::fs::read_to_string(&svg).unwrap();
        assert!(
            picture.contains(title),
            "{extra:?}: no `{title}` in the picture"
        );
        assert!(
            !picture.contains(HELD_OUT),
            "{extra:?}: the picture names 2^40"
        );
        let mut args = vec![
            "replay",
            &g,
            "--experiment",
            &e,
            "--trial",
            "1",
            "--html",
            html_s,
        ];
        args.extend_from_slice(extra);
        run_ok(&args);
        let page = std::fs::read_to_string(&html).unwrap();
        assert!(
            page.contains(&format!("<title>{title}</title>")),
            "{extra:?}: the page is not titled `{title}`"
        );
    }
}

#[test]
fn validation_worlds_reproduce_the_runs_validation_fitness() {
    let (_dir, runs) = validated_run();
    let run = runs.join("seed-5");
    let best = run.join("best.json");
    let best_s = best.to_str().unwrap();
    let origin =
        &serde_json::from_slice::<Value>(&std::fs::read(&best).unwrap()).unwrap()["origin"];
    let generation = origin["generation"].as_u64().unwrap();
    // fitness.csv's validation columns of the generation the champion was validated after.
    let csv = std::fs::read_to_string(run.join("fitness.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let row: Vec<&str> = lines
        .find(|l| l.split(',').next() == Some(&generation.to_string()))
        .unwrap()
        .split(',')
        .collect();
    let column = |name: &str| -> f64 {
        let k = header.iter().position(|h| *h == name).unwrap();
        row[k].parse().unwrap()
    };
    let (fitness, distinct) = (
        column("validation_best"),
        column("validation_distinct_food"),
    );
    assert_ne!(
        fitness,
        fitness.round(),
        "a round fitness would prove little"
    );

    // compare, with the experiment found beside best.json.
    let c = json(&[
        "compare",
        best_s,
        "--worlds",
        "validation",
        "--random",
        "0",
        "--json",
    ]);
    assert_eq!(c["worlds"]["validation"], true);
    assert_eq!(c["trials"], 3);
    let g = &c["genomes"][0];
    assert_eq!(g["fitness"].as_f64(), Some(fitness), "{c}");
    assert_eq!(g["measures"]["distinct_food"].as_f64(), Some(distinct));
    let description = origin["description"].as_str().unwrap();
    assert!(
        description.contains(&format!("validation fitness {fitness} ")),
        "{description}"
    );
    // replay, trial by trial.
    let r = json(&["replay", best_s, "--worlds", "validation", "--json"]);
    assert_eq!(r["fitness"].as_f64(), Some(fitness));
    assert_eq!(r["worlds"], "validation");
    assert_eq!(r["trials"], g["trials"]);
    // summary: validation.csv holds the same value.
    let s = json(&[
        "summary",
        runs.to_str().unwrap(),
        "--worlds",
        "validation",
        "--random",
        "0",
        "--json",
    ]);
    let h = &s["held_out"];
    assert_eq!(h["worlds"], "validation");
    assert!(h["held_out_csv"]
        .as_str()
        .unwrap()
        .ends_with("validation.csv"));
    assert_eq!(h["rows"][0]["fitness"].as_f64(), Some(fitness));
    // Fewer validation worlds with --trials: the first ones.
    let two = json(&[
        "compare",
        best_s,
        "--worlds",
        "validation",
        "--trials",
        "2",
        "--random",
        "0",
        "--json",
    ]);
    assert_eq!(
        &two["genomes"][0]["trials"].as_array().unwrap()[..],
        &g["trials"].as_array().unwrap()[..2]
    );
}

#[test]
fn validation_worlds_are_refused_without_a_validation_table() {
    let tiny = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/tiny.toml");
    let genome = tempfile::tempdir().unwrap();
    let run = genome.path().join("run");
    run_ok(&[
        "run",
        tiny.to_str().unwrap(),
        "--generations",
        "1",
        "--quiet",
        "--out",
        run.to_str().unwrap(),
    ]);
    let best = run.join("best.json");
    for command in ["compare", "replay", "render"] {
        let experiment = run.join("experiment.toml");
        let err = run_err(&[
            command,
            best.to_str().unwrap(),
            "--experiment",
            experiment.to_str().unwrap(),
            "--worlds",
            "validation",
        ]);
        assert!(
            err.contains("has no [validation] table") && err.contains("--worlds held-out"),
            "{command}: {err}"
        );
    }
}

#[test]
fn summary_trials_sets_how_many_held_out_worlds() {
    let (_dir, runs) = validated_run();
    let best = runs.join("seed-5/best.json");
    for trials in ["2", "5"] {
        let s = json(&[
            "summary",
            runs.to_str().unwrap(),
            "--trials",
            trials,
            "--random",
            "0",
            "--json",
        ]);
        let h = &s["held_out"];
        assert_eq!(h["trials"].to_string(), trials);
        assert_eq!(h.get("worlds"), None);
        // The seed's best.json as compare evaluates it on as many held-out worlds.
        let c = json(&[
            "compare",
            best.to_str().unwrap(),
            "--trials",
            trials,
            "--random",
            "0",
            "--json",
        ]);
        assert_eq!(
            h["rows"][0]["fitness"], c["genomes"][0]["fitness"],
            "--trials {trials}"
        );
        assert_eq!(
            c["genomes"][0]["trials"]
                .as_array()
                .unwrap()
                .len()
                .to_string(),
            trials
        );
    }
}

#[test]
fn the_experiment_beside_a_run_folders_genome_is_used() {
    let (_dir, runs) = validated_run();
    let run = runs.join("seed-5");
    let (best, exp) = (run.join("best.json"), run.join("experiment.toml"));
    let (best_s, exp_s) = (best.to_str().unwrap(), exp.to_str().unwrap());
    for command in [
        &["replay", best_s, "--trial", "0"][..],
        &["compare", best_s, "--random", "2"][..],
    ] {
        let inferred = run_ok(command);
        let given = run_ok(&[command, &["--experiment", exp_s]].concat());
        assert_eq!(inferred.stdout, given.stdout, "{command:?}");
        let note = String::from_utf8_lossy(&inferred.stderr);
        assert!(
            note.contains(&format!("note: experiment file {exp_s} (beside {best_s})")),
            "{command:?}: {note}"
        );
        assert!(!String::from_utf8_lossy(&given.stderr).contains("note: experiment file"));
    }
    // A genome extracted into the run folder finds it too.
    let extracted = run.join("individual-0.json");
    run_ok(&[
        "extract",
        run.to_str().unwrap(),
        "--individual",
        "0",
        "-o",
        extracted.to_str().unwrap(),
    ]);
    let svg = run.join("individual-0.svg");
    run_ok(&[
        "render",
        extracted.to_str().unwrap(),
        "-o",
        svg.to_str().unwrap(),
    ]);
    assert!(std::fs::read_to_string(&svg)
        .unwrap()
        .contains("tiny: trial 0 of generation"));
    // A genome elsewhere needs --experiment, and says so.
    let err = run_err(&["replay", &champion()]);
    assert!(
        err.contains("give --experiment") && err.contains("experiment.toml beside"),
        "{err}"
    );
    // Genomes beside different experiment files: which worlds would be ambiguous.
    let other = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(&exp)
        .unwrap()
        .replace("seed = 5", "seed = 6");
    std::fs::write(other.path().join("experiment.toml"), text).unwrap();
    let copy = other.path().join("best.json");
    std::fs::copy(&best, &copy).unwrap();
    let err = run_err(&["compare", best_s, copy.to_str().unwrap()]);
    assert!(err.contains("different experiment files"), "{err}");
}

#[test]
fn a_genome_replayed_in_another_experiment_is_warned_about() {
    let g = champion();
    // The foraging champion's inputs fit crowded-arena: it runs, with a warning.
    let crowded = experiment("crowded-arena.toml");
    for command in ["replay", "compare"] {
        let mut args = vec![command, &g, "--experiment", &crowded];
        if command == "replay" {
            args.extend(["--trial", "0"]);
        } else {
            args.extend(["--trials", "1", "--random", "0"]);
        }
        let err = stderr(&args);
        assert!(
            err.contains("warning: ")
                && err.contains("evolved in experiment `foraging`")
                && err.contains("in experiment `crowded-arena`"),
            "{command}: {err}"
        );
    }
    // In its own experiment (another seed: only the note), no warning.
    let err = stderr(&[
        "replay",
        &g,
        "--experiment",
        &experiment("foraging.toml"),
        "--trial",
        "0",
    ]);
    assert!(!err.contains("warning"), "{err}");
}

/// The design worlds, where hand-designed controllers and settings are tuned: named
/// `--worlds design`, the old `--generation 1099511627777` to the byte, and not the held-out
/// worlds.
#[test]
fn the_design_worlds_have_a_name_and_are_not_the_held_out_ones() {
    let (g, e) = (champion(), experiment("foraging.toml"));
    let compare = |extra: &[&str]| {
        let mut args = vec![
            "compare",
            g.as_str(),
            "--experiment",
            e.as_str(),
            "--trials",
            "2",
            "--random",
            "2",
            "--json",
        ];
        args.extend_from_slice(extra);
        run_ok(&args).stdout
    };
    let named = compare(&["--worlds", "design"]);
    assert_eq!(named, compare(&["--generation", "1099511627777"]));
    let held_out: Value = serde_json::from_slice(&compare(&[])).unwrap();
    let design: Value = serde_json::from_slice(&named).unwrap();
    assert_ne!(
        held_out["genomes"], design["genomes"],
        "design worlds are other worlds"
    );
    let text = String::from_utf8(
        run_ok(&[
            "compare",
            &g,
            "--experiment",
            &e,
            "--trials",
            "1",
            "--random",
            "2",
            "--worlds",
            "design",
        ])
        .stdout,
    )
    .unwrap();
    assert!(text.contains("on the design worlds"), "{text}");
}
