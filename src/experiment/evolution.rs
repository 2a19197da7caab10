//! The `[evolution]` table: the generational genetic algorithm's settings (population,
//! elitism, selection, crossover, mutation, initialisation) and their validation.
//!
//! ```toml
//! [evolution]
//! population = 64
//! generations = 50
//! elitism = 2
//! init_range = 1.0
//!
//! [evolution.selection]
//! kind = "tournament"        # or "truncation", "rank"
//! tournament_size = 3        # only with kind = "tournament"
//!
//! [evolution.crossover]
//! kind = "uniform"           # or "none", "one_point", "arithmetic"
//! probability = 0.5          # not with kind = "none"
//!
//! [evolution.mutation]
//! probability = 0.1
//! sigma = 0.1
//! self_adaptive = false      # tau and min_sigma only with self_adaptive = true
//! ```
//!
//! `algorithm = "pgpe"` replaces the genetic algorithm by PGPE with ClipUp (see
//! `evo::pgpe` and [`PgpeSpec`]): then only `population` (even), `generations` and the
//! `[evolution.pgpe]` table apply, and the GA's keys must be left out. `algorithm =
//! "sep-cma-es"` and `"cma-es"` likewise, with the `[evolution.cma_es]` table ([`CmaEsSpec`]).
//! `algorithm = "novelty"` keeps the GA's keys and selects by novelty ([`NoveltySpec`],
//! `[evolution.novelty]`). `algorithm = "map-elites"` keeps a grid archive of elites
//! ([`MapElitesSpec`], `[evolution.map_elites]`): of the GA's keys only `init_range` applies.
//!
//! Every key has a default. A key that only matters for a setting the table did not choose
//! (`rank_pressure` with `kind = "tournament"`, `probability` with crossover `kind = "none"`,
//! `tau` with `self_adaptive = false`) is an error rather than silently ignored, so that a
//! forgotten `kind` line can never make a run use other settings than the file shows.
//! Written back (e.g. to a run folder), each sub-table shows its kind and exactly the values
//! that kind uses, defaults included.

use crate::experiment::tables::{area_index, Measure};
use crate::seed::Normals;
use crate::sim::spec::WorldSpec;
use crate::validate::{count_within, non_negative, within, InvalidValue, Valid};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// The largest population accepted: two generations of genomes are held in memory at once,
/// and selection keeps per-individual buffers.
pub const MAX_POPULATION: usize = 1_000_000;

/// The largest number of generations accepted (far beyond any run that can finish).
pub const MAX_GENERATIONS: u64 = 1_000_000_000;

/// The largest initialisation range and mutation standard deviation accepted. Network
/// parameters this large already saturate every unit; the limit keeps every draw, and every
/// self-adapted step size, finite.
pub const MAX_MAGNITUDE: f64 = 1.0e6;

/// The most parameters full CMA-ES accepts: its covariance matrix and eigenvectors hold
/// 2 n² numbers (in memory and in every checkpoint) and each eigendecomposition costs O(n³);
/// beyond this, sep-CMA-ES (linear in n) is the one to use.
pub const MAX_CMA_ES_PARAMETERS: usize = 2_000;

/// `[evolution]`: the search algorithm (the generational genetic algorithm by default).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct EvolutionSpec {
    /// `algorithm`: `"ga"` (the generational genetic algorithm, default), `"pgpe"`
    /// (Sehnke et al.'s PGPE with ClipUp, `evo::pgpe`), `"sep-cma-es"` (Ros & Hansen's
    /// diagonal CMA-ES, `evo::search::sep_cma_es`), `"cma-es"` (Hansen's CMA-ES with a full
    /// covariance matrix, `evo::search::cma_es`; at most 2,000 brain parameters) or
    /// `"novelty"` (the GA selecting by novelty, `[evolution.novelty]`) or `"map-elites"` (a
    /// grid archive of elites, `[evolution.map_elites]`). Not written back when "ga", so GA
    /// experiments keep their bytes and config hash.
    #[serde(skip_serializing_if = "Algorithm::is_ga")]
    pub algorithm: Algorithm,
    /// Individuals per generation (default: 64; 2 to 1 000 000).
    pub population: usize,
    /// How many generations a run evaluates, counting the random initial population as the
    /// first (default: 50; at most 10^9).
    pub generations: u64,
    /// How many of the best parents are copied unchanged into the next generation, best
    /// first (default: 2; at most the population).
    pub elitism: usize,
    /// Initial parameters are drawn uniformly from [−init_range, init_range) (default: 1;
    /// 0 to 10^6).
    pub init_range: f64,
    /// How parents are chosen (`[evolution.selection]`; default: tournament of 3).
    pub selection: SelectionSpec,
    /// How two parents are recombined (`[evolution.crossover]`; default: uniform with
    /// probability 0.5).
    pub crossover: CrossoverSpec,
    /// How offspring are mutated (`[evolution.mutation]`; default: each gene with
    /// probability 0.1 gets Gaussian noise of standard deviation 0.1).
    pub mutation: MutationSpec,
    /// PGPE's settings (`[evolution.pgpe]`; only with `algorithm = "pgpe"`, where a missing
    /// table means every default of [`PgpeSpec`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pgpe: Option<PgpeSpec>,
    /// sep-CMA-ES's and CMA-ES's settings (`[evolution.cma_es]`; only with `algorithm =
    /// "sep-cma-es"` or `"cma-es"`, where a missing table means every default of [`CmaEsSpec`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cma_es: Option<CmaEsSpec>,
    /// Novelty search's settings (`[evolution.novelty]`; only with `algorithm = "novelty"`,
    /// which needs its `descriptors`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub novelty: Option<NoveltySpec>,
    /// MAP-Elites' settings (`[evolution.map_elites]`; only with `algorithm = "map-elites"`,
    /// which needs its `descriptors`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub map_elites: Option<MapElitesSpec>,
    /// `draw_order`: how the search draws its random numbers (default: 1; 1 or 2). 1 is the
    /// order every shipped experiment was run with: the GA draws a chance for every gene from
    /// one stream per generation, and normals by Box–Muller. 2 is for large brains (thousands
    /// of parameters), where 1 makes the search a visible share of a generation: each GA
    /// offspring draws from its own stream (so offspring are made in parallel), mutation
    /// takes two genes' chances from one draw, uniform crossover 64 genes' choices, and
    /// every search's normals are drawn by the ziggurat method, each individual's from its
    /// own stream. Both are exact and reproducible; they give
    /// different runs from the same seed. Not written back when 1, so existing files keep their
    /// bytes and config hash.
    #[serde(skip_serializing_if = "is_first_draw_order")]
    pub draw_order: u32,
}

/// True for draw order 1 (the default, not written back).
fn is_first_draw_order(order: &u32) -> bool {
    *order == 1
}

/// The search algorithms `[evolution] algorithm` chooses from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Algorithm {
    /// The generational genetic algorithm (elitism, selection, crossover, mutation).
    #[default]
    Ga,
    /// PGPE with symmetric sampling, centred-rank fitness shaping and ClipUp.
    Pgpe,
    /// sep-CMA-ES: CMA-ES with a diagonal covariance matrix (Ros & Hansen 2008), linear in
    /// the number of parameters.
    #[serde(rename = "sep-cma-es")]
    SepCmaEs,
    /// CMA-ES with a full covariance matrix (Hansen's tutorial), quadratic in memory and
    /// cubic per eigendecomposition in the number of parameters (at most 2,000).
    #[serde(rename = "cma-es")]
    CmaEs,
    /// Novelty search (Lehman & Stanley 2011): the GA selecting by novelty in behaviour
    /// space (`[evolution.novelty]`).
    Novelty,
    /// MAP-Elites (Mouret & Clune 2015): a grid archive keeping the best genome of every
    /// cell of behaviour space, each generation made by varying elites drawn from it
    /// (`[evolution.map_elites]`).
    #[serde(rename = "map-elites")]
    MapElites,
}

impl Algorithm {
    /// True for the genetic algorithm (the default, not written back).
    pub fn is_ga(&self) -> bool {
        *self == Algorithm::Ga
    }
}

impl Default for EvolutionSpec {
    fn default() -> Self {
        EvolutionSpec {
            algorithm: Algorithm::Ga,
            population: 64,
            generations: 50,
            elitism: 2,
            init_range: 1.0,
            selection: SelectionSpec::default(),
            crossover: CrossoverSpec::default(),
            mutation: MutationSpec::default(),
            pgpe: None,
            cma_es: None,
            novelty: None,
            map_elites: None,
            draw_order: 1,
        }
    }
}

impl EvolutionSpec {
    /// How this search turns words into normal draws (`draw_order`).
    pub fn normals(&self) -> Normals {
        if self.draw_order >= 2 {
            Normals::Ziggurat
        } else {
            Normals::BoxMuller
        }
    }

    /// Whether each GA offspring draws from its own stream, two genes' chances a draw
    /// (`draw_order = 2`).
    pub fn offspring_streams(&self) -> bool {
        self.draw_order >= 2
    }

    /// PGPE's settings when `algorithm = "pgpe"` (the table's, or every default).
    pub fn pgpe_settings(&self) -> Option<PgpeSpec> {
        match self.algorithm {
            Algorithm::Ga
            | Algorithm::SepCmaEs
            | Algorithm::CmaEs
            | Algorithm::Novelty
            | Algorithm::MapElites => None,
            Algorithm::Pgpe => Some(self.pgpe.unwrap_or_default()),
        }
    }

    /// Novelty search's settings when `algorithm = "novelty"` (the table's, or every default).
    pub fn novelty_settings(&self) -> Option<NoveltySpec> {
        (self.algorithm == Algorithm::Novelty).then(|| self.novelty.clone().unwrap_or_default())
    }

    /// MAP-Elites' settings when `algorithm = "map-elites"` (the table's, or every default).
    pub fn map_elites_settings(&self) -> Option<MapElitesSpec> {
        (self.algorithm == Algorithm::MapElites)
            .then(|| self.map_elites.clone().unwrap_or_default())
    }

    /// True when the search keeps an archive of elites (MAP-Elites), whose quality-diversity
    /// metrics fitness.csv gains as columns and whose cells `archive.csv` lists.
    pub fn has_archive(&self) -> bool {
        self.algorithm == Algorithm::MapElites
    }

    /// The search's descriptors (novelty's or MAP-Elites'), with the key they sit under;
    /// `None` for a search without.
    fn descriptor_list(&self) -> Option<(&'static str, Vec<DescriptorSpec>)> {
        if let Some(novelty) = self.novelty_settings() {
            Some(("evolution.novelty.descriptors", novelty.descriptors))
        } else {
            self.map_elites_settings().map(|grid| {
                (
                    "evolution.map_elites.descriptors",
                    grid.descriptors.iter().map(|d| d.descriptor()).collect(),
                )
            })
        }
    }

    /// Novelty's and MAP-Elites' descriptors must be measures `[behaviour] measures`
    /// computes (each individual's evaluation carries them in that order), but those that
    /// name an `area`: `time_in_area` only, at most [`MAX_DESCRIBED_AREAS`] of them, each a
    /// named area of `world`.
    pub fn validate_descriptors(&self, measures: &[Measure], world: &WorldSpec) -> Valid {
        let Some((key, descriptors)) = self.descriptor_list() else {
            return Ok(());
        };
        let computed: Vec<&str> = measures.iter().map(|m| m.name()).collect();
        let mut areas = 0;
        for (i, d) in descriptors.iter().enumerate() {
            if let Some(area) = &d.area {
                let at = format!("{key}[{i}].area");
                if d.measure != Measure::TimeInArea {
                    return Err(InvalidValue::new(
                        &at,
                        format!(
                            "only `time_in_area` counts the time in an area it names, not `{}`; \
                             remove `area` or use measure = \"time_in_area\"",
                            d.measure.name()
                        ),
                    ));
                }
                area_index(world, &at, area)?;
                areas += 1;
                if areas > MAX_DESCRIBED_AREAS {
                    return Err(InvalidValue::new(
                        &at,
                        format!(
                            "at most {MAX_DESCRIBED_AREAS} descriptors may name an area (limit: \
                             each is counted every tick of every trial); describe fewer areas"
                        ),
                    ));
                }
                continue;
            }
            if !measures.contains(&d.measure) {
                return Err(InvalidValue::new(
                    key,
                    format!(
                        "`{}` is not computed by this experiment: [behaviour] measures = [{}]; \
                         add it to [behaviour] measures or describe behaviour by one of those",
                        d.measure.name(),
                        computed.join(", ")
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The areas the search's descriptors name, resolved in `world` (the experiment's
    /// `[world]`; a name not found there, which validation refuses, is left out).
    pub fn described_areas(&self, world: &WorldSpec) -> DescribedAreas {
        let mut areas = DescribedAreas::default();
        let Some((_, descriptors)) = self.descriptor_list() else {
            return areas;
        };
        for d in &descriptors {
            if let Some(name) = &d.area {
                if let (Ok(k), true) =
                    (area_index(world, "", name), areas.len < MAX_DESCRIBED_AREAS)
                {
                    areas.at[areas.len] = k;
                    areas.len += 1;
                }
            }
        }
        areas
    }

    /// Individuals evaluated per generation: the population, plus PGPE's centre or
    /// sep-CMA-ES's mean, which is evaluated as one more individual (the last) so that it can
    /// become the champion.
    pub fn evaluated_per_generation(&self) -> usize {
        match self.algorithm {
            Algorithm::Ga | Algorithm::Novelty | Algorithm::MapElites => self.population,
            Algorithm::Pgpe | Algorithm::SepCmaEs | Algorithm::CmaEs => self.population + 1,
        }
    }

    /// Checks the algorithm against the brain's parameter count: full CMA-ES is refused
    /// beyond [`MAX_CMA_ES_PARAMETERS`].
    pub fn validate_against_parameters(&self, parameters: u64) -> Valid {
        if self.algorithm == Algorithm::CmaEs && parameters > MAX_CMA_ES_PARAMETERS as u64 {
            return Err(InvalidValue::new(
                "evolution.algorithm",
                format!(
                    "\"cma-es\" keeps a full covariance matrix, so it takes brains of at most \
                     {MAX_CMA_ES_PARAMETERS} parameters (limit: n² memory and an n³ \
                     eigendecomposition), but this brain has {parameters}; use algorithm = \
                     \"sep-cma-es\" (diagonal, linear in n) or a smaller brain"
                ),
            ));
        }
        Ok(())
    }

    /// The GA's keys would be silently ignored by `algorithm`: refuse them (a key written
    /// with its default value cannot be told apart and is accepted).
    fn refuse_ga_keys(&self, algorithm: &str) -> Valid {
        self.refuse_ga_keys_but(algorithm, false)
    }

    /// [`EvolutionSpec::refuse_ga_keys`], accepting `init_range` when `keep_init_range`
    /// (MAP-Elites draws its random genomes as the GA's generation 0).
    fn refuse_ga_keys_but(&self, algorithm: &str, keep_init_range: bool) -> Valid {
        let ga = EvolutionSpec::default();
        for (differs, key) in [
            (self.elitism != ga.elitism, "elitism"),
            (
                !keep_init_range && self.init_range != ga.init_range,
                "init_range",
            ),
            (self.selection != ga.selection, "selection"),
            (self.crossover != ga.crossover, "crossover"),
            (self.mutation != ga.mutation, "mutation"),
        ] {
            if differs {
                return Err(InvalidValue::new(
                    format!("evolution.{key}"),
                    format!("is only used with algorithm = \"ga\", but this table has algorithm = \"{algorithm}\"; remove it"),
                ));
            }
        }
        Ok(())
    }

    /// Checks every value; keys start with `evolution.`.
    pub fn validate(&self) -> Valid {
        if self.population < 2 {
            // The real minimum, and, for the GA, what else a population of 2 needs (the
            // default tournament of 3 is larger).
            let ga = if self.algorithm == Algorithm::Ga {
                " (with [evolution.selection] tournament_size = 2 or less: the default \
                 tournament of 3 needs a population of 3)"
            } else {
                ""
            };
            return Err(InvalidValue::new(
                "evolution.population",
                format!("must be at least 2{ga}, got {}", self.population),
            ));
        }
        count_within(
            "evolution.population",
            self.population as u64,
            2,
            MAX_POPULATION as u64,
            "limit: memory for two generations of genomes",
        )?;
        count_within(
            "evolution.generations",
            self.generations,
            1,
            MAX_GENERATIONS,
            "limit",
        )?;
        if self.elitism > self.population {
            return Err(InvalidValue::new(
                "evolution.elitism",
                format!(
                    "elitism {} is larger than the population {}",
                    self.elitism, self.population
                ),
            ));
        }
        magnitude("evolution.init_range", self.init_range)?;
        if !(1..=2).contains(&self.draw_order) {
            return Err(InvalidValue::new(
                "evolution.draw_order",
                format!(
                    "must be 1 (the order every shipped experiment uses) or 2 (for brains of \
                     thousands of parameters: offspring in parallel, fewer draws per gene), \
                     got {}",
                    self.draw_order
                ),
            ));
        }
        self.selection.validate(self.population)?;
        self.crossover.validate()?;
        self.mutation.validate()?;
        let cma = matches!(self.algorithm, Algorithm::SepCmaEs | Algorithm::CmaEs);
        if self.cma_es.is_some() && !cma {
            return Err(InvalidValue::new(
                "evolution.cma_es",
                "is only used with algorithm = \"sep-cma-es\" or \"cma-es\"; remove it or set one of them",
            ));
        }
        if self.novelty.is_some() && self.algorithm != Algorithm::Novelty {
            return Err(InvalidValue::new(
                "evolution.novelty",
                "is only used with algorithm = \"novelty\"; remove it or set algorithm = \"novelty\"",
            ));
        }
        if self.map_elites.is_some() && self.algorithm != Algorithm::MapElites {
            return Err(InvalidValue::new(
                "evolution.map_elites",
                "is only used with algorithm = \"map-elites\"; remove it or set algorithm = \"map-elites\"",
            ));
        }
        match self.algorithm {
            Algorithm::MapElites => {
                if self.pgpe.is_some() {
                    return Err(InvalidValue::new(
                        "evolution.pgpe",
                        "is only used with algorithm = \"pgpe\", but this table has algorithm = \"map-elites\"; remove it",
                    ));
                }
                self.refuse_ga_keys_but("map-elites", true)?;
                self.map_elites_settings().unwrap_or_default().validate()
            }
            Algorithm::Novelty => {
                if self.pgpe.is_some() {
                    return Err(InvalidValue::new(
                        "evolution.pgpe",
                        "is only used with algorithm = \"pgpe\", but this table has algorithm = \"novelty\"; remove it",
                    ));
                }
                self.novelty_settings()
                    .unwrap_or_default()
                    .validate(self.population)
            }
            Algorithm::SepCmaEs | Algorithm::CmaEs => {
                let name = if self.algorithm == Algorithm::CmaEs {
                    "cma-es"
                } else {
                    "sep-cma-es"
                };
                if self.pgpe.is_some() {
                    return Err(InvalidValue::new(
                        "evolution.pgpe",
                        format!("is only used with algorithm = \"pgpe\", but this table has algorithm = \"{name}\"; remove it"),
                    ));
                }
                self.refuse_ga_keys(name)?;
                self.cma_es.unwrap_or_default().validate()
            }
            Algorithm::Ga => {
                if self.pgpe.is_some() {
                    return Err(InvalidValue::new(
                        "evolution.pgpe",
                        "is only used with algorithm = \"pgpe\", but this table has algorithm = \"ga\"; remove it or set algorithm = \"pgpe\"",
                    ));
                }
                Ok(())
            }
            Algorithm::Pgpe => {
                if self.population % 2 != 0 {
                    return Err(InvalidValue::new(
                        "evolution.population",
                        format!(
                            "pgpe samples in mirrored pairs, so the population must be even, got {}",
                            self.population
                        ),
                    ));
                }
                self.refuse_ga_keys("pgpe")?;
                self.pgpe_settings().unwrap_or_default().validate()
            }
        }
    }
}

/// `[evolution.pgpe]`: PGPE (Sehnke et al. 2010) with ClipUp (Toklu et al. 2020), as
/// EvoJAX's `PGPE(optimizer = "clipup")`; the defaults are EvoJAX's.
///
/// ```toml
/// [evolution]
/// algorithm = "pgpe"
/// population = 64                # even: 32 mirrored pairs, plus the centre evaluated too
///
/// [evolution.pgpe]
/// center_learning_rate = 0.15    # ClipUp step size
/// max_speed = 0.15               # ClipUp's largest centre step per generation (L2 norm)
/// momentum = 0.9                 # ClipUp momentum
/// stdev_init = 0.1               # every parameter's initial standard deviation
/// stdev_learning_rate = 0.1
/// stdev_max_change = 0.2         # relative change of a standard deviation per generation
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct PgpeSpec {
    /// `center_learning_rate`: ClipUp's step size α, the length (L2, parameter units) of the
    /// normalised gradient step added to the velocity each generation (default: 0.15; greater
    /// than 0, at most 10^6).
    pub center_learning_rate: f64,
    /// `max_speed`: ClipUp's largest velocity, i.e. the largest move of the centre per
    /// generation in L2 norm (default: 0.15, EvoJAX's; the ClipUp paper suggests
    /// 2 × center_learning_rate; greater than 0, at most 10^6).
    pub max_speed: f64,
    /// `momentum`: ClipUp's momentum μ, the share of the velocity kept from one generation to
    /// the next (default: 0.9; 0 to below 1).
    pub momentum: f64,
    /// `stdev_init`: the initial standard deviation of every parameter, in parameter units
    /// (default: 0.1; greater than 0, at most 10^6).
    pub stdev_init: f64,
    /// `stdev_learning_rate`: the learning rate of the standard deviations' plain gradient
    /// step (default: 0.1; 0 to 10^6; 0 keeps them fixed).
    pub stdev_learning_rate: f64,
    /// `stdev_max_change`: a standard deviation changes by at most this share of itself per
    /// generation (default: 0.2; 0 to below 1).
    pub stdev_max_change: f64,
}

impl Default for PgpeSpec {
    fn default() -> Self {
        PgpeSpec {
            center_learning_rate: 0.15,
            max_speed: 0.15,
            momentum: 0.9,
            stdev_init: 0.1,
            stdev_learning_rate: 0.1,
            stdev_max_change: 0.2,
        }
    }
}

impl PgpeSpec {
    /// Checks the table; keys start with `evolution.pgpe.`.
    pub fn validate(&self) -> Valid {
        for (key, value) in [
            ("center_learning_rate", self.center_learning_rate),
            ("max_speed", self.max_speed),
            ("stdev_init", self.stdev_init),
        ] {
            let key = format!("evolution.pgpe.{key}");
            magnitude(&key, value)?;
            if value == 0.0 {
                return Err(InvalidValue::new(key, "must be greater than 0, got 0"));
            }
        }
        magnitude(
            "evolution.pgpe.stdev_learning_rate",
            self.stdev_learning_rate,
        )?;
        for (key, value) in [
            ("momentum", self.momentum),
            ("stdev_max_change", self.stdev_max_change),
        ] {
            let key = format!("evolution.pgpe.{key}");
            within(&key, value, 0.0, 1.0)?;
            if value == 1.0 {
                return Err(InvalidValue::new(key, "must be below 1, got 1"));
            }
        }
        Ok(())
    }
}

/// `[evolution.cma_es]`: sep-CMA-ES (Ros & Hansen 2008), CMA-ES with a diagonal covariance
/// matrix, and full CMA-ES (`algorithm = "cma-es"`, `evo::search::cma_es`), which share it. `population` is λ, the samples per generation (Hansen's default for n parameters
/// is 4 + ⌊3 ln n⌋, e.g. 24 for 1,000; more helps on noisy and multimodal problems); μ = ⌊λ/2⌋,
/// the recombination weights and every learning rate follow Hansen's tutorial (see
/// `evo::search::sep_cma_es`), so the table only sets where the search starts.
///
/// ```toml
/// [evolution]
/// algorithm = "sep-cma-es"
/// population = 32                # λ samples; the mean is evaluated too, as a 33rd
///
/// [evolution.cma_es]
/// sigma_init = 0.5               # the initial step size σ
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct CmaEsSpec {
    /// `sigma_init`: the initial step size σ, the standard deviation of every parameter at the
    /// start, in parameter units (the mean starts at 0) (default: 0.5; greater than 0, at most
    /// 10^6).
    pub sigma_init: f64,
}

impl Default for CmaEsSpec {
    fn default() -> Self {
        CmaEsSpec { sigma_init: 0.5 }
    }
}

impl CmaEsSpec {
    /// Checks the table; keys start with `evolution.cma_es.`.
    pub fn validate(&self) -> Valid {
        magnitude("evolution.cma_es.sigma_init", self.sigma_init)?;
        if self.sigma_init == 0.0 {
            return Err(InvalidValue::new(
                "evolution.cma_es.sigma_init",
                "must be greater than 0, got 0",
            ));
        }
        Ok(())
    }
}

/// A finite value in [0, MAX_MAGNITUDE].
fn magnitude(key: &str, value: f64) -> Valid {
    non_negative(key, value)?;
    if value > MAX_MAGNITUDE {
        return Err(InvalidValue::new(
            key,
            format!("must be at most {MAX_MAGNITUDE} (limit), got {value}"),
        ));
    }
    Ok(())
}

/// A probability: finite and in [0, 1].
fn probability(key: &str, value: f64) -> Valid {
    within(key, value, 0.0, 1.0)
}

/// `[evolution.selection]`: how each parent of an offspring is chosen from the evaluated
/// generation. Higher fitness is better; equal fitness is broken in favour of the lower index.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(try_from = "RawSelection", into = "RawSelection")]
pub enum SelectionSpec {
    /// `kind = "tournament"`: the best of `tournament_size` distinct individuals drawn
    /// uniformly (without replacement, so a tournament of the whole population always picks
    /// the best and a tournament of 1 is uniform).
    Tournament {
        /// `tournament_size`: individuals per tournament (default: 3; 1 to the population).
        size: usize,
    },
    /// `kind = "truncation"`: uniform among the best ⌈truncation_fraction · n⌉ (at least 1).
    Truncation {
        /// `truncation_fraction`: the share of the population that may become a parent
        /// (default: 0.2; greater than 0, at most 1).
        fraction: f64,
    },
    /// `kind = "rank"`: Baker's linear ranking. The individual of rank r (0 = worst,
    /// n − 1 = best) is picked with probability ((2 − s) + 2(s − 1) r / (n − 1)) / n.
    Rank {
        /// `rank_pressure` s: expected number of picks of the best individual per n picks
        /// (default: 1.7; 1 = uniform, 2 = the worst is never picked).
        pressure: f64,
    },
}

/// Default tournament size.
pub const DEFAULT_TOURNAMENT_SIZE: usize = 3;
/// Default truncation fraction.
pub const DEFAULT_TRUNCATION_FRACTION: f64 = 0.2;
/// Default linear-ranking pressure.
pub const DEFAULT_RANK_PRESSURE: f64 = 1.7;

impl Default for SelectionSpec {
    fn default() -> Self {
        SelectionSpec::Tournament {
            size: DEFAULT_TOURNAMENT_SIZE,
        }
    }
}

impl SelectionSpec {
    /// Checks the table against the population size; keys start with `evolution.selection.`.
    pub fn validate(&self, population: usize) -> Valid {
        match *self {
            SelectionSpec::Tournament { size } if size > population && size > 0 => {
                // Usually a small population with the default tournament of 3: name both keys
                // and the population this tournament needs, not only the key the user never
                // wrote.
                Err(InvalidValue::new(
                    "evolution.selection.tournament_size",
                    format!(
                        "a tournament of {size} (3 when not written) needs a population of at \
                         least {size}, got evolution.population = {population}; raise the \
                         population to {size} or more, or set tournament_size to at most \
                         {population} (the smallest population a GA takes is 2, with \
                         tournament_size = 2 or less)"
                    ),
                ))
            }
            SelectionSpec::Tournament { size } => count_within(
                "evolution.selection.tournament_size",
                size as u64,
                1,
                population as u64,
                "the population",
            ),
            SelectionSpec::Truncation { fraction } => {
                let key = "evolution.selection.truncation_fraction";
                within(key, fraction, 0.0, 1.0)?;
                if fraction == 0.0 {
                    return Err(InvalidValue::new(key, "must be greater than 0, got 0"));
                }
                Ok(())
            }
            SelectionSpec::Rank { pressure } => {
                within("evolution.selection.rank_pressure", pressure, 1.0, 2.0)
            }
        }
    }
}

/// The kinds of selection, as spelt in TOML.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
enum SelectionKind {
    #[default]
    Tournament,
    Truncation,
    Rank,
}

/// `[evolution.selection]` as written: every key optional, checked against `kind`.
#[derive(Debug, Clone, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
struct RawSelection {
    /// `"tournament"`, `"truncation"` or `"rank"` (default: `"tournament"`).
    kind: SelectionKind,
    /// Tournament only: individuals per tournament, drawn without replacement (default: 3).
    #[serde(skip_serializing_if = "Option::is_none")]
    tournament_size: Option<usize>,
    /// Truncation only: the share of the population that may become a parent (default: 0.2).
    #[serde(skip_serializing_if = "Option::is_none")]
    truncation_fraction: Option<f64>,
    /// Rank only: Baker's pressure s, expected picks of the best individual per n picks
    /// (default: 1.7; 1 = uniform, 2 = the worst is never picked).
    #[serde(skip_serializing_if = "Option::is_none")]
    rank_pressure: Option<f64>,
}

/// The error for a key that the chosen kind does not use.
fn unused_key(key: &str, used_by: &str, chosen: &str) -> String {
    format!("`{key}` is only used with {used_by}, but this table has {chosen}; remove it")
}

impl TryFrom<RawSelection> for SelectionSpec {
    type Error = String;

    fn try_from(raw: RawSelection) -> Result<Self, String> {
        let (name, spec) = match raw.kind {
            SelectionKind::Tournament => (
                "tournament",
                SelectionSpec::Tournament {
                    size: raw.tournament_size.unwrap_or(DEFAULT_TOURNAMENT_SIZE),
                },
            ),
            SelectionKind::Truncation => (
                "truncation",
                SelectionSpec::Truncation {
                    fraction: raw
                        .truncation_fraction
                        .unwrap_or(DEFAULT_TRUNCATION_FRACTION),
                },
            ),
            SelectionKind::Rank => (
                "rank",
                SelectionSpec::Rank {
                    pressure: raw.rank_pressure.unwrap_or(DEFAULT_RANK_PRESSURE),
                },
            ),
        };
        let chosen = format!("kind = \"{name}\"");
        let foreign = [
            (
                raw.tournament_size.is_some() && raw.kind != SelectionKind::Tournament,
                "tournament_size",
                "kind = \"tournament\"",
            ),
            (
                raw.truncation_fraction.is_some() && raw.kind != SelectionKind::Truncation,
                "truncation_fraction",
                "kind = \"truncation\"",
            ),
            (
                raw.rank_pressure.is_some() && raw.kind != SelectionKind::Rank,
                "rank_pressure",
                "kind = \"rank\"",
            ),
        ];
        for (present, key, used_by) in foreign {
            if present {
                return Err(unused_key(
                    &format!("evolution.selection.{key}"),
                    used_by,
                    &chosen,
                ));
            }
        }
        Ok(spec)
    }
}

impl From<SelectionSpec> for RawSelection {
    fn from(spec: SelectionSpec) -> Self {
        match spec {
            SelectionSpec::Tournament { size } => RawSelection {
                kind: SelectionKind::Tournament,
                tournament_size: Some(size),
                ..RawSelection::default()
            },
            SelectionSpec::Truncation { fraction } => RawSelection {
                kind: SelectionKind::Truncation,
                truncation_fraction: Some(fraction),
                ..RawSelection::default()
            },
            SelectionSpec::Rank { pressure } => RawSelection {
                kind: SelectionKind::Rank,
                rank_pressure: Some(pressure),
                ..RawSelection::default()
            },
        }
    }
}

/// `[evolution.crossover]`: how the two parents of an offspring are recombined. With
/// probability `probability` an offspring is their recombination, otherwise a copy of the
/// first parent; mutation follows either way.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(try_from = "RawCrossover", into = "RawCrossover")]
pub enum CrossoverSpec {
    /// `kind = "none"`: offspring are mutated copies of one selected parent (no second parent
    /// is selected; `probability` must not be given).
    None,
    /// `kind = "uniform"`: each gene comes from either parent with probability 1/2.
    Uniform {
        /// `probability`: chance that an offspring is recombined (default: 0.5; 0 to 1).
        probability: f64,
    },
    /// `kind = "one_point"`: genes before a cut point drawn uniformly from 1..n come from the
    /// first parent, the rest from the second (n = number of genes; with n < 2 there is no
    /// cut and the offspring copies the first parent).
    OnePoint {
        /// `probability`: chance that an offspring is recombined (default: 0.5; 0 to 1).
        probability: f64,
    },
    /// `kind = "arithmetic"`: whole arithmetic recombination, child = a·x + (1 − a)·y for
    /// parents x and y with one a drawn uniformly from [0, 1) per offspring.
    Arithmetic {
        /// `probability`: chance that an offspring is recombined (default: 0.5; 0 to 1).
        probability: f64,
    },
}

/// Default crossover probability.
pub const DEFAULT_CROSSOVER_PROBABILITY: f64 = 0.5;

impl Default for CrossoverSpec {
    fn default() -> Self {
        CrossoverSpec::Uniform {
            probability: DEFAULT_CROSSOVER_PROBABILITY,
        }
    }
}

impl CrossoverSpec {
    /// The chance that an offspring is recombined (0 for `none`).
    pub fn probability(&self) -> f64 {
        match *self {
            CrossoverSpec::None => 0.0,
            CrossoverSpec::Uniform { probability }
            | CrossoverSpec::OnePoint { probability }
            | CrossoverSpec::Arithmetic { probability } => probability,
        }
    }

    /// Checks the table; keys start with `evolution.crossover.`.
    pub fn validate(&self) -> Valid {
        match self {
            CrossoverSpec::None => Ok(()),
            _ => probability("evolution.crossover.probability", self.probability()),
        }
    }
}

/// The kinds of crossover, as spelt in TOML.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
enum CrossoverKind {
    None,
    #[default]
    Uniform,
    OnePoint,
    Arithmetic,
}

/// `[evolution.crossover]` as written.
#[derive(Debug, Clone, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
struct RawCrossover {
    /// `"none"`, `"uniform"`, `"one_point"` or `"arithmetic"` (default: `"uniform"`).
    kind: CrossoverKind,
    /// Chance that an offspring is recombined rather than a copy of its first parent
    /// (default: 0.5; not with `kind = "none"`).
    #[serde(skip_serializing_if = "Option::is_none")]
    probability: Option<f64>,
}

impl TryFrom<RawCrossover> for CrossoverSpec {
    type Error = String;

    fn try_from(raw: RawCrossover) -> Result<Self, String> {
        let probability = raw.probability.unwrap_or(DEFAULT_CROSSOVER_PROBABILITY);
        Ok(match raw.kind {
            CrossoverKind::None => {
                if raw.probability.is_some() {
                    return Err(unused_key(
                        "evolution.crossover.probability",
                        "a crossover kind other than \"none\"",
                        "kind = \"none\"",
                    ));
                }
                CrossoverSpec::None
            }
            CrossoverKind::Uniform => CrossoverSpec::Uniform { probability },
            CrossoverKind::OnePoint => CrossoverSpec::OnePoint { probability },
            CrossoverKind::Arithmetic => CrossoverSpec::Arithmetic { probability },
        })
    }
}

impl From<CrossoverSpec> for RawCrossover {
    fn from(spec: CrossoverSpec) -> Self {
        let kind = match spec {
            CrossoverSpec::None => CrossoverKind::None,
            CrossoverSpec::Uniform { .. } => CrossoverKind::Uniform,
            CrossoverSpec::OnePoint { .. } => CrossoverKind::OnePoint,
            CrossoverSpec::Arithmetic { .. } => CrossoverKind::Arithmetic,
        };
        RawCrossover {
            kind,
            probability: match spec {
                CrossoverSpec::None => None,
                _ => Some(spec.probability()),
            },
        }
    }
}

/// `[evolution.mutation]`: per-gene Gaussian mutation, with an optional self-adaptive step
/// size that each genome carries and that evolves with it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(try_from = "RawMutation", into = "RawMutation")]
pub struct MutationSpec {
    /// `probability`: chance that each gene of an offspring is mutated (default: 0.1; 0 to 1).
    pub probability: f64,
    /// `sigma`: standard deviation of the Gaussian added to a mutated gene, in parameter
    /// units; with self-adaptation, the initial population's step size (default: 0.1;
    /// 0 to 10^6).
    pub sigma: f64,
    /// `self_adaptive = true`: each genome carries its own step size, mutated log-normally
    /// before its genes (default: off, written `self_adaptive = false`).
    pub self_adaptive: Option<SelfAdaptation>,
}

/// Settings of self-adaptive mutation (Schwefel's log-normal rule): before its genes, an
/// offspring's step size σ becomes σ' = σ · exp(τ · N(0, 1)), kept within
/// [min_sigma, 10^6], and its mutated genes get N(0, σ'²).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SelfAdaptation {
    /// `tau`: learning rate τ of the step size, dimensionless (default: 1/√n for n genes;
    /// at least 0).
    pub tau: Option<f64>,
    /// `min_sigma`: the smallest step size, in parameter units, so that a step size cannot
    /// collapse to 0 (default: 10^-6; 0 to `sigma`).
    pub min_sigma: f64,
}

/// Default per-gene mutation probability.
pub const DEFAULT_MUTATION_PROBABILITY: f64 = 0.1;
/// Default mutation standard deviation.
pub const DEFAULT_SIGMA: f64 = 0.1;
/// Default floor of a self-adaptive step size.
pub const DEFAULT_MIN_SIGMA: f64 = 1.0e-6;

impl Default for MutationSpec {
    fn default() -> Self {
        MutationSpec {
            probability: DEFAULT_MUTATION_PROBABILITY,
            sigma: DEFAULT_SIGMA,
            self_adaptive: None,
        }
    }
}

impl Default for SelfAdaptation {
    fn default() -> Self {
        SelfAdaptation {
            tau: None,
            min_sigma: DEFAULT_MIN_SIGMA,
        }
    }
}

impl SelfAdaptation {
    /// The learning rate for genomes of `genes` parameters: `tau`, or 1/√n by default
    /// (n taken as at least 1).
    pub fn tau_for(&self, genes: usize) -> f64 {
        self.tau
            .unwrap_or_else(|| 1.0 / (genes.max(1) as f64).sqrt())
    }
}

impl MutationSpec {
    /// Checks the table; keys start with `evolution.mutation.`.
    pub fn validate(&self) -> Valid {
        probability("evolution.mutation.probability", self.probability)?;
        magnitude("evolution.mutation.sigma", self.sigma)?;
        if let Some(adaptation) = &self.self_adaptive {
            if let Some(tau) = adaptation.tau {
                non_negative("evolution.mutation.tau", tau)?;
            }
            let key = "evolution.mutation.min_sigma";
            non_negative(key, adaptation.min_sigma)?;
            if adaptation.min_sigma > self.sigma {
                return Err(InvalidValue::new(
                    key,
                    format!(
                        "must be at most sigma ({}), the initial step size, got {}",
                        self.sigma, adaptation.min_sigma
                    ),
                ));
            }
        }
        Ok(())
    }
}

/// `[evolution.mutation]` as written.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
struct RawMutation {
    /// Chance that each gene of an offspring is mutated (default: 0.1).
    probability: f64,
    /// Standard deviation of the Gaussian added to a mutated gene, in parameter units; with
    /// self-adaptation, the initial step size (default: 0.1).
    sigma: f64,
    /// Each genome carries its own step size σ, mutated log-normally before its genes,
    /// σ' = σ · exp(τ · N(0, 1)) (default: false).
    self_adaptive: bool,
    /// Self-adaptive only: learning rate τ of the step size (default: absent = 1/√n for n
    /// genes).
    #[serde(skip_serializing_if = "Option::is_none")]
    tau: Option<f64>,
    /// Self-adaptive only: the smallest step size, so that it cannot collapse to 0
    /// (default: 10^-6).
    #[serde(skip_serializing_if = "Option::is_none")]
    min_sigma: Option<f64>,
}

impl Default for RawMutation {
    fn default() -> Self {
        MutationSpec::default().into()
    }
}

impl TryFrom<RawMutation> for MutationSpec {
    type Error = String;

    fn try_from(raw: RawMutation) -> Result<Self, String> {
        let self_adaptive = if raw.self_adaptive {
            Some(SelfAdaptation {
                tau: raw.tau,
                min_sigma: raw.min_sigma.unwrap_or(DEFAULT_MIN_SIGMA),
            })
        } else {
            for (present, key) in [
                (raw.tau.is_some(), "tau"),
                (raw.min_sigma.is_some(), "min_sigma"),
            ] {
                if present {
                    return Err(unused_key(
                        &format!("evolution.mutation.{key}"),
                        "self_adaptive = true",
                        "self_adaptive = false",
                    ));
                }
            }
            None
        };
        Ok(MutationSpec {
            probability: raw.probability,
            sigma: raw.sigma,
            self_adaptive,
        })
    }
}

impl From<MutationSpec> for RawMutation {
    fn from(spec: MutationSpec) -> Self {
        RawMutation {
            probability: spec.probability,
            sigma: spec.sigma,
            self_adaptive: spec.self_adaptive.is_some(),
            tau: spec.self_adaptive.and_then(|a| a.tau),
            min_sigma: spec.self_adaptive.map(|a| a.min_sigma),
        }
    }
}

/// `[evolution.novelty]`: novelty search (Lehman & Stanley 2011). The GA's selection,
/// crossover, mutation and elitism (the `[evolution]` keys) act on a score instead of the
/// fitness: novelty, the mean Euclidean distance of an individual's behaviour to its `k`
/// nearest neighbours among the rest of its generation and an archive of past behaviours.
/// A behaviour is the individual's `[behaviour]` measures named by `descriptors`, each scaled
/// from [min, max] to [0, 1] (values outside are clamped). With `fitness_weight` w the score
/// is (1 − w) · novelty's rank + w · fitness's rank, each rank scaled to [0, 1].
///
/// ```toml
/// [behaviour]
/// measures = ["distinct_food", "food_types"]
///
/// [evolution]
/// algorithm = "novelty"
///
/// [evolution.novelty]
/// descriptors = [
///     { measure = "distinct_food", min = 0, max = 20 },
///     { measure = "food_types", min = 0, max = 4 },
/// ]
/// k = 15                        # neighbours
/// archive_probability = 0.1     # or archive_threshold = 0.05
/// archive_size = 500            # the oldest entry leaves when full
/// fitness_weight = 0.0
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct NoveltySpec {
    /// `descriptors`: the behaviour space, one `{ measure, min, max }` per dimension
    /// (required with novelty; each a `[behaviour]` measure, or `time_in_area` with an `area`
    /// of its own; at most once).
    pub descriptors: Vec<DescriptorSpec>,
    /// `k`: how many nearest neighbours novelty averages over (default: 15; at least 1, at
    /// most population − 1 + archive_size, the most neighbours an individual can have).
    pub k: usize,
    /// `archive_threshold`: an individual enters the archive when its novelty is above this
    /// distance (in scaled descriptor units); not with `archive_probability` (default: absent).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub archive_threshold: Option<f64>,
    /// `archive_probability`: each individual enters the archive with this chance (drawn from
    /// the novelty stream of its generation, in index order; default: 0.1 when no
    /// `archive_threshold` is given; 0 to 1).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub archive_probability: Option<f64>,
    /// `archive_size`: the archive's capacity; when full, the oldest entry leaves for each
    /// new one (default: 500; 0 to 100 000).
    pub archive_size: usize,
    /// `fitness_weight`: w in score = (1 − w) · novelty rank + w · fitness rank, ranks
    /// scaled to [0, 1] (default: 0, pure novelty; 0 to 1).
    pub fitness_weight: f64,
}

/// The largest novelty archive accepted (every individual is compared with every entry).
pub const MAX_NOVELTY_ARCHIVE: usize = 100_000;

/// `archive_probability` when neither it nor `archive_threshold` is given.
pub const DEFAULT_ARCHIVE_PROBABILITY: f64 = 0.1;

/// One dimension of a behaviour space: a `[behaviour]` measure and the range mapped to [0, 1].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct DescriptorSpec {
    /// `measure`: the `[behaviour]` measure, by name (e.g. `"distinct_food"`).
    pub measure: Measure,
    /// `min`: the measure's value mapped to 0 (below: clamped).
    pub min: f64,
    /// `max`: the measure's value mapped to 1 (above: clamped); greater than `min`.
    pub max: f64,
    /// `area`: with `measure = "time_in_area"` only, the `[[world.areas]]` entry (by `name`)
    /// whose time this dimension counts: the ticks alive the creature's centre spent inside
    /// it, mean over the trials, independent of `[behaviour] area`; such a descriptor need
    /// not be in `[behaviour] measures` (its value is its own). At most 3 descriptors name
    /// an area (default: none: the measure of `[behaviour]`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub area: Option<String>,
}

impl DescriptorSpec {
    /// The dimension's name in outputs: the measure's (`time_in_area`), or with an area
    /// `time_in_area:nest`.
    pub fn label(&self) -> String {
        descriptor_label(self.measure, self.area.as_deref())
    }
}

/// A descriptor's name in outputs: `measure`, or `measure:area` for an area's own.
fn descriptor_label(measure: Measure, area: Option<&str>) -> String {
    match area {
        Some(a) => format!("{}:{a}", measure.name()),
        None => measure.name().to_string(),
    }
}

/// The most descriptors that name an `area` (each one counts its ticks in every trial).
pub const MAX_DESCRIBED_AREAS: usize = 3;

/// The areas a search's descriptors name (`area = "..."`), as indices into `[[world.areas]]`
/// in descriptor order: what every trial counts the ticks in. Empty for every search that
/// names none, and then no trial counts anything more.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct DescribedAreas {
    at: [usize; MAX_DESCRIBED_AREAS],
    len: usize,
}

impl DescribedAreas {
    /// The areas' indices into `[[world.areas]]`, in descriptor order.
    pub fn indices(&self) -> &[usize] {
        &self.at[..self.len]
    }

    /// How many areas.
    pub fn len(&self) -> usize {
        self.len
    }

    /// True without areas.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }
}

impl Default for NoveltySpec {
    fn default() -> Self {
        NoveltySpec {
            descriptors: Vec::new(),
            k: 15,
            archive_threshold: None,
            archive_probability: None,
            archive_size: 500,
            fitness_weight: 0.0,
        }
    }
}

impl NoveltySpec {
    /// Checks the table for a population of `population`; keys start with
    /// `evolution.novelty.` (the descriptors' measures are checked against `[behaviour]` by
    /// [`EvolutionSpec::validate_descriptors`]).
    pub fn validate(&self, population: usize) -> Valid {
        let key = "evolution.novelty.descriptors";
        if self.descriptors.is_empty() {
            return Err(InvalidValue::new(
                key,
                "novelty search needs at least one descriptor, e.g. \
                 descriptors = [{ measure = \"distinct_food\", min = 0, max = 20 }] \
                 (a measure of [behaviour] measures)",
            ));
        }
        for (i, d) in self.descriptors.iter().enumerate() {
            let name = d.label();
            if !(d.min.is_finite() && d.max.is_finite()) || d.min >= d.max {
                return Err(InvalidValue::new(
                    key,
                    format!(
                        "the range of `{name}` must have min < max (both finite), got min = {} and max = {}",
                        d.min, d.max
                    ),
                ));
            }
            if self.descriptors[..i]
                .iter()
                .any(|e| e.measure == d.measure && e.area == d.area)
            {
                return Err(InvalidValue::new(key, format!("names `{name}` twice")));
            }
        }
        count_within(
            "evolution.novelty.archive_size",
            self.archive_size as u64,
            0,
            MAX_NOVELTY_ARCHIVE as u64,
            "limit: every individual is compared with every entry",
        )?;
        let pool = population - 1 + self.archive_size;
        if self.k == 0 || self.k > pool {
            return Err(InvalidValue::new(
                "evolution.novelty.k",
                format!(
                    "must be from 1 to the most neighbours an individual can have, population − 1 + \
                     archive_size = {} − 1 + {} = {pool}, got {}",
                    population, self.archive_size, self.k
                ),
            ));
        }
        match (self.archive_threshold, self.archive_probability) {
            (Some(_), Some(_)) => {
                return Err(InvalidValue::new(
                    "evolution.novelty.archive_probability",
                    "cannot be given with archive_threshold: an individual enters the archive \
                     either by chance or by its novelty; remove one",
                ))
            }
            (Some(t), None) => non_negative("evolution.novelty.archive_threshold", t)?,
            (None, Some(p)) => probability("evolution.novelty.archive_probability", p)?,
            (None, None) => {}
        }
        within(
            "evolution.novelty.fitness_weight",
            self.fitness_weight,
            0.0,
            1.0,
        )
    }
}

/// `[evolution.map_elites]`: MAP-Elites (Mouret & Clune 2015) with a grid archive. Each
/// descriptor (a `[behaviour]` measure) splits its [min, max] into `bins` equal cells (values
/// outside are clamped to the first or last); the archive keeps, per cell, the genome of the
/// highest fitness seen there. Each generation (`[evolution] population` genomes: the batch
/// size) is random while the archive holds fewer than `initial_random` elites (generation 0
/// always), and otherwise made by an emitter from elites drawn uniformly from the archive.
///
/// ```toml
/// [behaviour]
/// measures = ["distinct_food", "food_types"]
///
/// [evolution]
/// algorithm = "map-elites"
/// population = 64               # the batch: genomes evaluated per generation
///
/// [evolution.map_elites]
/// descriptors = [
///     { measure = "distinct_food", min = 0, max = 20, bins = 20 },
///     { measure = "food_types", min = 0, max = 4, bins = 5 },
/// ]
/// initial_random = 1            # random generations until the archive holds this many
/// emitter = "iso-line"          # or "gaussian" (then sigma, not iso_sigma/line_sigma)
/// iso_sigma = 0.02
/// line_sigma = 0.2
/// qd_offset = 0.0               # QD score = sum over elites of (fitness − qd_offset)
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct MapElitesSpec {
    /// `descriptors`: the grid, one `{ measure, min, max, bins }` per dimension (1 to 3,
    /// required; each a `[behaviour]` measure, or `time_in_area` with an `area` of its own; at
    /// most once; at most 100,000 cells in all).
    pub descriptors: Vec<GridDescriptorSpec>,
    /// `initial_random`: generations are random genomes (drawn as the GA's generation 0,
    /// uniform in ±`init_range`) while the archive holds fewer elites than this; generation 0
    /// always is (default: 1; at least 1, at most the grid's cells).
    pub initial_random: usize,
    /// `emitter`: how an offspring is made from elites: `"iso-line"` (Vassiliades & Mouret
    /// 2018, default) or `"gaussian"`.
    pub emitter: Emitter,
    /// `sigma`: the Gaussian emitter's x' = x + sigma · N(0, I) (default: 0.1, the GA's
    /// mutation sigma; only with `emitter = "gaussian"`; 0 to 10^6).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sigma: Option<f64>,
    /// `iso_sigma`: the iso-line emitter's isotropic noise σ_iso in
    /// x' = x_i + σ_iso · N(0, I) + σ_line · N(0, 1) · (x_j − x_i) (default: 0.02, the paper's
    /// 0.01 for genes in [0, 1] scaled to genes in [−1, 1]; only with `emitter = "iso-line"`;
    /// 0 to 10^6).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub iso_sigma: Option<f64>,
    /// `line_sigma`: the iso-line emitter's σ_line, a fraction of the distance between the two
    /// elites (default: 0.2, the paper's; only with `emitter = "iso-line"`; 0 to 10^6).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub line_sigma: Option<f64>,
    /// `qd_offset`: the QD score is the sum over elites of (fitness − qd_offset), as pyribs'
    /// `qd_offset`; set it at or below the lowest fitness the experiment can give so that
    /// every elite adds to the score (default: 0; finite).
    pub qd_offset: f64,
}

/// One dimension of a grid archive: a `[behaviour]` measure, its range and its cells.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct GridDescriptorSpec {
    /// `measure`: the `[behaviour]` measure, by name (e.g. `"distinct_food"`).
    pub measure: Measure,
    /// `min`: the low end of the first cell (values below fall in it).
    pub min: f64,
    /// `max`: the high end of the last cell (values above fall in it); greater than `min`.
    pub max: f64,
    /// `bins`: how many equal cells [min, max] is split into (at least 1).
    pub bins: usize,
    /// `area`: with `measure = "time_in_area"` only, the `[[world.areas]]` entry (by `name`)
    /// whose time this dimension counts: the ticks alive the creature's centre spent inside
    /// it, mean over the trials, independent of `[behaviour] area`; such a descriptor need
    /// not be in `[behaviour] measures` (its value is its own). At most 3 descriptors name
    /// an area; archive.csv names the column `time_in_area:<area>` (default: none: the
    /// measure of `[behaviour]`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub area: Option<String>,
}

impl GridDescriptorSpec {
    /// The dimension as a behaviour space's descriptor (its range, without the bins).
    pub fn descriptor(&self) -> DescriptorSpec {
        DescriptorSpec {
            measure: self.measure,
            min: self.min,
            max: self.max,
            area: self.area.clone(),
        }
    }

    /// The dimension's name in outputs: the measure's, or `time_in_area:<area>`.
    pub fn label(&self) -> String {
        descriptor_label(self.measure, self.area.as_deref())
    }
}

/// How MAP-Elites makes an offspring from the archive's elites.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
pub enum Emitter {
    /// x' = x_i + σ_iso · N(0, I) + σ_line · N(0, 1) · (x_j − x_i), two elites drawn
    /// uniformly (Vassiliades & Mouret 2018).
    #[default]
    #[serde(rename = "iso-line")]
    IsoLine,
    /// x' = x + σ · N(0, I), one elite drawn uniformly.
    #[serde(rename = "gaussian")]
    Gaussian,
}

/// The most cells a grid archive may have (the product of the descriptors' bins): every
/// cell's elite holds a genome in memory and in every checkpoint.
pub const MAX_GRID_CELLS: usize = 100_000;

/// The most descriptors (grid dimensions) MAP-Elites accepts: what `plot` can draw.
pub const MAX_GRID_DIMENSIONS: usize = 3;

/// The Gaussian emitter's `sigma` when not given (the GA's mutation sigma).
pub const DEFAULT_GAUSSIAN_SIGMA: f64 = 0.1;

/// The iso-line emitter's `iso_sigma` when not given: Vassiliades & Mouret's 0.01 for genes
/// in [0, 1], scaled by 2 to the default initial genes in [−1, 1].
pub const DEFAULT_ISO_SIGMA: f64 = 0.02;

/// The iso-line emitter's `line_sigma` when not given (Vassiliades & Mouret's; a fraction of
/// the distance between two elites, so it needs no scaling).
pub const DEFAULT_LINE_SIGMA: f64 = 0.2;

impl Default for MapElitesSpec {
    fn default() -> Self {
        MapElitesSpec {
            descriptors: Vec::new(),
            initial_random: 1,
            emitter: Emitter::IsoLine,
            sigma: None,
            iso_sigma: None,
            line_sigma: None,
            qd_offset: 0.0,
        }
    }
}

impl MapElitesSpec {
    /// The grid's cells: the product of the descriptors' bins (saturating, so that a grid
    /// far over the limit still reads as over it).
    pub fn cells(&self) -> usize {
        self.descriptors
            .iter()
            .fold(1usize, |n, d| n.saturating_mul(d.bins))
    }

    /// The Gaussian emitter's sigma (given or default).
    pub fn gaussian_sigma(&self) -> f64 {
        self.sigma.unwrap_or(DEFAULT_GAUSSIAN_SIGMA)
    }

    /// The iso-line emitter's (σ_iso, σ_line) (given or default).
    pub fn iso_line_sigmas(&self) -> (f64, f64) {
        (
            self.iso_sigma.unwrap_or(DEFAULT_ISO_SIGMA),
            self.line_sigma.unwrap_or(DEFAULT_LINE_SIGMA),
        )
    }

    /// Checks the table; keys start with `evolution.map_elites.` (the descriptors' measures
    /// are checked against `[behaviour]` by [`EvolutionSpec::validate_descriptors`]).
    pub fn validate(&self) -> Valid {
        let key = "evolution.map_elites.descriptors";
        if self.descriptors.is_empty() {
            return Err(InvalidValue::new(
                key,
                "map-elites needs at least one descriptor, e.g. descriptors = \
                 [{ measure = \"distinct_food\", min = 0, max = 20, bins = 20 }] \
                 (a measure of [behaviour] measures)",
            ));
        }
        if self.descriptors.len() > MAX_GRID_DIMENSIONS {
            return Err(InvalidValue::new(
                key,
                format!(
                    "a grid archive has 1 to {MAX_GRID_DIMENSIONS} dimensions (limit: what plot \
                     draws as a heat map), got {}; describe behaviour by fewer measures",
                    self.descriptors.len()
                ),
            ));
        }
        for (i, d) in self.descriptors.iter().enumerate() {
            let name = d.label();
            if !(d.min.is_finite() && d.max.is_finite()) || d.min >= d.max {
                return Err(InvalidValue::new(
                    key,
                    format!(
                        "the range of `{name}` must have min < max (both finite), got min = {} and max = {}",
                        d.min, d.max
                    ),
                ));
            }
            if d.bins == 0 {
                return Err(InvalidValue::new(
                    key,
                    format!("`{name}` must have bins of at least 1, got bins = 0"),
                ));
            }
            if self.descriptors[..i]
                .iter()
                .any(|e| e.measure == d.measure && e.area == d.area)
            {
                return Err(InvalidValue::new(key, format!("names `{name}` twice")));
            }
        }
        let cells = self.cells();
        if cells > MAX_GRID_CELLS {
            let bins: Vec<String> = self
                .descriptors
                .iter()
                .map(|d| d.bins.to_string())
                .collect();
            return Err(InvalidValue::new(
                key,
                format!(
                    "the grid has {} cells (bins {}), more than the limit of {MAX_GRID_CELLS} \
                     (limit: every cell's elite is a genome kept in memory and in every \
                     checkpoint); use fewer bins",
                    if cells == usize::MAX {
                        "too many".to_string()
                    } else {
                        cells.to_string()
                    },
                    bins.join(" × ")
                ),
            ));
        }
        if self.initial_random == 0 || self.initial_random > cells {
            return Err(InvalidValue::new(
                "evolution.map_elites.initial_random",
                format!(
                    "must be from 1 to the grid's {cells} cells (random generations until the \
                     archive holds this many elites), got {}",
                    self.initial_random
                ),
            ));
        }
        match self.emitter {
            Emitter::Gaussian => {
                for (given, k) in [
                    (self.iso_sigma.is_some(), "iso_sigma"),
                    (self.line_sigma.is_some(), "line_sigma"),
                ] {
                    if given {
                        return Err(InvalidValue::new(
                            format!("evolution.map_elites.{k}"),
                            "is only used with emitter = \"iso-line\", but this table has \
                             emitter = \"gaussian\" (which uses sigma); remove it",
                        ));
                    }
                }
                magnitude("evolution.map_elites.sigma", self.gaussian_sigma())?;
            }
            Emitter::IsoLine => {
                if self.sigma.is_some() {
                    return Err(InvalidValue::new(
                        "evolution.map_elites.sigma",
                        "is only used with emitter = \"gaussian\", but this table has emitter = \
                         \"iso-line\" (which uses iso_sigma and line_sigma); remove it",
                    ));
                }
                let (iso, line) = self.iso_line_sigmas();
                magnitude("evolution.map_elites.iso_sigma", iso)?;
                magnitude("evolution.map_elites.line_sigma", line)?;
            }
        }
        crate::validate::finite("evolution.map_elites.qd_offset", self.qd_offset)
    }
}
