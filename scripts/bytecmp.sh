#!/usr/bin/env bash
# Same results? Runs every shipped experiment (experiments/*.toml) for a few generations with
# one binary into a folder, or compares two such folders file by file: fitness.csv, best.json
# and the checkpoints (whose "program" field and checksum name the build, so they are left out
# of the comparison).
#
#   bash scripts/bytecmp.sh run BINARY OUT_DIR [GENERATIONS]   (default 8 generations)
#   bash scripts/bytecmp.sh compare DIR_A DIR_B
set -euo pipefail
cd "$(dirname "$0")/.."
case "${1:-}" in
run)
  bin=$(realpath "$2"); out=$3; gens=${4:-8}
  mkdir -p "$out"
  for f in experiments/*.toml; do
    name=$(basename "$f" .toml)
    "$bin" run "$f" --generations "$gens" --out "$out/$name" --force --quiet >/dev/null 2>"$out/$name.stderr" ||
      echo "$name: run failed (see $out/$name.stderr)"
  done ;;
compare)
  a=$2; b=$3; status=0
  strip() { python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); [d.pop(k,None) for k in ("program","checksum")]; print(json.dumps(d,sort_keys=True))' "$1"; }
  for dir in "$a"/*/; do
    name=$(basename "$dir")
    for f in fitness.csv best.json; do
      if cmp -s "$a/$name/$f" "$b/$name/$f"; then :; else echo "$name/$f differs"; status=1; fi
    done
    for c in "$a/$name"/checkpoints/*.json; do
      rel=checkpoints/$(basename "$c")
      if [ "$(strip "$c")" != "$(strip "$b/$name/$rel" 2>/dev/null)" ]; then echo "$name/$rel differs"; status=1; fi
    done
  done
  [ $status = 0 ] && echo "all identical"
  exit $status ;;
*) sed -n 2,8p "$0"; exit 2 ;;
esac
