#!/usr/bin/env python3
"""SciPy FITPACK peer of sjp10 Fig. 2: bicubic splines of the same signed
distance functions the sjp10_cells study fits, at their best: fine samples,
FITPACK's own knot placement, and least-squares splines on knots graded
towards the medial axis; errors on a dense probe plus multi-scale points
near the medial axis and near the surface.

    sjp10_fitpack.py --results DIR [--dflab build/dflab] [--cases circle,...]
                     [--data-n 1201] [--s0-n 9,17,...] [--rms 1e-4,...]
                     [--lsq-m 11,27,...] [--lsq-p 1,2,3] [--val-n 401]
                     [--seed-n 241] [--band 0.02] [--eps 1e-4] [--lsq-check]

Shapes: configs/shapes/sjp10_{circle,convex,nonconvex,tip}.ini (tip: the
teardrop) and the smooth case of configs/paper/sjp10/sjp10_cells.ini (a
circle centred outside the square).  Exact SDF values come from `dflab
probe` on a config that includes the very shape files the studies use
([field] kind = exact).  dflab's SDF is negative inside (sjp10: positive).

Data: the exact SDF on the data_n x data_n node grid of the unit square
(default 1201^2, spacing 1/1200).  sample_s is the wall time of that probe
(exact SDF plus the probe's CSV input/output, so an upper bound of the
sample cost), charged to every fit of the shape; fit_s is the fit alone.

Methods (bicubic, kx = ky = 3):
  fitpack_s0        RectBivariateSpline, s = 0, on the n x n sub-grid of the
                    data (n - 1 divides data_n - 1): interpolation with
                    not-a-knot ends, n + 4 knots per axis, n^2 coefficients;
  fitpack_smooth    RectBivariateSpline on all data with s = N r^2 (N data
                    points, r a target RMS residual): FITPACK places knots
                    until the residual sum of squares fp <= s;
  lsq_graded        the least-squares tensor spline on user knots: m interior
                    knots per axis, graded towards c (power p, p = 1 uniform):
                    u_j = (j + 1) / (m + 1), t = c - c ((c - u) / c)^p below c
                    and c + (1 - c) ((u - c) / (1 - c))^p above (u_j on the
                    knot share c of the left side).  c is the median of the
                    medial-axis points' coordinate on that axis when their
                    interquartile range is < 0.02 (the axis sees a point or an
                    axis-parallel medial axis; the circle: 0.5, 0.5), else
                    that axis is uniform: a tensor grid can grade only towards
                    axis-parallel features.  On grid data the least-squares
                    problem separates: C = Bx^+ Z By^+T (B the collocation
                    matrices, ^+ the pseudo-inverse, the minimum-norm solution
                    where a cell holds too few data).  Knots finer than the
                    data make the problem ill-posed (wild values between data
                    nodes): while an axis' collocation matrix has a condition
                    number > 1e3, one knot of its narrowest gap (the one
                    nearer c) is dropped (knots_dropped; cond is the larger
                    axis' condition number after; rank_deficiency counts the
                    coefficients the data do not determine, 0 when the
                    knots are well-posed).  --lsq-check also runs
                    LSQBivariateSpline on the same data and knots (bbox the unit
                    square) and writes the largest coefficient difference
                    (lsq_check_diff).
Sizes: coefficients = (nx - 4)(ny - 4) for nx, ny knots; knots = nx + ny;
bytes = 8 (coefficients + knots), the doubles a user must store.

Validation (one point set per shape, the same for every fit, none a data
node in general position):
  dense    the val_n^2 grid ((i + g) / val_n), g = 0.618...;
  medial   from every node x of the seed_n^2 grid whose normal line meets
           the medial axis within w0 = 2 sqrt(2) / (seed_n - 1) (the band
           criterion of pht/validate.h with w = w0), the crossing x_m is
           located on the criterion's defect by 8 rounds of a 16-section search
           of [0, w0] (to w0 16^-8 ~ 2e-10 w0); the
           points x_m + o n, o = 0 and +- h0 2^(-k/2), k = 0..37
           (h0 = 1 / (seed_n - 1), down to ~1e-8), n = grad d(x), inside
           the square;
  surface  from every seed node with |d| < h0, the footpoint p = x - d n
           and p + o n, o = +-1e-5, +-1e-4, +-1e-3, +-3e-3, inside the square.
The medial band of width w (--band) is the library's criterion (x is in the
band iff |d(x)| + w - |d(x + w sign(d) grad d)| > 1e-6 w + 1e-12 (1 + |x|)).
Columns: max_whole (all points), max_band / max_off (in / off the band),
near_medial_max, near_surface_max, share_above_eps (share of all points with
error > eps), data_n / data_max / data_rms (count, max and RMS residual at
the data nodes the fit used; s = 0 interpolates them to rounding), fp (FITPACK's residual sum of squares over
all data, s > 0 rows).  A non-finite spline value is an error of +inf.

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
import warnings

import numpy as np
from scipy.interpolate import BSpline, BivariateSpline, LSQBivariateSpline, RectBivariateSpline

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

CASES = [
    ("circle", "[shape]\ninclude = {root}/configs/shapes/sjp10_circle.ini\n"),
    ("convex", "[shape]\ninclude = {root}/configs/shapes/sjp10_convex.ini\n"),
    ("nonconvex", "[shape]\ninclude = {root}/configs/shapes/sjp10_nonconvex.ini\n"),
    ("tip", "[shape]\ninclude = {root}/configs/shapes/sjp10_tip.ini\n"),
    # the [smooth] section of configs/paper/sjp10/sjp10_cells.ini
    ("smooth", "[shape]\nkind = circle\ncenter = -0.4 0.5\nradius = 0.1\n"),
]
S0_N = [9, 17, 25, 49, 101, 151, 301, 601, 1201]
RMS = [1e-4, 1e-5, 1e-6, 5e-7]
LSQ_M = [11, 27, 59, 123]
LSQ_P = [1, 2, 3]
GOLD = 0.6180339887498949
MEDIAL_SECTIONS = 16
MEDIAL_ROUNDS = 8
MEDIAL_SCALES = 37
SURFACE_OFFSETS = [1e-5, 1e-4, 1e-3, 3e-3]
GRADE_IQR = 0.02
COND_MAX = 1e3

COLS = ["method", "shape", "setting", "coefficients", "knots", "knots_x", "knots_y", "bytes",
        "s", "fp", "data_n", "data_max", "data_rms", "fit_s", "sample_s", "max_whole",
        "max_band", "max_off", "near_medial_max", "near_surface_max", "eps", "share_above_eps",
        "val_points", "band_points", "medial_points", "surface_points", "grade_cx", "grade_cy",
        "cond", "knots_dropped", "rank_deficiency", "lsq_check_diff"]


def write_points(path, pts):
    with open(path, "w") as fp:
        fp.write("x,y\n")
        np.savetxt(fp, pts, delimiter=",", fmt="%.17g")


def write_grid(path, x):
    """The tensor grid x by x, x fastest, each coordinate formatted once."""
    xs = [repr(float(v)) for v in x]
    with open(path, "w") as fp:
        fp.write("x,y\n")
        for yv in xs:
            fp.write("".join(f"{xv},{yv}\n" for xv in xs))


def run_probe(dflab, cfg, pfile, cols):
    out = subprocess.run([dflab, "probe", cfg, "--points", pfile], check=True,
                         capture_output=True, text=True).stdout
    return np.loadtxt(io.StringIO(out), delimiter=",", skiprows=1, usecols=cols, ndmin=2)


def probe(dflab, cfg, pts, tmp):
    """(value, gradient (m, 2)) of the exact SDF at pts (m, 2)."""
    if len(pts) == 0:
        return np.zeros(0), np.zeros((0, 2))
    pfile = os.path.join(tmp, "pts.csv")
    write_points(pfile, pts)
    a = run_probe(dflab, cfg, pfile, (3, 4, 5))
    return a[:, 0], a[:, 1:3]


def defect(dflab, cfg, pts, d, g, t, tmp):
    """|d(x)| + t - |d(x + t sign(d) grad d)| and the criterion's tolerance."""
    sig = np.where(d >= 0, 1.0, -1.0)
    dy, _ = probe(dflab, cfg, pts + (t * sig)[:, None] * g, tmp)
    tol = 1e-6 * t + 1e-12 * (1 + np.linalg.norm(pts, axis=1))
    return np.abs(d) + t - np.abs(dy), tol


def inside(p):
    return np.all((p >= 0.0) & (p <= 1.0), axis=1)


def validation_set(dflab, cfg, val_n, seed_n, w, tmp):
    """Points, exact values, masks (band, medial, surface) and the medial
    crossings (see the module doc)."""
    xv = (np.arange(val_n) + GOLD) / val_n
    X, Y = np.meshgrid(xv, xv)
    dense = np.c_[X.ravel(), Y.ravel()]
    xs = np.linspace(0.0, 1.0, seed_n)
    X, Y = np.meshgrid(xs, xs)
    seeds = np.c_[X.ravel(), Y.ravel()]
    ds, gs = probe(dflab, cfg, seeds, tmp)
    h0 = 1.0 / (seed_n - 1)
    w0 = 2.0 * math.sqrt(2.0) * h0
    df, tol = defect(dflab, cfg, seeds, ds, gs, w0, tmp)
    sel = df > tol
    xm_seed, dm, gm = seeds[sel], ds[sel], gs[sel]
    # the crossing is the first t in (0, w0] past which the defect exceeds
    # its tolerance: MEDIAL_ROUNDS rounds of a MEDIAL_SECTIONS-section search
    # (one probe each) shrink [lo, hi] to w0 MEDIAL_SECTIONS^-MEDIAL_ROUNDS
    lo, hi = np.zeros(len(dm)), np.full(len(dm), w0)
    sig = np.where(dm >= 0, 1.0, -1.0)
    frac = np.arange(1, MEDIAL_SECTIONS) / MEDIAL_SECTIONS
    for _ in range(MEDIAL_ROUNDS if len(dm) else 0):
        t = lo[:, None] + (hi - lo)[:, None] * frac[None, :]
        q = xm_seed[:, None, :] + (t * sig[:, None])[:, :, None] * gm[:, None, :]
        dy, _ = probe(dflab, cfg, q.reshape(-1, 2), tmp)
        dy = dy.reshape(t.shape)
        tol = 1e-6 * t + 1e-12 * (1 + np.linalg.norm(xm_seed, axis=1))[:, None]
        past = np.abs(dm)[:, None] + t - np.abs(dy) > tol
        first = np.where(past.any(axis=1), past.argmax(axis=1), len(frac))
        t_ext = np.c_[lo, t, hi]
        lo, hi = t_ext[np.arange(len(lo)), first], t_ext[np.arange(len(lo)), first + 1]
    sig = np.where(dm >= 0, 1.0, -1.0)
    xm = xm_seed + (hi * sig)[:, None] * gm
    offs = np.r_[0.0, h0 * 2.0 ** (-np.arange(MEDIAL_SCALES + 1) / 2.0)]
    offs = np.r_[offs, -offs[1:]]
    medial = (xm[:, None, :] + offs[None, :, None] * gm[:, None, :]).reshape(-1, 2)
    medial = medial[inside(medial)]
    near = np.abs(ds) < h0
    foot = seeds[near] - ds[near][:, None] * gs[near]
    so = np.r_[0.0, SURFACE_OFFSETS, -np.array(SURFACE_OFFSETS)]
    surface = (foot[:, None, :] + so[None, :, None] * gs[near][:, None, :]).reshape(-1, 2)
    surface = surface[inside(surface)]
    pts = np.vstack([dense, medial, surface])
    d, g = probe(dflab, cfg, pts, tmp)
    if w > 0:
        df, tol = defect(dflab, cfg, pts, d, g, w, tmp)
        band = df > tol
    else:
        band = np.zeros(len(pts), bool)
    kind = np.r_[np.zeros(len(dense), int), np.ones(len(medial), int), np.full(len(surface), 2)]
    xm_in = xm[inside(xm)]
    return pts, d, band, kind == 1, kind == 2, xm_in


def grade_centre(xm, axis):
    """The knot grading centre of an axis, or None (module doc)."""
    if len(xm) < 1:
        return None
    q1, med, q3 = np.percentile(xm[:, axis], [25, 50, 75])
    if q3 - q1 >= GRADE_IQR or not 0.0 < med < 1.0:
        return None
    return float(med)


def graded_knots(m, p, c):
    """m interior knots on (0, 1), graded towards c with power p (module doc)."""
    u = (np.arange(m) + 1.0) / (m + 1.0)
    if c is None or p == 1:
        return u
    t = np.where(u < c, c - c * np.clip((c - u) / c, 0, None) ** p,
                 c + (1 - c) * np.clip((u - c) / (1 - c), 0, None) ** p)
    return t


def collocation(x, kint):
    return BSpline.design_matrix(x, np.r_[[0.0] * 4, kint, [1.0] * 4], 3).toarray()


def well_posed(x, kint, c):
    """kint without the knots that make the least-squares problem on the
    data x ill-posed: while the collocation matrix's condition number
    exceeds COND_MAX, drop one knot of the narrowest gap (the one nearer c).
    Returns (knots, condition number, knots dropped)."""
    kint = np.asarray(kint, float)
    dropped = 0
    while True:
        sv = np.linalg.svd(collocation(x, kint), compute_uv=False)
        cond = sv[0] / sv[-1] if sv[-1] > 0 else math.inf
        if cond <= COND_MAX or len(kint) == 0:
            return kint, cond, dropped
        ends = np.r_[0.0, kint, 1.0]
        j = int(np.argmin(np.diff(ends)))  # gap between ends[j] and ends[j + 1]
        cand = [i for i in (j, j + 1) if 1 <= i <= len(kint)]
        ref = 0.5 if c is None else c
        drop = min(cand, key=lambda i: abs(ends[i] - ref)) - 1
        kint = np.delete(kint, drop)
        dropped += 1


def lsq_tensor(x, z, kx_int, ky_int):
    """Least-squares bicubic coefficients on the grid x by x (z[i, j] = f(x_i, x_j))."""
    tx = np.r_[[0.0] * 4, kx_int, [1.0] * 4]
    ty = np.r_[[0.0] * 4, ky_int, [1.0] * 4]
    Bx, By = collocation(x, kx_int), collocation(x, ky_int)
    C = np.linalg.pinv(Bx) @ z @ np.linalg.pinv(By).T
    deficiency = Bx.shape[1] * By.shape[1] - np.linalg.matrix_rank(Bx) * np.linalg.matrix_rank(By)
    return BivariateSpline._from_tck((tx, ty, C.ravel(), 3, 3)), C, int(deficiency)


def run_case(name, text, a, tmp):
    cfg = os.path.join(tmp, f"{name}.ini")
    with open(cfg, "w") as fp:
        fp.write(text.format(root=ROOT) + "[field]\nkind = exact\n")
    n = a.data_n
    x = np.linspace(0.0, 1.0, n)
    gfile = os.path.join(tmp, "grid.csv")
    write_grid(gfile, x)
    t0 = time.perf_counter()
    z = run_probe(a.dflab, cfg, gfile, (3,))[:, 0].reshape(n, n).T  # z[i, j] = f(x_i, y_j)
    sample_s = time.perf_counter() - t0
    pts, d, band, med, surf, xm = validation_set(a.dflab, cfg, a.val_n, a.seed_n, a.band, tmp)
    cx, cy = grade_centre(xm, 0), grade_centre(xm, 1)
    rows = []

    def row(method, setting, spl, fit_s, data_err, coeffs, tx, ty, **extra):
        v = spl.ev(pts[:, 0], pts[:, 1])
        e = np.abs(v - d)
        e = np.where(np.isfinite(e), e, math.inf)
        de = np.abs(data_err)
        de = np.where(np.isfinite(de), de, math.inf)

        def mx(mask):
            return float(e[mask].max()) if mask.any() else math.nan
        r = {"method": method, "shape": name, "setting": setting, "coefficients": coeffs,
             "knots": len(tx) + len(ty), "knots_x": len(tx), "knots_y": len(ty),
             "bytes": 8 * (coeffs + len(tx) + len(ty)), "data_n": de.size,
             "data_max": float(de.max()), "data_rms": float(np.sqrt(np.mean(de * de))),
             "fit_s": fit_s, "sample_s": sample_s, "max_whole": float(e.max()),
             "max_band": mx(band), "max_off": mx(~band), "near_medial_max": mx(med),
             "near_surface_max": mx(surf), "eps": a.eps,
             "share_above_eps": float(np.mean(e > a.eps)), "val_points": len(e),
             "band_points": int(band.sum()), "medial_points": int(med.sum()),
             "surface_points": int(surf.sum()),
             "grade_cx": "" if cx is None else cx, "grade_cy": "" if cy is None else cy}
        r.update(extra)
        rows.append(r)

    for m in a.s0_n:
        step = (n - 1) // (m - 1)
        xs, zs = x[::step], z[::step, ::step]
        t0 = time.perf_counter()
        spl = RectBivariateSpline(xs, xs, zs, kx=3, ky=3, s=0)
        fit_s = time.perf_counter() - t0
        tx, ty = spl.get_knots()
        row("fitpack_s0", f"n={m}", spl, fit_s, spl(xs, xs) - zs, len(spl.get_coeffs()), tx, ty)
    for r in a.rms:
        s = n * n * r * r
        t0 = time.perf_counter()
        spl = RectBivariateSpline(x, x, z, kx=3, ky=3, s=s)
        fit_s = time.perf_counter() - t0
        tx, ty = spl.get_knots()
        row("fitpack_smooth", f"rms={r:g}", spl, fit_s, spl(x, x) - z, len(spl.get_coeffs()), tx, ty,
            s=s, fp=float(spl.get_residual()))
    for m in a.lsq_m:
        for p in a.lsq_p:
            if p != 1 and cx is None and cy is None:
                continue  # nothing to grade towards: the p = 1 row is the fit
            kx_int, cond_x, drop_x = well_posed(x, graded_knots(m, p, cx), cx)
            ky_int, cond_y, drop_y = well_posed(x, graded_knots(m, p, cy), cy)
            t0 = time.perf_counter()
            spl, C, deficiency = lsq_tensor(x, z, kx_int, ky_int)
            fit_s = time.perf_counter() - t0
            tx, ty = spl.get_knots()
            extra = {"rank_deficiency": deficiency, "cond": max(cond_x, cond_y),
                     "knots_dropped": drop_x + drop_y}
            if a.lsq_check:
                X, Y = np.meshgrid(x, x, indexing="ij")
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")  # the rank is in rank_deficiency
                    ref = LSQBivariateSpline(X.ravel(), Y.ravel(), z.ravel(), kx_int, ky_int,
                                             bbox=[0.0, 1.0, 0.0, 1.0], kx=3, ky=3)
                extra["lsq_check_diff"] = float(np.abs(ref.get_coeffs() - C.ravel()).max())
            row("lsq_graded", f"m={m} p={p:g}", spl, fit_s, spl(x, x) - z, C.size, tx, ty,
                fp=float(np.sum((spl(x, x) - z) ** 2)), **extra)
    return rows


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--results", required=True, help="results directory (writes <DIR>/sjp10_peers/)")
    ap.add_argument("--dflab", default=os.environ.get("DFL_DFLAB", os.path.join(ROOT, "build", "dflab")))
    ap.add_argument("--cases", default=",".join(c for c, _ in CASES),
                    help="comma-separated subset of " + ",".join(c for c, _ in CASES))
    ap.add_argument("--data-n", type=int, default=1201, help="data grid nodes per axis, >= 4")
    ap.add_argument("--s0-n", default=",".join(map(str, S0_N)),
                    help="sub-grid sizes of the s = 0 fits (n - 1 divides data_n - 1)")
    ap.add_argument("--rms", default=",".join(map(str, RMS)), help="target RMS residuals of the s > 0 fits")
    ap.add_argument("--lsq-m", default=",".join(map(str, LSQ_M)), help="interior knots per axis of the LSQ fits")
    ap.add_argument("--lsq-p", default=",".join(map(str, LSQ_P)), help="grading powers of the LSQ fits (>= 1)")
    ap.add_argument("--val-n", type=int, default=401, help="dense validation grid per axis, >= 2")
    ap.add_argument("--seed-n", type=int, default=241, help="seed grid of the medial/surface points, >= 3")
    ap.add_argument("--band", type=float, default=0.02)
    ap.add_argument("--eps", type=float, default=1e-4, help="error level of share_above_eps")
    ap.add_argument("--lsq-check", action="store_true", help="also fit with LSQBivariateSpline (slow)")
    a = ap.parse_args(argv)
    want = a.cases.split(",")
    unknown = [c for c in want if c not in dict(CASES)]
    if unknown:
        print(f"sjp10_fitpack: error: --cases: unknown case(s) {', '.join(unknown)}", file=sys.stderr)
        return 2
    if a.data_n < 4 or a.val_n < 2 or a.seed_n < 3:
        print("sjp10_fitpack: error: --data-n: expected >= 4, --val-n >= 2, --seed-n >= 3", file=sys.stderr)
        return 2
    try:
        a.s0_n = [int(v) for v in a.s0_n.split(",") if v]
        a.rms = [float(v) for v in a.rms.split(",") if v]
        a.lsq_m = [int(v) for v in a.lsq_m.split(",") if v]
        a.lsq_p = [float(v) for v in a.lsq_p.split(",") if v]
    except ValueError:
        print("sjp10_fitpack: error: --s0-n / --rms / --lsq-m / --lsq-p: expected comma-separated numbers",
              file=sys.stderr)
        return 2
    if any(m < 4 or m > a.data_n or (a.data_n - 1) % (m - 1) for m in a.s0_n):
        print(f"sjp10_fitpack: error: --s0-n: expected 4 <= n <= {a.data_n} with n - 1 dividing "
              f"{a.data_n - 1}", file=sys.stderr)
        return 2
    if any(not (r > 0 and math.isfinite(r)) for r in a.rms):
        print("sjp10_fitpack: error: --rms: expected r > 0", file=sys.stderr)
        return 2
    if any(m < 1 for m in a.lsq_m) or any(not (p >= 1 and math.isfinite(p)) for p in a.lsq_p):
        print("sjp10_fitpack: error: --lsq-m: expected m >= 1; --lsq-p: expected p >= 1", file=sys.stderr)
        return 2
    if not (a.band >= 0 and math.isfinite(a.band)) or not (a.eps > 0 and math.isfinite(a.eps)):
        print("sjp10_fitpack: error: --band: expected >= 0; --eps: expected > 0", file=sys.stderr)
        return 2
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        try:
            for name, text in CASES:
                if name in want:
                    rows += run_case(name, text, a, tmp)
        except subprocess.CalledProcessError as e:
            print(f"sjp10_fitpack: error: dflab probe failed: {e.stderr.strip()}", file=sys.stderr)
            return 1
    out_dir = os.path.join(a.results, "sjp10_peers")
    os.makedirs(out_dir, exist_ok=True)
    path = os.path.join(out_dir, "sjp10_fitpack.csv")
    tmpf = path + ".tmp"
    with open(tmpf, "w", newline="") as fp:
        wr = csv.DictWriter(fp, fieldnames=COLS)
        wr.writeheader()
        for r in rows:
            wr.writerow({k: (repr(v) if isinstance(v, float) else v) for k, v in
                         ((c, r.get(c, "")) for c in COLS)})
    os.replace(tmpf, path)
    with open(os.path.join(out_dir, "README.txt"), "w") as fp:
        fp.write("sjp10_fitpack.csv: SciPy FITPACK peer of sjp10 Fig. 2 "
                 "(scripts/peers/sjp10_fitpack.py; see its docstring).\n")
    print(f"sjp10_fitpack: wrote {path} ({len(rows)} rows)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
