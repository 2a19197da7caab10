//! Behaviour descriptors: an individual's `[behaviour]` measures, as named by a search's
//! `descriptors`, each scaled from its [min, max] to [0, 1], so that distances in behaviour
//! space weigh every dimension alike (novelty search; MAP-Elites' grid archive bins the
//! same vector). A descriptor that names an `area` reads that area's own ticks
//! ([`Evaluation::area_ticks`]) instead.

use crate::evo::evaluate::Evaluation;
use crate::experiment::evolution::DescriptorSpec;
use crate::experiment::tables::Measure;

/// Where a dimension's value sits in an evaluation.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Source {
    /// An index into `Evaluation::measures`.
    Measure(usize),
    /// An index into `Evaluation::area_ticks`.
    Area(usize),
}

/// A behaviour space: where each descriptor's value sits in an evaluation and the range that
/// maps to [0, 1].
#[derive(Debug, Clone, PartialEq)]
pub struct Descriptors {
    /// Per dimension: (where its value is, min, max).
    dimensions: Vec<(Source, f64, f64)>,
}

impl Descriptors {
    /// The space of `descriptors` over an experiment computing `measures` (its
    /// `[behaviour] measures`, in order). A descriptor whose measure is not computed reads 0
    /// (validation refuses such a file, so only a checkpoint of another experiment meets it).
    /// The descriptors that name an area read the evaluation's area ticks in their order (the
    /// order [`crate::experiment::EvolutionSpec::described_areas`] counts them in).
    pub fn new(descriptors: &[DescriptorSpec], measures: &[Measure]) -> Descriptors {
        let mut areas = 0;
        Descriptors {
            dimensions: descriptors
                .iter()
                .map(|d| {
                    let at = if d.area.is_some() {
                        areas += 1;
                        Source::Area(areas - 1)
                    } else {
                        Source::Measure(
                            measures
                                .iter()
                                .position(|m| *m == d.measure)
                                .unwrap_or(usize::MAX),
                        )
                    };
                    (at, d.min, d.max)
                })
                .collect(),
        }
    }

    /// How many dimensions.
    pub fn len(&self) -> usize {
        self.dimensions.len()
    }

    /// True without dimensions.
    pub fn is_empty(&self) -> bool {
        self.dimensions.is_empty()
    }

    /// The behaviour of `evaluation`: each measure scaled to [0, 1] by its range and clamped
    /// there (a missing or non-finite value reads as the range's low end, 0).
    pub fn of(&self, evaluation: &Evaluation) -> Vec<f64> {
        self.scale(&self.raw(evaluation))
    }

    /// The measures of `evaluation` the descriptors name, unscaled, in descriptor order (a
    /// missing one reads as its range's low end).
    pub fn raw(&self, evaluation: &Evaluation) -> Vec<f64> {
        self.dimensions
            .iter()
            .map(|&(at, min, _)| {
                match at {
                    Source::Measure(k) => evaluation.measures.get(k),
                    Source::Area(k) => evaluation.area_ticks.get(k),
                }
                .copied()
                .unwrap_or(min)
            })
            .collect()
    }

    /// `raw` (one value per dimension) scaled to [0, 1] by each range and clamped there (a
    /// non-finite value reads as 0).
    pub fn scale(&self, raw: &[f64]) -> Vec<f64> {
        self.dimensions
            .iter()
            .zip(raw)
            .map(|(&(_, min, max), &x)| {
                let scaled = (x - min) / (max - min);
                if scaled.is_finite() {
                    scaled.clamp(0.0, 1.0)
                } else {
                    0.0
                }
            })
            .collect()
    }
}

/// Euclidean distance between two behaviours of the same length, summed in dimension order.
pub fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}
