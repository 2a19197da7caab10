//! Genome files (JSON): a genome with the brain it encodes, the observation layout it
//! expects, and where it came from, so it can be replayed or compared later.

use crate::brain::genome::Genome;
use crate::brain::spec::{BrainSpec, Topology};
use crate::experiment::Experiment;
use crate::record::atomic::write_atomic;
use crate::sim::metabolism::Metabolism;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use thiserror::Error;

/// The genome file format this program writes and reads.
pub const GENOME_FORMAT: u32 = 1;

/// Where a genome came from. Evolved champions fill every field; hand-designed genomes
/// usually give only a description.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Origin {
    /// Free text, e.g. "hand-designed Braitenberg forager".
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub description: Option<String>,
    /// Name of the experiment that evolved it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub experiment: Option<String>,
    /// That experiment's config hash.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub config_hash: Option<String>,
    /// The experiment's seed when it was evolved (`replay --seed` reproduces its worlds).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seed: Option<u64>,
    /// The generation it was evaluated in.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub generation: Option<u64>,
    /// Its index in that generation.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub individual: Option<u64>,
    /// Its fitness there.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fitness: Option<f64>,
    /// Its mean final metabolic vector there.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub metabolism: Option<Metabolism>,
}

impl Origin {
    /// The origin of an individual evolved by `experiment`: its name, config hash and seed,
    /// and where in the run the individual was evaluated and how it did.
    pub fn evolved(
        experiment: &Experiment,
        generation: u64,
        individual: Option<u64>,
        fitness: Option<f64>,
        metabolism: Option<Metabolism>,
    ) -> Origin {
        Origin {
            description: None,
            experiment: Some(experiment.name.clone()),
            config_hash: Some(experiment.config_hash()),
            seed: Some(experiment.seed),
            generation: Some(generation),
            individual,
            fitness,
            metabolism,
        }
    }
}

/// A genome file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GenomeFile {
    /// File format version ([`GENOME_FORMAT`]).
    pub format: u32,
    /// The brain the parameters belong to.
    pub brain: BrainSpec,
    /// Names of the observation inputs it expects, in order.
    pub inputs: Vec<String>,
    /// Names of its outputs, in order.
    pub outputs: Vec<String>,
    /// The parameters, in the brain's documented order.
    pub parameters: Vec<f64>,
    /// The self-adaptive mutation step size, if the experiment used one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub step_size: Option<f64>,
    /// Provenance.
    pub origin: Origin,
}

/// Why a genome file cannot be read, written or used. Every variant names the file.
#[derive(Debug, Error)]
pub enum GenomeFileError {
    /// Reading or writing failed.
    #[error("{path}: {error}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        error: std::io::Error,
    },
    /// Not a genome file: bad JSON, missing or unknown field.
    #[error("{path}: not a valid genome file: {message}")]
    Parse {
        /// The file.
        path: PathBuf,
        /// serde_json's message with line and column.
        message: String,
    },
    /// A format this program does not read.
    #[error("{path}: genome format {found} is not supported (this program reads format {GENOME_FORMAT})")]
    Format {
        /// The file.
        path: PathBuf,
        /// The format the file says.
        found: u32,
    },
    /// The genome cannot be used with the experiment.
    #[error("{path}: {reason}")]
    Mismatch {
        /// The file.
        path: PathBuf,
        /// What differs.
        reason: String,
    },
}

impl GenomeFile {
    /// A genome file for `genome` as used by `experiment`.
    pub fn new(experiment: &Experiment, genome: &Genome, origin: Origin) -> GenomeFile {
        GenomeFile {
            format: GENOME_FORMAT,
            brain: experiment.brain.clone(),
            inputs: experiment.layout().names().to_vec(),
            outputs: experiment.output_names(),
            parameters: genome.parameters.clone(),
            step_size: genome.step_size,
            origin,
        }
    }

    /// The genome it holds.
    pub fn genome(&self) -> Genome {
        Genome {
            parameters: self.parameters.clone(),
            step_size: self.step_size,
        }
    }

    /// Reads and checks a genome file (format, finite values, parameter count).
    pub fn load(path: &Path) -> Result<GenomeFile, GenomeFileError> {
        let bytes =
            crate::input::read_regular(path, crate::input::MAX_GENOME_BYTES).map_err(|error| {
                GenomeFileError::Io {
                    path: path.to_path_buf(),
                    error,
                }
            })?;
        GenomeFile::from_slice(&bytes, path)
    }

    /// Parses and checks genome file bytes; `origin` only names the error in errors.
    pub fn from_slice(bytes: &[u8], origin: &Path) -> Result<GenomeFile, GenomeFileError> {
        let file: GenomeFile =
            serde_json::from_slice(bytes).map_err(|e| GenomeFileError::Parse {
                path: origin.to_path_buf(),
                message: e.to_string(),
            })?;
        if file.format != GENOME_FORMAT {
            return Err(GenomeFileError::Format {
                path: origin.to_path_buf(),
                found: file.format,
            });
        }
        let mismatch = |reason: String| GenomeFileError::Mismatch {
            path: origin.to_path_buf(),
            reason,
        };
        file.brain
            .validate()
            .map_err(|e| mismatch(format!("invalid brain: {e}")))?;
        let topology = Topology {
            spec: file.brain.clone(),
            inputs: file.inputs.len(),
            outputs: file.outputs.len(),
            signals: Default::default(),
        };
        if topology.parameter_count() != file.parameters.len() {
            return Err(mismatch(format!(
                "the brain needs {} parameters but the file has {}",
                topology.parameter_count(),
                file.parameters.len()
            )));
        }
        if let Some(i) = file.parameters.iter().position(|p| !p.is_finite()) {
            return Err(mismatch(format!("parameters[{i}] is not a finite number")));
        }
        Ok(file)
    }

    /// The topology to decode this genome with inside `experiment`, or why it does not fit:
    /// the experiment must produce exactly the inputs the genome expects and take its outputs.
    pub fn topology_for(
        &self,
        experiment: &Experiment,
        path: &Path,
    ) -> Result<Topology, GenomeFileError> {
        let mismatch = |reason: String| GenomeFileError::Mismatch {
            path: path.to_path_buf(),
            reason,
        };
        let layout = experiment.layout();
        if self.inputs != layout.names() {
            let first = self
                .inputs
                .iter()
                .zip(layout.names())
                .position(|(a, b)| a != b)
                .unwrap_or(self.inputs.len().min(layout.len()));
            return Err(mismatch(format!(
                "the genome expects {} inputs but experiment `{}` gives {} (first difference at input {first}: genome `{}`, experiment `{}`); switch the same [creature.inputs] groups on",
                self.inputs.len(),
                experiment.name,
                layout.len(),
                self.inputs.get(first).map_or("none", String::as_str),
                layout.names().get(first).map_or("none", String::as_str),
            )));
        }
        if self.outputs != experiment.output_names() {
            return Err(mismatch(format!(
                "the genome has outputs {:?} but experiment `{}` needs {:?} (check creature.eating)",
                self.outputs,
                experiment.name,
                experiment.output_names()
            )));
        }
        Ok(Topology {
            spec: self.brain.clone(),
            inputs: self.inputs.len(),
            outputs: self.outputs.len(),
            signals: crate::brain::SignalInputs::from_layout(&layout),
        })
    }

    /// The file as pretty JSON (stable bytes: field order is fixed, floats round-trip).
    pub fn to_json(&self) -> Vec<u8> {
        let mut bytes = serde_json::to_vec_pretty(self).expect("genome file serialises");
        bytes.push(b'\n');
        bytes
    }

    /// The file as one line of compact JSON ending in a newline (a line of a JSON Lines
    /// file such as `champions.jsonl`; the same fields and values as [`GenomeFile::to_json`]).
    pub fn to_json_line(&self) -> Vec<u8> {
        let mut bytes = serde_json::to_vec(self).expect("genome file serialises");
        bytes.push(b'\n');
        bytes
    }

    /// Refuses, naming `path`, a file whose numbers JSON cannot hold (serde_json would write
    /// a NaN or an infinity as `null`, which no reader accepts back).
    pub fn check_finite(&self, path: &Path) -> Result<(), GenomeFileError> {
        let refuse = |what: String| {
            Err(GenomeFileError::Mismatch {
                path: path.to_path_buf(),
                reason: format!("refusing to write: {what} is not finite"),
            })
        };
        if let Some(i) = self.parameters.iter().position(|p| !p.is_finite()) {
            return refuse(format!("parameters[{i}]"));
        }
        if self.step_size.is_some_and(|s| !s.is_finite()) {
            return refuse("step_size".to_string());
        }
        if self.origin.fitness.is_some_and(|f| !f.is_finite()) {
            return refuse("origin.fitness".to_string());
        }
        if let Some(i) = self
            .origin
            .metabolism
            .and_then(|m| m.iter().position(|x| !x.is_finite()))
        {
            return refuse(format!("origin.metabolism[{i}]"));
        }
        Ok(())
    }

    /// Writes the file atomically. Non-finite values are refused before writing.
    pub fn save(&self, path: &Path) -> Result<(), GenomeFileError> {
        self.check_finite(path)?;
        write_atomic(path, &self.to_json()).map_err(|error| GenomeFileError::Io {
            path: path.to_path_buf(),
            error,
        })
    }
}
