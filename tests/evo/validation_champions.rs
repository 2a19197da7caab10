//! Champions chosen on validation worlds: the validation step picks by validation score, not
//! by training luck; a run's best.json is the validation champion; validation worlds are
//! their own set; results do not depend on threads or on stopping and resuming.

use berry_evolve::brain::genome::Genome;
use berry_evolve::evo::door::{Evaluate, Worlds};
use berry_evolve::evo::evaluate::Evaluation;
use berry_evolve::evo::life::trial_stream;
use berry_evolve::evo::search::ga::first_population;
use berry_evolve::evo::state::{EvaluatedGeneration, Individual};
use berry_evolve::evo::validation::{is_due, top_candidates, top_individuals, validate};
use berry_evolve::evo::worlds::{validation_worlds, WorldSet};
use berry_evolve::evo::TrialPlan;
use berry_evolve::experiment::Experiment;
use berry_evolve::record::genome_file::GenomeFile;
use berry_evolve::run::{self, CheckpointPayload, RunOptions, Silent};
use berry_evolve::seed::{Generation, TrialIndex};
use berry_evolve::sim::world::World;
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;

fn tiny(validation: &str) -> Experiment {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let path = root.join("tests/fixtures/tiny.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    Experiment::from_toml(&format!("{text}\n{validation}"), &path).unwrap_or_else(|e| panic!("{e}"))
}

const VALIDATION: &str = "[validation]\nevery = 2\ntop = 4\ntrials = 6\n";

fn fake(genome: &Genome, fitness: f64) -> Individual {
    Individual {
        genome: genome.clone(),
        evaluation: Evaluation {
            fitness: Some(fitness),
            metabolism: [0.0; 4],
            measures: Vec::new(),
            area_ticks: Vec::new(),
        },
        lineage: None,
    }
}

/// The luckiest in training (a brain that does nothing, given a training fitness of 100) is
/// not the validation best: a random genome that eats on the validation worlds is.
#[test]
fn validation_chooses_by_validation_score_not_training_luck() {
    let e = tiny(VALIDATION);
    let topology = e.topology();
    let worlds = WorldSet::Validation.build(&e).unwrap();
    // The random genome of generation 0 that eats most on the validation worlds.
    let population = first_population(&e, &topology);
    let scores = Evaluate::new(&e, &topology, &population, Worlds::Built(&worlds))
        .run()
        .unwrap();
    let (forager, best_score) = scores
        .iter()
        .enumerate()
        .map(|(i, s)| (i, s.fitness.unwrap()))
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap();
    assert!(best_score > 0.0, "{scores:?}");
    let idle = Genome::new(vec![0.0; topology.parameter_count()]);
    let generation = EvaluatedGeneration {
        generation: 7,
        individuals: vec![
            fake(&population[(forager + 1) % population.len()], 3.0),
            fake(&idle, 100.0),
            fake(&population[forager], 1.0),
        ],
    };
    assert_eq!(top_individuals(&generation, 4), vec![1, 0, 2]);
    let candidates = top_candidates(&e, &generation);
    assert_eq!(candidates.len(), 3);
    let chosen = validate(&e, &topology, &candidates, &worlds)
        .unwrap()
        .unwrap();
    assert_eq!(chosen.genome, population[forager]);
    assert_eq!(chosen.individual, Some(2));
    assert_eq!(chosen.training_fitness, Some(1.0));
    assert_eq!(chosen.generation, 7);
    assert_eq!(chosen.validation.fitness, Some(best_score));
    // Only the top 2 offered: the forager is not among them, the better of the other two wins.
    let two = &candidates[..2];
    let chosen = validate(&e, &topology, two, &worlds).unwrap().unwrap();
    assert_ne!(chosen.genome, population[forager]);
}

#[test]
fn validation_is_due_every_n_generations_and_after_the_last() {
    let e = tiny("[validation]\nevery = 3\n");
    let due: Vec<u64> = (0..8).filter(|&g| is_due(&e.validation, g, 8)).collect();
    assert_eq!(due, vec![2, 5, 7]);
    let off = tiny("");
    assert!((0..8).all(|g| !is_due(&off.validation, g, 8)));
}

/// The validation worlds are the same at every call, and differ from every training world
/// and from compare's held-out worlds (the creature's start differs).
#[test]
fn validation_worlds_are_fixed_and_their_own_set() {
    let e = tiny(VALIDATION);
    let start = |w: &World| w.creatures()[0].pose.position;
    let a = validation_worlds(&e).unwrap();
    let b = validation_worlds(&e).unwrap();
    assert_eq!(a.len(), 6);
    assert_eq!(
        a.iter().map(start).collect::<Vec<_>>(),
        b.iter().map(start).collect::<Vec<_>>()
    );
    let held_out = 1u64 << 40;
    for v in &a {
        for g in (0..50).chain([held_out]) {
            for t in 0..6 {
                let rng = trial_stream(&TrialPlan::new(&e), Generation(g), 0, TrialIndex(t));
                let w = World::new(&e.world, &e.creature, 1, rng).unwrap();
                assert_ne!(start(v), start(&w), "generation {g} trial {t}");
            }
        }
    }
}

fn run_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("validation-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

fn options(jobs: usize) -> RunOptions<'static> {
    RunOptions {
        jobs,
        stop: None,
        evaluator: None,
    }
}

fn last_payload(dir: &Path) -> CheckpointPayload {
    run::load_checkpoint(dir).unwrap().2
}

/// A run with validation: best.json is the validation champion (its origin says so), and the
/// fitness CSV's validation_best column has a value exactly at the validated generations, the
/// champion's being the largest.
#[test]
fn a_run_keeps_the_validation_champion_as_best_json() {
    let e = tiny(VALIDATION);
    let dir = run_dir("champion");
    run::start(e.clone(), &dir, false, options(2), &mut Silent).unwrap();
    let payload = last_payload(&dir);
    let champion = payload.validated_best.clone().unwrap();
    let best = GenomeFile::load(&dir.join("best.json")).unwrap();
    assert_eq!(best.genome(), champion.genome);
    let description = best.origin.description.clone().unwrap();
    assert!(
        description.contains("chosen on validation"),
        "{description}"
    );
    assert_eq!(best.origin.generation, Some(champion.generation));
    assert_eq!(best.origin.individual, champion.individual);
    assert_eq!(best.origin.fitness, champion.training_fitness);
    let table = berry_evolve::record::fitness_csv::read_table(&dir.join("fitness.csv")).unwrap();
    assert_eq!(table.extra, ["validation_best"]);
    let column = table.column("validation_best");
    let validated: Vec<usize> = (0..column.len()).filter(|&g| column[g].is_some()).collect();
    // Generations 1, 3, 5 and 7 of 8.
    assert_eq!(validated, vec![1, 3, 5, 7]);
    let top = column.iter().flatten().fold(f64::MIN, |a, &b| a.max(b));
    assert_eq!(champion.validation.fitness, Some(top));
    // The first generation reaching the top is the champion's (ties keep the older one).
    let first = column.iter().position(|v| *v == Some(top)).unwrap();
    assert_eq!(champion.generation, first as u64);
    // Re-evaluating best.json on the validation worlds gives its validation fitness.
    let genome = [best.genome()];
    let topology = e.topology();
    let again = Evaluate::new(&e, &topology, &genome, Worlds::Alone(WorldSet::Validation))
        .run()
        .unwrap();
    assert_eq!(again[0].fitness, champion.validation.fitness);
    let _ = std::fs::remove_dir_all(&dir);
}

/// One and two threads give the same files; a run stopped after its first generation and
/// resumed gives the same files as one never stopped.
#[test]
fn validation_keeps_the_thread_count_and_resume_guarantees() {
    let e = tiny(VALIDATION);
    let one = run_dir("one");
    let two = run_dir("two");
    let resumed = run_dir("resumed");
    run::start(e.clone(), &one, false, options(1), &mut Silent).unwrap();
    run::start(e.clone(), &two, false, options(2), &mut Silent).unwrap();
    let stop = AtomicBool::new(true);
    let stopped = run::start(
        e.clone(),
        &resumed,
        false,
        RunOptions {
            jobs: 2,
            stop: Some(&stop),
            evaluator: None,
        },
        &mut Silent,
    );
    assert!(stopped.is_err(), "the run stops after its first generation");
    // Stopped after generation 0, before any validation.
    run::resume(&resumed, None, false, options(1), &mut Silent).unwrap();
    // Resumed from generation 3's checkpoint, after two validations: the validation champion
    // and the validation worlds come back.
    let from_three = run_dir("from-three");
    copy_dir(&one, &from_three);
    let checkpoint = std::fs::read_dir(from_three.join("checkpoints"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .find(|p| p.to_string_lossy().contains("000003"))
        .expect("generation 3's checkpoint is kept");
    std::fs::remove_file(from_three.join("best.json")).unwrap();
    // Resuming an older checkpoint moves the newer ones aside, and says so (--discard-newer).
    run::resume_with(
        &checkpoint,
        run::ResumeRequest {
            generations: None,
            allow_config_change: false,
            discard_newer: true,
            shorten: false,
        },
        options(2),
        &mut Silent,
    )
    .unwrap();
    for f in ["fitness.csv", "best.json"] {
        let a = std::fs::read(one.join(f)).unwrap();
        assert_eq!(
            a,
            std::fs::read(two.join(f)).unwrap(),
            "{f}: 1 vs 2 threads"
        );
        assert_eq!(a, std::fs::read(resumed.join(f)).unwrap(), "{f}: resumed");
        assert_eq!(a, std::fs::read(from_three.join(f)).unwrap(), "{f}: from 3");
    }
    for d in [one, two, resumed, from_three] {
        let _ = std::fs::remove_dir_all(&d);
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
