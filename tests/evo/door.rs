//! The one evaluation door (`evo::door::Evaluate`): a set's worlds met alone give, genome by
//! genome and trial by trial, the lives `trial::run_trial` lives for group 0 (what `compare`
//! always reported); worlds built beforehand number genome i individual i (validation's
//! numbering); lives of several episodes come with their choices and the same outcomes; the
//! refusals name what is wrong. Also the reference paths other tests set the door against:
//! one trial at a time (`run_trial`), group by group (`evaluate_group`).

use berry_evolve::brain::genome::Genome;
use berry_evolve::brain::spec::Topology;
use berry_evolve::evo::door::{Evaluate, Worlds};
use berry_evolve::evo::evaluate::{aggregate, Evaluation};
use berry_evolve::evo::life::{EvaluationError, TrialOutcome};
use berry_evolve::evo::trial::{self, NoObserver};
use berry_evolve::evo::worlds::{random_genomes, WorldSet, HELD_OUT_GENERATION};
use berry_evolve::evo::TrialPlan;
use berry_evolve::experiment::Experiment;
use berry_evolve::seed::{Generation, TrialIndex};
use std::path::Path;

/// Trial `trial` of generation `generation` for group `group`, one world at a time, watched
/// by nobody: the reference every faster path is set against.
pub fn run_trial(
    experiment: &Experiment,
    topology: &Topology,
    genomes: &[Genome],
    generation: Generation,
    group: u64,
    trial: TrialIndex,
) -> Result<Vec<TrialOutcome>, EvaluationError> {
    trial::run_trial(
        &TrialPlan::new(experiment),
        topology,
        genomes,
        generation,
        group,
        trial,
        NoObserver,
    )
}

/// Group `group` (individuals `group*k .. group*k + k`) evaluated serially, trial by trial
/// with [`run_trial`].
pub fn evaluate_group(
    experiment: &Experiment,
    topology: &Topology,
    genomes: &[Genome],
    generation: Generation,
    group: u64,
) -> Result<Vec<Evaluation>, EvaluationError> {
    let mut per_individual: Vec<Vec<TrialOutcome>> = vec![Vec::new(); genomes.len()];
    for t in 0..experiment.evaluation.trials {
        let outcomes = run_trial(
            experiment,
            topology,
            genomes,
            generation,
            group,
            TrialIndex(t),
        )?;
        for (list, outcome) in per_individual.iter_mut().zip(outcomes) {
            list.push(outcome);
        }
    }
    let plan = TrialPlan::new(experiment);
    Ok(per_individual
        .iter()
        .map(|trials| aggregate(&plan, trials))
        .collect())
}

/// The whole population as generation `generation`, through the door.
pub fn evaluate_population(
    experiment: &Experiment,
    topology: &Topology,
    population: &[Genome],
    generation: Generation,
) -> Result<Vec<Evaluation>, EvaluationError> {
    Evaluate::new(
        experiment,
        topology,
        population,
        Worlds::Training(generation),
    )
    .run()
}

fn load(name: &str) -> Experiment {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("experiments")
        .join(name);
    Experiment::load(&path).unwrap()
}

/// `experiment` with `trials` trials (and validation worlds) of `ticks` ticks.
fn short(experiment: &Experiment, trials: u64, ticks: u64) -> Experiment {
    experiment
        .with_overrides()
        .edit(|c| {
            c.evaluation.trials = trials;
            c.evaluation.ticks = ticks;
            c.validation.trials = trials;
        })
        .build()
        .unwrap()
}

fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
}

/// Each genome alone in a set's worlds lives, trial by trial, what `run_trial` lives for it
/// as group 0 of the set's generation (held-out, design, a training generation), on 1 and 2
/// threads; and its evaluation is the aggregate of those lives.
#[test]
fn a_set_met_alone_is_group_zero_of_its_generation_trial_by_trial() {
    for name in ["foraging.toml", "t-maze.toml"] {
        let e = short(&load(name), 3, 120);
        let topology = e.topology();
        let genomes = random_genomes(&e, Generation(HELD_OUT_GENERATION), 3);
        for set in [WorldSet::HeldOut, WorldSet::Design, WorldSet::Training(4)] {
            let request = Evaluate::new(&e, &topology, &genomes, Worlds::Alone(set));
            let lives = pool(1).install(|| request.lives()).unwrap();
            assert_eq!(pool(2).install(|| request.lives()).unwrap(), lives);
            for (genome, lived) in genomes.iter().zip(&lives) {
                assert_eq!(lived.len(), 3);
                for (t, life) in lived.iter().enumerate() {
                    let g = std::slice::from_ref(genome);
                    let alone =
                        run_trial(&e, &topology, g, set.generation(), 0, TrialIndex(t as u64));
                    assert_eq!(*life, alone.unwrap()[0], "{name}: {set:?}, trial {t}");
                }
            }
            let evaluations = request.run().unwrap();
            for (evaluation, lived) in evaluations.iter().zip(&lives) {
                assert_eq!(
                    *evaluation,
                    aggregate(&TrialPlan::new(&e), lived),
                    "{name}: {set:?}"
                );
            }
        }
    }
}

/// The validation worlds built once and met through `Worlds::Built` are those
/// `Worlds::Alone(validation)` builds: one genome gives the same lives either way.
#[test]
fn built_validation_worlds_are_the_validation_set() {
    let e = short(&load("foraging.toml"), 2, 100);
    let topology = e.topology();
    let genomes = random_genomes(&e, Generation(0), 1);
    let built = WorldSet::Validation.build(&e).unwrap();
    assert_eq!(built.worlds.len(), 2);
    let by_set = Evaluate::new(&e, &topology, &genomes, Worlds::Alone(WorldSet::Validation));
    let by_built = Evaluate::new(&e, &topology, &genomes, Worlds::Built(&built));
    assert_eq!(by_set.lives().unwrap(), by_built.lives().unwrap());
}

/// A generation's training worlds through the door: the run's evaluation (groups, common
/// random numbers), on 1 and 2 threads, equal to group by group; `lives` aggregates to `run`.
#[test]
fn training_worlds_are_the_runs_generation() {
    let e = short(&load("foraging.toml"), 2, 80);
    let topology = e.topology();
    let genomes = random_genomes(&e, Generation(0), 4);
    let request = Evaluate::new(&e, &topology, &genomes, Worlds::Training(Generation(2)));
    let one = pool(1).install(|| request.run()).unwrap();
    assert_eq!(pool(2).install(|| request.run()).unwrap(), one);
    let k = e.evaluation.group_size as usize;
    let mut serial = Vec::new();
    for (g, group) in genomes.chunks(k).enumerate() {
        serial.extend(evaluate_group(&e, &topology, group, Generation(2), g as u64).unwrap());
    }
    assert_eq!(one, serial);
    let lives = request.lives().unwrap();
    let plan = TrialPlan::new(&e);
    let aggregated: Vec<Evaluation> = lives.iter().map(|l| aggregate(&plan, l)).collect();
    assert_eq!(aggregated, one);
}

/// Lives of several episodes: `lives_by_episode` gives the outcomes `lives` gives, each with
/// its life's schedule (one `exchanged` flag and one first choice per episode).
#[test]
fn lives_by_episode_are_the_lives_with_their_choices() {
    let e = short(&load("t-maze-switch.toml"), 2, 60);
    let topology = e.topology();
    let genomes = random_genomes(&e, Generation(0), 2);
    let episodes = e.evaluation.episodes_per_life as usize;
    assert!(episodes > 1);
    for worlds in [
        Worlds::Alone(WorldSet::HeldOut),
        Worlds::Training(Generation(1)),
    ] {
        let request = Evaluate::new(&e, &topology, &genomes, worlds);
        let plain = request.lives().unwrap();
        let by_episode = request.lives_by_episode().unwrap();
        assert_eq!(by_episode.len(), genomes.len());
        for (lived, with) in plain.iter().zip(&by_episode) {
            let outcomes: Vec<TrialOutcome> = with.iter().map(|(o, _)| *o).collect();
            assert_eq!(*lived, outcomes, "{worlds:?}");
            for (_, choices) in with {
                assert_eq!(choices.exchanged.len(), episodes);
                assert_eq!(choices.correct_first_choice.len(), episodes);
            }
        }
    }
}

/// The refusals: validation worlds of an experiment without `[validation]`, training worlds
/// for genomes that do not fill their groups; each says what to do.
#[test]
fn the_door_refuses_what_cannot_be_evaluated_as_asked() {
    let e = load("foraging.toml");
    let topology = e.topology();
    let none = e
        .with_overrides()
        .edit(|c| c.validation.every = 0)
        .build()
        .unwrap();
    let genomes = random_genomes(&e, Generation(0), 1);
    let request = Evaluate::new(
        &none,
        &topology,
        &genomes,
        Worlds::Alone(WorldSet::Validation),
    );
    let error = request.check().unwrap_err().to_string();
    assert!(
        error.contains("[validation]") && error.contains("held-out"),
        "{error}"
    );
    let grouped = e
        .with_overrides()
        .edit(|c| c.evaluation.group_size = 2)
        .build()
        .unwrap();
    let worlds = Worlds::of(WorldSet::Training(0));
    let error = Evaluate::new(&grouped, &topology, &genomes, worlds)
        .check()
        .unwrap_err()
        .to_string();
    assert!(
        error.contains("group_size") && error.contains("multiple of 2"),
        "{error}"
    );
    let fine = Evaluate::new(&e, &topology, &genomes, Worlds::of(WorldSet::HeldOut));
    fine.check().unwrap();
}
