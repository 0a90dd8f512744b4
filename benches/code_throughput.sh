#!/usr/bin/env bash
# DEM-code throughput of a sweep, every code and scene side by side in one run: N impacts of a
# scene's shipped case (cases/SCENE.toml, η spread over [0, 0.9], each a distinct η) at 200 steps
# per contact, on --jobs JOBS. Modes:
#   batched  this build, --batch BATCH;
#   single   this build, one process per impact (--batch 1);
#   before   the millimpact named by BEFORE (an older build), with its own defaults.
# Each (code, scene, mode) runs REPEATS times, interleaved so that a change in the machine's load
# falls on all alike; the table gives the median wall time of the whole `millimpact sweep`
# command (start-up, probe, sizing, every code process, every row written) and the impacts per
# second it makes, with the load average before and after. A point that is not `ok` is counted
# out and its status printed; a batch that fell back to single runs says why.
#
#   bash benches/code_throughput.sh [N=200] [JOBS=2] [BATCH=256] [CODES=all]
#       [SCENES="ball_plate ball_ball rod_end"] [REPEATS=3] [MODES=batched]
#   BEFORE=/path/to/old/millimpact bash benches/code_throughput.sh 200 2 256 all all 1 "batched before"
set -euo pipefail
cd "$(dirname "$0")/.."
n=${1:-200}
jobs=${2:-2}
batch=${3:-256}
codes=${4:-all}
scenes=${5:-all}
repeats=${6:-3}
modes=${7:-batched}
[ "$codes" = all ] && codes="liggghts liggghts-paper yade yade-paper lammps lammps-2025 lammps-paper kratos"
[ "$scenes" = all ] && scenes="ball_plate ball_ball rod_end"
if [[ " $modes " == *" before "* ]] && [ ! -x "${BEFORE:-}" ]; then
  echo "mode before needs BEFORE=/path/to/an/older/millimpact" >&2
  exit 2
fi
cargo build --release --quiet
bin=${CARGO_TARGET_DIR:-target}/release/millimpact
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg) (1, 5, 15 min; $(nproc) cores)"
for code in $codes; do
  for scene in $scenes; do
    cat >"$work/$code-$scene.toml" <<TOML
base = "$PWD/cases/$scene.toml"
[axes]
loss_coefficient = { start = 0.0, stop = 0.9, count = $n }
code = ["$code"]
steps_per_contact = [200]
TOML
  done
done
for r in $(seq "$repeats"); do
  for code in $codes; do
    for scene in $scenes; do
      for mode in $modes; do
        case $mode in
          batched) command=("$bin" sweep --batch "$batch") ;;
          single) command=("$bin" sweep --batch 1) ;;
          before) command=("$BEFORE" sweep) ;;
          *) echo "unknown mode $mode" >&2; exit 2 ;;
        esac
        run="$work/$code-$scene-$mode-$r"
        start=$(date +%s.%N)
        CI=1 "${command[@]}" "$work/$code-$scene.toml" --jobs "$jobs" --out "$run.csv" \
          2>"$run.err" || true
        end=$(date +%s.%N)
        ok=$(grep -c ',ok$' "$run.csv" || true)
        echo "$code $scene $mode $ok $(echo "$end - $start" | bc -l)" >>"$work/times"
        if [ "$ok" -ne "$n" ]; then
          echo "  $code $scene $mode: $((n - ok)) of $n not ok, e.g. $(grep -v ',ok$' "$run.csv" | sed -n 2p | grep -o '[^,]*$')" >&2
        fi
        if grep -q "single runs\|ran alone" "$run.err"; then
          echo "  $code $scene $mode: $(grep -m1 -o 'ran \(as single runs\|alone\): .*' "$run.err")" >&2
        fi
      done
    done
  done
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
printf '%-12s %-11s %-8s %8s %16s %12s\n' code scene mode "ok" "median wall (s)" "impacts/s"
for code in $codes; do
  for scene in $scenes; do
    for mode in $modes; do
      awk -v c="$code" -v s="$scene" -v m="$mode" '$1 == c && $2 == s && $3 == m { print $5, $4 }' "$work/times" |
        sort -g | awk -v c="$code" -v s="$scene" -v m="$mode" -v n="$n" '
          { wall[NR] = $1; ok[NR] = $2 }
          END {
            mid = int((NR + 1) / 2)
            printf "%-12s %-11s %-8s %4d/%-3d %16.2f %12.1f\n", c, s, m, ok[mid], n, wall[mid], ok[mid] / wall[mid]
          }'
    done
  done
done
