//! End-to-end tests of the `berry-evolve` binary: the reproducibility contract (same seed,
//! same bytes; any thread count; resumed or not) and clear errors for every class of bad input.

use crate::cli_common::{bin, fixture, read, run_err, run_ok};

use std::path::{Path, PathBuf};

fn checkpoints(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir.join("checkpoints"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    v.sort();
    v
}

/// The run's outputs that must be byte-identical, with names for a useful message.
fn outputs(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let last = checkpoints(dir).pop().expect("a checkpoint");
    vec![
        ("fitness.csv".into(), read(&dir.join("fitness.csv"))),
        ("best.json".into(), read(&dir.join("best.json"))),
        ("champions.jsonl".into(), read(&dir.join("champions.jsonl"))),
        ("experiment.toml".into(), read(&dir.join("experiment.toml"))),
        (
            format!(
                "checkpoints/{}",
                last.file_name().unwrap().to_string_lossy()
            ),
            read(&last),
        ),
    ]
}

fn assert_same_outputs(a: &Path, b: &Path, what: &str) {
    for ((name_a, bytes_a), (name_b, bytes_b)) in outputs(a).into_iter().zip(outputs(b)) {
        assert_eq!(name_a, name_b, "{what}: different final checkpoint");
        assert!(bytes_a == bytes_b, "{what}: {name_a} differs");
    }
}

fn run_tiny(dir: &Path, extra: &[&str]) {
    let exp = fixture("tiny.toml");
    let mut args = vec![
        "run",
        exp.to_str().unwrap(),
        "--out",
        dir.to_str().unwrap(),
        "--quiet",
    ];
    args.extend_from_slice(extra);
    run_ok(&args);
}

#[test]
fn same_seed_gives_same_bytes_with_one_or_two_threads() {
    let tmp = tempfile::tempdir().unwrap();
    let a = tmp.path().join("a");
    let b = tmp.path().join("b");
    let c = tmp.path().join("c");
    run_tiny(&a, &["--jobs", "1"]);
    run_tiny(&b, &["--jobs", "2"]);
    run_tiny(&c, &["--jobs", "2"]);
    assert_same_outputs(&a, &b, "--jobs 1 vs --jobs 2");
    assert_same_outputs(&b, &c, "two runs with --jobs 2");
    let csv = String::from_utf8(read(&a.join("fitness.csv"))).unwrap();
    assert_eq!(
        csv.lines().count(),
        1 + 8,
        "header + one row per generation"
    );
    assert!(csv.starts_with("generation,evaluations,best,mean,median,worst,std,best_ever,"));
    // The bare form `berry-evolve FILE` (the README's main command) is the same as `run FILE`.
    let bare = tmp.path().join("bare");
    let exp = fixture("tiny.toml");
    run_ok(&[
        exp.to_str().unwrap(),
        "--out",
        bare.to_str().unwrap(),
        "--quiet",
        "--jobs",
        "2",
    ]);
    assert_same_outputs(&a, &bare, "bare command vs run");
    // A different seed is a different run.
    let d = tmp.path().join("d");
    run_tiny(&d, &["--seed", "6"]);
    assert_ne!(read(&a.join("fitness.csv")), read(&d.join("fitness.csv")));
}

#[test]
fn resumed_run_equals_uninterrupted_run() {
    let tmp = tempfile::tempdir().unwrap();
    let full = tmp.path().join("full");
    run_tiny(&full, &["--jobs", "2"]);

    // Stopped early (a finished 3-generation run), then extended to the full length.
    let short = tmp.path().join("short");
    run_tiny(&short, &["--generations", "3"]);
    run_ok(&[
        "resume",
        short.to_str().unwrap(),
        "--generations",
        "8",
        "--quiet",
        "--jobs",
        "1",
    ]);
    assert_same_outputs(&full, &short, "extended run");
    let err = run_err(&["resume", short.to_str().unwrap(), "--generations", "5"]);
    assert!(
        err.contains("already holds 8 completed generations"),
        "{err}"
    );

    // Killed between checkpoints: the folder holds rows past its newest checkpoint and a
    // half-written row; the newer checkpoints are gone.
    let killed = tmp.path().join("killed");
    run_tiny(&killed, &["--jobs", "1"]);
    let cps = checkpoints(&killed);
    for late in cps.iter().filter(|p| !p.ends_with("gen-000003.json")) {
        std::fs::remove_file(late).unwrap();
    }
    let mut csv = read(&killed.join("fitness.csv"));
    csv.extend_from_slice(b"8,108,0.5,0.");
    std::fs::write(killed.join("fitness.csv"), csv).unwrap();
    std::fs::write(killed.join("best.json"), b"{ half a file").unwrap();
    // champions.jsonl holds lines past the checkpoint (generations 4 to 7) and a half line.
    let mut champions = read(&killed.join("champions.jsonl"));
    champions.extend_from_slice(b"{\"format\":1,\"brain\":{\"kind");
    std::fs::write(killed.join("champions.jsonl"), champions).unwrap();
    std::fs::write(
        killed.join("checkpoints/.gen-000005.json.tmp-999-0"),
        b"junk",
    )
    .unwrap();
    run_ok(&["resume", killed.to_str().unwrap(), "--quiet"]);
    assert_same_outputs(&full, &killed, "resume after a kill");
    assert!(
        !killed
            .join("checkpoints/.gen-000005.json.tmp-999-0")
            .exists(),
        "stale temporary file left behind"
    );
}

#[test]
fn export_csv_reproduces_fitness_csv() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("run");
    run_tiny(&dir, &[]);
    let out = run_ok(&["export-csv", dir.to_str().unwrap()]);
    assert_eq!(out.stdout, read(&dir.join("fitness.csv")));
    let out = run_ok(&["export-csv", dir.to_str().unwrap(), "--population"]);
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.starts_with("id,fitness,food_a,food_b,food_c,food_d,birth,parent_a,parent_b\n"));
    assert_eq!(text.lines().count(), 1 + 12);
}

#[test]
fn replay_of_best_genome_matches_its_recorded_fitness() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("run");
    run_tiny(&dir, &[]);
    let best: serde_json::Value = serde_json::from_slice(&read(&dir.join("best.json"))).unwrap();
    let fitness = best["origin"]["fitness"].as_f64().unwrap();
    let trace = tmp.path().join("trace.csv");
    let out = run_ok(&[
        "replay",
        dir.join("best.json").to_str().unwrap(),
        "--experiment",
        fixture("tiny.toml").to_str().unwrap(),
        "--trace",
        trace.to_str().unwrap(),
    ]);
    let text = String::from_utf8(out.stdout).unwrap();
    let line = text.lines().find(|l| l.starts_with("fitness ")).unwrap();
    let replayed: f64 = line.split_whitespace().nth(1).unwrap().parse().unwrap();
    assert!(
        (replayed - fitness).abs() < 1e-6,
        "replayed {replayed} vs recorded {fitness}"
    );
    let trace_text = std::fs::read_to_string(&trace).unwrap();
    assert_eq!(
        trace_text.lines().count(),
        1 + 2 * 120,
        "header + ticks of both trials"
    );
}

#[test]
fn running_into_a_used_folder_is_refused_unless_forced() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("run");
    run_tiny(&dir, &["--generations", "1"]);
    let exp = fixture("tiny.toml");
    let err = run_err(&["run", exp.to_str().unwrap(), "--out", dir.to_str().unwrap()]);
    assert!(
        err.contains("already holds a run") && err.contains("resume"),
        "{err}"
    );
    run_tiny(&dir, &["--generations", "1", "--force"]);
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

fn tiny_with(edit: impl FnOnce(String) -> String) -> String {
    edit(std::fs::read_to_string(fixture("tiny.toml")).unwrap())
}

#[test]
fn bad_experiment_files_give_clear_errors() {
    let tmp = tempfile::tempdir().unwrap();
    let cases: Vec<(&str, String, Vec<&str>)> = vec![
        (
            "unknown_key.toml",
            tiny_with(|t| t.replace("[evaluation]", "[evaluation]\ntrails = 3")),
            vec!["unknown_key.toml", "trails"],
        ),
        (
            "wrong_type.toml",
            tiny_with(|t| t.replace("ticks = 120", "ticks = \"long\"")),
            vec!["wrong_type.toml", "ticks"],
        ),
        (
            "out_of_range.toml",
            tiny_with(|t| t.replace("ticks = 120", "ticks = 1000000000000000")),
            vec!["out_of_range.toml", "evaluation.ticks", "at most"],
        ),
        (
            "elitism.toml",
            tiny_with(|t| t.replace("elitism = 1", "elitism = 20")),
            vec!["elitism.toml", "evolution.elitism", "population"],
        ),
        (
            "negative_radius.toml",
            tiny_with(|t| t.replacen("radius = 2.0", "radius = -2.0", 1)),
            vec!["negative_radius.toml", "radius"],
        ),
        (
            "syntax.toml",
            "name = \"x\"\nseed = [".to_string(),
            vec!["syntax.toml", "line"],
        ),
    ];
    for (name, text, needles) in cases {
        let path = write(tmp.path(), name, &text);
        let err = run_err(&[
            "run",
            path.to_str().unwrap(),
            "--out",
            tmp.path().join("o").to_str().unwrap(),
        ]);
        for needle in needles {
            assert!(
                err.contains(needle),
                "{name}: error lacks `{needle}`:\n{err}"
            );
        }
    }
    let err = run_err(&["run", "no/such/file.toml"]);
    assert!(err.contains("no/such/file.toml"), "{err}");
}

#[test]
fn damaged_or_foreign_checkpoints_and_genomes_are_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("run");
    run_tiny(&dir, &[]);
    let cps = checkpoints(&dir);
    let newest = cps.last().unwrap().clone();

    // Truncated newest checkpoint: resuming from it names the previous good one.
    let bytes = read(&newest);
    std::fs::write(&newest, &bytes[..bytes.len() / 2]).unwrap();
    let err = run_err(&["resume", newest.to_str().unwrap()]);
    assert!(
        err.contains(newest.file_name().unwrap().to_str().unwrap()),
        "{err}"
    );
    assert!(
        err.contains(cps[cps.len() - 2].file_name().unwrap().to_str().unwrap()),
        "{err}"
    );
    std::fs::write(&newest, &bytes).unwrap();

    // A checkpoint of another experiment in this folder.
    let other = tmp.path().join("other");
    let exp = write(
        tmp.path(),
        "other.toml",
        &tiny_with(|t| t.replace("seed = 5", "seed = 99")),
    );
    run_ok(&[
        "run",
        exp.to_str().unwrap(),
        "--out",
        other.to_str().unwrap(),
        "--quiet",
        "--generations",
        "10",
    ]);
    let foreign = checkpoints(&other).pop().unwrap();
    let planted = dir.join("checkpoints/gen-000009.json");
    std::fs::copy(&foreign, &planted).unwrap();
    let err = run_err(&["resume", dir.to_str().unwrap()]);
    assert!(
        err.contains("experiment.toml") && err.contains("--allow-config-change"),
        "{err}"
    );
    std::fs::remove_file(&planted).unwrap();

    // A genome whose observation layout does not fit the experiment.
    let no_smell = write(
        tmp.path(),
        "no_smell.toml",
        &tiny_with(|t| t.replace("[brain]", "[creature.inputs]\nsmell = false\n\n[brain]")),
    );
    let err = run_err(&[
        "replay",
        dir.join("best.json").to_str().unwrap(),
        "--experiment",
        no_smell.to_str().unwrap(),
    ]);
    assert!(err.contains("best.json") && err.contains("inputs"), "{err}");
}

#[test]
fn simulate_writes_the_same_trace_twice() {
    let tmp = tempfile::tempdir().unwrap();
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    for demo in [
        "experiments/open-arena.toml",
        "experiments/walled-arena.toml",
    ] {
        let file = root.join(demo);
        let a = tmp.path().join("a.csv");
        let b = tmp.path().join("b.csv");
        for trace in [&a, &b] {
            run_ok(&[
                "simulate",
                file.to_str().unwrap(),
                "--ticks",
                "300",
                "--trace",
                trace.to_str().unwrap(),
            ]);
        }
        let text = std::fs::read_to_string(&a).unwrap();
        assert!(text.starts_with("tick,creature,x,y,heading,"), "{demo}");
        assert!(read(&a) == read(&b), "{demo}: traces differ");
    }
}

#[test]
fn hand_designed_forager_replays_and_eats() {
    // All five trials of generation 0: single worlds can hold no reachable food.
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let out = run_ok(&[
        "replay",
        root.join("genomes/braitenberg-forager.json")
            .to_str()
            .unwrap(),
        "--experiment",
        root.join("experiments/foraging.toml").to_str().unwrap(),
    ]);
    let text = String::from_utf8(out.stdout).unwrap();
    let line = text.lines().find(|l| l.starts_with("fitness ")).unwrap();
    let fitness: f64 = line.split_whitespace().nth(1).unwrap().parse().unwrap();
    assert!(
        fitness > 0.0,
        "the hand-designed forager should eat something:\n{text}"
    );
}

#[test]
fn kept_champion_replays_to_its_recorded_fitness() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let genome = root.join("genomes/foraging-champion-seed2.json");
    let recorded: serde_json::Value = serde_json::from_slice(&read(&genome)).unwrap();
    let recorded = recorded["origin"]["fitness"].as_f64().unwrap();
    // The champion was evolved in the 0.3.5 foraging world, kept as a fixture.
    let experiment = root.join("tests/fixtures/foraging-v035.toml");
    let replay = |extra: &[&str]| {
        let mut args = vec![
            "replay",
            genome.to_str().unwrap(),
            "--experiment",
            experiment.to_str().unwrap(),
        ];
        args.extend_from_slice(extra);
        bin().args(&args).output().unwrap()
    };
    // With its own seed the worlds are the ones it was scored in: the same fitness.
    let out = replay(&["--seed", "2"]);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    let line = text.lines().find(|l| l.starts_with("fitness ")).unwrap();
    let fitness: f64 = line.split_whitespace().nth(1).unwrap().parse().unwrap();
    assert!(
        (fitness - recorded).abs() < 1e-6,
        "replayed {fitness}, recorded {recorded}"
    );
    assert!(!String::from_utf8_lossy(&out.stderr).contains("note:"));
    // With another seed the user is told why the numbers differ.
    let out = replay(&["--trial", "0"]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("another seed"));
}

/// A checkpoint written by another version of the program resumes, with a note that later
/// generations may differ from a run made entirely with that version.
#[test]
fn resuming_another_versions_checkpoint_says_so() {
    use sha2::{Digest, Sha256};
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("old");
    run_tiny(&dir, &["--generations", "3"]);
    let newest = checkpoints(&dir).pop().unwrap();
    let envelope: serde_json::Value = serde_json::from_slice(&read(&newest)).unwrap();
    // Re-sign the envelope as version 0.1.0 would have (the checksum covers `program`).
    let old = "berry-evolve 0.1.0";
    let fields = |checksum: Option<&str>| {
        format!(
            "{{\"format\":{},\"program\":{},\"config_hash\":{},\"generation\":{}{},\"payload\":{}}}",
            envelope["format"],
            serde_json::to_string(old).unwrap(),
            envelope["config_hash"],
            envelope["generation"],
            checksum.map_or(String::new(), |c| format!(",\"checksum\":\"{c}\"")),
            serde_json::to_string(&envelope["payload"]).unwrap()
        )
    };
    let digest = Sha256::digest(fields(None).as_bytes());
    let hex: String = digest.iter().map(|b| format!("{b:02x}")).collect();
    std::fs::write(&newest, fields(Some(&format!("sha256:{hex}"))) + "\n").unwrap();
    let out = bin()
        .args(["resume", dir.to_str().unwrap(), "--generations", "4"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(
        stderr.contains("note:") && stderr.contains("was written by berry-evolve 0.1.0"),
        "{stderr}"
    );
    // Resuming this version's own checkpoint says nothing of the kind.
    let out = bin()
        .args(["resume", dir.to_str().unwrap(), "--generations", "5"])
        .output()
        .unwrap();
    assert!(out.status.success());
    assert!(!String::from_utf8_lossy(&out.stderr).contains("was written by"));
}

/// champions.jsonl: one genome file per generation, each that generation's best individual
/// (fitness.csv's `best`), which replays to its recorded fitness; --force removes it.
#[test]
fn champions_jsonl_holds_each_generations_best_genome() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("run");
    run_tiny(&dir, &[]);
    let text = String::from_utf8(read(&dir.join("champions.jsonl"))).unwrap();
    let csv = String::from_utf8(read(&dir.join("fitness.csv"))).unwrap();
    let best_column: Vec<f64> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(2).unwrap().parse().unwrap())
        .collect();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 8, "one line per generation:\n{text}");
    for (g, line) in lines.iter().enumerate() {
        let v: serde_json::Value = serde_json::from_str(line).unwrap();
        assert_eq!(v["origin"]["generation"], g as u64, "line {g}");
        assert_eq!(v["origin"]["seed"], 5, "line {g}");
        assert_eq!(
            v["origin"]["fitness"].as_f64(),
            Some(best_column[g]),
            "line {g}"
        );
    }
    // A line is a genome file: written out on its own, replay reproduces its fitness.
    let last: serde_json::Value = serde_json::from_str(lines[7]).unwrap();
    let genome = tmp.path().join("champion-7.json");
    std::fs::write(&genome, lines[7]).unwrap();
    let out = run_ok(&[
        "replay",
        genome.to_str().unwrap(),
        "--experiment",
        dir.join("experiment.toml").to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    let recorded = last["origin"]["fitness"].as_f64().unwrap();
    assert!(
        stdout.contains(&format!("fitness {recorded:.6}")),
        "recorded {recorded}:\n{stdout}"
    );
}

/// The checkpoint in tests/fixtures/checkpoint-v035/ was written by berry-evolve 0.3.5 (its
/// binary, `run experiment.toml --out RUN`, the fixture's experiment.toml), before lineage
/// was recorded. It still resumes, and the run extended from it ends byte-identical to a run
/// made entirely with this version; champions.jsonl then starts after the checkpoint, with a
/// note. Its population exports with empty lineage columns and extracts as genome files.
#[test]
fn a_checkpoint_from_before_lineage_resumes_to_the_same_bytes() {
    let tmp = tempfile::tempdir().unwrap();
    let old = fixture("checkpoint-v035/gen-000002.json");
    let text = String::from_utf8(read(&old)).unwrap();
    assert!(text.contains("\"program\":\"berry-evolve 0.3.5\""));
    assert!(!text.contains("lineage"), "the fixture predates lineage");
    let experiment = fixture("checkpoint-v035/experiment.toml");

    let full = tmp.path().join("full");
    run_ok(&[
        "run",
        experiment.to_str().unwrap(),
        "--generations",
        "8",
        "--out",
        full.to_str().unwrap(),
        "--quiet",
    ]);
    let dir = tmp.path().join("resumed");
    std::fs::create_dir_all(dir.join("checkpoints")).unwrap();
    std::fs::copy(&old, dir.join("checkpoints/gen-000002.json")).unwrap();

    let population = run_ok(&["export-csv", dir.to_str().unwrap(), "--population"]);
    let csv = String::from_utf8(population.stdout).unwrap();
    assert!(csv.starts_with("id,fitness,food_a,food_b,food_c,food_d,birth,parent_a,parent_b\n"));
    assert!(csv.lines().nth(1).unwrap().ends_with(",,,"), "{csv}");
    let g = tmp.path().join("old-1.json");
    run_ok(&[
        "extract",
        dir.to_str().unwrap(),
        "--individual",
        "1",
        "-o",
        g.to_str().unwrap(),
    ]);
    run_ok(&[
        "compare",
        g.to_str().unwrap(),
        "--experiment",
        experiment.to_str().unwrap(),
    ]);

    let out = bin()
        .args(["resume", dir.to_str().unwrap(), "--generations", "8"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(
        stderr.contains("champions.jsonl was missing")
            && stderr.contains("starts with generation 3"),
        "{stderr}"
    );
    for f in ["fitness.csv", "best.json", "experiment.toml"] {
        assert!(read(&full.join(f)) == read(&dir.join(f)), "{f} differs");
    }
    let (a, b) = (
        checkpoints(&full).pop().unwrap(),
        checkpoints(&dir).pop().unwrap(),
    );
    assert_eq!(a.file_name(), b.file_name());
    assert!(read(&a) == read(&b), "the final checkpoint differs");
    // champions.jsonl: the uninterrupted run's lines of generations 3 to 7.
    let whole = String::from_utf8(read(&full.join("champions.jsonl"))).unwrap();
    let tail: String = whole.lines().skip(3).map(|l| format!("{l}\n")).collect();
    assert_eq!(
        String::from_utf8(read(&dir.join("champions.jsonl"))).unwrap(),
        tail
    );
}

/// `extract` writes individual K of a checkpoint as a genome file that replay and compare
/// take, whose replay gives the fitness the checkpoint recorded; K out of range, a file that
/// is not a checkpoint and an output naming an input are refused with what to do.
#[test]
fn extract_writes_an_individual_that_replays_to_its_recorded_fitness() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("run");
    run_tiny(&dir, &[]);
    let population = run_ok(&["export-csv", dir.to_str().unwrap(), "--population"]);
    let csv = String::from_utf8(population.stdout).unwrap();
    // The individual with the highest fitness that is not an elite copy (so that its
    // genome is not also best.json's), with its lineage.
    let rows: Vec<Vec<String>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect();
    assert_eq!(rows.len(), 12);
    assert!(rows.iter().any(|r| r[6] == "elite"), "{csv}");
    assert!(
        rows.iter().all(|r| match r[6].as_str() {
            "elite" | "mutated" => !r[7].is_empty() && r[8].is_empty(),
            "crossover" => !r[7].is_empty() && !r[8].is_empty(),
            other => panic!("birth {other} in a GA run"),
        }),
        "{csv}"
    );
    let k = rows
        .iter()
        .filter(|r| r[6] != "elite")
        .max_by(|a, b| {
            let f = |r: &Vec<String>| r[1].parse::<f64>().unwrap();
            f(a).total_cmp(&f(b))
        })
        .unwrap()[0]
        .clone();
    let genome = tmp.path().join("k.json");
    let out = run_ok(&[
        "extract",
        dir.join("checkpoints/gen-000007.json").to_str().unwrap(),
        "--individual",
        &k,
        "-o",
        genome.to_str().unwrap(),
    ]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("wrote individual"));
    let file: serde_json::Value = serde_json::from_slice(&read(&genome)).unwrap();
    assert_eq!(file["origin"]["generation"], 7);
    assert_eq!(file["origin"]["individual"].to_string(), k);
    assert_eq!(file["origin"]["seed"], 5);
    let recorded = file["origin"]["fitness"].as_f64().unwrap();
    let experiment = dir.join("experiment.toml");
    let out = run_ok(&[
        "replay",
        genome.to_str().unwrap(),
        "--experiment",
        experiment.to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains(&format!("fitness {recorded:.6}")),
        "recorded {recorded}:\n{stdout}"
    );
    run_ok(&[
        "compare",
        genome.to_str().unwrap(),
        dir.join("best.json").to_str().unwrap(),
        "--experiment",
        experiment.to_str().unwrap(),
    ]);

    let extract = |target: &Path, k: &str, output: &Path| {
        run_err(&[
            "extract",
            target.to_str().unwrap(),
            "--individual",
            k,
            "-o",
            output.to_str().unwrap(),
        ])
    };
    let elsewhere = tmp.path().join("x.json");
    let err = extract(&dir, "12", &elsewhere);
    assert!(
        err.contains("--individual 12") && err.contains("numbered 0 to 11"),
        "{err}"
    );
    let err = extract(&dir.join("best.json"), "0", &elsewhere);
    assert!(err.contains("it is a genome file"), "{err}");
    let err = extract(&dir.join("fitness.csv"), "0", &elsewhere);
    assert!(err.contains("not a readable checkpoint"), "{err}");
    assert!(!elsewhere.exists());
    for input in [
        "best.json",
        "champions.jsonl",
        "checkpoints/gen-000005.json",
    ] {
        let before = read(&dir.join(input));
        let err = extract(&dir, "0", &dir.join(input));
        assert!(err.contains("-o"), "{input}: {err}");
        assert!(read(&dir.join(input)) == before, "{input} was changed");
    }
}
