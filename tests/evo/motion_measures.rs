//! The motion measures (`forward_share`, `path_length`, `final_x`, `final_y`) on
//! hand-computed lives: a creature driven with equal wheel signals in an empty arena moves
//! 2π·w·signal LU straight along its heading each tick. Then both evaluation paths agree on
//! them to the bit, and novelty search takes them as descriptors.

use crate::door::{evaluate_group, evaluate_population};
use berry_evolve::evo::evaluate::Evaluation;
use berry_evolve::evo::fitness::{LifePlan, LifeScore, MEASURE_COUNT};
use berry_evolve::evo::TrialPlan;
use berry_evolve::experiment::{Experiment, Measure};
use berry_evolve::seed::{stream, Generation, IndividualId, Purpose, Seed, TrialIndex};
use berry_evolve::sim::controller::{Controller, MotorCommand};
use berry_evolve::sim::world::World;
use std::path::Path;

/// An empty 400 × 400 arena; the creature starts near (100, 200) facing right (heading 0°),
/// wheel w = 2 LU.
const TEXT: &str = r#"
name = "motion"
seed = 3

[world]
arena = [400.0, 400.0]
[world.start]
region = [100.0, 200.0, 102.0, 202.0]
heading = 0.0

[brain]
kind = "mlp"
hidden = [3]

[evolution]
population = 6
generations = 2

[evaluation]
trials = 2
ticks = 30

[behaviour]
measures = ["forward_share", "path_length", "final_x", "final_y"]
"#;

fn experiment(text: &str) -> Experiment {
    Experiment::from_toml(text, Path::new("motion.toml")).unwrap_or_else(|e| panic!("{e}"))
}

/// Wheel signals (left, right) in RPT, one pair per tick.
struct Script(Vec<(f64, f64)>, usize);

impl Controller for Script {
    fn act(&mut self, _: &[f64]) -> MotorCommand {
        let (left, right) = self.0[self.1];
        self.1 += 1;
        MotorCommand {
            left,
            right,
            ..MotorCommand::default()
        }
    }
}

/// Lives the script as evaluation does; returns the start, the measures and the world.
fn live(e: &Experiment, script: Vec<(f64, f64)>) -> ([f64; 2], [f64; MEASURE_COUNT]) {
    let rng = stream(
        Seed(1),
        Purpose::Demo,
        Generation(0),
        IndividualId(0),
        TrialIndex(0),
    );
    let mut world = World::new(&e.world, &e.creature, 1, rng).unwrap();
    let plan = LifePlan::new(&TrialPlan::new(e), &world);
    assert!(
        plan.needs_world_every_tick(),
        "the motion measures follow every tick"
    );
    plan.prepare(&mut world);
    let mut score = LifeScore::start(&plan, &world, 0);
    let start = world.creatures()[0].pose.position;
    let ticks = script.len();
    let mut controller = [Script(script, 0)];
    for _ in 0..ticks {
        world.step(&mut controller);
        let c = &world.creatures()[0];
        score.record_tick(&c.metabolism, c.shocked);
        score.record_world(&plan, &world, 0);
    }
    let (_, m) = score.finish_in(&plan, &world, 0);
    ([start.x, start.y], m)
}

fn get(m: &[f64; MEASURE_COUNT], which: Measure) -> f64 {
    m[which.index()]
}

fn close(a: f64, b: f64, what: &str) {
    assert!((a - b).abs() < 1e-9, "{what}: {a} vs {b}");
}

/// One tick at equal signals s moves 2π·w·s LU (eq. 28–30, w = 2).
fn step(signal: f64) -> f64 {
    std::f64::consts::TAU * 2.0 * signal
}

#[test]
fn driving_straight_forward_moves_n_times_the_speed() {
    let e = experiment(TEXT);
    let ([x0, y0], m) = live(&e, vec![(0.1, 0.1); 20]);
    let d = step(0.1);
    close(get(&m, Measure::PathLength), 20.0 * d, "path_length");
    assert_eq!(get(&m, Measure::ForwardShare), 1.0);
    close(get(&m, Measure::FinalX), x0 + 20.0 * d, "final_x");
    // Facing exactly +x, a straight move leaves y untouched.
    assert_eq!(get(&m, Measure::FinalY), y0);
}

#[test]
fn driving_backwards_is_never_forward() {
    let e = experiment(TEXT);
    let ([x0, y0], m) = live(&e, vec![(-0.1, -0.1); 20]);
    let d = step(0.1);
    assert_eq!(get(&m, Measure::ForwardShare), 0.0);
    close(get(&m, Measure::PathLength), 20.0 * d, "path_length");
    close(get(&m, Measure::FinalX), x0 - 20.0 * d, "final_x");
    assert_eq!(get(&m, Measure::FinalY), y0);
}

#[test]
fn standing_or_spinning_in_place_travels_nothing() {
    let e = experiment(TEXT);
    for (what, signals) in [("standing", (0.0, 0.0)), ("spinning", (0.1, -0.1))] {
        let ([x0, y0], m) = live(&e, vec![signals; 15]);
        assert_eq!(get(&m, Measure::PathLength), 0.0, "{what}");
        assert_eq!(get(&m, Measure::ForwardShare), 0.0, "{what}");
        assert_eq!(
            [get(&m, Measure::FinalX), get(&m, Measure::FinalY)],
            [x0, y0],
            "{what}"
        );
    }
}

/// 6 ticks forward, 4 back, 2 standing: forward on half of 12 ticks; 10 steps travelled and
/// 2 steps net to the right.
#[test]
fn a_mixed_life_counts_its_forward_ticks() {
    let e = experiment(TEXT);
    let mut script = vec![(0.1, 0.1); 6];
    script.extend([(-0.1, -0.1); 4]);
    script.extend([(0.0, 0.0); 2]);
    let ([x0, _], m) = live(&e, script);
    let d = step(0.1);
    assert_eq!(get(&m, Measure::ForwardShare), 0.5);
    close(get(&m, Measure::PathLength), 10.0 * d, "path_length");
    close(get(&m, Measure::FinalX), x0 + 2.0 * d, "final_x");
}

/// A step below 0.01 LU (`FORWARD_STEP`) is not forward motion; a step above it is.
#[test]
fn a_crawl_below_the_forward_step_does_not_count() {
    let e = experiment(TEXT);
    let slow = 0.005 / step(1.0);
    let (_, m) = live(&e, vec![(slow, slow); 4]);
    assert_eq!(get(&m, Measure::ForwardShare), 0.0);
    close(get(&m, Measure::PathLength), 0.02, "path_length");
    let faster = 0.02 / step(1.0);
    let (_, m) = live(&e, vec![(faster, faster); 4]);
    assert_eq!(get(&m, Measure::ForwardShare), 1.0);
}

/// With forward_bonus off and only the motion measures on, random genomes give the same bits
/// on the lockstep path (`evaluate_population`) and group by group (`evaluate_group`), and
/// they differ between genomes.
#[test]
fn lockstep_and_single_trials_agree_on_the_motion_measures() {
    let text = TEXT.replace(
        "[world.start]",
        "[world.kinds.food_a]\nclass = \"food\"\nradius = 2.0\nsubstance = [4.0, 0.0, 0.0, 0.0]\n\
         bite = [0.5, 0.0, 0.0, 0.0]\nodour = [1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]\n\
         intensity = 1.0\nrange = 80.0\n[[world.place]]\nkind = \"food_a\"\ncount = 30\n\
         [[world.walls]]\nfrom = [150.0, 0.0]\nto = [150.0, 300.0]\n[world.start]",
    );
    let e = experiment(&text.replace("population = 6", "population = 16"));
    let topology = e.topology();
    let population = berry_evolve::evo::search::ga::first_population(&e, &topology);
    let together = evaluate_population(&e, &topology, &population, Generation(1)).unwrap();
    let mut alone = Vec::new();
    for (g, genome) in population.iter().enumerate() {
        alone.extend(
            evaluate_group(
                &e,
                &topology,
                std::slice::from_ref(genome),
                Generation(1),
                g as u64,
            )
            .unwrap(),
        );
    }
    let bits = |e: &[Evaluation]| -> Vec<Vec<u64>> {
        e.iter()
            .map(|e| e.measures.iter().map(|m| m.to_bits()).collect())
            .collect()
    };
    assert_eq!(bits(&together), bits(&alone));
    assert!(together.iter().all(|e| e.measures.len() == 4));
    let paths: std::collections::BTreeSet<u64> =
        together.iter().map(|e| e.measures[1].to_bits()).collect();
    assert!(paths.len() > 1, "{together:?}");
    for e in &together {
        assert!((0.0..=1.0).contains(&e.measures[0]), "{e:?}");
        assert!(e.measures[1] >= 0.0, "{e:?}");
    }
}

fn novelty_text() -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/tiny-novelty.toml");
    std::fs::read_to_string(path)
        .unwrap()
        .replace(
            "    { measure = \"distinct_food\", min = 0, max = 6 },\n    { measure = \"food_types\", min = 0, max = 2 },",
            "    { measure = \"forward_share\", min = 0, max = 1 },\n    { measure = \"path_length\", min = 0, max = 200 },",
        )
        .replace(
            "measures = [\"food_types\", \"distinct_food\"]",
            "measures = [\"forward_share\", \"path_length\", \"final_x\", \"final_y\"]",
        )
}

/// Novelty search with `forward_share` and `path_length` as descriptors validates and runs,
/// and fitness.csv reports the motion measures.
#[test]
fn novelty_search_takes_forward_share_as_a_descriptor() {
    let text = novelty_text().replace("generations = 8", "generations = 3");
    assert!(text.contains("measure = \"forward_share\""));
    let e = Experiment::from_toml(&text, Path::new("motion-novelty.toml"))
        .unwrap_or_else(|e| panic!("{e}"));
    let dir = std::env::temp_dir().join(format!("motion-novelty-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    berry_evolve::run::start(
        e,
        &dir,
        false,
        berry_evolve::run::RunOptions {
            jobs: 1,
            stop: None,
            evaluator: None,
        },
        &mut berry_evolve::run::Silent,
    )
    .unwrap();
    let table = berry_evolve::record::fitness_csv::read_table(&dir.join("fitness.csv")).unwrap();
    assert_eq!(
        table.extra[..4],
        [
            "best_forward_share",
            "mean_forward_share",
            "best_path_length",
            "mean_path_length"
        ]
    );
    assert_eq!(table.rows.len(), 3);
    for values in &table.extras {
        let share = values[1].unwrap();
        assert!((0.0..=1.0).contains(&share), "{values:?}");
        assert!(values[3].unwrap() >= 0.0, "{values:?}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A descriptor the experiment does not compute is refused, naming the key and the measure.
#[test]
fn a_motion_descriptor_not_in_the_measures_is_refused() {
    let text = novelty_text().replace(
        "measures = [\"forward_share\", \"path_length\", \"final_x\", \"final_y\"]",
        "measures = [\"path_length\"]",
    );
    let problem = Experiment::from_toml(&text, Path::new("motion-novelty.toml"))
        .unwrap_err()
        .to_string();
    assert!(
        problem.contains("evolution.novelty.descriptors") && problem.contains("forward_share"),
        "{problem}"
    );
}
