#!/usr/bin/env bash
# The wall time a user gets from `millimpact sweep` for 10^4 impacts at COR error <= 1e-10,
# both forms, run after one another in rounds (so that a change of the machine's load falls on
# every command alike), medians over the rounds, with the CPU time (user + system) beside it;
# and the largest resident memory of a 10^6-point sweep in both forms (`/usr/bin/time -v`).
#
#   bash benches/sweep_wall.sh [ROUNDS] [BEFORE_BINARY]
#
# BEFORE_BINARY: another build to measure beside this one. A build that knows `tolerance` runs
# the same two commands; an earlier one runs the method and the steps per period the tolerance
# chooses now (and its shipped sweeps/eta.toml at 400). Run from the project root after
# `cargo build --release`; this build is $CARGO_TARGET_DIR (or target/) release/millimpact.
# Prints Markdown tables.
set -euo pipefail

rounds=${1:-21}
before=${2:-}
bin="${CARGO_TARGET_DIR:-target}/release/millimpact"
[[ -x "$bin" ]] || { echo "no $bin: cargo build --release first" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
root=$(pwd)

# What the tolerance chooses, from the note the sweep prints.
steps=$("$bin" sweep sweeps/eta.toml 2>&1 >/dev/null | sed -n 's/.* at \([0-9]*\) steps per period.*/\1/p')
[[ -n "$steps" ]] || { echo "sweeps/eta.toml did not name its steps per period" >&2; exit 1; }
cat >"$work/eta-fixed.toml" <<EOF
base = "$root/cases/ball_plate.toml"
[axes]
loss_coefficient = { start = 0.0, stop = 0.9999, count = 10000 }
method = ["rk4-event"]
steps_per_period = [$steps]
EOF
cat >"$work/eta-400.toml" <<EOF
base = "$root/cases/ball_plate.toml"
[axes]
loss_coefficient = { start = 0.0, stop = 0.9999, count = 10000 }
method = ["rk4-event"]
steps_per_period = [400]
EOF

file_form="sweep sweeps/eta.toml"
legacy_form="sweep cases/ball_plate.toml --loss-coefficient 0:0.9999:0.0001 --tolerance 1e-10"
labels=()
commands=()
add() { labels+=("$1"); commands+=("$2"); }
add "$file_form (tolerance = 1e-10)" "$bin $file_form"
add "$legacy_form" "$bin $legacy_form"
if [[ -n "$before" ]]; then
    if "$before" $file_form >/dev/null 2>&1; then
        add "before: $file_form" "$before $file_form"
        add "before: $legacy_form" "$before $legacy_form"
    else
        add "earlier build: sweep file, rk4-event at $steps steps per period" "$before sweep $work/eta-fixed.toml"
        add "earlier build: sweep file, rk4-event at 400 (its eta.toml)" "$before sweep $work/eta-400.toml"
        add "earlier build: --loss-coefficient 0:0.9999:0.0001 --method rk4-event --steps-per-period $steps" \
            "$before sweep cases/ball_plate.toml --loss-coefficient 0:0.9999:0.0001 --method rk4-event --steps-per-period $steps"
    fi
fi

for c in "${commands[@]}"; do $c >/dev/null 2>&1; done   # warm the page cache
load_before=$(cut -d' ' -f1-3 /proc/loadavg)
declare -A times cpu
TIMEFORMAT='%3U %3S'
for ((r = 0; r < rounds; r++)); do
    for i in "${!commands[@]}"; do
        start=$(date +%s%N)
        # bash's `time` reads the command's own CPU time (no process of its own in between).
        used=$( { time ${commands[$i]} >/dev/null 2>&1; } 2>&1 )
        end=$(date +%s%N)
        times[$i]+="$(( (end - start) / 1000 )) "
        cpu[$i]+="$(echo "$used" | awk '{printf "%d", ($1 + $2) * 1e6}') "
    done
done
load_after=$(cut -d' ' -f1-3 /proc/loadavg)

sorted() { tr ' ' '\n' | grep . | sort -n; }
median() { sorted | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
ms() { printf '%.1f ms' "$(echo "$1/1000" | bc -l)"; }
echo "load (1, 5, 15 min) before: $load_before; after: $load_after"
echo
echo "| command (10^4 impacts, 2 threads) | median wall | fastest | slowest | median CPU (user + system) |"
echo "|---|---|---|---|---|"
for i in "${!commands[@]}"; do
    m=$(echo "${times[$i]}" | median)
    lo=$(echo "${times[$i]}" | sorted | head -1)
    hi=$(echo "${times[$i]}" | sorted | tail -1)
    c=$(echo "${cpu[$i]}" | median)
    printf '| `%s` | %s | %s | %s | %s |\n' "${labels[$i]}" "$(ms "$m")" "$(ms "$lo")" "$(ms "$hi")" "$(ms "$c")"
done

cat >"$work/million.toml" <<EOF
base = "$root/cases/ball_plate.toml"
tolerance = 1e-10
[axes]
loss_coefficient = { start = 0.0, stop = 0.999999, count = 1000000 }
EOF
rss() { /usr/bin/time -v "$@" 2>&1 >/dev/null | sed -n 's/.*Maximum resident set size (kbytes): //p'; }
echo
echo "| 10^6 points, rows to /dev/null | largest resident memory |"
echo "|---|---|"
printf '| `sweep million.toml` (a sweep file, count = 10^6) | %.1f MB |\n' "$(echo "$(rss "$bin" sweep "$work/million.toml")/1024" | bc -l)"
printf '| `sweep cases/ball_plate.toml --loss-coefficient 0:0.999999:0.000001 --tolerance 1e-10` | %.1f MB |\n' \
    "$(echo "$(rss "$bin" sweep cases/ball_plate.toml --loss-coefficient 0:0.999999:0.000001 --tolerance 1e-10)/1024" | bc -l)"
