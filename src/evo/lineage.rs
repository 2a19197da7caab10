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
}

impl Birth {
    /// The name used in checkpoints and CSV (`random`, `elite`, `mutated`, `crossover`,
    /// `pgpe_sample`, `pgpe_centre`, `cma_sample`, `cma_mean`).
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
}

impl Lineage {
    /// A lineage without parents.
    pub fn orphan(birth: Birth) -> Lineage {
        Lineage {
            birth,
            parents: Vec::new(),
        }
    }

    /// A lineage with the parents at indices `parents` of the previous generation.
    pub fn of(birth: Birth, parents: &[usize]) -> Lineage {
        Lineage {
            birth,
            parents: parents.iter().map(|&p| p as u64).collect(),
        }
    }
}
