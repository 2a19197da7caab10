"""The fine layer: Gymnasium's checker, episodes that are evaluation's trials, the vector env
stepping in Rust with next-step autoreset."""

import json
import subprocess

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import berry_evolve as be
from conftest import FORAGING


def test_check_env_passes():
    env = be.make_env(FORAGING, seed=1)
    check_env(env, skip_render_check=True)


def test_an_episode_is_a_trial_and_its_return_the_trial_score(cli, tmp_path):
    exp = be.Experiment.load(FORAGING)
    env = be.make_env(exp, worlds="held-out")
    assert env.action_space.shape == (2,)
    assert env.observation_space.shape == (len(exp.layout["inputs"]),)
    obs, info = env.reset(options={"trial": 1})
    assert info["trial"] == 1
    total, ticks = 0.0, 0
    while True:
        # A hand-written controller: turn towards the stronger smell on the left/right.
        left, right = obs[:8].sum(), obs[8:16].sum()
        obs, reward, terminated, truncated, _ = env.step(np.array([0.6 + right - left, 0.6 + left - right]))
        total += reward
        ticks += 1
        if terminated or truncated:
            break
    assert truncated and ticks == exp.ticks
    outcome = env.outcome()
    assert total == pytest.approx(outcome["score"], abs=1e-9)
    assert set(outcome["measures"]) == {"distinct_food", "food_types"}


def test_same_seed_same_episode_and_vector_env_agrees_with_env():
    a = be.make_env(FORAGING)
    b = be.make_env(FORAGING)
    oa, ia = a.reset(seed=11)
    ob, ib = b.reset(seed=11)
    assert ia == ib and oa.tobytes() == ob.tobytes()
    venv = be.make_vec_env(FORAGING, 4, seed=3)
    assert isinstance(venv, gym.vector.VectorEnv)
    obs, info = venv.reset()
    assert obs.shape == (4, 24)
    single = be.make_env(FORAGING)
    o1, _ = single.reset(options={"trial": int(info["trial"][2])})
    assert o1.tobytes() == obs[2].tobytes()
    rng = np.random.default_rng(0)
    for _ in range(30):
        actions = rng.uniform(-1, 1, size=(4, 2))
        obs, rewards, terminated, truncated, _ = venv.step(actions)
        o1, r1, t1, u1, _ = single.step(actions[2])
        assert obs[2].tobytes() == o1.tobytes() and rewards[2] == r1


def test_vector_env_autoresets_on_the_next_step():
    exp = be.Experiment.from_toml(
        FORAGING.read_text().replace("ticks = 800", "ticks = 5", 1)
    )
    venv = be.make_vec_env(exp, 3, seed=0)
    venv.reset()
    for _ in range(4):
        _, _, terminated, truncated, _ = venv.step(np.zeros((3, 2)))
        assert not truncated.any()
    _, _, terminated, truncated, _ = venv.step(np.zeros((3, 2)))
    assert truncated.all() and not terminated.any()
    obs, rewards, terminated, truncated, _ = venv.step(np.ones((3, 2)))
    assert (rewards == 0).all() and not truncated.any() and not terminated.any()
    with pytest.raises(ValueError, match="actions have shape"):
        venv.step(np.zeros((2, 2)))
