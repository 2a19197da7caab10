//! Fitness statistics of one generation, computed serially in index order so that their
//! bits never depend on the number of threads that evaluated it.

use serde::{Deserialize, Serialize};

/// Summary of a generation's fitness values.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FitnessStats {
    /// The largest value.
    pub best: f64,
    /// The arithmetic mean.
    pub mean: f64,
    /// The middle value; the mean of the two middle values for an even count.
    pub median: f64,
    /// The smallest value.
    pub worst: f64,
    /// The population standard deviation √(Σ(x − mean)² / n), computed in two passes (mean
    /// first) for accuracy.
    pub std: f64,
}

impl FitnessStats {
    /// The statistics of `values`, which should all be finite.
    ///
    /// An empty slice (e.g. a generation in which no individual got a finite fitness) gives
    /// all zeros rather than NaN, which CSV and JSON files cannot carry; callers that must
    /// tell it apart check the count themselves.
    pub fn of(values: &[f64]) -> FitnessStats {
        if values.is_empty() {
            return FitnessStats {
                best: 0.0,
                mean: 0.0,
                median: 0.0,
                worst: 0.0,
                std: 0.0,
            };
        }
        let n = values.len() as f64;
        let mut best = values[0];
        let mut worst = values[0];
        let mut sum = 0.0;
        for &v in values {
            best = best.max(v);
            worst = worst.min(v);
            sum += v;
        }
        let mean = sum / n;
        let mut squares = 0.0;
        for &v in values {
            let d = v - mean;
            squares += d * d;
        }
        let std = (squares / n).sqrt();
        let mut sorted = values.to_vec();
        sorted.sort_unstable_by(f64::total_cmp);
        let middle = sorted.len() / 2;
        let median = if sorted.len() % 2 == 1 {
            sorted[middle]
        } else {
            (sorted[middle - 1] + sorted[middle]) / 2.0
        };
        FitnessStats {
            best,
            mean,
            median,
            worst,
            std,
        }
    }
}
