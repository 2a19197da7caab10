//! The measures the science table used to compute in scripts (`eaten`, `still_share`,
//! `richest_side_first`) on hand-computed lives of a scripted creature: one standing on a
//! meal, one parked, spinning or driving, and one choosing a side of its start line.

use berry_evolve::evo::fitness::{LifePlan, LifeScore, MEASURE_COUNT};
use berry_evolve::evo::TrialPlan;
use berry_evolve::experiment::{Experiment, Measure};
use berry_evolve::seed::{stream, Generation, IndividualId, Purpose, Seed, TrialIndex};
use berry_evolve::sim::controller::{Controller, MotorCommand};
use berry_evolve::sim::world::World;
use std::path::Path;

/// An empty 400 × 400 arena; the creature starts near (100, 200) facing right (heading 0°),
/// wheel w = 2 LU, body radius 3 LU. `OBJECTS` is replaced by each test's food.
const TEXT: &str = r#"
name = "measures"
seed = 3

[world]
arena = [400.0, 400.0]
OBJECTS
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
measures = ["eaten", "still_share", "richest_side_first", "forward_share"]
"#;

/// A food kind `name` of radius `radius` holding `substance`, bitten `bite` per tick, and
/// one object of it at (x, y).
fn food(name: &str, radius: f64, substance: [f64; 4], bite: [f64; 4], at: [f64; 2]) -> String {
    format!(
        "[world.kinds.{name}]\nclass = \"food\"\nradius = {radius:?}\nsubstance = {substance:?}\n\
         bite = {bite:?}\nregen = [0.0, 0.0, 0.0, 0.0]\n\
         [[world.objects]]\nkind = \"{name}\"\nposition = {at:?}\n"
    )
}

fn experiment(objects: &str) -> Experiment {
    Experiment::from_toml(
        &TEXT.replace("OBJECTS", objects),
        Path::new("measures.toml"),
    )
    .unwrap_or_else(|e| panic!("{e}"))
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

/// What a scripted life gave: the start, the measures, and each tick's end position with
/// whether some food object had been bitten by then.
struct Life {
    start: [f64; 2],
    measures: [f64; MEASURE_COUNT],
    path: Vec<([f64; 2], bool)>,
}

impl Life {
    fn get(&self, which: Measure) -> f64 {
        self.measures[which.index()]
    }
}

/// Lives the script as evaluation does.
fn live(e: &Experiment, script: Vec<(f64, f64)>) -> Life {
    let rng = stream(
        Seed(1),
        Purpose::Demo,
        Generation(0),
        IndividualId(0),
        TrialIndex(0),
    );
    let mut world = World::new(&e.world, &e.creature, 1, rng).unwrap();
    let plan = LifePlan::new(&TrialPlan::new(e), &world);
    assert!(plan.needs_world_every_tick() && plan.needs_bites());
    plan.prepare(&mut world);
    let mut score = LifeScore::start(&plan, &world, 0);
    let start = world.creatures()[0].pose.position;
    let ticks = script.len();
    let mut controller = [Script(script, 0)];
    let mut path = Vec::new();
    for _ in 0..ticks {
        world.step(&mut controller);
        let c = &world.creatures()[0];
        score.record_tick(&c.metabolism, c.shocked);
        score.record_world(&plan, &world, 0);
        let p = world.creatures()[0].pose.position;
        path.push(([p.x, p.y], world.bitten(0).iter().any(|&b| b)));
    }
    let (_, measures) = score.finish_in(&plan, &world, 0);
    Life {
        start: [start.x, start.y],
        measures,
        path,
    }
}

/// One tick at equal signals s moves 2π·w·s LU (eq. 28–30, w = 2).
fn signal_for(lu_per_tick: f64) -> f64 {
    lu_per_tick / (std::f64::consts::TAU * 2.0)
}

/// A meal of 4 A and 1 B, bitten 0.5 A and 0.25 B a tick, of radius 10 at (116, 201): out of
/// reach at the start (14 LU or more from the centre, 13 needed), touched after a first tick
/// of 4 LU. Eating on that tick and 4 more, it takes 2.5 A and all of B (1.0, used up after 4
/// ticks): 3.5.
#[test]
fn eaten_sums_the_substance_taken_of_every_type() {
    let e = experiment(&food(
        "meal",
        10.0,
        [4.0, 1.0, 0.0, 0.0],
        [0.5, 0.25, 0.0, 0.0],
        [116.0, 201.0],
    ));
    let go = signal_for(4.0);
    let mut script = vec![(go, go)];
    script.extend([(0.0, 0.0); 4]);
    let life = live(&e, script);
    assert_eq!(life.get(Measure::Eaten), 3.5);
    // Far from the meal nothing is eaten.
    let e = experiment(&food(
        "meal",
        2.0,
        [4.0, 1.0, 0.0, 0.0],
        [0.5, 0.25, 0.0, 0.0],
        [300.0, 300.0],
    ));
    assert_eq!(live(&e, vec![(0.0, 0.0); 5]).get(Measure::Eaten), 0.0);
}

/// Parked or spinning on the spot: still on every tick; driving at 1.26 LU a tick: never.
/// 6 ticks forward, 4 back and 2 parked: still on 2 of 12.
#[test]
fn still_share_counts_the_ticks_that_moved_less_than_the_still_step() {
    let e = experiment("");
    for (what, signals) in [("parked", (0.0, 0.0)), ("spinning", (0.1, -0.1))] {
        let life = live(&e, vec![signals; 10]);
        assert_eq!(life.get(Measure::StillShare), 1.0, "{what}");
    }
    assert_eq!(live(&e, vec![(0.1, 0.1); 10]).get(Measure::StillShare), 0.0);
    let mut script = vec![(0.1, 0.1); 6];
    script.extend([(-0.1, -0.1); 4]);
    script.extend([(0.0, 0.0); 2]);
    let life = live(&e, script);
    assert_eq!(life.get(Measure::StillShare), 2.0 / 12.0);
    // 0.04 LU a tick is still (below 0.05 LU), 0.06 is not; reversing moves.
    let crawl = signal_for(0.04);
    assert_eq!(
        live(&e, vec![(crawl, crawl); 4]).get(Measure::StillShare),
        1.0
    );
    let creep = signal_for(0.06);
    assert_eq!(
        live(&e, vec![(creep, creep); 4]).get(Measure::StillShare),
        0.0
    );
    assert_eq!(
        live(&e, vec![(-creep, -creep); 4]).get(Measure::StillShare),
        0.0
    );
}

/// A crumb far away (first in the world's food) and the richest food, 4 A in a disc of
/// radius 30 at (150, 215): 13–15 LU to the creature's right of its start line (y grows
/// downwards; facing +x, its right is +y), so straying means going above y0 − 6.5…7.5.
fn choice() -> Experiment {
    experiment(&format!(
        "{}{}",
        food(
            "crumb",
            0.0,
            [0.0, 0.1, 0.0, 0.0],
            [0.0, 0.1, 0.0, 0.0],
            [350.0, 50.0]
        ),
        food(
            "goal",
            30.0,
            [4.0, 0.0, 0.0, 0.0],
            [0.5, 0.0, 0.0, 0.0],
            [150.0, 215.0]
        ),
    ))
}

/// The first tick on which the goal had been bitten, and the smallest y before it.
fn first_bite(life: &Life) -> (Option<usize>, f64) {
    let bite = life.path.iter().position(|(_, b)| *b);
    let before = &life.path[..bite.unwrap_or(life.path.len())];
    let top = before
        .iter()
        .map(|(p, _)| p[1])
        .fold(life.start[1], f64::min);
    (bite, top)
}

/// Wheel signals: (0.05, 0.15) turns 36° a tick towards −y (left), (0.15, 0.05) as much
/// towards +y; (0.1, 0.1) drives 1.26 LU straight.
const LEFT: (f64, f64) = (0.05, 0.15);
const RIGHT: (f64, f64) = (0.15, 0.05);
const AHEAD: (f64, f64) = (0.1, 0.1);

/// Straight ahead along its start line it touches the goal's disc and bites it, never
/// leaving the line: 1. Standing still it never bites: 0.
#[test]
fn richest_side_first_is_one_when_it_goes_straight_to_the_richest_food() {
    let e = choice();
    let life = live(&e, vec![AHEAD; 25]);
    let (bite, top) = first_bite(&life);
    assert!(bite.is_some(), "{:?}", life.path);
    assert_eq!(top, life.start[1], "a straight drive keeps to the line");
    assert_eq!(life.get(Measure::RichestSideFirst), 1.0);
    assert_eq!(
        live(&e, vec![(0.0, 0.0); 25]).get(Measure::RichestSideFirst),
        0.0
    );
}

/// Turning left and driving up more than 7.5 LU above its start line before coming round
/// to the goal and biting it: 0 (the wrong side first). Straying there only after the bite
/// does not count: 1.
#[test]
fn richest_side_first_is_zero_when_it_strays_to_the_other_side_first() {
    let e = choice();
    let mut script = vec![LEFT];
    script.extend([AHEAD; 14]);
    script.extend([RIGHT; 2]);
    script.extend([AHEAD; 25]);
    let life = live(&e, script);
    let (bite, top) = first_bite(&life);
    assert!(bite.is_some(), "it reaches the goal: {:?}", life.path);
    assert!(top < life.start[1] - 7.5, "it strayed first: {top}");
    assert_eq!(life.get(Measure::RichestSideFirst), 0.0);

    let mut script = vec![AHEAD; 25];
    script.extend([LEFT; 2]);
    script.extend([AHEAD; 20]);
    let life = live(&e, script);
    let (bite, top) = first_bite(&life);
    let end = life.path.last().unwrap().0;
    assert!(bite.is_some() && top == life.start[1]);
    assert!(end[1] < life.start[1] - 7.5, "it strays after: {end:?}");
    assert_eq!(life.get(Measure::RichestSideFirst), 1.0);
}
