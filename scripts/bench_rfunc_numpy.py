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

--kind strip2 | disk3 | strip3 times the strip and 3D kernels instead
(field_kind; 3D: the curve lifted to z = 0.05 sin(3 th), points at z = 0).

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


def field_kind(a, b, p, x, y, z, kind, block=8):
    """The strip trim (2D, kind strip2) and the 3D segments (disk3, strip3)
    of src/rfunc/batch.c's other kernels: with e = (b - a)/d,
    p1 = w . e, p2 = -(v . e), t = 2 p1 p2 / (p1 + p2 + |(p1, p2)|),
    mt = max(-t, 0), h grad h = f grad f - mt (p2 - p1)/r e for the strip;
    in 3D f^2 = |w|^2 - (w . e)^2 (the two normals' squares) and
    f grad f = w - (w . e) e."""
    dim = a.shape[1]
    U = b - a
    d = np.sqrt((U * U).sum(axis=1))
    e = U / d[:, None]
    idd = 1.0 / d
    pts = np.stack([x, y] + ([z] if dim == 3 else []), axis=1)
    m = x.size
    u = np.empty(m)
    g = np.empty((m, dim))
    strip = kind.startswith("strip")
    for s0 in range(0, m, block):
        P = pts[s0:s0 + block, None, :]
        W = P - a[None, :, :]
        V = W - U[None, :, :]
        we = (W * e).sum(axis=2)
        if dim == 2:
            n = np.stack([e[:, 1], -e[:, 0]], axis=1)
            f = (W * n).sum(axis=2)
            f2 = f * f
            fg = f[:, :, None] * n[None, :, :]
        else:
            fg = W - we[:, :, None] * e[None, :, :]
            f2 = (fg * fg).sum(axis=2)
        if strip:
            p1, p2 = we, -(V * e).sum(axis=2)
            r = np.sqrt(p1 * p1 + p2 * p2)
            t = 2.0 * p1 * p2 / (p1 + p2 + r)
            mt = np.maximum(-t, 0.0)
            hg = fg - (mt * (p2 - p1) / r)[:, :, None] * e[None, :, :]
        else:
            nt = (W * V).sum(axis=2) * idd
            mt = np.maximum(nt, 0.0)
            hg = fg + (mt * idd)[:, :, None] * (W + V)
        h2 = f2 + mt * mt
        r2 = 1.0 / h2
        w = ipow(r2, p // 2)
        if p % 2:
            w = w * np.sqrt(r2) if p > 1 else np.sqrt(r2)
        q = w * r2
        S = w.sum(axis=1)
        Vs = (q[:, :, None] * hg).sum(axis=1)
        us = S ** (-1.0 / p)
        u[s0:s0 + block] = us
        g[s0:s0 + block] = (us ** (p + 1))[:, None] * Vs
    return u, g[:, 0], g[:, 1]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--p", type=int, default=2)
    ap.add_argument("--segments", type=int, default=1500)
    ap.add_argument("--grid", type=int, default=96)
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--check", type=int, nargs="*", default=[])
    ap.add_argument("--kind", default="disk2", choices=["disk2", "strip2", "disk3", "strip3"])
    a = ap.parse_args()
    A, B = polyline(a.segments)
    if a.kind.endswith("3"):
        # the 3D polyline: the same closed curve lifted to z = 0.05 sin(3 th)
        th = 2.0 * np.pi * np.arange(a.segments) / a.segments
        A = np.concatenate([A, (0.05 * np.sin(3.0 * th))[:, None]], axis=1)
        B = np.roll(A, -1, axis=0)
    n = a.grid
    t = np.arange(n) / (n - 1.0)
    X, Y = np.meshgrid(t, t)  # row j = y index, x fastest when flattened
    x, y = X.ravel(), Y.ravel()
    best = float("inf")
    for _ in range(a.reps):
        t0 = time.perf_counter()
        if a.kind == "disk2":
            u, gx, gy = field(A, B, a.p, x, y)
        else:
            u, gx, gy = field_kind(A, B, a.p, x, y, np.zeros_like(x), a.kind)
        best = min(best, time.perf_counter() - t0)
    print(f"rate: {x.size * a.segments / best:.6e}")
    for i in a.check:
        print(f"check {i} {u[i]:.17g} {gx[i]:.17g} {gy[i]:.17g}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
