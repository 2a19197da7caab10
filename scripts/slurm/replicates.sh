#!/usr/bin/env bash
# Replicates of one experiment on a SLURM cluster: one array task per seed, then `summary`.
#
#   bash scripts/slurm/replicates.sh EXPERIMENT.toml SEEDS [OUT]
#   e.g. bash scripts/slurm/replicates.sh experiments/foraging.toml 1-20 results/foraging
#
# SEEDS is a SLURM array range (1-20, or 1,3,5). Each task runs `berry-evolve run EXPERIMENT
# --seeds <its seed> --out OUT` (seed.sbatch): the run folder OUT/seed-<s>/, byte-identical to
# `berry-evolve run EXPERIMENT --seed <s>` on any machine. A resubmitted task whose folder
# holds a stopped run continues it from its checkpoint, so the same command finishes an
# interrupted batch. When every task has succeeded, summary.sbatch writes OUT/summary.csv and
# OUT/held-out.csv. Extra sbatch options (partition, account, time, cores) go in
# SBATCH_* environment variables or in the #SBATCH lines of the two .sbatch files.
set -euo pipefail
if [ $# -lt 2 ]; then
    echo "usage: bash scripts/slurm/replicates.sh EXPERIMENT.toml SEEDS [OUT]" >&2
    exit 2
fi
experiment=$1
seeds=$2
name=$(basename "$experiment" .toml)
out=${3:-results/$name}
here=$(dirname "$0")
mkdir -p "$out"
array=$(sbatch --parsable --array="$seeds" --job-name="berry-$name" \
    --output="$out/slurm-%A_%a.out" "$here/seed.sbatch" "$experiment" "$out")
echo "submitted seeds $seeds as array job $array; summary after it: $out/summary.csv"
sbatch --parsable --dependency="afterok:$array" --job-name="berry-$name-summary" \
    --output="$out/slurm-summary-%j.out" "$here/summary.sbatch" "$out"
