//! What a run folder holds and how `--force` and `resume` treat it: `--force` removes only the
//! run's own files and says which; `resume` finds the run of a checkpoint wherever it is
//! named from, refuses an older checkpoint or a shorter run unless asked explicitly (with the
//! exact command), repairs fitness.csv from the checkpoint's rows and honours [output] edits.

use crate::cli_common::{bin, fixture, read, run_err, run_ok};
use std::path::{Path, PathBuf};

fn tiny_run(dir: &Path, extra: &[&str]) -> std::process::Output {
    let exp = fixture("tiny.toml");
    let mut args = vec!["run", exp.to_str().unwrap(), "--out", dir.to_str().unwrap()];
    args.extend_from_slice(extra);
    run_ok(&args)
}

fn checkpoints(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir.join("checkpoints"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.file_name().unwrap().to_str().unwrap().starts_with("gen-"))
        .collect();
    v.sort();
    v
}

fn same_run(a: &Path, b: &Path, what: &str) {
    for f in ["fitness.csv", "best.json", "champions.jsonl"] {
        assert!(read(&a.join(f)) == read(&b.join(f)), "{what}: {f} differs");
    }
    let (x, y) = (checkpoints(a).pop().unwrap(), checkpoints(b).pop().unwrap());
    assert_eq!(x.file_name(), y.file_name(), "{what}");
    assert!(read(&x) == read(&y), "{what}: final checkpoint differs");
}

#[test]
fn force_removes_only_the_runs_own_files_and_says_which() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("run");
    tiny_run(&dir, &["--quiet"]);
    std::fs::write(dir.join("checkpoints/model.pt"), b"user's model").unwrap();
    std::fs::write(dir.join("notes.txt"), b"user's notes").unwrap();
    let out = tiny_run(&dir, &["--force", "--generations", "2"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("--force removed")
            && stderr.contains("fitness.csv")
            && stderr.contains("champions.jsonl")
            && stderr.contains("checkpoints/gen-000007.json"),
        "{stderr}"
    );
    // The old run's champions are gone, not continued: the new run's two generations only.
    let champions = String::from_utf8(read(&dir.join("champions.jsonl"))).unwrap();
    assert_eq!(champions.lines().count(), 2, "{champions}");
    assert!(!stderr.contains("model.pt"), "{stderr}");
    assert_eq!(read(&dir.join("checkpoints/model.pt")), b"user's model");
    assert_eq!(read(&dir.join("notes.txt")), b"user's notes");

    // The user's own, commented experiment.toml is not the run's: refused, nothing removed.
    let mine = format!(
        "# my notes\n{}",
        String::from_utf8(read(&fixture("tiny.toml"))).unwrap()
    );
    std::fs::write(dir.join("experiment.toml"), &mine).unwrap();
    let before = checkpoints(&dir);
    let err = run_err(&[
        "run",
        fixture("tiny.toml").to_str().unwrap(),
        "--out",
        dir.to_str().unwrap(),
        "--force",
    ]);
    assert!(
        err.contains("experiment.toml") && err.contains("move it out"),
        "{err}"
    );
    assert_eq!(read(&dir.join("experiment.toml")), mine.as_bytes());
    assert_eq!(checkpoints(&dir), before);
}

#[test]
fn a_checkpoint_named_through_a_link_a_bare_name_or_a_copy_resumes_its_run_or_is_refused_first() {
    let tmp = tempfile::tempdir().unwrap();
    let full = tmp.path().join("full");
    tiny_run(&full, &["--quiet"]);
    // A short run, extended through a symbolic link to its newest checkpoint.
    let short = tmp.path().join("short");
    tiny_run(&short, &["--quiet", "--generations", "4"]);
    let link = tmp.path().join("latest.json");
    std::os::unix::fs::symlink(checkpoints(&short).pop().unwrap(), &link).unwrap();
    run_ok(&[
        "resume",
        link.to_str().unwrap(),
        "--generations",
        "8",
        "--quiet",
    ]);
    same_run(&full, &short, "resumed through a link");
    assert!(
        !tmp.path().join("fitness.csv").exists(),
        "run files beside the link"
    );

    // A bare name typed inside checkpoints/.
    let bare = tmp.path().join("bare");
    tiny_run(&bare, &["--quiet", "--generations", "4"]);
    let out = bin()
        .current_dir(bare.join("checkpoints"))
        .args(["resume", "gen-000003.json", "--generations", "8", "--quiet"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    same_run(&full, &bare, "resumed by a bare name");
    assert!(!bare.join("checkpoints/fitness.csv").exists());

    // A copy outside any run folder: refused at once, nothing written beside it.
    let lone = tmp.path().join("lone");
    std::fs::create_dir(&lone).unwrap();
    let copy = lone.join("gen-000007.json");
    std::fs::copy(checkpoints(&full).pop().unwrap(), &copy).unwrap();
    let started = std::time::Instant::now();
    let err = run_err(&["resume", copy.to_str().unwrap(), "--generations", "20"]);
    assert!(started.elapsed().as_secs() < 5, "computed before refusing");
    assert!(
        err.contains("not inside a run folder") && err.contains("berry-evolve resume RUN"),
        "{err}"
    );
    assert_eq!(
        std::fs::read_dir(&lone).unwrap().count(),
        1,
        "files written beside the copy"
    );
}

/// Every refusal of `resume` names the whole command that works at the first try, whatever
/// combination of flags the resume needs (an older checkpoint, fewer generations, an edited
/// experiment), and a refused resume touches nothing.
#[test]
fn each_resume_refusal_names_a_command_that_works_at_the_first_try() {
    let tmp = tempfile::tempdir().unwrap();
    let base = tmp.path().join("base");
    tiny_run(&base, &["--quiet", "--generations", "12"]);
    let cases: [(&str, &[&str], bool); 4] = [
        ("older, shorter", &["--generations", "9"], false),
        ("older, longer", &["--generations", "14"], false),
        ("older, edited file", &[], true),
        (
            "older, shorter, edited file",
            &["--generations", "10"],
            true,
        ),
    ];
    for (what, extra, edit) in cases {
        let dir = tmp.path().join(what.replace([',', ' '], "-"));
        copy_dir(&base, &dir);
        if edit {
            let path = dir.join("experiment.toml");
            let text = String::from_utf8(read(&path)).unwrap();
            std::fs::write(&path, text.replacen("seed = 5", "seed = 6", 1)).unwrap();
        }
        let older = checkpoints(&dir)[0].clone();
        let mut args = vec!["resume", older.to_str().unwrap()];
        args.extend_from_slice(extra);
        let before = checkpoints(&dir);
        let err = run_err(&args);
        assert_eq!(
            checkpoints(&dir),
            before,
            "{what}: a refusal changed the checkpoints"
        );
        assert!(
            !dir.join("config-changes.log").exists(),
            "{what}: a refusal wrote the log"
        );
        let command = err
            .rsplit(": ")
            .find(|part| part.contains(" resume "))
            .unwrap_or_else(|| panic!("{what}: no command in {err}"))
            .trim();
        let mut args: Vec<&str> = command.split_whitespace().skip(1).collect();
        args.push("--quiet");
        run_ok(&args);
    }
}

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let entry = entry.unwrap();
        let target = to.join(entry.file_name());
        if entry.file_type().unwrap().is_dir() {
            copy_dir(&entry.path(), &target);
        } else {
            std::fs::copy(entry.path(), target).unwrap();
        }
    }
}

#[test]
fn an_older_checkpoint_or_a_shorter_run_is_refused_with_the_command_that_does_it() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("run");
    tiny_run(&dir, &["--quiet"]);
    let cps = checkpoints(&dir);
    let older = cps[0].clone();
    let err = run_err(&["resume", older.to_str().unwrap(), "--generations", "6"]);
    assert!(
        err.contains("newer than") && err.contains("--discard-newer"),
        "{err}"
    );
    assert_eq!(
        checkpoints(&dir),
        cps,
        "a refused resume changed the checkpoints"
    );
    // The command named does it at the first try, explicitly (the run plans 8 generations,
    // so it shortens too): newer checkpoints moved aside, recorded.
    let command = err.split("run: ").nth(1).unwrap().trim();
    assert!(command.contains("--shorten"), "{command}");
    let mut args: Vec<&str> = command.split_whitespace().skip(1).collect();
    args.push("--quiet");
    run_ok(&args);
    assert!(dir.join("discarded-checkpoints/gen-000007.json").exists());
    let log = String::from_utf8(read(&dir.join("config-changes.log"))).unwrap();
    assert!(
        log.contains("--discard-newer") && log.contains("--shorten"),
        "{log}"
    );
    let csv = String::from_utf8(read(&dir.join("fitness.csv"))).unwrap();
    assert_eq!(csv.lines().count(), 1 + 6, "{csv}");
    // A 6-generation run made directly is the same run.
    let direct = tmp.path().join("direct");
    tiny_run(&direct, &["--quiet", "--generations", "6"]);
    same_run(&direct, &dir, "shortened run");
    // And the folder resumes further without being stuck.
    run_ok(&[
        "resume",
        dir.to_str().unwrap(),
        "--generations",
        "8",
        "--quiet",
    ]);
}

#[test]
fn a_damaged_fitness_row_is_repaired_from_the_checkpoint_and_output_edits_are_honoured() {
    let tmp = tempfile::tempdir().unwrap();
    let full = tmp.path().join("full");
    tiny_run(&full, &["--quiet"]);
    let dir = tmp.path().join("run");
    tiny_run(&dir, &["--quiet", "--generations", "4"]);
    let csv = String::from_utf8(read(&dir.join("fitness.csv"))).unwrap();
    let mut lines: Vec<String> = csv.lines().map(String::from).collect();
    // Generation 1's best fitness edited: still a parseable row.
    let mut cells: Vec<String> = lines[2].split(',').map(String::from).collect();
    cells[2] = "99.5".to_string();
    lines[2] = cells.join(",");
    std::fs::write(dir.join("fitness.csv"), lines.join("\n") + "\n").unwrap();
    let out = run_ok(&["resume", dir.to_str().unwrap(), "--generations", "8"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("repaired") && stderr.contains("generation 1"),
        "{stderr}"
    );
    assert!(read(&dir.join("fitness.csv")) == read(&full.join("fitness.csv")));

    // An edited [output] table is used, not reverted.
    let exp = dir.join("experiment.toml");
    let text = String::from_utf8(read(&exp)).unwrap();
    assert!(text.contains("keep_checkpoints = 3"), "{text}");
    std::fs::write(
        &exp,
        text.replace("keep_checkpoints = 3", "keep_checkpoints = 5"),
    )
    .unwrap();
    let out = run_ok(&["resume", dir.to_str().unwrap(), "--generations", "12"]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("[output]"));
    assert!(String::from_utf8(read(&exp))
        .unwrap()
        .contains("keep_checkpoints = 5"));
}

/// An edited experiment.toml is refused naming the keys that changed, and with
/// --allow-config-change the log records each key with its old and new value.
#[test]
fn a_changed_experiment_names_the_keys_that_changed() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("run");
    tiny_run(&dir, &["--quiet"]);
    let path = dir.join("experiment.toml");
    let text = String::from_utf8(read(&path)).unwrap();
    assert!(text.contains("elitism = 1\n"), "{text}");
    std::fs::write(&path, text.replace("elitism = 1\n", "elitism = 2\n")).unwrap();
    let err = run_err(&["resume", dir.to_str().unwrap(), "--generations", "10"]);
    assert!(err.contains("evolution.elitism: 1 -> 2"), "{err}");
    run_ok(&[
        "resume",
        dir.to_str().unwrap(),
        "--generations",
        "10",
        "--allow-config-change",
        "--quiet",
    ]);
    let log = String::from_utf8(read(&dir.join("config-changes.log"))).unwrap();
    assert!(log.contains("\n  evolution.elitism: 1 -> 2\n"), "{log}");
}
