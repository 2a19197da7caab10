//! The first hour: a run ends by saying whether it worked (the held-out check: the champion
//! against random genomes and the experiment's baseline on worlds evolution never saw, with
//! compare's numbers) and how to look at the champion; and no dead ends on the way (an empty
//! world is warned of, a world that cannot be built leaves no folder, the population's
//! minimum is said, resume names its checkpoint, a batch folder is not mixed with a run).

use crate::cli_common::{bin, experiment, fixture, run_err, run_ok};
use berry_evolve::experiment::templates::TEMPLATES;
use berry_evolve::experiment::Experiment;
use berry_evolve::record::genome_file::GenomeFile;
use serde_json::Value;
use std::path::{Path, PathBuf};

fn stderr(out: &std::process::Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// The line of `text` that starts with `prefix`.
fn line<'a>(text: &'a str, prefix: &str) -> &'a str {
    text.lines()
        .find(|l| l.trim_start().starts_with(prefix))
        .unwrap_or_else(|| panic!("no line starting with `{prefix}` in:\n{text}"))
}

/// tiny.toml with `[output] baseline = <baseline>` appended (its [output] table extended),
/// written as `dir/<name>`.
fn tiny_with_baseline(dir: &Path, name: &str, baseline: &str) -> PathBuf {
    let text = std::fs::read_to_string(fixture("tiny.toml")).unwrap();
    let text = text.replace(
        "keep_checkpoints = 3",
        &format!("keep_checkpoints = 3\nbaseline = \"{baseline}\""),
    );
    assert!(text.contains("baseline"), "tiny.toml has an [output] table");
    std::fs::create_dir_all(dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// A genome for tiny.toml's brain: the best.json of a 2-generation run, copied to
/// `tmp/genomes/base.json`.
fn a_tiny_genome(tmp: &Path) -> PathBuf {
    let dir = tmp.join("donor");
    run_ok(&[
        "run",
        fixture("tiny.toml").to_str().unwrap(),
        "--out",
        dir.to_str().unwrap(),
        "--generations",
        "2",
        "--quiet",
        "--no-check",
        "--no-estimate",
    ]);
    let genomes = tmp.join("genomes");
    std::fs::create_dir_all(&genomes).unwrap();
    let path = genomes.join("base.json");
    std::fs::copy(dir.join("best.json"), &path).unwrap();
    path
}

#[test]
fn a_run_ends_with_a_held_out_check_against_random_genomes_and_the_baseline_and_commands_to_look() {
    let tmp = tempfile::tempdir().unwrap();
    a_tiny_genome(tmp.path());
    // The experiment names the baseline relative to its own folder, as the shipped ones do.
    let file = tiny_with_baseline(&tmp.path().join("exp"), "tiny.toml", "../genomes/base.json");
    let dir = tmp.path().join("runs/deep/run");
    let out = run_ok(&[
        "run",
        file.to_str().unwrap(),
        "--out",
        dir.to_str().unwrap(),
        "--no-estimate",
    ]);
    let err = stderr(&out);
    let check = line(&err, "held-out check (");
    assert!(
        check.contains("champion ")
            && check.contains("5 random genomes median")
            && check.contains("baseline base "),
        "{check}"
    );
    assert!(
        check.contains(": the champion "),
        "a verdict in words: {check}"
    );
    // The run folder's experiment.toml names the baseline as written (the same bytes on any
    // machine), and the folder keeps a copy for a later resume.
    let stored = Experiment::load(&dir.join("experiment.toml")).unwrap();
    assert_eq!(
        stored.output.baseline.as_deref(),
        Some("../genomes/base.json")
    );
    assert_eq!(
        std::fs::read(dir.join("baseline.json")).unwrap(),
        std::fs::read(tmp.path().join("genomes/base.json")).unwrap()
    );
    // Then the commands to look at the champion, with the real paths; both work.
    let render = line(&err, "look at the champion: ");
    let replay = line(&err, "or watch it move: ");
    for (text, made) in [(render, "best-trial-0.svg"), (replay, "best.html")] {
        let command = text
            .split(": ")
            .nth(1)
            .unwrap()
            .split("  (")
            .next()
            .unwrap();
        let words: Vec<&str> = command.split_whitespace().collect();
        assert!(words[0].ends_with("berry-evolve"), "{command}");
        assert!(
            command.contains(dir.join("best.json").to_str().unwrap()),
            "{command}"
        );
        assert!(
            command.contains(dir.join("experiment.toml").to_str().unwrap()),
            "{command}"
        );
        run_ok(&words[1..]);
        assert!(dir.join(made).is_file(), "{command} wrote no {made}");
    }
}

#[test]
fn the_checks_numbers_are_compares_on_the_held_out_worlds_and_json_carries_them() {
    let tmp = tempfile::tempdir().unwrap();
    let genome = a_tiny_genome(tmp.path());
    let file = tiny_with_baseline(&tmp.path().join("exp"), "tiny.toml", "../genomes/base.json");
    let dir = tmp.path().join("run");
    let args = |dir: &Path| {
        vec![
            "run".to_string(),
            file.to_str().unwrap().to_string(),
            "--out".to_string(),
            dir.to_str().unwrap().to_string(),
            "--no-estimate".to_string(),
        ]
    };
    let a = args(&dir);
    let mut a: Vec<&str> = a.iter().map(String::as_str).collect();
    a.push("--json");
    let d: Value = serde_json::from_slice(&run_ok(&a).stdout).unwrap();
    let c = &d["check"];
    let worlds = c["worlds"].as_u64().unwrap();
    assert!((1..=10).contains(&worlds), "{c}");
    assert_eq!(c["generation"], 1u64 << 40, "compare's held-out generation");
    assert_eq!(c["random"]["count"], 5);
    // compare, asked for the same, gives the same numbers.
    let compare: Value = serde_json::from_slice(
        &run_ok(&[
            "compare",
            dir.join("best.json").to_str().unwrap(),
            genome.to_str().unwrap(),
            "--experiment",
            dir.join("experiment.toml").to_str().unwrap(),
            "--trials",
            &worlds.to_string(),
            "--random",
            "5",
            "--json",
        ])
        .stdout,
    )
    .unwrap();
    assert_eq!(c["champion"]["fitness"], compare["genomes"][0]["fitness"]);
    assert_eq!(c["baseline"]["fitness"], compare["genomes"][1]["fitness"]);
    assert_eq!(
        c["random"]["median"],
        compare["random"]["fitness"]["median"]
    );
    assert_eq!(c["random"]["best"], compare["random"]["fitness"]["best"]);
    assert_eq!(d["look"].as_array().unwrap().len(), 2);
    // The text run of the same state prints the same numbers, rounded as shown.
    let text_dir = tmp.path().join("text");
    let a = args(&text_dir);
    let a: Vec<&str> = a.iter().map(String::as_str).collect();
    let err = stderr(&run_ok(&a));
    let check = line(&err, "held-out check (");
    let f = |v: &Value| format!("{:.4}", v.as_f64().unwrap());
    for (what, v) in [
        ("champion ", &c["champion"]["fitness"]),
        ("median ", &c["random"]["median"]),
        ("(best ", &c["random"]["best"]),
        ("baseline base ", &c["baseline"]["fitness"]),
    ] {
        assert!(
            check.contains(&format!("{what}{}", f(v))),
            "{what}{v}: {check}"
        );
    }
    assert!(check.ends_with(c["verdict"].as_str().unwrap()), "{check}");
}

#[test]
fn no_check_skips_the_check_and_quiet_prints_nothing_unless_json() {
    let tmp = tempfile::tempdir().unwrap();
    let tiny = fixture("tiny.toml");
    let run = |name: &str, extra: &[&str]| {
        let dir = tmp.path().join(name);
        let mut args = vec![
            "run",
            tiny.to_str().unwrap(),
            "--no-estimate",
            "--generations",
            "2",
        ];
        let d = dir.to_str().unwrap().to_string();
        args.extend(["--out", &d]);
        args.extend(extra);
        run_ok(&args)
    };
    let out = run("plain", &["--no-check"]);
    assert!(!stderr(&out).contains("held-out check"), "{}", stderr(&out));
    assert!(stderr(&out).contains("look at the champion"));
    let out = run("quiet", &["--quiet"]);
    assert_eq!(
        stderr(&out),
        "",
        "--quiet prints nothing, the check included"
    );
    let out = run("quiet-json", &["--quiet", "--json"]);
    let d: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(d["check"]["verdict"].is_string(), "{d}");
    let out = run("json-no-check", &["--json", "--no-check"]);
    let d: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(d.get("check").is_none(), "{d}");
}

#[test]
fn resume_opens_with_the_checkpoint_it_continues_from_and_checks_at_the_end() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("run");
    run_ok(&[
        "run",
        fixture("tiny.toml").to_str().unwrap(),
        "--out",
        dir.to_str().unwrap(),
        "--quiet",
    ]);
    let out = run_ok(&["resume", dir.to_str().unwrap(), "--generations", "10"]);
    let err = stderr(&out);
    let first = err.lines().next().unwrap();
    let checkpoint = dir.join("checkpoints/gen-000007.json");
    assert_eq!(
        first,
        format!(
            "resuming the run in {} from checkpoint {} (generations 0 to 7 done)",
            dir.display(),
            checkpoint.display()
        )
    );
    assert!(err.contains("held-out check ("), "{err}");
    // A checkpoint named explicitly is the one named; a finished run says it too.
    let named = dir.join("checkpoints/gen-000009.json");
    let err = stderr(&run_ok(&["resume", named.to_str().unwrap(), "--no-check"]));
    assert!(
        err.starts_with(&format!(
            "resuming the run in {} from checkpoint {} (generations 0 to 9 done)\n",
            dir.display(),
            named.display()
        )),
        "{err}"
    );
    // A refused resume prints only its error.
    let err = run_err(&["resume", tmp.path().join("nothing").to_str().unwrap()]);
    assert!(!err.contains("resuming the run"), "{err}");
}

#[test]
fn a_relative_baseline_still_resolves_when_resume_runs_elsewhere_and_a_missing_one_is_a_note() {
    let tmp = tempfile::tempdir().unwrap();
    a_tiny_genome(tmp.path());
    tiny_with_baseline(&tmp.path().join("exp"), "tiny.toml", "../genomes/base.json");
    let dir = tmp.path().join("run");
    // Started from another folder with a relative experiment path, resumed from a third.
    let out = bin()
        .current_dir(tmp.path().join("exp"))
        .args([
            "run",
            "tiny.toml",
            "--out",
            dir.to_str().unwrap(),
            "--quiet",
        ])
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", stderr(&out));
    let elsewhere = tmp.path().join("elsewhere");
    std::fs::create_dir_all(&elsewhere).unwrap();
    let out = bin()
        .current_dir(&elsewhere)
        .args(["resume", dir.to_str().unwrap(), "--generations", "9"])
        .output()
        .unwrap();
    let err = stderr(&out);
    assert!(out.status.success(), "{err}");
    assert!(
        line(&err, "held-out check (").contains("baseline base "),
        "{err}"
    );
    assert!(!err.contains("left out"), "{err}");

    // A baseline file that is not there: a note at the start and in the check, never an error.
    let missing = tiny_with_baseline(&tmp.path().join("exp"), "gone.toml", "no/such.json");
    let out = run_ok(&[
        "run",
        missing.to_str().unwrap(),
        "--out",
        tmp.path().join("gone").to_str().unwrap(),
        "--no-estimate",
    ]);
    let err = stderr(&out);
    assert!(
        err.starts_with("note: the baseline genome") && err.contains("[output] baseline"),
        "{err}"
    );
    assert!(
        line(&err, "(baseline left out: ").contains("such.json"),
        "{err}"
    );
    assert!(
        !line(&err, "held-out check (").contains("baseline"),
        "{err}"
    );
}

#[test]
fn the_baseline_key_changes_no_config_hash_and_no_file_that_does_not_set_it() {
    let tmp = tempfile::tempdir().unwrap();
    let with = tiny_with_baseline(tmp.path(), "with.toml", "x.json");
    let hash = |f: &Path| {
        let d: Value = serde_json::from_slice(
            &run_ok(&["inspect", f.to_str().unwrap(), "--json", "--no-estimate"]).stdout,
        )
        .unwrap();
        d["config_hash"].clone()
    };
    assert_eq!(hash(&with), hash(&fixture("tiny.toml")));
    // A run of a file without the key writes no key (bytes as before the key existed).
    let dir = tmp.path().join("run");
    run_ok(&[
        "run",
        fixture("tiny.toml").to_str().unwrap(),
        "--out",
        dir.to_str().unwrap(),
        "--generations",
        "1",
        "--quiet",
    ]);
    let text = std::fs::read_to_string(dir.join("experiment.toml")).unwrap();
    assert!(!text.contains("baseline"), "{text}");
    let checkpoint = std::fs::read_to_string(dir.join("checkpoints/gen-000000.json")).unwrap();
    assert!(!checkpoint.contains("baseline"));
}

#[test]
fn every_shipped_experiment_with_a_baseline_genome_names_it_and_it_fits_the_brain() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    for t in TEMPLATES {
        let experiment = Experiment::load(&root.join(t.file)).unwrap();
        let own = root.join(format!("genomes/{}-baseline.json", t.name));
        let expected = match t.name {
            "foraging" => Some(root.join("genomes/braitenberg-forager.json")),
            _ if own.is_file() => Some(own),
            _ => None,
        };
        let named = experiment
            .output
            .baseline_in(&root.join("experiments"))
            .map(|p| std::fs::canonicalize(p).unwrap());
        assert_eq!(
            named,
            expected.map(|p| std::fs::canonicalize(p).unwrap()),
            "{}",
            t.file
        );
        if let Some(path) = named {
            let genome = GenomeFile::load(&path).unwrap();
            genome
                .topology_for(&experiment, &path)
                .unwrap_or_else(|e| panic!("{}: {e}", t.file));
        }
        // And nothing in a shipped world is mistaken for an empty one.
        assert!(
            experiment
                .fitness
                .can_vary(&experiment.world, &experiment.creature),
            "{}",
            t.file
        );
    }
}

#[test]
fn the_defaults_files_empty_world_is_warned_of_by_inspect_and_run() {
    let tmp = tempfile::tempdir().unwrap();
    let defaults = run_ok(&["config", "--defaults"]).stdout;
    let file = tmp.path().join("mine.toml");
    std::fs::write(&file, &defaults).unwrap();
    let text = String::from_utf8(defaults).unwrap();
    assert!(text.contains("the world is empty"), "the file says so too");
    let warning = "warning: nothing in this world can change the fitness";
    let inspect =
        String::from_utf8(run_ok(&["inspect", file.to_str().unwrap(), "--no-estimate"]).stdout)
            .unwrap();
    assert!(inspect.contains(warning), "{inspect}");
    assert!(inspect.contains("new NAME --from foraging"), "{inspect}");
    let json: Value = serde_json::from_slice(
        &run_ok(&["inspect", file.to_str().unwrap(), "--no-estimate", "--json"]).stdout,
    )
    .unwrap();
    assert!(json["warnings"][0].as_str().unwrap().starts_with(warning));
    // run warns as it starts, even with --quiet, and runs.
    let out = run_ok(&[
        "run",
        file.to_str().unwrap(),
        "--out",
        tmp.path().join("run").to_str().unwrap(),
        "--generations",
        "1",
        "--quiet",
    ]);
    assert!(stderr(&out).starts_with(warning), "{}", stderr(&out));
    // A world with food is not warned of.
    let tiny = String::from_utf8(
        run_ok(&[
            "inspect",
            fixture("tiny.toml").to_str().unwrap(),
            "--no-estimate",
        ])
        .stdout,
    )
    .unwrap();
    assert!(!tiny.contains("warning"), "{tiny}");
}

#[test]
fn a_world_that_cannot_be_built_is_caught_by_inspect_and_run_leaves_no_folder() {
    let tmp = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(fixture("tiny.toml")).unwrap();
    let file = tmp.path().join("crowded.toml");
    std::fs::write(&file, text.replace("count = 6", "count = 5000")).unwrap();
    let err = run_err(&["inspect", file.to_str().unwrap(), "--no-estimate"]);
    assert!(
        err.contains(file.to_str().unwrap())
            && err.contains("cannot place object")
            && err.contains("world.place[0]"),
        "{err}"
    );
    let dir = tmp.path().join("run");
    let command = [
        "run",
        file.to_str().unwrap(),
        "--out",
        dir.to_str().unwrap(),
        "--quiet",
    ];
    let err = run_err(&command);
    assert!(
        err.contains("cannot place object") && err.contains("nothing was written"),
        "{err}"
    );
    assert!(!dir.exists(), "a refused run leaves no folder");
    // The fixed file starts with the same command, no --force.
    std::fs::write(&file, text).unwrap();
    run_ok(&command);
    assert!(dir.join("best.json").is_file());
}

#[test]
fn the_library_refuses_a_world_that_cannot_be_built_before_creating_the_folder() {
    use berry_evolve::run::{start, RunError, RunOptions, Silent};
    let tmp = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(fixture("tiny.toml"))
        .unwrap()
        .replace("count = 6", "count = 5000");
    let experiment = Experiment::from_toml(&text, Path::new("crowded.toml")).unwrap();
    let dir = tmp.path().join("run");
    let options = RunOptions {
        jobs: 1,
        stop: None,
        evaluator: None,
    };
    let error = start(experiment, &dir, false, options, &mut Silent).unwrap_err();
    assert!(matches!(error, RunError::Evaluation(_)), "{error}");
    assert!(!dir.exists(), "{error}");
}

#[test]
fn the_population_error_says_the_real_minimum() {
    let tmp = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(fixture("tiny.toml")).unwrap();
    let with = |population: &str, extra: &str| {
        let file = tmp.path().join(format!("p{population}.toml"));
        let t = text.replace("population = 12", &format!("population = {population}"));
        let t = format!("{t}{extra}");
        std::fs::write(&file, t).unwrap();
        file
    };
    let err = run_err(&["inspect", with("1", "").to_str().unwrap(), "--no-estimate"]);
    assert!(
        err.contains("`evolution.population`") && err.contains("at least 2"),
        "{err}"
    );
    // 2 with the default tournament of 3: the message names the population it needs.
    let err = run_err(&["inspect", with("2", "").to_str().unwrap(), "--no-estimate"]);
    assert!(
        err.contains("tournament_size")
            && err.contains("needs a population of at least 3")
            && err.contains("evolution.population = 2"),
        "{err}"
    );
    // And 2 is accepted with a tournament that fits.
    let file = with("2", "\n[evolution.selection]\ntournament_size = 2\n");
    run_ok(&["inspect", file.to_str().unwrap(), "--no-estimate"]);
}

#[test]
fn run_out_refuses_a_folder_of_seed_replicates_and_says_what_to_do() {
    let tmp = tempfile::tempdir().unwrap();
    let batch = tmp.path().join("batch");
    let tiny = fixture("tiny.toml");
    run_ok(&[
        "run",
        tiny.to_str().unwrap(),
        "--seeds",
        "1..2",
        "--generations",
        "1",
        "--out",
        batch.to_str().unwrap(),
        "--quiet",
    ]);
    let err = run_err(&[
        "run",
        tiny.to_str().unwrap(),
        "--out",
        batch.to_str().unwrap(),
    ]);
    assert!(
        err.contains("seed replicates")
            && err.contains("seed-1/, seed-2/")
            && err.contains(&format!("--seeds 5 --out {}", batch.display())),
        "{err}"
    );
    assert!(!batch.join("experiment.toml").exists(), "nothing written");
    let err = run_err(&[
        "run",
        tiny.to_str().unwrap(),
        "--out",
        batch.to_str().unwrap(),
        "--seed",
        "2",
    ]);
    assert!(
        err.contains(&format!("resume {}", batch.join("seed-2").display())),
        "{err}"
    );
    // The batch itself continues as before.
    run_ok(&[
        "run",
        tiny.to_str().unwrap(),
        "--seeds",
        "1..3",
        "--generations",
        "1",
        "--out",
        batch.to_str().unwrap(),
        "--quiet",
    ]);
}

#[test]
fn a_shipped_experiment_run_checks_against_its_baseline() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("run");
    let out = run_ok(&[
        "run",
        &experiment("foraging.toml"),
        "--out",
        dir.to_str().unwrap(),
        "--generations",
        "1",
        "--no-estimate",
    ]);
    let err = stderr(&out);
    let check = line(&err, "held-out check (");
    assert!(check.contains("baseline braitenberg-forager "), "{check}");
}
