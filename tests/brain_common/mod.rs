//! Helpers shared by the brain tests and the brain's allocation tests: a seeded stream, brains
//! from `[brain]` TOML text, and the topologies every kind is checked on.
#![allow(dead_code)]

use berry_evolve::brain::{BrainSpec, Topology};
use berry_evolve::seed::{stream, Generation, IndividualId, Purpose, Rng, Seed, TrialIndex};

pub fn rng(individual: u64) -> Rng {
    stream(
        Seed(20_240_601),
        Purpose::Baseline,
        Generation(0),
        IndividualId(individual),
        TrialIndex(0),
    )
}

pub fn spec(toml_text: &str) -> BrainSpec {
    toml::from_str(toml_text).unwrap_or_else(|e| panic!("{toml_text:?} should parse: {e}"))
}

pub fn topology(toml_text: &str, inputs: usize, outputs: usize) -> Topology {
    Topology::new(spec(toml_text), inputs, outputs)
        .unwrap_or_else(|e| panic!("{toml_text:?} should be valid: {e}"))
}

pub fn round_trip_topologies() -> Vec<Topology> {
    vec![
        topology("", 24, 3),
        topology("hidden = []", 5, 2),
        topology("hidden = [6, 4]\nactivation = \"relu\"", 7, 3),
        topology("hidden = [3]\nactivation = \"sigmoid\"", 4, 2),
        topology("kind = \"recurrent\"\nhidden = [5]", 6, 3),
        topology("kind = \"ctrnn\"\nneurons = 4", 3, 2),
        topology(
            "kind = \"ctrnn\"\nneurons = 3\nsubsteps = 3\ntau = [0.2, 50]",
            2,
            3,
        ),
    ]
}

/// Brains with seeded parameters, for the batched passes.
pub mod batch {
    use berry_evolve::brain::{Brain, BrainSpec, Topology};
    use berry_evolve::seed::{
        stream, uniform, Generation, IndividualId, Purpose, Seed, TrialIndex,
    };

    pub fn values(seed: u64, count: usize, bound: f64) -> Vec<f64> {
        let mut rng = stream(
            Seed(seed),
            Purpose::Baseline,
            Generation(0),
            IndividualId(0),
            TrialIndex(0),
        );
        (0..count)
            .map(|_| uniform(&mut rng, -bound, bound))
            .collect()
    }

    pub fn brain(toml_text: &str, inputs: usize, outputs: usize, seed: u64) -> Brain {
        let spec: BrainSpec = toml::from_str(toml_text).expect("spec");
        let topology = Topology::new(spec, inputs, outputs).expect("topology");
        let parameters = values(seed, topology.parameter_count(), 2.0);
        Brain::new(&topology, &parameters).expect("brain")
    }
}
