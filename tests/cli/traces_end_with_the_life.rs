//! `simulate --trace` and `replay --trace` end by the same rule, a scored trial's: the last
//! rows are those of the tick in which the last creature died (alive = 0), and a creature
//! killed in tick 58 lived 57 ticks.

use crate::cli_common::{read, run_ok};
use std::path::Path;

/// An air predator that stays away 58 ticks, then strikes the whole arena in tick 58.
const DEATH_IN_TICK_58: &str = r#"
name = "death"
seed = 4

[world]
arena = [100.0, 100.0]
[[world.air_predators]]
speed = 1.0
strike_radius = 1000.0
effect = "lethal"
pause = [58, 58]

[brain]
kind = "mlp"

[evolution]
population = 4
generations = 1
elitism = 0

[evaluation]
trials = 1
ticks = 100

[behaviour]
measures = ["ticks_alive"]

[demo]
creatures = 2
"#;

/// Per tick of the trace CSV at `path`, in order: (tick, the alive column of its rows).
fn alive_by_tick(path: &Path) -> Vec<(u64, Vec<u8>)> {
    let text = String::from_utf8(read(path)).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |name: &str| {
        header
            .iter()
            .position(|h| *h == name)
            .unwrap_or_else(|| panic!("{}: no column {name}", path.display()))
    };
    let (tick, alive) = (col("tick"), col("alive"));
    let mut out: Vec<(u64, Vec<u8>)> = Vec::new();
    for line in lines {
        let cells: Vec<&str> = line.split(',').collect();
        let t: u64 = cells[tick].parse().unwrap();
        let a: u8 = cells[alive].parse().unwrap();
        match out.last_mut() {
            Some((last, rows)) if *last == t => rows.push(a),
            _ => out.push((t, vec![a])),
        }
    }
    out
}

#[test]
fn simulate_and_replay_traces_both_end_on_the_death_tick() {
    let tmp = tempfile::tempdir().unwrap();
    let file = tmp.path().join("death.toml");
    std::fs::write(&file, DEATH_IN_TICK_58).unwrap();
    let file = file.to_str().unwrap();
    let run = tmp.path().join("run");
    run_ok(&["run", file, "--out", run.to_str().unwrap(), "--quiet"]);
    let replayed = tmp.path().join("replay.csv");
    let out = run_ok(&[
        "replay",
        run.join("best.json").to_str().unwrap(),
        "--experiment",
        file,
        "--trace",
        replayed.to_str().unwrap(),
        "--json",
    ]);
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(
        json["measures"]["ticks_alive"], 57.0,
        "killed in tick 58, alive at the end of ticks 1–57: {json}"
    );
    let simulated = tmp.path().join("simulate.csv");
    let out = run_ok(&[
        "simulate",
        file,
        "--ticks",
        "100",
        "--trace",
        simulated.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("every creature was dead after tick 58 of 100"),
        "{stderr}"
    );
    for (trace, creatures) in [(&replayed, 1), (&simulated, 2)] {
        let ticks = alive_by_tick(trace);
        let name = trace.display();
        assert_eq!(ticks.len(), 58, "{name}: ticks 1 to 58");
        for (k, (tick, alive)) in ticks.iter().enumerate() {
            assert_eq!(*tick, k as u64 + 1, "{name}");
            let want = u8::from(*tick < 58);
            assert_eq!(alive, &vec![want; creatures], "{name}: tick {tick}");
        }
    }
}
