//! `champions.jsonl`: each generation's best genome, one genome file object per line (JSON
//! Lines), appended as the run goes, under the same crash rules as the fitness CSV: each line
//! is written in one write and synced before a checkpoint, so the lines of every checkpointed
//! generation are on disk; on resume the lines after the checkpoint, and a half-written last
//! line, are dropped, so a resumed run ends with the same bytes as one never stopped.
//!
//! A line's `origin.generation` says which generation it is; a generation in which no
//! individual had a finite fitness has no line.

use crate::record::atomic::write_atomic;
use crate::record::genome_file::GenomeFile;
use std::fs::{File, OpenOptions};
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use thiserror::Error;

/// Why `champions.jsonl` cannot be read or written. Every variant names the file.
#[derive(Debug, Error)]
pub enum ChampionsError {
    /// Reading, writing or syncing failed.
    #[error("champions file {path}: cannot {action}: {error}")]
    Io {
        /// The file.
        path: PathBuf,
        /// What was being done.
        action: &'static str,
        /// The I/O error.
        error: io::Error,
    },
    /// A complete line is not a genome file.
    #[error("champions file {path}, line {line}: {message}; move the file out of the run folder to resume without it (the resumed run starts a new one)")]
    BadLine {
        /// The file.
        path: PathBuf,
        /// The line, from 1.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// A line's generation is not after the previous line's.
    #[error("champions file {path}, line {line}: generation {generation} follows generation {previous}; lines must be in increasing generation order")]
    OutOfOrder {
        /// The file.
        path: PathBuf,
        /// The line, from 1.
        line: usize,
        /// This line's generation.
        generation: u64,
        /// The previous line's generation.
        previous: u64,
    },
    /// The last line has no newline: a write was cut short (only [`read_champions`]).
    #[error("champions file {path}: line {line} is incomplete (the run was stopped while writing it; `resume` removes it)")]
    PartialLine {
        /// The file.
        path: PathBuf,
        /// The line, from 1.
        line: usize,
    },
}

fn io_error(path: &Path, action: &'static str, error: io::Error) -> ChampionsError {
    ChampionsError::Io {
        path: path.to_path_buf(),
        action,
        error,
    }
}

/// `champions.jsonl` open for appending.
#[derive(Debug)]
pub struct ChampionsLog {
    path: PathBuf,
    file: File,
    /// The last line's generation, to refuse lines out of order.
    last_generation: Option<u64>,
    /// Lines in the file (for messages).
    lines: usize,
}

/// The result of [`ChampionsLog::reopen_for_resume`].
#[derive(Debug)]
pub struct Reopened {
    /// The log, ready to append the line after the resumed generation.
    pub log: ChampionsLog,
    /// Complete lines removed because they came after the resumed generation.
    pub dropped_lines: usize,
    /// Whether a partial last line (from a killed write) was removed.
    pub dropped_partial_line: bool,
    /// Whether the file was missing and has been created empty (a run started by a version
    /// that did not write it, or a deleted file).
    pub created: bool,
}

/// The lines of a file, parsed up to a generation.
struct Parsed {
    champions: Vec<GenomeFile>,
    /// Bytes of the kept lines, line ends included.
    kept_bytes: usize,
    dropped_lines: usize,
    /// The line number of a partial last line.
    partial_line: Option<usize>,
}

/// Parses `bytes`, keeping the lines up to generation `keep_up_to` (all with `None`); the
/// first line of a later generation and everything after it are counted as dropped.
fn parse(path: &Path, bytes: &[u8], keep_up_to: Option<u64>) -> Result<Parsed, ChampionsError> {
    let mut parsed = Parsed {
        champions: Vec::new(),
        kept_bytes: 0,
        dropped_lines: 0,
        partial_line: None,
    };
    let mut start = 0;
    let mut line = 0;
    while start < bytes.len() {
        line += 1;
        let Some(length) = bytes[start..].iter().position(|&b| b == b'\n') else {
            parsed.partial_line = Some(line);
            break;
        };
        let end = start + length + 1;
        if parsed.dropped_lines > 0 {
            parsed.dropped_lines += 1;
            start = end;
            continue;
        }
        let champion = GenomeFile::from_slice(&bytes[start..end], path).map_err(|e| {
            ChampionsError::BadLine {
                path: path.to_path_buf(),
                line,
                message: e.to_string(),
            }
        })?;
        let Some(generation) = champion.origin.generation else {
            return Err(ChampionsError::BadLine {
                path: path.to_path_buf(),
                line,
                message: "its origin names no generation".to_string(),
            });
        };
        if keep_up_to.is_some_and(|last| generation > last) {
            parsed.dropped_lines = 1;
            start = end;
            continue;
        }
        if let Some(previous) = parsed.champions.last().and_then(|c| c.origin.generation) {
            if generation <= previous {
                return Err(ChampionsError::OutOfOrder {
                    path: path.to_path_buf(),
                    line,
                    generation,
                    previous,
                });
            }
        }
        parsed.champions.push(champion);
        parsed.kept_bytes = end;
        start = end;
    }
    Ok(parsed)
}

impl ChampionsLog {
    /// Creates (or empties) the file at `path`, atomically, and opens it for appending.
    pub fn create(path: &Path) -> Result<ChampionsLog, ChampionsError> {
        write_atomic(path, b"").map_err(|e| io_error(path, "write", e))?;
        Self::open_append(path, None, 0)
    }

    /// Reopens the file of a run that resumes after generation `last_generation`: keeps the
    /// lines up to that generation, drops later lines and a partial last line (rewriting the
    /// file atomically when anything is dropped), and opens it for appending. A missing file
    /// is created empty (see [`Reopened::created`]); a damaged kept line is refused.
    pub fn reopen_for_resume(
        path: &Path,
        last_generation: u64,
    ) -> Result<Reopened, ChampionsError> {
        let bytes = match crate::input::read_regular(path, crate::input::MAX_CHAMPIONS_BYTES) {
            Ok(bytes) => bytes,
            Err(e) if e.kind() == io::ErrorKind::NotFound => {
                return Ok(Reopened {
                    log: Self::create(path)?,
                    dropped_lines: 0,
                    dropped_partial_line: false,
                    created: true,
                })
            }
            Err(e) => return Err(io_error(path, "read", e)),
        };
        let parsed = parse(path, &bytes, Some(last_generation))?;
        if parsed.kept_bytes < bytes.len() {
            write_atomic(path, &bytes[..parsed.kept_bytes])
                .map_err(|e| io_error(path, "write", e))?;
        }
        let last = parsed.champions.last().and_then(|c| c.origin.generation);
        Ok(Reopened {
            log: Self::open_append(path, last, parsed.champions.len())?,
            dropped_lines: parsed.dropped_lines,
            dropped_partial_line: parsed.partial_line.is_some(),
            created: false,
        })
    }

    fn open_append(
        path: &Path,
        last_generation: Option<u64>,
        lines: usize,
    ) -> Result<ChampionsLog, ChampionsError> {
        let file = OpenOptions::new()
            .append(true)
            .open(path)
            .map_err(|e| io_error(path, "open for appending", e))?;
        Ok(ChampionsLog {
            path: path.to_path_buf(),
            file,
            last_generation,
            lines,
        })
    }

    /// Appends `champion` as one line, in a single write, and flushes it. Refuses a champion
    /// without a generation, or one not after the previous line's, and non-finite values.
    pub fn append(&mut self, champion: &GenomeFile) -> Result<(), ChampionsError> {
        let line = self.lines + 1;
        let generation = champion
            .origin
            .generation
            .ok_or_else(|| ChampionsError::BadLine {
                path: self.path.clone(),
                line,
                message: "refusing to write a champion whose origin names no generation"
                    .to_string(),
            })?;
        if let Some(previous) = self.last_generation.filter(|&p| generation <= p) {
            return Err(ChampionsError::OutOfOrder {
                path: self.path.clone(),
                line,
                generation,
                previous,
            });
        }
        champion
            .check_finite(&self.path)
            .map_err(|e| ChampionsError::BadLine {
                path: self.path.clone(),
                line,
                message: e.to_string(),
            })?;
        self.file
            .write_all(&champion.to_json_line())
            .and_then(|()| self.file.flush())
            .map_err(|e| io_error(&self.path, "write", e))?;
        self.last_generation = Some(generation);
        self.lines = line;
        Ok(())
    }

    /// Forces the lines written so far to disk (`fsync`). Call it before writing a checkpoint.
    pub fn sync(&mut self) -> Result<(), ChampionsError> {
        self.file
            .sync_data()
            .map_err(|e| io_error(&self.path, "sync", e))
    }
}

/// Reads every line of a champions file, strictly: each a genome file with a generation,
/// generations increasing, no partial last line.
pub fn read_champions(path: &Path) -> Result<Vec<GenomeFile>, ChampionsError> {
    let bytes = crate::input::read_regular(path, crate::input::MAX_CHAMPIONS_BYTES)
        .map_err(|e| io_error(path, "read", e))?;
    let parsed = parse(path, &bytes, None)?;
    if let Some(line) = parsed.partial_line {
        return Err(ChampionsError::PartialLine {
            path: path.to_path_buf(),
            line,
        });
    }
    Ok(parsed.champions)
}
