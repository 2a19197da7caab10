//! Batched MLP forward passes (`BrainController::act_batch`) allocate nothing once warmed
//! up, and still give every observation the command `act` gives alone.

use berry_evolve::brain::BrainController;
use berry_evolve::sim::controller::{Controller, MotorCommand};

use crate::alloc_common::allocations;
use crate::brain_common::batch::{brain, values};

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
