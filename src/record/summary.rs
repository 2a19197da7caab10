//! Replicate summaries: the run folders `seed-<s>/` of one experiment (made by
//! `run --seeds`) read together into `summary.csv` (per generation, quartiles across seeds of
//! the best, mean and validation fitness) and `held-out.csv` (per seed, and for random and
//! baseline genomes, the held-out fitness and behaviour measures).
//!
//! Quartiles are type 7 of Hyndman and Fan (R's and NumPy's default): for n sorted values
//! x₀ ≤ … ≤ xₙ₋₁ and p in [0, 1], h = (n − 1)·p and q(p) = x⌊h⌋ + (h − ⌊h⌋)·(x⌊h⌋₊₁ − x⌊h⌋),
//! linear interpolation between the closest ranks; one value is its own quartiles.

use crate::record::atomic::write_atomic;
use crate::record::fitness_csv::{read_table, FitnessCsvError, Table};
use serde::Serialize;
use std::path::{Path, PathBuf};
use thiserror::Error;

/// The summary file's name inside the experiment's folder.
pub const SUMMARY_FILE: &str = "summary.csv";
/// A run folder's fitness CSV (`crate::run::FITNESS_FILE`, named here because `record` sits
/// below `run`).
const FITNESS_FILE: &str = "fitness.csv";
/// The held-out file's name inside the experiment's folder.
pub const HELD_OUT_FILE: &str = "held-out.csv";

/// Why a summary could not be made.
#[derive(Debug, Error)]
pub enum SummaryError {
    /// The folder could not be listed.
    #[error("cannot list {path}: {error}")]
    List {
        /// The folder.
        path: PathBuf,
        /// The cause.
        error: std::io::Error,
    },
    /// No `seed-<s>/` folder with a fitness.csv.
    #[error("{path} holds no seed-<s>/ run folder with a fitness.csv; make them with `{program} run EXPERIMENT.toml --seeds 1..5 --out {path}`", program = crate::invocation::program())]
    NoSeeds {
        /// The folder.
        path: PathBuf,
    },
    /// A seed's fitness CSV could not be read.
    #[error(transparent)]
    Csv(#[from] FitnessCsvError),
    /// A file could not be written.
    #[error("cannot write {path}: {error}")]
    Write {
        /// The file.
        path: PathBuf,
        /// The cause.
        error: std::io::Error,
    },
}

/// The quantile of `sorted` (ascending, not empty) at `p` by linear interpolation (type 7).
pub fn quantile(sorted: &[f64], p: f64) -> f64 {
    let n = sorted.len();
    if n == 1 {
        return sorted[0];
    }
    let h = (n - 1) as f64 * p;
    let lo = h.floor() as usize;
    if lo + 1 >= n {
        return sorted[n - 1];
    }
    sorted[lo] + (h - lo as f64) * (sorted[lo + 1] - sorted[lo])
}

/// First quartile, median and third quartile of `values` (any order; empty: `None`).
pub fn quartiles(values: &[f64]) -> Option<[f64; 3]> {
    if values.is_empty() {
        return None;
    }
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    Some([
        quantile(&sorted, 0.25),
        quantile(&sorted, 0.5),
        quantile(&sorted, 0.75),
    ])
}

/// The run folders `seed-<s>/` under `folder` that hold a fitness.csv, by increasing seed.
pub fn seed_folders(folder: &Path) -> Result<Vec<(u64, PathBuf)>, SummaryError> {
    let list = |error| SummaryError::List {
        path: folder.to_path_buf(),
        error,
    };
    let mut seeds = Vec::new();
    for entry in std::fs::read_dir(folder).map_err(list)? {
        let entry = entry.map_err(list)?;
        let name = entry.file_name();
        let Some(seed) = name
            .to_str()
            .and_then(|n| n.strip_prefix("seed-"))
            .and_then(|s| s.parse::<u64>().ok())
        else {
            continue;
        };
        if entry.path().join(FITNESS_FILE).is_file() {
            seeds.push((seed, entry.path()));
        }
    }
    seeds.sort();
    if seeds.is_empty() {
        return Err(SummaryError::NoSeeds {
            path: folder.to_path_buf(),
        });
    }
    Ok(seeds)
}

/// One generation's line of `summary.csv`. The field order is the column order; `None`
/// is an empty field.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SummaryRow {
    /// The generation.
    pub generation: u64,
    /// How many seeds have a row for it.
    pub seeds: u64,
    /// First quartile across seeds of the generation's best fitness.
    pub best_q1: f64,
    /// Median across seeds of the generation's best fitness.
    pub best_median: f64,
    /// Third quartile across seeds of the generation's best fitness.
    pub best_q3: f64,
    /// First quartile across seeds of the population's mean fitness.
    pub mean_q1: f64,
    /// Median across seeds of the population's mean fitness.
    pub mean_median: f64,
    /// Third quartile across seeds of the population's mean fitness.
    pub mean_q3: f64,
    /// First quartile of `validation_best` over the seeds validated in this generation.
    pub validation_best_q1: Option<f64>,
    /// Median of `validation_best` over the seeds validated in this generation.
    pub validation_best_median: Option<f64>,
    /// Third quartile of `validation_best` over the seeds validated in this generation.
    pub validation_best_q3: Option<f64>,
}

/// Per generation (every generation some seed has), the quartiles across the seeds' tables.
pub fn summarize(tables: &[Table]) -> Vec<SummaryRow> {
    let mut generations: Vec<u64> = tables
        .iter()
        .flat_map(|t| t.rows.iter().map(|r| r.generation))
        .collect();
    generations.sort_unstable();
    generations.dedup();
    let validation: Vec<Vec<Option<f64>>> =
        tables.iter().map(|t| t.column("validation_best")).collect();
    generations
        .into_iter()
        .map(|g| {
            let mut best = Vec::new();
            let mut mean = Vec::new();
            let mut valid = Vec::new();
            for (t, v) in tables.iter().zip(&validation) {
                if let Some(k) = t.rows.iter().position(|r| r.generation == g) {
                    best.push(t.rows[k].best);
                    mean.push(t.rows[k].mean);
                    if let Some(x) = v[k] {
                        valid.push(x);
                    }
                }
            }
            let [best_q1, best_median, best_q3] = quartiles(&best).unwrap_or([0.0; 3]);
            let [mean_q1, mean_median, mean_q3] = quartiles(&mean).unwrap_or([0.0; 3]);
            let v = quartiles(&valid);
            SummaryRow {
                generation: g,
                seeds: best.len() as u64,
                best_q1,
                best_median,
                best_q3,
                mean_q1,
                mean_median,
                mean_q3,
                validation_best_q1: v.map(|q| q[0]),
                validation_best_median: v.map(|q| q[1]),
                validation_best_q3: v.map(|q| q[2]),
            }
        })
        .collect()
}

/// Reads every seed's fitness CSV under `folder` (see [`seed_folders`]).
pub fn read_seeds(folder: &Path) -> Result<Vec<(u64, Table)>, SummaryError> {
    seed_folders(folder)?
        .into_iter()
        .map(|(seed, dir)| Ok((seed, read_table(&dir.join(FITNESS_FILE))?)))
        .collect()
}

/// `rows` as the bytes of `summary.csv` (header first; floats as the csv crate writes them,
/// the shortest text that reads back to the same bits).
pub fn summary_bytes(rows: &[SummaryRow]) -> Result<Vec<u8>, std::io::Error> {
    let mut w = csv::WriterBuilder::new()
        .terminator(csv::Terminator::Any(b'\n'))
        .from_writer(Vec::new());
    if rows.is_empty() {
        w.write_record([
            "generation",
            "seeds",
            "best_q1",
            "best_median",
            "best_q3",
            "mean_q1",
            "mean_median",
            "mean_q3",
            "validation_best_q1",
            "validation_best_median",
            "validation_best_q3",
        ])?;
    }
    for row in rows {
        w.serialize(row).map_err(std::io::Error::other)?;
    }
    w.into_inner()
        .map_err(|e| std::io::Error::other(e.to_string()))
}

/// One line of `held-out.csv`: a genome's held-out evaluation.
#[derive(Debug, Clone, PartialEq)]
pub struct HeldOutRow {
    /// What it is: `seed`, `random_median`, `random_best`, `baseline`.
    pub who: String,
    /// The seed (for `seed` rows).
    pub seed: Option<u64>,
    /// The genome file, when there is one.
    pub genome: Option<String>,
    /// The held-out fitness (`None`: non-finite).
    pub fitness: Option<f64>,
    /// The behaviour measures, in the experiment's order.
    pub measures: Vec<f64>,
}

/// `rows` as the bytes of `held-out.csv`: columns `who,seed,genome,fitness` then one per
/// measure name in `measures`.
pub fn held_out_bytes(measures: &[String], rows: &[HeldOutRow]) -> Result<Vec<u8>, std::io::Error> {
    let mut w = csv::WriterBuilder::new()
        .terminator(csv::Terminator::Any(b'\n'))
        .from_writer(Vec::new());
    let mut header = vec![
        "who".to_string(),
        "seed".into(),
        "genome".into(),
        "fitness".into(),
    ];
    header.extend(measures.iter().cloned());
    w.write_record(&header)?;
    for r in rows {
        let mut record = vec![
            r.who.clone(),
            r.seed.map(|s| s.to_string()).unwrap_or_default(),
            r.genome.clone().unwrap_or_default(),
            r.fitness.map(|f| f.to_string()).unwrap_or_default(),
        ];
        record.extend(r.measures.iter().map(|m| m.to_string()));
        w.write_record(&record)?;
    }
    w.into_inner()
        .map_err(|e| std::io::Error::other(e.to_string()))
}

/// Writes `bytes` to `path` atomically.
pub fn write(path: &Path, bytes: &[u8]) -> Result<(), SummaryError> {
    write_atomic(path, bytes).map_err(|error| SummaryError::Write {
        path: path.to_path_buf(),
        error,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn type_7_quartiles_by_hand() {
        // n = 4: h = 0.75, 1.5, 2.25.
        assert_eq!(quartiles(&[4.0, 1.0, 3.0, 2.0]), Some([1.75, 2.5, 3.25]));
        // n = 5: h = 1, 2, 3.
        assert_eq!(
            quartiles(&[10.0, 0.0, 5.0, 7.0, 1.0]),
            Some([1.0, 5.0, 7.0])
        );
        assert_eq!(quartiles(&[3.0]), Some([3.0, 3.0, 3.0]));
        // n = 2: h = 0.25, 0.5, 0.75.
        assert_eq!(quartiles(&[0.0, 8.0]), Some([2.0, 4.0, 6.0]));
        assert_eq!(quartiles(&[]), None);
    }
}
