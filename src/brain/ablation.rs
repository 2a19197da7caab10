//! Ablations of a plastic brain: the controls that tell whether a champion's learning matters
//! (`compare --ablate`). Each turns a plastic genome and its topology into another genome and
//! topology that the ordinary brain code runs, so an ablated brain is a brain one could have
//! evolved, and nothing in the tick knows about ablations.
//!
//! - [`Ablation::Frozen`]: plasticity off, the weights never change. With evolved initial
//!   weights this is the fixed MLP of the genome's weights and biases (`plasticity = "none"`,
//!   the rule's and modulation's genes dropped), so it is bit for bit that fixed MLP by
//!   construction. With random initial weights there is no fixed genome to fall back on (each
//!   life draws its own weights), so the rule stays but with η = 0 and no modulation
//!   (`"hebbian"`): Δw = (0·1)·s = 0 for every finite s, and the drawn weights, already within
//!   the bounds, stay as drawn.
//! - [`Ablation::Ungated`] ("modulators cut"): the neuromodulated rule runs with g = 1 on
//!   every tick, i.e. the `"hebbian"` rule with the same coefficients (η, A, B, C, D) and the
//!   modulation genes dropped. Cutting m to 0 would give g = tanh(0) = 0, the frozen brain
//!   again, which tells nothing new; with g = 1 the same rule runs but the events (food,
//!   modulatory neurons) no longer decide when and in which direction it learns. A hebbian
//!   genome is ungated already, so this ablation does not apply to it.
//!
//! Holding g at a constant c (say its mean over a life) is the hebbian rule with every η
//! multiplied by c: (η·c)·s is computed the same way either way. It needs the intact brain's
//! g measured first, so it is not offered here (docs/learning.md, "Controls and the episode
//! curve").

use super::genome::Genome;
use super::plasticity::{InitialWeights, Plasticity};
use super::spec::{BrainSpec, Topology};
use thiserror::Error;

/// A control applied to a plastic genome before it is evaluated.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Ablation {
    /// Plasticity off: the weights stay those a life starts with.
    Frozen,
    /// The modulatory signal cut: the rule runs ungated (g = 1), as `"hebbian"`.
    Ungated,
}

/// Every ablation, in the order `compare` reports them.
pub const ABLATIONS: [Ablation; 2] = [Ablation::Frozen, Ablation::Ungated];

impl Ablation {
    /// The name used on the command line and in reports.
    pub fn name(self) -> &'static str {
        match self {
            Ablation::Frozen => "frozen",
            Ablation::Ungated => "ungated",
        }
    }
}

/// Why an ablation cannot be applied to a genome.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum AblationError {
    /// The brain has no plasticity to take away.
    #[error("the brain is not plastic (`brain.plasticity` is \"none\"), so there is no learning to ablate")]
    NotPlastic,
    /// `ungated` of a rule that has no gate.
    #[error("the rule is \"hebbian\", which is ungated already; `ungated` applies to a neuromodulated rule")]
    NoGate,
    /// The genome does not fit its topology.
    #[error("the genome has {got} parameters but its brain needs {expected}")]
    ParameterCount {
        /// What the topology needs.
        expected: usize,
        /// What the genome has.
        got: usize,
    },
}

/// `ablation` applied to a plastic `genome` of `topology`: the topology and genome to evaluate
/// instead (see the module docs). The result's parameters are a prefix of the genome's (with
/// the η genes zeroed for a frozen brain with random initial weights); the step size is kept.
pub fn ablate(
    topology: &Topology,
    genome: &Genome,
    ablation: Ablation,
) -> Result<(Topology, Genome), AblationError> {
    let settings = topology
        .spec
        .plastic_settings()
        .ok_or(AblationError::NotPlastic)?;
    let expected = topology.parameter_count();
    if genome.parameters.len() != expected {
        return Err(AblationError::ParameterCount {
            expected,
            got: genome.parameters.len(),
        });
    }
    // The spec without any plasticity key (a fixed MLP refuses them), then with the rule
    // `rule` and no modulation.
    let fixed = BrainSpec {
        plasticity: None,
        granularity: None,
        weight_bounds: None,
        initial_weights: None,
        modulators: None,
        modulatory_neurons: None,
        ..topology.spec.clone()
    };
    let hebbian = BrainSpec {
        plasticity: Some(Plasticity::Hebbian),
        modulators: None,
        modulatory_neurons: None,
        ..topology.spec.clone()
    };
    let (spec, zero_eta) = match ablation {
        Ablation::Frozen if settings.initial == InitialWeights::Evolved => (fixed, false),
        Ablation::Frozen => (hebbian, true),
        Ablation::Ungated if settings.rule == Plasticity::Hebbian => {
            return Err(AblationError::NoGate)
        }
        Ablation::Ungated => (hebbian, false),
    };
    let ablated = Topology {
        spec,
        ..topology.clone()
    };
    // Both specs keep the genome's layout up to where they stop: the fixed network's weights
    // and biases, then (hebbian) the rule's coefficients; the modulation genes come last.
    let kept = ablated.parameter_count();
    let mut parameters = genome.parameters[..kept].to_vec();
    if zero_eta {
        for (p, name) in parameters.iter_mut().zip(ablated.parameter_names()) {
            if name.starts_with("rule_eta") {
                *p = 0.0;
            }
        }
    }
    Ok((
        ablated,
        Genome {
            parameters,
            step_size: genome.step_size,
        },
    ))
}
