//! The per-tick trace CSV: one row per creature per tick with its pose, senses, shock and
//! metabolism, for plotting a trial and for byte-for-byte determinism checks.
//!
//! Columns (header written once): `tick` (ticks done, so 1 after the first step), `creature`
//! (index), `x`, `y` (LU, after the tick's move), `heading` (radians, atan2 of the heading's
//! y and x; positive is clockwise on screen), `whisker_left`, `whisker_right` (0/1, sensed at
//! the start of the tick), `smell_left`, `smell_right` (sum of the 8 receptors of each
//! sensor, sensed at the start of the tick; 0 unless smell is an input or
//! `World::set_full_sensing` is on), `food_a`..`food_d` (food detectors, 0/1, start of the
//! tick), `shock` (0/1, the shock state at the end of the tick, which the shock sensor reads
//! next tick), `m_a`..`m_d` (metabolism after the tick), `alive` (0/1).
//!
//! Rows cover every creature on every tick, dead ones included (alive = 0, pose and
//! metabolism as they were when it died). `simulate` stops after the tick in which the last
//! creature died, so its trace ends on the first tick whose rows all say alive = 0: the same
//! rule as a scored trial, whose trace `replay --trace` writes ([`crate::evo::trace`]). A creature
//! killed in tick 58 has rows up to tick 58 (alive = 0 there) and lived 57 ticks
//! (`ticks_alive`: the ticks at whose end it was alive).
//!
//! Numbers are written by the csv crate's shortest round-trip formatting, so the same world
//! gives the same bytes.
//!
//! This is the small trace of `berry-evolve simulate`. The trace of the whole world (every
//! creature's observation and command, wanderers, predators, food amounts, events and a
//! description of the world), recorded on the one trial path for `replay`, is
//! [`crate::evo::trace`] (what is recorded, by a watcher of the trial beside the trial code)
//! and [`files`] (its CSV and JSON-lines files).

pub mod files;

use crate::sim::World;
use serde::Serialize;
use std::io::Write;

/// One row of the trace.
#[derive(Debug, Serialize)]
struct TraceRow {
    tick: u64,
    creature: usize,
    x: f64,
    y: f64,
    heading: f64,
    whisker_left: u8,
    whisker_right: u8,
    smell_left: f64,
    smell_right: f64,
    food_a: u8,
    food_b: u8,
    food_c: u8,
    food_d: u8,
    shock: u8,
    m_a: f64,
    m_b: f64,
    m_c: f64,
    m_d: f64,
    alive: u8,
}

/// Writes a trace CSV to `W`, one call to [`TraceWriter::write_tick`] after each step.
pub struct TraceWriter<W: Write> {
    csv: csv::Writer<W>,
}

impl<W: Write> TraceWriter<W> {
    /// A trace writer to `w`; the header is written with the first row.
    pub fn new(w: W) -> Self {
        TraceWriter {
            csv: csv::WriterBuilder::new().has_headers(true).from_writer(w),
        }
    }

    /// Writes one row per creature (dead ones included, with `alive = 0`) for the world's
    /// current state.
    pub fn write_tick(&mut self, world: &World) -> Result<(), csv::Error> {
        let bit = |b: bool| u8::from(b);
        for (i, c) in world.creatures().iter().enumerate() {
            let m = c.metabolism;
            self.csv.serialize(TraceRow {
                tick: world.tick(),
                creature: i,
                x: c.pose.position.x,
                y: c.pose.position.y,
                heading: libm::atan2(c.pose.heading.y, c.pose.heading.x),
                whisker_left: bit(c.whiskers[0]),
                whisker_right: bit(c.whiskers[1]),
                smell_left: c.smell[0].iter().sum(),
                smell_right: c.smell[1].iter().sum(),
                food_a: bit(c.food_detectors[0]),
                food_b: bit(c.food_detectors[1]),
                food_c: bit(c.food_detectors[2]),
                food_d: bit(c.food_detectors[3]),
                shock: bit(c.shocked),
                m_a: m[0],
                m_b: m[1],
                m_c: m[2],
                m_d: m[3],
                alive: bit(c.alive),
            })?;
        }
        Ok(())
    }

    /// Flushes buffered rows to the underlying writer.
    pub fn flush(&mut self) -> std::io::Result<()> {
        self.csv.flush()
    }

    /// Flushes and returns the underlying writer.
    pub fn into_inner(self) -> Result<W, csv::Error> {
        self.csv
            .into_inner()
            .map_err(|e| csv::Error::from(e.into_error()))
    }
}
