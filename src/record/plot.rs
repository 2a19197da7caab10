//! The tables `berry-evolve plot` draws, read from file, and the written picture: a CSV of
//! numbers by header name ([`Table`]), read like every other input file (a regular file, at
//! most [`crate::input::MAX_CSV_BYTES`] unless `BERRY_MAX_INPUT_BYTES` says otherwise), and
//! the SVG replaced atomically ([`write_svg`]). The drawing is [`crate::view::plot`]'s.
//!
//! Two kinds of table are read, each by its header names, so columns added later (or in
//! another order) just work: a run's `fitness.csv` (and a MAP-Elites run's `archive.csv`)
//! and a `summary.csv` across seeds. Empty or non-finite cells are None.

use crate::input::{read_regular, MAX_CSV_BYTES};
use crate::record::atomic::write_atomic;
use std::path::{Path, PathBuf};
use thiserror::Error;

/// Why a plot could not be made.
#[derive(Debug, Error)]
pub enum PlotError {
    /// The table could not be read.
    #[error("cannot read {path}: {error}")]
    Read {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        error: csv::Error,
    },
    /// A needed column is missing.
    #[error("{path}: no column `{column}` in its header ({header}); {hint}")]
    Column {
        /// The file.
        path: PathBuf,
        /// The column.
        column: String,
        /// The header it has.
        header: String,
        /// What to do.
        hint: &'static str,
    },
    /// A cell is not a number.
    #[error("{path}: line {line}, column `{column}`: `{value}` is not a number")]
    Number {
        /// The file.
        path: PathBuf,
        /// Line number (1 = header).
        line: usize,
        /// The column.
        column: String,
        /// The cell.
        value: String,
    },
    /// Nothing to draw.
    #[error("{path}: {reason}")]
    Empty {
        /// The file.
        path: PathBuf,
        /// Why.
        reason: String,
    },
    /// Drawing failed.
    #[error("cannot draw the plot: {0}")]
    Draw(String),
    /// The picture could not be written.
    #[error("cannot write {path}: {error}")]
    Write {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        error: std::io::Error,
    },
}

/// A CSV table of numbers, columns by header name; empty cells are None.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    /// The file it came from.
    pub path: PathBuf,
    /// Header names.
    pub header: Vec<String>,
    /// Rows of cells.
    pub rows: Vec<Vec<Option<f64>>>,
}

impl Table {
    /// Reads a CSV file whose cells are numbers or empty.
    pub fn load(path: &Path) -> Result<Table, PlotError> {
        let read = |error| PlotError::Read {
            path: path.to_path_buf(),
            error,
        };
        // Checked and capped like every input file (a FIFO or /dev/zero is refused at once).
        let bytes = read_regular(path, MAX_CSV_BYTES).map_err(|e| read(csv::Error::from(e)))?;
        let mut reader = csv::Reader::from_reader(bytes.as_slice());
        let header: Vec<String> = reader
            .headers()
            .map_err(read)?
            .iter()
            .map(str::to_string)
            .collect();
        let mut rows = Vec::new();
        for (n, record) in reader.records().enumerate() {
            let record = record.map_err(read)?;
            let row = record
                .iter()
                .zip(&header)
                .map(|(cell, column)| {
                    let cell = cell.trim();
                    if cell.is_empty() {
                        return Ok(None);
                    }
                    cell.parse::<f64>()
                        .map(|x| x.is_finite().then_some(x))
                        .map_err(|_| PlotError::Number {
                            path: path.to_path_buf(),
                            line: n + 2,
                            column: column.clone(),
                            value: cell.to_string(),
                        })
                })
                .collect::<Result<Vec<_>, _>>()?;
            rows.push(row);
        }
        Ok(Table {
            path: path.to_path_buf(),
            header,
            rows,
        })
    }

    /// The index of column `name`.
    pub fn column(&self, name: &str) -> Option<usize> {
        self.header.iter().position(|h| h == name)
    }

    /// (x, y) points of column `y` against column `x`, leaving out empty cells.
    pub fn points(&self, x: usize, y: usize) -> Vec<(f64, f64)> {
        self.rows
            .iter()
            .filter_map(|r| Some((r.get(x).copied()??, r.get(y).copied()??)))
            .collect()
    }
}

/// Writes `svg` to `path` atomically.
pub fn write_svg(path: &Path, svg: &str) -> Result<(), PlotError> {
    write_atomic(path, svg.as_bytes()).map_err(|error| PlotError::Write {
        path: path.to_path_buf(),
        error,
    })
}
