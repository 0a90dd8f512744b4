#!/usr/bin/env bash
# One impact of ball_plate at COR error <= 1e-10 by millimpact (rk4-event at 400 steps per
# period, dopri5 at rtol 1e-10) and by scipy's solve_ivp (DOP853, terminal events, the loosest
# rtol that reaches the same accuracy), timed one after the other on this machine, printed side
# by side with the ratio; then millimpact's full benchmark report (every canonical case, the
# defaults, the 10^4-η sweep). Installs the peer environment first (scripts/peer/setup.sh).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
cd "$root"
bash scripts/peer/setup.sh
python="$root/.codes/peer/venv/bin/python"

cargo bench --bench impact --no-run --quiet
ours="$(MILLIMPACT_BENCH_REPORT=1 cargo bench --bench impact --quiet 2>/dev/null)"
peer="$("$python" scripts/peer/scipy_impact.py --format json)"

OURS="$ours" PEER="$peer" "$python" - <<'PY'
import json, os, re

peer = json.loads(os.environ["PEER"])
rows = [line for line in os.environ["OURS"].splitlines() if line.startswith("| ball_plate |")]
def time_of(cell):
    value, unit = cell.split()
    return float(value) * {"ns": 1e-9, "µs": 1e-6, "ms": 1e-3, "s": 1.0}[unit]

print("One impact of ball_plate (η = 0.35) at COR error ≤ 1e-10, one run on this machine:")
print()
print("| source | knob | COR error | peak error | contact-time error | rhs evals | time per impact | scipy's time over this |")
print("|---|---|---|---|---|---|---|---|")
peer_time = peer["median_seconds_per_impact"]
for knob in ("400 /period", "rtol 1e-10"):
    row = next(r for r in rows if f"| {knob} |" in r)
    cells = [c.strip() for c in row.strip("|").split("|")]
    _, method, knob, cor, peak, contact, evals, time = cells
    ratio = peer_time / time_of(time)
    print(f"| millimpact {method} | {knob} | {cor} | {peak} | {contact} | {evals} | {time} | {ratio:,.0f}× |")
print(
    f"| scipy {peer['scipy']} solve_ivp DOP853 | rtol {peer['rtol']:.0e} "
    f"| {peer['cor_error']:.2e} | {peer['peak_error']:.2e} | {peer['contact_time_error']:.2e} "
    f"| {peer['rhs_evaluations']} | {peer_time * 1e3:.2f} ms | 1× |"
)
print()
print(f"(scipy: median of {peer['repeats']} impacts, Python {peer['python']}, numpy {peer['numpy']}; "
      f"millimpact: median of 15 batches of at least 20 ms)")
PY
echo
echo "millimpact, every point of benches/impact.rs (MILLIMPACT_BENCH_REPORT=1 cargo bench --bench impact):"
echo
echo "$ours"
