#!/usr/bin/env python3
"""Behaviour measures of a genome on held-out worlds, for the design2 experiments.

Until the `measures` branch reports behaviour measures itself, this replays a genome on the
held-out worlds that `berry-evolve compare` uses (`--worlds held-out`), reads the per-tick trace
(`replay --trace`) and computes each experiment's behaviour measure from the creature's path:

  t-maze          goal box reached (share of trials), rewarded arm entered first (share)
  locked-room     trigger touched (door opened), room entered, food eaten inside (shares)
  predator-arena  ticks survived (mean), share of trials alive at the end, share of ticks in nest
  air-raid        ticks survived (mean), share alive at the end, share of ticks sheltered
  landmark-arena  food patch reached (share), share of ticks in the patch

With --plot FILE.png it draws the paths of the first trials over the experiment's walls.

Usage: python3 scripts/design2-behaviour.py EXPERIMENT.toml GENOME.json [--trials 20]
       [--plot out.png] [--bin target/release/berry-evolve]
"""
import argparse
import csv
import json
import os
import re
import subprocess
import sys
import tempfile
import tomllib


def in_region(x, y, r, pad=0.0):
    return r[0] - pad <= x <= r[2] + pad and r[1] - pad <= y <= r[3] + pad


def trace(binary, experiment, genome, trials, seed=None):
    """Replays `genome` on `trials` held-out worlds; returns one list of rows per trial."""
    text = open(experiment).read()
    # A copy of the experiment with `trials` trials: held-out world k depends only on the
    # seed and k, so these are compare's held-out worlds.
    # Only [evaluation]'s `trials` ([validation] has one too).
    text, n = re.subn(r"(?ms)^(\[evaluation\][^\[]*?^)trials\s*=\s*\d+",
                      lambda m: m.group(1) + f"trials = {trials}", text)
    if n != 1:
        sys.exit(f"{experiment}: expected one `trials = N` line in [evaluation]")
    with tempfile.TemporaryDirectory() as tmp:
        exp = os.path.join(tmp, "experiment.toml")
        open(exp, "w").write(text)
        out = os.path.join(tmp, "trace.csv")
        cmd = [binary, "replay", "--experiment", exp, genome, "--worlds", "held-out",
               "--trace", out, "--json"]
        if seed is not None:
            cmd += ["--seed", str(seed)]
        res = subprocess.run(cmd, capture_output=True, text=True, check=True)
        # replay --json: one document whose trials carry their scores (null: not finite).
        fitness = [float("nan") if t["score"] is None else t["score"]
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
    return runs, fitness


def tmaze(spec, runs, ticks):
    reached = first_right = 0
    for r in runs:
        first_arm, eaten_arm = None, None
        for i, row in enumerate(r):
            x, y = row["x"], row["y"]
            if y < 120 and first_arm is None and (x < 125 or x > 175):
                first_arm = "L" if x < 150 else "R"
            if i > 0 and row["m_a"] > r[i - 1]["m_a"] + 0.2 and y < 120 and eaten_arm is None:
                eaten_arm = "L" if x < 150 else "R"
        reached += eaten_arm is not None
        first_right += eaten_arm is not None and first_arm == eaten_arm
    n = len(runs)
    return {"goal_reached": reached / n, "rewarded_arm_first": first_right / n}


def locked(spec, runs, ticks):
    door = spec["world"]["doors"][0]
    tx, ty = door["trigger"]
    reach = door["trigger_radius"] + spec["creature"].get("diameter", 6.0) / 2
    trig = entered = ate = 0
    for r in runs:
        t = any((row["x"] - tx) ** 2 + (row["y"] - ty) ** 2 <= reach ** 2 for row in r)
        e = any(row["x"] > 180 and row["y"] < 120 for row in r)
        a = any(r[i]["m_a"] > r[i - 1]["m_a"] and r[i]["x"] > 180 and r[i]["y"] < 120
                for i in range(1, len(r)))
        trig, entered, ate = trig + t, entered + e, ate + a
    n = len(runs)
    return {"door_opened": trig / n, "room_entered": entered / n, "ate_inside": ate / n}


def survival(spec, runs, ticks, key):
    safe = [a["region"] for a in spec["world"].get("areas", []) if a.get("kind") == "safe"]
    alive_end = sum(1 for r in runs if len(r) >= ticks and r[-1]["alive"] == 1)
    lived = [len(r) if r[-1]["alive"] == 1 else len(r) - 1 for r in runs]
    in_safe = sum(sum(1 for row in r if any(in_region(row["x"], row["y"], s) for s in safe))
                  for r in runs)
    n = len(runs)
    return {"ticks_survived": sum(lived) / n, "alive_at_end": alive_end / n,
            key: in_safe / max(1, sum(len(r) for r in runs))}


def landmark(spec, runs, ticks):
    patch = [a["region"] for a in spec["world"]["areas"] if a.get("kind", "plain") == "plain"][0]
    reached = sum(1 for r in runs if any(in_region(row["x"], row["y"], patch) for row in r))
    inside = sum(sum(1 for row in r if in_region(row["x"], row["y"], patch)) for r in runs)
    n = len(runs)
    return {"patch_reached": reached / n,
            "ticks_in_patch": inside / max(1, sum(len(r) for r in runs))}


MEASURES = {
    "t-maze": tmaze,
    "locked-room": locked,
    "predator-arena": lambda s, r, t: survival(s, r, t, "share_in_nest"),
    "air-raid": lambda s, r, t: survival(s, r, t, "share_sheltered"),
    "landmark-arena": landmark,
}


def plot(spec, runs, path, count):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    w, h = spec["world"]["arena"]
    fig, ax = plt.subplots(figsize=(6, 6))
    for wall in spec["world"].get("walls", []):
        ax.plot([wall["from"][0], wall["to"][0]], [wall["from"][1], wall["to"][1]], "k-", lw=2)
    for d in spec["world"].get("doors", []):
        ax.plot([d["from"][0], d["to"][0]], [d["from"][1], d["to"][1]], "-", c="brown", lw=3)
        ax.add_patch(plt.Circle(d["trigger"], d["trigger_radius"], color="orange", alpha=0.5))
    for a in spec["world"].get("areas", []):
        r = a["region"]
        ax.add_patch(plt.Rectangle((r[0], r[1]), r[2] - r[0], r[3] - r[1],
                                   color="green" if a.get("kind") == "safe" else "yellow",
                                   alpha=0.2))
    for o in spec["world"].get("objects", []):
        ax.plot(*o["position"], "g.", ms=6)
    for p in spec["world"].get("predators", []):
        ax.plot(*p["start"], "rx", ms=10)
    colours = plt.cm.tab10.colors
    for k, r in enumerate(runs[:count]):
        xs, ys = [row["x"] for row in r], [row["y"] for row in r]
        ax.plot(xs, ys, "-", c=colours[k % 10], lw=0.8)
        ax.plot(xs[0], ys[0], "o", c=colours[k % 10], ms=4)
        if r[-1]["alive"] == 0:
            ax.plot(xs[-1], ys[-1], "x", c=colours[k % 10], ms=8)
    ax.set_xlim(0, w)
    ax.set_ylim(h, 0)
    ax.set_aspect("equal")
    ax.set_title(f"{spec['name']}: {count} held-out trials (o start, x death)")
    fig.savefig(path, dpi=80)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("experiment")
    ap.add_argument("genomes", nargs="+")
    ap.add_argument("--trials", type=int, default=20)
    ap.add_argument("--plot")
    ap.add_argument("--plot-trials", type=int, default=6)
    ap.add_argument("--seed", type=int)
    ap.add_argument("--bin", default="target/release/berry-evolve")
    a = ap.parse_args()
    spec = tomllib.load(open(a.experiment, "rb"))
    ticks = spec["evaluation"]["ticks"]
    measure = MEASURES[spec["name"]]
    for g in a.genomes:
        runs, fitness = trace(a.bin, a.experiment, g, a.trials, a.seed)
        m = measure(spec, runs, ticks)
        mean = sum(fitness) / len(fitness)
        print(g, f"fitness {mean:.3f}", " ".join(f"{k} {v:.3f}" for k, v in m.items()))
        if a.plot:
            plot(spec, runs, a.plot, a.plot_trials)


if __name__ == "__main__":
    main()
