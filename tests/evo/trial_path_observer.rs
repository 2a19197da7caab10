//! One trial path: for every shipped experiment, a trial replayed through
//! `evo::trial::run_trial` with an observer gives the fitness evaluation gave
//! (`evaluate_population`, on the lockstep path for these MLPs, and `evaluate_group`, on the
//! trial path), and what the observer saw is that very life: its last tick's metabolic vector,
//! its shocked ticks and its length are the outcome's.

use crate::door::{evaluate_group, evaluate_population};
use berry_evolve::brain::genome::Genome;
use berry_evolve::evo::evaluate::aggregate;
use berry_evolve::evo::life::TrialOutcome;
use berry_evolve::evo::search::ga::first_population;
use berry_evolve::evo::trial::{run_trial, TickObserver, TrialId};
use berry_evolve::evo::TrialPlan;
use berry_evolve::experiment::Experiment;
use berry_evolve::seed::{Generation, TrialIndex};
use berry_evolve::sim::world::World;
use std::path::{Path, PathBuf};

/// What a life looked like tick by tick, per creature.
#[derive(Default)]
struct Seen {
    started: Option<TrialId>,
    ticks: Vec<u64>,
    metabolism: Vec<Vec<[f64; 4]>>,
    shocked_alive: Vec<u64>,
    finished: Option<Vec<TrialOutcome>>,
}

impl TickObserver for Seen {
    fn start(&mut self, trial: TrialId, world: &World) {
        self.started = Some(trial);
        self.metabolism = vec![Vec::new(); world.creatures().len()];
        self.shocked_alive = vec![0; world.creatures().len()];
    }

    fn tick(&mut self, world: &World, tick: u64) {
        assert_eq!(tick, world.tick());
        self.ticks.push(tick);
        for (i, c) in world.creatures().iter().enumerate() {
            self.metabolism[i].push(c.metabolism);
            self.shocked_alive[i] += u64::from(c.alive && c.shocked);
        }
    }

    fn finish(&mut self, _world: &World, outcomes: &[TrialOutcome]) {
        self.finished = Some(outcomes.to_vec());
    }
}

pub fn shipped_experiments() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("experiments");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    assert!(files.len() >= 5, "experiments/*.toml: {files:?}");
    files
}

/// The experiment at `path`, small enough for a test: at most 8 individuals (whole groups)
/// and 3 trials.
fn small(path: &Path) -> Experiment {
    let mut e = Experiment::load(path).unwrap().into_config();
    let k = e.evaluation.group_size;
    e.evolution.population = ((8 / k).max(1) * k) as usize;
    e.evolution.elitism = e.evolution.elitism.min(1);
    e.evaluation.trials = e.evaluation.trials.min(3);
    Experiment::try_from(e).unwrap_or_else(|err| panic!("{}: {err}", path.display()))
}

#[test]
fn a_replayed_trial_is_the_scored_trial_in_every_shipped_experiment() {
    for path in shipped_experiments() {
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        let experiment = small(&path);
        // A life of several episodes shows each episode to the observer as a trial of its own
        // (tests/evo/episodes_and_switches.rs); the checks below are for one-episode lives.
        if experiment.evaluation.episodes_per_life > 1 {
            continue;
        }
        let topology = experiment.topology();
        let population: Vec<Genome> = first_population(&experiment, &topology);
        let generation = Generation(3);
        let evaluations =
            evaluate_population(&experiment, &topology, &population, generation).unwrap();
        let k = experiment.evaluation.group_size as usize;
        for g in 0..population.len() / k {
            let genomes = &population[g * k..(g + 1) * k];
            let group =
                evaluate_group(&experiment, &topology, genomes, generation, g as u64).unwrap();
            // Each group lives worlds of its own without common random numbers.
            let mut per_individual: Vec<Vec<TrialOutcome>> = vec![Vec::new(); k];
            for t in 0..experiment.evaluation.trials {
                let mut seen = Seen::default();
                let outcomes = run_trial(
                    &TrialPlan::new(&experiment),
                    &topology,
                    genomes,
                    generation,
                    g as u64,
                    TrialIndex(t),
                    &mut seen,
                )
                .unwrap();
                assert_eq!(
                    seen.started,
                    Some(TrialId {
                        generation,
                        group: g as u64,
                        trial: TrialIndex(t)
                    }),
                    "{name}"
                );
                assert_eq!(seen.finished.as_deref(), Some(&outcomes[..]), "{name}");
                assert!(!seen.ticks.is_empty(), "{name}: no tick seen");
                assert!(seen.ticks.len() as u64 <= experiment.evaluation.ticks);
                assert!(seen.ticks.iter().copied().eq(1..=seen.ticks.len() as u64));
                for (i, o) in outcomes.iter().enumerate() {
                    let last = seen.metabolism[i].last().unwrap();
                    assert_eq!(
                        last.map(f64::to_bits),
                        o.metabolism.map(f64::to_bits),
                        "{name}: group {g} trial {t} creature {i}: the trace's last metabolism"
                    );
                    assert_eq!(
                        seen.shocked_alive[i], o.shocked_ticks,
                        "{name}: group {g} trial {t} creature {i}: shocked ticks"
                    );
                    per_individual[i].push(*o);
                }
            }
            for (i, trials) in per_individual.iter().enumerate() {
                let replayed = aggregate(&TrialPlan::new(&experiment), trials);
                let id = g * k + i;
                let bits = |e: &berry_evolve::evo::evaluate::Evaluation| {
                    (e.fitness.map(f64::to_bits), e.metabolism.map(f64::to_bits))
                };
                assert_eq!(
                    bits(&replayed),
                    bits(&evaluations[id]),
                    "{name}: individual {id}: replay vs evaluate_population"
                );
                assert_eq!(
                    bits(&replayed),
                    bits(&group[i]),
                    "{name}: individual {id}: replay vs evaluate_group"
                );
            }
        }
    }
}
