//! berry-evolve: a deterministic re-creation of the BERRY III artificial-creature world
//! (Balkenius, Lund University) driven by a genetic algorithm that evolves neural-network
//! controllers, evaluating whole populations in parallel.
//!
//! # Layers (dependencies point one way; `bash scripts/imports.sh` checks it)
//!
//! ```text
//! geometry, seed, validate, input, cpu, invocation  <-  sim  <-  brain  <-  experiment  <-  evo
//!                                       <-  record  <-  view  <-  run  <-  cli
//! ```
//!
//! - [`geometry`]: the report's §6, pure functions on circles, segments and rays.
//! - [`seed`]: the one function that derives every random stream from the master seed.
//! - [`validate`]: range checks that name the key; [`input`]: reading a user's file safely;
//!   [`cpu`]: does this CPU have the extensions the build was compiled for; [`invocation`]:
//!   how messages name this program (`berry-evolve`, or the path it was started by).
//! - `sim`: the world, creatures, sensors and motion (§3–§9); knows nothing of networks. The
//!   model (`sim::world`, `sim::sensors`, `sim::motion`, `sim::smell`, ...) reads as the report;
//!   what exists only for speed is in `sim::index`, bit-identical to the plain loops.
//! - `brain`: genomes and the controllers they encode (MLP, recurrent, CTRNN).
//! - `experiment`: TOML experiment files (raw `ExperimentConfig`, validated `Experiment`),
//!   `[evolution]` included; the shipped ones built into the program (`experiment::templates`).
//! - `evo`: the searches behind one ask/tell trait (`evo::search`: GA, PGPE, CMA-ES,
//!   novelty, MAP-Elites), and parallel, deterministic evaluation through one door
//!   (`evo::door`: `Evaluate { genomes, worlds }`, worlds of training generation g, a named
//!   set alone or built worlds, here or on MPI ranks): what a trial reads of the experiment,
//!   resolved once per request (`evo::trial_plan`), one trial path (`evo::trial`), the
//!   parts evaluation and lockstep share (`evo::life`), the named world sets, held-out and
//!   design included, and the random baselines (`evo::worlds`), the fitness plan and scoring
//!   (`evo::fitness`, which reads the world's events), lives of several episodes
//!   (`evo::episodes`), one creature's trial stepped by a caller (`evo::episode`), the
//!   whole-world trace of a trial recorded by a watcher of the trial path (`evo::trace`).
//! - `record`: file I/O: fitness CSV, checkpoints, genome files, trace files, the MAP-Elites
//!   archive, the tables plots read.
//! - `view`: the pictures, drawn from traces and tables: the trajectory picture
//!   (`view::render`, one function per layer of the picture), the replay page
//!   (`view::replay_html`), the fitness plots (`view::plot`), the archive's heat map
//!   (`view::heat_map`), the per-episode curve of learning (`view::episode_curve`).
//! - `run`: one run folder, by concern: errors, the folder (names, lock, own files),
//!   checkpoints, start, resume (a pure plan, then an apply step), the generation loop.
//! - `cli`: the command-line front end (lives in the binary). The Python package (`python/`,
//!   a crate of its own in this workspace) is another front door onto this library.
//!
//! rayon runs evo's evaluation (on a pool `run` builds) and the binary's `compare` and
//! `bench`; each collects in index order and reduces serially.
//!
//! # The report's sections in the code
//!
//! | § | report | code |
//! |---|---|---|
//! | §2 | units, optional start grid | `geometry::Vec2`; `sim::placement` (`place_objects`, `place_creatures`) |
//! | §3, §4.1 | arena, walls | `sim::spec::WorldSpec`, `sim::wall::{Wall, Walls}` |
//! | §4.2, §7.1–7.2 | smell, eq. 25–26 | `sim::smell` (eq. 25 once: `diffusion`; `falloff`, `Shade`, `WallShade`); plain loop `sim::sensors::Surroundings::smell_at_all`, fast pass `sim::index::senses` |
//! | §4.3, §4.4 | food, aversive objects | `sim::food::{Food, Aversive}`; regrowth `World::regenerate_food`, eating and shock in `World::move_and_contact` |
//! | §4.5.1, §4.5.2 | teleporters, locked doors | `sim::gadgets::Gadgets` (`teleport`, `trigger_doors`, `close_doors`), specs in `sim::spec` |
//! | §4.5.3, §4.6 | distal landmarks, areas | `sim::area` (`bearing`, `Area`), `World::in_safe_area` |
//! | §4.7, §4.8 | predators, wanderers | `sim::gadgets` (`Actor`, `Flyer`, `Gadgets::contacts`), `World::act_actor` |
//! | §5.1, §5.3 | creature, metabolism | `sim::creature::Creature`, `sim::spec::CreatureSpec`, `sim::metabolism` (`Metabolism`, `Decay`) |
//! | §5.2, §7.3 | food detectors, shock, whiskers | plain loops in `sim::sensors` (`food_detectors_all`, `whisker_touches_all`), fast in `sim::index::senses` |
//! | §6 | geometry, eq. 1–24 | `geometry` (`circles_touch`, `circle_touches_segment`, `segments_intersect`) |
//! | §7.4 | eye | `sim::eye::{Eye, Scene}` (ray casting) |
//! | §7.5 | noise, eq. 27 | `sim::noise::Noise` |
//! | §8.1–8.2 | motion, eq. 28–38 | `sim::motion` (`drive`, `plan_clamped_move`, `admissible`, the search); the plain §8.2 reference in `sim::motion::reference` |
//! | §9 | the tick | `sim::world::World::step` (`begin_tick`, `observe`, `apply`, `end_tick`) |
//! | — | which objects a sense or move tests | `sim::index` (static grid, smell grid, whisker cells, mover cells) |
//!
//! # Glossary (one name per concept)
//! World, Arena, Wall, Door, Food, FoodType (A–D), Odour, Aversive, Teleporter, Landmark,
//! Area, Predator, Wanderer (irrelevant creature), Creature, Body, Pose, Whisker, SmellSensor,
//! Eye, Retina, Observation, MotorCommand, Metabolism (the vector m), Brain, Genome,
//! Individual, Population, Trial, Evaluation, Fitness, GenerationReport, Checkpoint,
//! Experiment, Run.

pub mod brain;
pub mod cpu;
pub mod evo;
pub mod experiment;
pub mod geometry;
pub mod input;
pub mod invocation;
pub mod record;
pub mod run;
pub mod seed;
pub mod sim;
pub mod validate;
pub mod view;
