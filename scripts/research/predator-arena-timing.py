#!/usr/bin/env python3
"""When does a predator-arena creature go into the nest: before the hunt, or when it starts?

Renders every trial of GENOME in EXPERIMENT (berry-evolve render, one SVG per trial), reads
the predator's and the creature's paths from the SVG (one point per tick), and reports per trial:
  wake     the tick the predator first moves (its sleep, [world.predators] asleep), or "-" if
           it sleeps through the trial
  out_pre  share of the ticks before the wake (or of the whole life if it never wakes) the
           creature spent OUTSIDE the nest: foraging while the predator sleeps
  in_post  share of the ticks alive after the wake spent inside the nest
  lat      ticks from the wake to the first tick inside the nest, for a creature outside at
           the wake ("in" if it was already inside; "never" if it did not get in)
  alive    ticks alive
Then the means over trials, split by "outside at the wake" or not.

Nest and arena geometry are read from EXPERIMENT (the first [[world.areas]] region); the SVG
scale is 2.4 px per LU with the arena's corner at (20, 50) px, as berry-evolve render draws it.

Usage: python3 scripts/research/predator-arena-timing.py GENOME EXPERIMENT [GENERATION] [TRIALS]
  (GENERATION default 1099511627777 = the design set; TRIALS default and at most the
   experiment's [evaluation] trials, which render can draw)
Needs BERRY_EVOLVE (default target/release/berry-evolve).
"""
import os
import re
import subprocess
import sys
import tempfile
import tomllib

BIN = os.environ.get("BERRY_EVOLVE", "target/release/berry-evolve")


def points(text):
    return [tuple(float(v) for v in p.split(",")) for p in text.split()]


def main():
    genome, exp = sys.argv[1], sys.argv[2]
    gen = sys.argv[3] if len(sys.argv) > 3 else "1099511627777"
    cfg = tomllib.load(open(exp, "rb"))
    trials = int(sys.argv[4]) if len(sys.argv) > 4 else cfg["evaluation"]["trials"]
    x0, y0, x1, y1 = cfg["world"]["areas"][0]["region"]
    # pixel geometry of berry-evolve render: px = 20 + s*x, py = 50 + s*y
    aw = cfg["world"]["arena"][0]
    s = 720.0 / aw if aw else 2.4
    s = 2.4 if abs(aw - 300.0) < 1e-9 else s
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for t in range(trials):
            svg = os.path.join(tmp, f"t{t}.svg")
            subprocess.run([BIN, "render", genome, "--experiment", exp, "--trial", str(t),
                            "--generation", gen, "-o", svg], check=True, capture_output=True)
            text = open(svg).read()
            pred = points(re.search(r'class="predator-path" points="([^"]*)"', text).group(1))
            i = text.index('class="creature-path"')
            j = text.index("</g>", i)
            segs = [points(p) for p in re.findall(r'<polyline points="([^"]*)"', text[i:j])]
            path = segs[0][:]
            for sg in segs[1:]:
                path += sg[1:]
            inside = [x0 <= (px - 20) / s <= x1 and y0 <= (py - 50) / s <= y1 for px, py in path]
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
    import math
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
