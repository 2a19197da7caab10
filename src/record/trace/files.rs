//! Trace files: the [`TrialTrace`]s of a replay as CSV tables in long format (one row per
//! thing per tick, for pandas) and as JSON lines (for the replay page), every file written
//! through [`crate::record::atomic`] (a temporary file renamed over the name).
//!
//! `--trace PATH.csv` writes five files next to each other (`PATH` without `.csv` is the
//! stem):
//!
//! - `PATH.csv`, the creatures: `trial, tick, creature, x, y, heading, left, right, eat,
//!   alive, shock, m_a, m_b, m_c, m_d, whisker_left, whisker_right, food_a, food_b, food_c,
//!   food_d, travelled`, then one `in_<name>` column per observation input (the names of
//!   `berry-evolve inspect`, e.g. `in_smell_left_1`, `in_bias`). One row per creature per tick
//!   (dead ones included, `alive = 0`). `tick` counts ticks done (1 after the first); `x, y`
//!   (LU, y downwards) and `heading` (radians, atan2 of the heading, positive clockwise on
//!   screen) after the tick; `left, right` (rotations per tick, clamped) and `eat` the motor
//!   command of the tick; `shock` the shock state at the end of the tick; `m_*` the metabolic
//!   vector after it; whiskers and food detectors as sensed at the start of the tick (0/1);
//!   `travelled` the distance so far; `in_*` what the brain received (sensor noise included).
//! - `STEM-actors.csv`: `trial, tick, kind, index, x, y, heading`: every wanderer, ground
//!   predator and air predator (`kind`), `index` among its kind, after every tick.
//! - `STEM-objects.csv`: `trial, tick, object, kind, x, y, amount_a, amount_b, amount_c,
//!   amount_d`: every food object at tick 0, then each one whose amount changed, after that
//!   tick.
//! - `STEM-events.csv`: `trial, tick, event, creature, target_kind, target, x, y, from_x,
//!   from_y, amount_a, amount_b, amount_c, amount_d`; `event` is `eat`, `shock` (onset),
//!   `teleport`, `door_open`, `door_close`, `attack` or `death` (see
//!   [`crate::evo::trace`] for how each is found); empty cells where a column
//!   does not apply.
//! - `STEM-world.jsonl`: one JSON object per trial, the [`WorldDescription`] of its world as
//!   built (walls with colour and opacity, doors and triggers, teleporters, areas, landmarks,
//!   food with kind, type, radius, amount and capacity, aversive objects, start poses,
//!   wanderers, predators and their waypoints, air predators), so that a picture can be drawn
//!   from the trace alone.
//!
//! A life of several episodes is one trial per episode (ticks from 1 in each): the creatures',
//! actors', objects' and events' CSV files then have an `episode` column (from 1) after
//! `trial`, and each world line an `episode` object (`episode`, `episodes`, `switched`,
//! `exchanged`, `switch_kinds`). A life of one episode has neither: its files are as they
//! always were.
//!
//! A plastic brain (`[brain] plasticity`) adds two files ([`learning_paths`]):
//!
//! - `STEM-learning.csv`: `trial, episode, tick, creature, m, g, dw_norm`: per tick the
//!   modulatory signal m (empty for a Hebbian rule), its gate g = tanh(m/2) (1 for Hebbian)
//!   and ‖Δw‖, the L2 norm of the tick's change over all plastic weights.
//! - `STEM-synapses.csv`: `trial, episode, tick, creature, synapse, layer, from, to, weight`:
//!   the followed synapses' weights (see [`crate::evo::trace`] for which), at tick 0 (the
//!   episode's start) and after every tick; `synapse` is the genome name (`w_h0[3][5]`).
//!
//! `--trace-jsonl PATH` writes the same data as JSON lines, each with a `type`: `world` (the
//! description, once per trial), `learning` (a plastic brain's followed synapses and their
//! weights at tick 0, after the world line), `tick` (`trial`, `tick`, `creatures`, `actors`,
//! `objects`, `events` of that tick, and `learning`: m, g, `dw_norm` and `weights` per
//! plastic creature) and `outcome` (`trial` and each creature's score, metabolism, shocked
//! ticks). Fixed brains' lines have no learning fields. Numbers are written
//! shortest-round-trip, or rounded to a number of decimals (the replay page uses 4: a
//! ten-thousandth of an LU).

use crate::evo::trace::{
    ActorTick, CreatureTick, Event, LearningInfo, LearningTick, ObjectTick, OutcomeInfo,
    TrialTrace, WorldDescription,
};
use crate::record::atomic::write_atomic_with;
use serde::Serialize;
use std::io::{self, Write};
use std::path::{Path, PathBuf};

/// The five files `--trace PATH` writes, PATH first.
pub fn csv_paths(path: &Path) -> [PathBuf; 5] {
    let stem = path.with_extension("");
    let sibling = |suffix: &str| {
        let mut name = stem.file_name().unwrap_or_default().to_os_string();
        name.push(suffix);
        stem.with_file_name(name)
    };
    [
        path.to_path_buf(),
        sibling("-actors.csv"),
        sibling("-objects.csv"),
        sibling("-events.csv"),
        sibling("-world.jsonl"),
    ]
}

/// The two files a plastic brain's trace adds beside `--trace PATH`: `STEM-learning.csv`
/// and `STEM-synapses.csv`.
pub fn learning_paths(path: &Path) -> [PathBuf; 2] {
    let stem = path.with_extension("");
    let sibling = |suffix: &str| {
        let mut name = stem.file_name().unwrap_or_default().to_os_string();
        name.push(suffix);
        stem.with_file_name(name)
    };
    [sibling("-learning.csv"), sibling("-synapses.csv")]
}

/// The files `--trace PATH` writes for `trials`: [`csv_paths`], then [`learning_paths`]
/// when a brain is plastic.
pub fn written_paths(trials: &[TrialTrace], path: &Path) -> Vec<PathBuf> {
    let mut out = csv_paths(path).to_vec();
    if has_learning(trials) {
        out.extend(learning_paths(path));
    }
    out
}

fn has_learning(trials: &[TrialTrace]) -> bool {
    trials.iter().any(|t| !t.learning.is_empty())
}

fn has_episodes(trials: &[TrialTrace]) -> bool {
    trials.iter().any(|t| t.world.episode.is_some())
}

/// The episode number of a trial (1 for a life of one episode).
fn episode_of(t: &TrialTrace) -> u64 {
    t.world.episode.as_ref().map_or(1, |e| e.episode)
}

/// One CSV cell.
#[derive(Clone, Copy, Serialize)]
#[serde(untagged)]
enum Cell<'a> {
    U(u64),
    F(f64),
    S(&'a str),
    Empty(Option<u8>),
}

const EMPTY: Cell<'static> = Cell::Empty(None);

fn bit(b: bool) -> Cell<'static> {
    Cell::U(u64::from(b))
}

fn opt_u(x: Option<usize>) -> Cell<'static> {
    x.map_or(EMPTY, |x| Cell::U(x as u64))
}

fn write_csv(
    path: &Path,
    header: &[String],
    rows: impl FnMut(&mut dyn FnMut(&[Cell]) -> io::Result<()>) -> io::Result<()>,
) -> io::Result<()> {
    let mut rows = rows;
    write_atomic_with(path, |w| {
        let mut csv = csv::WriterBuilder::new().has_headers(false).from_writer(w);
        csv.write_record(header).map_err(io::Error::from)?;
        rows(&mut |cells: &[Cell]| csv.serialize(cells).map_err(io::Error::from))?;
        csv.flush()
    })
}

fn names(list: &[&str]) -> Vec<String> {
    list.iter().map(|s| s.to_string()).collect()
}

/// Writes `trials` as the five CSV and JSON-lines files of [`csv_paths`]`(path)`.
pub fn write_csv_files(trials: &[TrialTrace], path: &Path) -> io::Result<()> {
    let [creatures, actors, objects, events, world] = csv_paths(path);
    let inputs: Vec<String> = trials
        .first()
        .map(|t| t.world.inputs.clone())
        .unwrap_or_default();
    let episodes = has_episodes(trials);
    // The trial column, then the episode column in lives of several episodes.
    let lead = |header: Vec<String>| -> Vec<String> {
        let mut header = header;
        if episodes {
            header.insert(1, "episode".into());
        }
        header
    };
    fn lead_cells(episodes: bool, t: &TrialTrace, cells: &mut Vec<Cell<'_>>) {
        cells.push(Cell::U(t.world.trial));
        if episodes {
            cells.push(Cell::U(episode_of(t)));
        }
    }
    let key = |t: &TrialTrace, cells: &mut Vec<Cell<'_>>| lead_cells(episodes, t, cells);
    let mut header = names(&[
        "trial",
        "tick",
        "creature",
        "x",
        "y",
        "heading",
        "left",
        "right",
        "eat",
        "alive",
        "shock",
        "m_a",
        "m_b",
        "m_c",
        "m_d",
        "whisker_left",
        "whisker_right",
        "food_a",
        "food_b",
        "food_c",
        "food_d",
        "travelled",
    ]);
    header.extend(inputs.iter().map(|n| format!("in_{n}")));
    let header = lead(header);
    write_csv(&creatures, &header, |row| {
        let mut cells = Vec::new();
        for t in trials {
            for c in &t.creatures {
                cells.clear();
                key(t, &mut cells);
                creature_cells(c, &mut cells);
                row(&cells)?;
            }
        }
        Ok(())
    })?;
    let header = lead(names(&[
        "trial", "tick", "kind", "index", "x", "y", "heading",
    ]));
    write_csv(&actors, &header, |row| {
        let mut cells = Vec::new();
        for t in trials {
            for a in &t.actors {
                cells.clear();
                key(t, &mut cells);
                cells.extend([
                    Cell::U(a.tick),
                    Cell::S(a.kind.name()),
                    Cell::U(a.index as u64),
                    Cell::F(a.x),
                    Cell::F(a.y),
                    Cell::F(a.heading),
                ]);
                row(&cells)?;
            }
        }
        Ok(())
    })?;
    let header = lead(names(&[
        "trial", "tick", "object", "kind", "x", "y", "amount_a", "amount_b", "amount_c", "amount_d",
    ]));
    write_csv(&objects, &header, |row| {
        let mut cells = Vec::new();
        for t in trials {
            let food = &t.world.food;
            let start = food.iter().enumerate().map(|(k, f)| (0, k, f.amount));
            let changes = t.objects.iter().map(|o| (o.tick, o.object, o.amount));
            for (tick, k, amount) in start.chain(changes) {
                let f = &food[k];
                cells.clear();
                key(t, &mut cells);
                cells.extend([
                    Cell::U(tick),
                    Cell::U(k as u64),
                    Cell::S(&f.kind),
                    Cell::F(f.position[0]),
                    Cell::F(f.position[1]),
                    Cell::F(amount[0]),
                    Cell::F(amount[1]),
                    Cell::F(amount[2]),
                    Cell::F(amount[3]),
                ]);
                row(&cells)?;
            }
        }
        Ok(())
    })?;
    let header = lead(names(&[
        "trial",
        "tick",
        "event",
        "creature",
        "target_kind",
        "target",
        "x",
        "y",
        "from_x",
        "from_y",
        "amount_a",
        "amount_b",
        "amount_c",
        "amount_d",
    ]));
    write_csv(&events, &header, |row| {
        let mut cells = Vec::new();
        for t in trials {
            for e in &t.events {
                let from = |k: usize| e.from.map_or(EMPTY, |p| Cell::F(p[k]));
                let amount = |k: usize| e.amount.map_or(EMPTY, |a| Cell::F(a[k]));
                cells.clear();
                key(t, &mut cells);
                cells.extend([
                    Cell::U(e.tick),
                    Cell::S(e.event.name()),
                    opt_u(e.creature),
                    e.target_kind.as_deref().map_or(EMPTY, Cell::S),
                    opt_u(e.target),
                    Cell::F(e.x),
                    Cell::F(e.y),
                    from(0),
                    from(1),
                    amount(0),
                    amount(1),
                    amount(2),
                    amount(3),
                ]);
                row(&cells)?;
            }
        }
        Ok(())
    })?;
    write_atomic_with(&world, |w| {
        for t in trials {
            serde_json::to_writer(&mut *w, &t.world)?;
            w.write_all(b"\n")?;
        }
        Ok(())
    })?;
    if has_learning(trials) {
        write_learning_csv(trials, path)?;
    }
    Ok(())
}

/// Writes the two files of [`learning_paths`] (see the module docs).
fn write_learning_csv(trials: &[TrialTrace], path: &Path) -> io::Result<()> {
    let [learning, synapses] = learning_paths(path);
    let lead = |t: &TrialTrace, tick: u64, creature: usize| {
        [
            Cell::U(t.world.trial),
            Cell::U(episode_of(t)),
            Cell::U(tick),
            Cell::U(creature as u64),
        ]
    };
    let header = names(&["trial", "episode", "tick", "creature", "m", "g", "dw_norm"]);
    write_csv(&learning, &header, |row| {
        for t in trials {
            for l in &t.learning_ticks {
                let mut cells = lead(t, l.tick, l.creature).to_vec();
                cells.extend([l.m.map_or(EMPTY, Cell::F), Cell::F(l.g), Cell::F(l.dw_norm)]);
                row(&cells)?;
            }
        }
        Ok(())
    })?;
    let header = names(&[
        "trial", "episode", "tick", "creature", "synapse", "layer", "from", "to", "weight",
    ]);
    write_csv(&synapses, &header, |row| {
        for t in trials {
            let info = |creature: usize| t.learning.iter().find(|i| i.creature == creature);
            let starts = t.learning.iter().map(|i| (0, i.creature, &i.start));
            let ticks = t
                .learning_ticks
                .iter()
                .map(|l| (l.tick, l.creature, &l.weights));
            for (tick, creature, weights) in starts.chain(ticks) {
                let Some(info) = info(creature) else { continue };
                for (s, &w) in info.synapses.iter().zip(weights) {
                    let mut cells = lead(t, tick, creature).to_vec();
                    cells.extend([
                        Cell::S(&s.name),
                        Cell::U(s.layer as u64),
                        Cell::U(s.from as u64),
                        Cell::U(s.to as u64),
                        Cell::F(w),
                    ]);
                    row(&cells)?;
                }
            }
        }
        Ok(())
    })
}

fn creature_cells(c: &CreatureTick, cells: &mut Vec<Cell<'static>>) {
    cells.extend([
        Cell::U(c.tick),
        Cell::U(c.creature as u64),
        Cell::F(c.x),
        Cell::F(c.y),
        Cell::F(c.heading),
        Cell::F(c.left),
        Cell::F(c.right),
        Cell::F(c.eat),
        bit(c.alive),
        bit(c.shock),
    ]);
    cells.extend(c.metabolism.map(Cell::F));
    cells.extend(c.whiskers.map(bit));
    cells.extend(c.food.map(bit));
    cells.push(Cell::F(c.travelled));
    cells.extend(c.inputs.iter().map(|&x| Cell::F(x)));
}

/// A line of the JSON-lines trace.
#[derive(Serialize)]
#[serde(tag = "type", rename_all = "snake_case")]
enum Line<'a> {
    World(&'a WorldDescription),
    Learning {
        trial: u64,
        creatures: &'a [LearningInfo],
    },
    Tick {
        trial: u64,
        tick: u64,
        creatures: Vec<CreatureTick>,
        actors: &'a [ActorTick],
        objects: &'a [ObjectTick],
        events: &'a [Event],
        #[serde(skip_serializing_if = "Vec::is_empty")]
        learning: Vec<LearningTick>,
    },
    Outcome {
        trial: u64,
        creatures: &'a [OutcomeInfo],
    },
}

/// `x` rounded to `decimals` decimals (as the shortest f64 that prints so), or `x` itself.
fn round(x: f64, decimals: Option<u32>) -> f64 {
    match decimals {
        Some(d) if x.is_finite() => {
            let scale = 10f64.powi(d as i32);
            let r = (x * scale).round() / scale;
            if r.is_finite() {
                r
            } else {
                x
            }
        }
        _ => x,
    }
}

fn rounded_creature(c: &CreatureTick, d: Option<u32>) -> CreatureTick {
    let q = |x: f64| round(x, d);
    CreatureTick {
        x: q(c.x),
        y: q(c.y),
        heading: q(c.heading),
        left: q(c.left),
        right: q(c.right),
        eat: q(c.eat),
        metabolism: c.metabolism.map(q),
        travelled: q(c.travelled),
        inputs: c.inputs.iter().map(|&x| q(x)).collect(),
        ..c.clone()
    }
}

/// Slices of `rows` (sorted by tick) per tick: `rows[start..end]` for each tick in turn.
fn by_tick<'a, T>(rows: &'a [T], tick: impl Fn(&T) -> u64 + 'a) -> impl FnMut(u64) -> &'a [T] + 'a {
    let mut at = 0;
    move |t| {
        while at < rows.len() && tick(&rows[at]) < t {
            at += 1;
        }
        let start = at;
        while at < rows.len() && tick(&rows[at]) == t {
            at += 1;
        }
        &rows[start..at]
    }
}

/// Writes `trials` as JSON lines to `w` (see the module docs), numbers of the per-tick
/// records rounded to `decimals` decimals when given.
pub fn write_jsonl_to(
    trials: &[TrialTrace],
    decimals: Option<u32>,
    w: &mut dyn Write,
) -> io::Result<()> {
    for t in trials {
        let trial = t.world.trial;
        serde_json::to_writer(&mut *w, &Line::World(&t.world))?;
        w.write_all(b"\n")?;
        if !t.learning.is_empty() {
            let line = Line::Learning {
                trial,
                creatures: &t.learning,
            };
            serde_json::to_writer(&mut *w, &line)?;
            w.write_all(b"\n")?;
        }
        let mut creatures = by_tick(&t.creatures, |c| c.tick);
        let mut learning = by_tick(&t.learning_ticks, |l| l.tick);
        let mut actors = by_tick(&t.actors, |a| a.tick);
        let mut objects = by_tick(&t.objects, |o| o.tick);
        let mut events = by_tick(&t.events, |e| e.tick);
        for tick in 1..=t.ticks() {
            let cs = creatures(tick)
                .iter()
                .map(|c| rounded_creature(c, decimals))
                .collect();
            let acts = actors(tick);
            let acts_rounded: Vec<ActorTick> = acts
                .iter()
                .map(|a| ActorTick {
                    x: round(a.x, decimals),
                    y: round(a.y, decimals),
                    heading: round(a.heading, decimals),
                    ..*a
                })
                .collect();
            let line = Line::Tick {
                trial,
                tick,
                creatures: cs,
                actors: &acts_rounded,
                objects: objects(tick),
                events: events(tick),
                learning: learning(tick)
                    .iter()
                    .map(|l| LearningTick {
                        m: l.m.map(|m| round(m, decimals)),
                        g: round(l.g, decimals),
                        dw_norm: round(l.dw_norm, decimals.map(|d| d + 4)),
                        weights: l.weights.iter().map(|&x| round(x, decimals)).collect(),
                        ..*l
                    })
                    .collect(),
            };
            serde_json::to_writer(&mut *w, &line)?;
            w.write_all(b"\n")?;
        }
        serde_json::to_writer(
            &mut *w,
            &Line::Outcome {
                trial,
                creatures: &t.outcomes,
            },
        )?;
        w.write_all(b"\n")?;
    }
    Ok(())
}

/// Writes `trials` as a JSON-lines file at `path` (atomically).
pub fn write_jsonl(trials: &[TrialTrace], path: &Path) -> io::Result<()> {
    write_atomic_with(path, |w| write_jsonl_to(trials, None, w))
}
