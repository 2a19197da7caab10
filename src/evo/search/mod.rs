//! Search, ask/tell: the one seam between an evolution algorithm and everything around it.
//!
//! A [`Search`] owns its state and says three things: which genomes to evaluate next, with
//! their lineage ([`Search::ask`]); what it learns from their evaluation ([`Search::tell`]);
//! and what of its state a checkpoint must hold ([`Search::state`], as [`SearchState`]). It
//! also names its champions: which individual may become the best ever
//! ([`Search::improved_champion`]) and which extra candidates validation must consider
//! ([`Search::champion_candidates`]). The generation loop, `bench`, `inspect` and the
//! estimate only talk to this trait; [`of`] is the one place that matches on
//! `[evolution] algorithm` (as pycma's `ask`/`tell`, EvoJAX's `NEAlgorithm` and pyribs'
//! scheduler keep the task apart from the algorithm).
//!
//! # The contract, generation by generation
//!
//! A new run: `of(experiment)`, then `ask()` gives generation 0. After generation g is
//! evaluated, the loop checkpoints `state()` (the state that sampled g), then `tell(g)` and
//! `ask()` gives g + 1. A resumed run: `of(experiment)`, `restore(checkpoint's state, g)`,
//! `tell(checkpoint's generation g)`, `ask()`: the same generation g + 1 as a run never
//! stopped, bit for bit, because every random draw comes from a stream derived from the seed
//! and the generation (never from a generator kept in the search).
//!
//! # Algorithms
//!
//! - [`ga::Ga`], the generational genetic algorithm (`algorithm = "ga"`, the default): its
//!   state is its last evaluated generation, which the checkpoint holds anyway, so it
//!   saves no [`SearchState`] and GA checkpoints have no `search` field.
//! - [`pgpe::Pgpe`], PGPE with ClipUp (`algorithm = "pgpe"`): saves its distribution
//!   ([`pgpe::PgpeState`]) as `"search": {"pgpe": {...}}`.
//! - [`sep_cma_es::SepCmaEs`], CMA-ES with a diagonal covariance (`algorithm =
//!   "sep-cma-es"`): saves its distribution ([`sep_cma_es::SepCmaState`]) as
//!   `"search": {"sep_cma_es": {...}}`.
//! - [`cma_es::CmaEs`], CMA-ES with a full covariance (`algorithm = "cma-es"`): saves
//!   [`cma_es::CmaState`] as `"search": {"cma_es": {...}}`.
//! - [`novelty::Novelty`], novelty search, the GA ranking by novelty in behaviour space
//!   ([`descriptors`]; `algorithm = "novelty"`): saves its archive as `"search":
//!   {"novelty": {...}}`.
//! - [`map_elites::MapElites`], MAP-Elites with a grid archive ([`grid`]; `algorithm =
//!   "map-elites"`): saves its elites as `"search": {"map_elites": {...}}`, and shows its
//!   archive to the outputs through [`Search::archive`].
//!
//! docs/search.md, "Adding a search algorithm: a checklist", says how to add another.

pub mod cma_es;
pub mod cma_family;
pub mod descriptors;
pub mod draws;
pub mod factory;
pub mod ga;
pub mod grid;
pub mod map_elites;
pub mod novelty;
pub mod pgpe;
pub mod sep_cma_es;

use crate::brain::genome::Genome;
use crate::evo::lineage::Lineage;
use crate::evo::state::{improved_champion, Champion, EvaluatedGeneration, GenerationSummary};
use crate::evo::validation::Candidate;
use grid::ArchiveView;
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};

/// What a search carries from one generation to the next besides the evaluated generation
/// itself, as a checkpoint's `search` field holds it: the algorithm's own state under its
/// tag (`{"pgpe": {...}}`, `{"sep_cma_es": {...}}`). Each search writes and reads its own
/// state ([`SearchState::of`], [`SearchState::read`]), so this module names no algorithm and
/// a new one needs no change here. The GA has none.
#[derive(Debug, Clone, PartialEq)]
pub struct SearchState {
    tag: String,
    state: serde_json::Value,
}

impl SearchState {
    /// `state` under `tag` (the algorithm's name in snake case, as the checkpoint shows it).
    pub fn of<T: Serialize>(tag: &str, state: &T) -> SearchState {
        SearchState {
            tag: tag.to_string(),
            // A state of plain numbers and vectors always converts; a failure would be a bug
            // in the state type, so it shows as a state that does not read back.
            state: serde_json::to_value(state).unwrap_or(serde_json::Value::Null),
        }
    }

    /// The state under `tag`: `None` when this is another algorithm's state, `Err` when it is
    /// this algorithm's but does not read as `T`.
    pub fn read<T: DeserializeOwned>(&self, tag: &str) -> Option<Result<T, String>> {
        (self.tag == tag).then(|| T::deserialize(&self.state).map_err(|e| e.to_string()))
    }

    /// The algorithm whose state this is, as `[evolution] algorithm` names it (`pgpe`,
    /// `sep-cma-es`, ...).
    pub fn algorithm(&self) -> String {
        self.tag.replace('_', "-")
    }
}

/// `state` as the search `tag`'s own state `T` (`name`: the algorithm as `[evolution]
/// algorithm` names it), or why it is not: none, another algorithm's, or one that does not
/// read as `T`. For the searches' `restore` and `state_problem`.
pub fn own_state<T: DeserializeOwned>(
    state: Option<&SearchState>,
    tag: &str,
    name: &str,
) -> Result<T, String> {
    let Some(state) = state else {
        return Err(format!(
            "its experiment uses {name}, but it holds no {name} state"
        ));
    };
    match state.read::<T>(tag) {
        None => Err(format!(
            "it holds a {} state, but its experiment uses {name}",
            state.algorithm()
        )),
        Some(Err(e)) => Err(format!("its {name} state does not read back: {e}")),
        Some(Ok(t)) => Ok(t),
    }
}

impl Serialize for SearchState {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let mut map = serializer.serialize_map(Some(1))?;
        map.serialize_entry(&self.tag, &self.state)?;
        map.end()
    }
}

impl<'de> Deserialize<'de> for SearchState {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let map = serde_json::Map::<String, serde_json::Value>::deserialize(deserializer)?;
        let mut entries = map.into_iter();
        match (entries.next(), entries.next()) {
            (Some((tag, state)), None) => Ok(SearchState { tag, state }),
            _ => Err(serde::de::Error::custom(
                "a search state is one algorithm's name with its state, e.g. {\"pgpe\": {...}}",
            )),
        }
    }
}

/// A generation before its evaluation: its genomes in population order and where each came
/// from.
#[derive(Debug, Clone, PartialEq)]
pub struct Unevaluated {
    /// The genomes.
    pub genomes: Vec<Genome>,
    /// One lineage per genome, in the same order.
    pub lineage: Vec<Lineage>,
}

/// An evolution algorithm behind the ask/tell seam (see the module documentation for the
/// order of calls). `Send + Sync` so that the generation loop can run it on its thread pool.
pub trait Search: Send + Sync {
    /// The algorithm's name as `[evolution] algorithm` writes it (`ga`, `pgpe`).
    fn name(&self) -> &'static str;

    /// The algorithm in words, for `inspect` and `bench` (`genetic algorithm`, `PGPE`).
    fn describe(&self) -> &'static str;

    /// Individuals evaluated per generation: what [`Search::ask`] gives.
    fn evaluated_per_generation(&self) -> usize;

    /// The number of the generation [`Search::ask`] gives.
    fn generation(&self) -> u64;

    /// The next generation to evaluate, with each individual's lineage. Pure: asking twice
    /// gives the same genomes.
    fn ask(&self) -> Unevaluated;

    /// Learns from the evaluated generation that [`Search::ask`] gave (scores and behaviour
    /// measures, in population order); the next `ask` gives the generation after it.
    fn tell(&mut self, evaluated: &EvaluatedGeneration);

    /// What a checkpoint must hold to continue this search: the state that sampled the
    /// generation [`Search::ask`] gives (`None` for a search whose state is its last
    /// evaluated generation, as the GA's).
    fn state(&self) -> Option<SearchState>;

    /// Continues from a checkpoint: the search as it was when it had sampled generation
    /// `generation` with `state` (what [`Search::state`] returned then). Lenient, for a run
    /// resumed with a changed algorithm (`resume --allow-config-change`): a state of another
    /// algorithm, or none, is set aside and the search starts from the evaluated generation
    /// it is told next. [`Search::state_problem`] is the strict check.
    fn restore(&mut self, state: Option<&SearchState>, generation: u64);

    /// Why `state`, read from a checkpoint of this experiment, cannot continue this search
    /// (another algorithm's state, a missing one, wrong lengths, non-finite values), or
    /// `None` if it can.
    fn state_problem(&self, state: Option<&SearchState>) -> Option<String>;

    /// The first `n` genomes of generation 0 (at most the generation's size), drawn as
    /// [`Search::ask`] draws them on a new search but without the rest: what a timing
    /// calibration lives with, so that it meets the brains a run starts from at the cost of
    /// a few.
    fn first_genomes(&self, n: usize) -> Vec<Genome>;

    /// The new best-ever individual if `generation` beats `previous` (strictly). By default
    /// any individual ([`improved_champion`]).
    fn improved_champion(
        &self,
        previous: Option<&Champion>,
        generation: &EvaluatedGeneration,
        summary: &GenerationSummary,
    ) -> Option<Champion> {
        improved_champion(previous, generation, summary)
    }

    /// Candidates validation must consider besides the generation's top individuals (e.g. a
    /// search distribution's centre, also when its training score does not rank it among
    /// them). By default none.
    fn champion_candidates(&self, evaluated: &EvaluatedGeneration) -> Vec<Candidate> {
        let _ = evaluated;
        Vec::new()
    }

    /// How many candidates [`Search::champion_candidates`] gives per generation, at most
    /// (for the estimate). By default 0.
    fn champion_candidates_per_generation(&self) -> usize {
        0
    }

    /// The search's archive of elites as it will be once `evaluated` (the generation
    /// [`Search::ask`] gave, not yet told) is told: what archive.csv, fitness.csv's
    /// quality-diversity columns, `plot` and `extract --cell` show. `None` for a search
    /// without one (the default).
    fn archive<'a>(&'a self, evaluated: &'a EvaluatedGeneration) -> Option<ArchiveView<'a>> {
        let _ = evaluated;
        None
    }
}

/// The new champion of a distribution search whose solution is its centre (PGPE's centre,
/// sep-CMA-ES's mean), evaluated as the generation's last individual: only that individual,
/// and only when it beats `previous` strictly.
pub(crate) fn improved_centre(
    previous: Option<&Champion>,
    generation: &EvaluatedGeneration,
) -> Option<Champion> {
    let c = generation.individuals.len().checked_sub(1)?;
    let centre = &generation.individuals[c];
    let fitness = centre.evaluation.fitness?;
    if previous.is_some_and(|p| fitness <= p.fitness) {
        return None;
    }
    Some(Champion {
        genome: centre.genome.clone(),
        fitness,
        metabolism: centre.evaluation.metabolism,
        generation: generation.generation,
        individual: c as u64,
    })
}

/// The centre of a distribution search (the generation's last individual) as a validation
/// candidate: validation always considers it, after the top individuals, also when its
/// training score does not rank it among them.
pub(crate) fn centre_candidate(evaluated: &EvaluatedGeneration) -> Vec<Candidate> {
    let Some(last) = evaluated.individuals.len().checked_sub(1) else {
        return Vec::new();
    };
    let centre = &evaluated.individuals[last];
    vec![Candidate {
        genome: centre.genome.clone(),
        generation: evaluated.generation,
        individual: Some(last as u64),
        training_fitness: centre.evaluation.fitness,
        training_metabolism: Some(centre.evaluation.metabolism),
    }]
}
