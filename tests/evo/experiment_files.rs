//! Experiment files and genome files: every shipped file loads, round-trips, and hashes stably;
//! genome files round-trip parameters bit for bit.

use berry_evolve::brain::genome::Genome;
use berry_evolve::experiment::Experiment;
use berry_evolve::record::genome_file::{GenomeFile, Origin};
use berry_evolve::seed::{stream, unit, Generation, IndividualId, Purpose, Seed, TrialIndex};
use rand::RngCore;
use std::path::{Path, PathBuf};

fn shipped_experiments() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    for dir in ["experiments", "experiments/bench", "tests/fixtures"] {
        for entry in std::fs::read_dir(root.join(dir)).unwrap() {
            let path = entry.unwrap().path();
            if path.extension().is_some_and(|e| e == "toml") {
                files.push(path);
            }
        }
    }
    files.sort();
    assert!(
        files.len() >= 5,
        "expected the shipped experiments, found {files:?}"
    );
    files
}

#[test]
fn every_shipped_experiment_loads_and_round_trips_through_toml() {
    for path in shipped_experiments() {
        let experiment =
            Experiment::load(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        // experiment.toml in a run folder is this text; resume re-reads it and compares hashes.
        let text = experiment.to_toml();
        let again = Experiment::from_toml(&text, &path)
            .unwrap_or_else(|e| panic!("{} after round trip: {e}\n{text}", path.display()));
        assert_eq!(again, experiment, "{}", path.display());
        assert_eq!(again.config_hash(), experiment.config_hash());
        assert_eq!(again.to_toml(), text, "{}: TOML not stable", path.display());
    }
}

#[test]
fn config_hash_ignores_run_length_and_output_but_not_the_seed() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/tiny.toml");
    let base = Experiment::load(&path).unwrap();
    let mut longer = base.config().clone();
    longer.evolution.generations += 10;
    longer.output.checkpoint_every = 1;
    assert_eq!(base.config_hash(), longer.config_hash());
    let mut reseeded = base.config().clone();
    reseeded.seed += 1;
    assert_ne!(base.config_hash(), reseeded.config_hash());
    let mut retuned = base.config().clone();
    retuned.evolution.mutation.sigma *= 2.0;
    assert_ne!(base.config_hash(), retuned.config_hash());
    assert_eq!(base.config_hash().len(), 64);
}

#[test]
fn genome_file_round_trips_parameters_bit_for_bit() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/tiny.toml");
    let experiment = Experiment::load(&path).unwrap();
    let n = experiment.topology().parameter_count();
    let mut rng = stream(
        Seed(3),
        Purpose::Baseline,
        Generation(0),
        IndividualId(0),
        TrialIndex(0),
    );
    let specials = [
        0.1 + 0.2,
        -0.0,
        5e-324,
        1e-308,
        1e308,
        f64::MAX,
        f64::MIN_POSITIVE,
    ];
    for round in 0..200 {
        let parameters: Vec<f64> = (0..n)
            .map(|i| match (round + i) % 3 {
                0 => specials[(round * 7 + i) % specials.len()],
                1 => (unit(&mut rng) - 0.5) * 10f64.powi((i % 40) as i32 - 20),
                _ => {
                    // Random bit patterns, skipping the non-finite ones a genome cannot hold.
                    let x = f64::from_bits(rng.next_u64());
                    if x.is_finite() {
                        x
                    } else {
                        1.5
                    }
                }
            })
            .collect();
        let genome = Genome {
            parameters,
            step_size: (round % 2 == 0).then_some(0.1 + round as f64),
        };
        let origin = Origin {
            experiment: Some(experiment.name.clone()),
            config_hash: Some(experiment.config_hash()),
            seed: Some(round as u64 * 7),
            generation: Some(round as u64),
            individual: Some(3),
            fitness: Some(unit(&mut rng)),
            metabolism: Some([1.0, 0.5, 0.25, 0.0]),
            description: None,
        };
        let file = GenomeFile::new(&experiment, &genome, origin);
        let back = GenomeFile::from_slice(&file.to_json(), Path::new("mem.json")).unwrap();
        let bits = |g: &Genome| g.parameters.iter().map(|p| p.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&back.genome()), bits(&genome), "round {round}");
        assert_eq!(
            back.step_size.map(f64::to_bits),
            genome.step_size.map(f64::to_bits)
        );
        assert_eq!(back, file);
        back.topology_for(&experiment, Path::new("mem.json"))
            .unwrap();
    }
}

#[test]
fn genome_files_refuse_non_finite_and_wrong_sizes() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/tiny.toml");
    let experiment = Experiment::load(&path).unwrap();
    let n = experiment.topology().parameter_count();
    let file = GenomeFile::new(&experiment, &Genome::new(vec![0.5; n]), Origin::default());
    let text = String::from_utf8(file.to_json()).unwrap();
    let short = text.replacen("0.5,", "", 1);
    let err = GenomeFile::from_slice(short.as_bytes(), Path::new("short.json")).unwrap_err();
    assert!(
        err.to_string().contains("short.json") && err.to_string().contains("parameters"),
        "{err}"
    );
    let tmp = tempfile::tempdir().unwrap();
    let mut bad = file.clone();
    bad.parameters[2] = f64::NAN;
    let err = bad.save(&tmp.path().join("bad.json")).unwrap_err();
    assert!(err.to_string().contains("parameters[2]"), "{err}");
    assert!(!tmp.path().join("bad.json").exists());
    let future = text.replacen("\"format\": 1", "\"format\": 9", 1);
    let err = GenomeFile::from_slice(future.as_bytes(), Path::new("f.json")).unwrap_err();
    assert!(err.to_string().contains("format 9"), "{err}");
}

#[test]
fn every_shipped_genome_fits_its_experiment() {
    // genomes/<experiment>-baseline.json fits experiments/<experiment>.toml; the others are
    // foragers for the main experiment.
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut count = 0;
    for entry in std::fs::read_dir(root.join("genomes")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "json") {
            let name = path.file_name().unwrap().to_str().unwrap();
            let toml = match name.strip_suffix("-baseline.json") {
                Some(experiment) => format!("experiments/{experiment}.toml"),
                None => "experiments/foraging.toml".to_owned(),
            };
            let experiment = Experiment::load(&root.join(&toml)).unwrap_or_else(|e| panic!("{e}"));
            let file = GenomeFile::load(&path).unwrap_or_else(|e| panic!("{e}"));
            // A hand-designed baseline `<name>-baseline.json` belongs to experiments/<name>.toml.
            let name = path.file_name().unwrap().to_string_lossy();
            let own = name.strip_suffix("-baseline.json").map(|n| {
                Experiment::load(&root.join(format!("experiments/{n}.toml")))
                    .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
            });
            file.topology_for(own.as_ref().unwrap_or(&experiment), &path)
                .unwrap_or_else(|e| panic!("{e}"));
            count += 1;
        }
    }
    assert!(
        count >= 2,
        "expected the hand-designed forager and a kept champion"
    );
}

/// The config hash of a frozen experiment file is pinned: a dependency update (serde, toml,
/// the hash's own code or a feature change) that silently changed how a file hashes would
/// change every run folder's identity and make `resume` refuse every old run. The hash covers
/// the whole normalised configuration, defaults included, so adding a key changes it too (it
/// moved from 0.3.5's 78d47ba0... when the [fitness], [behaviour] and [validation] keys came):
/// then update the pin on purpose, in the same commit.
#[test]
fn the_config_hash_of_a_frozen_experiment_is_pinned() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/foraging-v035.toml");
    let experiment = Experiment::load(&path).unwrap();
    assert_eq!(
        experiment.config_hash(),
        "294039f116077617881a38f69c1cc9b7830dac6b1afc8f8e07e27a16c168c0f2",
        "the config hash of {} changed",
        path.display()
    );
}
