#!/usr/bin/env python3
"""SciPy's solve_ivp and odeint, and SUNDIALS' CVODE (scikit-sundae), on
spintop's work-precision problems, written in the CSV columns of `spintop bench
--out` so that `spintop bench --join` can put them side by side.

What a student who does not use spintop would write: the body rate equations
Omega' = F(Omega) of the truncated (4.2)-(4.4), reduced (4.12)-(4.14) and
general truncated (3.3) models as plain Python functions, handed to
`scipy.integrate.solve_ivp` with `t_eval` at t = 1, 2, ..., 200 (tau units),
for RK45, DOP853, Radau and LSODA over a ladder of tolerances; the same with
`scipy.integrate.odeint` (LSODA with its loop in Fortran, method `odeint`) and,
where scikit-sundae installs, with CVODE's Adams and BDF methods (`cvode-adams`,
`cvode-bdf`; compiled C, called back into Python for the right-hand side). The start, the
parameters, the absolute tolerance (1e-6 * rtol * |Omega0|) and the reference
(crates/spintop/reference/*.csv, mpmath at 40 digits) are spintop's, so the errors are
measured the same way: the largest relative error of Omega over the 200 points.
The full ALE (3.4) is not run: its physical solution needs a backward shoot
that solve_ivp does not offer.

    pip install scipy numpy scikit-sundae     # scikit-sundae is optional
    python3 benches/scipy_work_precision.py --out scipy.csv            # a few minutes
    python3 benches/scipy_work_precision.py --quick --out scipy.csv    # about a minute
    cargo run --release -- bench --out spintop.csv
    cargo run --release -- bench --join spintop.csv scipy.csv

Columns: rhs_evals is solve_ivp's nfev (for Radau it includes the finite
differences of the Jacobian); steps are the accepted steps of an untimed
second run without t_eval; rejected is derived from nfev for the explicit
methods (nfev = 2 + stages * attempts) and left empty for Radau and LSODA,
which do not report it; time_s is the median wall time of one solve_ivp call.
"""

import argparse
import csv
import math
import os
import statistics
import sys
import time

import numpy as np
from scipy.integrate import odeint, solve_ivp

try:
    from sksundae.cvode import CVODE
except ImportError:  # CVODE is optional: its rows are then skipped
    CVODE = None

HERE = os.path.dirname(os.path.abspath(__file__))
COLUMNS = [
    "source", "model", "method", "target", "knob", "value", "omega_error",
    "orientation_error", "rhs_evals", "steps", "rejected", "time_s", "repeats", "status",
]
OMEGA0 = [0.0, 0.1, 0.2]
TIMES = [float(i) for i in range(1, 201)]
RATIO = 0.4  # I3/I1 of the symmetric top, tau = 1
TAU = 1.0
INERTIA = np.array([1.0, 1.5, 0.8])  # the general top, kappa = 1
DIPOLE = np.array([0.2, 0.0, 1.0])


def truncated(t, w):
    """(4.2)-(4.4)."""
    w1, w2, w3 = w
    wt = (1.0 - RATIO) * w3
    damp = TAU * (w1 * w1 + w2 * w2)
    return [wt * w2 - damp * w1, -wt * w1 - damp * w2, -damp * w3]


def reduced(t, w):
    """(4.12)-(4.14)."""
    w1, w2, w3 = w
    wt = (1.0 - RATIO) * w3
    k = RATIO * w3
    damp = TAU * (w1 * w1 + w2 * w2 + k * k)
    return [wt * w2 - damp * w1, -wt * w1 - damp * w2, 0.0]


def general(t, w):
    """(3.3): (I + d (d x W)^T) W' = -W x IW - |d x W|^2 W."""
    dw = np.cross(DIPOLE, w)
    b = -np.cross(w, INERTIA * w) - dw.dot(dw) * w
    return np.linalg.solve(np.diag(INERTIA) + np.outer(DIPOLE, dw), b)


MODELS = {"truncated": truncated, "reduced": reduced, "general": general}
METHODS = ["RK45", "DOP853", "Radau", "LSODA", "odeint", "cvode-adams", "cvode-bdf"]
STAGES = {"RK45": 6, "DOP853": 12}


def reference(model):
    rows = []
    with open(os.path.join(HERE, "reference", f"{model}.csv")) as f:
        for line in f:
            if line.startswith("#") or line.startswith("t,"):
                continue
            v = [float(x) for x in line.split(",")]
            rows.append(v[1:4])
    assert len(rows) == len(TIMES)
    return np.array(rows)


def omega_error(ref, got):
    """max over the points of |got - ref| / |ref|, as in spintop."""
    if got.shape != ref.shape or not np.all(np.isfinite(got)):
        return math.inf
    return float(np.max(np.linalg.norm(got - ref, axis=1) / np.linalg.norm(ref, axis=1)))


class Solution:
    """What every method returns: Omega at TIMES (rows), evaluations, steps."""

    def __init__(self, success, message, y=None, nfev=None, steps=None):
        self.success, self.message, self.y, self.nfev, self.steps = success, message, y, nfev, steps


def solve(f, method, rtol, t_eval=TIMES):
    atol = max(1e-6 * rtol * math.sqrt(sum(x * x for x in OMEGA0)), 1e-300)
    if method == "odeint":
        ts = [0.0] + (t_eval or [TIMES[-1]])
        y, info = odeint(f, OMEGA0, ts, rtol=rtol, atol=atol, tfirst=True, full_output=True,
                         mxstep=10**7)
        ok = info["message"].startswith("Integration successful")
        return Solution(ok, info["message"], y[1:], int(info["nfe"][-1]), int(info["nst"][-1]))
    if method.startswith("cvode-"):
        def rhs(t, y, yp):
            yp[:] = f(t, y)
        kind = "Adams" if method == "cvode-adams" else "BDF"
        solver = CVODE(rhs, rtol=rtol, atol=atol, method=kind, max_num_steps=10**7)
        ts = np.array([0.0] + (t_eval or [TIMES[-1]]))
        sol = solver.solve(ts, np.array(OMEGA0))
        return Solution(bool(sol.success), sol.message, np.array(sol.y)[1:], int(sol.nfev), None)
    sol = solve_ivp(f, (0.0, TIMES[-1]), OMEGA0, method=method, t_eval=t_eval, rtol=rtol, atol=atol)
    return Solution(sol.success, sol.message, sol.y.T, sol.nfev, len(sol.t) - 1)


def measure(model, method, rtol, repeats):
    f = MODELS[model]
    row = dict.fromkeys(COLUMNS, "")
    row.update(source="scipy", model=model, method=method, target="omega", knob="rtol",
               value=repr(rtol), repeats="0", status="ok")
    if method.startswith("cvode-") and CVODE is None:
        row["status"] = "skipped: scikit-sundae is not installed"
        return row
    try:
        sol = solve(f, method, rtol)
        if not sol.success:
            row["status"] = str(sol.message).replace(",", ";")
            return row
        row["omega_error"] = repr(omega_error(reference(model), sol.y))
        row["rhs_evals"] = str(sol.nfev)
        plain = solve(f, method, rtol, t_eval=None)
        if plain.steps is not None:
            row["steps"] = str(plain.steps)
        if method in STAGES:
            attempts = (plain.nfev - 2) // STAGES[method]
            row["rejected"] = str(max(attempts - plain.steps, 0))
        samples = []
        for _ in range(repeats):
            start = time.perf_counter()
            solve(f, method, rtol)
            samples.append(time.perf_counter() - start)
        row["time_s"] = repr(statistics.median(samples))
        row["repeats"] = str(repeats)
    except Exception as e:  # a failed run is a row, not the end of the sweep
        row["status"] = f"{type(e).__name__}: {e}".replace(",", ";").replace("\n", " ")
    return row


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default="scipy.csv", help="CSV file to write (default scipy.csv)")
    ap.add_argument("--quick", action="store_true", help="4 tolerances and 3 repeats")
    ap.add_argument("--repeats", type=int, default=None, help="timed solves per row (median)")
    ap.add_argument("--models", default="truncated,reduced,general")
    ap.add_argument("--methods", default=",".join(METHODS))
    args = ap.parse_args()
    rtols = [1e-4, 1e-7, 1e-10, 1e-13] if args.quick else [10.0**-k for k in range(3, 15)]
    repeats = args.repeats or (3 if args.quick else 5)
    rows = []
    for model in args.models.split(","):
        for method in args.methods.split(","):
            for rtol in rtols:
                row = measure(model, method, rtol, repeats)
                rows.append(row)
                print(f"{model:10} {method:7} rtol={rtol:.0e}  error={row['omega_error'] or '-':>24}  "
                      f"nfev={row['rhs_evals'] or '-':>7}  time={row['time_s'] or '-':>22}  {row['status']}",
                      file=sys.stderr, flush=True)
    with open(args.out, "w", newline="") as out:
        w = csv.DictWriter(out, fieldnames=COLUMNS, lineterminator="\n")
        w.writeheader()
        w.writerows(rows)
    print(f"wrote {len(rows)} rows to {args.out} (scipy {__import__('scipy').__version__}, "
          f"numpy {np.__version__}, python {sys.version.split()[0]})")


if __name__ == "__main__":
    main()
