//! The run guarantees every search keeps, checked one way for all of them: a fixture run on 1
//! and on 2 threads gives the same bytes, and a run stopped after 3 generations and resumed to
//! 6 gives the bytes of one never stopped (each search's own test then reads its state out of
//! the checkpoint).
use crate::cli_common::{fixture, read, run_ok};
use std::path::{Path, PathBuf};
use tempfile::TempDir;

/// The files compared, besides those a search adds (`archive.csv`).
const COMPARED: [&str; 4] = [
    "fitness.csv",
    "best.json",
    "champions.jsonl",
    "checkpoints/gen-000005.json",
];

/// `berry-evolve run FILE --out OUT --generations G --jobs J --quiet`, which must succeed.
pub fn run(file: &Path, out: &Path, generations: &str, jobs: &str) {
    run_ok(&[
        "run",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--generations",
        generations,
        "--jobs",
        jobs,
        "--quiet",
        "--no-estimate",
    ]);
}

fn same_files(a: &Path, b: &Path, also: &[&str], what: &str) {
    for f in COMPARED.iter().chain(also) {
        assert!(read(&a.join(f)) == read(&b.join(f)), "{what}: {f} differs");
    }
}

/// Runs `tests/fixtures/<name>` for 6 generations on 1 thread, again on 2, and stopped after 3
/// and resumed to 6, and asserts that all three give the same bytes (`also`: files beyond
/// fitness.csv, best.json, champions.jsonl and the last checkpoint). Returns the folder holding
/// the runs and the 1-thread run, whose checkpoint the caller inspects.
pub fn same_bytes_on_any_thread_count_and_resumed(name: &str, also: &[&str]) -> (TempDir, PathBuf) {
    same_bytes_for(&fixture(name), name, also)
}

/// [`same_bytes_on_any_thread_count_and_resumed`] for any experiment file (`what` names it
/// in a failure).
pub fn same_bytes_for(file: &Path, what: &str, also: &[&str]) -> (TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let [one, two, resumed] = ["one", "two", "resumed"].map(|d| dir.path().join(d));
    run(file, &one, "6", "1");
    run(file, &two, "6", "2");
    same_files(&one, &two, also, &format!("{what}: --jobs 1 vs 2"));
    run(file, &resumed, "3", "2");
    run_ok(&[
        "resume",
        resumed.to_str().unwrap(),
        "--generations",
        "6",
        "--quiet",
    ]);
    same_files(
        &one,
        &resumed,
        also,
        &format!("{what}: resumed vs uninterrupted"),
    );
    (dir, one)
}

/// The checkpoint of generation 5 of a run made by [`same_bytes_on_any_thread_count_and_resumed`].
pub fn last_checkpoint(run: &Path) -> serde_json::Value {
    serde_json::from_slice(&read(&run.join("checkpoints/gen-000005.json"))).unwrap()
}
