//! Food detectors (§5.2), eating by contact and by action, depletion, regeneration (§4.3),
//! metabolism decay (§5.3), the shock sensor, and dead creatures, with hand-computed values.

use crate::sim_common::{assert_close, put, world, Fixed, Still};
use berry_evolve::sim::controller::{Controller, MotorCommand};
use std::f64::consts::PI;

/// An apple of radius 1 at (50, 50) holding A = 1 and C = 2, bites ⟨0.4, 1, 0.5, 1⟩.
fn apple(extra_kind: &str, creature: &str) -> String {
    format!(
        r#"
[world.kinds.apple]
class = "food"
radius = 1
substance = [1, 0, 2, 0]
bite = [0.4, 1, 0.5, 1]
{extra_kind}

[[world.objects]]
kind = "apple"
position = [50, 50]

[world.start]
region = [200, 200, 250, 250]

[creature]
{creature}
"#
    )
}

/// Default layout: 16 smell, 2 whiskers, then the food detectors, shock, bias.
const FOOD: usize = 18;
const SHOCK: usize = 22;

#[test]
fn food_detectors_react_on_contact_with_food_that_holds_the_substance() {
    let mut w = world(&apple("depletes = false", ""), 1, 1);
    // Body radius 3 + apple radius 1 = 4: touching counts (eq. 1).
    put(&mut w, 0, 54.0, 50.0, 0.0);
    w.step(&mut [Still]);
    assert_eq!(w.creatures()[0].food_detectors, [true, false, true, false]);
    assert_eq!(w.observation(0)[FOOD..FOOD + 4], [1.0, 0.0, 1.0, 0.0]);
    put(&mut w, 0, 54.01, 50.0, 0.0);
    w.step(&mut [Still]);
    assert_eq!(w.creatures()[0].food_detectors, [false; 4]);
    assert_eq!(w.observation(0)[FOOD..FOOD + 4], [0.0; 4]);
}

#[test]
fn eating_by_contact_takes_a_bite_every_tick_until_empty() {
    let mut w = world(&apple("", ""), 1, 2);
    put(&mut w, 0, 54.0, 50.0, 0.0);
    // Tick by tick: A 1 -> 0.6 -> 0.2 -> 0 (last bite 0.2), C 2 -> 1.5 -> 1 -> 0.5 -> 0.
    let eaten_a = [0.4, 0.8, 1.0, 1.0, 1.0];
    let eaten_c = [0.5, 1.0, 1.5, 2.0, 2.0];
    let left_a = [0.6, 0.2, 0.0, 0.0, 0.0];
    let detector_a = [true, true, true, false, false];
    let detector_c = [true, true, true, true, false];
    for t in 0..5 {
        w.step(&mut [Still]);
        let c = &w.creatures()[0];
        let tick = format!("tick {}", t + 1);
        assert_close(c.eaten[0], eaten_a[t], &format!("{tick}: eaten A"));
        assert_close(c.eaten[2], eaten_c[t], &format!("{tick}: eaten C"));
        assert_eq!(c.eaten[1], 0.0, "{tick}: nothing of B to eat");
        assert_close(w.food()[0].amount[0], left_a[t], &format!("{tick}: A left"));
        assert_close(
            w.food()[0].amount[2],
            2.0 - eaten_c[t],
            &format!("{tick}: C left"),
        );
        // No decay configured: m is what was eaten.
        assert_eq!(c.metabolism, c.eaten, "{tick}");
        assert_eq!(c.food_detectors[0], detector_a[t], "{tick}: detector A");
        assert_eq!(c.food_detectors[2], detector_c[t], "{tick}: detector C");
    }
}

#[test]
fn without_depletion_the_food_feeds_forever() {
    let mut w = world(&apple("depletes = false", ""), 1, 3);
    put(&mut w, 0, 54.0, 50.0, 0.0);
    for _ in 0..3 {
        w.step(&mut [Still]);
    }
    assert_eq!(w.food()[0].amount, [1.0, 0.0, 2.0, 0.0]);
    assert_close(w.creatures()[0].eaten[0], 1.2, "A");
    assert_close(w.creatures()[0].eaten[2], 1.5, "C");
}

#[test]
fn eating_by_action_needs_an_eat_output_above_one_half() {
    let mut w = world(&apple("", "eating = \"action\""), 1, 4);
    put(&mut w, 0, 54.0, 50.0, 0.0);
    let eat = |e: f64| {
        Fixed(MotorCommand {
            left: 0.0,
            right: 0.0,
            eat: e,
        })
    };
    w.step(&mut [eat(0.5)]);
    w.step(&mut [eat(0.0)]);
    assert_eq!(w.creatures()[0].eaten, [0.0; 4], "0.5 is not above 0.5");
    assert!(w.creatures()[0].food_detectors[0], "in contact all along");
    w.step(&mut [eat(0.51)]);
    assert_close(w.creatures()[0].eaten[0], 0.4, "one bite of A");
    assert_close(w.food()[0].amount[0], 0.6, "A left");
}

#[test]
fn regeneration_runs_up_to_capacity() {
    let text = apple("capacity = [1, 0, 2, 0]\nregen = [0.3, 0, 0, 0]", "")
        .replace("substance = [1, 0, 2, 0]", "substance = [0, 0, 2, 0]");
    let mut w = world(&text, 1, 5);
    // The creature stays far away (start region), so nothing is eaten.
    for want in [0.3, 0.6, 0.9, 1.0, 1.0] {
        w.step(&mut [Still]);
        assert_close(w.food()[0].amount[0], want, "A after regeneration");
    }
    assert_close(w.food()[0].regenerated[0], 1.0, "regenerated in total");
}

#[test]
fn food_regenerates_before_creatures_act() {
    // An empty apple that regrows 0.3 A per tick with a creature on it: each tick the
    // regrowth comes first (§9), the detector sees it and the creature eats all of it.
    let text = apple("capacity = [1, 0, 0, 0]\nregen = [0.3, 0, 0, 0]", "")
        .replace("substance = [1, 0, 2, 0]", "substance = [0, 0, 0, 0]");
    let mut w = world(&text, 1, 6);
    put(&mut w, 0, 54.0, 50.0, 0.0);
    for t in 1..=3 {
        w.step(&mut [Still]);
        assert!(w.creatures()[0].food_detectors[0], "tick {t}");
        assert_eq!(w.food()[0].amount[0], 0.0, "tick {t}");
    }
    assert_close(w.creatures()[0].eaten[0], 0.9, "3 x 0.3");
}

#[test]
fn metabolism_decays_per_tick_and_per_lu_travelled() {
    // L = R = 0.1 RPT with w = 2: each wheel travels 2π · 2 · 0.1 = 0.4π LU per tick, a
    // straight move of M = 0.4π.
    let text = apple(
        "",
        "initial_metabolism = [10, 10, 10, 0.1]\n\
         decay_per_tick = [0.1, 0, 0, 1]\n\
         decay_per_lu = [0, 0.5, 0, 0]",
    );
    let mut w = world(&text, 1, 7);
    put(&mut w, 0, 150.0, 150.0, 0.0);
    let go = Fixed(MotorCommand {
        left: 0.1,
        right: 0.1,
        eat: 0.0,
    });
    w.step(&mut [go]);
    w.step(&mut [go]);
    let c = &w.creatures()[0];
    assert_close(c.travelled, 0.8 * PI, "travelled");
    assert_close(c.pose.position.x, 150.0 + 0.8 * PI, "x");
    assert_close(c.metabolism[0], 9.8, "A: 0.1 per tick");
    assert_close(c.metabolism[1], 10.0 - 0.5 * 0.8 * PI, "B: 0.5 per LU");
    assert_eq!(c.metabolism[2], 10.0, "C: no decay");
    assert_eq!(c.metabolism[3], 0.0, "D: 0.1 - 1 stops at 0");
}

#[test]
fn eating_is_added_before_decay_is_subtracted() {
    // m_A = 0, a bite of 0.4, decay 0.3 per tick: 0 + 0.4 - 0.3 = 0.1 (clamping before
    // adding would give 0.4).
    let text = apple("depletes = false", "decay_per_tick = [0.3, 0, 0, 0]");
    let mut w = world(&text, 1, 8);
    put(&mut w, 0, 54.0, 50.0, 0.0);
    w.step(&mut [Still]);
    assert_close(w.creatures()[0].metabolism[0], 0.1, "A");
    // With decay larger than the bite m stays at 0.
    let text = apple("depletes = false", "decay_per_tick = [0.5, 0, 0, 0]");
    let mut w = world(&text, 1, 8);
    put(&mut w, 0, 54.0, 50.0, 0.0);
    w.step(&mut [Still]);
    assert_eq!(w.creatures()[0].metabolism[0], 0.0);
}

#[test]
fn shock_sensor_reads_the_contact_of_the_previous_tick() {
    let text = r#"
[world.kinds.nettle]
class = "aversive"
radius = 2

[[world.objects]]
kind = "nettle"
position = [100, 100]

[world.start]
region = [200, 200, 250, 250]
"#;
    let mut w = world(text, 1, 9);
    put(&mut w, 0, 105.0, 100.0, 0.0); // 3 + 2 = 5: touching
    w.step(&mut [Still]);
    assert_eq!(
        w.observation(0)[SHOCK],
        0.0,
        "nothing before the first contact"
    );
    assert!(w.creatures()[0].shocked);
    w.step(&mut [Still]);
    assert_eq!(w.observation(0)[SHOCK], 1.0);
    put(&mut w, 0, 105.01, 100.0, 0.0);
    w.step(&mut [Still]);
    assert_eq!(w.observation(0)[SHOCK], 1.0, "the previous tick's shock");
    assert!(!w.creatures()[0].shocked);
    w.step(&mut [Still]);
    assert_eq!(w.observation(0)[SHOCK], 0.0);
    assert_eq!(w.creatures()[0].shock_ticks, 2);
}

#[test]
fn a_wall_stopping_the_move_shocks_only_with_wall_shock() {
    for wall_shock in [false, true] {
        let text = format!(
            "[world]\nwall_shock = {wall_shock}\n[world.start]\nregion = [200, 200, 250, 250]"
        );
        let mut w = world(&text, 1, 10);
        // Facing the left boundary wall from x = 10 at π LU per tick: blocked on tick 3.
        put(&mut w, 0, 10.0, 150.0, 180.0);
        let go = Fixed(MotorCommand {
            left: 0.25,
            right: 0.25,
            eat: 0.0,
        });
        let mut shocked = Vec::new();
        for _ in 0..4 {
            w.step(&mut [go]);
            shocked.push(w.creatures()[0].shocked);
        }
        let x = w.creatures()[0].pose.position.x;
        assert!(
            (3.0..3.01).contains(&x),
            "stopped against the wall, x = {x}"
        );
        let want = if wall_shock {
            vec![false, false, true, true]
        } else {
            vec![false; 4]
        };
        assert_eq!(shocked, want, "wall_shock = {wall_shock}");
    }
}

/// Counts how often it is asked.
struct Counting(u32, MotorCommand);

impl Controller for Counting {
    fn act(&mut self, _: &[f64]) -> MotorCommand {
        self.0 += 1;
        self.1
    }
}

#[test]
fn dead_creatures_neither_act_nor_block() {
    let mut w = world("[world.start]\nregion = [200, 200, 250, 250]", 2, 11);
    put(&mut w, 0, 100.0, 100.0, 0.0);
    put(&mut w, 1, 110.0, 100.0, 180.0);
    w.kill(0);
    let go = MotorCommand {
        left: 0.25,
        right: 0.25,
        eat: 0.0,
    };
    let mut controllers = [Counting(0, go), Counting(0, go)];
    for _ in 0..5 {
        w.step(&mut controllers);
    }
    assert_eq!(
        controllers[0].0, 0,
        "a dead creature's controller is not called"
    );
    assert_eq!(controllers[1].0, 5);
    assert_eq!(w.creatures()[0].age, 0);
    assert_eq!(w.creatures()[0].pose.position.x, 100.0);
    // Five moves of π LU straight through where the dead body lies.
    assert_close(w.creatures()[1].pose.position.x, 110.0 - 5.0 * PI, "x");
}

#[test]
fn a_metabolism_spread_draws_each_creatures_birth_state_after_the_world() {
    let plain = apple("", "initial_metabolism = [0.5, 0, 0, 1]");
    let spread = apple(
        "",
        "initial_metabolism = [0.5, 0, 0, 1]\ninitial_metabolism_spread = [1, 0, 0.25, 2]",
    );
    let mut seen = Vec::new();
    for seed in 1..=20 {
        let (p, s) = (world(&plain, 3, seed), world(&spread, 3, seed));
        for (a, b) in p.creatures().iter().zip(s.creatures()) {
            // The world's own draws come first: same poses and food with or without it.
            assert_eq!(a.pose, b.pose);
            assert_eq!(a.metabolism, [0.5, 0.0, 0.0, 1.0]);
            let m = b.metabolism;
            assert!((0.5..1.5).contains(&m[0]), "{m:?}");
            assert_eq!(m[1], 0.0);
            assert!((0.0..0.25).contains(&m[2]), "{m:?}");
            assert!((1.0..3.0).contains(&m[3]), "{m:?}");
            seen.push(m);
        }
        assert_eq!(p.food()[0].position, s.food()[0].position);
    }
    // Drawn for each creature and each world, not once.
    assert!(seen.windows(2).all(|w| w[0] != w[1]));
}
