//! End-to-end through the `berry-evolve` binary (`env!("CARGO_BIN_EXE_berry-evolve")`):
//! reproducibility, errors and reliability of every command, pictures, replay, replicates, and
//! the start-up CPU check, and working outside the repository (`new`, `bench`'s built-in worlds).

#[path = "../cli_common/mod.rs"]
mod cli_common;

mod anywhere;
mod atomic_outputs;
mod completions_and_man;
mod config_reference;
mod console_output;
mod controls_and_episode_curve;
mod dead_end_messages;
mod first_hour;
mod gadget_experiments;
mod held_out_by_name;
mod hostile_inputs;
mod json_output;
mod landmark_experiments;
mod learning_traces;
mod old_cpus;
mod one_writer_per_folder;
mod pictures;
mod plain_wording;
mod replay_in_browser;
mod replicates;
mod reproducibility_and_errors;
mod run_folder;
mod traces_end_with_the_life;
mod unwritable_outputs;
mod workload_estimate;
