"""berry_evolve: the BERRY III artificial-creature world and its evaluation, from Python.

A thin door onto the Rust library (the same code as the ``berry-evolve`` command line):

- ``Experiment.load(path)`` / ``Experiment.from_toml(text)``; ``exp.layout``, ``exp.num_params``;
  ``exp.evaluate(genomes, generation=0, worlds="training")`` -> ``(fitness, measures)``, the same
  bits as the command line (``berry-evolve compare --json`` on the held-out and validation
  worlds; the run's own evaluation of generation g on the training worlds).
- ``load_genome`` / ``Experiment.save_genome``: genome files to and from numpy.
- ``make_env`` / ``make_vec_env``: Gymnasium environments (one creature, its input vector as the
  observation, the wheel speeds as the action).
- ``open_run(dir)``: a run folder's fitness curve, champions, checkpoints and best genome.
"""

from __future__ import annotations

import os
from typing import Dict, Union

import numpy as np

from . import _berry_evolve as _native

__all__ = [
    "Experiment",
    "Evaluation",
    "HELD_OUT_GENERATION",
    "load_genome",
    "make_env",
    "make_vec_env",
    "open_run",
]

#: The generation whose training streams build the held-out worlds (2**40).
HELD_OUT_GENERATION: int = _native.HELD_OUT_GENERATION

PathLike = Union[str, "os.PathLike[str]"]


class Evaluation(tuple):
    """``(fitness, measures)`` as returned by :meth:`Experiment.evaluate`, with the mean final
    metabolic vector as ``.metabolism`` (n, 4)."""

    fitness: np.ndarray
    measures: Dict[str, np.ndarray]
    metabolism: np.ndarray

    def __new__(cls, fitness, metabolism, measures):
        self = super().__new__(cls, (fitness, measures))
        self.fitness = fitness
        self.measures = measures
        self.metabolism = metabolism
        return self


class Experiment:
    """A validated experiment file: its worlds, creature, brain and fitness."""

    def __init__(self, native: "_native.Experiment", path: "str | None" = None):
        self._native = native
        self.path = path

    @classmethod
    def load(cls, path: PathLike) -> "Experiment":
        """The experiment file at ``path`` (``ValueError`` naming the line and key of a bad
        value, ``OSError`` when it cannot be read)."""
        return cls(_native.Experiment.load(os.fspath(path)), os.fspath(path))

    @classmethod
    def from_toml(cls, text: str) -> "Experiment":
        """An experiment from TOML text (called ``<string>`` in error messages)."""
        return cls(_native.Experiment.from_toml(text))

    @property
    def name(self) -> str:
        return self._native.name

    @property
    def seed(self) -> int:
        return self._native.seed

    @property
    def num_params(self) -> int:
        """The length of a genome (the brain's parameter count)."""
        return self._native.num_params

    @property
    def layout(self) -> Dict[str, list]:
        """``{"inputs": [...], "outputs": [...], "measures": [...]}``, each by name, in order."""
        return {
            "inputs": list(self._native.inputs),
            "outputs": list(self._native.outputs),
            "measures": list(self._native.measures),
        }

    @property
    def trials(self) -> int:
        return self._native.trials

    @property
    def ticks(self) -> int:
        return self._native.ticks

    @property
    def population(self) -> int:
        return self._native.population

    @property
    def group_size(self) -> int:
        return self._native.group_size

    @property
    def max_rpt(self) -> float:
        return self._native.max_rpt

    def __repr__(self) -> str:
        return f"Experiment({self.name!r}, num_params={self.num_params})"

    def evaluate(
        self,
        genomes,
        generation: int = 0,
        worlds: str = "training",
    ) -> Evaluation:
        """Evaluates each row of ``genomes`` (an ``(n, num_params)`` float64 array; one genome
        of ``num_params`` is taken as ``n = 1``) and returns ``(fitness, measures)``: fitness
        ``(n,)`` (NaN where a brain gave a non-finite output) and the behaviour measures as a
        dict of ``(n,)`` arrays; ``.metabolism`` holds the mean final metabolic vectors.

        ``worlds``: ``"training"`` (generation ``generation``'s trial worlds, evaluated as the
        run evaluates that generation), ``"validation"``, ``"held-out"`` or ``"design"`` (each
        genome alone in the same worlds, as ``berry-evolve compare`` does; tune by hand on
        ``"design"``, report on ``"held-out"``). Runs on all cores with the GIL
        released; the same bits on any number of threads.
        """
        g = np.ascontiguousarray(genomes, dtype=np.float64)
        if g.ndim == 1:
            g = g.reshape(1, -1)
        if g.ndim != 2:
            raise ValueError(
                f"genomes must be an (n, {self.num_params}) array, got shape {g.shape}"
            )
        if g.shape[0] > 0 and g.shape[1] != self.num_params:
            raise ValueError(
                f"individual 0: wrong number of brain parameters: the topology needs "
                f"{self.num_params}, got {g.shape[1]}"
            )
        fitness, metabolism, measures = self._native.evaluate_arrays(
            g, int(generation), str(worlds)
        )
        return Evaluation(fitness, metabolism, dict(measures))

    def load_genome(self, path: PathLike) -> np.ndarray:
        """The genome file at ``path`` as a float64 array, refused unless it fits this
        experiment's inputs and outputs."""
        return self._native.load_genome(os.fspath(path))

    def save_genome(self, path: PathLike, genome, description: "str | None" = None) -> None:
        """Writes ``genome`` as a genome file (what ``compare``, ``replay`` and ``render``
        read)."""
        g = np.ascontiguousarray(genome, dtype=np.float64).reshape(-1)
        self._native.save_genome(os.fspath(path), g, description)


def load_genome(path: PathLike) -> np.ndarray:
    """The parameters of the genome file at ``path`` (any experiment's) as a float64 array."""
    return _native.load_genome_file(os.fspath(path))


def make_env(experiment, seed: "int | None" = None, **kwargs):
    """A ``gymnasium.Env`` of one creature in ``experiment`` (a path or an
    :class:`Experiment`); see :class:`berry_evolve.envs.BerryEnv`."""
    BerryEnv = _envs().BerryEnv
    return BerryEnv(experiment, seed=seed, **kwargs)


def make_vec_env(experiment, num_envs: int, seed: "int | None" = None, **kwargs):
    """A ``gymnasium.vector.VectorEnv`` of ``num_envs`` worlds stepped together in Rust; see
    :class:`berry_evolve.envs.BerryVecEnv`."""
    BerryVecEnv = _envs().BerryVecEnv
    return BerryVecEnv(experiment, num_envs, seed=seed, **kwargs)


def open_run(directory: PathLike):
    """A run folder (``berry-evolve run``'s output); see :class:`berry_evolve.runs.Run`."""
    from .runs import Run

    return Run(directory)


def _envs():
    """The environments' module, or an ImportError that says what to install."""
    try:
        import gymnasium  # noqa: F401
    except ImportError as error:
        raise ImportError(
            "the environments need gymnasium: pip install gymnasium (or pip install "
            "'./python[gym]' from the repository)"
        ) from error
    from . import envs

    return envs


def _experiment(experiment) -> Experiment:
    if isinstance(experiment, Experiment):
        return experiment
    return Experiment.load(experiment)


def _set_generation(worlds: str, generation: int) -> int:
    """The generation whose streams build ``worlds`` for the environments."""
    if worlds == "training":
        return int(generation)
    if worlds == "held-out":
        return HELD_OUT_GENERATION
    raise ValueError(
        f"unknown world set `{worlds}` for an environment: possible values: held-out, training"
    )

