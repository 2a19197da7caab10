//! The simulator (`berry_evolve::sim` and the geometry under it): the report's equations on
//! hand-computed cases, the world tables, placement, gadgets, seeded invariants, and the
//! acceleration structures compared bit for bit with the plain loops.

#[path = "../sim_common/mod.rs"]
mod sim_common;

mod contact_cells_vs_brute_force;
mod food_and_metabolism;
mod gadgets;
mod geometry;
mod grid_vs_brute_force;
mod invariants;
mod invariants_under_load;
mod landmarks_areas_eye_noise;
mod motion;
mod mover_cells_vs_brute_force;
mod observation_offsets;
mod observe_into;
mod placement;
mod report_pieces;
mod scripted_controllers;
mod smell;
mod spec_tables;
mod trace_determinism;
mod whisker_cells_vs_plain_loops;
mod whisker_pictures;
mod world_events;
