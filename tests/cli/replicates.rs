//! Replicates: `run --seeds` gives each seed the very files of a single-seed run, continues
//! an interrupted batch, and `summary` writes quartiles across seeds (checked on hand-written
//! fitness files) and the held-out evaluation of every seed's champion.

use berry_evolve::brain::genome::Genome;
use berry_evolve::evo::evaluate::aggregate;
use berry_evolve::evo::trial::{run_trial, NoObserver};
use berry_evolve::evo::TrialPlan;
use berry_evolve::experiment::Experiment;
use berry_evolve::record::genome_file::GenomeFile;
use berry_evolve::seed::{Generation, TrialIndex};
use std::path::{Path, PathBuf};
use std::process::Command;

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_berry-evolve"))
}

fn fixture() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/tiny.toml")
}

fn temp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("replicates-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

fn ok(command: &mut Command) -> String {
    let out = command.output().unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

fn files(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut all = Vec::new();
    for f in ["fitness.csv", "best.json", "experiment.toml"] {
        all.push((f.to_string(), std::fs::read(dir.join(f)).unwrap()));
    }
    let mut checkpoints: Vec<PathBuf> = std::fs::read_dir(dir.join("checkpoints"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    checkpoints.sort();
    for c in checkpoints {
        let name = c.file_name().unwrap().to_string_lossy().to_string();
        all.push((name, std::fs::read(&c).unwrap()));
    }
    all
}

#[test]
fn each_seed_of_a_batch_is_the_single_seed_run() {
    let batch = temp("batch");
    let single = temp("single");
    let out = ok(bin()
        .args([
            "run",
            fixture().to_str().unwrap(),
            "--seeds",
            "2,3",
            "--quiet",
        ])
        .arg("--out")
        .arg(&batch)
        .args(["--jobs", "2"]));
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), 2, "{out}");
    assert!(lines[0].starts_with("seed 2: 8 generations"), "{out}");
    assert!(lines[1].starts_with("seed 3: 8 generations"), "{out}");
    for seed in ["2", "3"] {
        let dir = single.join(seed);
        ok(bin()
            .args([
                "run",
                fixture().to_str().unwrap(),
                "--seed",
                seed,
                "--quiet",
            ])
            .arg("--out")
            .arg(&dir)
            .args(["--jobs", "1"]));
        assert_eq!(
            files(&batch.join(format!("seed-{seed}"))),
            files(&dir),
            "seed {seed}"
        );
    }
    // The same command again continues each seed's run (already finished): same files.
    let before = files(&batch.join("seed-3"));
    let again = ok(bin()
        .args([
            "run",
            fixture().to_str().unwrap(),
            "--seeds",
            "2..3",
            "--quiet",
        ])
        .arg("--out")
        .arg(&batch));
    assert!(
        again.contains("seed 3 (continued): 8 generations"),
        "{again}"
    );
    assert_eq!(files(&batch.join("seed-3")), before);

    // held-out.csv: each seed's best.json on compare's held-out worlds.
    ok(bin()
        .arg("summary")
        .arg(&batch)
        .args(["--random", "4", "--trials", "3"]));
    let held_out = std::fs::read_to_string(batch.join("held-out.csv")).unwrap();
    let rows: Vec<Vec<&str>> = held_out.lines().map(|l| l.split(',').collect()).collect();
    assert_eq!(rows[0], ["who", "seed", "genome", "fitness"]);
    assert_eq!(rows.len(), 1 + 2 + 2, "{held_out}");
    let experiment = Experiment::load(&batch.join("seed-2/experiment.toml"))
        .unwrap()
        .with_overrides()
        .trials(3)
        .build()
        .unwrap();
    for (row, seed) in rows[1..3].iter().zip(["2", "3"]) {
        assert_eq!(row[0], "seed");
        assert_eq!(row[1], seed);
        // As compare evaluates it: trial by trial in the held-out generation's worlds.
        let genome: Genome = GenomeFile::load(Path::new(row[2])).unwrap().genome();
        let outcomes: Vec<_> = (0..3)
            .map(|t| {
                run_trial(
                    &TrialPlan::new(&experiment),
                    &experiment.topology(),
                    std::slice::from_ref(&genome),
                    Generation(1 << 40),
                    0,
                    TrialIndex(t),
                    NoObserver,
                )
                .unwrap()[0]
            })
            .collect();
        let expected = aggregate(&TrialPlan::new(&experiment), &outcomes)
            .fitness
            .unwrap();
        assert_eq!(row[3].parse::<f64>().unwrap(), expected, "seed {seed}");
    }
    assert_eq!(rows[3][0], "random_median");
    assert_eq!(rows[4][0], "random_best");
    let summary = std::fs::read_to_string(batch.join("summary.csv")).unwrap();
    assert_eq!(summary.lines().count(), 1 + 8);
    for d in [batch, single] {
        let _ = std::fs::remove_dir_all(d);
    }
}

const HEADER: &str = "generation,evaluations,best,mean,median,worst,std,best_ever,\
mean_food_a,mean_food_b,mean_food_c,mean_food_d,best_food_a,best_food_b,best_food_c,\
best_food_d,non_finite";

/// A fitness.csv with the given (best, mean) per generation and, when `validation` is given,
/// a validation_best column.
fn write_fitness(dir: &Path, rows: &[(f64, f64)], validation: Option<&[Option<f64>]>) {
    std::fs::create_dir_all(dir).unwrap();
    let mut text = HEADER.to_string();
    if validation.is_some() {
        text.push_str(",validation_best");
    }
    text.push('\n');
    for (g, (best, mean)) in rows.iter().enumerate() {
        text.push_str(&format!(
            "{g},{},{best:?},{mean:?},0.0,0.0,0.0,{best:?},0.0,0.0,0.0,0.0,0.0,0.0,0.0,0.0,0",
            10 * (g + 1)
        ));
        if let Some(v) = validation {
            text.push(',');
            if let Some(x) = v[g] {
                text.push_str(&format!("{x:?}"));
            }
        }
        text.push('\n');
    }
    std::fs::write(dir.join("fitness.csv"), text).unwrap();
}

/// Three seeds, the third one generation short, two of them validated in generation 1:
/// quartiles by linear interpolation worked out by hand.
#[test]
fn summary_csv_by_hand() {
    let folder = temp("summary");
    write_fitness(
        &folder.join("seed-1"),
        &[(1.0, 0.5), (4.0, 2.0)],
        Some(&[None, Some(3.0)]),
    );
    write_fitness(
        &folder.join("seed-2"),
        &[(2.0, 1.0), (8.0, 3.0)],
        Some(&[None, Some(5.0)]),
    );
    write_fitness(&folder.join("seed-10"), &[(6.0, 0.0)], None);
    // Not a seed folder: ignored.
    std::fs::create_dir_all(folder.join("notes")).unwrap();
    ok(bin().arg("summary").arg(&folder).arg("--no-held-out"));
    let text = std::fs::read_to_string(folder.join("summary.csv")).unwrap();
    // Generation 0: best {1, 2, 6}: h = 0.5, 1, 1.5 → 1.5, 2, 4; mean {0.5, 1, 0}:
    // sorted 0, 0.5, 1 → 0.25, 0.5, 0.75; no validation.
    // Generation 1: two seeds, best {4, 8} → 5, 6, 7; mean {2, 3} → 2.25, 2.5, 2.75;
    // validation {3, 5} → 3.5, 4, 4.5.
    assert_eq!(
        text,
        "generation,seeds,best_q1,best_median,best_q3,mean_q1,mean_median,mean_q3,\
validation_best_q1,validation_best_median,validation_best_q3\n\
0,3,1.5,2.0,4.0,0.25,0.5,0.75,,,\n\
1,2,5.0,6.0,7.0,2.25,2.5,2.75,3.5,4.0,4.5\n"
    );
    let _ = std::fs::remove_dir_all(&folder);
}

#[test]
fn summary_of_a_folder_without_seeds_says_what_to_do() {
    let folder = temp("empty");
    std::fs::create_dir_all(&folder).unwrap();
    let out = bin().arg("summary").arg(&folder).output().unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("--seeds"), "{err}");
    let _ = std::fs::remove_dir_all(&folder);
}
