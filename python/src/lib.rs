//! `berry_evolve._berry_evolve`: the Rust half of the Python package, a thin door onto the
//! library (ARCHITECTURE.md, style example 16). Nothing here simulates or scores: the
//! experiment, the world sets and their evaluation (`evo::worlds`), the stepped episodes
//! under the Gymnasium environments (`evo::episode`), genome files and checkpoints are the
//! crate's own code. This file only converts: numpy arrays in and out (written in place where
//! the caller hands a buffer), library errors into Python exceptions carrying the library's
//! message, and the GIL released around every batch so rayon's threads run the work.

use berry_evolve::brain::genome::Genome;
use berry_evolve::brain::spec::Topology;
use berry_evolve::evo::door::{self, Evaluate};
use berry_evolve::evo::episode::Episode;
use berry_evolve::evo::evaluate::Evaluation;
use berry_evolve::evo::life::EvaluationError;
use berry_evolve::evo::worlds::{WorldSet, HELD_OUT_GENERATION};
use berry_evolve::evo::TrialPlan;
use berry_evolve::experiment::{Experiment, ExperimentError};
use berry_evolve::record::genome_file::{GenomeFile, GenomeFileError, Origin};
use berry_evolve::seed::{Generation, TrialIndex};
use berry_evolve::sim::controller::MotorCommand;
use numpy::{
    PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2, PyReadwriteArray1,
    PyReadwriteArray2, PyUntypedArrayMethods,
};
use pyo3::exceptions::{PyOSError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rayon::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// A library error as a `ValueError` with its message (the CLI prints the same words).
fn value_error(error: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(error.to_string())
}

/// An experiment file's error: `OSError` when it could not be read, `ValueError` otherwise.
fn experiment_error(error: ExperimentError) -> PyErr {
    match error {
        ExperimentError::Read { .. } => PyOSError::new_err(error.to_string()),
        other => value_error(other),
    }
}

/// A genome file's error: `OSError` when it could not be read or written, `ValueError`
/// otherwise.
fn genome_file_error(error: GenomeFileError) -> PyErr {
    match error {
        GenomeFileError::Io { .. } => PyOSError::new_err(error.to_string()),
        other => value_error(other),
    }
}

/// What `evaluate_arrays` returns: fitness (n,), metabolism (n, 4), {measure: (n,)}.
type EvaluatedArrays<'py> = (
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyDict>,
);

/// An experiment, validated, with its brain topology: what Python's `Experiment` wraps.
#[pyclass(name = "Experiment", module = "berry_evolve", frozen)]
struct PyExperiment {
    experiment: Arc<Experiment>,
    topology: Topology,
}

impl PyExperiment {
    fn new(experiment: Experiment) -> PyExperiment {
        PyExperiment {
            topology: experiment.topology(),
            experiment: Arc::new(experiment),
        }
    }

    /// One genome from `parameters`, refused (with the library's message) unless it has the
    /// topology's length and only finite values.
    fn genome(&self, parameters: Vec<f64>) -> PyResult<Genome> {
        let genome = Genome::new(parameters);
        berry_evolve::brain::Brain::new(&self.topology, &genome.parameters).map_err(value_error)?;
        Ok(genome)
    }
}

#[pymethods]
impl PyExperiment {
    /// The experiment file at `path`, validated (`ValueError` with the file, line and key of
    /// what is wrong; `OSError` when it cannot be read).
    #[staticmethod]
    fn load(path: PathBuf) -> PyResult<PyExperiment> {
        Experiment::load(&path)
            .map(PyExperiment::new)
            .map_err(experiment_error)
    }

    /// An experiment from TOML text (named `<string>` in messages).
    #[staticmethod]
    fn from_toml(text: &str) -> PyResult<PyExperiment> {
        Experiment::from_toml(text, Path::new("<string>"))
            .map(PyExperiment::new)
            .map_err(experiment_error)
    }

    /// The experiment's name.
    #[getter]
    fn name(&self) -> String {
        self.experiment.name.clone()
    }

    /// The master seed.
    #[getter]
    fn seed(&self) -> u64 {
        self.experiment.seed
    }

    /// The length of a genome: the brain's parameter count.
    #[getter]
    fn num_params(&self) -> usize {
        self.topology.parameter_count()
    }

    /// The observation's inputs by name, in order.
    #[getter]
    fn inputs(&self) -> Vec<String> {
        self.experiment.layout().names().to_vec()
    }

    /// The brain's outputs by name, in order.
    #[getter]
    fn outputs(&self) -> Vec<String> {
        self.experiment.output_names()
    }

    /// The `[behaviour]` measures by name, in order.
    #[getter]
    fn measures(&self) -> Vec<String> {
        self.experiment
            .behaviour
            .measures
            .iter()
            .map(|m| m.name().to_string())
            .collect()
    }

    /// `[evaluation] trials`.
    #[getter]
    fn trials(&self) -> u64 {
        self.experiment.evaluation.trials
    }

    /// `[evaluation] ticks`.
    #[getter]
    fn ticks(&self) -> u64 {
        self.experiment.evaluation.ticks
    }

    /// `[evolution] population`.
    #[getter]
    fn population(&self) -> usize {
        self.experiment.evolution.population
    }

    /// `[evaluation] group_size`.
    #[getter]
    fn group_size(&self) -> u64 {
        self.experiment.evaluation.group_size
    }

    /// The largest motor command, in rotations per tick (`creature.max_rpt`).
    #[getter]
    fn max_rpt(&self) -> f64 {
        self.experiment.creature.max_rpt
    }

    /// True when the creature eats by an output (`creature.eating = "action"`).
    #[getter]
    fn eats_by_action(&self) -> bool {
        self.experiment.creature.eats_by_action()
    }

    /// The generation whose training streams build the held-out worlds.
    #[classattr]
    #[allow(non_snake_case)]
    fn HELD_OUT_GENERATION() -> u64 {
        HELD_OUT_GENERATION
    }

    /// Evaluates each row of `genomes` ((n, num_params) float64) on a world set and returns
    /// (fitness (n,), metabolism (n, 4), {measure: (n,)}): fitness NaN where a brain gave a
    /// non-finite output. The work runs on rayon's threads with the GIL released.
    #[pyo3(signature = (genomes, generation = 0, worlds = "training"))]
    fn evaluate_arrays<'py>(
        &self,
        py: Python<'py>,
        genomes: PyReadonlyArray2<'py, f64>,
        generation: u64,
        worlds: &str,
    ) -> PyResult<EvaluatedArrays<'py>> {
        let set = WorldSet::parse(worlds, generation).map_err(value_error)?;
        let list: Vec<Genome> = genomes
            .as_array()
            .rows()
            .into_iter()
            .map(|row| Genome::new(row.to_vec()))
            .collect();
        let (experiment, topology) = (&*self.experiment, &self.topology);
        let request = Evaluate::new(experiment, topology, &list, door::Worlds::of(set));
        request.check().map_err(value_error)?;
        let evaluations: Vec<Evaluation> =
            py.allow_threads(|| request.run()).map_err(value_error)?;
        let fitness: Vec<f64> = evaluations
            .iter()
            .map(|e| e.fitness.unwrap_or(f64::NAN))
            .collect();
        let metabolism: Vec<f64> = evaluations.iter().flat_map(|e| e.metabolism).collect();
        let measures = PyDict::new(py);
        for (k, m) in experiment.behaviour.measures.iter().enumerate() {
            let values: Vec<f64> = evaluations.iter().map(|e| e.measures[k]).collect();
            measures.set_item(m.name(), PyArray1::from_vec(py, values))?;
        }
        let n = evaluations.len();
        Ok((
            PyArray1::from_vec(py, fitness),
            PyArray1::from_vec(py, metabolism).reshape([n, 4])?,
            measures,
        ))
    }

    /// The genome of the genome file at `path` as a float64 array, refused unless it fits this
    /// experiment (the inputs and outputs the CLI checks).
    fn load_genome<'py>(
        &self,
        py: Python<'py>,
        path: PathBuf,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let file = GenomeFile::load(&path).map_err(genome_file_error)?;
        let topology = file
            .topology_for(&self.experiment, &path)
            .map_err(genome_file_error)?;
        // The command line decodes a genome with its own file's brain; this experiment's
        // evaluate decodes every row with the experiment's [brain], so they must agree.
        if topology != self.topology {
            return Err(value_error(format!(
                "{}: the genome's brain ({} parameters) is not experiment `{}`'s [brain] ({} \
                 parameters); evaluate it with the experiment it was evolved in, or with \
                 `berry-evolve compare`, which uses the genome's own brain",
                path.display(),
                topology.parameter_count(),
                self.experiment.name,
                self.topology.parameter_count()
            )));
        }
        Ok(PyArray1::from_vec(py, file.genome().parameters))
    }

    /// Writes `genome` as a genome file for this experiment (the format `compare`, `replay`
    /// and `render` read), with an optional description.
    #[pyo3(signature = (path, genome, description = None))]
    fn save_genome(
        &self,
        path: PathBuf,
        genome: PyReadonlyArray1<'_, f64>,
        description: Option<String>,
    ) -> PyResult<()> {
        let genome = self.genome(genome.as_array().to_vec())?;
        let origin = Origin {
            description,
            experiment: Some(self.experiment.name.clone()),
            config_hash: Some(self.experiment.config_hash()),
            ..Origin::default()
        };
        GenomeFile::new(&self.experiment, &genome, origin)
            .save(&path)
            .map_err(genome_file_error)
    }
}

/// The parameters of the genome file at `path`, whatever experiment it was made for.
#[pyfunction]
fn load_genome_file<'py>(py: Python<'py>, path: PathBuf) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let file = GenomeFile::load(&path).map_err(genome_file_error)?;
    Ok(PyArray1::from_vec(py, file.genome().parameters))
}

/// A run folder's newest good checkpoint (or the checkpoint file `path`): (generation,
/// population (n, num_params), fitness (n,) with NaN for non-finite brains).
#[pyfunction]
#[allow(clippy::type_complexity)]
fn load_checkpoint<'py>(
    py: Python<'py>,
    path: PathBuf,
) -> PyResult<(u64, Bound<'py, PyArray2<f64>>, Bound<'py, PyArray1<f64>>)> {
    let (_, _, payload, _) = berry_evolve::run::load_checkpoint(&path).map_err(value_error)?;
    let individuals = &payload.last.individuals;
    let width = individuals.first().map_or(0, |i| i.genome.parameters.len());
    let flat: Vec<f64> = individuals
        .iter()
        .flat_map(|i| i.genome.parameters.iter().copied())
        .collect();
    let fitness: Vec<f64> = individuals
        .iter()
        .map(|i| i.evaluation.fitness.unwrap_or(f64::NAN))
        .collect();
    Ok((
        payload.last.generation,
        PyArray1::from_vec(py, flat).reshape([individuals.len(), width])?,
        PyArray1::from_vec(py, fitness),
    ))
}

/// `num_envs` one-creature episodes stepped together (the core of Python's `make_env` and
/// `make_vec_env`): each step runs every episode's tick on rayon's threads with the GIL
/// released, writing observations, rewards and flags into the caller's numpy arrays.
///
/// Episode e of env i (counted from its last reset) lives trial `base_i + e` of
/// `generation`'s worlds, `base_i` given at reset: the trial worlds evaluation uses
/// (training worlds of that generation, or the held-out worlds for
/// `Experiment.HELD_OUT_GENERATION`), any index giving a world of the same distribution.
#[pyclass(module = "berry_evolve")]
struct Worlds {
    experiment: Arc<Experiment>,
    generation: Generation,
    episodes: Vec<Option<Episode>>,
    next_trial: Vec<u64>,
    actions: usize,
}

/// The motor command of an action row: the wheel speeds, and the eat output when the
/// creature eats by action.
fn command(action: &[f64]) -> MotorCommand {
    MotorCommand {
        left: action[0],
        right: action[1],
        eat: action.get(2).copied().unwrap_or(0.0),
    }
}

/// Rows of at least this many episodes per rayon task: a tick costs microseconds, so a
/// task per episode would spend a noticeable share splitting work.
const EPISODES_PER_TASK: usize = 8;

#[pymethods]
impl Worlds {
    #[new]
    fn new(experiment: &PyExperiment, num_envs: usize, generation: u64) -> Worlds {
        Worlds {
            experiment: experiment.experiment.clone(),
            generation: Generation(generation),
            episodes: (0..num_envs).map(|_| None).collect(),
            next_trial: vec![0; num_envs],
            actions: if experiment.experiment.creature.eats_by_action() {
                3
            } else {
                2
            },
        }
    }

    /// How many numbers an action row holds: 2 (left, right wheel in rotations per tick), 3
    /// with the eat output.
    #[getter]
    fn action_width(&self) -> usize {
        self.actions
    }

    /// How many inputs an observation holds.
    #[getter]
    fn observation_width(&self) -> usize {
        self.experiment.layout().len()
    }

    /// Starts env `index`'s next episode in trial `trial` and writes its first observation
    /// into `obs` (its row); the episodes after it (autoreset) take trials `trial + 1`, ...
    fn reset(
        &mut self,
        index: usize,
        trial: u64,
        mut obs: PyReadwriteArray1<'_, f64>,
    ) -> PyResult<()> {
        if index >= self.episodes.len() {
            return Err(value_error(format!(
                "env {index} does not exist: there are {}",
                self.episodes.len()
            )));
        }
        let plan = TrialPlan::new(&self.experiment);
        let episode =
            Episode::new(&plan, self.generation, TrialIndex(trial)).map_err(value_error)?;
        let out = obs.as_slice_mut().map_err(value_error)?;
        if out.len() != episode.observation().len() {
            return Err(value_error(format!(
                "the observation buffer holds {} numbers, an observation {}",
                out.len(),
                episode.observation().len()
            )));
        }
        out.copy_from_slice(episode.observation());
        self.episodes[index] = Some(episode);
        self.next_trial[index] = trial.wrapping_add(1) & (u64::MAX >> 1);
        Ok(())
    }

    /// One tick of every env: `actions` (num_envs, action_width) in; the next observations,
    /// rewards, terminated and truncated flags written into the given arrays. With
    /// `autoreset`, an env whose episode ended at the previous step starts its next episode
    /// instead (its action ignored, reward 0, flags false: Gymnasium's next-step autoreset).
    #[pyo3(signature = (actions, obs, rewards, terminated, truncated, autoreset = true))]
    // Python's signature: the action batch, the four output buffers and the mode.
    #[allow(clippy::too_many_arguments)]
    fn step(
        &mut self,
        py: Python<'_>,
        actions: PyReadonlyArray2<'_, f64>,
        mut obs: PyReadwriteArray2<'_, f64>,
        mut rewards: PyReadwriteArray1<'_, f64>,
        mut terminated: PyReadwriteArray1<'_, bool>,
        mut truncated: PyReadwriteArray1<'_, bool>,
        autoreset: bool,
    ) -> PyResult<()> {
        let n = self.episodes.len();
        let width = self.experiment.layout().len();
        if actions.shape() != [n, self.actions] {
            return Err(value_error(format!(
                "actions have shape {:?}; {n} envs need ({n}, {}) (left and right wheel in \
                 rotations per tick{})",
                actions.shape(),
                self.actions,
                if self.actions == 3 { ", eat" } else { "" }
            )));
        }
        if self.episodes.iter().any(Option::is_none) {
            return Err(value_error("call reset before step"));
        }
        let actions = actions.as_slice().map_err(value_error)?;
        let obs = obs.as_slice_mut().map_err(value_error)?;
        let rewards = rewards.as_slice_mut().map_err(value_error)?;
        let terminated = terminated.as_slice_mut().map_err(value_error)?;
        let truncated = truncated.as_slice_mut().map_err(value_error)?;
        if obs.len() != n * width
            || rewards.len() != n
            || terminated.len() != n
            || truncated.len() != n
        {
            return Err(value_error("output buffers of the wrong size"));
        }
        let plan = TrialPlan::new(&self.experiment);
        let (plan, generation, a) = (&plan, self.generation, self.actions);
        let episodes = &mut self.episodes;
        let next_trial = &mut self.next_trial;
        py.allow_threads(|| {
            episodes
                .par_iter_mut()
                .zip(next_trial.par_iter_mut())
                .zip(obs.par_chunks_mut(width))
                .zip(rewards.par_iter_mut())
                .zip(terminated.par_iter_mut())
                .zip(truncated.par_iter_mut())
                .zip(actions.par_chunks(a))
                .with_min_len(EPISODES_PER_TASK)
                .try_for_each(
                    |((((((slot, next), out), reward), term), trunc), action)| -> Result<(), EvaluationError> {
                        let episode = slot.as_mut().expect("reset before step");
                        if autoreset && episode.is_over() {
                            *episode = Episode::new(plan, generation, TrialIndex(*next))?;
                            *next = next.wrapping_add(1) & (u64::MAX >> 1);
                            *reward = 0.0;
                            *term = false;
                            *trunc = false;
                        } else {
                            let step = episode.step(command(action));
                            *reward = step.reward;
                            *term = step.terminated;
                            *trunc = step.truncated;
                        }
                        out.copy_from_slice(episode.observation());
                        Ok(())
                    },
                )
        })
        .map_err(value_error)
    }

    /// Env `index`'s life so far, as evaluation reports a trial: {"score", "metabolism",
    /// "non_finite", "measures": {name: value}}.
    fn outcome<'py>(&self, py: Python<'py>, index: usize) -> PyResult<Bound<'py, PyDict>> {
        let episode = self
            .episodes
            .get(index)
            .and_then(Option::as_ref)
            .ok_or_else(|| value_error(format!("env {index} has no episode: call reset")))?;
        let o = episode.outcome();
        let d = PyDict::new(py);
        d.set_item("score", o.score)?;
        d.set_item("metabolism", o.metabolism.to_vec())?;
        d.set_item("non_finite", o.non_finite)?;
        d.set_item("ticks", episode.world().tick())?;
        let measures = PyDict::new(py);
        for m in &self.experiment.behaviour.measures {
            measures.set_item(m.name(), o.measures[m.index()])?;
        }
        d.set_item("measures", measures)?;
        Ok(d)
    }
}

/// The extension module.
#[pymodule]
fn _berry_evolve(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyExperiment>()?;
    m.add_class::<Worlds>()?;
    m.add_function(wrap_pyfunction!(load_genome_file, m)?)?;
    m.add_function(wrap_pyfunction!(load_checkpoint, m)?)?;
    m.add("HELD_OUT_GENERATION", HELD_OUT_GENERATION)?;
    m.add("VERSION", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
