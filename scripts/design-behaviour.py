#!/usr/bin/env python3
"""Behaviour measures of a genome on held-out worlds, for the design helper's experiments
(foraging, crowded-arena, shock-avoidance, eye-arena, balanced-diet).

Until the `measures` branch reports behaviour measures itself, this replays a genome on the
held-out worlds that `berry-evolve compare` uses (`--worlds held-out`), reads the per-tick trace
(`replay --trace`) and computes, as means over the trials:

  eaten           substance eaten (sum of the metabolic vector at the end; no decay here)
  distinct_food   distinct eating sites: ticks on which the metabolism rose, at places more
                  than 6 LU from every earlier such place (a food object is 2 LU in radius,
                  a body 3), i.e. about the number of different food objects eaten from
  food_types      food types eaten from (components of m above 0 at the end)
  min_component   the smallest component of m at the end (what balance = "min" scores)
  shocked_ticks   ticks with the shock sensor on
  still_share     share of ticks on which the creature moved less than 0.05 LU (parking)

With --plot FILE.png it draws the paths of the first trials, eating sites as dots.

Usage: python3 scripts/design-behaviour.py EXPERIMENT.toml GENOME.json... [--trials 20]
       [--plot out.png] [--bin target/release/berry-evolve]
"""
import argparse
import csv
import json
import math
import os
import re
import subprocess
import sys
import tempfile
import tomllib


def trace(binary, experiment, genome, trials):
    """Replays `genome` on `trials` held-out worlds; returns one list of rows per trial and
    the trials' scores."""
    text = open(experiment).read()
    # A copy with `trials` trials: held-out world k depends only on the seed and k, so these
    # are compare's held-out worlds.
    # (Only the [evaluation] table's: [validation] has a `trials` key too.)
    start = text.find("[evaluation]")
    head, tail = text[:start], text[start:]
    tail, n = re.subn(r"(?m)^trials\s*=\s*\d+", f"trials = {trials}", tail, count=1)
    if start < 0 or n != 1:
        sys.exit(f"{experiment}: expected a `trials = N` line in [evaluation]")
    text = head + tail
    with tempfile.TemporaryDirectory() as tmp:
        exp = os.path.join(tmp, "experiment.toml")
        open(exp, "w").write(text)
        out = os.path.join(tmp, "trace.csv")
        res = subprocess.run([binary, "replay", "--experiment", exp, genome, "--worlds",
                              "held-out", "--trace", out, "--json"],
                             capture_output=True, text=True, check=True)
        # replay --json: one document whose trials carry their scores (null: not finite).
        scores = [float("nan") if t["score"] is None else t["score"]
                  for t in json.loads(res.stdout)["trials"]]
        runs, cur, last = [], [], 0
        with open(out) as f:
            for row in csv.DictReader(f):
                t = int(row["tick"])
                if t <= last and cur:
                    runs.append(cur)
                    cur = []
                last = t
                cur.append({k: float(v) for k, v in row.items()})
        if cur:
            runs.append(cur)
    return runs, scores


def measures(runs):
    keys = ["eaten", "distinct_food", "food_types", "min_component", "shocked_ticks",
            "still_share"]
    total = {k: 0.0 for k in keys}
    for r in runs:
        sites, prev_m, prev_xy, still = [], 0.0, None, 0
        for row in r:
            m = row["m_a"] + row["m_b"] + row["m_c"] + row["m_d"]
            xy = (row["x"], row["y"])
            if m > prev_m + 1e-12 and all(math.dist(xy, s) > 6.0 for s in sites):
                sites.append(xy)
            if prev_xy is not None and math.dist(xy, prev_xy) < 0.05:
                still += 1
            prev_m, prev_xy = m, xy
        end = r[-1]
        comps = [end["m_a"], end["m_b"], end["m_c"], end["m_d"]]
        total["eaten"] += sum(comps)
        total["distinct_food"] += len(sites)
        total["food_types"] += sum(1 for c in comps if c > 0)
        total["min_component"] += min(comps)
        total["shocked_ticks"] += sum(row["shock"] for row in r)
        total["still_share"] += still / len(r)
    return {k: v / len(runs) for k, v in total.items()}


def plot(spec, runs, path, count):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    w, h = spec["world"]["arena"]
    n = min(count, len(runs))
    cols = min(n, 3)
    rows = (n + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(4 * cols, 4 * rows), squeeze=False)
    for k in range(rows * cols):
        ax = axes[k // cols][k % cols]
        ax.set_xlim(0, w)
        ax.set_ylim(h, 0)
        ax.set_aspect("equal")
        if k >= n:
            ax.axis("off")
            continue
        for wall in spec["world"].get("walls", []):
            ax.plot([wall["from"][0], wall["to"][0]], [wall["from"][1], wall["to"][1]], "k-")
        for o in spec["world"].get("objects", []):
            kind = spec["world"]["kinds"][o["kind"]]
            ax.plot(*o["position"], "o", color="red" if kind["class"] == "aversive"
                    else "green", ms=3)
        r = runs[k]
        ax.plot([q["x"] for q in r], [q["y"] for q in r], "b-", lw=0.6)
        prev = 0.0
        for q in r:
            m = q["m_a"] + q["m_b"] + q["m_c"] + q["m_d"]
            if m > prev + 1e-12:
                ax.plot(q["x"], q["y"], ".", color="orange", ms=3)
            if q["shock"] > 0:
                ax.plot(q["x"], q["y"], "x", color="red", ms=3)
            prev = m
        ax.plot(r[0]["x"], r[0]["y"], "ks", ms=4)
        ax.set_title(f"held-out trial {k}", fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=80)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("experiment")
    ap.add_argument("genomes", nargs="+")
    ap.add_argument("--trials", type=int, default=20)
    ap.add_argument("--plot")
    ap.add_argument("--plot-trials", type=int, default=6)
    ap.add_argument("--bin", default="target/release/berry-evolve")
    a = ap.parse_args()
    spec = tomllib.load(open(a.experiment, "rb"))
    for g in a.genomes:
        runs, scores = trace(a.bin, a.experiment, g, a.trials)
        m = measures(runs)
        mean = sum(scores) / len(scores)
        print(g, f"fitness {mean:.3f}", " ".join(f"{k} {v:.3f}" for k, v in m.items()))
        if a.plot:
            plot(spec, runs, a.plot, a.plot_trials)


if __name__ == "__main__":
    main()
