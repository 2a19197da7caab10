//! Plastic brains (`brain.plasticity`): the rule Δw = η·(A·pre·post + B·pre + C·post + D) on
//! hand-computed single synapses (each coefficient alone, the tanh(m/2) gate, the clamp), the
//! genome layout, frozen plasticity (η = 0) equal to the fixed MLP over a whole trial, reset,
//! random initial weights per life, bad tables refused naming the key, and the ablations of
//! `compare --ablate` (frozen, ungated).

use crate::brain_common::spec;
use berry_evolve::brain::activation::tanh;
use berry_evolve::brain::genome::Genome;
use berry_evolve::brain::{Brain, LifeKey, SignalInputs, Topology};
use berry_evolve::evo::trial::{run_trial, NoObserver};
use berry_evolve::evo::TrialPlan;
use berry_evolve::experiment::Experiment;
use berry_evolve::seed::{Generation, IndividualId, Seed, TrialIndex};
use std::path::Path;

/// A one-input, one-output network without hidden layer (one synapse w and the output bias)
/// with `table` added to its `[brain]`, the input being food detector A.
fn synapse(table: &str, genome: &[f64]) -> Brain {
    let topology = Topology {
        spec: spec(&format!("hidden = []\n{table}")),
        inputs: 1,
        outputs: 1,
        signals: SignalInputs {
            food: Some(0),
            ..SignalInputs::default()
        },
    };
    Brain::new(&topology, genome).unwrap_or_else(|e| panic!("{table}: {e}"))
}

/// The live weights (input-major) of a plastic MLP.
fn weights(brain: &Brain) -> Vec<f64> {
    match brain {
        Brain::Mlp(mlp) => mlp.live_weights(),
        other => panic!("not an mlp: {:?}", other.kind()),
    }
}

/// One tick with input `x`: the output.
fn tick(brain: &mut Brain, x: f64) -> f64 {
    let mut y = [f64::NAN];
    brain.activate(&[x], &mut y);
    y[0]
}

/// The documented rule, operation by operation, for one synapse.
fn rule(
    w: f64,
    pre: f64,
    post: f64,
    [eta, a, b, c, d]: [f64; 5],
    g: f64,
    [lo, hi]: [f64; 2],
) -> f64 {
    let s = ((a * pre) * post + b * pre) + (c * post + d);
    let dw = (eta * g) * s;
    let w = w + dw;
    let w = if w > lo { w } else { lo };
    if w < hi {
        w
    } else {
        hi
    }
}

/// Each coefficient alone, over four ticks: D adds η·D, B adds η·B·pre, C adds η·C·post, A
/// adds η·A·pre·post, and η scales them all. The literal cases are exact in binary.
#[test]
fn each_coefficient_alone_changes_one_synapse_as_computed_by_hand() {
    // D alone: w = 0.5 + 0.25 per tick, whatever the input.
    let mut brain = synapse(
        "plasticity = \"hebbian\"",
        &[0.5, 0.0, 0.25, 0.0, 0.0, 0.0, 1.0],
    );
    for (k, expected) in [0.75, 1.0, 1.25, 1.5].into_iter().enumerate() {
        let y = tick(&mut brain, [0.0, 3.0, -1.0, 0.5][k]);
        assert!(y.is_finite());
        assert_eq!(weights(&brain), [expected], "D alone, tick {k}");
    }
    // B alone: Δw = η·B·pre = 0.5 · 0.25 · 2 = 0.25 per tick at pre = 2, 0 at pre = 0.
    let mut brain = synapse(
        "plasticity = \"hebbian\"",
        &[0.5, 0.0, 0.5, 0.0, 0.25, 0.0, 0.0],
    );
    for (x, expected) in [(2.0, 0.75), (2.0, 1.0), (0.0, 1.0), (-2.0, 0.75)] {
        tick(&mut brain, x);
        assert_eq!(weights(&brain), [expected], "B alone, pre {x}");
    }
    // η scales: the same B with η = 1 doubles the step.
    let mut brain = synapse(
        "plasticity = \"hebbian\"",
        &[0.5, 0.0, 1.0, 0.0, 0.25, 0.0, 0.0],
    );
    tick(&mut brain, 2.0);
    assert_eq!(weights(&brain), [1.0], "eta scales the change");
    // C and A need post = tanh(b + w·pre): follow the output the network gives.
    for (name, coefficients) in [
        ("C", [0.5, 0.0, 0.0, 1.5, 0.0]),
        ("A", [0.5, 2.0, 0.0, 0.0, 0.0]),
        ("all", [0.3, -1.25, 0.75, 0.5, -0.125]),
    ] {
        let (w0, bias) = (0.25, 0.125);
        let mut genome = vec![w0, bias];
        genome.extend(coefficients);
        let mut brain = synapse("plasticity = \"hebbian\"", &genome);
        let mut w = w0;
        for x in [1.0, -0.5, 2.0, 0.75] {
            let y = tick(&mut brain, x);
            assert_eq!(
                y.to_bits(),
                tanh(bias + w * x).to_bits(),
                "{name}: forward pass"
            );
            w = rule(w, x, y, coefficients, 1.0, [-4.0, 4.0]);
            assert_eq!(weights(&brain), [w], "{name}: x = {x}");
        }
        assert_ne!(w, w0, "{name}: the weight changed");
    }
    // C alone by hand: pre 0, bias 0, w 0.5 → post = tanh(0) = 0, no change; the bias drives
    // post instead: bias 0.5 → post = tanh(0.5), Δw = 0.5 · 1.5 · tanh(0.5).
    let mut brain = synapse(
        "plasticity = \"hebbian\"",
        &[0.5, 0.5, 0.5, 0.0, 0.0, 1.5, 0.0],
    );
    tick(&mut brain, 0.0);
    assert_eq!(weights(&brain), [0.5 + 0.5 * 1.5 * tanh(0.5)]);
}

/// The clamp: weights stop exactly at the bounds, from either side, and a change inside the
/// bounds is not clamped.
#[test]
fn weights_are_clamped_to_the_bounds() {
    let table = "plasticity = \"hebbian\"\nweight_bounds = [-1.0, 1.5]";
    let mut up = synapse(table, &[0.5, 0.0, 1.0, 0.0, 0.0, 0.0, 0.75]);
    for expected in [1.25, 1.5, 1.5, 1.5] {
        tick(&mut up, 1.0);
        assert_eq!(weights(&up), [expected]);
    }
    let mut down = synapse(table, &[0.5, 0.0, 1.0, 0.0, 0.0, 0.0, -0.75]);
    for expected in [-0.25, -1.0, -1.0] {
        tick(&mut down, 1.0);
        assert_eq!(weights(&down), [expected]);
    }
}

/// Neuromodulation: Δw is multiplied by tanh(m/2), m = gene · food detector A. No food, no
/// change; food 1 with gene 2 gives tanh(1); a negative gene reverses the change.
#[test]
fn the_modulatory_signal_gates_the_change_by_tanh_of_half_m() {
    let table = "plasticity = \"neuromodulated\"\nmodulators = [\"food_a\"]";
    // w, b, η, A, B, C, D, then mod_food_a.
    let mut brain = synapse(table, &[0.5, 0.0, 0.5, 0.0, 0.0, 0.0, 1.0, 2.0]);
    tick(&mut brain, 0.0);
    assert_eq!(weights(&brain), [0.5], "m = 0: tanh(0) = 0 stops learning");
    tick(&mut brain, 1.0);
    let w = 0.5 + (0.5 * 1.0) * tanh(2.0 * 1.0 * 0.5);
    assert_eq!(weights(&brain), [w], "m = 2");
    tick(&mut brain, 0.5);
    let w = w + (0.5 * 1.0) * tanh(2.0 * 0.5 * 0.5);
    assert_eq!(weights(&brain), [w], "m = 1");
    let mut reversed = synapse(table, &[0.5, 0.0, 0.5, 0.0, 0.0, 0.0, 1.0, -2.0]);
    tick(&mut reversed, 1.0);
    assert_eq!(weights(&reversed), [0.5 - 0.5 * tanh(1.0)], "m = -2");
    // The same coefficients without the gate (hebbian) learn on every tick.
    let mut hebbian = synapse(
        "plasticity = \"hebbian\"",
        &[0.5, 0.0, 0.5, 0.0, 0.0, 0.0, 1.0],
    );
    tick(&mut hebbian, 0.0);
    assert_eq!(weights(&hebbian), [1.0]);
}

/// Reset (the start of a life) restores the genome's weights, and the brain then behaves
/// bit for bit as a new one; nothing else restores them (activating keeps learning).
#[test]
fn reset_restores_the_genome_weights() {
    let genome = [0.25, 0.125, 0.3, -1.25, 0.75, 0.5, -0.125];
    let mut brain = synapse("plasticity = \"hebbian\"", &genome);
    let fresh = brain.clone();
    let first: Vec<u64> = [1.0, -0.5, 2.0]
        .iter()
        .map(|&x| tick(&mut brain, x).to_bits())
        .collect();
    assert_ne!(weights(&brain), [0.25]);
    brain.reset();
    assert_eq!(weights(&brain), [0.25]);
    assert_eq!(brain, fresh, "reset gives the brain as built");
    let again: Vec<u64> = [1.0, -0.5, 2.0]
        .iter()
        .map(|&x| tick(&mut brain, x).to_bits())
        .collect();
    assert_eq!(first, again);
    assert_eq!(
        brain.parameters(),
        genome,
        "the genome itself never changes"
    );
    assert!(
        !brain.is_stateless(),
        "a plastic brain keeps state: no lockstep batches"
    );
}

/// Layout: the rule's and the modulation's genes follow the network's weights and biases in
/// the documented order, for each granularity, and random initial weights leave the network
/// out of the genome.
#[test]
fn genome_layout_lists_the_rule_and_modulation_genes() {
    let topology = |table: &str| Topology {
        spec: spec(&format!("hidden = [2]\n{table}")),
        inputs: 3,
        outputs: 2,
        signals: SignalInputs {
            food: Some(0),
            shock: Some(2),
            metabolism: None,
        },
    };
    let fixed = topology("").parameter_count();
    assert_eq!(fixed, 2 * 4 + 2 * 3);
    let network = topology("plasticity = \"hebbian\"");
    assert_eq!(network.parameter_count(), fixed + 5);
    assert_eq!(
        network.parameter_names()[fixed..],
        ["rule_eta", "rule_a", "rule_b", "rule_c", "rule_d"]
    );
    let layer = topology("plasticity = \"hebbian\"\ngranularity = \"layer\"");
    assert_eq!(layer.parameter_count(), fixed + 10);
    assert_eq!(layer.parameter_names()[fixed + 5], "rule_eta_out");
    let per_synapse = topology("plasticity = \"hebbian\"\ngranularity = \"synapse\"");
    assert_eq!(per_synapse.parameter_count(), fixed + 5 * (2 * 3 + 2 * 2));
    let names = per_synapse.parameter_names();
    assert_eq!(names[fixed], "rule_eta_h0[0][0]");
    assert_eq!(names[fixed + 6], "rule_a_h0[0][0]");
    assert_eq!(names[fixed + 30], "rule_eta_out[0][0]");
    let modulated = topology(
        "plasticity = \"neuromodulated\"\nmodulators = [\"shock\", \"neurons\", \"food_b\"]\n\
         modulatory_neurons = 2",
    );
    assert_eq!(modulated.parameter_count(), fixed + 5 + 1 + 2 * 3 + 1);
    assert_eq!(
        modulated.parameter_names()[fixed + 5..],
        [
            "mod_shock",
            "w_mod[0][0]",
            "w_mod[0][1]",
            "w_mod[1][0]",
            "w_mod[1][1]",
            "b_mod[0]",
            "b_mod[1]",
            "mod_food_b"
        ]
    );
    let random = topology("plasticity = \"hebbian\"\ninitial_weights = \"random\"");
    assert_eq!(random.parameter_count(), 5);
    assert_eq!(random.parameter_names().len(), 5);
    for t in [network, layer, per_synapse, modulated, random] {
        let genome = vec![0.125; t.parameter_count()];
        let brain = Brain::new(&t, &genome).expect("every layout builds");
        assert_eq!(brain.parameters(), genome);
    }
}

/// A modulatory neuron reads the last hidden layer: with the hidden unit at tanh(1) and the
/// neuron's weight 2, bias −0.5, m = tanh(2·tanh(1) − 0.5), the gate tanh(m/2).
#[test]
fn modulatory_neurons_read_the_last_hidden_layer() {
    let topology = Topology {
        spec: spec(
            "hidden = [1]\nplasticity = \"neuromodulated\"\nmodulators = [\"neurons\"]\n\
             granularity = \"layer\"",
        ),
        inputs: 1,
        outputs: 1,
        signals: SignalInputs::default(),
    };
    // w_h0, b_h0, w_out, b_out; rules h0 (frozen) and out (D = 1, η = 1); w_mod, b_mod.
    let genome = [
        1.0, 0.0, 0.5, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 2.0, -0.5,
    ];
    let mut brain = Brain::new(&topology, &genome).expect("brain");
    tick(&mut brain, 1.0);
    let m = tanh(2.0 * tanh(1.0) + -0.5);
    assert_eq!(weights(&brain), [1.0, 0.5 + tanh(m * 0.5)]);
}

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The benchmark world with `brain` appended to its `[brain]` table.
fn foraging(brain: &str) -> Experiment {
    let path = root().join("experiments/bench/foraging-world.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    Experiment::from_toml(&format!("{text}\n{brain}\n"), &path).unwrap_or_else(|e| panic!("{e}"))
}

/// Frozen plasticity (η = 0, every other coefficient and modulator gene nonzero) lives a
/// whole trial exactly as the fixed MLP with the same weights: same score and metabolism,
/// bit for bit, for the hebbian and the neuromodulated rule and every granularity.
#[test]
fn frozen_plasticity_lives_a_trial_as_the_fixed_mlp_bit_for_bit() {
    let fixed = foraging("");
    let topology = fixed.topology();
    let parameters: Vec<f64> = (0..topology.parameter_count())
        .map(|k| ((k * 37 % 23) as f64 - 11.0) / 9.0)
        .collect();
    let expected = run_trial(
        &TrialPlan::new(&fixed),
        &topology,
        &[Genome::new(parameters.clone())],
        Generation(0),
        0,
        TrialIndex(0),
        NoObserver,
    )
    .unwrap();
    for table in [
        "plasticity = \"hebbian\"",
        "plasticity = \"hebbian\"\ngranularity = \"synapse\"",
        "plasticity = \"neuromodulated\"\nmodulators = [\"food_a\", \"shock\", \"neurons\"]\n\
         granularity = \"layer\"",
    ] {
        let plastic = foraging(table);
        let topology = plastic.topology();
        let names = topology.parameter_names();
        let mut genome = parameters.clone();
        genome.extend(names[parameters.len()..].iter().map(|name| {
            if name.starts_with("rule_eta") {
                0.0
            } else {
                0.75
            }
        }));
        let outcomes = run_trial(
            &TrialPlan::new(&plastic),
            &topology,
            &[Genome::new(genome.clone())],
            Generation(0),
            0,
            TrialIndex(0),
            NoObserver,
        )
        .unwrap();
        assert_eq!(
            outcomes[0].score.to_bits(),
            expected[0].score.to_bits(),
            "{table}"
        );
        assert_eq!(
            outcomes[0].metabolism.map(f64::to_bits),
            expected[0].metabolism.map(f64::to_bits),
            "{table}"
        );
    }
}

/// Random initial weights (`initial_weights = "random"`) are drawn per life: the same life
/// draws the same weights (and reset draws them again), another life other weights.
#[test]
fn random_initial_weights_differ_between_lives_and_repeat_for_the_same_life() {
    let topology = Topology::new(
        spec("hidden = [4]\nplasticity = \"hebbian\"\ninitial_weights = \"random\""),
        6,
        2,
    )
    .unwrap();
    let genome = vec![0.1, 0.2, 0.3, 0.4, 0.5];
    let life = |seed, generation, individual, trial| LifeKey {
        seed: Seed(seed),
        generation: Generation(generation),
        individual: IndividualId(individual),
        trial: TrialIndex(trial),
    };
    let drawn = |key: LifeKey| {
        let mut brain = Brain::new(&topology, &genome).unwrap();
        brain.start_life(key);
        weights(&brain)
    };
    let one = drawn(life(7, 3, 2, 1));
    assert_eq!(one.len(), 6 * 4 + 4 * 2);
    assert!(one.iter().all(|w| (-1.0..=1.0).contains(w)));
    assert_eq!(one, drawn(life(7, 3, 2, 1)), "same life, same weights");
    for other in [
        life(8, 3, 2, 1),
        life(7, 4, 2, 1),
        life(7, 3, 3, 1),
        life(7, 3, 2, 2),
    ] {
        assert_ne!(one, drawn(other), "{other:?}");
    }
    let mut brain = Brain::new(&topology, &genome).unwrap();
    brain.start_life(life(7, 3, 2, 1));
    let mut y = [0.0; 2];
    for _ in 0..5 {
        brain.activate(&[1.0, 0.5, -0.5, 0.25, 0.0, 1.0], &mut y);
    }
    assert_ne!(weights(&brain), one, "the weights learned");
    brain.reset();
    assert_eq!(weights(&brain), one, "reset draws the life's weights again");
}

/// Bad tables are refused naming the key and saying what to do.
#[test]
fn bad_plasticity_tables_are_refused_naming_the_key() {
    let refused = |brain: &str, inputs: &str, key: &str, words: &[&str]| {
        let path = root().join("experiments/bench/foraging-world.toml");
        let text = std::fs::read_to_string(&path).unwrap();
        let text = format!("{text}\n{brain}\n\n{inputs}\n");
        let error = Experiment::from_toml(&text, &path)
            .expect_err(brain)
            .to_string();
        assert!(error.contains(&format!("`{key}`")), "{brain}: {error}");
        for word in words {
            assert!(error.contains(word), "{brain}: {error} lacks {word:?}");
        }
    };
    refused(
        "plasticity = \"neuromodulated\"\nmodulators = [\"shock\"]",
        "[creature.inputs]\nshock = false",
        "brain.modulators",
        &["creature.inputs.shock = true"],
    );
    refused(
        "plasticity = \"neuromodulated\"\nmodulators = [\"metabolism_change\"]",
        "",
        "brain.modulators",
        &["creature.inputs.metabolism = true"],
    );
    refused(
        "plasticity = \"neuromodulated\"\nmodulators = [\"food_c\"]",
        "[creature.inputs]\nfood = false",
        "brain.modulators",
        &["creature.inputs.food = true"],
    );
    refused(
        "plasticity = \"neuromodulated\"",
        "",
        "brain.modulators",
        &["at least one"],
    );
    refused(
        "plasticity = \"hebbian\"\nmodulators = [\"food_a\"]",
        "",
        "brain.modulators",
        &["neuromodulated"],
    );
    refused(
        "plasticity = \"neuromodulated\"\nmodulators = [\"food_a\", \"food_a\"]",
        "",
        "brain.modulators",
        &["twice"],
    );
    refused(
        "plasticity = \"hebbian\"\nweight_bounds = [2.0, 2.0]",
        "",
        "brain.weight_bounds",
        &["min < max"],
    );
    refused(
        "plasticity = \"hebbian\"\nweight_bounds = [3.0, -3.0]",
        "",
        "brain.weight_bounds",
        &["min < max"],
    );
    refused(
        "granularity = \"layer\"",
        "",
        "brain.granularity",
        &["plastic"],
    );
    refused(
        "plasticity = \"hebbian\"\nmodulatory_neurons = 2",
        "",
        "brain.modulatory_neurons",
        &["\"neurons\""],
    );
    refused(
        "plasticity = \"hebbian\"\nprecision = \"f32\"",
        "",
        "brain.plasticity",
        &["f64"],
    );
    // Another kind: the file's `kind = "mlp"` is replaced.
    let path = root().join("experiments/bench/foraging-world.toml");
    let text = std::fs::read_to_string(&path)
        .unwrap()
        .replace("kind = \"mlp\"", "kind = \"recurrent\"");
    let error = Experiment::from_toml(&format!("{text}\nplasticity = \"hebbian\"\n"), &path)
        .expect_err("recurrent")
        .to_string();
    assert!(error.contains("`brain.plasticity`"), "{error}");
    assert!(error.contains("not supported yet"), "{error}");
    // The same modulators are accepted once the sensor is on.
    let text = std::fs::read_to_string(&path).unwrap();
    let text = format!(
        "{text}\nplasticity = \"neuromodulated\"\nmodulators = [\"metabolism_change\"]\n\n\
         [creature.inputs]\nmetabolism = true\n"
    );
    Experiment::from_toml(&text, &path).expect("metabolism on");
}

/// Plastic brains keep state, so evaluation runs them on the single-trial path (never in
/// lockstep): the population's evaluation on 1 and on 2 threads equals living every group's
/// trials one by one, bit for bit, with evolved and with random initial weights (whose
/// per-life draws thus do not depend on threads either), with common random numbers on and
/// off.
#[test]
fn plastic_evaluation_is_the_single_trial_path_on_any_thread_count() {
    use berry_evolve::evo::door::{Evaluate, Worlds};
    use berry_evolve::evo::evaluate::{aggregate, Evaluation};
    use berry_evolve::evo::lockstep;
    use berry_evolve::evo::search::ga::first_population;
    let bits = |evaluations: &[Evaluation]| -> Vec<(Option<u64>, [u64; 4])> {
        evaluations
            .iter()
            .map(|e| (e.fitness.map(f64::to_bits), e.metabolism.map(f64::to_bits)))
            .collect()
    };
    for (table, crn) in [
        (
            "plasticity = \"neuromodulated\"\nmodulators = [\"food_a\", \"shock\", \"neurons\"]",
            true,
        ),
        (
            "plasticity = \"hebbian\"\ninitial_weights = \"random\"",
            true,
        ),
        (
            "plasticity = \"hebbian\"\ninitial_weights = \"random\"",
            false,
        ),
    ] {
        let experiment = foraging(table)
            .with_overrides()
            .edit(|c| c.evolution.population = 6)
            .trials(3)
            .ticks(150)
            .common_random_numbers(crn)
            .build()
            .unwrap();
        let topology = experiment.topology();
        assert!(!lockstep::stateless(&topology), "{table}");
        let population = first_population(&experiment, &topology);
        let serial: Vec<Evaluation> = population
            .iter()
            .enumerate()
            .map(|(g, genome)| {
                // Alone, trial by trial: the single-trial path, serially.
                let lives: Vec<_> = (0..experiment.evaluation.trials)
                    .map(|t| {
                        run_trial(
                            &TrialPlan::new(&experiment),
                            &topology,
                            std::slice::from_ref(genome),
                            Generation(2),
                            g as u64,
                            TrialIndex(t),
                            NoObserver,
                        )
                        .unwrap()[0]
                    })
                    .collect();
                aggregate(&TrialPlan::new(&experiment), &lives)
            })
            .collect();
        for threads in [1, 2] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let parallel = pool
                .install(|| {
                    Evaluate::new(
                        &experiment,
                        &topology,
                        &population,
                        Worlds::Training(Generation(2)),
                    )
                    .run()
                })
                .unwrap();
            assert_eq!(
                bits(&parallel),
                bits(&serial),
                "{table}: {threads} thread(s)"
            );
        }
    }
}

/// Ablations (`compare --ablate`, [`berry_evolve::brain::ablation`]): `ungated` is the rule
/// with its gate held open (the same weights, tick by tick, as the neuromodulated brain whose
/// m is so large that g = tanh(m/2) = 1), which differs from the gated rule; `frozen` is the
/// fixed MLP of the genome's weights (its weights never move), and with random initial
/// weights it keeps the life's draw. Ablating what cannot be ablated is refused.
#[test]
fn ablations_freeze_the_weights_or_hold_the_gate_open() {
    use berry_evolve::brain::ablation::{ablate, Ablation, AblationError};
    let topology = |table: &str| Topology {
        spec: spec(&format!("hidden = [3]\n{table}")),
        inputs: 2,
        outputs: 2,
        signals: SignalInputs {
            food: Some(0),
            ..SignalInputs::default()
        },
    };
    let plastic = topology(
        "plasticity = \"neuromodulated\"\nmodulators = [\"food_a\"]\ngranularity = \"layer\"",
    );
    let names = plastic.parameter_names();
    // Weights from a fixed pattern; per layer η = 0.25, A = 0.5, B = −0.25, C = 0.125,
    // D = 0.0625; the food gene `gate`.
    let genome = |gate: f64| -> Vec<f64> {
        names
            .iter()
            .enumerate()
            .map(|(k, name)| match name.split('_').nth(1) {
                _ if name == "mod_food_a" => gate,
                Some("eta") => 0.25,
                Some("a") => 0.5,
                Some("b") => -0.25,
                Some("c") => 0.125,
                Some("d") => 0.0625,
                _ => ((k * 37 % 23) as f64 - 11.0) / 9.0,
            })
            .collect()
    };
    assert_eq!(tanh(5e5 * 0.5), 1.0, "the gate can be held open");
    let gated = Genome::new(genome(0.3));
    let (ungated_topology, ungated) = ablate(&plastic, &gated, Ablation::Ungated).unwrap();
    assert_eq!(
        ungated_topology.spec,
        spec("hidden = [3]\nplasticity = \"hebbian\"\ngranularity = \"layer\"")
    );
    let (frozen_topology, frozen) = ablate(&plastic, &gated, Ablation::Frozen).unwrap();
    assert_eq!(frozen_topology.spec, spec("hidden = [3]"));
    assert_eq!(
        frozen.parameters[..],
        gated.parameters[..frozen_topology.parameter_count()]
    );
    let mut brains = [
        Brain::new(&plastic, &gated.parameters).unwrap(),
        Brain::new(&plastic, &genome(5e5)).unwrap(),
        ungated.decode(&ungated_topology).unwrap(),
        frozen.decode(&frozen_topology).unwrap(),
    ];
    let start = weights(&brains[0]);
    let mut y = [0.0; 2];
    for t in 0..20 {
        // Food detector A on every tick (so the open gate stays open), the other input moving.
        let x = [1.0, f64::from(t % 5) * 0.25 - 0.5];
        for brain in &mut brains {
            brain.activate(&x, &mut y);
        }
        assert_eq!(
            weights(&brains[2]),
            weights(&brains[1]),
            "ungated = open, tick {t}"
        );
        assert_eq!(weights(&brains[3]), start, "frozen never moves, tick {t}");
    }
    assert_ne!(
        weights(&brains[0]),
        weights(&brains[2]),
        "the gate mattered"
    );
    assert_ne!(weights(&brains[0]), start, "the intact brain learned");

    // Random initial weights: frozen keeps the life's draw.
    let random = topology(
        "plasticity = \"neuromodulated\"\nmodulators = [\"food_a\"]\ninitial_weights = \"random\"",
    );
    let genes = Genome::new(vec![0.25, 0.5, -0.25, 0.125, 0.0625, 0.3]);
    let (t, g) = ablate(&random, &genes, Ablation::Frozen).unwrap();
    let key = LifeKey {
        seed: Seed(3),
        trial: TrialIndex(2),
        ..LifeKey::default()
    };
    let mut intact = Brain::new(&random, &genes.parameters).unwrap();
    let mut frozen = g.decode(&t).unwrap();
    intact.start_life(key);
    frozen.start_life(key);
    let drawn = weights(&intact);
    assert_eq!(weights(&frozen), drawn, "the same draw");
    for _ in 0..10 {
        intact.activate(&[1.0, 0.5], &mut y);
        frozen.activate(&[1.0, 0.5], &mut y);
    }
    assert_eq!(weights(&frozen), drawn);
    assert_ne!(weights(&intact), drawn);

    // Refusals.
    let fixed = topology("");
    let some = Genome::new(vec![0.0; fixed.parameter_count()]);
    assert_eq!(
        ablate(&fixed, &some, Ablation::Frozen).unwrap_err(),
        AblationError::NotPlastic
    );
    let hebbian = topology("plasticity = \"hebbian\"");
    let some = Genome::new(vec![0.0; hebbian.parameter_count()]);
    assert_eq!(
        ablate(&hebbian, &some, Ablation::Ungated).unwrap_err(),
        AblationError::NoGate
    );
    assert!(ablate(&hebbian, &some, Ablation::Frozen).is_ok());
    assert!(matches!(
        ablate(&plastic, &some, Ablation::Frozen),
        Err(AblationError::ParameterCount { .. })
    ));
}
