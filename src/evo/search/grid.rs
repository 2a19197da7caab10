//! The grid archive of MAP-Elites: behaviour space cut into equal cells, each holding its
//! elite, the genome of the highest fitness seen there. Also the read-only view of an archive
//! that everything outside the search uses ([`ArchiveView`]: archive.csv, fitness.csv's
//! quality-diversity columns, `plot`, `extract --cell`), so that they name no algorithm.
//!
//! # Insertion
//!
//! A genome with a finite fitness enters its cell when the cell is empty or its fitness is
//! strictly greater than the elite's ([`enters`]): on a tie the older elite stays, so the
//! archive never depends on anything but the order genomes are told in (index order within a
//! generation, generations in order).

use crate::brain::genome::Genome;
use crate::evo::lineage::{GenomeId, Lineage};
use crate::experiment::evolution::GridDescriptorSpec;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// One cell's elite as the archive (and a checkpoint) holds it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Elite {
    /// Its cell: one bin index per descriptor, from 0.
    pub cell: Vec<usize>,
    /// Its genome id (where it was evaluated).
    pub id: GenomeId,
    /// Its fitness (finite).
    pub fitness: f64,
    /// Its descriptors' measures, unscaled, in descriptor order.
    pub measures: Vec<f64>,
    /// Its genome.
    pub genome: Genome,
    /// How it was born, when its generation recorded it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lineage: Option<Lineage>,
}

/// Does a genome of fitness `fitness` enter a cell whose elite has fitness `elite` (`None`:
/// empty)? When empty or strictly better: ties keep the older elite.
pub fn enters(elite: Option<f64>, fitness: f64) -> bool {
    elite.is_none_or(|e| fitness > e)
}

/// The cell of a behaviour scaled to [0, 1] per dimension ([`super::descriptors`]): bin
/// ⌊s · bins⌋, the top edge s = 1 in the last bin.
pub fn cell_of(scaled: &[f64], bins: &[usize]) -> Vec<usize> {
    scaled
        .iter()
        .zip(bins)
        .map(|(&s, &b)| ((s * b as f64) as usize).min(b.saturating_sub(1)))
        .collect()
}

/// The flat index of `cell` in a grid of `bins` (the last dimension fastest).
pub fn flat_index(cell: &[usize], bins: &[usize]) -> usize {
    cell.iter().zip(bins).fold(0, |i, (&c, &b)| i * b + c)
}

/// A grid archive: its bins per dimension and its elites by flat cell index.
#[derive(Debug, Clone, PartialEq)]
pub struct GridArchive {
    bins: Vec<usize>,
    elites: BTreeMap<usize, Elite>,
}

impl GridArchive {
    /// An empty archive of `bins` cells per dimension.
    pub fn new(bins: Vec<usize>) -> GridArchive {
        GridArchive {
            bins,
            elites: BTreeMap::new(),
        }
    }

    /// Bins per dimension.
    pub fn bins(&self) -> &[usize] {
        &self.bins
    }

    /// How many cells hold an elite.
    pub fn len(&self) -> usize {
        self.elites.len()
    }

    /// True when no cell holds an elite.
    pub fn is_empty(&self) -> bool {
        self.elites.is_empty()
    }

    /// The elites in cell order (flat index, the last dimension fastest).
    pub fn elites(&self) -> impl Iterator<Item = &Elite> {
        self.elites.values()
    }

    /// The elite of `cell`, if any (`None` also for a cell outside the grid).
    pub fn get(&self, cell: &[usize]) -> Option<&Elite> {
        self.fits(cell)
            .then(|| self.elites.get(&flat_index(cell, &self.bins)))
            .flatten()
    }

    /// True when `cell` is a cell of this grid.
    pub fn fits(&self, cell: &[usize]) -> bool {
        cell.len() == self.bins.len() && cell.iter().zip(&self.bins).all(|(c, b)| c < b)
    }

    /// The fitness of `cell`'s elite, if any.
    pub fn fitness_at(&self, cell: &[usize]) -> Option<f64> {
        self.get(cell).map(|e| e.fitness)
    }

    /// Puts `elite` in its cell if it [`enters`] it; true if it did. An elite whose cell is
    /// outside the grid or whose fitness is not finite never enters.
    pub fn insert(&mut self, elite: Elite) -> bool {
        if !self.fits(&elite.cell) || !elite.fitness.is_finite() {
            return false;
        }
        let at = flat_index(&elite.cell, &self.bins);
        if !enters(self.elites.get(&at).map(|e| e.fitness), elite.fitness) {
            return false;
        }
        self.elites.insert(at, elite);
        true
    }
}

/// One dimension of an archive, as outputs describe it.
#[derive(Debug, Clone, PartialEq)]
pub struct Dimension {
    /// The measure's name (e.g. `distinct_food`; `time_in_area:nest` for an area's own).
    pub measure: String,
    /// The low end of the first bin.
    pub min: f64,
    /// The high end of the last bin.
    pub max: f64,
    /// How many bins.
    pub bins: usize,
}

impl From<&GridDescriptorSpec> for Dimension {
    fn from(d: &GridDescriptorSpec) -> Dimension {
        Dimension {
            measure: d.label(),
            min: d.min,
            max: d.max,
            bins: d.bins,
        }
    }
}

/// An elite as outputs see it: everything but a copy of its genome, which it borrows.
#[derive(Debug, Clone, PartialEq)]
pub struct EliteView<'a> {
    /// Its cell, one bin index per dimension.
    pub cell: Vec<usize>,
    /// Its genome id.
    pub id: GenomeId,
    /// Its fitness.
    pub fitness: f64,
    /// Its descriptors' measures, unscaled, in dimension order.
    pub measures: Vec<f64>,
    /// Its genome.
    pub genome: &'a Genome,
}

/// An archive as outputs see it: its grid, its elites in cell order and the QD score's offset.
#[derive(Debug, Clone, PartialEq)]
pub struct ArchiveView<'a> {
    /// The grid's dimensions, in descriptor order.
    pub dimensions: Vec<Dimension>,
    /// The offset subtracted from every elite's fitness in the QD score.
    pub qd_offset: f64,
    /// The elites in cell order (flat index, the last dimension fastest).
    pub elites: Vec<EliteView<'a>>,
}

/// The quality-diversity metrics of an archive, as pyribs and QDax report them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QdMetrics {
    /// Sum over elites of (fitness − qd_offset).
    pub qd_score: f64,
    /// Filled cells / all cells.
    pub coverage: f64,
    /// Filled cells.
    pub archive_size: usize,
    /// The highest elite fitness (`None` for an empty archive).
    pub max_fitness: Option<f64>,
}

/// fitness.csv's columns for an archive's [`QdMetrics`], in order.
pub const QD_COLUMNS: [&str; 4] = ["qd_score", "coverage", "archive_size", "max_fitness"];

impl QdMetrics {
    /// The values of [`QD_COLUMNS`], in order (an empty archive has no `max_fitness`).
    pub fn columns(&self) -> Vec<Option<f64>> {
        vec![
            Some(self.qd_score),
            Some(self.coverage),
            Some(self.archive_size as f64),
            self.max_fitness,
        ]
    }
}

impl ArchiveView<'_> {
    /// The grid's cells.
    pub fn cells(&self) -> usize {
        self.dimensions.iter().map(|d| d.bins).product()
    }

    /// Its QD score, coverage, size and best fitness (sums in cell order, so the bits are the
    /// same on every run).
    pub fn metrics(&self) -> QdMetrics {
        QdMetrics {
            qd_score: self.elites.iter().map(|e| e.fitness - self.qd_offset).sum(),
            coverage: self.elites.len() as f64 / self.cells() as f64,
            archive_size: self.elites.len(),
            max_fitness: self.elites.iter().map(|e| e.fitness).reduce(f64::max),
        }
    }

    /// The elite of `cell`, if any.
    pub fn get(&self, cell: &[usize]) -> Option<&EliteView<'_>> {
        self.elites.iter().find(|e| e.cell == cell)
    }
}
