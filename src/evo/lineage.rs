//! Lineage: how each individual of a generation was born and from which individuals of the
//! previous generation, kept in checkpoints so that ancestry can be analysed afterwards
//! (`export-csv --population` prints it). Recording it draws nothing and changes no genome.

use serde::{Deserialize, Serialize};

/// How an individual was made.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Birth {
    /// Generation 0 of the GA: drawn from the initialisation stream, no parents.
    Random,
    /// An elite: its one parent copied unchanged (step size included).
    Elite,
    /// Its one parent copied and mutated (crossover `none`, or the crossover chance said no).
    Mutated,
    /// Its two parents recombined (first parent x, second y, as the draw order of
    /// [`crate::evo::vary`] names them), then mutated.
    Crossover,
    /// PGPE: a sample, its generation's centre plus (or minus, for the second of a mirrored
    /// pair 2k, 2k + 1) noise. Its parent is the centre of its own generation (the last
    /// individual), not an individual of the previous one, so it lists no parent index.
    PgpeSample,
    /// PGPE: the centre itself. Its parent is the previous generation's centre, which PGPE's
    /// update moved using the fitness of every sample of that generation; or, when a run
    /// switched from the GA, the previous generation's best individual it was centred on. The
    /// first generation's centre has no parent.
    PgpeCentre,
    /// sep-CMA-ES: a sample, its generation's mean plus noise shaped by the step size and
    /// the diagonal covariance. Like a PGPE sample it lists no parent index.
    CmaSample,
    /// sep-CMA-ES: the mean itself, with the previous generation's mean (or, when the search
    /// was restarted there, its best individual) as parent; the first generation's has none.
    CmaMean,
    /// MAP-Elites: an elite of the archive plus Gaussian noise. Its parent is an elite of any
    /// earlier generation, so it is named in [`Lineage::elites`], not by an index.
    Gaussian,
    /// MAP-Elites: iso-line variation of two elites of the archive (the first moved along the
    /// line to the second), named in [`Lineage::elites`].
    IsoLine,
}

impl Birth {
    /// The name used in checkpoints and CSV (`random`, `elite`, `mutated`, `crossover`,
    /// `pgpe_sample`, `pgpe_centre`, `cma_sample`, `cma_mean`, `gaussian`, `iso_line`).
    pub fn name(self) -> &'static str {
        match self {
            Birth::Random => "random",
            Birth::Elite => "elite",
            Birth::Mutated => "mutated",
            Birth::Crossover => "crossover",
            Birth::PgpeSample => "pgpe_sample",
            Birth::PgpeCentre => "pgpe_centre",
            Birth::CmaSample => "cma_sample",
            Birth::CmaMean => "cma_mean",
            Birth::Gaussian => "gaussian",
            Birth::IsoLine => "iso_line",
        }
    }
}

/// Where one individual came from.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Lineage {
    /// How it was made.
    pub birth: Birth,
    /// Its parents: indices into the previous generation, in the order [`Birth`] describes
    /// (none, one, or two; both the same index when a selection picked one individual twice).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub parents: Vec<u64>,
    /// Its parents when they are archive elites of any earlier generation (MAP-Elites), by
    /// genome id, in the order [`Birth`] describes; absent otherwise, so the other
    /// algorithms' checkpoints keep their bytes.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub elites: Vec<GenomeId>,
}

/// A genome's id: the generation it was evaluated in and its index in that generation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
pub struct GenomeId {
    /// The generation.
    pub generation: u64,
    /// The index in the generation.
    pub individual: u64,
}

impl std::fmt::Display for GenomeId {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "individual {} of generation {}",
            self.individual, self.generation
        )
    }
}

impl Lineage {
    /// A lineage without parents.
    pub fn orphan(birth: Birth) -> Lineage {
        Lineage {
            birth,
            parents: Vec::new(),
            elites: Vec::new(),
        }
    }

    /// A lineage with the parents at indices `parents` of the previous generation.
    pub fn of(birth: Birth, parents: &[usize]) -> Lineage {
        Lineage {
            birth,
            parents: parents.iter().map(|&p| p as u64).collect(),
            elites: Vec::new(),
        }
    }

    /// A lineage whose parents are the archive elites `elites` (MAP-Elites).
    pub fn of_elites(birth: Birth, elites: &[GenomeId]) -> Lineage {
        Lineage {
            birth,
            parents: Vec::new(),
            elites: elites.to_vec(),
        }
    }
}
