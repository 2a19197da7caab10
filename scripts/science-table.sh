#!/usr/bin/env bash
# The science table (issue 16): for every shipped experiment (not the pure simulator demos,
# open-arena and walled-arena, which say so at their top), run 5 seeds at the file's own
# budget, then print as Markdown, per experiment: the algorithm and budget, the median wall
# time of a run, the median and range of held-out fitness (`compare --trials 20`, or the
# list's fifth column for experiments whose trials are too noisy for 20; worlds evolution
# never saw) and of the behaviour measures, 64 random genomes' median and best, the
# hand-designed baseline, and the ablation (the sense the behaviour needs taken away) with
# its drop.
#
#   bash scripts/science-table.sh                      # every experiment of the lists below
#   bash scripts/science-table.sh --only foraging      # experiments whose file name contains it
#   bash scripts/science-table.sh --runs results/science --seeds "1 2 3"
#
# Runs go to RUNS/<name>/seed-<n>/ (default results/science/, git-ignored) and are reused
# when they exist (delete a folder to re-run it); each run's wall time is kept in wall.txt.
# Runs use --jobs 1 each, JOBS of them side by side (default 2): the wall time is that of one
# run on one core while the other core runs another; a run alone with --jobs 2 is faster.
#
# The experiment lists (one per helper, tab-separated: experiment, ablation, baseline,
# optional behaviour measures to show, optional held-out trials, default 20) are data files,
# so that each helper edits only its own lines. The measures are built-in ones, all from
# compare's JSON: those the experiment's [behaviour] does not name are asked for with
# `compare --measure` (default: the first two the file names).
LISTS=(scripts/science-table.tsv scripts/science-table-design2.tsv)
set -euo pipefail
cd "$(dirname "$0")/.."
RUNS=results/science
SEEDS="1 2 3 4 5"
ONLY=""
JOBS=2
BIN=target/release/berry-evolve
while [ $# -gt 0 ]; do
  case "$1" in
    --runs) RUNS=$2; shift 2 ;;
    --seeds) SEEDS=$2; shift 2 ;;
    --only) ONLY=$2; shift 2 ;;
    --jobs) JOBS=$2; shift 2 ;;
    --bin) BIN=$2; shift 2 ;;
    *) echo "science-table.sh: unknown argument $1 (see the comments at the top)" >&2; exit 2 ;;
  esac
done
[ -x "$BIN" ] || cargo build --release
mkdir -p "$RUNS"

rows() {
  for list in "${LISTS[@]}"; do
    [ -f "$list" ] || continue
    grep -v '^#' "$list" | grep -v '^[[:space:]]*$' || true
  done
}

# 1. The runs, JOBS at a time.
run_one() {
  local exp=$1 seed=$2 name out start end
  name=$(basename "$exp" .toml)
  out=$RUNS/$name/seed-$seed
  [ -f "$out/wall.txt" ] && [ -f "$out/best.json" ] && return 0
  start=$(date +%s.%N)
  "$BIN" run "$exp" --seed "$seed" --out "$out" --jobs 1 --quiet --force
  end=$(date +%s.%N)
  python3 -c "print(f'{$end - $start:.1f}')" > "$out/wall.txt"
}
export -f run_one
export RUNS BIN
while IFS=$'\t' read -r exp _; do
  case "$exp" in *"$ONLY"*) ;; *) continue ;; esac
  for seed in $SEEDS; do echo "$exp $seed"; done
done < <(rows) | xargs -P "$JOBS" -n 2 bash -c 'run_one "$0" "$1"'

# 2. The table.
ROWS=$(rows) RUNS=$RUNS SEEDS=$SEEDS ONLY=$ONLY BIN=$BIN python3 - <<'PY'
import json, os, re, statistics, subprocess, sys

runs, seeds, only, binary = (os.environ[k] for k in ("RUNS", "SEEDS", "ONLY", "BIN"))
seeds = seeds.split()


def compare(experiment, genomes, random, trials, keys):
    """Held-out fitness of each genome file, its behaviour measures (the file's own and
    `keys`), and the random genomes' (median, best)."""
    extra = ["--measure", ",".join(keys)] if keys else []
    out = subprocess.run([binary, "compare", *genomes, "--experiment", experiment,
                          "--trials", str(trials), "--random", str(random), *extra, "--json"],
                         capture_output=True, text=True, check=True).stdout
    report = json.loads(out)
    fit = {g["path"]: nan_if_none(g["fitness"]) for g in report["genomes"]}
    # The measures, each averaged over the genome's trials.
    measures = {g["path"]: {k: nan_if_none(v) for k, v in g["measures"].items()}
                for g in report["genomes"]}
    rnd = None
    if report["random"]:
        stats = report["random"]["fitness"]
        rnd = (stats["median"], stats["best"])
    return fit, rnd, measures


def nan_if_none(x):
    return float("nan") if x is None else x


def med_range(values):
    if not values:
        return "n/a"
    return f"{statistics.median(values):.2f} ({min(values):.2f}–{max(values):.2f})"


def workload(experiment):
    out = subprocess.run([binary, "inspect", experiment, "--json", "--no-estimate"],
                         capture_output=True, text=True, check=True).stdout
    d = json.loads(out)
    w = d["workload"]
    population = w["individuals"] - (1 if d["algorithm"] == "pgpe" else 0)
    return f"{d['algorithm']} {population}×{w['generations']}×{w['trials']}×{w['ticks']}"


print("| experiment | algorithm, pop×gens×trials×ticks | wall (s, median) | held-out fitness, "
      "median (range) | behaviour, median (range) | random 64: median / best | baseline: "
      "fitness; behaviour | ablation: champions' median (drop); behaviour | bar met |")
print("|---|---|---|---|---|---|---|---|---|")
for line in os.environ["ROWS"].splitlines():
    cols = line.rstrip("\n").split("\t")
    exp, abl, base = cols[:3]
    keys = cols[3].split(",") if len(cols) > 3 and cols[3] else None
    trials = int(cols[4]) if len(cols) > 4 and cols[4] else 20
    if only not in exp:
        continue
    name = os.path.basename(exp)[:-5]
    champs = [f"{runs}/{name}/seed-{s}/best.json" for s in seeds]
    champs = [c for c in champs if os.path.exists(c)]
    if not champs:
        print(f"| {name} | {workload(exp)} | no runs | | | | | | |")
        continue
    walls = [float(open(os.path.join(os.path.dirname(c), "wall.txt")).read())
             for c in champs if os.path.exists(os.path.join(os.path.dirname(c), "wall.txt"))]
    have_base = os.path.exists(base)
    fit, rnd, beh = compare(exp, champs + ([base] if have_base else []), 64, trials, keys)
    if keys is None:
        keys = list(next(iter(beh.values())))[:2]
    held = [fit[c] for c in champs]
    bcol = "; ".join(f"{k} {med_range([beh[c][k] for c in champs if k in beh.get(c, {})])}"
                     for k in keys)
    if have_base:
        bb = beh.get(base, {})
        base_col = f"{fit[base]:.2f}; " + ", ".join(f"{k} {bb.get(k, float('nan')):.2f}"
                                                 for k in keys)
    else:
        base_col = "none"
    if os.path.exists(abl):
        afit, _, abeh = compare(abl, champs, 0, trials, keys)
        amed = statistics.median(afit[c] for c in champs)
        acol = (f"{amed:.2f} ({amed - statistics.median(held):+.2f}); "
                + ", ".join(f"{k} {statistics.median([abeh[c][k] for c in champs]):.2f}"
                            for k in keys))
    else:
        acol = "none"
    ok = statistics.median(held) > max(rnd[1] if rnd else float("-inf"),
                                       fit[base] if have_base else float("-inf"))
    wall = f"{statistics.median(walls):.0f}" if walls else "n/a"
    print(f"| {name} | {workload(exp)} | {wall} | {med_range(held)} (n={len(held)}, {trials} worlds) | {bcol} | "
          f"{rnd[0]:.2f} / {rnd[1]:.2f} | {base_col} | {acol} | {'yes' if ok else 'no'} |")
PY
