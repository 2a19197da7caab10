"""Reading a run folder (``berry-evolve run``'s output) into numpy, or pandas when installed.

The folder's files are read as the command line writes them: ``fitness.csv`` (one row per
generation), ``champions.jsonl`` (one genome file per line, each generation's best),
``best.json`` (the champion), ``experiment.toml`` and ``checkpoints/gen-NNNNNN.json`` (read by
the library's own checkpoint reader, which checks their checksums).
"""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Optional, Tuple

import numpy as np

from . import _berry_evolve as _native
from . import Experiment, load_genome

try:  # pandas is optional: plain numpy without it.
    import pandas as _pd
except ImportError:  # pragma: no cover - exercised where pandas is absent
    _pd = None


def _table(columns: dict):
    """A DataFrame of ``columns`` with pandas, else a dict of numpy arrays."""
    if _pd is not None:
        return _pd.DataFrame(columns)
    return {k: np.asarray(v) for k, v in columns.items()}


class Run:
    """One run folder."""

    def __init__(self, directory):
        self.path = Path(os.fspath(directory))
        if not (self.path / "experiment.toml").is_file():
            raise ValueError(
                f"{self.path} is not a run folder: it has no experiment.toml (give the folder "
                f"`berry-evolve run` wrote, e.g. results/foraging/seed-1)"
            )

    def __repr__(self) -> str:
        return f"Run({str(self.path)!r})"

    @property
    def experiment(self) -> Experiment:
        """The run's own experiment (its experiment.toml)."""
        return Experiment.load(self.path / "experiment.toml")

    @property
    def fitness(self):
        """The fitness curve: fitness.csv, one row per generation (a pandas DataFrame, or a
        dict of numpy arrays by column without pandas). Empty cells are NaN."""
        path = self.path / "fitness.csv"
        if _pd is not None:
            return _pd.read_csv(path)
        with open(path) as f:
            header = f.readline().strip().split(",")
            rows = [line.rstrip("\n").split(",") for line in f if line.strip()]
        return {
            name: np.array([float(r[k]) if r[k] else np.nan for r in rows])
            for k, name in enumerate(header)
        }

    def _champion_lines(self):
        path = self.path / "champions.jsonl"
        if not path.is_file():
            return []
        with open(path) as f:
            return [json.loads(line) for line in f if line.strip()]

    @property
    def champions(self):
        """Each generation's best individual: generation, individual, fitness and metabolism
        (a DataFrame, or a dict of arrays); their genomes are :attr:`champion_genomes`."""
        lines = self._champion_lines()

        def column(key, default=np.nan):
            return [
                d.get("origin", {}).get(key, default)
                if d.get("origin", {}).get(key) is not None
                else default
                for d in lines
            ]

        metabolism = np.array(
            [d.get("origin", {}).get("metabolism") or [np.nan] * 4 for d in lines],
            dtype=np.float64,
        ).reshape(-1, 4)
        cols = {
            "generation": np.array(column("generation", -1), dtype=np.int64),
            "individual": np.array(column("individual", -1), dtype=np.int64),
            "fitness": np.array(column("fitness"), dtype=np.float64),
        }
        for k, food in enumerate("abcd"):
            cols[f"food_{food}"] = metabolism[:, k]
        return _table(cols)

    @property
    def champion_genomes(self) -> np.ndarray:
        """Each generation's best genome, one row each, in champions.jsonl's order."""
        lines = self._champion_lines()
        if not lines:
            return np.zeros((0, 0))
        return np.array([d["parameters"] for d in lines], dtype=np.float64)

    @property
    def best_genome(self) -> np.ndarray:
        """The champion (best.json) as a float64 array."""
        return load_genome(self.path / "best.json")

    @property
    def checkpoints(self) -> list:
        """The generations that have a checkpoint, oldest first."""
        names = sorted((self.path / "checkpoints").glob("gen-*.json"))
        return [int(p.stem[len("gen-"):]) for p in names]

    def checkpoint(
        self, generation: Optional[int] = None
    ) -> Tuple[int, np.ndarray, np.ndarray]:
        """``(generation, population, fitness)`` of a checkpoint: the newest good one by
        default; the population is ``(n, num_params)``, the fitness ``(n,)`` (NaN for a
        non-finite brain)."""
        if generation is None:
            target = self.path
        else:
            target = self.path / "checkpoints" / f"gen-{int(generation):06d}.json"
        return _native.load_checkpoint(os.fspath(target))

    @property
    def population(self) -> np.ndarray:
        """The newest checkpoint's population, ``(n, num_params)``."""
        return self.checkpoint()[1]
