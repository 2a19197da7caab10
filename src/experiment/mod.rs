//! Experiments: one TOML file describes a whole run (world, creature, brain, evolution,
//! evaluation, fitness, output). This module parses it strictly into the raw
//! [`ExperimentConfig`], validates that into an [`Experiment`], and gives the effective
//! experiment a stable hash that checkpoints and genome files carry.
//!
//! An [`Experiment`] exists only validated: [`Experiment::load`], [`Experiment::from_toml`] and
//! `Experiment::try_from(config)` validate, and a command-line override goes through
//! [`Experiment::with_overrides`], whose [`Overrides::build`] validates the changed experiment
//! again. Its fields are read through [`std::ops::Deref`] to the configuration (there is no
//! `DerefMut`), so the hundreds of places that read `experiment.evaluation.ticks` read it as
//! before while none can assign it.

pub mod diff;
pub mod evolution;
pub mod plain;
pub mod reference;
pub mod tables;
pub mod templates;
pub mod terms;
pub mod tiled;

pub use evolution::{
    Algorithm, CmaEsSpec, CrossoverSpec, EvolutionSpec, MutationSpec, PgpeSpec, SelectionSpec,
    SelfAdaptation,
};

pub use tables::{
    Aggregate, Balance, BehaviourSpec, EvaluationSpec, FitnessMode, FitnessSpec, GoalAt, Measure,
    OutputSpec, SwitchSpec, SwitchStart, ValidationSpec, MEASURES,
};

use crate::brain::output_count;
use crate::brain::spec::{BrainSpec, Topology};
use crate::brain::SignalInputs;
use crate::seed::Seed;
use crate::sim::controller::ObservationLayout;
use crate::sim::scripted::DemoSpec;
use crate::sim::spec::{CreatureSpec, WorldSpec};
use crate::validate::{InvalidValue, Valid};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};
use std::path::{Path, PathBuf};
use thiserror::Error;

/// The largest seed accepted: TOML integers are signed 64-bit.
pub const MAX_SEED: u64 = i64::MAX as u64;

/// The longest experiment name: it names the run folder, and file systems allow 255 bytes
/// for a name (seed replicates and temporary files add to it).
pub const MAX_NAME_BYTES: usize = 100;

/// The most network parameters a generation may hold in total (population × parameters per
/// genome): 8 bytes each, and two generations are in memory at once, so at most 4 GB. Each
/// limit alone (population, units per layer, layers) still allows petabytes together.
pub const MAX_GENERATION_PARAMETERS: u64 = 250_000_000;

/// A whole experiment, exactly as its TOML file says (after defaults), not yet validated.
/// Unknown keys anywhere are errors, so a misspelt option can never be silently ignored.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ExperimentConfig {
    /// Name of the experiment; names the run folder `results/<name>/seed-<seed>/`.
    pub name: String,
    /// Master seed: every random draw of the run derives from it (0 ≤ seed < 2^63).
    pub seed: u64,
    /// The world of every trial (`[world]`).
    #[serde(default)]
    pub world: WorldSpec,
    /// The evolving creatures' body and senses (`[creature]`).
    #[serde(default)]
    pub creature: CreatureSpec,
    /// The controller network (`[brain]`).
    #[serde(default)]
    pub brain: BrainSpec,
    /// The genetic algorithm (`[evolution]`).
    #[serde(default)]
    pub evolution: EvolutionSpec,
    /// How an individual is evaluated (`[evaluation]`).
    #[serde(default)]
    pub evaluation: EvaluationSpec,
    /// How a life is scored (`[fitness]`).
    #[serde(default)]
    pub fitness: FitnessSpec,
    /// Behaviour measures reported next to fitness (`[behaviour]`; default: none).
    #[serde(default, skip_serializing_if = "BehaviourSpec::is_default")]
    pub behaviour: BehaviourSpec,
    /// Champions chosen on validation worlds (`[validation]`; default: off).
    #[serde(default, skip_serializing_if = "ValidationSpec::is_default")]
    pub validation: ValidationSpec,
    /// Checkpointing and run folders (`[output]`).
    #[serde(default)]
    pub output: OutputSpec,
    /// Scripted creatures for `berry-evolve simulate` (`[demo]`); unused by evolution.
    #[serde(default)]
    pub demo: DemoSpec,
}

/// A validated experiment: every table checked, and the constraints between tables. The only
/// ways to get one validate ([`Experiment::load`], [`Experiment::from_toml`],
/// `Experiment::try_from(config)`, [`Overrides::build`]); fields are read through `Deref`.
#[derive(Debug, Clone, PartialEq)]
pub struct Experiment {
    config: ExperimentConfig,
}

impl TryFrom<ExperimentConfig> for Experiment {
    type Error = InvalidValue;

    /// Validates `config` ([`ExperimentConfig::validate`]).
    fn try_from(config: ExperimentConfig) -> Result<Experiment, InvalidValue> {
        config.validate()?;
        Ok(Experiment { config })
    }
}

impl std::ops::Deref for Experiment {
    type Target = ExperimentConfig;

    fn deref(&self) -> &ExperimentConfig {
        &self.config
    }
}

/// A changed copy of an experiment on its way to validation: the command-line overrides
/// (`--seed`, `--generations`, `--trials`, common random numbers, a shorter life), each a
/// plain assignment, then [`Overrides::build`] checks the whole experiment again.
#[derive(Debug, Clone)]
#[must_use = "an override takes effect only through build()"]
pub struct Overrides {
    config: ExperimentConfig,
}

impl Overrides {
    /// The master seed.
    pub fn seed(mut self, seed: u64) -> Overrides {
        self.config.seed = seed;
        self
    }

    /// How many generations to run (`evolution.generations`).
    pub fn generations(mut self, generations: u64) -> Overrides {
        self.config.evolution.generations = generations;
        self
    }

    /// Trials per individual (`evaluation.trials`).
    pub fn trials(mut self, trials: u64) -> Overrides {
        self.config.evaluation.trials = trials;
        self
    }

    /// Ticks per trial (`evaluation.ticks`).
    pub fn ticks(mut self, ticks: u64) -> Overrides {
        self.config.evaluation.ticks = ticks;
        self
    }

    /// Whether every group of a generation lives the same trial worlds
    /// (`evaluation.common_random_numbers`).
    pub fn common_random_numbers(mut self, on: bool) -> Overrides {
        self.config.evaluation.common_random_numbers = on;
        self
    }

    /// Where and how often results are saved (`[output]`).
    pub fn output(mut self, output: OutputSpec) -> Overrides {
        self.config.output = output;
        self
    }

    /// Any other change (tests, a tool that varies one table): `change` edits the
    /// configuration, [`Overrides::build`] validates it like the rest.
    pub fn edit(mut self, change: impl FnOnce(&mut ExperimentConfig)) -> Overrides {
        change(&mut self.config);
        self
    }

    /// The overridden experiment, validated again; the error names the key and the reason,
    /// as for a file.
    pub fn build(self) -> Result<Experiment, InvalidValue> {
        Experiment::try_from(self.config)
    }
}

/// Why an experiment file could not be used. Every variant names the file.
#[derive(Debug, Error)]
pub enum ExperimentError {
    /// The file could not be read.
    #[error("cannot read experiment file {path}: {error}")]
    Read {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        error: std::io::Error,
    },
    /// The file is not valid TOML or does not have the experiment's shape (unknown key,
    /// wrong type, missing key), in plain words ([`plain`]): the key, the line, what is
    /// wrong, and toml's picture of the offending text.
    #[error("{}", parse_message(.path, .error))]
    Parse {
        /// The file.
        path: PathBuf,
        /// The key, the line and the plain message.
        error: plain::PlainError,
    },
    /// A value is well-formed but not acceptable.
    #[error("{path}: {error}")]
    Invalid {
        /// The file.
        path: PathBuf,
        /// The key and the reason.
        error: InvalidValue,
    },
}

/// The JSON Schema `schemars` derives from [`ExperimentConfig`] (draft-07, which taplo and
/// Even Better TOML read), as [`reference::schema`] starts from.
pub fn derived_schema() -> serde_json::Value {
    let generator = schemars::generate::SchemaSettings::draft07().into_generator();
    let schema = generator.into_root_schema_for::<ExperimentConfig>();
    serde_json::to_value(schema).expect("a schema is plain JSON")
}

/// "`evolution.population` in x.toml line 12: expected ..., found ...", then toml's picture.
fn parse_message(path: &Path, error: &plain::PlainError) -> String {
    let mut text = String::new();
    if let Some(key) = &error.key {
        text.push_str(&format!("`{}` in ", crate::input::cut(key, 200)));
    }
    text.push_str(&path.display().to_string());
    if let Some(line) = error.line {
        text.push_str(&format!(" line {line}"));
    }
    text.push_str(&format!(": {}", crate::input::cut(&error.message, 2000)));
    if !error.excerpt.is_empty() {
        text.push('\n');
        text.push_str(&error.excerpt);
    }
    text
}

impl Experiment {
    /// Reads and validates an experiment file.
    pub fn load(path: &Path) -> Result<Experiment, ExperimentError> {
        let text = crate::input::read_regular_text(path, crate::input::MAX_EXPERIMENT_BYTES)
            .map_err(|error| ExperimentError::Read {
                path: path.to_path_buf(),
                error,
            })?;
        Experiment::from_toml(&text, path)
    }

    /// Parses and validates experiment text; `origin` only names the error in errors.
    pub fn from_toml(text: &str, origin: &Path) -> Result<Experiment, ExperimentError> {
        // Parsing costs about 75 bytes of memory per byte of TOML, so an absurd world is
        // refused before it is parsed: every wall (and gadget) has a `from` key, so counting
        // the word bounds their number from above (comments only add a few).
        let froms = text.matches("from").count() as u64;
        let most = crate::sim::spec::MAX_WALLS + crate::sim::spec::MAX_ACTORS + 1000;
        if froms > most {
            return Err(ExperimentError::Invalid {
                path: origin.to_path_buf(),
                error: InvalidValue::new(
                    "world.walls",
                    format!(
                        "the file holds {froms} `from` keys, more walls than the limit of {} \
                         (the largest world this simulator supports); refused before parsing",
                        crate::sim::spec::MAX_WALLS
                    ),
                ),
            });
        }
        // A list where a table belongs is named first: serde would read it by position (and
        // then either accept it silently or complain about one of its elements).
        let parsed = toml::from_str::<ExperimentConfig>(text);
        if let Some((key, span)) = reference::tree::list_for_table(text, &derived_schema()) {
            return Err(ExperimentError::Parse {
                path: origin.to_path_buf(),
                error: plain::list_for_table_error(key, span, text),
            });
        }
        let config = parsed.map_err(|e| ExperimentError::Parse {
            path: origin.to_path_buf(),
            error: plain::plain_error(&e, text),
        })?;
        Experiment::try_from(config).map_err(|error| ExperimentError::Invalid {
            path: origin.to_path_buf(),
            error,
        })
    }

    /// The experiment's configuration (also reachable field by field through `Deref`).
    pub fn config(&self) -> &ExperimentConfig {
        &self.config
    }

    /// The configuration, for a caller that changes it and validates it again.
    pub fn into_config(self) -> ExperimentConfig {
        self.config
    }

    /// A builder for a changed copy of this experiment (command-line overrides), validated
    /// again by [`Overrides::build`].
    pub fn with_overrides(&self) -> Overrides {
        Overrides {
            config: self.config.clone(),
        }
    }
}

impl ExperimentConfig {
    /// Checks every table and the constraints between tables.
    pub fn validate(&self) -> Valid {
        if self.name.trim().is_empty() {
            return Err(InvalidValue::new("name", "must not be empty"));
        }
        if self.name.chars().all(|c| c == '.') {
            return Err(InvalidValue::new(
                "name",
                format!(
                    "`{}` is not a plain folder name (it names the run folder results/<name>/); \
                     use letters, digits, '-', '_' and '.', not only dots",
                    crate::input::cut(&self.name, 40)
                ),
            ));
        }
        if self
            .name
            .chars()
            .any(|c| !(c.is_ascii_alphanumeric() || c == '-' || c == '_' || c == '.'))
        {
            return Err(InvalidValue::new(
                "name",
                "may hold only letters, digits, '-', '_' and '.' (it names the run folder)",
            ));
        }
        if self.name.len() > MAX_NAME_BYTES {
            return Err(InvalidValue::new(
                "name",
                format!(
                    "is {} characters long; at most {MAX_NAME_BYTES} (it names the run folder \
                     results/<name>/, and seed replicates add to it): choose a shorter name",
                    self.name.chars().count()
                ),
            ));
        }
        if self.seed > MAX_SEED {
            return Err(InvalidValue::new(
                "seed",
                format!("must be below 2^63, got {}", self.seed),
            ));
        }
        self.creature.validate()?;
        self.world.validate(&self.creature)?;
        self.brain.validate()?;
        // A modulator must read a sensor the creature has (`brain.modulators`).
        self.topology().check_signals()?;
        self.evolution.validate()?;
        self.evaluation.validate()?;
        if let Some(switch) = &self.evaluation.switch {
            switch.validate(
                &self.world,
                &self.fitness.weights,
                self.evaluation.episodes_per_life,
            )?;
        }
        if self.evaluation.switch.is_none() {
            if let Some(m) = self.behaviour.measures.iter().find(|m| m.needs_switch()) {
                return Err(InvalidValue::new(
                    "behaviour.measures",
                    format!(
                        "`{}` needs [evaluation.switch] (which two kinds' payoffs are \
                         exchanged): add the table or remove the measure",
                        m.name()
                    ),
                ));
            }
            if let Some(term) = self.fitness.term_following(terms::Follows::Choices) {
                return Err(InvalidValue::new(
                    format!("fitness.{}", term.key),
                    "counts choices between the [evaluation.switch] kinds, but there is no \
                     switch: add the table or set the weight to 0",
                ));
            }
        }
        self.fitness.validate()?;
        self.fitness.validate_against_world(&self.world)?;
        self.behaviour.validate(&self.world)?;
        self.evolution
            .validate_descriptors(&self.behaviour.measures, &self.world)?;
        self.validation.validate()?;
        self.output.validate()?;
        // PGPE evaluates its centre as one more individual: groups must divide that count.
        self.evaluation
            .validate_against_population(self.evolution.evaluated_per_generation())?;
        let parameters = self.topology().parameter_count() as u64;
        self.evolution.validate_against_parameters(parameters)?;
        let total = parameters.saturating_mul(self.evolution.population as u64);
        if total > MAX_GENERATION_PARAMETERS {
            return Err(InvalidValue::new(
                "brain.hidden",
                format!(
                    "population × brain parameters must be at most {MAX_GENERATION_PARAMETERS} \
                     (limit: memory for two generations of genomes), got {} × {parameters} = \
                     {total}; use fewer or smaller hidden layers or a smaller \
                     evolution.population",
                    self.evolution.population
                ),
            ));
        }
        Ok(())
    }

    /// The master seed as a typed value.
    pub fn seed(&self) -> Seed {
        Seed(self.seed)
    }

    /// The observation layout the creature's senses produce.
    pub fn layout(&self) -> ObservationLayout {
        self.creature.layout(&self.world)
    }

    /// The names of the brain's outputs, in order.
    pub fn output_names(&self) -> Vec<String> {
        let mut names = vec!["motor_left".to_string(), "motor_right".to_string()];
        if self.creature.eats_by_action() {
            names.push("eat".to_string());
        }
        names
    }

    /// The network topology: the brain table plus the sizes the creature implies.
    pub fn topology(&self) -> Topology {
        let layout = self.layout();
        Topology {
            spec: self.brain.clone(),
            inputs: layout.len(),
            outputs: output_count(self.creature.eats_by_action()),
            signals: SignalInputs::from_layout(&layout),
        }
    }

    /// The experiment as TOML, as written to a run folder's `experiment.toml`.
    pub fn to_toml(&self) -> String {
        // Serialising plain data structures to TOML cannot fail: every field is a table,
        // an array or a scalar.
        toml::to_string(self).expect("experiment serialises to TOML")
    }

    /// A stable SHA-256 hash (hex) of everything that decides what a run computes.
    ///
    /// Excluded: `evolution.generations` (how long to run, not what is run, so a finished
    /// run can be extended with `resume --generations`) and `[output]` (where and how often
    /// results are saved). The canonical form is the JSON of the experiment with sorted keys.
    pub fn config_hash(&self) -> String {
        let bytes = serde_json::to_vec(&self.identity()).expect("JSON value serialises");
        let digest = Sha256::digest(&bytes);
        digest.iter().map(|b| format!("{b:02x}")).collect()
    }

    /// What [`ExperimentConfig::config_hash`] hashes: the configuration as JSON, without the
    /// run length and the output settings.
    pub fn identity(&self) -> serde_json::Value {
        let mut identity = self.clone();
        identity.evolution.generations = 0;
        identity.output = OutputSpec::default();
        serde_json::to_value(&identity).expect("experiment serialises to JSON")
    }

    /// The run folder used when `--out` is not given.
    pub fn default_run_dir(&self) -> PathBuf {
        PathBuf::from("results")
            .join(&self.name)
            .join(format!("seed-{}", self.seed))
    }
}
