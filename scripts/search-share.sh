#!/usr/bin/env bash
# The search's share of a generation (issue 30: under 2% for the GA, PGPE, novelty search and
# MAP-Elites with populations of 64-256 and up to 15,000 parameters) and CMA-ES's cost per
# generation at 50, 500 and 2,000 parameters, from `berry-evolve bench --json`.
#
#   bash scripts/search-share.sh                 # prints a Markdown table
#   bash scripts/search-share.sh --generations 10   # default 6: generation 0's random draw
#                                                 # counts once, as in a run it is amortised
#   bash scripts/search-share.sh --draw-order 2     # `[evolution] draw_order = 2` in every
#                                                 # case (offspring in parallel, two chances a
#                                                 # draw, one word a normal: for large brains)
#
# Each case is experiments/foraging.toml with the algorithm, the population and the hidden
# layer (24 -> h -> 2: 27h + 2 parameters, h = 0 for 50) changed, written to a temporary
# folder; `bench` times ask, tell and the generation's summary against the evaluation, on 1
# and 2 threads (the share printed is the 2-thread one, where evaluation is fastest and the
# share therefore largest).
set -euo pipefail
cd "$(dirname "$0")/.."
GENERATIONS=6
DRAW_ORDER=1
BIN=target/release/berry-evolve
while [ $# -gt 0 ]; do
  case "$1" in
    --generations) GENERATIONS=$2; shift 2 ;;
    --bin) BIN=$2; shift 2 ;;
    --draw-order) DRAW_ORDER=$2; shift 2 ;;
    *) echo "search-share.sh: unknown argument $1 (see the comments at the top)" >&2; exit 2 ;;
  esac
done
[ -x "$BIN" ] || cargo build --release
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT

BIN=$BIN TMP=$TMP GENERATIONS=$GENERATIONS DRAW_ORDER=$DRAW_ORDER python3 - <<'PY'
import json, os, re, subprocess

binary, tmp, generations = os.environ["BIN"], os.environ["TMP"], os.environ["GENERATIONS"]
draw_order = os.environ["DRAW_ORDER"]
base = open("experiments/foraging.toml").read()
base = base[base.index('name = "foraging"'):]
base = re.sub(r"\[output\][^\[]*$", "", base)

TABLES = {
    "ga": "",
    "pgpe": "",
    "sep-cma-es": "",
    "cma-es": "",
    "novelty": """
[evolution.novelty]
descriptors = [
    { measure = "distinct_food", min = 0.0, max = 20.0 },
    { measure = "food_types", min = 0.0, max = 4.0 },
]
""",
    "map-elites": """
[evolution.map_elites]
descriptors = [
    { measure = "distinct_food", min = 0.0, max = 20.0, bins = 20 },
    { measure = "food_types", min = 0.0, max = 4.0, bins = 5 },
]
""",
}


GA_ONLY = re.compile(r"elitism = \d+\n|\[evolution\.(selection|crossover|mutation)\]\n[^\[]*")


def case(algorithm, population, hidden):
    text = base if algorithm in ("ga", "novelty") else GA_ONLY.sub("", base)
    if algorithm == "map-elites":
        text = text.replace("\ninit_range", "\n#init_range").replace("\n#init_range", "\ninit_range")
    text = text.replace("population = 64", f"population = {population}")
    text = text.replace("hidden = []", f"hidden = [{hidden}]" if hidden else "hidden = []")
    text = text.replace("[evolution]\n", f'[evolution]\nalgorithm = "{algorithm}"\n', 1)
    if draw_order != "1":
        text = text.replace("[evolution]\n", f"[evolution]\ndraw_order = {draw_order}\n", 1)
    text = text.replace("[evaluation]\n", TABLES[algorithm].lstrip("\n") + "\n[evaluation]\n", 1)
    path = os.path.join(tmp, f"{algorithm}-{population}-{hidden}.toml")
    open(path, "w").write(text)
    out = subprocess.run([binary, "bench", "--evolution", path, "--generations", generations,
                          "--scaling", "0", "--worlds", "16", "--ticks", "10", "--json"],
                         capture_output=True, text=True)
    if out.returncode != 0:
        return None, out.stderr.strip().splitlines()[-1]
    evolution = json.loads(out.stdout)["evolution"]
    two = evolution["threads"][-1]
    seconds = 1.0 / two["generations_per_second"]
    return (two["search_share_percent"], 1000.0 * seconds * two["search_share_percent"] / 100), None


print(f"| algorithm | population | parameters | search share (2 threads, draw order {draw_order}) | search ms a generation |")
print("|---|---|---|---|---|")
cases = [(a, p, h) for a in ("ga", "pgpe", "novelty", "map-elites", "sep-cma-es")
         for p in (64, 256) for h in (0, 555)]
cases += [("cma-es", 64, h) for h in (0, 18, 74)]
for algorithm, population, hidden in cases:
    parameters = 27 * hidden + 2 if hidden else 50
    result, error = case(algorithm, population, hidden)
    if result is None:
        print(f"| {algorithm} | {population} | {parameters} | failed: {error} | |")
    else:
        share, ms = result
        print(f"| {algorithm} | {population} | {parameters} | {share:.2f}% | {ms:.1f} |")
PY
