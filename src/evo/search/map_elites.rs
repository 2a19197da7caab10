//! MAP-Elites (Mouret & Clune 2015) behind the [`Search`] trait (`[evolution] algorithm =
//! "map-elites"`, settings in `[evolution.map_elites]`): a grid archive ([`super::grid`])
//! keeps the best genome of every cell of behaviour space, and each generation varies elites
//! drawn from it.
//!
//! # One generation
//!
//! - **Ask g.** While the archive holds fewer than `initial_random` elites (generation 0
//!   always), the generation is `population` random genomes, uniform in ±`init_range`, drawn
//!   from `seed::stream(seed, Purpose::Initialisation, g, 0, 0)` (generation 0 is the GA's).
//!   Otherwise each of the `population` offspring is made by the emitter from elites drawn
//!   uniformly (`below`) from the archive in cell order, all from the variation stream of
//!   generation g − 1, offspring after offspring: the iso-line emitter draws elite i, elite j,
//!   one `gaussian` for the line, then one per gene ([`iso_line`]); the Gaussian emitter draws
//!   elite i, then one per gene ([`gaussian`]). The picks and the line are drawn in that
//!   order first, noting where each offspring's per-gene draws start in the stream; then all
//!   offspring's per-gene draws are made in one parallel pass ([`draws::gaussians_from`]),
//!   the same values as drawing them offspring after offspring. With `[evolution] draw_order
//!   = 2` every `gaussian` is [`crate::seed::gaussian_ziggurat`], and offspring k's per-gene
//!   draws come from its own stream ([`draws::own_stream`]), not the generation's.
//! - **Tell g.** Each individual with a finite fitness, in index order, enters the cell of its
//!   descriptors when it is empty or when its fitness is strictly greater
//!   ([`super::grid::enters`]).
//!
//! The population is the batch size: `[evolution] population` genomes are evaluated per
//! generation. The champion and best.json are chosen as for the GA (the best individual of a
//! generation, and on validation worlds). The archive is this search's state: a checkpoint
//! holds it (as it was before the checkpoint's generation was told, genomes included) as
//! `"search": {"map_elites": {"elites": [...]}}`, so a resumed run is the same bytes.

use super::descriptors::Descriptors;
use super::draws;
use super::grid::{
    cell_of, enters, flat_index, ArchiveView, Dimension, Elite, EliteView, GridArchive,
};
use super::{own_state, Search, SearchState, Unevaluated};
use crate::brain::genome::Genome;
use crate::evo::init::initial_population;
use crate::evo::lineage::{Birth, GenomeId, Lineage};
use crate::evo::state::EvaluatedGeneration;
use crate::experiment::evolution::{Emitter, EvolutionSpec, MapElitesSpec};
use crate::experiment::Experiment;
use crate::seed::{
    below, gaussian, stream, Generation, IndividualId, Normals, Purpose, Rng, Seed, TrialIndex,
};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// MAP-Elites' state: the archive's elites in cell order.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MapElitesState {
    /// The elites, in cell order.
    pub elites: Vec<Elite>,
}

/// The iso-line offspring of `xi` and `xj` given its normal draws: x' = x_i + σ_iso · n_k +
/// σ_line · line · (x_j − x_i), gene by gene (`isotropic[k]` the gene's draw, `line` the one
/// draw along the line).
pub fn iso_line_with(
    xi: &[f64],
    xj: &[f64],
    iso_sigma: f64,
    line_sigma: f64,
    line: f64,
    isotropic: &[f64],
) -> Vec<f64> {
    xi.iter()
        .zip(xj)
        .zip(isotropic)
        .map(|((&a, &b), &n)| a + iso_sigma * n + line_sigma * line * (b - a))
        .collect()
}

/// The iso-line offspring of `xi` and `xj` (Vassiliades & Mouret 2018), drawing one
/// `gaussian` for the line, then one per gene, from `rng` (draw order 1).
pub fn iso_line(
    xi: &[f64],
    xj: &[f64],
    iso_sigma: f64,
    line_sigma: f64,
    rng: &mut Rng,
) -> Vec<f64> {
    let line = gaussian(rng);
    let isotropic = draws::gaussians(rng, xi.len());
    iso_line_with(xi, xj, iso_sigma, line_sigma, line, &isotropic)
}

/// The Gaussian offspring of `x`: x + σ · N(0, I), one `gaussian` per gene from `rng` (draw
/// order 1).
pub fn gaussian_offspring(x: &[f64], sigma: f64, rng: &mut Rng) -> Vec<f64> {
    gaussian_offspring_with(x, sigma, &draws::gaussians(rng, x.len()))
}

/// x + σ · z, given the draws z.
fn gaussian_offspring_with(x: &[f64], sigma: f64, z: &[f64]) -> Vec<f64> {
    x.iter().zip(z).map(|(&a, &z)| a + sigma * z).collect()
}

/// One offspring's parents and where its draws are: the sequential part of `ask`, which
/// draws the picks and the line in stream order and only notes where each offspring's
/// per-gene draws start, so that all of them are drawn afterwards in one parallel pass.
struct Planned<'a> {
    first: &'a Elite,
    /// The iso-line emitter's second elite and its line draw.
    second: Option<(&'a Elite, f64)>,
    /// Where the per-gene draws come from: the stream word they start at (draw order 1), or
    /// the offspring's index, whose own stream they are (draw order 2).
    draws_at: u128,
}

/// MAP-Elites: its grid archive and what asks and tells need.
#[derive(Debug, Clone)]
pub struct MapElites {
    seed: Seed,
    spec: EvolutionSpec,
    settings: MapElitesSpec,
    parameters: usize,
    space: Descriptors,
    archive: GridArchive,
    /// The number of the generation `ask` gives.
    next: u64,
}

impl MapElites {
    /// A new search for `experiment` (whose algorithm is map-elites) with genomes of
    /// `parameters` parameters.
    pub fn new(experiment: &Experiment, parameters: usize) -> MapElites {
        let settings = experiment
            .evolution
            .map_elites_settings()
            .unwrap_or_default();
        let descriptors: Vec<_> = settings
            .descriptors
            .iter()
            .map(|d| d.descriptor())
            .collect();
        MapElites {
            seed: experiment.seed(),
            spec: experiment.evolution.clone(),
            parameters,
            space: Descriptors::new(&descriptors, &experiment.behaviour.measures),
            archive: GridArchive::new(settings.descriptors.iter().map(|d| d.bins).collect()),
            settings,
            next: 0,
        }
    }

    /// The archive, as told so far.
    pub fn grid(&self) -> &GridArchive {
        &self.archive
    }

    /// The measures (unscaled, finite: a non-finite one reads as its range's low end) and the
    /// cell of an evaluation.
    fn place(&self, evaluation: &crate::evo::evaluate::Evaluation) -> (Vec<f64>, Vec<usize>) {
        let mut raw = self.space.raw(evaluation);
        let scaled = self.space.scale(&raw);
        for ((x, d), s) in raw.iter_mut().zip(&self.settings.descriptors).zip(&scaled) {
            if !x.is_finite() {
                *x = d.min + s * (d.max - d.min);
            }
        }
        let cell = cell_of(&scaled, self.archive.bins());
        (raw, cell)
    }

    /// Why `elite` cannot be part of this search's archive, if it cannot.
    fn elite_problem(&self, elite: &Elite) -> Option<String> {
        let at = format!("the map-elites elite {}", elite.id);
        if !self.archive.fits(&elite.cell) {
            return Some(format!(
                "{at} sits in cell {:?}, outside the experiment's grid of bins {:?}",
                elite.cell,
                self.archive.bins()
            ));
        }
        if elite.measures.len() != self.space.len() {
            return Some(format!(
                "{at} has {} descriptors, but the experiment's grid has {}",
                elite.measures.len(),
                self.space.len()
            ));
        }
        if !elite.fitness.is_finite() || elite.measures.iter().any(|x| !x.is_finite()) {
            return Some(format!("{at} holds a non-finite fitness or descriptor"));
        }
        if elite.genome.parameters.len() != self.parameters {
            return Some(format!(
                "{at} has {} parameters, but the experiment's brain has {}",
                elite.genome.parameters.len(),
                self.parameters
            ));
        }
        if !elite.genome.is_finite() {
            return Some(format!("{at} holds a non-finite parameter"));
        }
        None
    }

    /// `population` random genomes for generation `generation`.
    fn random(&self, generation: u64, n: usize) -> Vec<Genome> {
        let mut spec = self.spec.clone();
        spec.population = n;
        // No self-adaptive mutation with map-elites (validation refuses the GA's mutation keys).
        spec.mutation.self_adaptive = None;
        initial_population(
            &spec,
            self.parameters,
            &mut stream(
                self.seed,
                Purpose::Initialisation,
                Generation(generation),
                IndividualId(0),
                TrialIndex(0),
            ),
        )
    }
}

impl Search for MapElites {
    fn name(&self) -> &'static str {
        "map-elites"
    }

    fn describe(&self) -> &'static str {
        "MAP-Elites"
    }

    fn evaluated_per_generation(&self) -> usize {
        self.spec.population
    }

    fn generation(&self) -> u64 {
        self.next
    }

    fn ask(&self) -> Unevaluated {
        let g = self.next;
        let n = self.spec.population;
        if g == 0 || self.archive.len() < self.settings.initial_random {
            return Unevaluated {
                genomes: self.random(g, n),
                lineage: vec![Lineage::orphan(Birth::Random); n],
            };
        }
        let elites: Vec<&Elite> = self.archive.elites().collect();
        let mut rng = stream(
            self.seed,
            Purpose::Variation,
            Generation(g - 1),
            IndividualId(0),
            TrialIndex(0),
        );
        let normals = self.spec.normals();
        let pick = |rng: &mut Rng| elites[below(rng, elites.len() as u64) as usize];
        let mut planned = Vec::with_capacity(n);
        let mut lineage = Vec::with_capacity(n);
        for k in 0..n {
            let first = pick(&mut rng);
            let second = match self.settings.emitter {
                Emitter::IsoLine => {
                    let b = pick(&mut rng);
                    lineage.push(Lineage::of_elites(Birth::IsoLine, &[first.id, b.id]));
                    Some((b, normals.draw(&mut rng)))
                }
                Emitter::Gaussian => {
                    lineage.push(Lineage::of_elites(Birth::Gaussian, &[first.id]));
                    None
                }
            };
            let draws_at = match normals {
                Normals::BoxMuller => {
                    draws::skip_gaussians(&mut rng, first.genome.parameters.len())
                }
                Normals::Ziggurat => k as u128,
            };
            planned.push(Planned {
                first,
                second,
                draws_at,
            });
        }
        let (iso, line_sigma) = self.settings.iso_line_sigmas();
        let sigma = self.settings.gaussian_sigma();
        let genomes = planned
            .par_iter()
            .map(|p| {
                let x = &p.first.genome.parameters;
                let z = match normals {
                    Normals::BoxMuller => draws::gaussians_from(&rng, p.draws_at, x.len()),
                    Normals::Ziggurat => draws::own_gaussians(&rng, p.draws_at as usize, x.len()),
                };
                let parameters = match p.second {
                    Some((b, line)) => {
                        iso_line_with(x, &b.genome.parameters, iso, line_sigma, line, &z)
                    }
                    None => gaussian_offspring_with(x, sigma, &z),
                };
                Genome {
                    parameters,
                    step_size: None,
                }
            })
            .collect();
        Unevaluated { genomes, lineage }
    }

    fn tell(&mut self, evaluated: &EvaluatedGeneration) {
        for (k, individual) in evaluated.individuals.iter().enumerate() {
            let Some(fitness) = individual.evaluation.fitness else {
                continue;
            };
            let (measures, cell) = self.place(&individual.evaluation);
            // Only a genome that enters is copied.
            if !enters(self.archive.fitness_at(&cell), fitness) {
                continue;
            }
            self.archive.insert(Elite {
                cell,
                id: GenomeId {
                    generation: evaluated.generation,
                    individual: k as u64,
                },
                fitness,
                measures,
                genome: individual.genome.clone(),
                lineage: individual.lineage.clone(),
            });
        }
        self.next = evaluated.generation + 1;
    }

    fn state(&self) -> Option<SearchState> {
        Some(SearchState::of(
            "map_elites",
            &MapElitesState {
                elites: self.archive.elites().cloned().collect(),
            },
        ))
    }

    fn restore(&mut self, state: Option<&SearchState>, generation: u64) {
        // Lenient (a changed experiment): the elites that fit are placed again by their
        // measures in the experiment's grid, in their order, by the insertion rule; another
        // algorithm's state starts an empty archive.
        self.archive = GridArchive::new(self.archive.bins().to_vec());
        if let Ok(s) = own_state::<MapElitesState>(state, "map_elites", "map-elites") {
            for mut elite in s.elites {
                if elite.measures.len() != self.space.len()
                    || elite.genome.parameters.len() != self.parameters
                    || !elite.genome.is_finite()
                {
                    continue;
                }
                elite.cell = cell_of(&self.space.scale(&elite.measures), self.archive.bins());
                self.archive.insert(elite);
            }
        }
        self.next = generation;
    }

    fn state_problem(&self, state: Option<&SearchState>) -> Option<String> {
        if state.is_none() {
            return Some(
                "it holds no map-elites archive, but its experiment uses map-elites".to_string(),
            );
        }
        let s = match own_state::<MapElitesState>(state, "map_elites", "map-elites") {
            Ok(s) => s,
            Err(why) => return Some(why),
        };
        let mut previous = None;
        for elite in &s.elites {
            if let Some(why) = self.elite_problem(elite) {
                return Some(why);
            }
            let at = flat_index(&elite.cell, self.archive.bins());
            if previous.is_some_and(|p| at <= p) {
                return Some(format!(
                    "its map-elites archive lists cell {:?} twice or out of cell order",
                    elite.cell
                ));
            }
            previous = Some(at);
        }
        None
    }

    fn first_genomes(&self, n: usize) -> Vec<Genome> {
        // Generation 0 is drawn individual after individual from one stream, so a smaller
        // batch is the first genomes of the full one.
        self.random(0, n.min(self.spec.population))
    }

    fn archive<'a>(&'a self, evaluated: &'a EvaluatedGeneration) -> Option<ArchiveView<'a>> {
        let mut cells: BTreeMap<usize, EliteView<'a>> = self
            .archive
            .elites()
            .map(|e| {
                (
                    flat_index(&e.cell, self.archive.bins()),
                    EliteView {
                        cell: e.cell.clone(),
                        id: e.id,
                        fitness: e.fitness,
                        measures: e.measures.clone(),
                        genome: &e.genome,
                    },
                )
            })
            .collect();
        // As `tell` would place the generation, without copying genomes.
        for (k, individual) in evaluated.individuals.iter().enumerate() {
            let Some(fitness) = individual.evaluation.fitness else {
                continue;
            };
            let (measures, cell) = self.place(&individual.evaluation);
            let at = flat_index(&cell, self.archive.bins());
            if enters(cells.get(&at).map(|e| e.fitness), fitness) {
                cells.insert(
                    at,
                    EliteView {
                        cell,
                        id: GenomeId {
                            generation: evaluated.generation,
                            individual: k as u64,
                        },
                        fitness,
                        measures,
                        genome: &individual.genome,
                    },
                );
            }
        }
        Some(ArchiveView {
            dimensions: self
                .settings
                .descriptors
                .iter()
                .map(Dimension::from)
                .collect(),
            qd_offset: self.settings.qd_offset,
            elites: cells.into_values().collect(),
        })
    }
}
