#!/usr/bin/env python3
"""SciPy FITPACK peer of sjp10 Fig. 2: bicubic splines of the same signed
distance functions the sjp10_cells study fits, on the same validation points.

    sjp10_fitpack.py --results DIR [--dflab build/dflab] [--val-n 301] [--band 0.02]
                     [--cases circle,...] [--s0-n 9,17,...] [--rms 1e-3,...]

Shapes: configs/shapes/sjp10_{circle,convex,nonconvex,tip}.ini and the smooth
case of configs/paper/sjp10/sjp10_cells.ini (a circle centred outside the
square).  Exact SDF values come from `dflab probe` on a config that includes
the very shape files the studies use ([field] kind = exact), so the shapes
are identical; dflab's SDF is negative inside (sjp10: positive inside).

Methods (scipy.interpolate.RectBivariateSpline, kx = ky = 3):
  fitpack_s0        s = 0 on an n x n grid of the unit square: uniform bicubic
                    interpolation (not-a-knot ends), n = 9 .. 257;
  fitpack_adaptive  s > 0 on the val_n x val_n node grid: FITPACK chooses its
                    knots until the sum of squared residuals is <= s; s is
                    given as a target RMS residual r (s = N r^2, N data points).
Stored scalars = B-spline coefficients (len(get_coeffs())) + the knots of both
axes; coefficients alone are also written.
Validation (as the dflab studies, pht/validate.h): val_n^2 nodes plus the
(val_n - 1)^2 cell midpoints; 'off' excludes the medial band of width w by
the library's criterion (x is in the band iff |d(x)| + w - |d(x + w sign(d)
grad d)| > 1e-6 w + 1e-12 (1 + |x|)), evaluated with a second probe.
For s > 0 the node points are FITPACK's own data: the midpoint error
(val_mid_max) is the honest one there, and val_max covers both.

Writes DIR/sjp10_peers/sjp10_fitpack.csv (long format, one row per fit)
and DIR/sjp10_peers/README.txt; nothing is written when a probe fails.
"""
import argparse
import csv
import io
import math
import os
import subprocess
import sys
import tempfile
import time

import numpy as np
from scipy.interpolate import RectBivariateSpline

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

CASES = [
    ("circle", "[shape]\ninclude = {root}/configs/shapes/sjp10_circle.ini\n"),
    ("convex", "[shape]\ninclude = {root}/configs/shapes/sjp10_convex.ini\n"),
    ("nonconvex", "[shape]\ninclude = {root}/configs/shapes/sjp10_nonconvex.ini\n"),
    ("tip", "[shape]\ninclude = {root}/configs/shapes/sjp10_tip.ini\n"),
    # the [smooth] section of configs/paper/sjp10/sjp10_cells.ini
    ("smooth", "[shape]\nkind = circle\ncenter = -0.4 0.5\nradius = 0.1\n"),
]
S0_N = [9, 17, 33, 65, 129, 257]
RMS = [1e-3, 3e-4, 1e-4, 3e-5, 1e-5, 3e-6]


def probe(dflab, cfg, pts, tmp):
    """(value, gradient (m, 2)) of the exact SDF at pts (m, 2) by dflab probe."""
    pfile = os.path.join(tmp, "pts.csv")
    with open(pfile, "w") as fp:
        fp.write("x,y\n")
        np.savetxt(fp, pts, delimiter=",", fmt="%.17g")
    out = subprocess.run([dflab, "probe", cfg, "--points", pfile], check=True,
                         capture_output=True, text=True).stdout
    a = np.loadtxt(io.StringIO(out), delimiter=",", skiprows=1)
    return a[:, 3], a[:, 4:6]


def grid_axes(n):
    return np.linspace(0.0, 1.0, n)


def mid_axes(n):
    return (np.arange(n - 1) + 0.5) / (n - 1)


def mesh_points(x, y):
    """Points of the tensor grid x by y, x fastest (dflab's node order)."""
    X, Y = np.meshgrid(x, y)
    return np.c_[X.ravel(), Y.ravel()]


def band_flags(dflab, cfg, pts, d, g, w, tmp):
    """The medial band criterion of pht/validate.h (see the module doc)."""
    if w <= 0:
        return np.zeros(len(pts), bool)
    sig = np.where(d >= 0, 1.0, -1.0)
    y = pts + w * sig[:, None] * g
    dy, _ = probe(dflab, cfg, y, tmp)
    tol = 1e-6 * w + 1e-12 * (1 + np.linalg.norm(pts, axis=1))
    return np.abs(d) + w - np.abs(dy) > tol


def stats(err, off):
    e = np.abs(err)
    return {"max": float(e.max()), "mean": float(e.mean()), "rms": float(np.sqrt((e * e).mean())),
            "off_max": float(e[~off].max()) if (~off).any() else math.nan,
            "off_mean": float(e[~off].mean()) if (~off).any() else math.nan}


def evaluate(spl, xn, xm):
    """Spline values on the node grid and the midpoint grid, x fastest."""
    # RectBivariateSpline(x, y, z): z[i, j] = f(x[i], y[j]); ev(x, y) likewise
    vn = spl(xn, xn).T.ravel()
    vm = spl(xm, xm).T.ravel()
    return vn, vm


def run_case(name, text, dflab, val_n, w, tmp, s0_n=S0_N, rms=RMS):
    cfg = os.path.join(tmp, f"{name}.ini")
    with open(cfg, "w") as fp:
        fp.write(text.format(root=ROOT) + "[field]\nkind = exact\n")
    xn, xm = grid_axes(val_n), mid_axes(val_n)
    pn, pm = mesh_points(xn, xn), mesh_points(xm, xm)
    grids = [mesh_points(grid_axes(n), grid_axes(n)) for n in s0_n]
    allp = np.vstack([pn, pm] + grids)
    d, g = probe(dflab, cfg, allp, tmp)
    nn, nm = len(pn), len(pm)
    dn, dm = d[:nn], d[nn:nn + nm]
    off = band_flags(dflab, cfg, np.vstack([pn, pm]), d[:nn + nm], g[:nn + nm], w, tmp)
    rows = []

    def row(method, param, spl, seconds):
        vn, vm = evaluate(spl, xn, xm)
        st = stats(np.r_[vn - dn, vm - dm], off)
        coefs = len(spl.get_coeffs())
        tx, ty = spl.get_knots()
        rows.append({"case": name, "method": method, "param": param, "coeffs": coefs,
                     "knots_x": len(tx), "knots_y": len(ty), "scalars": coefs + len(tx) + len(ty),
                     "val_max": st["max"], "val_mean": st["mean"], "val_rms": st["rms"],
                     "val_off_max": st["off_max"], "val_off_mean": st["off_mean"],
                     "val_node_max": float(np.abs(vn - dn).max()),
                     "val_mid_max": float(np.abs(vm - dm).max()),
                     "val_points": nn + nm, "val_band_points": int(off.sum()),
                     "seconds": seconds})

    at = nn + nm
    for n, gp in zip(s0_n, grids):
        z = d[at:at + len(gp)].reshape(n, n).T  # z[i, j] = f(x_i, y_j)
        at += len(gp)
        t0 = time.perf_counter()
        spl = RectBivariateSpline(grid_axes(n), grid_axes(n), z, kx=3, ky=3, s=0)
        row("fitpack_s0", f"n={n}", spl, time.perf_counter() - t0)
    zdata = dn.reshape(val_n, val_n).T
    for r in rms:
        s = nn * r * r
        t0 = time.perf_counter()
        spl = RectBivariateSpline(xn, xn, zdata, kx=3, ky=3, s=s)
        row("fitpack_adaptive", f"rms={r:g}", spl, time.perf_counter() - t0)
        rows[-1]["s"] = s
    return rows


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--results", required=True, help="results directory (writes <DIR>/sjp10_peers/)")
    ap.add_argument("--dflab", default=os.environ.get("DFL_DFLAB", os.path.join(ROOT, "build", "dflab")))
    ap.add_argument("--val-n", type=int, default=301)
    ap.add_argument("--band", type=float, default=0.02)
    ap.add_argument("--cases", default=",".join(c for c, _ in CASES),
                    help="comma-separated subset of " + ",".join(c for c, _ in CASES))
    ap.add_argument("--s0-n", default=",".join(map(str, S0_N)), help="grid sizes of the s = 0 fits")
    ap.add_argument("--rms", default=",".join(map(str, RMS)), help="target RMS residuals of the s > 0 fits")
    a = ap.parse_args(argv)
    want = a.cases.split(",")
    unknown = [c for c in want if c not in dict(CASES)]
    if unknown:
        print(f"sjp10_fitpack: error: --cases: unknown case(s) {', '.join(unknown)}", file=sys.stderr)
        return 2
    if a.val_n < 2:
        print("sjp10_fitpack: error: --val-n: expected >= 2", file=sys.stderr)
        return 2
    try:
        s0_n = [int(v) for v in a.s0_n.split(",") if v]
        rms = [float(v) for v in a.rms.split(",") if v]
    except ValueError:
        print("sjp10_fitpack: error: --s0-n / --rms: expected comma-separated numbers", file=sys.stderr)
        return 2
    if any(n < 4 for n in s0_n) or any(not r > 0 for r in rms):
        print("sjp10_fitpack: error: --s0-n: expected n >= 4; --rms: expected r > 0", file=sys.stderr)
        return 2
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        try:
            for name, text in CASES:
                if name in want:
                    rows += run_case(name, text, a.dflab, a.val_n, a.band, tmp, s0_n, rms)
        except subprocess.CalledProcessError as e:
            print(f"sjp10_fitpack: error: dflab probe failed: {e.stderr.strip()}", file=sys.stderr)
            return 1
    out_dir = os.path.join(a.results, "sjp10_peers")
    os.makedirs(out_dir, exist_ok=True)
    cols = ["case", "method", "param", "s", "coeffs", "knots_x", "knots_y", "scalars", "val_max",
            "val_mean", "val_rms", "val_off_max", "val_off_mean", "val_node_max", "val_mid_max",
            "val_points", "val_band_points", "seconds"]
    path = os.path.join(out_dir, "sjp10_fitpack.csv")
    tmpf = path + ".tmp"
    with open(tmpf, "w", newline="") as fp:
        wr = csv.DictWriter(fp, fieldnames=cols)
        wr.writeheader()
        for r in rows:
            wr.writerow({k: (repr(v) if isinstance(v, float) else v) for k, v in
                         ((c, r.get(c, "")) for c in cols)})
    os.replace(tmpf, path)
    with open(os.path.join(out_dir, "README.txt"), "w") as fp:
        fp.write("sjp10_fitpack.csv: SciPy FITPACK peer of sjp10 Fig. 2 "
                 "(scripts/peers/sjp10_fitpack.py; see its docstring).\n")
    print(f"sjp10_fitpack: wrote {path} ({len(rows)} rows)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
