//! Evolution and evaluation (`berry_evolve::evo`, `berry_evolve::experiment`): the search seam, the GA and PGPE, MAP-Elites,
//! trials, lockstep, fitness terms and measures, validation, and experiment files.

#[path = "../cli_common/mod.rs"]
mod cli_common;

mod area_descriptors;
mod cma_es;
mod door;
mod draw_order;
mod eating_and_choice_measures;
mod episode_steps;
mod episodes_and_switches;
mod experiment_files;
mod experiment_limits;
mod fitness_terms_and_measures;
mod genetic_algorithm;
mod jobs_counted_within_a_generation;
mod known_functions;
mod lockstep_vs_single_trials;
mod map_elites;
mod measures_from_events;
mod motion_measures;
mod novelty;
mod overflowing_brains;
mod parallel_draws;
mod pgpe;
mod predator_ends_life;
mod run_guarantees;
mod search_trait;
mod sep_cma_es;
mod trial_path_observer;
mod validation_champions;
