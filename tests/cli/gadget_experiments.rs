//! End-to-end runs of the experiments with doors, teleporters, predators and wanderers:
//! `simulate` writes the same trace twice, and evolution runs and reproduces its fitness file
//! byte for byte.

use crate::cli_common::{experiment, run_ok};

#[test]
fn gadget_experiments_simulate_and_evolve_reproducibly() {
    let tmp = tempfile::tempdir().unwrap();
    for name in [
        "t-maze.toml",
        "locked-room.toml",
        "predator-arena.toml",
        "air-raid.toml",
        "crowded-arena.toml",
    ] {
        let file = experiment(name);
        let traces: Vec<Vec<u8>> = ["a.csv", "b.csv"]
            .iter()
            .map(|t| {
                let path = tmp.path().join(format!("{name}-{t}"));
                run_ok(&[
                    "simulate",
                    &file,
                    "--ticks",
                    "500",
                    "--trace",
                    path.to_str().unwrap(),
                ]);
                std::fs::read(path).unwrap()
            })
            .collect();
        assert!(!traces[0].is_empty(), "{name}: empty trace");
        assert!(traces[0] == traces[1], "{name}: traces differ");

        let fitness: Vec<Vec<u8>> = ["run-a", "run-b"]
            .iter()
            .map(|run| {
                let dir = tmp.path().join(format!("{name}-{run}"));
                run_ok(&[&file, "--generations", "2", "--out", dir.to_str().unwrap()]);
                std::fs::read(dir.join("fitness.csv")).unwrap()
            })
            .collect();
        assert!(fitness[0] == fitness[1], "{name}: fitness files differ");
        assert_eq!(
            String::from_utf8_lossy(&fitness[0]).lines().count(),
            3,
            "{name}: header and two generations"
        );
    }
}

#[test]
fn bench_runs_both_benchmark_worlds() {
    let out = run_ok(&[
        "bench",
        "--world",
        &experiment("bench/foraging-world.toml"),
        "--world",
        &experiment("bench/eye-predators-world.toml"),
        "--worlds",
        "2",
        "--ticks",
        "50",
        "--generations",
        "0",
        "--scaling",
        "1,10",
        "--scaling-world",
        &experiment("bench/foraging-world.toml"),
    ]);
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("foraging-world.toml:"), "{text}");
    assert!(text.contains("eye-predators-world.toml:"), "{text}");
    assert!(
        text.contains("machine check around the 1-thread runs: a high-throughput"),
        "{text}"
    );
    // The scaling series of the performance issue: 40 food and 12 walls in 300 x 300, then
    // 100 times as much of both in 3000 x 3000.
    assert!(
        text.contains("x1: 300 x 300 arena, 12 walls, 40 objects:"),
        "{text}"
    );
    assert!(
        text.contains("x10: 3000 x 3000 arena, 1200 walls, 4000 objects:"),
        "{text}"
    );
}
