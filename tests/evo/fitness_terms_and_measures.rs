//! The `[fitness]` terms and `[behaviour]` measures on hand-computed lives: a creature moved
//! along a chosen path (and an air predator put where the test wants it), every value worked
//! out by hand; then both evaluation paths agree to the bit with every term and measure on,
//! and a run's fitness.csv carries the measure columns.

use crate::door::{evaluate_group, evaluate_population, run_trial};
use berry_evolve::brain::genome::Genome;
use berry_evolve::evo::evaluate::Evaluation;
use berry_evolve::evo::fitness::{LifePlan, LifeScore, MEASURE_COUNT};
use berry_evolve::evo::lockstep;
use berry_evolve::evo::TrialPlan;
use berry_evolve::experiment::{Experiment, Measure};
use berry_evolve::geometry::Vec2;
use berry_evolve::seed::{stream, Generation, IndividualId, Purpose, Seed, TrialIndex};
use berry_evolve::sim::controller::{Controller, MotorCommand};
use berry_evolve::sim::motion::Pose;
use berry_evolve::sim::world::World;
use std::path::Path;

/// A 200 × 200 arena: three food A objects along y = 50, one food B at (50, 150), a nettle at
/// (100, 150), a plain area "goal" in the bottom right, a safe area "nest" top left. The
/// creature (radius 3) starts in a small region near the bottom left corner.
const WORLD: &str = r#"
name = "measures"
seed = 3

[world]
arena = [200.0, 200.0]
[world.kinds.food_a]
class = "food"
radius = 2.0
substance = [4.0, 0.0, 0.0, 0.0]
bite = [0.5, 0.0, 0.0, 0.0]
depletes = true
[world.kinds.food_b]
class = "food"
radius = 2.0
substance = [0.0, 4.0, 0.0, 0.0]
bite = [0.0, 0.5, 0.0, 0.0]
depletes = true
[world.kinds.nettle]
class = "aversive"
radius = 3.0
[[world.objects]]
kind = "food_a"
position = [50.0, 50.0]
[[world.objects]]
kind = "food_a"
position = [100.0, 50.0]
[[world.objects]]
kind = "food_a"
position = [150.0, 50.0]
[[world.objects]]
kind = "food_b"
position = [50.0, 150.0]
[[world.objects]]
kind = "nettle"
position = [100.0, 150.0]
[[world.areas]]
name = "goal"
region = [140.0, 140.0, 190.0, 190.0]
[[world.areas]]
name = "nest"
region = [0.0, 0.0, 30.0, 30.0]
kind = "safe"
[world.start]
region = [10.0, 185.0, 12.0, 187.0]
"#;

const REST: &str = r#"
[brain]
kind = "mlp"
hidden = [3]

[evolution]
population = 6
generations = 3

[evaluation]
trials = 2
ticks = 40
"#;

fn experiment(world_extra: &str, tables: &str) -> Experiment {
    let text = format!("{WORLD}{world_extra}{REST}{tables}");
    Experiment::from_toml(&text, Path::new("measures.toml")).unwrap_or_else(|e| panic!("{e}"))
}

struct Still;

impl Controller for Still {
    fn act(&mut self, _: &[f64]) -> MotorCommand {
        MotorCommand::default()
    }
}

/// One tick of a scripted life: where the creature is put before the tick, and where the
/// (first) air predator is put, standing still.
struct Step {
    at: (f64, f64),
    flyer: Option<(f64, f64)>,
}

fn at(x: f64, y: f64) -> Step {
    Step {
        at: (x, y),
        flyer: None,
    }
}

/// Lives `path` in the experiment's world as evaluation does (stopping when the creature
/// dies) and returns its score and measures.
fn live(e: &Experiment, path: &[Step]) -> (f64, [f64; MEASURE_COUNT], World) {
    let mut world = demo_world(e);
    let plan = LifePlan::new(&TrialPlan::new(e), &world);
    plan.prepare(&mut world);
    let mut score = LifeScore::start(&plan, &world, 0);
    for step in path {
        world.set_pose(
            0,
            Pose {
                position: Vec2::new(step.at.0, step.at.1),
                heading: Vec2::X,
            },
        );
        if let Some((x, y)) = step.flyer {
            world.set_flyer(0, Vec2::new(x, y), Vec2::ZERO);
        }
        world.step(&mut [Still]);
        let c = &world.creatures()[0];
        if !c.alive {
            break;
        }
        score.record_tick(&c.metabolism, c.shocked);
        if plan.needs_world_every_tick() {
            score.record_world(&plan, &world, 0);
        }
    }
    let (s, m) = score.finish_in(&plan, &world, 0);
    (s, m, world)
}

/// The experiment's world with one creature, from the demo stream of seed 1.
fn demo_world(e: &Experiment) -> World {
    let rng = stream(
        Seed(1),
        Purpose::Demo,
        Generation(0),
        IndividualId(0),
        TrialIndex(0),
    );
    World::new(&e.world, &e.creature, 1, rng).unwrap()
}

fn measure(values: &[f64; MEASURE_COUNT], m: Measure) -> f64 {
    values[m.index()]
}

/// Three ticks on food 0, one on food 1, one on food B, two on the nettle, two in the goal
/// area, one in the middle of the arena.
fn forager_path() -> Vec<Step> {
    vec![
        at(50.0, 50.0),
        at(50.0, 50.0),
        at(50.0, 50.0),
        at(100.0, 50.0),
        at(50.0, 150.0),
        at(100.0, 150.0),
        at(100.0, 150.0),
        at(160.0, 160.0),
        at(165.0, 165.0),
        at(100.0, 100.0),
    ]
}

#[test]
fn foraging_measures_on_a_scripted_path() {
    let e = experiment(
        "",
        r#"
[behaviour]
measures = ["ticks_alive", "distinct_food", "food_types", "area_reached", "time_in_area",
            "aversive_contacts", "shocked_ticks", "door_opened"]
area = "goal"
"#,
    );
    let (_, m, world) = live(&e, &forager_path());
    assert_eq!(measure(&m, Measure::TicksAlive), 10.0);
    // Food objects 0, 1 and 3 (B) were bitten; object 2 never.
    assert_eq!(world.bitten(0), &[true, true, false, true]);
    assert_eq!(measure(&m, Measure::DistinctFood), 3.0);
    assert_eq!(measure(&m, Measure::FoodTypes), 2.0);
    assert_eq!(measure(&m, Measure::AreaReached), 1.0);
    assert_eq!(measure(&m, Measure::TimeInArea), 2.0);
    // Two ticks on the nettle: one contact, two shocked ticks.
    assert_eq!(measure(&m, Measure::AversiveContacts), 1.0);
    assert_eq!(measure(&m, Measure::ShockedTicks), 2.0);
    // No door in this world.
    assert_eq!(measure(&m, Measure::DoorOpened), 0.0);
    // The metabolism: 4 bites of A, 1 of B.
    assert_eq!(world.creatures()[0].metabolism, [2.0, 0.5, 0.0, 0.0]);
}

#[test]
fn every_fitness_term_on_a_scripted_path() {
    let e = experiment(
        "",
        r#"
[fitness]
weights = [1.0, 1.0, 0.0, 0.0]
shock_penalty = 0.25
alive_bonus = 0.1
area = "goal"
area_bonus = 1.0
goal_point = [100.0, 130.0]
goal_bonus = 4.0
goal_range = 40.0
distinct_food_bonus = 0.5
death_penalty = 7.0
"#,
    );
    let (score, _, _) = live(&e, &forager_path());
    // gain 2.0 + 0.5 = 2.5; alive 0.1 × 10 = 1; area 1 × 2 = 2; the end (100, 100) is 30 LU
    // from the goal: 4 × (1 − 30/40) = 1; distinct 0.5 × 3 = 1.5; shocks −0.25 × 2; alive at
    // the end, so no death penalty.
    assert_eq!(score, 2.5 + 1.0 + 2.0 + 1.0 + 1.5 - 0.5);
}

#[test]
fn goal_closest_takes_the_nearest_approach() {
    let e = experiment(
        "",
        r#"
[fitness]
weights = [0.0, 0.0, 0.0, 0.0]
goal_point = [100.0, 130.0]
goal_bonus = 4.0
goal_range = 40.0
goal_at = "closest"
"#,
    );
    let (score, _, _) = live(&e, &forager_path());
    // Closest at the nettle (100, 150): 20 LU, 4 × (1 − 20/40).
    assert_eq!(score, 2.0);
    // A goal area: from (100, 100) the goal box's corner (140, 140) is 40·√2 away, beyond
    // the default range (the diagonal 200·√2) by a factor 1/5: 3 × (1 − 0.2) = 2.4.
    let e = experiment(
        "",
        r#"
[fitness]
weights = [0.0, 0.0, 0.0, 0.0]
goal = "goal"
goal_bonus = 3.0
"#,
    );
    let (score, _, _) = live(&e, &forager_path());
    let d = (40.0f64 * 40.0 + 40.0 * 40.0).sqrt();
    let range = (200.0f64 * 200.0 + 200.0 * 200.0).sqrt();
    assert_eq!(score, 3.0 * (1.0 - d / range));
}

#[test]
fn balance_min_scores_the_scarcer_food() {
    let e = experiment(
        "",
        r#"
[fitness]
weights = [1.0, 2.0, 0.0, 0.0]
balance = "min"
"#,
    );
    // fA 2.0, fB 0.5 weighted 1.0: min(2.0, 1.0).
    let (score, _, _) = live(&e, &forager_path());
    assert_eq!(score, 1.0);
    let e = experiment(
        "",
        r#"
[fitness]
weights = [1.0, 2.0, 0.0, 0.0]
imbalance_penalty = 0.5
"#,
    );
    // 2.0 + 1.0 − 0.5 × (2.0 − 1.0).
    let (score, _, _) = live(&e, &forager_path());
    assert_eq!(score, 2.5);
}

#[test]
fn food_in_area_counts_the_objects_inside_it() {
    let e = experiment(
        "[[world.areas]]\nname = \"top\"\nregion = [0.0, 0.0, 199.0, 100.0]\n",
        "[behaviour]\nmeasures = [\"food_in_area_eaten\"]\narea = \"top\"\n",
    );
    let (_, m, _) = live(&e, &forager_path());
    // Objects 0 and 1 lie in the top half and were eaten; 2 lies there too but was not.
    assert_eq!(measure(&m, Measure::FoodInAreaEaten), 2.0);
}

const AIR: &str = r#"
[[world.air_predators]]
speed = 1.0
strike_radius = 10.0
effect = "shock"
"#;

/// Tick 1: in the nest with the predator overhead; 2: predator gone (a sheltered pass ends);
/// 3: out in the open under it (struck); 4: gone (an unsheltered pass ends); 5: back in the
/// nest under it (a sheltered pass still going at the end).
fn raid_path() -> Vec<Step> {
    let s = |c: (f64, f64), f: (f64, f64)| Step {
        at: c,
        flyer: Some(f),
    };
    vec![
        s((15.0, 15.0), (15.0, 15.0)),
        s((15.0, 15.0), (100.0, 100.0)),
        s((100.0, 100.0), (105.0, 100.0)),
        s((100.0, 100.0), (180.0, 20.0)),
        s((15.0, 15.0), (20.0, 15.0)),
    ]
}

#[test]
fn shelter_and_strikes_under_an_air_predator() {
    let e = experiment(
        AIR,
        r#"
[behaviour]
measures = ["shelter_while_threat", "strikes_survived", "shocked_ticks", "ticks_alive"]
"#,
    );
    let (_, m, _) = live(&e, &raid_path());
    // Threat near at ticks 1, 3 and 5; sheltered at 1 and 5.
    assert_eq!(measure(&m, Measure::ShelterWhileThreat), 2.0 / 3.0);
    // The passes of ticks 1 and 5 were sheltered; the one of tick 3 was not.
    assert_eq!(measure(&m, Measure::StrikesSurvived), 2.0);
    assert_eq!(measure(&m, Measure::ShockedTicks), 1.0);
    assert_eq!(measure(&m, Measure::TicksAlive), 5.0);
}

#[test]
fn shelter_bonus_pays_for_sheltered_threatened_ticks_only() {
    // Without the measure: the bonus counts threats on its own.
    let e = experiment(
        AIR,
        r#"
[fitness]
weights = [0.0, 0.0, 0.0, 0.0]
shelter_bonus = 10.0
"#,
    );
    let (score, m, _) = live(&e, &raid_path());
    // Threat near at ticks 1, 3 and 5; sheltered at 1 and 5 (tick 2 sheltered but no threat;
    // tick 3 threatened in the open): 2 × 10.
    assert_eq!(score, 20.0);
    assert_eq!(
        measure(&m, Measure::ShelterWhileThreat),
        0.0,
        "not reported"
    );
    // The same life with a radius that no pass comes within: nothing.
    let far = experiment(
        AIR,
        r#"
[fitness]
weights = [0.0, 0.0, 0.0, 0.0]
shelter_bonus = 10.0

[behaviour]
threat_radius = 0.001
"#,
    );
    // Tick 1's predator sits exactly on the creature: still within any radius.
    assert_eq!(live(&far, &raid_path()).0, 10.0);
}

#[test]
fn a_lethal_strike_ends_the_life_with_the_death_penalty() {
    let e = experiment(
        &AIR.replace("\"shock\"", "\"lethal\""),
        r#"
[fitness]
weights = [0.0, 0.0, 0.0, 0.0]
alive_bonus = 1.0
death_penalty = 5.0

[behaviour]
measures = ["strikes_survived", "ticks_alive", "shelter_while_threat"]
"#,
    );
    let (score, m, world) = live(&e, &raid_path());
    assert!(!world.creatures()[0].alive);
    // Killed in tick 3: two ticks alive, then the penalty.
    assert_eq!(score, 2.0 - 5.0);
    assert_eq!(measure(&m, Measure::TicksAlive), 2.0);
    assert_eq!(measure(&m, Measure::StrikesSurvived), 1.0);
    assert_eq!(measure(&m, Measure::ShelterWhileThreat), 1.0);
}

#[test]
fn door_opened_when_the_trigger_is_touched() {
    let door = r#"
[[world.doors]]
from = [120.0, 0.0]
to = [120.0, 40.0]
trigger = [60.0, 100.0]
trigger_radius = 2.0
open_ticks = 3
"#;
    let e = experiment(door, "[behaviour]\nmeasures = [\"door_opened\"]\n");
    let (_, m, _) = live(&e, &[at(100.0, 100.0), at(60.0, 100.0), at(80.0, 100.0)]);
    assert_eq!(measure(&m, Measure::DoorOpened), 1.0);
    let (_, m, _) = live(&e, &[at(100.0, 100.0), at(80.0, 100.0)]);
    assert_eq!(measure(&m, Measure::DoorOpened), 0.0);
}

#[test]
fn unknown_area_names_are_refused_with_the_key() {
    let text = format!("{WORLD}{REST}[fitness]\narea = \"gaol\"\narea_bonus = 1.0\n");
    let err = Experiment::from_toml(&text, Path::new("x.toml")).unwrap_err();
    let message = err.to_string();
    assert!(message.contains("fitness.area"), "{message}");
    assert!(message.contains("goal, nest"), "{message}");
    let text = format!("{WORLD}{REST}[behaviour]\nmeasures = [\"time_in_area\"]\n");
    let err = Experiment::from_toml(&text, Path::new("x.toml")).unwrap_err();
    assert!(err.to_string().contains("behaviour.area"), "{err}");
}

fn bits(e: &[Evaluation]) -> Vec<(Option<u64>, [u64; 4], Vec<u64>)> {
    e.iter()
        .map(|e| {
            (
                e.fitness.map(f64::to_bits),
                e.metabolism.map(f64::to_bits),
                e.measures.iter().map(|m| m.to_bits()).collect(),
            )
        })
        .collect()
}

/// With every term and measure on, the lockstep path (stateless MLP) and the trial-by-trial
/// path give the same bits, and random genomes actually move the measures.
#[test]
fn both_evaluation_paths_agree_on_every_term_and_measure() {
    let e = experiment(
        &format!(
            "{AIR}[[world.place]]\nkind = \"food_a\"\ncount = 40\n[[world.place]]\nkind = \"nettle\"\ncount = 30\n"
        ),
        r#"
[fitness]
weights = [1.0, 1.0, 0.0, 0.0]
balance = "min"
imbalance_penalty = 0.1
shock_penalty = 0.01
alive_bonus = 0.01
area = "goal"
area_bonus = 0.1
goal = "goal"
goal_bonus = 1.0
goal_at = "closest"
distinct_food_bonus = 0.3
forward_bonus = 0.02
shelter_bonus = 0.05
death_penalty = 1.0

[behaviour]
measures = ["ticks_alive", "distinct_food", "food_types", "area_reached", "time_in_area",
            "door_opened", "food_in_area_eaten", "shelter_while_threat", "strikes_survived",
            "aversive_contacts", "shocked_ticks", "forward_share", "path_length",
            "final_x", "final_y", "eaten", "still_share", "richest_side_first"]
area = "goal"
threat_radius = 60.0
"#,
    );
    let topology = e.topology();
    assert!(lockstep::stateless(&topology));
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
    assert_eq!(bits(&together), bits(&alone));
    assert!(together.iter().all(|e| e.measures.len() == 18));
    // Random genomes do move: some measure differs between individuals.
    let distinct: std::collections::BTreeSet<Vec<u64>> =
        bits(&together).into_iter().map(|b| b.2).collect();
    assert!(distinct.len() > 1, "{together:?}");
}

/// An experiment without the new keys scores exactly as `LifeScore::finish` alone says,
/// and its evaluations carry no measures.
#[test]
fn plain_fitness_has_no_measures_and_the_plain_score() {
    let e = experiment("", "");
    let topology = e.topology();
    let genome = Genome::new(vec![0.1; topology.parameter_count()]);
    let o = run_trial(
        &e,
        &topology,
        std::slice::from_ref(&genome),
        Generation(0),
        0,
        TrialIndex(0),
    )
    .unwrap()[0];
    assert_eq!(o.measures, [0.0; MEASURE_COUNT]);
    let evaluation = evaluate_group(&e, &topology, &[genome], Generation(0), 0).unwrap();
    assert!(evaluation[0].measures.is_empty());
    assert_eq!(
        o.score,
        o.metabolism.iter().sum::<f64>(),
        "weights [1, 1, 1, 1], final mode"
    );
}

/// A run's fitness.csv names the measures' columns, and their values are the generation's
/// best individual's and the population mean.
#[test]
fn fitness_csv_carries_measure_columns() {
    let e = experiment(
        "[[world.place]]\nkind = \"food_a\"\ncount = 40\n",
        "[behaviour]\nmeasures = [\"distinct_food\", \"ticks_alive\"]\n",
    );
    let dir = std::env::temp_dir().join(format!("measures-csv-{}", std::process::id()));
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
        table.extra,
        [
            "best_distinct_food",
            "mean_distinct_food",
            "best_ticks_alive",
            "mean_ticks_alive"
        ]
    );
    assert_eq!(table.rows.len(), 3);
    for values in &table.extras {
        // Nobody dies here: every life is 40 ticks.
        assert_eq!(values[2], Some(40.0));
        assert_eq!(values[3], Some(40.0));
        assert!(values[0].is_some() && values[1].is_some());
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn forward_bonus_pays_for_forward_motion_only() {
    let e = experiment(
        "heading = 0.0\n",
        r#"
[fitness]
weights = [0.0, 0.0, 0.0, 0.0]
forward_bonus = 0.5
"#,
    );
    let x0 = demo_world(&e).creatures()[0].pose.position.x;
    // Facing +x all along: 50 − x0 and 10 forward, 5 back (nothing), 30 sideways (nothing),
    // 15 forward.
    let path = [
        at(50.0, 50.0),
        at(60.0, 50.0),
        at(55.0, 50.0),
        at(55.0, 80.0),
        at(70.0, 80.0),
    ];
    let (score, _, _) = live(&e, &path);
    assert_eq!(score, 0.5 * ((50.0 - x0) + 10.0 + 15.0));
}

/// Both wheels at the same signal for every tick.
struct Drive(f64);

impl Controller for Drive {
    fn act(&mut self, _: &[f64]) -> MotorCommand {
        MotorCommand {
            left: self.0,
            right: self.0,
            ..MotorCommand::default()
        }
    }
}

#[test]
fn driving_backwards_earns_no_forward_bonus() {
    let e = experiment(
        "heading = 270.0\n",
        r#"
[fitness]
weights = [0.0, 0.0, 0.0, 0.0]
forward_bonus = 1.0
"#,
    );
    for (signal, forward) in [(0.1, true), (-0.1, false)] {
        let mut world = demo_world(&e);
        let plan = LifePlan::new(&TrialPlan::new(&e), &world);
        let mut score = LifeScore::start(&plan, &world, 0);
        let start = world.creatures()[0].pose.position;
        // Heading up the screen (270°) from near the bottom: 10 ticks straight, no wall hit.
        for _ in 0..10 {
            world.step(&mut [Drive(signal)]);
            let c = &world.creatures()[0];
            score.record_tick(&c.metabolism, c.shocked);
            score.record_world(&plan, &world, 0);
        }
        let travelled = (world.creatures()[0].pose.position - start).length();
        assert!(travelled > 5.0, "the creature hardly moved: {travelled}");
        let (s, _) = score.finish_in(&plan, &world, 0);
        if forward {
            assert!((s - travelled).abs() < 1e-9, "{s} vs {travelled}");
        } else {
            assert_eq!(s, 0.0);
        }
    }
}
