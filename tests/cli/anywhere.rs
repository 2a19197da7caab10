//! The program works outside the repository (issue 19): `new` writes experiments from the
//! templates built into the binary, `bench` finds its built-in worlds from any folder and
//! prints JSON, `run` says where its results go, and printed commands name the program as it
//! was started. Every test runs the binary in an empty temporary folder.

use crate::cli_common::{bin, fixture};
use std::path::Path;
use std::process::Output;

/// Runs the binary in `cwd` with `args`; returns its output.
fn run_in(cwd: &Path, args: &[&str]) -> Output {
    bin()
        .current_dir(cwd)
        .args(args)
        .output()
        .expect("binary runs")
}

fn ok_in(cwd: &Path, args: &[&str]) -> Output {
    let out = run_in(cwd, args);
    assert!(
        out.status.success(),
        "berry-evolve {args:?} failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// The names of experiments/*.toml, sorted.
fn shipped_experiments() -> Vec<String> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("experiments");
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| {
            let name = e.unwrap().file_name().into_string().unwrap();
            name.strip_suffix(".toml").map(str::to_string)
        })
        .collect();
    names.sort();
    names
}

#[test]
fn new_list_names_every_shipped_experiment_with_its_opening_comment() {
    let dir = tempfile::tempdir().unwrap();
    let out = ok_in(dir.path(), &["new", "--list"]);
    let listed = text(&out.stdout);
    let names: Vec<String> = listed
        .lines()
        .map(|l| l.split_whitespace().next().unwrap().to_string())
        .collect();
    assert_eq!(
        names,
        shipped_experiments(),
        "every experiments/*.toml must be a built-in template (experiment::templates::TEMPLATES)"
    );
    // Each line's purpose is the start of the file's opening comment.
    for line in listed.lines() {
        let (name, purpose) = line.split_once(' ').unwrap();
        let file = std::fs::read_to_string(
            Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("experiments/{name}.toml")),
        )
        .unwrap();
        let comment: Vec<&str> = file
            .lines()
            .map_while(|l| l.strip_prefix('#'))
            .map(str::trim)
            .collect();
        let purpose = purpose.trim_start();
        assert!(
            purpose.len() > 20 && comment.join(" ").starts_with(purpose),
            "{name}: {purpose}"
        );
    }
}

#[test]
fn new_writes_every_template_and_each_inspects_and_runs_a_generation_anywhere() {
    let dir = tempfile::tempdir().unwrap();
    for template in shipped_experiments() {
        let name = format!("my-{template}");
        let out = ok_in(dir.path(), &["new", &name, "--from", &template]);
        let file = dir.path().join(format!("{name}.toml"));
        assert!(
            text(&out.stdout).contains(&format!("wrote {name}.toml")),
            "{}",
            text(&out.stdout)
        );
        // As shipped, comments and all, but for its name.
        let written = std::fs::read_to_string(&file).unwrap();
        let shipped = std::fs::read_to_string(
            Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("experiments/{template}.toml")),
        )
        .unwrap();
        assert_eq!(
            written.replace(&format!("name = \"{name}\""), ""),
            shipped.replace(&format!("name = \"{template}\""), ""),
            "{template}"
        );
        let inspect = ok_in(dir.path(), &["inspect", &format!("{name}.toml")]);
        assert!(
            text(&inspect.stdout).starts_with(&format!("experiment `{name}`")),
            "{}",
            text(&inspect.stdout)
        );
        ok_in(
            dir.path(),
            &["run", &format!("{name}.toml"), "--generations", "1", "-q"],
        );
        let seed_dirs: Vec<_> = std::fs::read_dir(dir.path().join("results").join(&name))
            .unwrap()
            .collect();
        assert_eq!(seed_dirs.len(), 1, "{template}");
        let run_dir = seed_dirs[0].as_ref().unwrap().path();
        let csv = std::fs::read_to_string(run_dir.join("fitness.csv")).unwrap();
        assert_eq!(
            csv.lines().count(),
            2,
            "{template}: header and generation 0"
        );
        assert!(run_dir.join("best.json").is_file(), "{template}");
    }
}

#[test]
fn new_refuses_to_overwrite_a_file_unless_forced() {
    let dir = tempfile::tempdir().unwrap();
    ok_in(dir.path(), &["new", "mine", "--from", "t-maze"]);
    let file = dir.path().join("mine.toml");
    std::fs::write(&file, "# my own notes\n").unwrap();
    let out = run_in(dir.path(), &["new", "mine", "--from", "foraging"]);
    assert_eq!(out.status.code(), Some(1));
    let err = text(&out.stderr);
    assert!(
        err.starts_with("error: mine.toml already exists") && err.contains("--force"),
        "{err}"
    );
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "# my own notes\n");
    ok_in(
        dir.path(),
        &["new", "mine", "--from", "foraging", "--force"],
    );
    assert!(std::fs::read_to_string(&file)
        .unwrap()
        .contains("name = \"mine\""));
    // -o a file, and -o a folder (NAME.toml in it).
    std::fs::create_dir(dir.path().join("sub")).unwrap();
    ok_in(dir.path(), &["new", "a", "-o", "sub/other.toml"]);
    ok_in(dir.path(), &["new", "b", "-o", "sub"]);
    assert!(dir.path().join("sub/other.toml").is_file());
    assert!(dir.path().join("sub/b.toml").is_file());
    // No temporary file is left behind.
    let names: Vec<String> = std::fs::read_dir(dir.path().join("sub"))
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    assert_eq!(names.len(), 2, "{names:?}");
}

#[test]
fn new_with_an_unknown_template_or_a_bad_name_suggests_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    for (from, suggestion) in [
        ("foragin", Some("foraging")),
        ("forag", Some("foraging")),
        ("t-mzae", Some("t-maze")),
        ("zzzzzz", None),
    ] {
        let out = run_in(dir.path(), &["new", "x", "--from", from]);
        assert_eq!(out.status.code(), Some(1), "{from}");
        let err = text(&out.stderr);
        assert!(
            err.starts_with(&format!("error: there is no built-in experiment `{from}`")),
            "{err}"
        );
        assert!(err.contains("new --list"), "{err}");
        match suggestion {
            Some(s) => assert!(err.contains(&format!("did you mean `{s}`?")), "{err}"),
            None => assert!(!err.contains("did you mean"), "{err}"),
        }
    }
    let out = run_in(
        dir.path(),
        &["new", "..", "--from", "foraging", "-o", "x.toml"],
    );
    assert_eq!(out.status.code(), Some(1));
    assert!(
        text(&out.stderr).contains("`name`"),
        "{}",
        text(&out.stderr)
    );
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}

/// The number printed just before `unit` in `line`, e.g. `1221328` before `creature-ticks/s`.
fn number_before<'a>(line: &'a str, unit: &str) -> &'a str {
    let words: Vec<&str> = line.split_whitespace().collect();
    let at = words
        .iter()
        .position(|w| *w == unit)
        .unwrap_or_else(|| panic!("no `{unit}` in {line}"));
    words[at - 1]
}

#[test]
fn bench_runs_from_any_folder_and_its_json_carries_the_texts_figures() {
    let dir = tempfile::tempdir().unwrap();
    let out = ok_in(
        dir.path(),
        &[
            "bench",
            "--worlds",
            "16",
            "--ticks",
            "100",
            "--scaling",
            "1,2",
            "--generations",
            "1",
            "--json",
        ],
    );
    let stdout = text(&out.stdout);
    let report: serde_json::Value = serde_json::from_str(&stdout)
        .unwrap_or_else(|e| panic!("stdout is not one JSON document: {e}\n{stdout}"));
    assert!(
        stdout
            .trim_start()
            .starts_with("{\n  \"schema\": \"berry-evolve/bench/1\""),
        "{stdout}"
    );
    // The text goes to stderr, with the same figures.
    let stderr = text(&out.stderr);
    let lines: Vec<&str> = stderr.lines().collect();
    let simulator = report["simulator"].as_array().unwrap();
    let worlds: Vec<&str> = simulator
        .iter()
        .map(|s| s["world"].as_str().unwrap())
        .collect();
    assert_eq!(
        worlds,
        [
            "experiments/bench/foraging-world.toml",
            "experiments/bench/eye-predators-world.toml"
        ]
    );
    for s in simulator {
        assert_eq!(s["built_in"], true);
        let world = s["world"].as_str().unwrap();
        let line = lines
            .iter()
            .find(|l| l.starts_with(&format!("simulator {world}:")))
            .unwrap_or_else(|| panic!("no text line for {world}:\n{stderr}"));
        let one = s["one_thread"].as_f64().unwrap();
        assert!(one > 0.0);
        assert_eq!(
            number_before(line, "creature-ticks/s"),
            format!("{one:.0}"),
            "{line}"
        );
        let two = s["two_threads"].as_f64().unwrap();
        assert!(line.contains(&format!(", {two:.0} on 2 threads")), "{line}");
        assert!(
            line.contains(&format!("({:.2}x)", s["speed_up"].as_f64().unwrap())),
            "{line}"
        );
    }
    let scaling = report["scaling"].as_array().unwrap();
    assert_eq!(scaling.len(), 2);
    for s in scaling {
        let k = s["k"].as_u64().unwrap();
        let line = lines
            .iter()
            .find(|l| l.starts_with("scaling ") && l.contains(&format!(" x{k}:")))
            .unwrap();
        let rate = s["one_thread"].as_f64().unwrap();
        assert_eq!(
            number_before(line, "creature-ticks/s"),
            format!("{rate:.0}"),
            "{line}"
        );
        assert!(line.contains(&format!("{} walls", s["walls"])), "{line}");
    }
    assert_eq!(scaling[1]["walls"], 48);
    let evolution = &report["evolution"];
    assert_eq!(evolution["experiment"], "experiments/foraging.toml");
    assert_eq!(evolution["identical_bests"], true);
    for t in evolution["threads"].as_array().unwrap() {
        let threads = t["threads"].as_u64().unwrap();
        let line = lines
            .iter()
            .find(|l| l.contains(&format!("on {threads} thread(s)")))
            .unwrap();
        let rate = t["generations_per_second"].as_f64().unwrap();
        assert!(
            line.contains(&format!(": {rate:.3} generations/s")),
            "{line}"
        );
        let ticks = t["creature_ticks_per_second"].as_f64().unwrap();
        assert_eq!(
            number_before(line, "creature-ticks/s"),
            format!("{ticks:.0}")
        );
        // 64 individuals x 5 trials x 800 ticks per generation.
        assert!((ticks / rate - 256_000.0).abs() < 1e-6, "{ticks} / {rate}");
    }
    // Without --json the same text goes to stdout and nothing else.
    let out = ok_in(
        dir.path(),
        &[
            "bench",
            "--worlds",
            "2",
            "--ticks",
            "10",
            "--scaling",
            "0",
            "--generations",
            "0",
        ],
    );
    let stdout = text(&out.stdout);
    assert!(stdout.starts_with("berry-evolve "), "{stdout}");
    assert!(
        stdout.contains("simulator experiments/bench/eye-predators-world.toml:"),
        "{stdout}"
    );
    assert!(!stdout.contains('{'), "{stdout}");
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        0,
        "bench writes no file"
    );
}

#[test]
fn run_says_where_results_go_and_hints_name_the_program_as_started() {
    let dir = tempfile::tempdir().unwrap();
    let tiny = fixture("tiny.toml");
    let tiny = tiny.to_str().unwrap();
    let out = ok_in(dir.path(), &["run", tiny, "--generations", "1"]);
    let stderr = text(&out.stderr);
    let cwd = dir.path().canonicalize().unwrap();
    assert_eq!(
        stderr.lines().next().unwrap(),
        format!(
            "running `tiny` seed 5: results go to results/tiny/seed-5 (in {}; --out chooses another folder)",
            cwd.display()
        )
    );
    let out = ok_in(
        dir.path(),
        &[
            "run",
            tiny,
            "--generations",
            "1",
            "--seeds",
            "1,3",
            "--out",
            "reps",
        ],
    );
    assert_eq!(
        text(&out.stderr).lines().next().unwrap(),
        format!(
            "running `tiny` seeds 1, 3: results go to reps/seed-<s> (in {}; --out chooses another folder)",
            cwd.display()
        )
    );
    // A second run into the same folder is refused with a hint; what does it call the program?
    let hint = |mut command: std::process::Command| {
        let out = command
            .current_dir(dir.path())
            .args(["run", tiny, "--generations", "1"])
            .output()
            .unwrap();
        text(&out.stderr)
    };
    // Started by its path (as the tests start it): that path.
    let exe = env!("CARGO_BIN_EXE_berry-evolve");
    let err = hint(bin());
    assert!(
        err.contains(&format!(
            "continue it with `{exe} resume results/tiny/seed-5`"
        )),
        "{err}"
    );
    // Started by its name from the PATH, or by a path while the PATH's berry-evolve is this
    // same program (a link to it): the name.
    let bin_dir = dir.path().join("bin");
    std::fs::create_dir(&bin_dir).unwrap();
    std::os::unix::fs::symlink(exe, bin_dir.join("berry-evolve")).unwrap();
    let mut by_name = std::process::Command::new("berry-evolve");
    by_name.env("PATH", &bin_dir);
    let mut by_path = bin();
    by_path.env("PATH", &bin_dir);
    for command in [by_name, by_path] {
        let err = hint(command);
        assert!(
            err.contains("continue it with `berry-evolve resume results/tiny/seed-5`"),
            "{err}"
        );
    }
}
