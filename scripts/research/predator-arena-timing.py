#!/usr/bin/env python3
"""When does a predator-arena creature go into the nest: before the hunt, or when it starts?

Replays GENOME on EXPERIMENT's worlds of GENERATION with a trace (`berry-evolve replay
--trace`, see docs/replay-and-traces.md), reads the predator's and the creature's positions
per tick from it (trace-actors.csv, trace.csv, and their start poses from trace-world.jsonl),
and reports per trial:
  wake     the tick the predator first moves (its sleep, [world.predators] asleep), or "-" if
           it sleeps through the trial
  out_pre  share of the ticks before the wake (or of the whole life if it never wakes) the
           creature spent OUTSIDE the nest: foraging while the predator sleeps
  in_post  share of the ticks alive after the wake spent inside the nest
  lat      ticks from the wake to the first tick inside the nest, for a creature outside at
           the wake ("in" if it was already inside; "never" if it did not get in)
  alive    ticks in the trace (the tick of a death included)
Then the means over trials, split by "outside at the wake" or not. The nest is the world's
first area (trace-world.jsonl's `areas`); positions count from the start (tick 0).

Usage: python3 scripts/research/predator-arena-timing.py GENOME EXPERIMENT [GENERATION] [TRIALS]
  (GENERATION default 1099511627777 = the design set; TRIALS default and at most the
   experiment's [evaluation] trials)
Needs BERRY_EVOLVE (default target/release/berry-evolve).
"""
import csv
import json
import math
import os
import subprocess
import sys
import tempfile

BIN = os.environ.get("BERRY_EVOLVE", "target/release/berry-evolve")


def paths(genome, exp, gen):
    """Per trial: (the creature's positions, the predator's positions, the nest (lo, hi)),
    each path from the start (tick 0) to the trace's last tick."""
    with tempfile.TemporaryDirectory() as tmp:
        trace = os.path.join(tmp, "trace.csv")
        subprocess.run([BIN, "replay", genome, "--experiment", exp, "--generation", gen,
                        "--trace", trace], check=True, capture_output=True)
        stem = trace[:-len(".csv")]
        worlds = {}
        with open(stem + "-world.jsonl") as f:
            for line in f:
                w = json.loads(line)
                predator = next(a for a in w["actors"] if a["role"] == "predator")
                area = w["areas"][0]
                worlds[w["trial"]] = ([tuple(w["creatures"][0]["position"])],
                                      [tuple(predator["start"]["position"])],
                                      (area["lo"], area["hi"]))
        with open(trace) as f:
            for row in csv.DictReader(f):
                if row["creature"] == "0":
                    worlds[int(row["trial"])][0].append((float(row["x"]), float(row["y"])))
        # The first predator of each trial (actors are numbered per kind).
        with open(stem + "-actors.csv") as f:
            for row in csv.DictReader(f):
                if row["kind"] == "predator" and row["index"] == "0":
                    worlds[int(row["trial"])][1].append((float(row["x"]), float(row["y"])))
    return worlds


def main():
    genome, exp = sys.argv[1], sys.argv[2]
    gen = sys.argv[3] if len(sys.argv) > 3 else "1099511627777"
    worlds = paths(genome, exp, gen)
    trials = int(sys.argv[4]) if len(sys.argv) > 4 else len(worlds)
    rows = []
    for t in range(min(trials, len(worlds))):
        path, pred, ((x0, y0), (x1, y1)) = worlds[t]
        inside = [x0 <= x <= x1 and y0 <= y <= y1 for x, y in path]
        wake = next((k for k in range(1, len(pred)) if pred[k] != pred[0]), None)
        alive = len(path) - 1
        pre = inside[: (wake if wake is not None else len(inside))]
        out_pre = (sum(1 for v in pre if not v) / len(pre)) if pre else float("nan")
        if wake is not None and wake < len(inside):
            post = inside[wake:]
            in_post = sum(post) / len(post)
            if inside[wake]:
                lat = "in"
            else:
                lat = next((str(k - wake) for k in range(wake, len(inside)) if inside[k]),
                           "never")
        else:
            in_post, lat = float("nan"), "-"
        rows.append((t, wake, out_pre, in_post, lat, alive))
    print("trial wake out_pre in_post lat alive")
    for t, wake, op, ip, lat, alive in rows:
        print(f"{t:5d} {wake if wake is not None else '-':>4} {op:7.2f} {ip:7.2f} {lat:>5} {alive:5d}")

    def mean(v):
        v = [x for x in v if not math.isnan(x)]
        return sum(v) / len(v) if v else float("nan")
    woke = [r for r in rows if r[1] is not None and r[1] < r[5] + 1]
    outside = [r for r in woke if r[4] not in ("in", "-")]
    lats = sorted(int(r[4]) for r in outside if r[4] != "never")
    print(f"mean out_pre {mean([r[2] for r in rows]):.2f} (share of the pre-hunt ticks outside the nest)")
    print(f"mean in_post {mean([r[3] for r in woke]):.2f} over {len(woke)} trials with a hunt")
    print(f"outside at the wake: {len(outside)} trials, got in: {len(lats)}, "
          f"median latency {lats[len(lats)//2] if lats else '-'} ticks; "
          f"inside at the wake: {sum(1 for r in woke if r[4] == 'in')}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
