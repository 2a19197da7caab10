"""Speed of the Python package against the command line (issue 32's targets).

    python python/bench.py [--reps 5] [--steps 2000] [--envs 256]

1. ``Experiment.evaluate`` of one foraging generation (generation 0's 64 genomes on its
   training worlds) against the command line evaluating the very same generation: inside the
   process, ``berry-evolve bench --generations 1`` (its evolution figure on all cores: the
   evaluation of generation 0 plus the search's ask and tell), and as a whole process,
   ``berry-evolve run experiments/foraging.toml --generations 1`` (plus process start, reading
   the experiment and writing the run folder, synced). The genomes are the run's own (read back
   from its checkpoint, and checked to give the run's bits), so all do the same work. Medians of
   ``--reps`` runs, interleaved.
2. ``make_vec_env`` with ``--envs`` worlds driven by a numpy linear controller: env-steps per
   second, and the share of the time spent outside the Rust step (the controller in numpy and
   the Python wrapper).

Needs the package installed and target/release/berry-evolve built (``cargo build --release``).
"""

import argparse
import json
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

# Run as `python python/bench.py`, this folder is first on the path and its berry_evolve/
# (the sources, without the built extension) would shadow the installed package.
sys.path = [p for p in sys.path if Path(p or ".").resolve() != Path(__file__).resolve().parent]
import berry_evolve as be  # noqa: E402

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


def cli_bench(reps: int) -> float:
    """Seconds per foraging generation 0 in `berry-evolve bench` (its fastest thread count)."""
    out = subprocess.run(
        [str(CLI), "bench", "--generations", "1", "--scaling", "0", "--worlds", "16",
         "--ticks", "10", "--repeat", str(reps), "--json"],
        check=True, capture_output=True, text=True,
    ).stdout
    threads = json.loads(out)["evolution"]["threads"]
    return 1.0 / max(t["generations_per_second"] for t in threads)


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
        b = cli_bench(reps)
    c, p = statistics.median(cli_times), statistics.median(py_times)
    print(
        f"evaluate, one foraging generation ({len(population)} genomes x {exp.trials} trials x "
        f"{exp.ticks} ticks): Python {p * 1000:.1f} ms; command line {b * 1000:.1f} ms in "
        f"`bench` (Python/CLI {p / b:.3f}), {c * 1000:.1f} ms as a whole `run` process "
        f"(Python/CLI {p / c:.3f})"
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
