//! Novelty search (Lehman & Stanley 2011) behind the [`Search`] trait (`[evolution]
//! algorithm = "novelty"`, settings in `[evolution.novelty]`): the GA of [`super::ga`], its
//! selection, crossover, mutation and elitism unchanged, ranking individuals by a score
//! instead of their fitness.
//!
//! # One generation, told
//!
//! 1. Each individual's behaviour is its descriptors, scaled to [0, 1]
//!    ([`super::descriptors`]).
//! 2. Its novelty is the mean Euclidean distance to its `k` nearest neighbours among the other
//!    individuals of its generation and the archive as it was before this generation
//!    ([`novelty`]; fewer neighbours while the pool is smaller than `k`).
//! 3. Its score is (1 − w) · rank(novelty) + w · rank(fitness), w = `fitness_weight`, each
//!    rank scaled to [0, 1] (0 the lowest, 1 the highest; equal values share their mean
//!    rank), so that novelty and fitness weigh alike whatever their units ([`scores`]). An
//!    individual whose brain gave a non-finite output scores below every other, as in the GA.
//! 4. The archive gains, in index order, each individual (with a finite fitness) whose
//!    novelty is above `archive_threshold`, or, by default, each with chance
//!    `archive_probability`, one draw per individual from `seed::stream(seed,
//!    Purpose::Novelty, g, 0, 0)` ([`archive_additions`]). Beyond `archive_size` the oldest
//!    entries leave.
//! 5. The GA makes generation g + 1 from generation g with these scores, drawing from its
//!    own variation stream.
//!
//! Fitness is still what fitness.csv records and what chooses the champion and best.json.
//! The archive is this search's state: a checkpoint holds it (the archive before the
//! checkpoint's generation was told) as `"search": {"novelty": {"archive": [...]}}`, so a
//! resumed run is the same bytes.

use super::descriptors::{distance, Descriptors};
use super::ga::Ga;
use super::{own_state, Search, SearchState, Unevaluated};
use crate::brain::genome::Genome;
use crate::evo::state::EvaluatedGeneration;
use crate::experiment::evolution::{NoveltySpec, DEFAULT_ARCHIVE_PROBABILITY};
use crate::experiment::Experiment;
use crate::seed::{stream, unit, Generation, IndividualId, Purpose, Rng, Seed, TrialIndex};
use serde::{Deserialize, Serialize};

/// One behaviour in the novelty archive, with the individual it came from.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ArchiveEntry {
    /// The generation it was evaluated in.
    pub generation: u64,
    /// Its index in that generation.
    pub individual: u64,
    /// Its scaled descriptors, in `descriptors` order.
    pub behaviour: Vec<f64>,
}

/// Novelty search's state: its archive, oldest entry first.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NoveltyState {
    /// The archive of past behaviours, oldest first.
    pub archive: Vec<ArchiveEntry>,
}

/// How an individual enters the archive.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Addition {
    /// When its novelty is above the threshold.
    Threshold(f64),
    /// With this chance, one draw per individual in index order.
    Probability(f64),
}

impl Addition {
    /// The rule `settings` chooses (by default, chance 0.1).
    pub fn of(settings: &NoveltySpec) -> Addition {
        match settings.archive_threshold {
            Some(t) => Addition::Threshold(t),
            None => Addition::Probability(
                settings
                    .archive_probability
                    .unwrap_or(DEFAULT_ARCHIVE_PROBABILITY),
            ),
        }
    }
}

/// The novelty of each behaviour of `population`: the mean distance to its `k` nearest
/// neighbours among the other behaviours of `population` and those of `archive` (all of
/// them when there are fewer than `k`; 0 when there are none). Distances are sorted with
/// `total_cmp`, so equal distances need no tie rule: the mean is the same.
pub fn novelty(population: &[Vec<f64>], archive: &[Vec<f64>], k: usize) -> Vec<f64> {
    let mut distances = Vec::with_capacity(population.len() + archive.len());
    population
        .iter()
        .enumerate()
        .map(|(i, b)| {
            distances.clear();
            distances.extend(
                population
                    .iter()
                    .enumerate()
                    .filter(|&(j, _)| j != i)
                    .map(|(_, other)| distance(b, other)),
            );
            distances.extend(archive.iter().map(|other| distance(b, other)));
            distances.sort_by(f64::total_cmp);
            let nearest = &distances[..k.min(distances.len())];
            if nearest.is_empty() {
                0.0
            } else {
                nearest.iter().sum::<f64>() / nearest.len() as f64
            }
        })
        .collect()
}

/// Each value's rank scaled to [0, 1]: 0 for the lowest, 1 for the highest, equal values
/// sharing the mean of their ranks (a single value: 0.5).
pub fn scaled_ranks(values: &[f64]) -> Vec<f64> {
    let n = values.len();
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| values[a].total_cmp(&values[b]).then(a.cmp(&b)));
    let mut ranks = vec![0.5; n];
    if n < 2 {
        return ranks;
    }
    let mut start = 0;
    while start < n {
        let mut end = start + 1;
        while end < n && values[order[end]] == values[order[start]] {
            end += 1;
        }
        let mean = (start + end - 1) as f64 / 2.0;
        for &i in &order[start..end] {
            ranks[i] = mean / (n - 1) as f64;
        }
        start = end;
    }
    ranks
}

/// The selection scores: (1 − w) · rank(novelty) + w · rank(fitness), ranks scaled to
/// [0, 1] ([`scaled_ranks`]); an individual without a finite fitness scores `f64::MIN`.
pub fn scores(novelty: &[f64], fitness: &[Option<f64>], fitness_weight: f64) -> Vec<f64> {
    let novelty_rank = scaled_ranks(novelty);
    let fitness_rank = scaled_ranks(
        &fitness
            .iter()
            .map(|f| f.unwrap_or(f64::MIN))
            .collect::<Vec<_>>(),
    );
    novelty_rank
        .iter()
        .zip(&fitness_rank)
        .zip(fitness)
        .map(|((n, f), fit)| match fit {
            Some(_) => (1.0 - fitness_weight) * n + fitness_weight * f,
            None => f64::MIN,
        })
        .collect()
}

/// The individuals that enter the archive, in index order: those with a finite fitness whose
/// novelty is above the threshold, or drawn with the rule's chance (one `unit` draw from
/// `rng` per individual, whether it could enter or not, so the draws do not depend on the
/// values).
pub fn archive_additions(
    novelty: &[f64],
    fitness: &[Option<f64>],
    rule: Addition,
    rng: &mut Rng,
) -> Vec<usize> {
    (0..novelty.len())
        .filter(|&i| {
            let chosen = match rule {
                Addition::Threshold(t) => novelty[i] > t,
                Addition::Probability(p) => unit(rng) < p,
            };
            chosen && fitness[i].is_some()
        })
        .collect()
}

/// Adds `entries` in order to `archive`, then removes the oldest entries beyond `capacity`.
pub fn add_to_archive(
    archive: &mut Vec<ArchiveEntry>,
    entries: Vec<ArchiveEntry>,
    capacity: usize,
) {
    archive.extend(entries);
    let excess = archive.len().saturating_sub(capacity);
    archive.drain(..excess);
}

/// Novelty search: the GA ranking by novelty scores, and its archive.
#[derive(Debug, Clone)]
pub struct Novelty {
    ga: Ga,
    seed: Seed,
    settings: NoveltySpec,
    space: Descriptors,
    archive: Vec<ArchiveEntry>,
}

impl Novelty {
    /// A new search for `experiment` (whose algorithm is novelty) with genomes of
    /// `parameters` parameters.
    pub fn new(experiment: &Experiment, parameters: usize) -> Novelty {
        let settings = experiment.evolution.novelty_settings().unwrap_or_default();
        Novelty {
            ga: Ga::new(experiment, parameters),
            seed: experiment.seed(),
            space: Descriptors::new(&settings.descriptors, &experiment.behaviour.measures),
            settings,
            archive: Vec::new(),
        }
    }

    /// The archive, oldest entry first.
    pub fn archive(&self) -> &[ArchiveEntry] {
        &self.archive
    }

    /// Why `entry` cannot be part of this search's archive, if it cannot.
    fn entry_problem(&self, entry: &ArchiveEntry) -> Option<String> {
        if entry.behaviour.len() != self.space.len() {
            return Some(format!(
                "a novelty archive entry (generation {}, individual {}) has {} descriptors, but the experiment's novelty search has {}",
                entry.generation,
                entry.individual,
                entry.behaviour.len(),
                self.space.len()
            ));
        }
        if entry.behaviour.iter().any(|x| !x.is_finite()) {
            return Some(format!(
                "a novelty archive entry (generation {}, individual {}) holds a non-finite descriptor",
                entry.generation, entry.individual
            ));
        }
        None
    }
}

impl Search for Novelty {
    fn name(&self) -> &'static str {
        "novelty"
    }

    fn describe(&self) -> &'static str {
        "novelty search"
    }

    fn evaluated_per_generation(&self) -> usize {
        self.ga.evaluated_per_generation()
    }

    fn generation(&self) -> u64 {
        self.ga.generation()
    }

    fn ask(&self) -> Unevaluated {
        self.ga.ask()
    }

    fn tell(&mut self, evaluated: &EvaluatedGeneration) {
        let behaviours: Vec<Vec<f64>> = evaluated
            .individuals
            .iter()
            .map(|i| self.space.of(&i.evaluation))
            .collect();
        let archived: Vec<Vec<f64>> = self.archive.iter().map(|e| e.behaviour.clone()).collect();
        let novelty = novelty(&behaviours, &archived, self.settings.k);
        let fitness: Vec<Option<f64>> = evaluated
            .individuals
            .iter()
            .map(|i| i.evaluation.fitness)
            .collect();
        let mut rng = stream(
            self.seed,
            Purpose::Novelty,
            Generation(evaluated.generation),
            IndividualId(0),
            TrialIndex(0),
        );
        let added = archive_additions(&novelty, &fitness, Addition::of(&self.settings), &mut rng);
        let entries = added
            .into_iter()
            .map(|i| ArchiveEntry {
                generation: evaluated.generation,
                individual: i as u64,
                behaviour: behaviours[i].clone(),
            })
            .collect();
        add_to_archive(&mut self.archive, entries, self.settings.archive_size);
        self.ga.tell_scores(
            evaluated,
            scores(&novelty, &fitness, self.settings.fitness_weight),
        );
    }

    fn state(&self) -> Option<SearchState> {
        Some(SearchState::of(
            "novelty",
            &NoveltyState {
                archive: self.archive.clone(),
            },
        ))
    }

    fn restore(&mut self, state: Option<&SearchState>, _generation: u64) {
        // Lenient (a changed experiment): keep the entries that fit, the newest within the
        // capacity; another algorithm's state starts an empty archive.
        self.archive = match own_state::<NoveltyState>(state, "novelty", "novelty") {
            Ok(s) => s
                .archive
                .iter()
                .filter(|e| self.entry_problem(e).is_none())
                .cloned()
                .collect(),
            Err(_) => Vec::new(),
        };
        add_to_archive(&mut self.archive, Vec::new(), self.settings.archive_size);
    }

    fn state_problem(&self, state: Option<&SearchState>) -> Option<String> {
        if state.is_none() {
            return Some(
                "it holds no novelty archive, but its experiment uses novelty search".to_string(),
            );
        }
        let s = match own_state::<NoveltyState>(state, "novelty", "novelty") {
            Ok(s) => s,
            Err(why) => return Some(why),
        };
        if s.archive.len() > self.settings.archive_size {
            return Some(format!(
                "its novelty archive holds {} entries, more than [evolution.novelty] archive_size = {}",
                s.archive.len(),
                self.settings.archive_size
            ));
        }
        s.archive.iter().find_map(|e| self.entry_problem(e))
    }

    fn first_genomes(&self, n: usize) -> Vec<Genome> {
        self.ga.first_genomes(n)
    }
}
