//! No allocation per tick: a counting global allocator (`alloc_common`, per thread, so the
//! tests may run side by side) watches the world's tick, the lockstep tick and the brains.
//!
//! Its own test binary because `#[global_allocator]` is process-wide: the other test binaries
//! keep the system allocator the program itself runs on.

#[path = "../alloc_common/mod.rs"]
mod alloc_common;
#[path = "../brain_common/mod.rs"]
mod brain_common;
#[path = "../sim_common/mod.rs"]
mod sim_common;

mod brain_activate_and_act;
mod brain_batches;
mod lockstep_tick;
mod world_step;
