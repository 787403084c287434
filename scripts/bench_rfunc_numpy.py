#!/usr/bin/env python3
"""numpy version of the bs04 field that tests/bench/bench_rfunc.c times.

The same formulas as src/rfunc/batch.c (2D polyline, disk trim of
eq. 4, R-equivalence of order p, value + gradient):

    w = x - a, v = x - b, d = |b - a|, n = (b_y - a_y, -(b_x - a_x)) / d
    f = w . n,  -t = (w . v) / d,  mt = max(-t, 0),  h^2 = f^2 + mt^2
    h grad h = f n + mt (w + v) / d
    S = sum h^-p,  V = sum h^-(p+2) h grad h,  u = S^(-1/p),  grad u = u^(p+1) V

written the way numpy wants it: broadcasting over a block of points x all
segments (2D arrays), one pass of whole-array operations per block.  The
polyline and grid are the benchmark's (same formula as the C side):
a closed wobbly circle r(th) = 0.3 + 0.05 sin(5 th) around (0.5, 0.5) with
--segments vertices, and an n x n grid on [0, 1]^2, node (i, j) at
(i/(n-1), j/(n-1)).

Prints `rate: <segment evaluations per second>` (best of --reps) and, for
the C side to check that this is the same function, `check <i> <u> <gx> <gy>`
for a few node indices i (x fastest)."""
import argparse
import sys
import time

import numpy as np


def polyline(nseg):
    th = 2.0 * np.pi * np.arange(nseg) / nseg
    r = 0.3 + 0.05 * np.sin(5.0 * th)
    a = np.stack([0.5 + r * np.cos(th), 0.5 + r * np.sin(th)], axis=1)
    b = np.roll(a, -1, axis=0)
    return a, b


def ipow(a, k):
    """a**k for an integer k >= 0 by repeated squaring (numpy's ** takes
    the slow generic pow() path for exponents other than 0, 1, 2, 0.5)."""
    r = None
    while k > 0:
        if k & 1:
            r = a if r is None else r * a
        k >>= 1
        if k:
            a = a * a
    return r if r is not None else np.ones_like(a)


def field(a, b, p, x, y, block=8):
    """u and grad u at the points (x, y) (1D arrays)."""
    ux, uy = b[:, 0] - a[:, 0], b[:, 1] - a[:, 1]
    d = np.hypot(ux, uy)
    nx, ny = uy / d, -ux / d
    idd = 1.0 / d
    m = x.size
    u = np.empty(m)
    gx = np.empty(m)
    gy = np.empty(m)
    for s in range(0, m, block):
        xs = x[s:s + block, None]
        ys = y[s:s + block, None]
        wx = xs - a[:, 0]
        wy = ys - a[:, 1]
        vx = wx - ux
        vy = wy - uy
        f = wx * nx + wy * ny
        nt = (wx * vx + wy * vy) * idd
        mt = np.maximum(nt, 0.0)
        h2 = f * f + mt * mt
        mi = mt * idd
        hgx = f * nx + mi * (wx + vx)
        hgy = f * ny + mi * (wy + vy)
        r2 = 1.0 / h2
        w = ipow(r2, p // 2)  # h^-p (times 1/h for odd p below)
        if p % 2:
            w = w * np.sqrt(r2) if p > 1 else np.sqrt(r2)
        q = w * r2
        S = w.sum(axis=1)
        Vx = (q * hgx).sum(axis=1)
        Vy = (q * hgy).sum(axis=1)
        us = S ** (-1.0 / p)
        up = us ** (p + 1)
        u[s:s + block] = us
        gx[s:s + block] = up * Vx
        gy[s:s + block] = up * Vy
    return u, gx, gy


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--p", type=int, default=2)
    ap.add_argument("--segments", type=int, default=1500)
    ap.add_argument("--grid", type=int, default=96)
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--check", type=int, nargs="*", default=[])
    a = ap.parse_args()
    A, B = polyline(a.segments)
    n = a.grid
    t = np.arange(n) / (n - 1.0)
    X, Y = np.meshgrid(t, t)  # row j = y index, x fastest when flattened
    x, y = X.ravel(), Y.ravel()
    best = float("inf")
    for _ in range(a.reps):
        t0 = time.perf_counter()
        u, gx, gy = field(A, B, a.p, x, y)
        best = min(best, time.perf_counter() - t0)
    print(f"rate: {x.size * a.segments / best:.6e}")
    for i in a.check:
        print(f"check {i} {u[i]:.17g} {gx[i]:.17g} {gy[i]:.17g}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
