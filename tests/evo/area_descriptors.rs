//! Descriptors that name an area (`{ measure = "time_in_area", area = "field", ... }`): the
//! ticks counted on a hand-computed straight path through two rectangles, independent of
//! `[behaviour] area`; the same count as `time_in_area` through the whole evaluation (both
//! paths); the refusals naming their key; a MAP-Elites run over two areas gives the same bytes
//! on 1 and 2 threads and resumed, with archive.csv naming its columns by area.

use crate::cli_common::read;
use crate::door::evaluate_population;
use crate::run_guarantees::same_bytes_on_any_thread_count_and_resumed;
use berry_evolve::evo::fitness::{LifePlan, LifeScore};
use berry_evolve::evo::lockstep;
use berry_evolve::evo::search::ga::first_population;
use berry_evolve::evo::TrialPlan;
use berry_evolve::experiment::{Experiment, Measure};
use berry_evolve::geometry::Vec2;
use berry_evolve::seed::{stream, Generation, IndividualId, Purpose, Seed, TrialIndex};
use berry_evolve::sim::controller::{Controller, MotorCommand};
use berry_evolve::sim::motion::Pose;
use berry_evolve::sim::world::World;
use std::path::Path;

/// A 200 × 200 arena with three named areas: "nest" top left, "field" a band across the
/// right (x 100 to 200, y 40 to 140), "goal" bottom right, "shade" on the left. Creatures
/// start across the field's edge.
const WORLD: &str = r#"
name = "areas"
seed = 3

[world]
arena = [200.0, 200.0]
[world.kinds.food_a]
class = "food"
radius = 2.0
substance = [4.0, 0.0, 0.0, 0.0]
bite = [0.5, 0.0, 0.0, 0.0]
depletes = true
odour = [1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]
intensity = 1.0
range = 80.0
[[world.place]]
kind = "food_a"
count = 20
[[world.areas]]
name = "nest"
region = [0.0, 0.0, 30.0, 30.0]
[[world.areas]]
name = "field"
region = [100.0, 40.0, 200.0, 140.0]
[[world.areas]]
name = "goal"
region = [140.0, 150.0, 190.0, 190.0]
[[world.areas]]
name = "shade"
region = [0.0, 100.0, 50.0, 200.0]
[world.start]
region = [80.0, 20.0, 140.0, 80.0]

[brain]
kind = "mlp"
hidden = [3]

[evaluation]
trials = 2
ticks = 60
"#;

fn text(evolution: &str, behaviour: &str) -> String {
    format!("{WORLD}\n[evolution]\npopulation = 12\ngenerations = 3\n{evolution}\n{behaviour}")
}

fn experiment(evolution: &str, behaviour: &str) -> Experiment {
    Experiment::from_toml(&text(evolution, behaviour), Path::new("areas.toml"))
        .unwrap_or_else(|e| panic!("{e}"))
}

fn refusal(evolution: &str, behaviour: &str) -> String {
    match Experiment::from_toml(&text(evolution, behaviour), Path::new("areas.toml")) {
        Ok(_) => panic!("accepted:\n{evolution}\n{behaviour}"),
        Err(e) => e.to_string(),
    }
}

/// MAP-Elites over the ticks in "field" and in "nest" (in that order).
const FIELD_AND_NEST: &str = r#"algorithm = "map-elites"
[evolution.map_elites]
descriptors = [
    { measure = "time_in_area", area = "field", min = 0, max = 60, bins = 4 },
    { measure = "time_in_area", area = "nest", min = 0, max = 60, bins = 4 },
]
"#;

struct Still;

impl Controller for Still {
    fn act(&mut self, _: &[f64]) -> MotorCommand {
        MotorCommand::default()
    }
}

/// Lives the path (the creature put at each point before its tick) as evaluation does and
/// returns the ticks in the described areas and the measures.
fn live(e: &Experiment, path: &[(f64, f64)]) -> ([f64; 3], f64) {
    let rng = stream(
        Seed(1),
        Purpose::Demo,
        Generation(0),
        IndividualId(0),
        TrialIndex(0),
    );
    let mut world = World::new(&e.world, &e.creature, 1, rng).unwrap();
    let plan = LifePlan::new(&TrialPlan::new(e), &world);
    plan.prepare(&mut world);
    let mut score = LifeScore::start(&plan, &world, 0);
    for &(x, y) in path {
        world.set_pose(
            0,
            Pose {
                position: Vec2::new(x, y),
                heading: Vec2::X,
            },
        );
        world.step(&mut [Still]);
        let c = &world.creatures()[0];
        assert!(c.alive);
        score.record_tick(&c.metabolism, c.shocked);
        if plan.needs_world_every_tick() {
            score.record_world(&plan, &world, 0);
        }
    }
    let (_, measures) = score.finish_in(&plan, &world, 0);
    (
        score.described_area_ticks(),
        measures[Measure::TimeInArea.index()],
    )
}

/// Two ticks in the nest, then straight along y = 50 from x = 85 to 185 in steps of 10: the
/// field (x from 100) holds x = 105, 115, ..., 185, nine ticks; the goal none.
#[test]
fn a_straight_path_counts_the_ticks_inside_each_described_area() {
    let mut path = vec![(15.0, 15.0), (20.0, 20.0)];
    path.extend((0..11).map(|i| (85.0 + 10.0 * f64::from(i), 50.0)));
    // `[behaviour] area` is the goal: the descriptors count their own areas regardless.
    let e = experiment(
        FIELD_AND_NEST,
        "[behaviour]\nmeasures = [\"time_in_area\"]\narea = \"goal\"\n",
    );
    let (ticks, time_in_goal) = live(&e, &path);
    assert_eq!(ticks, [9.0, 2.0, 0.0]);
    assert_eq!(time_in_goal, 0.0);
    // Without `[behaviour]` at all, the same.
    let e = experiment(FIELD_AND_NEST, "");
    assert_eq!(live(&e, &path).0, [9.0, 2.0, 0.0]);
    // Without area descriptors nothing is counted.
    let e = experiment("", "");
    assert_eq!(live(&e, &path).0, [0.0; 3]);
}

/// Through the whole evaluation (the lockstep path of a stateless MLP),
/// a descriptor's area ticks are `time_in_area` of the same area, and the search reads them.
#[test]
fn an_evaluation_carries_the_described_areas_like_time_in_area() {
    let e = experiment(
        FIELD_AND_NEST,
        "[behaviour]\nmeasures = [\"time_in_area\", \"ticks_alive\", \"final_x\", \"final_y\"]\narea = \"field\"\n",
    );
    let topology = e.topology();
    assert!(lockstep::stateless(&topology));
    let population = first_population(&e, &topology);
    let evaluations = evaluate_population(&e, &topology, &population, Generation(1)).unwrap();
    for ev in &evaluations {
        assert_eq!(ev.area_ticks.len(), 2);
        assert_eq!(ev.area_ticks[0], ev.measures[0]);
    }
    assert!(
        evaluations.iter().any(|ev| ev.area_ticks[0] > 0.0),
        "some random creature spends time in the field"
    );
    let e = experiment(
        FIELD_AND_NEST,
        "[behaviour]\nmeasures = [\"time_in_area\"]\narea = \"nest\"\n",
    );
    let again = evaluate_population(&e, &topology, &population, Generation(1)).unwrap();
    for (ev, nest) in evaluations.iter().zip(&again) {
        assert_eq!(ev.area_ticks[1], nest.measures[0]);
    }
    // Lives of two episodes: the mean over the episodes, as `time_in_area`'s.
    let text = text(
        FIELD_AND_NEST,
        "[behaviour]\nmeasures = [\"time_in_area\"]\narea = \"field\"\n",
    )
    .replace("ticks = 60\n", "ticks = 30\nepisodes_per_life = 2\n");
    let e = Experiment::from_toml(&text, Path::new("areas.toml")).unwrap();
    let lives = evaluate_population(&e, &topology, &population, Generation(1)).unwrap();
    for ev in &lives {
        assert_eq!(ev.area_ticks[0], ev.measures[0]);
    }
    assert!(lives.iter().any(|ev| ev.area_ticks[0] > 0.0));
    // Without area descriptors the evaluation has none (and checkpoints stay as they were).
    let e = experiment(
        "",
        "[behaviour]\nmeasures = [\"time_in_area\"]\narea = \"nest\"\n",
    );
    let plain = evaluate_population(&e, &topology, &population, Generation(1)).unwrap();
    assert!(plain.iter().all(|ev| ev.area_ticks.is_empty()));
}

#[test]
fn area_descriptors_are_checked_and_name_their_key() {
    let unknown = refusal(
        r#"algorithm = "map-elites"
[evolution.map_elites]
descriptors = [
    { measure = "time_in_area", area = "field", min = 0, max = 60, bins = 4 },
    { measure = "time_in_area", area = "feild", min = 0, max = 60, bins = 4 },
]"#,
        "",
    );
    assert!(
        unknown.contains("evolution.map_elites.descriptors[1].area"),
        "{unknown}"
    );
    assert!(unknown.contains("nest, field, goal, shade"), "{unknown}");

    let other = refusal(
        r#"algorithm = "novelty"
[evolution.novelty]
descriptors = [{ measure = "distinct_food", area = "field", min = 0, max = 20 }]"#,
        "[behaviour]\nmeasures = [\"distinct_food\"]\n",
    );
    assert!(
        other.contains("evolution.novelty.descriptors[0].area"),
        "{other}"
    );
    assert!(other.contains("distinct_food"), "{other}");

    let four = refusal(
        r#"algorithm = "novelty"
[evolution.novelty]
descriptors = [
    { measure = "time_in_area", area = "field", min = 0, max = 60 },
    { measure = "time_in_area", area = "nest", min = 0, max = 60 },
    { measure = "time_in_area", area = "goal", min = 0, max = 60 },
    { measure = "time_in_area", area = "shade", min = 0, max = 60 },
]"#,
        "",
    );
    assert!(
        four.contains("evolution.novelty.descriptors[3].area"),
        "{four}"
    );
    assert!(four.contains("at most 3"), "{four}");

    let twice = refusal(
        r#"algorithm = "map-elites"
[evolution.map_elites]
descriptors = [
    { measure = "time_in_area", area = "nest", min = 0, max = 60, bins = 4 },
    { measure = "time_in_area", area = "nest", min = 0, max = 30, bins = 4 },
]"#,
        "",
    );
    assert!(twice.contains("time_in_area:nest` twice"), "{twice}");

    // A plain `time_in_area` descriptor still needs the measure (and its area) in `[behaviour]`.
    let plain = refusal(
        r#"algorithm = "novelty"
[evolution.novelty]
descriptors = [
    { measure = "time_in_area", area = "nest", min = 0, max = 60 },
    { measure = "time_in_area", min = 0, max = 60 },
]"#,
        "",
    );
    assert!(plain.contains("evolution.novelty.descriptors"), "{plain}");
    assert!(plain.contains("not computed"), "{plain}");
    // ... and with it, both go together.
    experiment(
        r#"algorithm = "novelty"
[evolution.novelty]
descriptors = [
    { measure = "time_in_area", area = "nest", min = 0, max = 60 },
    { measure = "time_in_area", min = 0, max = 60 },
]"#,
        "[behaviour]\nmeasures = [\"time_in_area\"]\narea = \"goal\"\n",
    );
}

/// 1 and 2 threads, stopped and resumed: the same bytes, archive.csv included, whose columns
/// name the areas; the cells hold each elite's ticks in the two areas.
#[test]
fn a_map_elites_run_over_two_areas_is_the_same_bytes_on_any_thread_count_and_resumed() {
    let (_dir, one) =
        same_bytes_on_any_thread_count_and_resumed("tiny-map-elites-areas.toml", &["archive.csv"]);
    let archive = String::from_utf8(read(&one.join("archive.csv"))).unwrap();
    let mut lines = archive.lines();
    assert_eq!(
        lines.next().unwrap(),
        "cell_time_in_area:nest,cell_time_in_area:field,time_in_area:nest,time_in_area:field,\
         fitness,generation,individual"
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    assert!(rows.len() > 1, "the archive fills more than one cell");
    for r in &rows {
        // Cells of 20 ticks over [0, 120].
        for d in 0..2 {
            assert_eq!(r[d], (r[2 + d] / 20.0).floor().min(5.0), "{r:?}");
        }
    }
    assert!(
        rows.iter().any(|r| r[2] != r[3]),
        "the two areas' times differ for some elite"
    );
}
