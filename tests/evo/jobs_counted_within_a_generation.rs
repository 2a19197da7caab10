//! Progress within a generation: a watched request (`Evaluate::watched`) on a generation's
//! training worlds is told of every evaluation job once (as many as `evaluation_jobs` says,
//! on 1 and 2 threads, lockstep and one trial per job), and its results are the same bits as
//! the unwatched request's. The calibration's
//! brains (`first_genomes`) are the first individuals of generation 0 exactly.

use berry_evolve::evo::door::{Evaluate, Worlds};
use berry_evolve::evo::evaluate::evaluation_jobs;
use berry_evolve::evo::search::factory::{first_generation, first_genomes};
use berry_evolve::experiment::Experiment;
use berry_evolve::seed::Generation;
use std::path::Path;
use std::sync::atomic::{AtomicU64, Ordering};

fn fixture(name: &str, replace: (&str, &str)) -> Experiment {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures")
        .join(name);
    let text = std::fs::read_to_string(&path)
        .unwrap()
        .replace(replace.0, replace.1);
    Experiment::from_toml(&text, &path).unwrap_or_else(|e| panic!("{name}: {e}"))
}

#[test]
fn every_job_is_counted_once_and_counting_changes_no_bit() {
    let mlp = fixture("tiny.toml", ("", ""));
    let recurrent = fixture("tiny.toml", ("kind = \"mlp\"", "kind = \"recurrent\""));
    let no_crn = fixture(
        "tiny.toml",
        ("ticks = 120", "ticks = 120\ncommon_random_numbers = false"),
    );
    for (name, e) in [("mlp", mlp), ("recurrent", recurrent), ("no crn", no_crn)] {
        let topology = e.topology();
        let population = first_generation(&e, &topology).genomes;
        let request = Evaluate::new(&e, &topology, &population, Worlds::Training(Generation(0)));
        let plain = request.run().unwrap();
        let jobs = evaluation_jobs(&e, &topology, population.len());
        // 12 individuals × 2 trials: one lockstep job per individual, or one per trial.
        let expected = if name == "recurrent" { 24 } else { 12 };
        assert_eq!(jobs, expected, "{name}");
        for threads in [1, 2] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let done = AtomicU64::new(0);
            let count = || {
                done.fetch_add(1, Ordering::Relaxed);
            };
            let watched = pool
                .install(|| request.watched(Some(&count)).run())
                .unwrap();
            assert_eq!(
                done.load(Ordering::Relaxed),
                jobs,
                "{name}, {threads} threads"
            );
            assert_eq!(
                format!("{watched:?}"),
                format!("{plain:?}"),
                "{name}, {threads} threads: counting changed a result"
            );
        }
    }
}

#[test]
fn the_calibration_lives_with_generation_zero_s_first_individuals() {
    for name in ["tiny.toml", "tiny-pgpe.toml"] {
        let e = fixture(name, ("", ""));
        let topology = e.topology();
        let all = first_generation(&e, &topology).genomes;
        for n in [1, 2, 5, all.len()] {
            assert_eq!(first_genomes(&e, &topology, n), all[..n], "{name}, n = {n}");
        }
        assert_eq!(first_genomes(&e, &topology, all.len() + 10), all, "{name}");
    }
}
