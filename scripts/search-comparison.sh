#!/usr/bin/env bash
# The search comparison (issue 30): the experiments of experiments/search/ that share a name
# (foraging-plain, foraging-plain-pgpe, ...: one world, brain, fitness and budget, a different
# [evolution]) run 5 seeds each; every champion (best.json, chosen on validation worlds) is
# then scored on the same held-out worlds (`compare --worlds held-out`, the family's first
# file's seed), and the table gives per algorithm the median and quartiles of held-out fitness,
# the behaviour measures, the two-sided exact Mann-Whitney U test against the GA's champions
# (the file without a suffix), the evaluations per run and the median wall time of a run.
#
#   bash scripts/search-comparison.sh                          # every family below
#   bash scripts/search-comparison.sh --only foraging-plain    # one family
#   bash scripts/search-comparison.sh --seeds "1 2 3" --runs results/search
#   bash scripts/search-comparison.sh --files map-elites    # run only the files matching it
#
# Runs go to RUNS/<file name>/seed-<n>/ (default results/search/, git-ignored) and are reused
# when they hold best.json and wall.txt; runs use --jobs 1, JOBS side by side (default 2), so
# a wall time is one run on one core while the other core runs another.
set -euo pipefail
cd "$(dirname "$0")/.."
RUNS=results/search
SEEDS="1 2 3 4 5"
ONLY=""
FILES=""
JOBS=2
TRIALS=20
BIN=target/release/berry-evolve
# family, its files (the GA first), the hand-designed baseline (or -), the measures to show.
FAMILIES=(
  "foraging-plain|experiments/search/foraging-plain.toml experiments/search/foraging-plain-pgpe.toml experiments/search/foraging-plain-cma-es.toml experiments/search/foraging-plain-novelty.toml experiments/search/foraging-plain-map-elites.toml|genomes/braitenberg-forager.json|forward_share,distinct_food,path_length"
  "predator-arena-no-beacon|experiments/search/predator-arena-no-beacon.toml experiments/search/predator-arena-no-beacon-novelty.toml experiments/search/predator-arena-no-beacon-map-elites.toml|-|shelter_while_threat,ticks_alive,distinct_food"
)
while [ $# -gt 0 ]; do
  case "$1" in
    --runs) RUNS=$2; shift 2 ;;
    --seeds) SEEDS=$2; shift 2 ;;
    --only) ONLY=$2; shift 2 ;;
    --files) FILES=$2; shift 2 ;;
    --jobs) JOBS=$2; shift 2 ;;
    --trials) TRIALS=$2; shift 2 ;;
    --bin) BIN=$2; shift 2 ;;
    *) echo "search-comparison.sh: unknown argument $1 (see the comments at the top)" >&2; exit 2 ;;
  esac
done
[ -x "$BIN" ] || cargo build --release
mkdir -p "$RUNS"

run_one() {
  local exp=$1 seed=$2 name out start end
  name=$(basename "$exp" .toml)
  out=$RUNS/$name/seed-$seed
  [ -f "$exp" ] || return 0
  [ -f "$out/wall.txt" ] && [ -f "$out/best.json" ] && return 0
  # wall.txt: the run's wall time and its CPU time (user + system) in seconds; on a shared
  # machine the CPU time is the fairer figure.
  python3 - "$BIN" "$exp" "$seed" "$out" <<'TIME'
import resource, subprocess, sys, time
binary, exp, seed, out = sys.argv[1:]
start = time.monotonic()
subprocess.run([binary, "run", exp, "--seed", seed, "--out", out, "--jobs", "1", "--quiet",
                "--force", "--no-check"], check=True)
wall = time.monotonic() - start
usage = resource.getrusage(resource.RUSAGE_CHILDREN)
open(f"{out}/wall.txt", "w").write(f"{wall:.1f} {usage.ru_utime + usage.ru_stime:.1f}\n")
TIME
}
export -f run_one
export RUNS BIN
for family in "${FAMILIES[@]}"; do
  IFS='|' read -r fname files _ _ <<< "$family"
  case "$fname" in *"$ONLY"*) ;; *) continue ;; esac
  for exp in $files; do
    case "$exp" in *"$FILES"*) ;; *) continue ;; esac
    for seed in $SEEDS; do echo "$exp $seed"; done
  done
done | xargs -P "$JOBS" -n 2 bash -c 'run_one "$0" "$1"'

FAMILIES_TEXT=$(printf '%s\n' "${FAMILIES[@]}") RUNS=$RUNS SEEDS=$SEEDS ONLY=$ONLY BIN=$BIN \
TRIALS=$TRIALS python3 - <<'PY'
import itertools, json, os, statistics, subprocess

runs, seeds, only, binary = (os.environ[k] for k in ("RUNS", "SEEDS", "ONLY", "BIN"))
trials = os.environ["TRIALS"]
seeds = seeds.split()


def quartiles(values):
    """Median and the first and third quartiles (the medians of the lower and upper halves)."""
    v = sorted(values)
    n = len(v)
    half = n // 2
    low, high = v[:half], v[(n + 1) // 2:]
    return (statistics.median(v), statistics.median(low) if low else v[0],
            statistics.median(high) if high else v[-1])


def mann_whitney(a, b):
    """U of `a` against `b` and the exact two-sided p value: the share of all ways to split
    the pooled values into groups of len(a) and len(b) whose U is at least as far from its
    mean (ties share their mid-rank)."""
    pooled = sorted(a + b)
    def rank(x):
        first = pooled.index(x) + 1
        last = len(pooled) - pooled[::-1].index(x)
        return (first + last) / 2
    ranks = [rank(x) for x in a + b]
    n1, n2 = len(a), len(b)
    def u_of(idx):
        return sum(ranks[i] for i in idx) - n1 * (n1 + 1) / 2
    u = u_of(range(n1))
    centre = n1 * n2 / 2
    splits = list(itertools.combinations(range(n1 + n2), n1))
    extreme = sum(1 for s in splits if abs(u_of(s) - centre) >= abs(u - centre) - 1e-9)
    return u, extreme / len(splits)


def algorithm_and_evaluations(experiment):
    d = json.loads(subprocess.run([binary, "inspect", experiment, "--json", "--no-estimate"],
                                  capture_output=True, text=True, check=True).stdout)
    w = d["workload"]
    return d["algorithm"], w["individuals"] * w["generations"]


for line in os.environ["FAMILIES_TEXT"].splitlines():
    fname, files, baseline, keys = line.split("|")
    if only not in fname:
        continue
    files = files.split()
    keys = keys.split(",")
    have = [f for f in files if os.path.exists(f)]
    champs = {f: [c for c in (f"{runs}/{os.path.basename(f)[:-5]}/seed-{s}/best.json"
                              for s in seeds)
                     if os.path.exists(os.path.join(os.path.dirname(c), "wall.txt"))]
              for f in have}
    genomes = [c for f in have for c in champs[f]]
    if baseline != "-":
        genomes.append(baseline)
    if not genomes:
        continue
    report = json.loads(subprocess.run(
        [binary, "compare", *genomes, "--experiment", files[0], "--worlds", "held-out",
         "--trials", trials, "--random", "64", "--json"],
        capture_output=True, text=True, check=True).stdout)
    fit = {g["path"]: g["fitness"] for g in report["genomes"]}
    meas = {g["path"]: g["measures"] for g in report["genomes"]}
    rnd = report["random"]["fitness"]
    print(f"### {fname}: held-out fitness on {trials} worlds (seed of {files[0]}), "
          f"{len(seeds)} seeds each\n")
    base_text = ""
    if baseline != "-":
        base_text = (f"; the hand-designed baseline ({baseline}) scores {fit[baseline]:.1f} ("
                     + ", ".join(f"{k} {meas[baseline].get(k, float('nan')):.2f}" for k in keys)
                     + ")")
    print(f"64 random genomes: median {rnd['median']:.1f}, best {rnd['best']:.1f}{base_text}.\n")
    print("| algorithm | evaluations | wall / CPU s a run (median) | held-out: median (Q1–Q3) | per seed | "
          + " | ".join(f"{k}, median" for k in keys) + " | Mann–Whitney U vs GA (p) |")
    print("|---|---|---|---|---|" + "---|" * len(keys) + "---|")
    ga = [fit[c] for c in champs.get(files[0], [])]
    for f in have:
        cs = champs[f]
        if not cs:
            continue
        held = [fit[c] for c in cs]
        m, q1, q3 = quartiles(held)
        times = [open(os.path.join(os.path.dirname(c), "wall.txt")).read().split() for c in cs]
        walls = [float(t[0]) for t in times]
        cpus = [float(t[1]) for t in times if len(t) > 1]
        algorithm, evaluations = algorithm_and_evaluations(f)
        beh = " | ".join(f"{statistics.median(meas[c].get(k, float('nan')) for c in cs):.2f}"
                         for k in keys)
        if f == files[0] or not ga:
            test = "—"
        else:
            u, p = mann_whitney(held, ga)
            test = f"{u:.0f} ({p:.3f})"
        print(f"| {algorithm} ({os.path.basename(f)}) | {evaluations} | "
              f"{statistics.median(walls):.0f}"
              + (f" / {statistics.median(cpus):.0f}" if cpus else "") + f" | {m:.1f} ({q1:.1f}–{q3:.1f}) | "
              + ", ".join(f"{h:.1f}" for h in held) + f" | {beh} | {test} |")
    print()
PY
