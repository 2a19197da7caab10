"""The coarse layer: Experiment, evaluate, genome files, errors; evaluate gives the command
line's bits (compare --json on the held-out and validation worlds, the run's own evaluation of a
generation on the training worlds)."""

import json
import subprocess

import numpy as np
import pytest

import berry_evolve as be
from conftest import FORAGING


@pytest.fixture(scope="module")
def exp():
    return be.Experiment.load(FORAGING)


def test_layout_names_the_inputs_outputs_and_measures(exp):
    layout = exp.layout
    assert layout["inputs"][:2] == ["smell_left_1", "smell_left_2"]
    assert layout["inputs"][-1] == "bias"
    assert layout["outputs"] == ["motor_left", "motor_right"]
    assert layout["measures"] == ["distinct_food", "food_types"]
    assert exp.num_params == 50  # 24 inputs + ... : (24 + 1) x 2 for the MLP without hidden
    assert exp.name == "foraging"


def test_from_toml_is_load(exp):
    other = be.Experiment.from_toml(FORAGING.read_text())
    x = np.random.default_rng(1).normal(size=(3, exp.num_params))
    a, b = exp.evaluate(x)[0], other.evaluate(x)[0]
    assert a.tobytes() == b.tobytes()


def test_evaluate_shapes_and_determinism(exp):
    x = np.random.default_rng(2).normal(size=(6, exp.num_params))
    fitness, measures = exp.evaluate(x, generation=4)
    assert fitness.shape == (6,) and fitness.dtype == np.float64
    assert set(measures) == {"distinct_food", "food_types"}
    assert all(v.shape == (6,) for v in measures.values())
    again = exp.evaluate(x, generation=4)
    assert fitness.tobytes() == again.fitness.tobytes()
    assert exp.evaluate(x, generation=5).fitness.tobytes() != fitness.tobytes()
    assert exp.evaluate(x).metabolism.shape == (6, 4)
    # A lone genome is one row; no genome is an empty batch.
    assert exp.evaluate(x[0]).fitness[0] == exp.evaluate(x[:1]).fitness[0]
    assert exp.evaluate(np.zeros((0, exp.num_params))).fitness.shape == (0,)


@pytest.mark.parametrize("worlds", ["held-out", "validation"])
def test_evaluate_is_compare_json_bit_for_bit(exp, cli, tmp_path, worlds):
    x = np.random.default_rng(3).normal(size=(3, exp.num_params))
    paths = []
    for i, g in enumerate(x):
        p = tmp_path / f"g{i}.json"
        exp.save_genome(p, g, description="random genome from the pytest suite")
        paths.append(str(p))
        assert exp.load_genome(p).tobytes() == g.tobytes()
    out = subprocess.run(
        [cli, "compare", *paths, "--experiment", str(FORAGING), "--json", "--random", "0",
         "--worlds", worlds],
        check=True, capture_output=True, text=True,
    ).stdout
    report = json.loads(out)
    fitness, measures = exp.evaluate(x, worlds=worlds)
    for i, g in enumerate(report["genomes"]):
        assert g["fitness"] == fitness[i], (i, g["fitness"], fitness[i])
        for name, value in g["measures"].items():
            assert value == measures[name][i], (i, name)


def test_training_evaluate_is_the_runs_own_evaluation(run_dir, small_foraging):
    run = be.open_run(run_dir)
    generation, population, fitness = run.checkpoint()
    assert generation == 2 and population.shape == (16, 50)
    exp = be.Experiment.load(small_foraging)
    again = exp.evaluate(population, generation=generation, worlds="training").fitness
    assert again.tobytes() == fitness.tobytes()
    curve = run.fitness
    assert float(curve["best"][generation]) == np.max(fitness)


def test_bad_input_raises_the_command_lines_message(exp):
    x = np.zeros((2, exp.num_params))
    with pytest.raises(ValueError, match="wrong number of brain parameters: the topology needs 50, got 7"):
        exp.evaluate(np.zeros((2, 7)))
    with pytest.raises(ValueError, match="unknown world set `test`"):
        exp.evaluate(x, worlds="test")
    bad = x.copy()
    bad[1, 3] = np.inf
    with pytest.raises(ValueError, match=r"individual 1: brain parameter 3 .* is not finite"):
        exp.evaluate(bad)
    with pytest.raises(ValueError, match="unknown key `nme`; did you mean `name`"):
        be.Experiment.from_toml(FORAGING.read_text().replace("name =", "nme =", 1))
    with pytest.raises(OSError, match="cannot read experiment file"):
        be.Experiment.load("/no/such/experiment.toml")
    with pytest.raises(ValueError, match="not finite"):
        exp.save_genome("/tmp/never-written.json", np.full(exp.num_params, np.nan))
    with pytest.raises(ValueError):
        exp.evaluate(np.zeros((2, 3, 4)))


def test_a_genome_of_another_brain_is_refused_with_its_reason(exp):
    from conftest import ROOT

    path = ROOT / "genomes" / "foraging-champion-seed2.json"
    assert be.load_genome(path).ndim == 1
    with pytest.raises(ValueError, match="is not experiment `foraging`'s \\[brain\\]"):
        exp.load_genome(path)
