//! The whole-world trace: the events the world told (door opened and closed, eat with the
//! object and amount, teleport, shock from an aversive object, attack, death) as rows, on a
//! hand-made world where each is staged; the two cases the old re-derivation from two world
//! states got wrong (the teleporter of a jump through the t-maze's right arm, whose exit both
//! arms share; a bite's amount, which it took as a difference of running sums); and, for every
//! shipped experiment, the trace written to CSV and JSON lines is the scored life.

use crate::sim_common::{put, rng, Still};
use berry_evolve::evo::search::ga::first_population;
use berry_evolve::evo::trace::{EventKind, TraceRecorder};
use berry_evolve::evo::trial::{run_trial, TickObserver, TrialId};
use berry_evolve::evo::TrialPlan;
use berry_evolve::experiment::Experiment;
use berry_evolve::record::trace::files::{csv_paths, write_csv_files, write_jsonl};
use berry_evolve::seed::{Generation, TrialIndex};
use berry_evolve::sim::World;
use std::path::Path;

const STAGE: &str = r#"
name = "stage"
seed = 3

[world]
arena = [200.0, 200.0]
[[world.doors]]
from = [100.0, 0.0]
to = [100.0, 50.0]
trigger = [20.0, 180.0]
trigger_radius = 5.0
open_ticks = 3
[[world.teleporters]]
entry = [150.0, 150.0]
radius = 4.0
exit = [50.0, 60.0]
[world.kinds.food]
class = "food"
radius = 2.0
substance = [4.0, 0.0, 0.0, 0.0]
bite = [0.5, 0.0, 0.0, 0.0]
depletes = true
[world.kinds.nettle]
class = "aversive"
radius = 3.0
[[world.objects]]
kind = "food"
position = [30.0, 100.0]
[[world.objects]]
kind = "nettle"
position = [170.0, 30.0]
[[world.predators]]
strategy = "patrol"
waypoints = [[190.0, 190.0], [180.0, 190.0]]
effect = "lethal"
max_rpt = 0.01
start = [190.0, 190.0]
[world.start]
region = [60.0, 100.0, 80.0, 120.0]
"#;

#[test]
fn staged_events_are_told_by_the_world() {
    let experiment = Experiment::from_toml(STAGE, Path::new("stage.toml")).unwrap();
    let mut world = World::new(&experiment.world, &experiment.creature, 1, rng(3)).unwrap();
    let mut recorder = TraceRecorder::new(&experiment);
    let id = TrialId {
        generation: Generation(0),
        group: 0,
        trial: TrialIndex(0),
    };
    world.set_event_log(recorder.listens());
    recorder.start(id, &world);
    let mut controllers = [Still];
    let mut step = |world: &mut World, recorder: &mut TraceRecorder| {
        world.step(&mut controllers);
        recorder.tick(world, world.tick());
    };
    // Tick 1: on the trigger; 2: on the food; 3, 4: away; 5: the door closes (open through
    // tick 1 + 3); 6: onto the teleporter; 7: onto the nettle; 8: onto the predator.
    put(&mut world, 0, 20.0, 180.0, 0.0);
    step(&mut world, &mut recorder);
    put(&mut world, 0, 30.0, 104.0, 0.0);
    step(&mut world, &mut recorder);
    put(&mut world, 0, 60.0, 140.0, 0.0);
    for _ in 0..3 {
        step(&mut world, &mut recorder);
    }
    put(&mut world, 0, 150.0, 153.0, 0.0);
    step(&mut world, &mut recorder);
    put(&mut world, 0, 170.0, 34.0, 0.0);
    step(&mut world, &mut recorder);
    let p = world.actors()[0].pose.position;
    put(&mut world, 0, p.x - 4.0, p.y, 0.0);
    step(&mut world, &mut recorder);

    let trace = &recorder.trials[0];
    let events: Vec<(u64, EventKind, Option<&str>, Option<usize>)> = trace
        .events
        .iter()
        .map(|e| (e.tick, e.event, e.target_kind.as_deref(), e.target))
        .collect();
    assert_eq!(
        events,
        vec![
            (1, EventKind::DoorOpen, Some("door"), Some(0)),
            (2, EventKind::Eat, Some("food"), Some(0)),
            (5, EventKind::DoorClose, Some("door"), Some(0)),
            (6, EventKind::Teleport, Some("teleporter"), Some(0)),
            (7, EventKind::Shock, Some("aversive"), Some(0)),
            (8, EventKind::Attack, Some("predator"), Some(0)),
            (8, EventKind::Death, None, None),
        ],
        "{:#?}",
        trace.events
    );
    let eat = &trace.events[1];
    assert_eq!(eat.amount, Some([0.5, 0.0, 0.0, 0.0]));
    assert_eq!(eat.creature, Some(0));
    assert_eq!(trace.events[0].creature, Some(0), "who opened the door");
    let teleport = &trace.events[3];
    assert_eq!((teleport.x, teleport.y), (50.0, 60.0));
    assert_eq!(teleport.from, Some([150.0, 150.0]));
    // The food's amount is recorded where it changed: once, at tick 2.
    let changes: Vec<(u64, usize, f64)> = trace
        .objects
        .iter()
        .map(|o| (o.tick, o.object, o.amount[0]))
        .collect();
    assert_eq!(changes, vec![(2, 0, 3.5)]);
    // The description: one door with its trigger, one teleporter, 4 boundary walls, food
    // and nettle, the patrolling predator with its waypoints.
    let w = &trace.world;
    assert_eq!(w.walls.len(), 4);
    assert_eq!(w.doors.len(), 1);
    assert_eq!(w.doors[0].trigger, [20.0, 180.0]);
    assert_eq!(w.teleporters[0].exit, [50.0, 60.0]);
    assert_eq!(w.food.len(), 1);
    assert_eq!(w.food[0].capacity, [4.0, 0.0, 0.0, 0.0]);
    assert_eq!(w.aversives.len(), 1);
    assert_eq!(w.actors[0].role, "predator");
    assert_eq!(w.actors[0].waypoints.len(), 2);
    // Per tick: one creature row and one predator row.
    assert_eq!(trace.creatures.len(), 8);
    assert_eq!(trace.actors.len(), 8);
    assert!(!trace.creatures.last().unwrap().alive);
}

/// A creature still on a food object that never depletes, between the t-maze's two
/// teleporters (one exit at (150, 270)).
const ARMS: &str = r#"
name = "arms"
seed = 3

[world]
arena = [300.0, 300.0]
[[world.teleporters]]
entry = [70.0, 100.0]
radius = 4.0
exit = [150.0, 270.0]
[[world.teleporters]]
entry = [230.0, 100.0]
radius = 4.0
exit = [150.0, 270.0]
[world.kinds.spring]
class = "food"
radius = 2.0
substance = [1.0, 0.0, 0.0, 0.0]
bite = [0.1, 0.0, 0.0, 0.0]
depletes = false
[[world.objects]]
kind = "spring"
position = [150.0, 150.0]
[world.start]
region = [140.0, 140.0, 160.0, 160.0]
"#;

#[test]
fn a_jump_through_the_right_arm_and_every_bite_are_rows_as_the_world_told_them() {
    let experiment = Experiment::from_toml(ARMS, Path::new("arms.toml")).unwrap();
    let mut world = World::new(&experiment.world, &experiment.creature, 1, rng(3)).unwrap();
    let mut recorder = TraceRecorder::new(&experiment);
    let id = TrialId {
        generation: Generation(0),
        group: 0,
        trial: TrialIndex(0),
    };
    world.set_event_log(recorder.listens());
    recorder.start(id, &world);
    let mut controllers = [Still];
    // 30 ticks on the spring: 30 bites of 0.1. Their running sum is not a multiple of 0.1
    // in floating point, so differences of it (the old way) are not 0.1 on every tick.
    put(&mut world, 0, 154.0, 150.0, 0.0);
    for _ in 0..30 {
        world.step(&mut controllers);
        recorder.tick(&world, world.tick());
    }
    // Through the right arm's entry.
    put(&mut world, 0, 233.0, 100.0, 0.0);
    world.step(&mut controllers);
    recorder.tick(&world, world.tick());
    let trace = &recorder.trials[0];
    let eats: Vec<_> = trace
        .events
        .iter()
        .filter(|e| e.event == EventKind::Eat)
        .collect();
    assert_eq!(eats.len(), 30);
    for e in &eats {
        assert_eq!(e.amount, Some([0.1, 0.0, 0.0, 0.0]), "tick {}", e.tick);
    }
    let jump = trace.events.last().unwrap();
    assert_eq!(jump.event, EventKind::Teleport);
    assert_eq!(jump.tick, 31);
    assert_eq!(jump.target, Some(1), "the right arm's teleporter");
    assert_eq!(jump.from, Some([230.0, 100.0]));
    assert_eq!((jump.x, jump.y), (150.0, 270.0));
}

/// The experiment at `path` with at most 2 trials.
fn small(path: &Path) -> Experiment {
    let mut e = Experiment::load(path).unwrap().into_config();
    e.evaluation.trials = e.evaluation.trials.min(2);
    e.evolution.population = (e.evaluation.group_size as usize).max(8);
    e.evolution.elitism = 0;
    Experiment::try_from(e).unwrap()
}

#[test]
fn the_written_trace_is_the_scored_life_in_every_shipped_experiment() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("experiments");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    for path in files {
        let name = path.file_stem().unwrap().to_string_lossy().to_string();
        let experiment = small(&path);
        if experiment.evaluation.episodes_per_life > 1 {
            // Each episode is a trace of its own and a life's outcome sums them: the lives
            // of several episodes are checked in tests/evo/episodes_and_switches.rs.
            continue;
        }
        let topology = experiment.topology();
        let mut genomes = first_population(&experiment, &topology);
        genomes.truncate(experiment.evaluation.group_size as usize);
        let mut recorder = TraceRecorder::new(&experiment);
        let mut outcomes = Vec::new();
        for t in 0..experiment.evaluation.trials {
            outcomes.push(
                run_trial(
                    &TrialPlan::new(&experiment),
                    &topology,
                    &genomes,
                    Generation(1),
                    0,
                    TrialIndex(t),
                    &mut recorder,
                )
                .unwrap(),
            );
        }
        let k = genomes.len();
        for (t, trace) in recorder.trials.iter().enumerate() {
            assert_eq!(trace.world.trial, t as u64);
            assert_eq!(trace.world.inputs, experiment.layout().names());
            assert_eq!(
                trace.creatures.len() as u64,
                trace.ticks() * k as u64,
                "{name}"
            );
            for (i, o) in outcomes[t].iter().enumerate() {
                let last = &trace.creatures[trace.creatures.len() - k + i];
                assert_eq!(last.metabolism, o.metabolism, "{name} trial {t}");
                assert_eq!(trace.outcomes[i].score.to_bits(), o.score.to_bits());
                // Without decay, what the eat events moved is what the metabolism gained.
                let c = &experiment.creature;
                if c.decay_per_tick == [0.0; 4] && c.decay_per_lu == [0.0; 4] {
                    let mut eaten = c.initial_metabolism;
                    for e in trace.events.iter().filter(|e| e.creature == Some(i)) {
                        if let Some(a) = e.amount {
                            for (m, x) in eaten.iter_mut().zip(a) {
                                *m += x;
                            }
                        }
                    }
                    for (a, b) in eaten.iter().zip(o.metabolism) {
                        assert!((a - b).abs() < 1e-9, "{name} trial {t}: {eaten:?} {o:?}");
                    }
                }
            }
        }
        let csv = tmp.path().join(format!("{name}.csv"));
        write_csv_files(&recorder.trials, &csv).unwrap();
        let [creatures, actors, objects, events, world] = csv_paths(&csv);
        let text = std::fs::read_to_string(&creatures).unwrap();
        let header: Vec<&str> = text.lines().next().unwrap().split(',').collect();
        assert_eq!(&header[..3], ["trial", "tick", "creature"]);
        let inputs = experiment.layout().names().len();
        assert_eq!(header.len(), 22 + inputs, "{name}");
        let rows: usize = recorder.trials.iter().map(|t| t.creatures.len()).sum();
        assert_eq!(text.lines().count(), 1 + rows, "{name}");
        // Every row has every column; the last trial's rows say so.
        let last = text.lines().last().unwrap();
        assert_eq!(last.split(',').count(), header.len());
        assert!(last.starts_with(&format!("{},", recorder.trials.len() - 1)));
        for p in [&actors, &objects, &events] {
            let t = std::fs::read_to_string(p).unwrap();
            assert!(
                t.lines().next().unwrap().starts_with("trial,tick,"),
                "{p:?}"
            );
        }
        let world_lines = std::fs::read_to_string(&world).unwrap();
        assert_eq!(world_lines.lines().count(), recorder.trials.len());
        let jsonl = tmp.path().join(format!("{name}.jsonl"));
        write_jsonl(&recorder.trials, &jsonl).unwrap();
        let text = std::fs::read_to_string(&jsonl).unwrap();
        let lines: Vec<serde_json::Value> = text
            .lines()
            .map(|l| serde_json::from_str(l).unwrap())
            .collect();
        let ticks: u64 = recorder.trials.iter().map(|t| t.ticks()).sum();
        assert_eq!(lines.len() as u64, ticks + 2 * recorder.trials.len() as u64);
        assert_eq!(lines[0]["type"], "world");
        assert_eq!(lines[1]["type"], "tick");
        assert_eq!(lines[1]["tick"], 1);
        let x = lines[1]["creatures"][0]["x"].as_f64().unwrap();
        assert_eq!(x, recorder.trials[0].creatures[0].x, "exact numbers");
        // No temporary file is left beside the outputs.
        for entry in std::fs::read_dir(tmp.path()).unwrap() {
            let n = entry.unwrap().file_name().to_string_lossy().to_string();
            assert!(!n.contains(".tmp-"), "{n}");
        }
    }
}
