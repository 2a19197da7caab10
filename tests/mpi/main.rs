//! MPI ranks give the bytes of one machine (issue 20). Built only with the `mpi` feature:
//! `cargo test --release --features mpi --test mpi` (needs Open MPI's `mpirun`; ranks are
//! oversubscribed, so it runs on any number of cores). Each test compares `fitness.csv`,
//! `best.json` and every checkpoint byte for byte with a run of the same binary started
//! without `mpirun`, which initialises no MPI and evaluates on its own threads exactly as a
//! build without the feature does.

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

/// The binary under test (built with the `mpi` feature).
fn bin() -> &'static str {
    env!("CARGO_BIN_EXE_berry-evolve")
}

/// `berry-evolve` on `np` oversubscribed ranks (as root too, as in CI).
fn mpirun(np: usize) -> Command {
    let mut c = Command::new("mpirun");
    c.args(["--oversubscribe", "-np", &np.to_string(), bin()])
        .env("OMPI_ALLOW_RUN_AS_ROOT", "1")
        .env("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1");
    c
}

/// `berry-evolve` alone, without MPI.
fn plain() -> Command {
    Command::new(bin())
}

/// Runs `command` with `args`, expects success, returns its output.
fn ok(mut command: Command, args: &[&str]) -> Output {
    let out = command
        .args(args)
        .output()
        .expect("mpirun and berry-evolve run");
    assert!(
        out.status.success(),
        "{command:?} failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

fn path(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// `name`, a copy of `source` (relative to the repository) with `edit` applied to its text,
/// written into `dir`.
fn variant(dir: &Path, source: &str, name: &str, edit: impl Fn(String) -> String) -> PathBuf {
    let text = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join(source))
        .expect("experiment file");
    let out = dir.join(name);
    std::fs::write(&out, edit(text)).unwrap();
    out
}

/// A checkpoint every `every` generations instead of the file's own `[output]` table.
fn checkpoint_every(every: u64) -> impl Fn(String) -> String {
    move |text| {
        let mut table: toml::Table = text.parse().expect("toml");
        let output = table
            .entry("output")
            .or_insert_with(|| toml::Value::Table(toml::Table::new()));
        let output = output.as_table_mut().expect("[output] table");
        output.insert(
            "checkpoint_every".into(),
            toml::Value::Integer(every as i64),
        );
        output.insert("keep_checkpoints".into(), toml::Value::Integer(1000));
        toml::to_string(&table).unwrap()
    }
}

/// `other` holds the run `reference` holds: the same fitness.csv, best.json and every
/// checkpoint of `reference` (an extra older one in `other`, left by a leg that ended
/// earlier, does not count), naming the first file that differs.
fn assert_same_run(reference: &Path, other: &Path, what: &str) {
    for f in ["fitness.csv", "best.json", "archive.csv"] {
        if f == "archive.csv" && !reference.join(f).exists() {
            continue; // only archive searches write it
        }
        let a = std::fs::read(reference.join(f)).unwrap();
        let b = std::fs::read(other.join(f))
            .unwrap_or_else(|e| panic!("{what}: no {f} in {}: {e}", other.display()));
        assert!(a == b, "{what}: {f} differs from the plain run's");
    }
    let mut names: Vec<_> = std::fs::read_dir(reference.join("checkpoints"))
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    names.sort();
    assert!(
        !names.is_empty(),
        "{what}: the plain run wrote no checkpoint"
    );
    for name in names {
        let a = std::fs::read(reference.join("checkpoints").join(&name)).unwrap();
        let b = std::fs::read(other.join("checkpoints").join(&name))
            .unwrap_or_else(|e| panic!("{what}: checkpoint {name:?} missing: {e}"));
        assert!(
            a == b,
            "{what}: checkpoint {name:?} differs from the plain run's"
        );
    }
}

/// The jobs each rank evaluated, from the run's closing note.
fn jobs_per_rank(stderr: &str) -> Vec<u64> {
    let line = stderr
        .lines()
        .find(|l| l.starts_with("evaluated on "))
        .unwrap_or_else(|| panic!("no jobs-per-rank note in:\n{stderr}"));
    line.rsplit(": ")
        .next()
        .unwrap()
        .split(", ")
        .map(|n| n.parse().unwrap())
        .collect()
}

/// Waits until `file` exists (the run got that far), failing after a minute.
fn wait_for(file: &Path, child: &mut Child) {
    let start = Instant::now();
    while !file.exists() {
        if let Some(status) = child.try_wait().unwrap() {
            panic!("the run ended ({status}) before {} existed", file.display());
        }
        assert!(
            start.elapsed() < Duration::from_secs(60),
            "{} did not appear within a minute",
            file.display()
        );
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// The process of MPI rank `rank` whose command line names `marker`.
fn rank_pid(rank: usize, marker: &str) -> u32 {
    let wanted = format!("OMPI_COMM_WORLD_RANK={rank}");
    for entry in std::fs::read_dir("/proc").unwrap().flatten() {
        let Ok(pid) = entry.file_name().to_string_lossy().parse::<u32>() else {
            continue;
        };
        let cmdline = std::fs::read(entry.path().join("cmdline")).unwrap_or_default();
        let environ = std::fs::read(entry.path().join("environ")).unwrap_or_default();
        let has = |bytes: &[u8], s: &str| bytes.split(|&b| b == 0).any(|w| w == s.as_bytes());
        let names = String::from_utf8_lossy(&cmdline).contains(marker);
        if names
            && has(&environ, &wanted)
            && !String::from_utf8_lossy(&cmdline).starts_with("mpirun")
        {
            return pid;
        }
    }
    panic!("no process of rank {rank} for {marker}");
}

fn signal(pid: u32, name: &str) {
    let status = Command::new("kill")
        .args([name, &pid.to_string()])
        .status()
        .unwrap();
    assert!(status.success(), "kill {name} {pid}");
}

/// The `[brain]` lines that make t-maze-switch-tiny's MLP a neuromodulated plastic one.
const PLASTIC: &str = "hidden = [8]\nplasticity = \"neuromodulated\"\ngranularity = \"layer\"\nmodulators = [\"food_a\", \"food_c\", \"neurons\"]\n";

#[test]
fn one_two_and_three_ranks_give_the_plain_bytes() {
    let tmp = tempfile::tempdir().unwrap();
    let t = tmp.path();
    // A gadget world (doors, lockstep MLP), validation with behaviour measures, a stateful
    // brain (one job per trial), PGPE (its centre evaluated last), novelty search and
    // MAP-Elites.
    let cases = [
        (
            variant(
                t,
                "experiments/locked-room.toml",
                "locked-room.toml",
                checkpoint_every(1),
            ),
            "3",
        ),
        (
            variant(
                t,
                "experiments/foraging.toml",
                "foraging.toml",
                checkpoint_every(2),
            ),
            "4",
        ),
        (
            variant(t, "tests/fixtures/tiny.toml", "tiny-ctrnn.toml", |s| {
                s.replace("kind = \"mlp\"\nhidden = [4]", "kind = \"ctrnn\"")
            }),
            "4",
        ),
        (
            variant(t, "tests/fixtures/tiny-pgpe.toml", "tiny-pgpe.toml", |s| s),
            "4",
        ),
        // A plastic brain over lives of several episodes with a switch (issue 31): the
        // weights it learns carry across episodes, so each life is one job; its ranks must
        // give the plain bytes too.
        (
            variant(
                t,
                "tests/fixtures/t-maze-switch-tiny.toml",
                "t-maze-switch-plastic.toml",
                |s| s.replace("hidden = [8]\n", PLASTIC),
            ),
            "3",
        ),
        // Archive searches: the novelty archive and MAP-Elites' grid are told the
        // generation's behaviour measures, which each rank sends back with the fitness
        // (MAP-Elites: archive.csv and the checkpoint's elites too).
        (
            variant(
                t,
                "tests/fixtures/tiny-novelty.toml",
                "tiny-novelty.toml",
                |s| s,
            ),
            "4",
        ),
        (
            variant(
                t,
                "tests/fixtures/tiny-map-elites.toml",
                "tiny-map-elites.toml",
                |s| s,
            ),
            "5",
        ),
        // ... with descriptors that count the time in named areas, which the ranks send back
        // with each trial's outcome.
        (
            variant(
                t,
                "tests/fixtures/tiny-map-elites-areas.toml",
                "tiny-map-elites-areas.toml",
                |s| s,
            ),
            "4",
        ),
        // ... and in draw order 2, where each offspring draws from its own stream.
        (
            variant(
                t,
                "tests/fixtures/tiny.toml",
                "tiny-draw-order-2.toml",
                |s| s.replacen("\n[evolution]\n", "\n[evolution]\ndraw_order = 2\n", 1),
            ),
            "4",
        ),
    ];
    for (experiment, generations) in &cases {
        let name = experiment
            .file_stem()
            .unwrap()
            .to_string_lossy()
            .to_string();
        let reference = t.join(format!("{name}-plain"));
        ok(
            plain(),
            &[
                "run",
                path(experiment),
                "--generations",
                generations,
                "--jobs",
                "2",
                "--quiet",
                "--out",
                path(&reference),
            ],
        );
        for np in 1..=3 {
            let dir = t.join(format!("{name}-np{np}"));
            let out = ok(
                mpirun(np),
                &[
                    "run",
                    path(experiment),
                    "--generations",
                    generations,
                    "--jobs",
                    "1",
                    "--out",
                    path(&dir),
                ],
            );
            let stderr = String::from_utf8_lossy(&out.stderr);
            let done = jobs_per_rank(&stderr);
            assert_eq!(done.len(), np, "{name} on {np} ranks: {stderr}");
            assert!(
                done.iter().all(|&j| j > 0),
                "{name}: a rank evaluated nothing: {done:?}"
            );
            assert_same_run(&reference, &dir, &format!("{name} on {np} ranks"));
        }
    }
}

/// foraging.toml with a checkpoint every 2 generations, and its plain run of 30 generations.
fn foraging_reference(t: &Path) -> (PathBuf, PathBuf) {
    let experiment = variant(
        t,
        "experiments/foraging.toml",
        "foraging.toml",
        checkpoint_every(2),
    );
    let reference = t.join("plain");
    ok(
        plain(),
        &[
            "run",
            path(&experiment),
            "--generations",
            "30",
            "--jobs",
            "2",
            "--quiet",
            "--out",
            path(&reference),
        ],
    );
    (experiment, reference)
}

/// `ranks` ranks running the foraging experiment for 30 generations into `dir`, once its
/// third checkpoint is there (stderr piped, for the test to read).
fn started_foraging_run(ranks: usize, experiment: &Path, dir: &Path) -> std::process::Child {
    let mut child = mpirun(ranks)
        .args([
            "run",
            path(experiment),
            "--generations",
            "30",
            "--jobs",
            "1",
            "--out",
            path(dir),
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    wait_for(&dir.join("checkpoints/gen-000003.json"), &mut child);
    child
}

#[test]
fn a_killed_rank_stops_the_run_and_resume_on_one_rank_gives_the_plain_bytes() {
    let tmp = tempfile::tempdir().unwrap();
    let (experiment, reference) = foraging_reference(tmp.path());
    let dir = tmp.path().join("killed-rank");
    let child = started_foraging_run(3, &experiment, &dir);
    signal(rank_pid(2, path(&dir)), "-KILL");
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success(),
        "the run went on without rank 2:\n{stderr}"
    );
    assert!(
        stderr.contains("rank 2"),
        "the message does not name rank 2:\n{stderr}"
    );
    assert!(!stderr.contains("panicked"), "{stderr}");
    let rows = std::fs::read_to_string(dir.join("fitness.csv"))
        .unwrap()
        .lines()
        .count();
    assert!(
        rows < 31,
        "the run finished before the kill; nothing was tested"
    );
    // The last good checkpoint is there: resume on one machine, no MPI.
    ok(plain(), &["resume", path(&dir), "--jobs", "2", "--quiet"]);
    assert_same_run(&reference, &dir, "killed rank 2, resumed without MPI");
}

#[test]
fn sigint_to_mpirun_stops_after_the_generation_and_three_ranks_resume() {
    let tmp = tempfile::tempdir().unwrap();
    let (experiment, reference) = foraging_reference(tmp.path());
    let dir = tmp.path().join("interrupted");
    let child = started_foraging_run(2, &experiment, &dir);
    // mpirun passes it on to every rank as SIGTERM (after 1 s): rank 0 finishes the
    // generation, writes its checkpoint and releases the workers.
    signal(child.id(), "-INT");
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    let stopped = stderr
        .lines()
        .find(|l| l.starts_with("stopped: interrupted after generation "))
        .unwrap_or_else(|| panic!("no clean stop:\n{stderr}"));
    let generation: u64 = stopped
        .trim_start_matches("stopped: interrupted after generation ")
        .split(';')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!(
        generation < 29,
        "the run finished before the signal; nothing was tested"
    );
    let newest = dir.join(format!("checkpoints/gen-{generation:06}.json"));
    assert!(
        newest.exists(),
        "no checkpoint of generation {generation}:\n{stderr}"
    );
    let out = ok(mpirun(3), &["resume", path(&dir), "--jobs", "1"]);
    assert_eq!(
        jobs_per_rank(&String::from_utf8_lossy(&out.stderr)).len(),
        3
    );
    assert_same_run(&reference, &dir, "interrupted on 2 ranks, resumed on 3");
}

/// A run started on `first` that goes on, from its checkpoint of generation 1, on `then`
/// (`resume CHECKPOINT --discard-newer`: the generations after it are evaluated again there).
fn moved_run(t: &Path, experiment: &str, name: &str, first: Command, then: Command) -> PathBuf {
    let dir = t.join(name);
    ok(
        first,
        &[
            "run",
            experiment,
            "--generations",
            "6",
            "--jobs",
            "1",
            "--quiet",
            "--out",
            path(&dir),
        ],
    );
    let checkpoint = dir.join("checkpoints/gen-000001.json");
    ok(
        then,
        &[
            "resume",
            path(&checkpoint),
            "--discard-newer",
            "--jobs",
            "1",
            "--quiet",
        ],
    );
    dir
}

#[test]
fn a_run_moves_from_three_ranks_to_one_and_from_one_to_three() {
    let tmp = tempfile::tempdir().unwrap();
    let t = tmp.path();
    let experiment = variant(
        t,
        "experiments/locked-room.toml",
        "locked-room.toml",
        checkpoint_every(1),
    );
    let e = path(&experiment);
    let reference = t.join("plain");
    ok(
        plain(),
        &[
            "run",
            e,
            "--generations",
            "6",
            "--jobs",
            "2",
            "--quiet",
            "--out",
            path(&reference),
        ],
    );
    let down = moved_run(t, e, "three-to-one", mpirun(3), mpirun(1));
    assert_same_run(&reference, &down, "3 ranks, then 1");
    let down = moved_run(t, e, "three-to-none", mpirun(3), plain());
    assert_same_run(&reference, &down, "3 ranks, then no MPI");
    let up = moved_run(t, e, "one-to-three", plain(), mpirun(3));
    assert_same_run(&reference, &up, "no MPI, then 3 ranks");
}
