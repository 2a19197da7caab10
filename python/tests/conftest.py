"""Shared fixtures: the repository's paths, the command-line binary (built with cargo when
missing; BERRY_EVOLVE_BIN names another), and a small run folder made by that binary."""

import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
FORAGING = ROOT / "experiments" / "foraging.toml"


@pytest.fixture(scope="session")
def cli():
    """The berry-evolve binary: BERRY_EVOLVE_BIN, else target/release/berry-evolve (built with
    `cargo build --release` first, a no-op when it is up to date)."""
    given = os.environ.get("BERRY_EVOLVE_BIN")
    if given:
        return given
    subprocess.run(
        ["cargo", "build", "--release", "--bin", "berry-evolve", "--quiet"],
        cwd=ROOT,
        check=True,
    )
    return str(ROOT / "target" / "release" / "berry-evolve")


@pytest.fixture(scope="session")
def small_foraging(tmp_path_factory):
    """experiments/foraging.toml with a population of 16 (a quick run)."""
    text = FORAGING.read_text().replace("population = 64", "population = 16", 1)
    assert "population = 16" in text
    path = tmp_path_factory.mktemp("exp") / "small-foraging.toml"
    path.write_text(text)
    return path


@pytest.fixture(scope="session")
def run_dir(cli, small_foraging, tmp_path_factory):
    """A 3-generation run of the small foraging experiment, made by the command line."""
    out = tmp_path_factory.mktemp("run") / "seed-1"
    subprocess.run(
        [cli, "run", str(small_foraging), "--generations", "3", "--out", str(out), "-q",
         "--no-estimate", "--no-check"],
        check=True,
    )
    return out
