#!/usr/bin/env bash
# DEM-code throughput of a sweep, side by side in one run: N impacts of the canonical ball on a
# plate (η spread over [0, 0.99]) at 200 steps per contact, one process per impact against
# batches of up to BATCH impacts per process, both on --jobs JOBS.
#
#   bash benches/code_throughput.sh [N=200] [JOBS=2] [BATCH=100] [CODES="lammps liggghts yade"]
set -euo pipefail
cd "$(dirname "$0")/.."
n=${1:-200}
jobs=${2:-2}
batch=${3:-100}
codes=${4:-lammps liggghts yade}
cargo build --release --quiet
bin=${CARGO_TARGET_DIR:-target}/release/millimpact
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
printf '%-10s %-8s %8s %10s %12s\n' code mode impacts "wall (s)" "impacts/s"
for code in $codes; do
  cat > "$work/$code.toml" <<TOML
base = "$PWD/cases/ball_plate.toml"
[axes]
loss_coefficient = { start = 0.0, stop = 0.99, count = $n }
code = ["$code"]
steps_per_contact = [200]
TOML
  for mode in single batched; do
    size=1
    [ "$mode" = batched ] && size=$batch
    rm -f "$work/$code-$mode.csv"
    start=$(date +%s.%N)
    CI=1 "$bin" sweep "$work/$code.toml" --jobs "$jobs" --batch "$size" --out "$work/$code-$mode.csv" 2>"$work/$code-$mode.err" || true
    end=$(date +%s.%N)
    ok=$(grep -c ',ok$' "$work/$code-$mode.csv" || true)
    awk -v c="$code" -v m="$mode" -v n="$ok" -v s="$start" -v e="$end" \
      'BEGIN { printf "%-10s %-8s %8d %10.2f %12.1f\n", c, m, n, e - s, n / (e - s) }'
    if [ "$mode" = batched ] && grep -q "single runs" "$work/$code-$mode.err"; then
      echo "  ($code: $(grep -m1 -o 'single runs: .*' "$work/$code-$mode.err"))"
    fi
  done
done
