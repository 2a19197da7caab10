#!/usr/bin/env bash
# Generations per second of one experiment on 1..N MPI ranks, the parallel efficiency, and
# the communication per generation (issue 20; docs/scale-out.md discusses the figures).
#
#   bash scripts/mpi-bench.sh [EXPERIMENT] [MAX_RANKS] [GENERATIONS] [THREADS_PER_RANK]
#   (defaults: experiments/foraging.toml 3 10 1)
#
# Builds with `--features mpi` (needs Open MPI: libopenmpi-dev openmpi-bin libclang-dev), runs
# the experiment once without MPI and once per rank count under `mpirun --oversubscribe`, and
# prints one row per run: wall seconds (mpirun's start-up included), generations per second,
# speed-up and efficiency against 1 rank (speed-up / ranks), rank 0's messages and bytes per
# generation, and whether fitness.csv, best.json and the checkpoints equal the run without MPI.
# On a machine with fewer cores than ranks x threads the ranks share cores (oversubscribed):
# the figures then show the overhead of the protocol and the balance of the work, not the
# scaling a cluster gives.
set -euo pipefail
cd "$(dirname "$0")/.."
experiment=${1:-experiments/foraging.toml}
max_ranks=${2:-3}
generations=${3:-10}
threads=${4:-1}
cargo build --release --features mpi --quiet
bin=target/release/berry-evolve
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
now() { date +%s.%N; }
since() { awk -v a="$1" -v b="$(now)" 'BEGIN { print b - a }'; }
same() {
    cmp -s "$1/fitness.csv" "$2/fitness.csv" && cmp -s "$1/best.json" "$2/best.json" &&
        diff -rq "$1/checkpoints" "$2/checkpoints" >/dev/null && echo yes || echo NO
}
cores=$(nproc)
echo "experiment $experiment, $generations generations, $threads thread(s) per rank, $cores core(s)"
echo "command: mpirun --oversubscribe -np N $bin run $experiment --generations $generations --jobs $threads"
t0=$(now)
"$bin" run "$experiment" --generations "$generations" --jobs "$threads" --quiet --out "$tmp/plain"
plain=$(since "$t0")
printf '%-10s %8s %8s %8s %8s %10s %12s %6s\n' ranks seconds gen/s speedup effic. msgs/gen bytes/gen same
awk -v t="$plain" -v g="$generations" \
    'BEGIN { printf "%-10s %8.2f %8.3f %8s %8s %10s %12s %6s\n", "no MPI", t, g / t, "-", "-", "-", "-", "-" }'
base=""
for np in $(seq 1 "$max_ranks"); do
    out="$tmp/np$np"
    t0=$(now)
    mpirun --oversubscribe -np "$np" "$bin" run "$experiment" --generations "$generations" \
        --jobs "$threads" --out "$out" 2>"$tmp/err$np" >/dev/null
    secs=$(since "$t0")
    note=$(grep '^evaluated on ' "$tmp/err$np")
    msgs=$(sed -E 's/.*per generation ([0-9.]+) messages.*/\1/' <<<"$note")
    bytes=$(sed -E 's/.*messages, ([0-9]+) bytes.*/\1/' <<<"$note")
    [ -z "$base" ] && base=$secs
    oversubscribed=""
    [ $((np * threads)) -gt "$cores" ] && oversubscribed=" (oversubscribed)"
    awk -v t="$secs" -v b="$base" -v g="$generations" -v n="$np" -v m="$msgs" -v by="$bytes" \
        -v s="$(same "$tmp/plain" "$out")" -v o="$oversubscribed" \
        'BEGIN { printf "%-10s %8.2f %8.3f %8.2f %8.2f %10s %12s %6s%s\n", n, t, g / t, b / t, b / t / n, m, by, s, o }'
done
