//! `evo::episode` (the stepping API under Python's Gymnasium environments): an episode driven
//! tick by tick by a genome's brain lives, to the bit, the life evaluation scores in the same
//! world (`evo::trial::run_trial` for one creature, group 0), in every shipped experiment with
//! one creature per world; its rewards add up to that trial's score; a non-finite command ends
//! it as evaluation does.

use berry_evolve::brain::genome::Genome;
use berry_evolve::brain::{Brain, BrainController};
use berry_evolve::evo::episode::Episode;
use berry_evolve::evo::search::ga::first_population;
use berry_evolve::evo::trial::{run_trial, NoObserver};
use berry_evolve::evo::TrialPlan;
use berry_evolve::experiment::Experiment;
use berry_evolve::seed::{Generation, TrialIndex};
use berry_evolve::sim::controller::{Controller, MotorCommand};
use std::path::Path;

fn experiments() -> Vec<std::path::PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("experiments");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    files
}

#[test]
fn an_episode_stepped_by_a_brain_is_the_scored_trial() {
    for path in experiments() {
        let name = path.display().to_string();
        let experiment = Experiment::load(&path).unwrap();
        // Step-by-step episodes live one episode per life (lives of several are refused, see
        // `Episode::new`).
        if experiment.evaluation.group_size != 1 || experiment.evaluation.episodes_per_life > 1 {
            continue;
        }
        let experiment = experiment
            .with_overrides()
            .ticks(experiment.evaluation.ticks.min(300))
            .build()
            .unwrap();
        let topology = experiment.topology();
        let genome: Genome = first_population(&experiment, &topology).swap_remove(1);
        for (generation, trial) in [(Generation(2), 0), (Generation(1 << 40), 3)] {
            let scored = run_trial(
                &TrialPlan::new(&experiment),
                &topology,
                std::slice::from_ref(&genome),
                generation,
                0,
                TrialIndex(trial),
                NoObserver,
            )
            .unwrap()[0];
            let mut brain = BrainController::new(
                Brain::new(&topology, &genome.parameters).unwrap(),
                experiment.creature.max_rpt,
                experiment.creature.eats_by_action(),
            );
            let mut episode =
                Episode::new(&TrialPlan::new(&experiment), generation, TrialIndex(trial)).unwrap();
            let mut total = 0.0;
            let mut ticks = 0;
            while !episode.is_over() {
                let command = brain.act(episode.observation());
                let step = episode.step(command);
                total += step.reward;
                ticks += 1;
                assert_eq!(
                    episode.is_over(),
                    step.terminated || step.truncated,
                    "{name}: tick {ticks}"
                );
            }
            let lived = episode.outcome();
            assert_eq!(lived.score.to_bits(), scored.score.to_bits(), "{name}");
            assert_eq!(
                lived.metabolism.map(f64::to_bits),
                scored.metabolism.map(f64::to_bits),
                "{name}"
            );
            assert_eq!(
                lived.measures.map(f64::to_bits),
                scored.measures.map(f64::to_bits),
                "{name}"
            );
            assert_eq!(lived.shocked_ticks, scored.shocked_ticks, "{name}");
            assert!(
                (total - scored.score).abs() <= 1e-9 * scored.score.abs().max(1.0),
                "{name}: rewards add up to {total}, the trial's score is {}",
                scored.score
            );
            assert!(ticks <= experiment.evaluation.ticks, "{name}");
        }
    }
}

#[test]
fn a_non_finite_command_ends_the_episode() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("experiments/foraging.toml");
    let experiment = Experiment::load(&path).unwrap();
    let mut episode =
        Episode::new(&TrialPlan::new(&experiment), Generation(0), TrialIndex(0)).unwrap();
    let step = episode.step(MotorCommand {
        left: f64::NAN,
        right: 0.0,
        eat: 0.0,
    });
    assert!(step.terminated && !step.truncated, "{step:?}");
    assert!(episode.is_over() && episode.outcome().non_finite);
    let after = episode.step(MotorCommand::default());
    assert_eq!(after.reward, 0.0);
    assert!(after.terminated);
}
