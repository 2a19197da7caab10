//! The fitness CSV: one row per generation, appended as the run goes, so that a killed run
//! leaves only complete rows (plus, at worst, one partial last line that resuming removes).
//!
//! # Format
//!
//! UTF-8, `\n` line ends, a header line [`HEADER`] with the columns in [`FitnessRow`]'s field
//! order, then one line per generation in increasing generation order. Nothing is quoted
//! (every field is a number).
//!
//! Integers are written in decimal. Floats are written by the `csv` crate's serializer, which
//! uses `ryu`: the shortest decimal that reads back to the same bits (`0.1`, `1e-308`,
//! `0.30000000000000004`, `-0.0`, integral values with a `.0`, e.g. `3.0`), so the text is a
//! pure function of the bits on every platform, and [`read_rows`] (Rust's correctly rounded
//! `str::parse::<f64>`) gives the bits back. Non-finite values, which a correct run does not
//! produce, would be written `NaN`, `inf` and `-inf` and also read back.
//!
//! # Crash safety
//!
//! [`FitnessCsv::create`] writes the header atomically. [`FitnessCsv::append`] formats a row in
//! memory and hands the whole line to the kernel in one `write` (the file is opened in append
//! mode), so a killed process leaves complete lines and, if the kernel was interrupted
//! mid-write, one partial last line without its `\n`. [`FitnessCsv::reopen_for_resume`] drops
//! that partial line and every row after the generation the run resumes from.
//!
//! `append` does not `fsync` (the kernel keeps written data when a process is killed); call
//! [`FitnessCsv::sync`] before writing a checkpoint so that after a power loss the CSV is never
//! behind the checkpoint.

use std::fs::{File, OpenOptions};
use std::io::{self, Write};
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use thiserror::Error;

use super::atomic::write_atomic;
use crate::evo::search::grid::QD_COLUMNS;

/// The header line, without its `\n`: the columns in [`FitnessRow`]'s field order.
pub const HEADER: &str = "generation,evaluations,best,mean,median,worst,std,best_ever,\
mean_food_a,mean_food_b,mean_food_c,mean_food_d,best_food_a,best_food_b,best_food_c,\
best_food_d,non_finite";

/// The number of columns.
pub const COLUMNS: usize = 17;

/// One generation's line of the fitness CSV. The field order is the column order.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FitnessRow {
    /// The generation, counted from 0 (the random initial population).
    pub generation: u64,
    /// Evaluations (individual × trial lives) run so far in the whole run, this generation
    /// included.
    pub evaluations: u64,
    /// The best fitness of this generation's population.
    pub best: f64,
    /// The mean fitness of this generation's population.
    pub mean: f64,
    /// The median fitness of this generation's population.
    pub median: f64,
    /// The worst fitness of this generation's population.
    pub worst: f64,
    /// The standard deviation of this generation's fitness values.
    pub std: f64,
    /// The best fitness seen in any generation so far, this one included.
    pub best_ever: f64,
    /// Population mean of metabolic component fA at the end of life (averaged over trials).
    pub mean_food_a: f64,
    /// Population mean of metabolic component fB at the end of life (averaged over trials).
    pub mean_food_b: f64,
    /// Population mean of metabolic component fC at the end of life (averaged over trials).
    pub mean_food_c: f64,
    /// Population mean of metabolic component fD at the end of life (averaged over trials).
    pub mean_food_d: f64,
    /// Metabolic component fA at the end of life (averaged over trials) of this generation's
    /// best individual.
    pub best_food_a: f64,
    /// Metabolic component fB at the end of life (averaged over trials) of this generation's
    /// best individual.
    pub best_food_b: f64,
    /// Metabolic component fC at the end of life (averaged over trials) of this generation's
    /// best individual.
    pub best_food_c: f64,
    /// Metabolic component fD at the end of life (averaged over trials) of this generation's
    /// best individual.
    pub best_food_d: f64,
    /// Evaluations of this generation whose brain produced NaN or an infinity.
    pub non_finite: u64,
}

/// An error about a fitness CSV; always names the file. Messages contain their cause, so no
/// variant has a `source()` (a cause-chain printer would print it twice).
#[derive(Debug, Error)]
pub enum FitnessCsvError {
    /// Reading, writing or opening failed.
    #[error("fitness csv {path}: cannot {action}: {error}")]
    Io {
        /// The file.
        path: PathBuf,
        /// What was being done: "read", "write", "open for appending", "sync".
        action: &'static str,
        /// The cause (in the message too, so not also a `source()`).
        error: io::Error,
    },
    /// The first line is not [`HEADER`] (followed by the expected extra columns).
    #[error("fitness csv {path}: not a berry-evolve fitness csv of this experiment: the first line is `{found}`, expected `{expected}`")]
    Header {
        /// The file.
        path: PathBuf,
        /// The first line (shortened).
        found: String,
        /// The header expected.
        expected: String,
    },
    /// A complete line that is not a valid row.
    #[error("fitness csv {path}, line {line}: {message}")]
    BadRow {
        /// The file.
        path: PathBuf,
        /// 1-based line number (the header is line 1).
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// The last line has no line end: the run was killed while writing it.
    #[error("fitness csv {path}, line {line}: incomplete last row (the run was stopped while writing it)")]
    PartialLine {
        /// The file.
        path: PathBuf,
        /// 1-based line number.
        line: usize,
    },
    /// Rows out of increasing generation order, in the file or in appends.
    #[error("fitness csv {path}, line {line}: generation {generation} follows generation {previous}; rows must be in increasing generation order")]
    OutOfOrder {
        /// The file.
        path: PathBuf,
        /// 1-based line number (of the file, or that the append would have written).
        line: usize,
        /// The row's generation.
        generation: u64,
        /// The previous row's generation.
        previous: u64,
    },
    /// Resuming after `expected`, but the file has no row for it.
    #[error("fitness csv {path}: {}, but the run resumes after generation {expected}; rows are missing", match .last_row { Some(g) => format!("the rows end at generation {g}"), None => "there are no rows".to_string() })]
    MissingRows {
        /// The file.
        path: PathBuf,
        /// The last row's generation at or before `expected`, if any.
        last_row: Option<u64>,
        /// The generation the run resumes after.
        expected: u64,
    },
}

/// A fitness CSV open for appending rows.
#[derive(Debug)]
pub struct FitnessCsv {
    path: PathBuf,
    file: File,
    /// The last row's generation, to refuse rows out of order.
    last_generation: Option<u64>,
    /// Lines in the file, header included (for messages).
    lines: usize,
    /// The line being appended; the buffer is reused from row to row.
    line: Vec<u8>,
    /// The columns after [`HEADER`]'s, by name (see [`extra_columns`]).
    extra: Vec<String>,
}

/// The result of [`FitnessCsv::reopen_for_resume`].
#[derive(Debug)]
pub struct Reopened {
    /// The CSV, ready to append the row after the resumed generation.
    pub csv: FitnessCsv,
    /// Complete rows removed because they came after the resumed generation.
    pub dropped_rows: usize,
    /// Whether a partial last line (from a killed write) was removed.
    pub dropped_partial_line: bool,
}

impl FitnessCsv {
    /// Creates (or replaces) the file at `path` holding only the header, atomically.
    pub fn create(path: &Path) -> Result<FitnessCsv, FitnessCsvError> {
        Self::create_with(path, &[])
    }

    /// [`FitnessCsv::create`] for a file with `extra` columns after [`HEADER`]'s (see
    /// [`extra_columns`]); with none, the same file.
    pub fn create_with(path: &Path, extra: &[String]) -> Result<FitnessCsv, FitnessCsvError> {
        write_atomic(path, format!("{}\n", header(extra)).as_bytes())
            .map_err(|e| io_error(path, "write", e))?;
        Self::open_append(path, None, 1, extra)
    }

    /// Reopens the CSV of a run that resumes from a checkpoint taken after generation
    /// `last_generation`: keeps the header and the rows up to and including
    /// `last_generation`, drops later rows and a partial last line (rewriting the file
    /// atomically when anything is dropped), and opens it for appending.
    ///
    /// The kept rows must end with `last_generation`'s row (else [`FitnessCsvError::MissingRows`]):
    /// a gap would make the resumed file differ from an uninterrupted run's. A run resuming
    /// before any row was written starts a new file with [`FitnessCsv::create`] instead.
    pub fn reopen_for_resume(
        path: &Path,
        last_generation: u64,
    ) -> Result<Reopened, FitnessCsvError> {
        Self::reopen_for_resume_with(path, last_generation, &[])
    }

    /// [`FitnessCsv::reopen_for_resume`] for a file with `extra` columns (its header must
    /// name exactly these).
    pub fn reopen_for_resume_with(
        path: &Path,
        last_generation: u64,
        extra: &[String],
    ) -> Result<Reopened, FitnessCsvError> {
        let bytes = crate::input::read_regular(path, crate::input::MAX_CSV_BYTES)
            .map_err(|e| io_error(path, "read", e))?;
        let parsed = parse(path, &bytes, Some(last_generation), Some(extra))?;
        let last_row = parsed.rows.last().map(|r| r.generation);
        if last_row != Some(last_generation) {
            return Err(FitnessCsvError::MissingRows {
                path: path.to_path_buf(),
                last_row,
                expected: last_generation,
            });
        }
        let dropped_partial_line = parsed.partial_line.is_some();
        if parsed.kept_bytes < bytes.len() {
            write_atomic(path, &bytes[..parsed.kept_bytes])
                .map_err(|e| io_error(path, "write", e))?;
        }
        let csv = Self::open_append(path, last_row, 1 + parsed.rows.len(), extra)?;
        Ok(Reopened {
            csv,
            dropped_rows: parsed.dropped_rows,
            dropped_partial_line,
        })
    }

    fn open_append(
        path: &Path,
        last_generation: Option<u64>,
        lines: usize,
        extra: &[String],
    ) -> Result<FitnessCsv, FitnessCsvError> {
        let file = OpenOptions::new()
            .append(true)
            .open(path)
            .map_err(|e| io_error(path, "open for appending", e))?;
        Ok(FitnessCsv {
            path: path.to_path_buf(),
            file,
            last_generation,
            lines,
            line: Vec::with_capacity(512),
            extra: extra.to_vec(),
        })
    }

    /// Appends `row` as one line, in a single write, and flushes it. Refuses a row whose
    /// generation is not greater than the previous row's.
    pub fn append(&mut self, row: &FitnessRow) -> Result<(), FitnessCsvError> {
        self.append_with(row, &[])
    }

    /// [`FitnessCsv::append`] with the values of the extra columns (`None`: an empty field).
    /// Missing values at the end are written empty; more values than columns are an error.
    pub fn append_with(
        &mut self,
        row: &FitnessRow,
        extras: &[Option<f64>],
    ) -> Result<(), FitnessCsvError> {
        if extras.len() > self.extra.len() {
            return Err(io_error(
                &self.path,
                "write",
                io::Error::other(format!(
                    "{} extra values for {} extra columns",
                    extras.len(),
                    self.extra.len()
                )),
            ));
        }
        if let Some(previous) = self.last_generation {
            if row.generation <= previous {
                return Err(FitnessCsvError::OutOfOrder {
                    path: self.path.clone(),
                    line: self.lines + 1,
                    generation: row.generation,
                    previous,
                });
            }
        }
        self.line.clear();
        format_row_with(row, extras, self.extra.len(), &mut self.line)
            .map_err(|e| io_error(&self.path, "write", e))?;
        self.file
            .write_all(&self.line)
            .and_then(|()| self.file.flush())
            .map_err(|e| io_error(&self.path, "write", e))?;
        self.last_generation = Some(row.generation);
        self.lines += 1;
        Ok(())
    }

    /// Forces the rows written so far to disk (`fsync`). Call it before writing a checkpoint.
    pub fn sync(&mut self) -> Result<(), FitnessCsvError> {
        self.file
            .sync_data()
            .map_err(|e| io_error(&self.path, "sync", e))
    }

    /// The file's path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The last row's generation, if there is a row.
    pub fn last_generation(&self) -> Option<u64> {
        self.last_generation
    }
}

/// Reads every row of the fitness CSV at `path`, strictly: the header must be [`HEADER`],
/// every line a complete row, generations increasing. A partial last line (a killed run) is
/// reported as [`FitnessCsvError::PartialLine`].
pub fn read_rows(path: &Path) -> Result<Vec<FitnessRow>, FitnessCsvError> {
    let bytes = crate::input::read_regular(path, crate::input::MAX_CSV_BYTES)
        .map_err(|e| io_error(path, "read", e))?;
    let parsed = parse(path, &bytes, None, Some(&[]))?;
    if let Some(line) = parsed.partial_line {
        return Err(FitnessCsvError::PartialLine {
            path: path.to_path_buf(),
            line,
        });
    }
    Ok(parsed.rows)
}

/// A fitness CSV read whole, with whatever extra columns its header names.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    /// The extra columns' names, in order.
    pub extra: Vec<String>,
    /// The rows, in order.
    pub rows: Vec<FitnessRow>,
    /// Per row, the extra columns' values (`None`: empty).
    pub extras: Vec<Vec<Option<f64>>>,
}

impl Table {
    /// The values of extra column `name`, one per row (`None` when the column is absent or
    /// the field empty).
    pub fn column(&self, name: &str) -> Vec<Option<f64>> {
        match self.extra.iter().position(|c| c == name) {
            Some(k) => self.extras.iter().map(|e| e[k]).collect(),
            None => vec![None; self.rows.len()],
        }
    }
}

/// Reads every row of the fitness CSV at `path` as [`read_rows`] does, accepting any extra
/// columns after [`HEADER`]'s.
pub fn read_table(path: &Path) -> Result<Table, FitnessCsvError> {
    let bytes = crate::input::read_regular(path, crate::input::MAX_CSV_BYTES)
        .map_err(|e| io_error(path, "read", e))?;
    let parsed = parse(path, &bytes, None, None)?;
    if let Some(line) = parsed.partial_line {
        return Err(FitnessCsvError::PartialLine {
            path: path.to_path_buf(),
            line,
        });
    }
    Ok(Table {
        extra: parsed.extra,
        rows: parsed.rows,
        extras: parsed.extras,
    })
}

/// The header line for `extra` columns after [`HEADER`]'s.
pub fn header(extra: &[String]) -> String {
    let mut h = HEADER.to_string();
    for c in extra {
        h.push(',');
        h.push_str(c);
    }
    h
}

/// The extra columns of `experiment`'s fitness CSV, after [`HEADER`]'s: for each behaviour
/// measure `m` it names, `best_<m>` (the generation's best individual's) and `mean_<m>` (the
/// population mean); with `[validation]` on, `validation_best` (the best validation fitness
/// among the candidates validated after this generation, empty in generations without
/// validation) and `validation_<m>` (that candidate's measures); for a search with an
/// archive (MAP-Elites), last, `qd_score`, `coverage`, `archive_size` and `max_fitness` of
/// the archive after this generation ([`crate::evo::search::grid::QdMetrics`]). None for an
/// experiment without any: the file is then exactly the plain format.
pub fn extra_columns(experiment: &crate::experiment::ExperimentConfig) -> Vec<String> {
    let measures = &experiment.behaviour.measures;
    let mut columns = Vec::new();
    for m in measures {
        columns.push(format!("best_{}", m.name()));
        columns.push(format!("mean_{}", m.name()));
    }
    if experiment.validation.enabled() {
        columns.push("validation_best".to_string());
        for m in measures {
            columns.push(format!("validation_{}", m.name()));
        }
    }
    // Only an archive search's file has them, so every other run keeps its bytes.
    if experiment.evolution.has_archive() {
        columns.extend(QD_COLUMNS.iter().map(|c| c.to_string()));
    }
    columns
}

/// [`to_bytes`] with extra columns: `extras[i]` holds row i's values (missing rows or values
/// are written empty).
pub fn to_bytes_with(
    extra: &[String],
    rows: &[FitnessRow],
    extras: &[Vec<Option<f64>>],
) -> io::Result<Vec<u8>> {
    let mut text = format!("{}\n", header(extra)).into_bytes();
    for (i, row) in rows.iter().enumerate() {
        let values = extras.get(i).map_or(&[][..], |v| &v[..]);
        format_row_with(row, values, extra.len(), &mut text)?;
    }
    Ok(text)
}

/// `rows` (header first) as the bytes of a fitness CSV, in the format `append` writes.
pub fn to_bytes(rows: &[FitnessRow]) -> io::Result<Vec<u8>> {
    let mut text = format!("{HEADER}\n").into_bytes();
    for row in rows {
        format_row(row, &mut text)?;
    }
    Ok(text)
}

/// Writes `rows` (header first) to `path`, atomically, in the format `append` writes.
pub fn write_all(path: &Path, rows: &[FitnessRow]) -> Result<(), FitnessCsvError> {
    let text = to_bytes(rows).map_err(|e| io_error(path, "write", e))?;
    write_atomic(path, &text).map_err(|e| io_error(path, "write", e))
}

/// Appends `row` and `columns` extra fields (`extras`, then empty ones) to `out` as one CSV
/// line with its `\n`. Extra values are written as the row's floats are (shortest
/// round-trip decimal, via `ryu`).
fn format_row_with(
    row: &FitnessRow,
    extras: &[Option<f64>],
    columns: usize,
    out: &mut Vec<u8>,
) -> io::Result<()> {
    format_row(row, out)?;
    if columns == 0 {
        return Ok(());
    }
    out.pop(); // the `\n`
    for k in 0..columns {
        out.push(b',');
        if let Some(Some(v)) = extras.get(k) {
            out.extend_from_slice(float_text(*v).as_bytes());
        }
    }
    out.push(b'\n');
    Ok(())
}

/// A float as the csv serializer writes it: `ryu`'s shortest round-trip text (`3.0`, `0.1`),
/// `NaN`, `inf` or `-inf`.
pub(crate) fn float_text(v: f64) -> String {
    let mut w = csv::WriterBuilder::new()
        .has_headers(false)
        .terminator(csv::Terminator::Any(b'\n'))
        .from_writer(Vec::new());
    // A single float always serialises; the fallback never shows.
    if w.serialize([v]).is_err() {
        return v.to_string();
    }
    let bytes = w.into_inner().unwrap_or_default();
    String::from_utf8_lossy(&bytes).trim_end().to_string()
}

/// Appends `row` to `out` as one CSV line with its `\n`.
fn format_row(row: &FitnessRow, out: &mut Vec<u8>) -> io::Result<()> {
    let mut writer = csv::WriterBuilder::new()
        .has_headers(false)
        .terminator(csv::Terminator::Any(b'\n'))
        .from_writer(out);
    writer
        .serialize(row)
        .map_err(|e| io::Error::other(e.to_string()))?;
    writer.flush()
}

fn io_error(path: &Path, action: &'static str, error: io::Error) -> FitnessCsvError {
    FitnessCsvError::Io {
        path: path.to_path_buf(),
        action,
        error,
    }
}

/// A parsed file: the rows kept, how many bytes they (and the header) take, what was dropped.
struct Parsed {
    rows: Vec<FitnessRow>,
    /// Length of the header and the kept rows, line ends included.
    kept_bytes: usize,
    /// Complete rows after `keep_up_to` (not parsed).
    dropped_rows: usize,
    /// The line number of a partial last line, if any.
    partial_line: Option<usize>,
    /// The extra columns' names.
    extra: Vec<String>,
    /// Per kept row, its extra values.
    extras: Vec<Vec<Option<f64>>>,
}

/// Parses `bytes`. With `keep_up_to`, stops keeping rows at the first one whose first field is
/// a greater generation; the rest of the file is counted as dropped but not checked (it is
/// discarded).
///
/// With `expect_extra`, the header must be exactly [`header`] of those columns; without, any
/// header that starts with [`HEADER`] and goes on with `,name` columns is accepted.
fn parse(
    path: &Path,
    bytes: &[u8],
    keep_up_to: Option<u64>,
    expect_extra: Option<&[String]>,
) -> Result<Parsed, FitnessCsvError> {
    let bad_row = |line: usize, message: String| FitnessCsvError::BadRow {
        path: path.to_path_buf(),
        line,
        message,
    };
    let header_end = bytes.iter().position(|&b| b == b'\n');
    let extra: Option<Vec<String>> = header_end.and_then(|end| {
        let line = &bytes[..end];
        match expect_extra {
            Some(extra) => (line == header(extra).as_bytes()).then(|| extra.to_vec()),
            None => {
                let rest = line.strip_prefix(HEADER.as_bytes())?;
                if rest.is_empty() {
                    return Some(Vec::new());
                }
                let rest = std::str::from_utf8(rest.strip_prefix(b",")?).ok()?;
                let names: Vec<String> = rest.split(',').map(str::to_string).collect();
                names.iter().all(|n| !n.is_empty()).then_some(names)
            }
        }
    });
    let header_ok = extra.is_some();
    let extra = extra.unwrap_or_default();
    let Some(header_end) = header_end.filter(|_| header_ok) else {
        let first = bytes.split(|&b| b == b'\n').next().unwrap_or_default();
        let first = String::from_utf8_lossy(first);
        let found = if first.chars().count() > 80 {
            format!("{}…", first.chars().take(80).collect::<String>())
        } else {
            first.into_owned()
        };
        return Err(FitnessCsvError::Header {
            path: path.to_path_buf(),
            found,
            expected: header(expect_extra.unwrap_or(&[])),
        });
    };

    let mut parsed = Parsed {
        rows: Vec::new(),
        kept_bytes: header_end + 1,
        dropped_rows: 0,
        partial_line: None,
        extra,
        extras: Vec::new(),
    };
    let mut start = header_end + 1;
    let mut line_number = 1;
    let mut dropping = false;
    while start < bytes.len() {
        line_number += 1;
        let Some(length) = bytes[start..].iter().position(|&b| b == b'\n') else {
            parsed.partial_line = Some(line_number);
            break;
        };
        let end = start + length + 1;
        if dropping {
            parsed.dropped_rows += 1;
            start = end;
            continue;
        }
        // A row after the kept ones is discarded whatever else it holds, so only its
        // generation is read.
        let line = &bytes[start..end];
        if keep_up_to.is_some_and(|last| leading_generation(line).is_some_and(|g| g > last)) {
            dropping = true;
            parsed.dropped_rows += 1;
            start = end;
            continue;
        }
        let (row, values) = parse_row(line, &parsed.extra).map_err(|m| bad_row(line_number, m))?;
        if let Some(previous) = parsed.rows.last() {
            if row.generation <= previous.generation {
                return Err(FitnessCsvError::OutOfOrder {
                    path: path.to_path_buf(),
                    line: line_number,
                    generation: row.generation,
                    previous: previous.generation,
                });
            }
        }
        parsed.rows.push(row);
        parsed.extras.push(values);
        parsed.kept_bytes = end;
        start = end;
    }
    Ok(parsed)
}

/// The generation at the start of a line, if its first field is a decimal integer.
fn leading_generation(line: &[u8]) -> Option<u64> {
    let field = line.split(|&b| b == b',').next()?;
    std::str::from_utf8(field).ok()?.parse().ok()
}

/// Parses one complete line (with its `\n`).
fn parse_row(line: &[u8], extra: &[String]) -> Result<(FitnessRow, Vec<Option<f64>>), String> {
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(false)
        .terminator(csv::Terminator::Any(b'\n'))
        .from_reader(line);
    let mut record = csv::StringRecord::new();
    match reader.read_record(&mut record) {
        Ok(true) => {}
        Ok(false) => return Err("empty line".into()),
        Err(e) => return Err(e.to_string()),
    }
    if record.len() != COLUMNS + extra.len() {
        return Err(format!(
            "{} fields, expected {} ({})",
            record.len(),
            COLUMNS + extra.len(),
            header(extra)
        ));
    }
    let mut values = Vec::with_capacity(extra.len());
    for (k, name) in extra.iter().enumerate() {
        let field = &record[COLUMNS + k];
        values.push(if field.is_empty() {
            None
        } else {
            Some(
                field
                    .parse::<f64>()
                    .map_err(|e| format!("column {} (`{name}`): {e}", COLUMNS + k + 1))?,
            )
        });
    }
    let plain: csv::StringRecord = record.iter().take(COLUMNS).collect();
    let row = plain.deserialize(None).map_err(|e| match e.kind() {
        csv::ErrorKind::Deserialize { err, .. } => match err.field() {
            Some(i) => format!(
                "column {} (`{}`): {}",
                i + 1,
                HEADER.split(',').nth(i as usize).unwrap_or("?"),
                err.kind()
            ),
            None => err.to_string(),
        },
        _ => e.to_string(),
    })?;
    Ok((row, values))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn header_matches_the_struct_fields() {
        let mut w = csv::Writer::from_writer(Vec::new());
        w.serialize(FitnessRow {
            generation: 0,
            evaluations: 0,
            best: 0.0,
            mean: 0.0,
            median: 0.0,
            worst: 0.0,
            std: 0.0,
            best_ever: 0.0,
            mean_food_a: 0.0,
            mean_food_b: 0.0,
            mean_food_c: 0.0,
            mean_food_d: 0.0,
            best_food_a: 0.0,
            best_food_b: 0.0,
            best_food_c: 0.0,
            best_food_d: 0.0,
            non_finite: 0,
        })
        .unwrap();
        let text = String::from_utf8(w.into_inner().unwrap()).unwrap();
        assert_eq!(text.lines().next(), Some(HEADER));
        assert_eq!(HEADER.split(',').count(), COLUMNS);
    }
}
