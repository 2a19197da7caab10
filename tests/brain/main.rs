//! Brains (`berry_evolve::brain`): hand-computed forward passes of every kind, parameter
//! layouts, the genome round trip, the `[brain]` table, the controller, batches and f32,
//! plastic brains.

#[path = "../brain_common/mod.rs"]
mod brain_common;

mod batches_and_f32;
mod networks;
mod plasticity;
