//! Batched MLP forward passes through the public API: `Brain::activate_batch` and
//! `BrainController::act_batch` give every observation the bits of a single pass, for every
//! activation and many batch sizes, and allocate nothing once warmed up.

use berry_evolve::brain::{Brain, BrainController, BrainSpec, Topology};
use berry_evolve::seed::{stream, uniform, Generation, IndividualId, Purpose, Seed, TrialIndex};
use berry_evolve::sim::controller::{Controller, MotorCommand};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

// Allocation counting per thread (tests run on several threads at once).
struct CountingAllocator;

thread_local! {
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

unsafe impl GlobalAlloc for CountingAllocator {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.with(|c| c.set(c.get() + 1));
        System.alloc(layout)
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        System.dealloc(ptr, layout)
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.with(|c| c.set(c.get() + 1));
        System.realloc(ptr, layout, new_size)
    }
}

#[global_allocator]
static GLOBAL: CountingAllocator = CountingAllocator;

fn allocations() -> usize {
    ALLOCATIONS.with(|c| c.get())
}

fn values(seed: u64, count: usize, bound: f64) -> Vec<f64> {
    let mut rng = stream(
        Seed(seed),
        Purpose::Baseline,
        Generation(0),
        IndividualId(0),
        TrialIndex(0),
    );
    (0..count)
        .map(|_| uniform(&mut rng, -bound, bound))
        .collect()
}

fn brain(toml_text: &str, inputs: usize, outputs: usize, seed: u64) -> Brain {
    let spec: BrainSpec = toml::from_str(toml_text).expect("spec");
    let topology = Topology::new(spec, inputs, outputs).expect("topology");
    let parameters = values(seed, topology.parameter_count(), 2.0);
    Brain::new(&topology, &parameters).expect("brain")
}

fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|f| f.to_bits()).collect()
}

#[test]
fn brain_batches_match_single_passes_bit_for_bit() {
    let shapes = [
        ("hidden = [16]", 24, 2),
        ("hidden = [16]", 24, 3),
        ("hidden = [100]", 98, 2),
        ("hidden = [7, 3]", 5, 3),
        ("hidden = []", 1, 2),
    ];
    for (k, (hidden, inputs, outputs)) in shapes.into_iter().enumerate() {
        for activation in ["tanh", "sigmoid", "relu"] {
            let text = format!("kind = \"mlp\"\n{hidden}\nactivation = \"{activation}\"");
            let mut batch = brain(&text, inputs, outputs, 100 + k as u64);
            let mut single = batch.clone();
            for n in (0..=9).chain([16, 33, 32, 5]) {
                let x = values(1000 + n as u64, n * inputs, 4.0);
                let mut y = vec![f64::NAN; n * outputs];
                batch.activate_batch(&x, &mut y);
                let mut expected = vec![0.0; n * outputs];
                for (xs, ys) in x
                    .chunks_exact(inputs)
                    .zip(expected.chunks_exact_mut(outputs))
                {
                    single.activate(xs, ys);
                }
                assert_eq!(bits(&y), bits(&expected), "{text} n={n}");
            }
        }
    }
}

#[test]
fn warmed_up_batches_allocate_nothing() {
    let mut controller = BrainController::new(brain("hidden = [16]", 24, 3, 7), 0.5, true);
    let x = values(8, 32 * 24, 1.0);
    let mut commands = vec![MotorCommand::default(); 32];
    // Warm-up: the largest batch sizes every buffer.
    controller.act_batch(&x, &mut commands);
    let before = allocations();
    for n in [32, 17, 8, 1, 0, 32, 5] {
        controller.act_batch(&x[..n * 24], &mut commands[..n]);
    }
    assert_eq!(allocations(), before, "allocations after warm-up");
    // Every command is still the one `act` gives alone.
    let mut single = BrainController::new(controller.brain().clone(), 0.5, true);
    controller.act_batch(&x, &mut commands);
    for (k, command) in commands.iter().enumerate() {
        assert_eq!(
            *command,
            single.act(&x[k * 24..(k + 1) * 24]),
            "observation {k}"
        );
    }
}
