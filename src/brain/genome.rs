//! The genome: a flat vector of real parameters that a brain topology decodes into a network,
//! plus the optional self-adaptive mutation step size the genetic algorithm carries with it.

use super::{Brain, BrainError, Topology};
use serde::{Deserialize, Serialize};

/// One individual's heritable material.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Genome {
    /// The network parameters, in the order the brain's topology documents.
    pub parameters: Vec<f64>,
    /// The individual's own mutation standard deviation when mutation is self-adaptive;
    /// `None` when the experiment uses a fixed step size.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub step_size: Option<f64>,
}

impl Genome {
    /// A genome with the given parameters and no self-adaptive step size.
    pub fn new(parameters: Vec<f64>) -> Self {
        Genome {
            parameters,
            step_size: None,
        }
    }

    /// The genome of `brain`: its parameters, bit for bit, and no step size.
    pub fn from_brain(brain: &Brain) -> Self {
        Genome::new(brain.parameters())
    }

    /// Decodes the parameters into a brain of `topology` (see [`Brain::new`]).
    pub fn decode(&self, topology: &Topology) -> Result<Brain, BrainError> {
        Brain::new(topology, &self.parameters)
    }

    /// True when every parameter (and the step size, if any) is finite.
    pub fn is_finite(&self) -> bool {
        self.parameters.iter().all(|p| p.is_finite())
            && self.step_size.is_none_or(|s| s.is_finite())
    }
}
