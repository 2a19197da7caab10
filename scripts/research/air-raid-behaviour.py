#!/usr/bin/env python3
"""Does a genome shelter WHEN a raider comes (experiments/air-raid.toml)? For each genome:

  compare --json --trials 20 (held-out worlds unless --generation): fitness, the [behaviour]
    measures, and the share of the trials with a strike (the creature died, or a raider passed
    within its strike radius while it was in the shelter) in which it lived through at least one
    strike in the shelter (strikes_survived > 0);
  replay --trace on the same generation's worlds (the experiment's own trial count): per tick,
    is the raider smelled (it is smelled only while in flight, within its range) and is the
    creature in the shelter (area input): P(in shelter | raider smelled), P(in shelter | quiet),
    entries into the shelter while a raider is smelled and exits from it, per trial.

A creature that shelters when raided and forages in the quiet spells has P(in | raider) high,
P(in | quiet) low, about one entry and one exit per raid.

Usage: python3 scripts/research/air-raid-behaviour.py EXPERIMENT.toml GENOME... [--generation G]
       [--binary BIN] [--trials 20]
"""
import argparse
import collections
import csv
import json
import os
import subprocess
import sys
import tempfile


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("experiment")
    ap.add_argument("genomes", nargs="+")
    ap.add_argument("--generation", default=None, help="default: compare's held-out worlds (--worlds held-out)")
    ap.add_argument("--binary", default=os.environ.get("BERRY_EVOLVE", "target/release/berry-evolve"))
    ap.add_argument("--trials", type=int, default=20)
    a = ap.parse_args()
    gen = ["--generation", a.generation] if a.generation else []
    # replay's default is the genome's own generation: name compare's worlds explicitly.
    worlds = gen or ["--worlds", "held-out"]
    out = subprocess.run([a.binary, "compare", *a.genomes, "--experiment", a.experiment,
                          "--trials", str(a.trials), "--random", "0", "--json", *gen],
                         capture_output=True, text=True, check=True).stdout
    doc = json.loads(out)
    ticks = doc["ticks"]
    tmp = tempfile.mkdtemp(prefix="air-raid-behaviour-")
    for g in doc["genomes"]:
        strike = [t for t in g["trials"]
                  if t["measures"]["ticks_alive"] < ticks or t["measures"]["strikes_survived"] > 0]
        survived = [t for t in strike if t["measures"]["strikes_survived"] > 0]
        m = " ".join(f"{k} {v:.3f}" for k, v in g["measures"].items())
        stem = os.path.join(tmp, "trace")
        subprocess.run([a.binary, "replay", g["path"], "--experiment", a.experiment,
                        *worlds, "--trace", stem + ".csv"],
                       capture_output=True, check=True)
        per = collections.defaultdict(list)
        for r in csv.DictReader(open(stem + ".csv")):
            per[int(r["trial"])].append(r)
        n = collections.Counter()
        entries = exits = 0
        for rows in per.values():
            was_in = None
            for r in rows:
                if r["alive"] != "1":
                    break
                raid = float(r["in_smell_left_7"]) + float(r["in_smell_right_7"]) > 0
                inside = any(float(v) > 0 for k, v in r.items() if k.startswith("in_area_"))
                n[(raid, inside)] += 1
                if was_in is not None and inside and not was_in and raid:
                    entries += 1
                if was_in and not inside:
                    exits += 1
                was_in = inside
        p_raid = n[(True, True)] / max(1, n[(True, True)] + n[(True, False)])
        p_quiet = n[(False, True)] / max(1, n[(False, True)] + n[(False, False)])
        k = max(1, len(per))
        print(f"{g['path']} fitness {g['fitness']:.1f} {m} "
              f"strike_trials {len(strike)} survived_a_strike {len(survived)} "
              f"p_in_raid {p_raid:.3f} p_in_quiet {p_quiet:.3f} "
              f"entries_in_raid_per_trial {entries / k:.2f} exits_per_trial {exits / k:.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
