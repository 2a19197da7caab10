//! The factory: the search `[evolution] algorithm` names, the one place that chooses an
//! algorithm (kept out of the trait's module so that the algorithms, which implement the
//! trait, and the factory, which builds them, import no circle).

use super::{cma_es, ga, map_elites, novelty, pgpe, sep_cma_es, Search, Unevaluated};
use crate::brain::genome::Genome;
use crate::brain::spec::Topology;
use crate::experiment::evolution::Algorithm;
use crate::experiment::Experiment;

/// The experiment's search, new: [`Search::ask`] gives generation 0. The one place that
/// matches on `[evolution] algorithm`.
pub fn of(experiment: &Experiment, topology: &Topology) -> Box<dyn Search> {
    let parameters = topology.parameter_count();
    match experiment.evolution.algorithm {
        Algorithm::Ga => Box::new(ga::Ga::new(experiment, parameters)),
        Algorithm::Pgpe => Box::new(pgpe::Pgpe::new(experiment, parameters)),
        Algorithm::SepCmaEs => Box::new(sep_cma_es::SepCmaEs::new(experiment, parameters)),
        Algorithm::CmaEs => Box::new(cma_es::CmaEs::new(experiment, parameters)),
        Algorithm::Novelty => Box::new(novelty::Novelty::new(experiment, parameters)),
        Algorithm::MapElites => Box::new(map_elites::MapElites::new(experiment, parameters)),
    }
}

/// Generation 0 of the experiment's search ([`of`]'s first ask).
pub fn first_generation(experiment: &Experiment, topology: &Topology) -> Unevaluated {
    of(experiment, topology).ask()
}

/// The first `n` genomes of generation 0 of the experiment's search (see
/// [`Search::first_genomes`]).
pub fn first_genomes(experiment: &Experiment, topology: &Topology, n: usize) -> Vec<Genome> {
    of(experiment, topology).first_genomes(n)
}
