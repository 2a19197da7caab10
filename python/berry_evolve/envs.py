"""Gymnasium environments: one creature in a BERRY world, driven by your controller.

- Observation: the creature's input vector (``Experiment.layout["inputs"]``), float64.
- Action: the left and right wheel speeds in rotations per tick, a ``Box`` of
  ``[-max_rpt, max_rpt]`` (a third number in ``[0, 1]``, the eat output, when the experiment's
  creature eats by action); the world clamps them as it clamps a brain's.
- Reward: the experiment's per-tick fitness increment (the trial's score if the life ended now,
  minus the same one tick earlier), so an episode's return is the trial's score.
- Terminated: the creature died (or an action was not finite). Truncated: the trial's
  ``[evaluation] ticks`` ran out.

Each episode lives one trial world of the experiment: ``worlds="training"`` draws them from
generation ``generation``'s streams (the worlds evaluation uses; any trial index gives a world
of the same distribution), ``worlds="held-out"`` from the held-out worlds'. ``reset(seed=s)``
seeds the choice of trial (Gymnasium's ``np_random``); ``reset(options={"trial": t})`` lives
trial ``t`` exactly, the world ``berry-evolve compare`` calls trial ``t``. The worlds step in
Rust (``evo::episode``), every env of a vector env in parallel with the GIL released.
"""

from __future__ import annotations

from typing import Any, Optional

import gymnasium as gym
import numpy as np
from gymnasium import spaces
from gymnasium.vector import AutoresetMode, VectorEnv

from . import _berry_evolve as _native
from . import _experiment, _set_generation

#: Trial indices are drawn below this (seeds stay below 2**63).
_TRIALS = 2**62


def _spaces(exp, width: int, actions: int):
    observation = spaces.Box(-np.inf, np.inf, shape=(width,), dtype=np.float64)
    low = np.array([-exp.max_rpt, -exp.max_rpt, 0.0][:actions])
    high = np.array([exp.max_rpt, exp.max_rpt, 1.0][:actions])
    return observation, spaces.Box(low, high, dtype=np.float64)


class BerryEnv(gym.Env):
    """One creature in one BERRY world at a time (see the module's docs)."""

    metadata = {"render_modes": []}

    def __init__(
        self,
        experiment,
        seed: Optional[int] = None,
        worlds: str = "training",
        generation: int = 0,
    ):
        self.experiment = _experiment(experiment)
        self._core = _native.Worlds(
            self.experiment._native, 1, _set_generation(worlds, generation)
        )
        width = self._core.observation_width
        self.observation_space, self.action_space = _spaces(
            self.experiment, width, self._core.action_width
        )
        self._seed = seed
        self._obs = np.zeros((1, width))
        self._reward = np.zeros(1)
        self._terminated = np.zeros(1, dtype=bool)
        self._truncated = np.zeros(1, dtype=bool)
        self._action = np.zeros((1, self._core.action_width))

    def reset(self, *, seed: Optional[int] = None, options: Optional[dict] = None):
        if seed is None and self._seed is not None:
            # make_env(seed=...): the first reset's seed.
            seed, self._seed = self._seed, None
        super().reset(seed=seed)
        if options and "trial" in options:
            trial = int(options["trial"])
        else:
            trial = int(self.np_random.integers(0, _TRIALS))
        self._core.reset(0, trial, self._obs[0])
        return self._obs[0].copy(), {"trial": trial}

    def step(self, action):
        self._action[0] = np.asarray(action, dtype=np.float64).reshape(-1)
        self._core.step(
            self._action,
            self._obs,
            self._reward,
            self._terminated,
            self._truncated,
            False,
        )
        return (
            self._obs[0].copy(),
            float(self._reward[0]),
            bool(self._terminated[0]),
            bool(self._truncated[0]),
            {},
        )

    def outcome(self) -> dict:
        """The life so far as evaluation reports a trial: score, metabolism, measures."""
        return self._core.outcome(0)


class BerryVecEnv(VectorEnv):
    """``num_envs`` BERRY worlds stepped together in Rust (rayon, GIL released), writing
    into preallocated numpy arrays (see the module's docs).

    Autoreset follows Gymnasium's next-step mode: the step after an episode ends starts the
    next one in that env (its action ignored, reward 0). With ``copy=False`` (the default)
    ``step`` and ``reset`` return the same observation, reward and flag arrays every call,
    overwritten by the next: copy what you keep.
    """

    metadata = {"autoreset_mode": AutoresetMode.NEXT_STEP, "render_modes": []}

    def __init__(
        self,
        experiment,
        num_envs: int,
        seed: Optional[int] = None,
        worlds: str = "training",
        generation: int = 0,
        copy: bool = False,
    ):
        self.experiment = _experiment(experiment)
        self.num_envs = int(num_envs)
        self._core = _native.Worlds(
            self.experiment._native, self.num_envs, _set_generation(worlds, generation)
        )
        width = self._core.observation_width
        self.single_observation_space, self.single_action_space = _spaces(
            self.experiment, width, self._core.action_width
        )
        self.observation_space = gym.vector.utils.batch_space(
            self.single_observation_space, self.num_envs
        )
        self.action_space = gym.vector.utils.batch_space(
            self.single_action_space, self.num_envs
        )
        self._seed = seed
        self._copy = copy
        self._obs = np.zeros((self.num_envs, width))
        self._rewards = np.zeros(self.num_envs)
        self._terminated = np.zeros(self.num_envs, dtype=bool)
        self._truncated = np.zeros(self.num_envs, dtype=bool)

    def reset(self, *, seed: Optional[int] = None, options: Optional[dict] = None):
        if seed is None and self._seed is not None:
            seed, self._seed = self._seed, None
        super().reset(seed=seed)
        trials = self.np_random.integers(0, _TRIALS, size=self.num_envs)
        for i, t in enumerate(trials):
            self._core.reset(i, int(t), self._obs[i])
        self._terminated[:] = False
        self._truncated[:] = False
        info: dict[str, Any] = {"trial": trials}
        return (self._obs.copy() if self._copy else self._obs), info

    def step(self, actions):
        a = np.ascontiguousarray(actions, dtype=np.float64)
        self._core.step(
            a, self._obs, self._rewards, self._terminated, self._truncated, True
        )
        if self._copy:
            return (
                self._obs.copy(),
                self._rewards.copy(),
                self._terminated.copy(),
                self._truncated.copy(),
                {},
            )
        return self._obs, self._rewards, self._terminated, self._truncated, {}

    def outcome(self, index: int) -> dict:
        """Env ``index``'s life so far, as evaluation reports a trial."""
        return self._core.outcome(index)
