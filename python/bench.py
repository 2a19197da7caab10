"""Speed of the Python package against the command line (issue 32's targets).

    python python/bench.py [--reps 5] [--steps 2000] [--envs 256]

1. ``Experiment.evaluate`` of one foraging generation (generation 0's 64 genomes on its
   training worlds) against the command line evaluating the very same generation
   (``berry-evolve run experiments/foraging.toml --generations 1``: that run's only work is this
   evaluation, plus process start, reading the experiment and writing the run folder). The
   genomes are the run's own (read back from its checkpoint), so both do the same work; both
   use every core. Median of ``--reps`` runs each, interleaved.
2. ``make_vec_env`` with ``--envs`` worlds driven by a numpy linear controller: env-steps per
   second, and the share of the time spent outside the Rust step (the controller in numpy and
   the Python wrapper).

Needs the package installed and target/release/berry-evolve built (``cargo build --release``).
"""

import argparse
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

import numpy as np

import berry_evolve as be

ROOT = Path(__file__).resolve().parents[1]
FORAGING = ROOT / "experiments" / "foraging.toml"
CLI = ROOT / "target" / "release" / "berry-evolve"


def cli_generation(out: Path) -> float:
    start = time.perf_counter()
    subprocess.run(
        [str(CLI), "run", str(FORAGING), "--generations", "1", "--out", str(out), "--force",
         "-q", "--no-estimate", "--no-check"],
        check=True,
    )
    return time.perf_counter() - start


def evaluate_speed(reps: int) -> None:
    exp = be.Experiment.load(FORAGING)
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "run"
        cli_generation(out)  # warm the page cache
        generation, population, fitness = be.open_run(out).checkpoint()
        assert generation == 0
        again = exp.evaluate(population, generation=0).fitness
        assert again.tobytes() == fitness.tobytes(), "not the run's bits"
        cli_times, py_times = [], []
        for _ in range(reps):
            cli_times.append(cli_generation(out))
            start = time.perf_counter()
            exp.evaluate(population, generation=0)
            py_times.append(time.perf_counter() - start)
    c, p = statistics.median(cli_times), statistics.median(py_times)
    print(
        f"evaluate, one foraging generation ({len(population)} genomes x {exp.trials} trials x "
        f"{exp.ticks} ticks): Python {p * 1000:.1f} ms, command line {c * 1000:.1f} ms "
        f"(whole process), Python/CLI {p / c:.3f}"
    )


def vec_env_speed(num_envs: int, steps: int) -> None:
    exp = be.Experiment.load(FORAGING)
    env = be.make_vec_env(exp, num_envs, seed=0)
    obs, _ = env.reset()
    rng = np.random.default_rng(0)
    w = rng.normal(scale=0.3, size=(obs.shape[1], 2))
    core = env._core
    inside = 0.0
    step = core.step

    def timed_step(*args):
        nonlocal inside
        t = time.perf_counter()
        step(*args)
        inside += time.perf_counter() - t

    core_step, env._core = core, _Timed(core, timed_step)
    start = time.perf_counter()
    for _ in range(steps):
        actions = np.tanh(obs @ w) * exp.max_rpt
        obs, rewards, terminated, truncated, _ = env.step(actions)
    total = time.perf_counter() - start
    env._core = core_step
    rate = num_envs * steps / total
    print(
        f"make_vec_env({num_envs}) with a numpy linear controller: {rate:,.0f} env-steps/s "
        f"({steps} steps in {total:.2f} s); {100 * (total - inside) / total:.0f}% of the time "
        f"outside the Rust step (numpy controller and Python wrapper)"
    )


class _Timed:
    """The Rust core with its step timed."""

    def __init__(self, core, step):
        self._core, self.step = core, step

    def __getattr__(self, name):
        return getattr(self._core, name)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--reps", type=int, default=5)
    parser.add_argument("--steps", type=int, default=2000)
    parser.add_argument("--envs", type=int, default=256)
    args = parser.parse_args()
    evaluate_speed(args.reps)
    vec_env_speed(args.envs, args.steps)


if __name__ == "__main__":
    main()
