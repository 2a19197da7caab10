//! `Brain::activate` and `BrainController::act` allocate nothing per tick, for every brain kind
//! (the topologies of the genome round trip in tests/brain/networks.rs).

use berry_evolve::brain::{Brain, BrainController};
use berry_evolve::seed::{gaussian, unit};
use berry_evolve::sim::controller::Controller;

use crate::alloc_common::allocations;
use crate::brain_common::{rng, round_trip_topologies};

#[test]
fn activate_and_act_allocate_nothing() {
    let mut rng = rng(6);
    for t in round_trip_topologies() {
        let p: Vec<f64> = (0..t.parameter_count())
            .map(|_| gaussian(&mut rng))
            .collect();
        let x: Vec<f64> = (0..t.inputs).map(|_| unit(&mut rng)).collect();
        let mut out = vec![0.0; t.outputs];
        let mut b = Brain::new(&t, &p).expect("valid");
        // The counter sees allocations on this thread.
        let before = allocations();
        std::hint::black_box(vec![0u8; 16]);
        assert!(allocations() > before, "the allocation counter works");
        let before = allocations();
        for _ in 0..100 {
            b.activate(&x, &mut out);
        }
        b.reset();
        assert_eq!(allocations(), before, "{:?} allocated in activate", t.spec);

        if t.outputs >= 2 {
            let mut c = BrainController::new(b, 3.0, t.outputs == 3);
            let before = allocations();
            for _ in 0..100 {
                c.act(&x);
            }
            assert_eq!(allocations(), before, "{:?} allocated in act", t.spec);
        }
    }
}

/// A plastic MLP's tick (forward pass, modulation and weight update) and its reset allocate
/// nothing either, for every granularity, random initial weights and every modulator kind.
#[test]
fn plastic_activate_and_reset_allocate_nothing() {
    use berry_evolve::brain::{SignalInputs, Topology};
    let mut rng = rng(7);
    for table in [
        "plasticity = \"hebbian\"",
        "plasticity = \"hebbian\"\ngranularity = \"synapse\"\ninitial_weights = \"random\"",
        "plasticity = \"neuromodulated\"\ngranularity = \"layer\"\n\
         modulators = [\"food_b\", \"shock\", \"metabolism_change\", \"neurons\"]\n\
         modulatory_neurons = 3",
    ] {
        let t = Topology {
            spec: crate::brain_common::spec(&format!("hidden = [6, 5]\n{table}")),
            inputs: 12,
            outputs: 3,
            signals: SignalInputs {
                food: Some(0),
                shock: Some(4),
                metabolism: Some(5),
            },
        };
        let p: Vec<f64> = (0..t.parameter_count())
            .map(|_| gaussian(&mut rng))
            .collect();
        let mut b = Brain::new(&t, &p).expect("valid");
        let mut out = vec![0.0; t.outputs];
        let before = allocations();
        for _ in 0..100 {
            let x = [
                0.5, 0.0, 1.0, 0.25, 1.0, 3.0, 2.0, 1.0, 0.0, -0.5, 0.75, 1.0,
            ];
            b.activate(&x, &mut out);
        }
        b.reset();
        assert_eq!(
            allocations(),
            before,
            "{table} allocated in activate or reset"
        );
    }
}
