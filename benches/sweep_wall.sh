#!/usr/bin/env bash
# The wall time a user gets from `millimpact sweep` for 10^4 impacts at COR error <= 1e-10,
# both forms, run after one another in rounds (so that a change of the machine's load falls on
# every command alike), medians over the rounds; and the largest resident memory of a 10^6-point
# sweep in both forms (`/usr/bin/time -v`).
#
#   bash benches/sweep_wall.sh [ROUNDS] [OLD_BINARY]
#
# OLD_BINARY: an earlier build to measure beside this one (its commands name the method and the
# steps per period the tolerance chooses now, and its shipped sweeps/eta.toml at 400). Run from
# the project root after `cargo build --release`; the binary is $CARGO_TARGET_DIR (or target/)
# release/millimpact. Prints Markdown tables.
set -euo pipefail

rounds=${1:-21}
old=${2:-}
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

labels=()
commands=()
add() { labels+=("$1"); commands+=("$2"); }
add "sweep sweeps/eta.toml (tolerance = 1e-10)" "$bin sweep sweeps/eta.toml"
add "sweep cases/ball_plate.toml --loss-coefficient 0:0.9999:0.0001 --tolerance 1e-10" \
    "$bin sweep cases/ball_plate.toml --loss-coefficient 0:0.9999:0.0001 --tolerance 1e-10"
if [[ -n "$old" ]]; then
    add "earlier build: sweep file, rk4-event at $steps steps per period" "$old sweep $work/eta-fixed.toml"
    add "earlier build: sweep file, rk4-event at 400 (its eta.toml)" "$old sweep $work/eta-400.toml"
    add "earlier build: --loss-coefficient 0:0.9999:0.0001 --method rk4-event --steps-per-period $steps" \
        "$old sweep cases/ball_plate.toml --loss-coefficient 0:0.9999:0.0001 --method rk4-event --steps-per-period $steps"
fi

for c in "${commands[@]}"; do $c >/dev/null 2>&1; done   # warm the page cache
declare -A times
for ((r = 0; r < rounds; r++)); do
    for i in "${!commands[@]}"; do
        start=$(date +%s%N)
        ${commands[$i]} >/dev/null 2>&1
        end=$(date +%s%N)
        times[$i]+="$(( (end - start) / 1000 )) "
    done
done

median() { tr ' ' '\n' | grep . | sort -n | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
echo "load before and after: $(cut -d' ' -f1-3 /proc/loadavg)"
echo
echo "| command (10^4 impacts, 2 threads) | median wall | fastest | slowest |"
echo "|---|---|---|---|"
for i in "${!commands[@]}"; do
    m=$(echo "${times[$i]}" | median)
    lo=$(echo "${times[$i]}" | tr ' ' '\n' | grep . | sort -n | head -1)
    hi=$(echo "${times[$i]}" | tr ' ' '\n' | grep . | sort -n | tail -1)
    printf '| `%s` | %.1f ms | %.1f ms | %.1f ms |\n' "${labels[$i]}" "$(echo "$m/1000" | bc -l)" \
        "$(echo "$lo/1000" | bc -l)" "$(echo "$hi/1000" | bc -l)"
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
