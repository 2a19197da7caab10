//! Brains: hand-computed forward passes for every kind (bit for bit against the documented
//! summation order and fast activation kernels, and within a tolerance of the libm values), the CTRNN's Euler integration and gene
//! mappings, parameter layouts, the bit-exact genome ↔ brain round trip, parameter and
//! `[brain]` table errors, and the motor mapping of `BrainController`. (No allocation per
//! tick is checked in tests/alloc/brain_activate_and_act.rs, under the counting allocator.)

use berry_evolve::brain::activation::{logistic as sigma, tanh, TANH_MAX_ERROR};
use berry_evolve::brain::ctrnn::{gain, time_constant};
use berry_evolve::brain::spec::{MAX_PARAMETERS, MAX_UNITS};
use berry_evolve::brain::{
    output_count, Activation, Brain, BrainController, BrainError, BrainKind, BrainSpec, Genome,
    Topology,
};
use berry_evolve::seed::{below, chance, gaussian, unit, Rng};
use berry_evolve::sim::controller::Controller;

use crate::brain_common::{rng, round_trip_topologies, spec, topology};

// ---------------------------------------------------------------------------------------------
// Helpers

fn brain(toml_text: &str, inputs: usize, outputs: usize, parameters: &[f64]) -> Brain {
    Brain::new(&topology(toml_text, inputs, outputs), parameters).expect("valid brain")
}

fn run(brain: &mut Brain, inputs: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; brain.outputs()];
    brain.activate(inputs, &mut out);
    out
}

/// How far a small network's outputs may be from the same network computed with libm's tanh
/// and exp: each fast activation is within [`TANH_MAX_ERROR`] (5.4e-10) of the exact value,
/// and in these hand-computed networks (weights ≤ 2, two layers) the errors add up to less
/// than 10 of those.
const LIBM_TOLERANCE: f64 = 10.0 * TANH_MAX_ERROR;

/// Checks a forward pass twice: bit for bit against `formula` (the same network written out
/// with the documented summation order b + w0 x0 + w1 x1 + … and the fast [`tanh`] and
/// [`sigma`] kernels), and within [`LIBM_TOLERANCE`] of `by_hand` (the values computed by hand
/// with exact tanh and σ), which shows the network still means the same thing.
fn assert_forward(got: &[f64], formula: &[f64], by_hand: &[f64], what: &str) {
    assert_eq!(got.len(), formula.len(), "{what}: length");
    assert_eq!(got.len(), by_hand.len(), "{what}: length");
    for (i, ((g, f), h)) in got.iter().zip(formula).zip(by_hand).enumerate() {
        assert_eq!(
            g.to_bits(),
            f.to_bits(),
            "{what}: output {i} is {g}, the documented formula gives {f}"
        );
        assert!(
            (g - h).abs() <= LIBM_TOLERANCE,
            "{what}: output {i} is {g}, {h} by hand with exact tanh (difference {})",
            g - h
        );
    }
}

// ---------------------------------------------------------------------------------------------
// MLP by hand

/// The 2 → 2 → 2 network used for every activation, in genome order:
/// w_h0 = [[0.5, -1.0], [0.25, 0.5]], b_h0 = [0.0, -0.25],
/// w_out = [[1.0, 2.0], [-1.0, 0.5]], b_out = [0.5, 0.0].
const MLP_2_2_2: [f64; 12] = [
    0.5, -1.0, 0.25, 0.5, // w_h0[0][0], w_h0[0][1], w_h0[1][0], w_h0[1][1]
    0.0, -0.25, // b_h0[0], b_h0[1]
    1.0, 2.0, -1.0, 0.5, // w_out[0][0], w_out[0][1], w_out[1][0], w_out[1][1]
    0.5, 0.0, // b_out[0], b_out[1]
];

// With inputs x = [1, 1] the hidden pre-activations are
//   a0 = 0.0 + 0.5·1 + (-1)·1 = -0.5
//   a1 = -0.25 + 0.25·1 + 0.5·1 = 0.5
// and the outputs are tanh(0.5 + 1·h0 + 2·h1) and tanh(0 + (-1)·h0 + 0.5·h1), each sum taken
// left to right from the bias (the documented order).

/// The 2 → 2 → 2 network's outputs for x = [1, 1], written out in the documented order with
/// the fast kernels: hidden activation `act`, tanh outputs.
// Every weight is written as it is in the genome (-1.0 · x included), term by term.
#[allow(clippy::neg_multiply)]
fn mlp_2_2_2_formula(act: impl Fn(f64) -> f64) -> [f64; 2] {
    let (x0, x1) = (1.0, 1.0);
    let h0 = act(0.0 + 0.5 * x0 + -1.0 * x1);
    let h1 = act(-0.25 + 0.25 * x0 + 0.5 * x1);
    [
        tanh(0.5 + 1.0 * h0 + 2.0 * h1),
        tanh(0.0 + -1.0 * h0 + 0.5 * h1),
    ]
}

#[test]
fn mlp_2_2_2_tanh_by_hand() {
    // h = [tanh(-0.5), tanh(0.5)] = [-0.46211715726000974, 0.46211715726000974]
    // o0 = tanh(-0.46211715726000974 + 0.92423431452001948 + 0.5) = tanh(0.9621171572600098)
    //    = 0.7452197423298184
    // o1 = tanh(0.46211715726000974 + 0.23105857863000487) = tanh(0.6931757358900146)
    //    = 0.6000182750981286
    let mut b = brain("hidden = [2]", 2, 2, &MLP_2_2_2);
    assert_forward(
        &run(&mut b, &[1.0, 1.0]),
        &mlp_2_2_2_formula(tanh),
        &[0.7452197423298184, 0.6000182750981286],
        "tanh",
    );
}

#[test]
fn mlp_2_2_2_sigmoid_by_hand() {
    // h = [σ(-0.5), σ(0.5)] = [0.3775406687981454, 0.6224593312018546]
    // o0 = tanh(0.3775406687981454 + 1.2449186624037092 + 0.5) = tanh(2.1224593312018545)
    //    = 0.9717314833682242
    // o1 = tanh(-0.3775406687981454 + 0.3112296656009273) = tanh(-0.0663110031972181)
    //    = -0.06621398071889728
    let mut b = brain("hidden = [2]\nactivation = \"sigmoid\"", 2, 2, &MLP_2_2_2);
    assert_forward(
        &run(&mut b, &[1.0, 1.0]),
        &mlp_2_2_2_formula(sigma),
        &[0.9717314833682242, -0.06621398071889728],
        "sigmoid",
    );
}

#[test]
fn mlp_2_2_2_relu_by_hand() {
    // h = [relu(-0.5), relu(0.5)] = [0, 0.5]
    // o0 = tanh(0 + 2·0.5 + 0.5) = tanh(1.5) = 0.9051482536448664
    // o1 = tanh(-0 + 0.5·0.5 + 0) = tanh(0.25) = 0.24491866240370913
    let mut b = brain("hidden = [2]\nactivation = \"relu\"", 2, 2, &MLP_2_2_2);
    assert_forward(
        &run(&mut b, &[1.0, 1.0]),
        &mlp_2_2_2_formula(|a: f64| a.max(0.0)),
        &[0.9051482536448664, 0.24491866240370913],
        "relu",
    );
}

#[test]
fn mlp_without_hidden_layers_wires_inputs_to_outputs() {
    // w_out = [[1, 0.5], [0, -2]], b_out = [0, 0.5]; x = [0.5, 1]
    // o0 = tanh(0 + 0.5 + 0.5) = tanh(1) = 0.7615941559557649
    // o1 = tanh(0.5 + 0 - 2) = tanh(-1.5) = -0.9051482536448664
    let mut b = brain("hidden = []", 2, 2, &[1.0, 0.5, 0.0, -2.0, 0.0, 0.5]);
    let (x0, x1) = (0.5, 1.0);
    assert_forward(
        &run(&mut b, &[x0, x1]),
        &[
            tanh(0.0 + 1.0 * x0 + 0.5 * x1),
            tanh(0.5 + 0.0 * x0 + -2.0 * x1),
        ],
        &[0.7615941559557649, -0.9051482536448664],
        "direct",
    );
}

#[test]
fn mlp_has_no_state() {
    let mut rng = rng(1);
    let t = topology("hidden = [5, 3]", 4, 3);
    let p: Vec<f64> = (0..t.parameter_count())
        .map(|_| gaussian(&mut rng))
        .collect();
    let mut b = Brain::new(&t, &p).expect("valid");
    let x = [0.1, -0.2, 0.3, 1.0];
    let first = run(&mut b, &x);
    run(&mut b, &[1.0, 1.0, 1.0, 1.0]);
    assert_eq!(run(&mut b, &x), first);
}

/// One layer the plain way, from the genome's row-major weights: y_j = b_j + w_j0 x_0 +
/// w_j1 x_1 + … left to right (the documented order), then `act`. `p` starts at the layer's
/// weights (units × inputs), followed by its biases.
fn reference_layer(p: &[f64], x: &[f64], units: usize, act: impl Fn(f64) -> f64) -> Vec<f64> {
    let n = x.len();
    (0..units)
        .map(|j| {
            let mut sum = p[units * n + j];
            for (i, xi) in x.iter().enumerate() {
                sum += p[j * n + i] * xi;
            }
            act(sum)
        })
        .collect()
}

/// The fast output kernel: tanh, and NaN → 0.
fn output_unit(a: f64) -> f64 {
    let o = tanh(a);
    if o.is_nan() {
        0.0
    } else {
        o
    }
}

#[test]
fn mlp_matches_the_documented_formula_bit_for_bit_at_every_size() {
    // Sizes that exercise every block width of the kernel (8, 4, 2, 1 units at a time).
    let mut rng = rng(6);
    for (hidden, inputs, outputs, act) in [
        (vec![16], 24, 2, "tanh"),
        (vec![16], 24, 3, "sigmoid"),
        (vec![15, 7], 5, 3, "relu"),
        (vec![1, 9], 13, 2, "tanh"),
        (vec![], 6, 3, "tanh"),
    ] {
        let text = format!("hidden = {hidden:?}\nactivation = \"{act}\"");
        let t = topology(&text, inputs, outputs);
        let p: Vec<f64> = (0..t.parameter_count())
            .map(|_| gaussian(&mut rng))
            .collect();
        let mut b = Brain::new(&t, &p).expect("valid");
        let f = |a: f64| match act {
            "tanh" => tanh(a),
            "sigmoid" => sigma(a),
            _ => a.max(0.0),
        };
        for _ in 0..20 {
            let x: Vec<f64> = (0..inputs).map(|_| gaussian(&mut rng) * 2.0).collect();
            let mut v = x.clone();
            let mut offset = 0;
            for &units in &hidden {
                let next = reference_layer(&p[offset..], &v, units, f);
                offset += units * (v.len() + 1);
                v = next;
            }
            let expected = reference_layer(&p[offset..], &v, outputs, output_unit);
            let got = run(&mut b, &x);
            assert!(
                got.iter()
                    .zip(&expected)
                    .all(|(g, e)| g.to_bits() == e.to_bits()),
                "{text}: {got:?} != {expected:?}"
            );
        }
    }
}

#[test]
fn recurrent_matches_the_documented_formula_bit_for_bit() {
    // h = act(b_h + W_h [x, c]), o = tanh(b_out + W_out h), c = h; 11 hidden units use the
    // kernel's 8-, 2- and 1-unit blocks.
    let mut rng = rng(7);
    let (inputs, hidden, outputs) = (6, 11, 3);
    let t = topology("kind = \"recurrent\"\nhidden = [11]", inputs, outputs);
    let p: Vec<f64> = (0..t.parameter_count())
        .map(|_| gaussian(&mut rng) * 0.5)
        .collect();
    let mut b = Brain::new(&t, &p).expect("valid");
    let mut context = vec![0.0; hidden];
    let output_start = hidden * (inputs + hidden + 1);
    for tick in 0..20 {
        let x: Vec<f64> = (0..inputs).map(|_| gaussian(&mut rng)).collect();
        let extended: Vec<f64> = x.iter().chain(&context).copied().collect();
        let h = reference_layer(&p, &extended, hidden, tanh);
        let expected = reference_layer(&p[output_start..], &h, outputs, output_unit);
        let got = run(&mut b, &x);
        assert!(
            got.iter()
                .zip(&expected)
                .all(|(g, e)| g.to_bits() == e.to_bits()),
            "tick {tick}: {got:?} != {expected:?}"
        );
        context = h;
    }
}

// ---------------------------------------------------------------------------------------------
// Elman recurrent network

/// 1 input, 1 hidden unit, 1 output: w_h[0][0] = 1, w_ctx[0][0] = `context`, b_h[0] = 0,
/// w_out[0][0] = 1, b_out[0] = 0.
fn elman(context: f64) -> Brain {
    brain(
        "kind = \"recurrent\"\nhidden = [1]",
        1,
        1,
        &[1.0, context, 0.0, 1.0, 0.0],
    )
}

#[test]
fn recurrent_context_changes_the_answer_to_the_same_input() {
    let mut b = elman(0.5);
    // Tick 1, context 0: h = tanh(1·1 + 0.5·0) = tanh(1) = 0.7615941559557649,
    //   o = tanh(0.7615941559557649) = 0.6420149920119997.
    let first = run(&mut b, &[1.0]);
    let h1 = tanh(0.0 + 1.0 * 1.0 + 0.5 * 0.0);
    assert_forward(
        &first,
        &[tanh(0.0 + 1.0 * h1)],
        &[0.6420149920119997],
        "tick 1",
    );
    // Tick 2, context 0.7615941559557649: h = tanh(1 + 0.38079707797788245)
    //   = tanh(1.3807970779778824) = 0.8811296283442258, o = tanh(h) = 0.7069847808056537.
    let second = run(&mut b, &[1.0]);
    let h2 = tanh(0.0 + 1.0 * 1.0 + 0.5 * h1);
    assert_forward(
        &second,
        &[tanh(0.0 + 1.0 * h2)],
        &[0.7069847808056537],
        "tick 2",
    );
    assert_ne!(first, second);
    if let Brain::Recurrent(e) = &b {
        assert_forward(
            e.context(),
            &[h2],
            &[0.8811296283442258],
            "context after tick 2",
        );
    } else {
        panic!("expected a recurrent brain, got {:?}", b.kind());
    }
    // After reset() the context is 0 again: the first answer comes back bit for bit.
    b.reset();
    assert_eq!(run(&mut b, &[1.0]), first);
}

#[test]
fn recurrent_without_context_weights_is_stateless() {
    let mut b = elman(0.0);
    let first = run(&mut b, &[1.0]);
    assert_eq!(run(&mut b, &[1.0]), first);
}

// ---------------------------------------------------------------------------------------------
// CTRNN

/// One neuron, no input, one output, dt = 0.5, τ = 2 (range [2, 2]) so dt/τ = 0.25, gain 1.
/// Genes: w[0][0] = `self_weight`, bias[0] = 0, tau[0] = 0, gain[0] = 0.
fn lone_neuron(self_weight: f64) -> Brain {
    brain(
        "kind = \"ctrnn\"\nneurons = 1\nstep = 0.5\nsubsteps = 1\ntau = [2.0, 2.0]\ngain = [1.0, 1.0]",
        0,
        1,
        &[self_weight, 0.0, 0.0, 0.0],
    )
}

fn ctrnn_mut(b: &mut Brain) -> &mut berry_evolve::brain::Ctrnn {
    match b {
        Brain::Ctrnn(c) => c,
        other => panic!("expected a ctrnn, got {:?}", other.kind()),
    }
}

#[test]
fn ctrnn_lone_neuron_decays_by_euler_steps() {
    let mut b = lone_neuron(0.0);
    ctrnn_mut(&mut b).set_state(&[4.0]);
    // No input, no weights: y ← y + 0.25·(-y + 0 + 0), equilibrium 0.
    // Step 1: y = 4 + 0.25·(-4) = 3; output 2σ(3) - 1 = tanh(1.5) = 0.9051482536448664.
    let out = run(&mut b, &[]);
    assert_eq!(ctrnn_mut(&mut b).state(), &[3.0]);
    assert_forward(
        &out,
        &[2.0 * sigma(1.0 * (3.0 + 0.0)) - 1.0],
        &[0.9051482536448664],
        "step 1",
    );
    // Step 2: y = 3 + 0.25·(-3) = 2.25; output 2σ(2.25) - 1 = tanh(1.125) = 0.809301070201781.
    let out = run(&mut b, &[]);
    assert_eq!(ctrnn_mut(&mut b).state(), &[2.25]);
    assert_forward(
        &out,
        &[2.0 * sigma(1.0 * (2.25 + 0.0)) - 1.0],
        &[0.809301070201781],
        "step 2",
    );
    // Then y_k = 4·0.75^k: a monotone decay toward the equilibrium.
    for k in 3..40 {
        run(&mut b, &[]);
        let y = ctrnn_mut(&mut b).state()[0];
        let expected = 4.0 * 0.75f64.powi(k);
        assert!(
            (y - expected).abs() < 1e-12,
            "step {k}: y = {y}, expected {expected}"
        );
    }
    b.reset();
    assert_eq!(ctrnn_mut(&mut b).state(), &[0.0]);
}

#[test]
fn ctrnn_self_connection_enters_through_the_firing_rate() {
    let mut b = lone_neuron(1.0);
    ctrnn_mut(&mut b).set_state(&[4.0]);
    // y = 4 + 0.25·((-4 + (0 + 1·σ(1·(4 + 0)))) + 0) = 4 + 0.25·(-4 + 0.9820137900379085)
    //   = 3.245503447509477 (with exact σ)
    run(&mut b, &[]);
    let y = ctrnn_mut(&mut b).state()[0];
    let formula = 4.0 + 0.25 * ((-4.0 + (0.0 + 1.0 * sigma(1.0 * (4.0 + 0.0)))) + 0.0);
    assert_forward(&[y], &[formula], &[3.245503447509477], "y");
}

#[test]
fn ctrnn_input_drives_every_neuron_and_substeps_are_euler_steps() {
    // One neuron, one input with w_in[0][0] = 2, w[0][0] = 0; x = 1 so I = 2, equilibrium 2.
    let params = [2.0, 0.0, 0.0, 0.0, 0.0];
    let one = "kind = \"ctrnn\"\nneurons = 1\nstep = 0.5\nsubsteps = 1\ntau = [2.0, 2.0]\ngain = [1.0, 1.0]";
    let mut b = brain(one, 1, 1, &params);
    // Tick 1: y = 0 + 0.25·(-0 + 0 + 2) = 0.5, output 2σ(0.5) - 1 = 0.2449186624037092.
    let out = |y: f64| 2.0 * sigma(1.0 * (y + 0.0)) - 1.0;
    assert_forward(
        &run(&mut b, &[1.0]),
        &[out(0.5)],
        &[0.2449186624037092],
        "tick 1",
    );
    // Tick 2: y = 0.5 + 0.25·(-0.5 + 2) = 0.875, output 2σ(0.875) - 1 = 0.4115700556740225.
    assert_forward(
        &run(&mut b, &[1.0]),
        &[out(0.875)],
        &[0.4115700556740225],
        "tick 2",
    );
    assert_eq!(ctrnn_mut(&mut b).state(), &[0.875]);
    // substeps = 2 does both Euler steps within one tick.
    let two = one.replace("substeps = 1", "substeps = 2");
    let mut b2 = brain(&two, 1, 1, &params);
    assert_forward(
        &run(&mut b2, &[1.0]),
        &[out(0.875)],
        &[0.4115700556740225],
        "two substeps",
    );
    assert_eq!(ctrnn_mut(&mut b2).state(), &[0.875]);
}

#[test]
fn ctrnn_motors_come_from_the_first_neurons() {
    // Three neurons, no input, no weights, biases [1, -1, 7]; gain 1; outputs read from
    // neurons 0 and 1: 2σ(y + θ) - 1 with y = 0 after the step (no drive).
    let t = topology("kind = \"ctrnn\"\nneurons = 3\ngain = [1.0, 1.0]", 0, 2);
    let mut p = vec![0.0; t.parameter_count()];
    let names = t.parameter_names();
    for (name, value) in [("bias[0]", 1.0), ("bias[1]", -1.0), ("bias[2]", 7.0)] {
        let i = names.iter().position(|n| n == name).expect(name);
        p[i] = value;
    }
    let mut b = Brain::new(&t, &p).expect("valid");
    // 2σ(1) - 1 = tanh(0.5) = 0.46211715726000974; 2σ(-1) - 1 = -0.46211715726000974.
    assert_forward(
        &run(&mut b, &[]),
        &[
            2.0 * sigma(1.0 * (0.0 + 1.0)) - 1.0,
            2.0 * sigma(1.0 * (0.0 + -1.0)) - 1.0,
        ],
        &[0.46211715726000974, -0.46211715726000974],
        "outputs",
    );
}

#[test]
fn ctrnn_gene_mappings_stay_in_range_for_extreme_genes() {
    let genes = [
        -f64::MAX,
        -1e300,
        -1e6,
        -745.0,
        -40.0,
        -1.0,
        -f64::MIN_POSITIVE,
        -0.0,
        0.0,
        5e-324,
        1.0,
        40.0,
        745.0,
        1e6,
        1e300,
        f64::MAX,
        f64::INFINITY,
        f64::NEG_INFINITY,
    ];
    // [0.3, 0.7]: 0.3 · (0.7 / 0.3) rounds to 0.7000000000000001, above τ_max.
    let ranges = [
        [1.0, 10.0],
        [0.1, 0.1],
        [0.3, 0.7],
        [0.1, 3.3],
        [0.5, 1e3],
        [1e-3, 1e6],
        [3.0, 3.0000000001],
    ];
    for range in ranges {
        for g in genes {
            let tau = time_constant(g, range);
            assert!(
                tau >= range[0] && tau <= range[1],
                "tau({g}) = {tau} outside {range:?}"
            );
        }
        assert_eq!(time_constant(-1e6, range), range[0]);
        let top = time_constant(1e6, range);
        assert!(
            range[1] - top <= 1e-15 * range[1],
            "tau(1e6) = {top} for {range:?}"
        );
        let middle = (range[0] * range[1]).sqrt();
        assert!(
            (time_constant(0.0, range) - middle).abs() <= 1e-12 * middle,
            "gene 0 gives the geometric middle of {range:?}"
        );
        let mut previous = 0.0;
        for k in -400..=400 {
            let tau = time_constant(f64::from(k) * 0.1, range);
            assert!(tau >= previous, "tau is monotone in the gene");
            previous = tau;
        }
    }
    for range in [[1.0, 5.0], [0.0, 0.0], [0.0, 1e9], [2.0, 2.0]] {
        for g in genes {
            let v = gain(g, range);
            assert!(
                v >= range[0] && v <= range[1],
                "gain({g}) = {v} outside {range:?}"
            );
        }
        assert_eq!(gain(-1e6, range), range[0]);
        assert_eq!(gain(1e6, range), range[1]);
    }
}

#[test]
fn ctrnn_decoded_time_constants_keep_euler_stable() {
    // step = tau[0]: dt/τ reaches 1 exactly for the fastest neuron, never more.
    let t = topology(
        "kind = \"ctrnn\"\nneurons = 6\nstep = 0.5\ntau = [0.5, 20.0]\ngain = [0.5, 3.0]",
        2,
        3,
    );
    let mut rng = rng(2);
    for _ in 0..200 {
        let p: Vec<f64> = (0..t.parameter_count())
            .map(|_| gaussian(&mut rng) * 1e3)
            .collect();
        let mut b = Brain::new(&t, &p).expect("valid");
        let c = ctrnn_mut(&mut b);
        for (&tau, &g) in c.time_constants().iter().zip(c.gains()) {
            assert!((0.5..=20.0).contains(&tau), "tau {tau}");
            assert!(0.5 / tau <= 1.0, "dt/tau = {}", 0.5 / tau);
            assert!((0.5..=3.0).contains(&g), "gain {g}");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Parameter layouts

#[test]
fn parameter_counts_follow_the_documented_formulas() {
    for (n, m) in [(0, 1), (1, 2), (24, 2), (24, 3), (7, 3)] {
        for hidden in [vec![], vec![16], vec![5, 3], vec![1, 1, 1]] {
            let t = Topology {
                spec: BrainSpec {
                    hidden: Some(hidden.clone()),
                    ..BrainSpec::default()
                },
                inputs: n,
                outputs: m,
                signals: Default::default(),
            };
            // Σ_l (H_{l-1} + 1) H_l + (H_{L-1} + 1) m, with H_{-1} = n.
            let mut expected = 0;
            let mut previous = n;
            for &h in &hidden {
                expected += (previous + 1) * h;
                previous = h;
            }
            expected += (previous + 1) * m;
            assert_eq!(t.parameter_count(), expected, "mlp {n} {hidden:?} {m}");
            assert_eq!(t.parameter_names().len(), expected);
        }
        for h in [1, 4, 16] {
            let t = topology(&format!("kind = \"recurrent\"\nhidden = [{h}]"), n, m);
            assert_eq!(
                t.parameter_count(),
                h * (n + h + 1) + m * (h + 1),
                "recurrent"
            );
            assert_eq!(t.parameter_names().len(), t.parameter_count());
        }
        for k in [m, 5, 8] {
            let t = topology(&format!("kind = \"ctrnn\"\nneurons = {k}"), n, m);
            assert_eq!(t.parameter_count(), k * n + k * k + 3 * k, "ctrnn");
            assert_eq!(t.parameter_names().len(), t.parameter_count());
        }
    }
    // The standard brain: 24 inputs, 16 tanh units, 3 outputs.
    let standard = Topology {
        spec: BrainSpec::default(),
        inputs: 24,
        outputs: 3,
        signals: Default::default(),
    };
    assert_eq!(standard.parameter_count(), 25 * 16 + 17 * 3);
}

#[test]
fn parameter_names_give_the_documented_order() {
    let t = topology("hidden = [4, 3]", 6, 2);
    let names = t.parameter_names();
    assert_eq!(names[0], "w_h0[0][0]");
    assert_eq!(names[3 * 6 + 5], "w_h0[3][5]");
    assert_eq!(names[24], "b_h0[0]");
    assert_eq!(names[28], "w_h1[0][0]");
    assert_eq!(names[28 + 12 + 2], "b_h1[2]");
    assert_eq!(names[43], "w_out[0][0]");
    assert_eq!(names[names.len() - 1], "b_out[1]");

    let t = topology("kind = \"recurrent\"\nhidden = [2]", 3, 1);
    let names = t.parameter_names();
    let expected_head = [
        "w_h[0][0]",
        "w_h[0][1]",
        "w_h[0][2]",
        "w_ctx[0][0]",
        "w_ctx[0][1]",
        "w_h[1][0]",
    ];
    assert_eq!(&names[..6], &expected_head);
    assert_eq!(names[10..12], ["b_h[0]", "b_h[1]"]);
    assert_eq!(names[12..], ["w_out[0][0]", "w_out[0][1]", "b_out[0]"]);

    let t = topology("kind = \"ctrnn\"\nneurons = 3", 2, 2);
    let names = t.parameter_names();
    assert_eq!(names[0], "w_in[0][0]");
    assert_eq!(names[5], "w_in[2][1]");
    assert_eq!(names[6], "w[0][0]");
    assert_eq!(names[6 + 9 - 1], "w[2][2]");
    assert_eq!(
        names[15..],
        [
            "bias[0]", "bias[1]", "bias[2]", "tau[0]", "tau[1]", "tau[2]", "gain[0]", "gain[1]",
            "gain[2]"
        ]
    );

    for t in [
        topology("hidden = [3, 2]", 4, 3),
        topology("kind = \"recurrent\"", 5, 2),
        topology("kind = \"ctrnn\"\nneurons = 4", 3, 3),
    ] {
        let mut names = t.parameter_names();
        names.sort();
        names.dedup();
        assert_eq!(names.len(), t.parameter_count(), "names are unique");
    }
}

// ---------------------------------------------------------------------------------------------
// Genome ↔ brain round trip, and totality

/// A parameter drawn to stress the round trip: ordinary values, signed zeros, subnormals,
/// huge values and the extremes of f64.
fn awkward_parameter(rng: &mut Rng) -> f64 {
    match below(rng, 8) {
        0 => -0.0,
        1 => 0.0,
        2 => {
            // A subnormal: exponent bits 0, random mantissa, random sign.
            let bits = (rng_u64(rng) & ((1u64 << 52) - 1)).max(1);
            let x = f64::from_bits(bits);
            if chance(rng, 0.5) {
                -x
            } else {
                x
            }
        }
        3 => [f64::MAX, -f64::MAX, f64::MIN_POSITIVE, -f64::MIN_POSITIVE][below(rng, 4) as usize],
        4 => (unit(rng) - 0.5) * 1e300,
        5 => {
            // Any finite bit pattern.
            loop {
                let x = f64::from_bits(rng_u64(rng));
                if x.is_finite() {
                    break x;
                }
            }
        }
        _ => gaussian(rng) * 3.0,
    }
}

fn rng_u64(rng: &mut Rng) -> u64 {
    use rand::RngCore;
    rng.next_u64()
}

#[test]
fn genome_to_brain_to_genome_is_bit_exact() {
    let mut rng = rng(3);
    let topologies = round_trip_topologies();
    for case in 0..3000 {
        let t = &topologies[case % topologies.len()];
        let p: Vec<f64> = (0..t.parameter_count())
            .map(|_| awkward_parameter(&mut rng))
            .collect();
        let genome = Genome::new(p.clone());
        let mut b = genome
            .decode(t)
            .unwrap_or_else(|e| panic!("case {case}: {e}"));
        let back = Genome::from_brain(&b).parameters;
        let same = back.iter().zip(&p).all(|(a, b)| a.to_bits() == b.to_bits());
        assert!(
            same && back.len() == p.len(),
            "case {case}: round trip changed bits"
        );
        // Running the brain does not touch its parameters.
        let x: Vec<f64> = (0..t.inputs).map(|_| unit(&mut rng)).collect();
        run(&mut b, &x);
        assert!(
            b.parameter_slice()
                .iter()
                .zip(&p)
                .all(|(a, b)| a.to_bits() == b.to_bits()),
            "case {case}: activate changed the parameters"
        );
    }
}

#[test]
fn every_finite_parameter_vector_gives_outputs_in_range() {
    // Huge weights overflow sums to ±∞ (and ∞ - ∞ = NaN); outputs must stay in [-1, 1].
    let mut rng = rng(4);
    let topologies = round_trip_topologies();
    for case in 0..2000 {
        let t = &topologies[case % topologies.len()];
        let p: Vec<f64> = (0..t.parameter_count())
            .map(|_| awkward_parameter(&mut rng))
            .collect();
        let mut b = Brain::new(t, &p).expect("finite parameters are valid");
        for tick in 0..5 {
            let x: Vec<f64> = (0..t.inputs).map(|_| gaussian(&mut rng) * 10.0).collect();
            let out = run(&mut b, &x);
            for (o, v) in out.iter().enumerate() {
                assert!(
                    (-1.0..=1.0).contains(v),
                    "case {case} ({:?}), tick {tick}: output {o} = {v}",
                    t.spec.kind
                );
            }
        }
    }
}

#[test]
fn overflowing_sums_give_zero_rather_than_nan() {
    // o = tanh(MAX·2 + (-MAX)·2 + 0) = tanh(∞ - ∞) = tanh(NaN): reported as 0.
    let mut b = brain("hidden = []", 2, 1, &[f64::MAX, -f64::MAX, 0.0]);
    assert_eq!(run(&mut b, &[2.0, 2.0]), [0.0]);
}

#[test]
fn same_parameters_give_the_same_bits() {
    let mut rng = rng(5);
    for t in round_trip_topologies() {
        let p: Vec<f64> = (0..t.parameter_count())
            .map(|_| gaussian(&mut rng))
            .collect();
        let mut a = Brain::new(&t, &p).expect("valid");
        let mut b = a.clone();
        for _ in 0..50 {
            let x: Vec<f64> = (0..t.inputs).map(|_| unit(&mut rng)).collect();
            let (oa, ob) = (run(&mut a, &x), run(&mut b, &x));
            assert!(oa.iter().zip(&ob).all(|(p, q)| p.to_bits() == q.to_bits()));
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Parameter errors

#[test]
fn wrong_parameter_count_is_an_error() {
    let t = topology("hidden = [2]", 2, 2);
    for len in [0, 11, 13] {
        let err = Brain::new(&t, &vec![0.0; len]).expect_err("wrong length");
        assert_eq!(
            err,
            BrainError::ParameterCount {
                expected: 12,
                got: len
            }
        );
        assert!(err.to_string().contains("needs 12, got"), "{err}");
    }
}

#[test]
fn non_finite_parameters_are_refused_with_their_name() {
    let t = topology("hidden = [2]", 2, 2);
    for (index, bad) in [(0, f64::NAN), (5, f64::INFINITY), (11, f64::NEG_INFINITY)] {
        let mut p = MLP_2_2_2;
        p[index] = bad;
        match Brain::new(&t, &p) {
            Err(BrainError::NonFinite { index: i, name, .. }) => {
                assert_eq!(i, index);
                assert_eq!(name, t.parameter_names()[index]);
            }
            other => panic!("parameter {index} = {bad}: expected NonFinite, got {other:?}"),
        }
    }
    let err = Brain::new(&t, &{
        let mut p = MLP_2_2_2;
        p[4] = f64::NAN;
        p
    })
    .expect_err("NaN");
    assert!(err.to_string().contains("`b_h0[0]`"), "{err}");
}

#[test]
fn invalid_topology_is_an_error_not_a_panic() {
    let t = Topology {
        spec: spec("kind = \"ctrnn\"\nneurons = 2"),
        inputs: 4,
        outputs: 3,
        signals: Default::default(),
    };
    let err = Brain::new(&t, &[]).expect_err("2 neurons cannot give 3 outputs");
    match err {
        BrainError::Topology(e) => assert_eq!(e.key, "brain.neurons"),
        other => panic!("expected a topology error, got {other:?}"),
    }
}

// ---------------------------------------------------------------------------------------------
// The [brain] table

#[derive(Debug, serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    brain: BrainSpec,
}

fn parse_error(text: &str) -> String {
    match toml::from_str::<File>(text) {
        Ok(f) => panic!("{text:?} should not parse, got {f:?}"),
        Err(e) => e.to_string(),
    }
}

fn invalid_key(text: &str) -> (String, String) {
    let file: File = toml::from_str(text).unwrap_or_else(|e| panic!("{text:?}: {e}"));
    let err = file
        .brain
        .validate()
        .expect_err(&format!("{text:?} should be invalid"));
    (err.key, err.reason)
}

#[test]
fn default_brain_is_mlp_16_tanh() {
    let file: File = toml::from_str("[brain]").expect("empty table");
    assert_eq!(file.brain, BrainSpec::default());
    assert_eq!(file.brain.kind, BrainKind::Mlp);
    file.brain.validate().expect("default is valid");
    let t = Topology::new(BrainSpec::default(), 10, 2).expect("valid");
    assert_eq!(t.parameter_count(), 11 * 16 + 17 * 2);
    // Spelled out, the defaults give the same brain.
    let explicit = topology(
        "kind = \"mlp\"\nhidden = [16]\nactivation = \"tanh\"",
        10,
        2,
    );
    assert_eq!(explicit.parameter_names(), t.parameter_names());
    assert_eq!(Activation::default(), Activation::Tanh);
}

#[test]
fn brain_table_round_trips_through_toml() {
    for text in [
        "kind = \"mlp\"\nhidden = [8, 4]\nactivation = \"relu\"\n",
        "kind = \"recurrent\"\nhidden = [12]\n",
        "kind = \"ctrnn\"\nneurons = 5\nstep = 0.1\nsubsteps = 10\ntau = [0.5, 8.0]\ngain = [1.0, 1.0]\n",
    ] {
        let s = spec(text);
        s.validate().expect("valid");
        let written = toml::to_string(&s).expect("serialisable");
        assert_eq!(spec(&written), s, "{written}");
    }
}

#[test]
fn unknown_key_is_refused_by_name() {
    let e = parse_error("[brain]\nkind = \"mlp\"\nhiden = [16]");
    assert!(e.contains("unknown field `hiden`"), "{e}");
    let e = parse_error("[brain]\nkind = \"perceptron\"");
    assert!(e.contains("perceptron") && e.contains("mlp"), "{e}");
    let e = parse_error("[brain]\nactivation = \"softplus\"");
    assert!(e.contains("softplus"), "{e}");
}

#[test]
fn wrong_type_is_refused_at_its_key() {
    for (text, key) in [
        ("[brain]\nhidden = \"16\"", "hidden"),
        ("[brain]\nhidden = 16", "hidden"),
        ("[brain]\nhidden = [-1]", "hidden"),
        ("[brain]\nhidden = [1.5]", "hidden"),
        ("[brain]\nkind = \"ctrnn\"\nneurons = \"many\"", "neurons"),
        ("[brain]\nkind = \"ctrnn\"\nstep = \"fast\"", "step"),
        ("[brain]\nkind = \"ctrnn\"\ntau = 3.0", "tau"),
    ] {
        let e = parse_error(text);
        assert!(e.contains(key), "{text:?}: {e}");
    }
    // A range is exactly [min, max]: a third value is an error, not silently dropped.
    let e = parse_error("[brain]\nkind = \"ctrnn\"\ntau = [1.0, 2.0, 3.0]");
    assert!(e.contains("invalid length 3"), "{e}");
    let e = parse_error("[brain]\nkind = \"ctrnn\"\ngain = [1.0]");
    assert!(e.contains("invalid length 1"), "{e}");
}

#[test]
fn bad_values_are_refused_with_their_key() {
    let cases = [
        ("[brain]\nhidden = [0]", "brain.hidden[0]"),
        ("[brain]\nhidden = [16, 0]", "brain.hidden[1]"),
        ("[brain]\nhidden = [16, 4097]", "brain.hidden[1]"),
        (
            "[brain]\nhidden = [1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1]",
            "brain.hidden",
        ),
        ("[brain]\nkind = \"recurrent\"\nhidden = []", "brain.hidden"),
        (
            "[brain]\nkind = \"recurrent\"\nhidden = [4, 4]",
            "brain.hidden",
        ),
        (
            "[brain]\nkind = \"recurrent\"\nhidden = [0]",
            "brain.hidden[0]",
        ),
        ("[brain]\nkind = \"ctrnn\"\nneurons = 0", "brain.neurons"),
        ("[brain]\nkind = \"ctrnn\"\nneurons = 4097", "brain.neurons"),
        ("[brain]\nkind = \"ctrnn\"\nstep = 0.0", "brain.step"),
        ("[brain]\nkind = \"ctrnn\"\nstep = -0.1", "brain.step"),
        ("[brain]\nkind = \"ctrnn\"\nstep = nan", "brain.step"),
        ("[brain]\nkind = \"ctrnn\"\nstep = 2.0", "brain.step"),
        ("[brain]\nkind = \"ctrnn\"\nsubsteps = 0", "brain.substeps"),
        (
            "[brain]\nkind = \"ctrnn\"\nsubsteps = 1001",
            "brain.substeps",
        ),
        (
            "[brain]\nkind = \"ctrnn\"\ntau = [0.0, 1.0]",
            "brain.tau[0]",
        ),
        (
            "[brain]\nkind = \"ctrnn\"\ntau = [1.0, inf]",
            "brain.tau[1]",
        ),
        ("[brain]\nkind = \"ctrnn\"\ntau = [5.0, 1.0]", "brain.tau"),
        (
            "[brain]\nkind = \"ctrnn\"\ngain = [-1.0, 1.0]",
            "brain.gain[0]",
        ),
        (
            "[brain]\nkind = \"ctrnn\"\ngain = [1.0, nan]",
            "brain.gain[1]",
        ),
        ("[brain]\nkind = \"ctrnn\"\ngain = [2.0, 1.0]", "brain.gain"),
    ];
    for (text, key) in cases {
        let (got, reason) = invalid_key(text);
        assert_eq!(got, key, "{text:?}: {reason}");
    }
    let (_, reason) = invalid_key("[brain]\nhidden = [5000]");
    assert!(reason.contains(&MAX_UNITS.to_string()), "{reason}");
    let (_, reason) = invalid_key("[brain]\nkind = \"ctrnn\"\nstep = 2.0");
    assert!(reason.contains("tau[0]"), "{reason}");
}

#[test]
fn fields_of_another_kind_are_refused_not_ignored() {
    for (text, key) in [
        ("[brain]\nkind = \"mlp\"\nneurons = 8", "brain.neurons"),
        ("[brain]\nstep = 0.1", "brain.step"),
        ("[brain]\nsubsteps = 2", "brain.substeps"),
        (
            "[brain]\nkind = \"recurrent\"\ntau = [1.0, 2.0]",
            "brain.tau",
        ),
        ("[brain]\nkind = \"mlp\"\ngain = [1.0, 2.0]", "brain.gain"),
        ("[brain]\nkind = \"ctrnn\"\nhidden = [16]", "brain.hidden"),
        (
            "[brain]\nkind = \"ctrnn\"\nactivation = \"tanh\"",
            "brain.activation",
        ),
    ] {
        let (got, reason) = invalid_key(text);
        assert_eq!(got, key, "{text:?}");
        assert!(reason.contains("applies only to"), "{text:?}: {reason}");
    }
    let (_, reason) = invalid_key("[brain]\nkind = \"mlp\"\nneurons = 8");
    assert!(
        reason.contains("ctrnn") && reason.contains("\"mlp\""),
        "the message names both kinds: {reason}"
    );
}

#[test]
fn topology_checks_what_needs_inputs_and_outputs() {
    let e = Topology::new(spec("kind = \"ctrnn\"\nneurons = 2"), 24, 3).expect_err("2 < 3");
    assert_eq!(e.key, "brain.neurons");
    assert!(Topology::new(spec("kind = \"ctrnn\"\nneurons = 3"), 24, 3).is_ok());
    // Two layers of 4096 units: every layer is allowed, but not the total.
    let e = Topology::new(spec("hidden = [4096, 4096]"), 24, 3).expect_err("too many");
    assert_eq!(e.key, "brain.hidden");
    assert!(e.reason.contains(&MAX_PARAMETERS.to_string()), "{e}");
    let e = Topology::new(spec("kind = \"ctrnn\"\nneurons = 4096"), 24, 3).expect_err("too many");
    assert_eq!(e.key, "brain.neurons");
    // Huge input counts saturate instead of overflowing.
    let t = Topology {
        spec: BrainSpec::default(),
        inputs: usize::MAX,
        outputs: 3,
        signals: Default::default(),
    };
    assert_eq!(t.parameter_count(), usize::MAX);
    assert!(t.validate().is_err());
}

// ---------------------------------------------------------------------------------------------
// BrainController

/// A direct 1-input brain whose outputs are tanh of its biases (all weights 0).
fn biased(biases: &[f64]) -> Brain {
    let m = biases.len();
    let mut p = vec![0.0; m];
    p.extend_from_slice(biases);
    brain("hidden = []", 1, m, &p)
}

#[test]
fn controller_maps_outputs_to_motors_and_eat() {
    assert_eq!(output_count(false), 2);
    assert_eq!(output_count(true), 3);
    // Outputs tanh(0.5 + 0·1) ≈ 0.46211715726000974, tanh(-0.25 + 0·1) ≈ -0.24491866240370913
    // (the fast tanh, within TANH_MAX_ERROR of these), tanh(0 + 0·1) = 0.
    let mut c = BrainController::new(biased(&[0.5, -0.25, 0.0]), 4.0, true);
    let cmd = c.act(&[1.0]);
    assert_eq!(cmd.left, 4.0 * tanh(0.5), "{cmd:?}");
    assert_eq!(cmd.right, 4.0 * tanh(-0.25), "{cmd:?}");
    assert!(
        (cmd.left - 4.0 * 0.46211715726000974).abs() < 4.0 * TANH_MAX_ERROR,
        "{cmd:?}"
    );
    assert!(
        (cmd.right + 4.0 * 0.24491866240370913).abs() < 4.0 * TANH_MAX_ERROR,
        "{cmd:?}"
    );
    // eat = (o2 + 1) / 2 = (0 + 1) / 2.
    assert_eq!(cmd.eat, 0.5);
    assert_eq!(c.last_outputs().len(), 3);
    assert_eq!(c.brain().outputs(), 3);

    // Saturated outputs give ±max_rpt and eat 0 or 1: tanh(40) = 1 and tanh(-40) = -1 exactly.
    let mut c = BrainController::new(biased(&[40.0, -40.0, -40.0]), 0.25, true);
    let cmd = c.act(&[0.0]);
    assert_eq!((cmd.left, cmd.right, cmd.eat), (0.25, -0.25, 0.0));
    let mut c = BrainController::new(biased(&[0.0, 0.0, 40.0]), 0.25, true);
    assert_eq!(c.act(&[0.0]).eat, 1.0);

    // Without an eat output, eat is 0 whatever the brain does.
    let mut c = BrainController::new(biased(&[-0.5, 0.5]), 2.0, false);
    let cmd = c.act(&[1.0]);
    assert_eq!(cmd.left, 2.0 * tanh(-0.5), "{cmd:?}");
    assert_eq!(cmd.right, 2.0 * tanh(0.5), "{cmd:?}");
    assert!(
        (cmd.left + 2.0 * 0.46211715726000974).abs() < 2.0 * TANH_MAX_ERROR,
        "{cmd:?}"
    );
    assert_eq!(cmd.eat, 0.0);
}

#[test]
fn controller_refuses_a_brain_with_the_wrong_output_count() {
    let err = BrainController::try_new(biased(&[0.0, 0.0]), 1.0, true).expect_err("2 != 3");
    assert_eq!(
        err,
        BrainError::OutputCount {
            expected: 3,
            got: 2
        }
    );
    assert!(BrainController::try_new(biased(&[0.0, 0.0, 0.0]), 1.0, false).is_err());
}

#[test]
#[should_panic(expected = "the controller needs 3")]
fn controller_new_panics_on_output_mismatch() {
    BrainController::new(biased(&[0.0, 0.0]), 1.0, true);
}

#[test]
fn controller_reset_clears_recurrent_state() {
    let mut c = BrainController::new(
        brain(
            "kind = \"recurrent\"\nhidden = [1]",
            1,
            2,
            &[1.0, 0.5, 0.0, 1.0, 0.0, 1.0, 0.0],
        ),
        1.0,
        false,
    );
    let first = c.act(&[1.0]);
    assert_ne!(c.act(&[1.0]), first);
    c.reset();
    assert_eq!(c.act(&[1.0]), first);
}
