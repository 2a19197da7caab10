#!/usr/bin/env bash
# The learning table (issue 31): for t-maze-switch and which-food, evolve 5 seeds each of the
# fixed-weight MLP (the shipped file), an Elman network, the neuromodulated plastic MLP and
# (t-maze-switch) the plastic MLP under novelty search and a small plastic MLP of the
# hand-designed learner's shape, and (t-maze-switch) the fixed, plastic and small plastic MLPs
# paid `choice_bonus` per correct first choice (experiments/learning/), all at the shipped
# file's budget; then compare every seed's champions on the same 20 held-out lives
# (`compare --trials 20`, the seed's worlds), with the plastic champions also frozen and
# ungated (`--ablate`) and 32 random genomes, and print a Markdown table: per row the median
# and range over the seeds of held-out fitness and of the behaviour measure (adapted_choice,
# good_bite_share), and each seed's behaviour value; t-maze-switch's hand-designed learner
# (genomes/t-maze-switch-baseline.json, scripts/genomes/learner.py) is a row too. Also draws the
# per-episode curve of seed CURVE_SEED (default 1) to docs/pictures/learning-<family>-curve.svg:
# the fixed MLP, the plastic champion and the hand-designed learner, the plastic ones also
# frozen, and the random genomes.
#
#   bash scripts/learning-table.sh                       # both families
#   bash scripts/learning-table.sh --only which-food     # one family
#   bash scripts/learning-table.sh --runs results/learning --seeds "1 2 3"
#
# Runs go to RUNS/<name>/seed-<n>/ (default results/learning/, git-ignored) and are reused
# when they exist (delete a folder to re-run it); each run's wall time is kept in wall.txt.
set -euo pipefail
cd "$(dirname "$0")/.."
RUNS=results/learning
SEEDS="1 2 3 4 5"
ONLY=""
CURVE_SEED=1
BIN=target/release/berry-evolve
while [ $# -gt 0 ]; do
  case "$1" in
    --runs) RUNS=$2; shift 2 ;;
    --seeds) SEEDS=$2; shift 2 ;;
    --only) ONLY=$2; shift 2 ;;
    --curve-seed) CURVE_SEED=$2; shift 2 ;;
    --bin) BIN=$2; shift 2 ;;
    *) echo "learning-table.sh: unknown argument $1 (see the comments at the top)" >&2; exit 2 ;;
  esac
done
[ -x "$BIN" ] || cargo build --release

# family, behaviour measure, hand-designed controller (- for none), experiment files (the
# first is the fixed-weight control).
FAMILIES=(
  "t-maze-switch adapted_choice genomes/t-maze-switch-baseline.json experiments/t-maze-switch.toml experiments/learning/t-maze-switch-elman.toml experiments/learning/t-maze-switch-plastic.toml experiments/learning/t-maze-switch-plastic-novelty.toml experiments/learning/t-maze-switch-plastic-small.toml experiments/learning/t-maze-switch-choice.toml experiments/learning/t-maze-switch-plastic-choice.toml experiments/learning/t-maze-switch-plastic-small-choice.toml"
  "which-food good_bite_share - experiments/which-food.toml experiments/learning/which-food-elman.toml experiments/learning/which-food-plastic.toml"
)

# 1. The runs, one after another, each on every core.
for family in "${FAMILIES[@]}"; do
  read -r name _ _ files <<<"$family"
  case "$name" in *"$ONLY"*) ;; *) continue ;; esac
  for exp in $files; do
    for seed in $SEEDS; do
      out=$RUNS/$(basename "$exp" .toml)/seed-$seed
      [ -f "$out/wall.txt" ] && [ -f "$out/best.json" ] && continue
      start=$(date +%s.%N)
      "$BIN" run "$exp" --seed "$seed" --out "$out" --quiet --no-check --force
      end=$(date +%s.%N)
      python3 -c "print(f'{$end - $start:.1f}')" > "$out/wall.txt"
    done
  done
done

# 2. The table.
FAMILIES_TEXT=$(printf '%s\n' "${FAMILIES[@]}") RUNS=$RUNS SEEDS=$SEEDS ONLY=$ONLY \
  BIN=$BIN CURVE_SEED=$CURVE_SEED python3 - <<'PY'
import json, os, statistics, subprocess

runs, binary, only = os.environ["RUNS"], os.environ["BIN"], os.environ["ONLY"]
seeds = os.environ["SEEDS"].split()
curve_seed = os.environ["CURVE_SEED"]


def med_range(values):
    values = [v for v in values if v is not None]
    if not values:
        return "n/a"
    return f"{statistics.median(values):.2f} ({min(values):.2f}–{max(values):.2f})"


for line in os.environ["FAMILIES_TEXT"].splitlines():
    family, measure, designed, *files = line.split()
    if only not in family:
        continue
    names = [os.path.basename(f)[:-5] for f in files]
    rows = {}  # label -> {"fitness": [...], "measure": [...]}
    walls = {n: [] for n in names}
    for seed in seeds:
        champs = [f"{runs}/{n}/seed-{seed}/best.json" for n in names]
        if not all(os.path.exists(c) for c in champs):
            continue
        for n in names:
            walls[n].append(float(open(f"{runs}/{n}/seed-{seed}/wall.txt").read()))
        experiment = f"{runs}/{names[0]}/seed-{seed}/experiment.toml"
        extra = [designed] if designed != "-" else []
        args = [binary, "compare", *champs, *extra, "--experiment", experiment, "--trials", "20",
                "--random", "32", "--ablate", "--measure", measure, "--json"]
        if seed == curve_seed:
            # The curve shows few rows, so that each can be told apart: the fixed control,
            # the plastic champion and the hand-designed learner, each plastic one frozen.
            shown = [champs[0], champs[2], *extra]
            subprocess.run([binary, "compare", *shown, "--experiment", experiment, "--trials",
                            "20", "--random", "32", "--ablate=frozen", "--episode-curve",
                            f"docs/pictures/learning-{family}-curve.svg"],
                           capture_output=True, text=True, check=True)
        report = json.loads(subprocess.run(args, capture_output=True, text=True,
                                           check=True).stdout)
        for g in report["genomes"]:
            name = (g["path"].split("/")[-3] if g["path"].startswith(runs)
                    else "hand-designed learner (" + g["path"] + ")")
            label = name + (f" ({g['ablation']})" if g.get("ablation") else "")
            row = rows.setdefault(label, {"fitness": [], "measure": []})
            row["fitness"].append(g["fitness"])
            row["measure"].append(g["measures"].get(measure))
        r = report["random"]
        row = rows.setdefault("32 random genomes (median)", {"fitness": [], "measure": []})
        row["fitness"].append(r["fitness"]["median"])
        row["measure"].append(r["measures"][measure]["median"])
    print(f"\n**{family}** (held-out lives, `compare --trials 20` on each seed's worlds; "
          f"{len(seeds)} seeds; behaviour: `{measure}`, chance about 0.5)\n")
    print(f"| row | wall s (median) | held-out fitness, median (range) | {measure}, median "
          f"(range) | {measure} per seed |")
    print("|---|---|---|---|---|")
    for label, row in rows.items():
        wall = f"{statistics.median(walls[label]):.0f}" if walls.get(label) else ""
        per_seed = ", ".join("n/a" if v is None else f"{v:.2f}" for v in row["measure"])
        print(f"| {label} | {wall} | {med_range(row['fitness'])} | "
              f"{med_range(row['measure'])} | {per_seed} |")
PY
