"""Real clients of the coarse layer: a pycma ask/tell loop and a pyribs MAP-Elites loop over
Experiment.evaluate on experiments/foraging.toml's training worlds."""

import numpy as np

import berry_evolve as be
from conftest import FORAGING


def test_pycma_ask_tell_improves_on_its_start():
    import cma

    exp = be.Experiment.load(FORAGING)
    x0 = np.random.default_rng(4).normal(scale=0.3, size=exp.num_params)
    start = exp.evaluate(x0).fitness[0]
    es = cma.CMAEvolutionStrategy(x0, 0.5, {"popsize": 8, "seed": 5, "verbose": -9})
    best = -np.inf
    for generation in range(6):
        genomes = np.array(es.ask())
        fitness = exp.evaluate(genomes, generation=generation).fitness
        fitness = np.nan_to_num(fitness, nan=-1e9)
        es.tell(list(genomes), list(-fitness))  # pycma minimises
        best = max(best, fitness.max())
    assert best > start, (best, start)


def test_pyribs_map_elites_fills_cells_with_behaviour_measures():
    from ribs.archives import GridArchive
    from ribs.emitters import GaussianEmitter
    from ribs.schedulers import Scheduler

    exp = be.Experiment.load(FORAGING)
    archive = GridArchive(
        solution_dim=exp.num_params, dims=[8, 4], ranges=[(0, 8), (0, 4)], seed=6
    )
    emitters = [
        GaussianEmitter(archive, sigma=0.5, x0=np.zeros(exp.num_params), batch_size=16, seed=7)
    ]
    scheduler = Scheduler(archive, emitters)
    for iteration in range(4):
        solutions = scheduler.ask()
        fitness, measures = exp.evaluate(solutions, generation=iteration)
        descriptors = np.stack([measures["distinct_food"], measures["food_types"]], axis=1)
        scheduler.tell(np.nan_to_num(fitness, nan=-1e9), descriptors)
    assert len(archive) >= 3, len(archive)
    assert archive.stats.obj_max > 0
