//! End-to-end runs of the experiments that use landmarks, areas, noise and the eye: `inspect`
//! names the new inputs, `simulate` writes the same trace twice, and evolution runs and
//! reproduces its fitness file byte for byte.

use crate::cli_common::{experiment, run_ok};

#[test]
fn new_experiments_inspect_simulate_and_evolve_reproducibly() {
    let tmp = tempfile::tempdir().unwrap();
    for (name, inputs, names) in [
        (
            "landmark-arena.toml",
            30,
            &["landmark_1_sin", "landmark_2_cos", "area_2", "bias"][..],
        ),
        (
            "eye-arena.toml",
            56,
            &["eye_r_0_0", "eye_b_0_15", "bias"][..],
        ),
    ] {
        let file = experiment(name);
        let out = run_ok(&["inspect", &file]);
        let text = String::from_utf8(out.stdout).unwrap();
        assert!(
            text.contains(&format!("observation: {inputs} inputs")),
            "{text}"
        );
        for n in names {
            assert!(text.contains(n), "{name}: no input {n}:\n{text}");
        }

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
