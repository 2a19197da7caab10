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
//! `--trace-jsonl PATH` writes the same data as JSON lines, each with a `type`: `world` (the
//! description, once per trial), `tick` (`trial`, `tick`, `creatures`, `actors`, `objects`,
//! `events` of that tick) and `outcome` (`trial` and each creature's score, metabolism,
//! shocked ticks). Numbers are written shortest-round-trip, or rounded to a number of
//! decimals (the replay page uses 4: a ten-thousandth of an LU).

use crate::evo::trace::{
    ActorTick, CreatureTick, Event, ObjectTick, OutcomeInfo, TrialTrace, WorldDescription,
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

/// One CSV cell.
#[derive(Serialize)]
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
    write_csv(&creatures, &header, |row| {
        let mut cells = Vec::new();
        for t in trials {
            for c in &t.creatures {
                cells.clear();
                creature_cells(t.world.trial, c, &mut cells);
                row(&cells)?;
            }
        }
        Ok(())
    })?;
    let header = names(&["trial", "tick", "kind", "index", "x", "y", "heading"]);
    write_csv(&actors, &header, |row| {
        for t in trials {
            for a in &t.actors {
                row(&[
                    Cell::U(t.world.trial),
                    Cell::U(a.tick),
                    Cell::S(a.kind.name()),
                    Cell::U(a.index as u64),
                    Cell::F(a.x),
                    Cell::F(a.y),
                    Cell::F(a.heading),
                ])?;
            }
        }
        Ok(())
    })?;
    let header = names(&[
        "trial", "tick", "object", "kind", "x", "y", "amount_a", "amount_b", "amount_c", "amount_d",
    ]);
    write_csv(&objects, &header, |row| {
        for t in trials {
            let food = &t.world.food;
            let start = food.iter().enumerate().map(|(k, f)| (0, k, f.amount));
            let changes = t.objects.iter().map(|o| (o.tick, o.object, o.amount));
            for (tick, k, amount) in start.chain(changes) {
                let f = &food[k];
                row(&[
                    Cell::U(t.world.trial),
                    Cell::U(tick),
                    Cell::U(k as u64),
                    Cell::S(&f.kind),
                    Cell::F(f.position[0]),
                    Cell::F(f.position[1]),
                    Cell::F(amount[0]),
                    Cell::F(amount[1]),
                    Cell::F(amount[2]),
                    Cell::F(amount[3]),
                ])?;
            }
        }
        Ok(())
    })?;
    let header = names(&[
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
    ]);
    write_csv(&events, &header, |row| {
        for t in trials {
            for e in &t.events {
                let from = |k: usize| e.from.map_or(EMPTY, |p| Cell::F(p[k]));
                let amount = |k: usize| e.amount.map_or(EMPTY, |a| Cell::F(a[k]));
                row(&[
                    Cell::U(t.world.trial),
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
                ])?;
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
    })
}

fn creature_cells(trial: u64, c: &CreatureTick, cells: &mut Vec<Cell<'static>>) {
    cells.extend([
        Cell::U(trial),
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
    Tick {
        trial: u64,
        tick: u64,
        creatures: Vec<CreatureTick>,
        actors: &'a [ActorTick],
        objects: &'a [ObjectTick],
        events: &'a [Event],
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
        let mut creatures = by_tick(&t.creatures, |c| c.tick);
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
