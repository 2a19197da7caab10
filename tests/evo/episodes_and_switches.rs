//! Lives of several episodes (`[evaluation] episodes_per_life`) and payoff switches
//! (`[evaluation.switch]`): one episode is the trial of before; a recurrent brain's state
//! carries over from episode to episode and is new for each life; switch draws are per life,
//! deterministic and inside their ranges; a switch exchanges the two kinds' payoffs and not
//! their place; lockstep equals the single-trial path; the switch measures on a hand-made
//! life; bad tables refused naming the key.

use crate::door::{evaluate_group, evaluate_population, run_trial};
use berry_evolve::brain::genome::Genome;
use berry_evolve::brain::{Brain, BrainController};
use berry_evolve::evo::episodes::{EpisodeChoices, Life, LifeOrigin, Schedule};
use berry_evolve::evo::fitness::{LifePlan, LifeScore};
use berry_evolve::evo::life::TrialOutcome;
use berry_evolve::evo::lockstep;
use berry_evolve::evo::trial::{TickObserver, TrialId};
use berry_evolve::evo::TrialPlan;
use berry_evolve::experiment::{Experiment, Measure};
use berry_evolve::seed::{stream, uniform, Generation, IndividualId, Purpose, TrialIndex};
use berry_evolve::sim::world::World;
use std::path::Path;

/// Two goals on the line y = 60, left (pays 2 A as written) and right (a trace of C), some
/// scattered crumbs so that episode worlds differ, creatures starting left of the left goal
/// heading right. `extra` is appended (its tables must not be in the base).
fn world(extra: &str) -> String {
    format!(
        r#"name = "episodes"
seed = 9

[world]
arena = [120.0, 120.0]

[world.kinds.left_goal]
class = "food"
radius = 4.0
substance = [2.0, 0.0, 0.0, 0.0]
bite = [0.5, 0.0, 0.0, 0.0]
odour = [1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]
intensity = 1.0
[world.kinds.right_goal]
class = "food"
radius = 4.0
substance = [0.0, 0.0, 0.01, 0.0]
bite = [0.0, 0.0, 0.01, 0.0]
odour = [1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]
intensity = 1.0
[world.kinds.crumb]
class = "food"
substance = [0.0, 0.5, 0.0, 0.0]

[[world.objects]]
kind = "left_goal"
position = [30.0, 60.0]
[[world.objects]]
kind = "right_goal"
position = [90.0, 60.0]
[[world.place]]
kind = "crumb"
count = 8
region = [0.0, 0.0, 120.0, 40.0]

[world.start]
region = [12.0, 58.0, 16.0, 62.0]
heading = 0.0

{extra}
"#
    )
}

fn load(text: &str) -> Experiment {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/episodes.toml");
    Experiment::from_toml(text, &path).unwrap_or_else(|e| panic!("{e}"))
}

fn refused(text: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/episodes.toml");
    match Experiment::from_toml(text, &path) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e.to_string(),
    }
}

/// Random parameters for `e`'s brain, from stream `k`.
fn genome(e: &Experiment, k: u64) -> Genome {
    let n = e.topology().parameter_count();
    let mut rng = stream(
        e.seed(),
        Purpose::Baseline,
        Generation(k),
        IndividualId(0),
        TrialIndex(0),
    );
    Genome::new((0..n).map(|_| uniform(&mut rng, -1.5, 1.5)).collect())
}

fn same(a: &TrialOutcome, b: &TrialOutcome, what: &str) {
    assert_eq!(a.score.to_bits(), b.score.to_bits(), "{what}: score");
    assert_eq!(
        a.metabolism.map(f64::to_bits),
        b.metabolism.map(f64::to_bits),
        "{what}: metabolism"
    );
    assert_eq!(a.shocked_ticks, b.shocked_ticks, "{what}");
    assert_eq!(a.non_finite, b.non_finite, "{what}");
    assert_eq!(
        a.measures.map(f64::to_bits),
        b.measures.map(f64::to_bits),
        "{what}: measures"
    );
}

const SWITCHED: &str = r#"
[brain]
kind = "mlp"
hidden = [4]

[fitness]
weights = [1.0, 1.0, 0.0, 0.0]
forward_bonus = 0.01
choice_bonus = 3.0

[behaviour]
measures = ["adapted_choice", "good_bite_share", "eaten", "distinct_food"]

[evolution]
population = 6

[evaluation]
trials = 19
ticks = 60
episodes_per_life = 4

[evaluation.switch]
kinds = ["left_goal", "right_goal"]
start = "random"
at = [[2, 3]]
"#;

/// `episodes_per_life = 1` written out is the experiment without the key: the same identity
/// (hash), the same file written to a run folder, the same trial outcomes.
#[test]
fn one_episode_per_life_is_the_trial_of_before() {
    let plain = world("[brain]\nkind = \"recurrent\"\nhidden = [3]\n\n[evaluation]\nticks = 50\n");
    let one = plain.replace("ticks = 50\n", "ticks = 50\nepisodes_per_life = 1\n");
    let (a, b) = (load(&plain), load(&one));
    assert_eq!(a.config_hash(), b.config_hash());
    assert_eq!(a.to_toml(), b.to_toml());
    let topology = a.topology();
    for t in 0..3 {
        let g = [genome(&a, t)];
        let x = run_trial(&a, &topology, &g, Generation(1), 0, TrialIndex(t)).unwrap();
        let y = run_trial(&b, &topology, &g, Generation(1), 0, TrialIndex(t)).unwrap();
        same(&x[0], &y[0], "K = 1");
    }
}

/// Lives one episode in `world` by hand with `controller` (the loop of the trial path: step,
/// record while alive), returning its score.
fn episode_by_hand(e: &Experiment, mut world: World, controller: &mut BrainController) -> f64 {
    let plan = LifePlan::new(&TrialPlan::new(e), &world);
    plan.prepare(&mut world);
    let mut score = LifeScore::start(&plan, &world, 0);
    for _ in 0..e.evaluation.ticks {
        world.step(std::slice::from_mut(controller));
        let c = &world.creatures()[0];
        if !c.alive {
            break;
        }
        score.record_tick(&c.metabolism, c.shocked);
        if plan.needs_world_every_tick() {
            score.record_world(&plan, &world, 0);
        }
    }
    score.finish_in(&plan, &world, 0).0
}

/// A recurrent brain (Elman, CTRNN) keeps its state from one episode to the next: a life of 3
/// episodes scores what one controller, built at the start of the life and never reset,
/// scores living the three episode worlds by hand; resetting it between episodes scores
/// otherwise. Each life starts with a new brain: the life of trial 1 is the same whether or
/// not trial 0 was lived before it, and equals a fresh controller's.
#[test]
fn a_recurrent_brain_carries_its_state_across_episodes_not_across_lives() {
    for brain in [
        "kind = \"recurrent\"\nhidden = [5]",
        "kind = \"ctrnn\"\nneurons = 5",
    ] {
        let e = load(&world(&format!(
            "[creature.inputs]\nwhiskers = true\n\n[brain]\n{brain}\n\n[fitness]\nforward_bonus = 1.0\n\n\
             [evaluation]\nticks = 40\nepisodes_per_life = 3\n"
        )));
        let topology = e.topology();
        let g = genome(&e, 3);
        for t in [0u64, 1] {
            let life = run_trial(
                &e,
                &topology,
                std::slice::from_ref(&g),
                Generation(2),
                0,
                TrialIndex(t),
            )
            .unwrap()[0];
            let plan = TrialPlan::new(&e);
            let origin = LifeOrigin::trial(&plan, Generation(2), 0, TrialIndex(t));
            let worlds = Life::new(&plan, origin);
            let by_hand = |reset: bool| {
                let brain = Brain::new(&topology, &g.parameters).unwrap();
                let mut c =
                    BrainController::new(brain, e.creature.max_rpt, e.creature.eats_by_action());
                let mut total = 0.0;
                for episode in 0..3 {
                    let w = worlds.world(1, episode).unwrap();
                    total += episode_by_hand(&e, w, &mut c);
                    if reset {
                        c.reset();
                    }
                }
                total
            };
            assert_eq!(life.score.to_bits(), by_hand(false).to_bits(), "{brain}");
            assert_ne!(life.score, by_hand(true), "{brain}: state should matter");
        }
    }
}

/// Each switch is drawn per life inside its range, the same every time; lives differ; a
/// random start is exchanged in about half of the lives.
#[test]
fn switch_draws_are_per_life_deterministic_and_inside_the_range() {
    let e = load(&world(
        "[evaluation]\nepisodes_per_life = 9\n\n[evaluation.switch]\n\
         kinds = [\"left_goal\", \"right_goal\"]\nstart = \"random\"\nat = [[3, 5], [7, 7]]\n",
    ));
    let plan = TrialPlan::new(&e);
    let mut firsts = std::collections::BTreeSet::new();
    let mut exchanged_at_start = 0;
    for t in 0..200 {
        let origin = LifeOrigin::trial(&plan, Generation(4), 0, TrialIndex(t));
        let s = Schedule::draw(&plan, origin);
        assert_eq!(s, Schedule::draw(&plan, origin), "deterministic");
        let switches = s.switches();
        assert_eq!(switches.len(), 2);
        assert!((3..=5).contains(&switches[0]), "{switches:?}");
        assert_eq!(switches[1], 7);
        firsts.insert(switches[0]);
        exchanged_at_start += usize::from(s.exchanged[0]);
        // Exchanged flips exactly at the switches (episode numbers from 1).
        for ep in 1..9 {
            let flips = s.exchanged[ep] != s.exchanged[ep - 1];
            assert_eq!(flips, switches.contains(&(ep as u64 + 1)));
        }
    }
    assert_eq!(firsts.len(), 3, "every episode of 3..=5 drawn: {firsts:?}");
    assert!(
        (70..=130).contains(&exchanged_at_start),
        "{exchanged_at_start}"
    );
    // Validation worlds draw their own.
    let a = Schedule::draw(
        &plan,
        LifeOrigin::trial(&plan, Generation(0), 0, TrialIndex(0)),
    );
    let lives: Vec<Schedule> = (0..20)
        .map(|t| Schedule::draw(&plan, LifeOrigin::validation(TrialIndex(t))))
        .collect();
    assert!(lives.iter().any(|s| *s != a));
}

/// After a switch the left goal holds what the right one held and bites as it did, and vice
/// versa, at the same places with the same smell; the crumbs are untouched; episodes of a
/// life are different worlds, the first is the trial world of a one-episode life.
#[test]
fn a_switch_exchanges_the_payoffs_not_the_look() {
    let e = load(&world(
        "[evaluation]\nepisodes_per_life = 3\n\n[evaluation.switch]\n\
         kinds = [\"left_goal\", \"right_goal\"]\nat = [[2, 2]]\n",
    ));
    let plan = TrialPlan::new(&e);
    let life = Life::new(
        &plan,
        LifeOrigin::trial(&plan, Generation(0), 0, TrialIndex(0)),
    );
    assert_eq!(life.schedule().exchanged, vec![false, true, true]);
    let [w0, w1, w2] = [0, 1, 2].map(|k| life.world(1, k).unwrap());
    let goal = |w: &World, name: &str| {
        let kind = w.kinds().iter().position(|k| k == name).unwrap();
        w.food().iter().find(|f| f.kind == kind).unwrap().clone()
    };
    for (name, other) in [("left_goal", "right_goal"), ("right_goal", "left_goal")] {
        let (before, after) = (goal(&w0, name), goal(&w1, name));
        let was = goal(&w0, other);
        assert_eq!(after.amount, was.amount, "{name}");
        assert_eq!(after.bite, was.bite, "{name}");
        assert_eq!(after.position, before.position, "{name}");
        assert_eq!(after.smell, before.smell, "{name}");
        assert_eq!(after.colour, before.colour, "{name}");
    }
    let crumbs = |w: &World| -> Vec<[f64; 2]> {
        w.food()
            .iter()
            .filter(|f| w.kinds()[f.kind] == "crumb")
            .map(|f| [f.position.x, f.position.y])
            .collect()
    };
    assert_ne!(crumbs(&w1), crumbs(&w2), "episode worlds differ");
    let one = load(&world(""));
    let first = berry_evolve::sim::world::World::build(
        berry_evolve::sim::world::ValidSpecs::new(&one.world, &one.creature).unwrap(),
        1,
        berry_evolve::evo::life::trial_stream(
            &TrialPlan::new(&one),
            Generation(0),
            0,
            TrialIndex(0),
        ),
    )
    .unwrap();
    assert_eq!(crumbs(&w0), crumbs(&first));
}

/// With K > 1 and switches, lockstep (stateless brains, several lives at once) gives each
/// life the bits of the single-trial path, measures included; and evaluating the population
/// (shared worlds, on 1 and 2 threads) equals evaluating group by group.
#[test]
fn lockstep_equals_single_trials_with_episodes_and_switches() {
    let e = load(&world(SWITCHED));
    assert_eq!(
        lockstep::lanes(&e.topology()),
        Some(lockstep::Lanes::Shared)
    );
    lockstep_equals_single_trials(&e);
}

/// A plastic brain runs in lockstep with one copy per life (`lockstep::WorldBrains`): each
/// life, its weights drawn anew from the life's own stream, changing within it and carried
/// over its episodes, gets the bits of the single-trial path, with switches (K = 4) and
/// without (K = 1).
#[test]
fn plastic_brains_in_lockstep_equal_single_trials() {
    let plastic = SWITCHED.replace(
        "hidden = [4]\n",
        "hidden = [4]\nplasticity = \"neuromodulated\"\ngranularity = \"synapse\"\n\
         initial_weights = \"random\"\nmodulators = [\"food_a\", \"food_c\", \"neurons\"]\n",
    );
    assert_ne!(plastic, SWITCHED);
    for text in [
        plastic.clone(),
        plastic.replace("episodes_per_life = 4", "episodes_per_life = 1")
            .replace("at = [[2, 3]]\n", "")
            .replace("[evaluation.switch]\nkinds = [\"left_goal\", \"right_goal\"]\nstart = \"random\"\n", "")
            .replace("\"adapted_choice\", \"good_bite_share\", ", "")
            .replace("choice_bonus = 3.0\n", ""),
    ] {
        let e = load(&world(&text));
        assert_eq!(lockstep::lanes(&e.topology()), Some(lockstep::Lanes::PerWorld));
        lockstep_equals_single_trials(&e);
    }
}

/// Each genome of a population of 6 lives every chunk of trials in lockstep with the bits
/// of the single-trial path; evaluating the population on 1 and 2 threads equals evaluating
/// group by group.
fn lockstep_equals_single_trials(e: &Experiment) {
    let topology = e.topology();
    let population: Vec<Genome> = (0..6).map(|k| genome(e, k)).collect();
    let mut bites = 0.0;
    for (g, genome) in population.iter().enumerate() {
        let genomes = std::slice::from_ref(genome);
        for chunk in lockstep::chunks(e.evaluation.trials) {
            let together = lockstep::run_trials(
                &TrialPlan::new(e),
                &topology,
                genomes,
                Generation(3),
                g as u64,
                chunk.clone(),
            )
            .unwrap();
            for (t, outcomes) in chunk.zip(&together) {
                let alone = run_trial(
                    e,
                    &topology,
                    genomes,
                    Generation(3),
                    g as u64,
                    TrialIndex(t),
                )
                .unwrap();
                same(&alone[0], &outcomes[0], &format!("genome {g} trial {t}"));
                bites += alone[0].measures[Measure::DistinctFood.index()];
            }
        }
    }
    assert!(bites > 0.0, "the case eats something");
    let serial: Vec<_> = (0..6)
        .flat_map(|g| {
            evaluate_group(e, &topology, &population[g..g + 1], Generation(3), g as u64).unwrap()
        })
        .collect();
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let together = pool
            .install(|| evaluate_population(e, &topology, &population, Generation(3)))
            .unwrap();
        assert_eq!(together, serial, "{threads} threads");
    }
}

/// A creature driving straight right (every weight 0.5, only the bias input: both motors
/// equal) bites the left goal first, then the right one, in every episode. Left pays in
/// episodes 1-2, right after the switch before episode 3 (of 5): first choices correct,
/// correct, wrong, wrong, wrong; `adapted_choice` counts episodes 2, 4 and 5: 1/3. Bites after
/// each phase's first: phase 1 right, left + right (1 good of 3), phase 2 right, left + right,
/// left + right (3 good of 5): `good_bite_share` 4/8.
#[test]
fn the_switch_measures_on_a_hand_made_life() {
    let e = load(&world(
        "[creature.inputs]\nsmell = false\nwhiskers = false\nfood = false\nshock = false\n\n\
         [brain]\nkind = \"mlp\"\nhidden = []\n\n\
         [behaviour]\nmeasures = [\"adapted_choice\", \"good_bite_share\", \"distinct_food\"]\n\n\
         [evaluation]\nticks = 60\nepisodes_per_life = 5\n\n[evaluation.switch]\n\
         kinds = [\"left_goal\", \"right_goal\"]\nat = [[3, 3]]\n",
    ));
    let topology = e.topology();
    let g = Genome::new(vec![0.5; topology.parameter_count()]);
    let life = run_trial(&e, &topology, &[g], Generation(0), 0, TrialIndex(0)).unwrap()[0];
    assert_eq!(life.measures[Measure::AdaptedChoice.index()], 1.0 / 3.0);
    assert_eq!(life.measures[Measure::GoodBiteShare.index()], 0.5);
    // Both goals and no crumb (they lie off the line) in every episode.
    assert_eq!(life.measures[Measure::DistinctFood.index()], 2.0);

    // The same bookkeeping on episodes given by hand, with a phase whose first episode
    // bites nothing (its first bite then comes in the next episode).
    let e = load(&world(
        "[evaluation]\nepisodes_per_life = 4\n\n[evaluation.switch]\n\
         kinds = [\"left_goal\", \"right_goal\"]\nat = [[2, 2]]\n",
    ));
    let plan = TrialPlan::new(&e);
    let l = Life::new(
        &plan,
        LifeOrigin::trial(&plan, Generation(0), 0, TrialIndex(0)),
    );
    let c = |first: Option<bool>, bites: u64, good: u64| {
        let o = run_trial(
            &e,
            &e.topology(),
            &[genome(&e, 0)],
            Generation(0),
            0,
            TrialIndex(0),
        )
        .unwrap()[0];
        (o, Some(EpisodeChoices { first, bites, good }))
    };
    let episodes = [
        c(Some(true), 3, 2),  // phase 1: 2 counted, 1 good
        c(None, 0, 0),        // phase 2 starts: nothing bitten
        c(Some(false), 2, 1), // the phase's first bite (wrong), then 1 good
        c(Some(true), 2, 2),  // 2 counted, 2 good
    ];
    let measures = [Measure::AdaptedChoice, Measure::GoodBiteShare];
    let o = l.outcome(&measures, &episodes);
    // Counted episodes: 3 (wrong) and 4 (right).
    assert_eq!(o.measures[Measure::AdaptedChoice.index()], 0.5);
    assert_eq!(o.measures[Measure::GoodBiteShare.index()], 4.0 / 5.0);
    assert_eq!(l.correct_choices(&episodes), vec![true, false, false, true]);
}

/// `[fitness] choice_bonus` adds its weight once per episode whose first choice paid: a
/// brain without senses drives straight right into the left goal every episode, which pays
/// in episodes 1 and 2 and not after the switch before episode 3, so the bonus adds 2 × 7
/// to the life's score and nothing else changes.
#[test]
fn choice_bonus_pays_each_correct_first_choice() {
    let text = |bonus: &str| {
        world(&format!(
            "[creature.inputs]\nsmell = false\nwhiskers = false\nfood = false\nshock = false\n\n\
             [brain]\nkind = \"mlp\"\nhidden = []\n\n[fitness]\n{bonus}\n\
             [behaviour]\nmeasures = [\"adapted_choice\"]\n\n\
             [evaluation]\nticks = 60\nepisodes_per_life = 5\n\n[evaluation.switch]\n\
             kinds = [\"left_goal\", \"right_goal\"]\nat = [[3, 3]]\n"
        ))
    };
    let (plain, paid) = (load(&text("")), load(&text("choice_bonus = 7.0")));
    let topology = plain.topology();
    let g = [Genome::new(vec![0.5; topology.parameter_count()])];
    let life =
        |e: &Experiment| run_trial(e, &topology, &g, Generation(0), 0, TrialIndex(0)).unwrap()[0];
    let (a, b) = (life(&plain), life(&paid));
    assert_eq!(a.measures[Measure::AdaptedChoice.index()], 1.0 / 3.0);
    assert!(
        (b.score - a.score - 14.0).abs() < 1e-9,
        "{} vs {}",
        b.score,
        a.score
    );
    assert_eq!(a.measures.map(f64::to_bits), b.measures.map(f64::to_bits));
    assert_eq!(
        a.metabolism.map(f64::to_bits),
        b.metabolism.map(f64::to_bits)
    );
}

/// Bad `[evaluation.switch]` tables and their neighbours are refused naming the key.
#[test]
fn bad_switch_tables_are_refused_naming_the_key() {
    let with = |k: u64, switch: &str| {
        world(&format!(
            "[evaluation]\nepisodes_per_life = {k}\n\n[evaluation.switch]\n{switch}\n"
        ))
    };
    let kinds = "kinds = [\"left_goal\", \"right_goal\"]\n";
    for (text, key, word) in [
        (
            with(4, "kinds = [\"left_goal\", \"nowhere\"]"),
            "evaluation.switch.kinds",
            "nowhere",
        ),
        (
            with(4, "kinds = [\"left_goal\"]"),
            "evaluation.switch.kinds",
            "two distinct",
        ),
        (
            with(4, "kinds = [\"left_goal\", \"left_goal\"]"),
            "evaluation.switch.kinds",
            "two distinct",
        ),
        (
            with(4, &format!("{kinds}at = [[1, 2]]")),
            "evaluation.switch.at",
            "outside 2..=4",
        ),
        (
            with(4, &format!("{kinds}at = [[3, 5]]")),
            "evaluation.switch.at",
            "outside 2..=4",
        ),
        (
            with(4, &format!("{kinds}at = [[3, 2]]")),
            "evaluation.switch.at",
            "lo 3 > hi 2",
        ),
        (
            with(6, &format!("{kinds}at = [[2, 4], [4, 5]]")),
            "evaluation.switch.at",
            "overlaps",
        ),
        (
            with(6, &format!("{kinds}at = [[4, 5], [2, 3]]")),
            "evaluation.switch.at",
            "in order",
        ),
        (with(1, kinds), "evaluation.switch", "episodes_per_life"),
        (
            with(4, "kinds = [\"left_goal\", \"right_goal\"]\nstart = \"sometimes\""),
            "start",
            "as_written",
        ),
        (
            world("[evaluation]\nepisodes_per_life = 0\n"),
            "evaluation.episodes_per_life",
            "at least",
        ),
        (
            world("[evolution]\npopulation = 4\n\n[evaluation]\nepisodes_per_life = 2\ngroup_size = 2\n"),
            "evaluation.episodes_per_life",
            "group_size",
        ),
        (
            world("[behaviour]\nmeasures = [\"adapted_choice\"]\n"),
            "behaviour.measures",
            "[evaluation.switch]",
        ),
        (
            world("[fitness]\nchoice_bonus = 5.0\n"),
            "fitness.choice_bonus",
            "[evaluation.switch]",
        ),
    ] {
        let message = refused(&text);
        assert!(message.contains(key), "does not name `{key}`: {message}");
        assert!(message.contains(word), "does not say `{word}`: {message}");
    }
    // Two kinds that pay the same cannot tell a paying one.
    let same = world(&format!(
        "[evaluation]\nepisodes_per_life = 2\n\n[evaluation.switch]\n{kinds}"
    ))
    .replace(
        "substance = [0.0, 0.0, 0.01, 0.0]",
        "substance = [2.0, 0.0, 0.0, 0.0]",
    );
    let message = refused(&same);
    assert!(
        message.contains("evaluation.switch.kinds") && message.contains("same"),
        "{message}"
    );
}

/// A run of the T-maze with a switch (tests/fixtures/t-maze-switch-tiny.toml: lives of 6
/// episodes, a switch in 3..=4) is the same bytes on 1 and 2 threads and resumed.
#[test]
fn t_maze_switch_runs_are_the_same_bytes_on_any_thread_count_and_resumed() {
    let (_dir, one) = crate::run_guarantees::same_bytes_on_any_thread_count_and_resumed(
        "t-maze-switch-tiny.toml",
        &[],
    );
    let fitness = std::fs::read_to_string(one.join("fitness.csv")).unwrap();
    assert!(fitness.contains("best_adapted_choice"), "{fitness}");
}

/// The same for a neuromodulated plastic brain (per-layer rules, its weights carried across
/// the episodes of a life): 1 and 2 threads and a resumed run give the same bytes, and the
/// rule's genes are in the champion (so the run did evolve a plastic brain).
#[test]
fn plastic_t_maze_switch_runs_are_the_same_bytes_on_any_thread_count_and_resumed() {
    let (_dir, one) = crate::run_guarantees::same_bytes_on_any_thread_count_and_resumed(
        "t-maze-switch-tiny-plastic.toml",
        &[],
    );
    let best = std::fs::read_to_string(one.join("best.json")).unwrap();
    assert!(best.contains("neuromodulated"), "{best}");
}

/// Counts what a trial observer is shown.
#[derive(Default)]
struct Shown {
    starts: Vec<TrialId>,
    ticks: Vec<u64>,
    finished: Vec<f64>,
}

impl TickObserver for Shown {
    fn start(&mut self, trial: TrialId, _world: &World) {
        self.starts.push(trial);
    }
    fn tick(&mut self, _world: &World, tick: u64) {
        self.ticks.push(tick);
    }
    fn finish(&mut self, _world: &World, outcomes: &[TrialOutcome]) {
        self.finished.push(outcomes[0].score);
    }
}

/// An observer (the trace, `replay`) sees each episode of a life as a trial of its own, with
/// its ticks from 1, and the episodes' scores add up to the life's.
#[test]
fn an_observer_sees_each_episode_as_a_trial() {
    let e = load(&world(SWITCHED));
    let topology = e.topology();
    let mut shown = Shown::default();
    let g = [genome(&e, 1)];
    let life = berry_evolve::evo::trial::run_trial(
        &TrialPlan::new(&e),
        &topology,
        &g,
        Generation(1),
        0,
        TrialIndex(2),
        &mut shown,
    )
    .unwrap()[0];
    assert_eq!(shown.starts.len(), 4);
    assert_eq!(shown.finished.len(), 4);
    assert_eq!(shown.ticks.iter().filter(|&&t| t == 1).count(), 4);
    let sum = shown.finished.iter().fold(0.0, |a, s| a + s);
    assert_eq!(sum.to_bits(), life.score.to_bits());
    let alone = run_trial(&e, &topology, &g, Generation(1), 0, TrialIndex(2)).unwrap()[0];
    same(&alone, &life, "watched and not");
}
