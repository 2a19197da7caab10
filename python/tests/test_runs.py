"""Reading a run folder: the fitness curve and champions as DataFrames, a checkpoint's
population, the best genome."""

import numpy as np
import pandas as pd
import pytest

import berry_evolve as be


def test_open_run_reads_the_folder(run_dir):
    run = be.open_run(run_dir)
    curve = run.fitness
    assert isinstance(curve, pd.DataFrame)
    assert list(curve["generation"]) == [0, 1, 2]
    assert {"best", "mean", "best_ever"} <= set(curve.columns)
    champions = run.champions
    assert isinstance(champions, pd.DataFrame)
    assert list(champions["generation"]) == [0, 1, 2]
    assert np.allclose(champions["fitness"], curve["best"])
    assert run.champion_genomes.shape == (3, 50)
    best = run.best_genome
    assert best.shape == (50,)
    assert run.checkpoints == [2]
    generation, population, fitness = run.checkpoint(2)
    assert generation == 2 and population.shape == (16, 50) and fitness.shape == (16,)
    assert run.population.tobytes() == population.tobytes()
    exp = run.experiment
    assert exp.evaluate(best, generation=0).fitness.shape == (1,)


def test_open_run_refuses_a_folder_that_is_not_a_run(tmp_path):
    with pytest.raises(ValueError, match="not a run folder"):
        be.open_run(tmp_path)
