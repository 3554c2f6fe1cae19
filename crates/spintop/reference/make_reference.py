#!/usr/bin/env python3
"""High-precision references for `spintop bench` (crates/spintop/src/workprecision.rs).

For the truncated (4.2)-(4.4), reduced (4.12)-(4.14) and general truncated (3.3)
models, this integrates the body rate and the orientation together,

    dOmega/dt = F(Omega),      dq/dt = q * (0, Omega) / 2    (body -> lab, q a unit quaternion),

with mpmath's arbitrary-precision Taylor-series integrator (`mpmath.odefun`) at
40 significant digits, from Omega(0) = (0, 0.1, 0.2) and O(0) = identity, and
writes Omega and q at t = 1, 2, ..., 200 (tau units) with 22 significant digits.

Every input is the exact binary value of the f64 that spintop uses (0.1, 0.2,
0.4, 0.8 are not exact decimals), so the references are those of spintop's
problem, not of a nearby one. For the truncated and reduced models the script
also checks Omega against the paper's closed forms (4.6)-(4.7) and
(4.15)-(4.16), evaluated here in the printed form (beta, sigma) at 40 digits.

    pip install mpmath
    python3 crates/spintop/reference/make_reference.py     # about 13 minutes (9 of them the general top)

writes crates/spintop/reference/{truncated,reduced,general}.csv next to this file.
"""

import os
import sys
import time

import mpmath as mp

mp.mp.dps = 40
HERE = os.path.dirname(os.path.abspath(__file__))
T_END = 200
TIMES = [mp.mpf(i) for i in range(1, T_END + 1)]
OMEGA0 = [mp.mpf(0.0), mp.mpf(0.1), mp.mpf(0.2)]

# The symmetric top of the paper's figures: I3/I1 = 2/5, tau = 1, I1 = 1.
RATIO = mp.mpf(0.4)
TAU = mp.mpf(1)
# The general top: principal moments and body dipole, kappa = 1 units.
INERTIA = [mp.mpf(1.0), mp.mpf(1.5), mp.mpf(0.8)]
DIPOLE = [mp.mpf(0.2), mp.mpf(0.0), mp.mpf(1.0)]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def truncated(w):
    """(4.2)-(4.4)."""
    wt = (1 - RATIO) * w[2]
    damp = TAU * (w[0] ** 2 + w[1] ** 2)
    return [wt * w[1] - damp * w[0], -wt * w[0] - damp * w[1], -damp * w[2]]


def reduced(w):
    """(4.12)-(4.14)."""
    wt = (1 - RATIO) * w[2]
    k = RATIO * w[2]
    damp = TAU * (w[0] ** 2 + w[1] ** 2 + k * k)
    return [wt * w[1] - damp * w[0], -wt * w[0] - damp * w[1], mp.mpf(0)]


def general(w):
    """(3.3): I W' + W x IW = -{|d x W|^2 W + (d.(W x W')) d}, solved as the
    3x3 linear system (I + d (d x W)^T) W' = -W x IW - |d x W|^2 W by LU."""
    iw = [INERTIA[i] * w[i] for i in range(3)]
    wv = cross(DIPOLE, w)
    rhs = [-c - dot(wv, wv) * x for c, x in zip(cross(w, iw), w)]
    m = mp.matrix(3, 3)
    for i in range(3):
        for j in range(3):
            m[i, j] = (INERTIA[i] if i == j else 0) + DIPOLE[i] * wv[j]
    sol = mp.lu_solve(m, mp.matrix(rhs))
    return [sol[0], sol[1], sol[2]]


def with_orientation(f):
    """(Omega, q) -> (F(Omega), q (0, Omega)/2)."""

    def rhs(_t, y):
        w = y[0:3]
        qw, qx, qy, qz = y[3:7]
        wx, wy, wz = w
        dq = [
            (-qx * wx - qy * wy - qz * wz) / 2,
            (qw * wx + qy * wz - qz * wy) / 2,
            (qw * wy - qx * wz + qz * wx) / 2,
            (qw * wz + qx * wy - qy * wx) / 2,
        ]
        return list(f(w)) + dq

    return rhs


def truncated_closed_form(t):
    """(4.6)-(4.7) with Omega10 = 0, as printed."""
    wp0 = mp.sqrt(OMEGA0[0] ** 2 + OMEGA0[1] ** 2)
    r = mp.sqrt(1 + 2 * TAU * wp0**2 * t)
    vartheta = (r - 1) / (TAU * wp0**2)
    alpha = (1 - RATIO) * OMEGA0[2] * vartheta
    return [OMEGA0[1] * mp.sin(alpha) / r, OMEGA0[1] * mp.cos(alpha) / r, OMEGA0[2] / r]


def reduced_closed_form(t):
    """(4.15)-(4.16) with Omega10 = 0, as printed: beta and sigma."""
    wp0sq = OMEGA0[0] ** 2 + OMEGA0[1] ** 2
    beta = 1 + (RATIO * OMEGA0[2]) ** 2 / wp0sq
    sigma = 1 / (RATIO**2 * OMEGA0[2] ** 2 * TAU)
    phi = mp.sqrt((beta - 1) / (beta * mp.exp(2 * t / sigma) - 1))
    alpha = (1 - RATIO) * OMEGA0[2] * t
    return [OMEGA0[1] * phi * mp.sin(alpha), OMEGA0[1] * phi * mp.cos(alpha), OMEGA0[2]]


def main():
    problems = [
        ("truncated", truncated, truncated_closed_form, "Eqs. (4.2)-(4.4), I3/I1 = 0.4, tau = 1"),
        ("reduced", reduced, reduced_closed_form, "Eqs. (4.12)-(4.14), I3/I1 = 0.4, tau = 1"),
        ("general", general, None, "Eq. (3.3), I = (1, 1.5, 0.8), d = (0.2, 0, 1), kappa = 1"),
    ]
    only = set(sys.argv[1:])
    for name, f, closed, what in problems:
        if only and name not in only:
            continue
        start = time.time()
        y0 = OMEGA0 + [mp.mpf(1), mp.mpf(0), mp.mpf(0), mp.mpf(0)]
        sol = mp.odefun(with_orientation(f), 0, y0)
        rows = []
        worst = mp.mpf(0)
        for t in TIMES:
            y = sol(t)
            if closed is not None:
                c = closed(t)
                err = mp.sqrt(sum((a - b) ** 2 for a, b in zip(y[0:3], c))) / mp.sqrt(
                    sum(b**2 for b in c)
                )
                worst = max(worst, err)
            rows.append((t, y))
        if closed is not None and worst > mp.mpf("1e-30"):
            sys.exit(f"{name}: the integration and the closed form differ by {mp.nstr(worst, 3)}")
        path = os.path.join(HERE, f"{name}.csv")
        with open(path, "w") as out:
            out.write(f"# spintop bench reference: the {name} model, {what}\n")
            out.write("# Omega0 = (0, 0.1, 0.2) 1/tau and O(0) = identity, as exact binary doubles\n")
            out.write("# mpmath.odefun (Taylor series) at 40 digits; written by make_reference.py\n")
            if closed is not None:
                out.write(f"# Omega agrees with the printed closed form to {mp.nstr(worst, 3)} (relative)\n")
            out.write("t,omega1,omega2,omega3,qw,qx,qy,qz\n")
            for t, y in rows:
                out.write(",".join([mp.nstr(t, 6)] + [mp.nstr(v, 22, strip_zeros=False) for v in y]) + "\n")
        print(f"{name}: {len(rows)} rows in {time.time() - start:.1f} s -> {path}")


if __name__ == "__main__":
    main()
