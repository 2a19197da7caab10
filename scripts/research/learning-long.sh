#!/usr/bin/env bash
# Longer runs of one learning-table file (docs/learning.md, "Paying per correct choice, and
# longer runs"): evolves seeds 1-5 of FILE for GENERATIONS generations into
# RUNS/<name>-g<GENERATIONS>/seed-<n>/ (reused when there), then compares each champion on that
# seed's 20 held-out lives of the shipped t-maze-switch (as scripts/learning-table.sh does,
# which must have run first: its seed folders give the worlds), and prints adapted_choice and fitness per seed and their medians (frozen and ungated rows for a
# plastic brain).
#
#   bash scripts/research/learning-long.sh experiments/learning/t-maze-switch-plastic-small-choice.toml 800
set -euo pipefail
cd "$(dirname "$0")/../.."
FILE=$1
GENERATIONS=$2
RUNS=${RUNS:-results/learning}
BIN=${BERRY_EVOLVE:-target/release/berry-evolve}
[ -x "$BIN" ] || cargo build --release
name=$(basename "$FILE" .toml)-g$GENERATIONS
for seed in 1 2 3 4 5; do
  out=$RUNS/$name/seed-$seed
  [ -f "$out/best.json" ] && continue
  "$BIN" run "$FILE" --seed "$seed" --generations "$GENERATIONS" --out "$out" --quiet --no-check --force
done
# Frozen and ungated rows only for a plastic brain (compare refuses --ablate otherwise).
ablate=()
grep -Eq '^plasticity *= *"(hebbian|neuromodulated)"' "$FILE" && ablate=(--ablate)
for seed in 1 2 3 4 5; do
  "$BIN" compare "$RUNS/$name/seed-$seed/best.json" \
    --experiment "$RUNS/t-maze-switch/seed-$seed/experiment.toml" \
    --trials 20 "${ablate[@]}" --measure adapted_choice --json 2>/dev/null
done | python3 -c '
import json, statistics, sys
decoder, text, rows = json.JSONDecoder(), sys.stdin.read(), {}
while text.strip():
    report, end = decoder.raw_decode(text.lstrip())
    text = text.lstrip()[end:]
    for g in report["genomes"]:
        row = rows.setdefault(g.get("ablation") or "champion", {"fitness": [], "choice": []})
        row["fitness"].append(g["fitness"])
        row["choice"].append(g["measures"]["adapted_choice"])
print("| row | held-out fitness, median | adapted_choice, median | adapted_choice per seed |")
print("|---|---|---|---|")
for label, row in rows.items():
    per_seed = ", ".join(f"{v:.2f}" for v in row["choice"])
    fitness, choice = statistics.median(row["fitness"]), statistics.median(row["choice"])
    print(f"| {label} | {fitness:.0f} | {choice:.2f} | {per_seed} |")
'
