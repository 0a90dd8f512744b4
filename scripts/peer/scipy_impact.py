#!/usr/bin/env python3
"""One impact of the paper's law by scipy's solve_ivp (DOP853 with terminal events): the peer a
user would pick instead of millimpact, timed on the same problem at the same accuracy.

The problem is the ball_plate case's, in the dimensionless form millimpact itself integrates
(physics.md §3; every case of the law is this one problem at its n and η):

    Y'' = -((n+1)/2) Y^n (1 + η sign Y'),   Y(0) = 0, Y'(0) = 1,   n = 1.5 (Hertz), η = 0.35.

Loading (1 + η) runs until the terminal event Y' = 0 (the turning point); unloading (1 - η)
restarts there and runs until the terminal event Y = 0 (the contact end). The COR is the exit
speed, against the closed form e = sqrt((1 - η)/(1 + η)). The contact time and the peak are
checked too: the peak against ((1 + η)^(-1/(n+1))), the contact time against
J(n) Y_max (1 + 1/e).

The script tries rtol from 1e-7 down (atol = rtol * 1e-6, the rule millimpact's dopri5 uses),
picks the loosest whose COR error is at most --target (1e-10), and reports the median wall time
of one impact at that rtol over --repeats runs after a warm-up, plus its errors and the number
of right-hand-side evaluations. Run it through scripts/peer/setup.sh's environment:

    bash scripts/peer/setup.sh && .codes/peer/venv/bin/python scripts/peer/scipy_impact.py
"""

import argparse
import json
import math
import statistics
import sys
import time

import numpy as np
import scipy
from scipy.integrate import solve_ivp
from scipy.special import gamma

N = 1.5
ETA = 0.35


def impact(rtol, atol):
    """One impact: (COR, peak, contact time, rhs evaluations)."""
    k_load = 0.5 * (N + 1.0) * (1.0 + ETA)
    k_unload = 0.5 * (N + 1.0) * (1.0 - ETA)

    def load(_t, s):
        return [s[1], -k_load * max(s[0], 0.0) ** N]

    def unload(_t, s):
        return [s[1], -k_unload * max(s[0], 0.0) ** N]

    def turning(_t, s):
        return s[1]

    turning.terminal = True
    turning.direction = -1

    def exit_(_t, s):
        return s[0]

    exit_.terminal = True
    exit_.direction = -1

    # Longer than either phase (the undamped quarter period is J(1.5) = 1.47; unloading takes
    # 1/e = 1.44 times the loading's time): the events end the integration, not the span.
    span = 10.0
    first = solve_ivp(load, (0.0, span), [0.0, 1.0], method="DOP853", rtol=rtol, atol=atol,
                      events=turning)
    if first.status != 1:
        raise RuntimeError(f"no turning point: {first.message}")
    t_turn = first.t_events[0][0]
    peak = first.y_events[0][0][0]
    second = solve_ivp(unload, (t_turn, t_turn + span), [peak, 0.0], method="DOP853",
                       rtol=rtol, atol=atol, events=exit_)
    if second.status != 1:
        raise RuntimeError(f"no contact end: {second.message}")
    t_end = second.t_events[0][0]
    exit_speed = -second.y_events[0][0][1]
    return exit_speed, peak, t_end, first.nfev + second.nfev


def closed_form():
    e = math.sqrt((1.0 - ETA) / (1.0 + ETA))
    peak = (1.0 + ETA) ** (-1.0 / (N + 1.0))
    p = 1.0 / (N + 1.0)
    j = math.sqrt(math.pi) * gamma(1.0 + p) / gamma(0.5 + p)
    return e, peak, j * peak * (1.0 + 1.0 / e)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--target", type=float, default=1e-10, help="largest COR error")
    parser.add_argument("--repeats", type=int, default=41, help="timed impacts")
    parser.add_argument("--format", choices=["table", "json"], default="table")
    args = parser.parse_args()

    e, peak_exact, contact_exact = closed_form()
    chosen = None
    tried = []
    for exponent in range(7, 15):
        rtol = 10.0 ** -exponent
        cor, peak, contact, nfev = impact(rtol, rtol * 1e-6)
        error = (cor - e) / e
        tried.append({"rtol": rtol, "cor_error": error, "rhs_evaluations": nfev})
        if abs(error) <= args.target:
            chosen = (rtol, cor, peak, contact, nfev)
            break
    if chosen is None:
        print(f"scipy DOP853 reaches no COR error <= {args.target:g} by rtol 1e-14", file=sys.stderr)
        sys.exit(1)
    rtol, cor, peak, contact, nfev = chosen
    atol = rtol * 1e-6

    for _ in range(3):
        impact(rtol, atol)
    times = []
    for _ in range(args.repeats):
        started = time.perf_counter()
        impact(rtol, atol)
        times.append(time.perf_counter() - started)
    median = statistics.median(times)

    result = {
        "solver": "scipy.integrate.solve_ivp DOP853, terminal events",
        "scipy": scipy.__version__,
        "numpy": np.__version__,
        "python": sys.version.split()[0],
        "case": "ball_plate (dimensionless, n = 1.5, eta = 0.35)",
        "rtol": rtol,
        "atol": atol,
        "cor": cor,
        "cor_error": (cor - e) / e,
        "peak_error": (peak - peak_exact) / peak_exact,
        "contact_time_error": (contact - contact_exact) / contact_exact,
        "rhs_evaluations": nfev,
        "median_seconds_per_impact": median,
        "repeats": args.repeats,
        "tried": tried,
    }
    if args.format == "json":
        print(json.dumps(result, indent=2))
        return
    print(
        f"| ball_plate | scipy DOP853 | rtol {rtol:.0e} | {result['cor_error']:.2e} "
        f"| {result['peak_error']:.2e} | {result['contact_time_error']:.2e} | {nfev} "
        f"| {median * 1e6:.1f} µs |"
    )


if __name__ == "__main__":
    main()
