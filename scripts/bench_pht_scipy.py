#!/usr/bin/env python3
"""SciPy peers of the PHT evaluation rows of tests/bench/bench_pht.c.

    bench_pht_scipy.py --peer rbs  --n N --points M [--reps R]
    bench_pht_scipy.py --peer mapc --n N --points M [--reps R]

rbs: scipy.interpolate.RectBivariateSpline (FITPACK, bicubic, s = 0: the
     interpolant with not-a-knot ends, N^2 coefficients) of the signed
     distance of the bench's circle (centre (0.5, 0.5), radius 0.3, negative
     inside) sampled on the N x N nodes of [0, 1]^2; timed: value and
     gradient (ev, ev dx = 1, ev dy = 1) at M uniform random points.
mapc: scipy.ndimage.map_coordinates, order 3 (cubic B-spline), of the
     bench's torus (centre (0.5, 0.5, 0.5), axis z, R 0.3, r 0.1) sampled on
     the N^3 nodes of [0, 1]^3; the B-spline prefilter (spline_filter) runs
     once, untimed (a build cost); timed: the value alone at M uniform random
     points (map_coordinates has no gradient: the peer is charged one
     interpolation where dflab computes value and gradient).

The time is CPU time of this process (time.process_time, best of --reps):
SciPy evaluates on one thread, and CPU time does not count the waits of a
shared machine.  Prints `rate: <points per CPU-second>`, `coefficients:
<stored doubles>` and `maxerr: <max |s - d| at the timed points>` (the
accuracy the rate was bought at)."""
import argparse
import sys
import time

import numpy as np


def circle_sdf(x, y):
    return np.hypot(x - 0.5, y - 0.5) - 0.3


def torus_sdf(x, y, z):
    q = np.hypot(x - 0.5, y - 0.5) - 0.3
    return np.hypot(q, z - 0.5) - 0.1


def best(reps, fn):
    t = float("inf")
    out = None
    for _ in range(reps):
        t0 = time.process_time()
        out = fn()
        t = min(t, time.process_time() - t0)
    return t, out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--peer", choices=("rbs", "mapc"), required=True)
    ap.add_argument("--n", type=int, required=True)
    ap.add_argument("--points", type=int, required=True)
    ap.add_argument("--reps", type=int, default=3)
    a = ap.parse_args()
    if a.n < 4 or a.points < 1 or a.reps < 1:
        print("bench_pht_scipy: --n >= 4, --points >= 1, --reps >= 1", file=sys.stderr)
        return 2
    rng = np.random.default_rng(11)
    t = np.linspace(0.0, 1.0, a.n)
    if a.peer == "rbs":
        from scipy.interpolate import RectBivariateSpline
        X, Y = np.meshgrid(t, t, indexing="ij")
        spl = RectBivariateSpline(t, t, circle_sdf(X, Y), kx=3, ky=3, s=0)
        px, py = rng.random(a.points), rng.random(a.points)

        def run():
            return spl.ev(px, py), spl.ev(px, py, dx=1), spl.ev(px, py, dy=1)

        sec, (v, _, _) = best(a.reps, run)
        err = np.max(np.abs(v - circle_sdf(px, py)))
        ncoef = len(spl.get_coeffs())
    else:
        from scipy.ndimage import map_coordinates, spline_filter
        X, Y, Z = np.meshgrid(t, t, t, indexing="ij")
        coef = spline_filter(torus_sdf(X, Y, Z), order=3)
        p = rng.random((3, a.points))
        idx = p * (a.n - 1)

        def run():
            return map_coordinates(coef, idx, order=3, prefilter=False)

        sec, v = best(a.reps, run)
        err = np.max(np.abs(v - torus_sdf(p[0], p[1], p[2])))
        ncoef = coef.size
    print(f"rate: {a.points / sec:.6e}")
    print(f"coefficients: {ncoef}")
    print(f"maxerr: {err:.6e}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
