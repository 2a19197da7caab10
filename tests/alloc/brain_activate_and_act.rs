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
