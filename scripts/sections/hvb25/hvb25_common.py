"""Shared helpers of the hvb25 sections: sibling runs, paper values, cells."""
import math
import os

import dflio

NORMS = [("L1", "l1", "L1 = mean |e|"), ("L2", "mse", "MSE, set beside the paper's \"L2\""),
         ("Linf", "linf", "L∞ = max |e|")]

ASSUMPTIONS = [
    "Verdict rule (hvb25): a table claim is reproduced when every cell's ours/paper ratio lies in "
    "[×0.5, ×2] (printed as the range of ratios); the paper prints 2–3 digits on an unknown "
    "error grid, so a factor of two is the resolution of the comparison.",
    "Shapes and domain (the paper gives neither): sphere radius 0.5 and torus R = 0.6, r = 0.25 "
    "(axis z), both centred in the field box [−1, 1]³; with these our order-1 SDF sphere at 16³ "
    "matches the paper's 0.0017 / 0.05 (see Table 1). Cone, Bézier surfaces: configs/shapes/hvb25_*.ini.",
    "Error grid: the paper's 217³ nodes of [−1, 1]³ in Tables 1, 3, the peers and the sweeps; "
    "Table 2 (cone, Bézier surfaces) uses every other node (109³, an exact subset), since its "
    "brute-force truth would take 8 times as long on the full grid; hvb25_grid109 reruns a few "
    "Table 1 cells on 109³ to show what the coarser grid changes (L∞ most: it is set by a few "
    "points near the medial axis).",
    "Metrics: L1 = mean |e|, MSE = mean e², RMS and L∞ = max |e|, each named, over the whole "
    "grid and in the band |d| ≤ 0.05 (the paper states no band). e = u − |d|: the paper's unsigned "
    "output against the exact distance. The paper's \"L2\" is not defined in its text; our MSE "
    "stands beside it, and a ratio is printed only where the paper's value can be an MSE at all "
    "(L1² ≤ MSE ≤ L1·L∞ within its printed digits): the reading table under Table 1 shows, per "
    "column, which readings (MSE, RMS, ‖e‖₂/N) the printed values admit.",
    "Storage: Tables 1–4 store every scalar in half precision (the paper's 16-bit textures), the "
    "footpoint as its displacement from the cell centre; the storage study compares double / float / "
    "half and displacement / absolute.",
    "Clip (the sphere constraint, no formula in the paper): radius 1 cell size for nearest, none "
    "for trilinear and Hermite; dflab's reading D = sgn φ max(|φ|, |x − p| − ρ) by default, the "
    "reading as proxy solid ∩ ball (max(φ, |x − p| − ρ), clip = paper) beside it in the clip "
    "study and hvb25_fig10 (proxy/filter.h).",
    "Curvature of parametric input from the fundamental forms with the correct Gaussian curvature "
    "K = (LN − M²)/(EG − F²): the paper prints (LM − N²)/(EG − F²), a typo (for a sphere of radius r, "
    "L = N = E/r, M = F = 0 on a latitude grid, so LM − N² = −N² would give K < 0).",
    "SDF input: curvature = analytic (the SDF's Hessian, the paper's ref. [6]) unless a config says fit.",
    "Implicit input: footpoint = paper is our reading of its method (gradient-direction starts, Newton, "
    "several starts); footpoint = robust is ours (proxy/input_implicit.h).",
    "Footpoint noise: the paper moved one footpoint by hand, without saying which; "
    "hvb25_noise_one moves one (the cell holding noise_at, a cell 0.069 outside the sphere), "
    "hvb25_noise moves every footpoint by the given length in a random direction (proxy/proxy.h), "
    "a stronger test.",
    "Table 4: our times are CPU times on this 2-core machine (one frame 256² in the paper configs, "
    "512² in make bench), beside the paper's GTX 1650 figures as a per-proxy and per-query cost, not "
    "as a race of machines; generation = building the grid from the input (best of one run).",
]


def sibling(ctx, name, csvname=None):
    """Rows of results/<name>/<csv> (another run of the same make reproduce),
    [] when that run is missing."""
    d = os.path.join(os.path.dirname(ctx.dir.rstrip("/")), name)
    p = os.path.join(d, csvname or "hvb25_accuracy.csv")
    return dflio.read_csv(p) if os.path.exists(p) else []


def f(row, key):
    return dflio.cell_nan(row, key)


def col(row, *keys):
    """First present of several column names (swept keys are field.X)."""
    for k in keys:
        if k in row and row[k] != "":
            return row[k]
    return ""


def pick(rows, **want):
    """Rows whose columns (or their field.* sweep columns) equal want."""
    out = []
    for r in rows:
        ok = True
        for k, v in want.items():
            have = col(r, k, "field." + k)
            try:
                ok = ok and float(have) == float(v)
            except ValueError:
                ok = ok and have == str(v)
        if ok:
            out.append(r)
    return out


def g(x):
    """Compact number."""
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "—"
    if x == 0:
        return "0"
    if abs(x) >= 1e3 or abs(x) < 1e-3:
        return f"{x:.2e}"
    return f"{x:.3g}"


def vs(ours, paper):
    """'ours (paper; ×ratio)' for a table cell."""
    if paper is None or (isinstance(paper, float) and math.isnan(paper)):
        return g(ours)
    if paper == 0:
        return f"{g(ours)} (0)"
    return f"{g(ours)} ({g(paper)}; ×{g(ours / paper)})"


def paper_rows(ctx, name):
    try:
        return ctx.ref(name)
    except OSError:
        return []


# The paper's "L2" (hvb25 Tables 1 and 3) is not defined in its text.  Any
# mean of squared errors obeys (mean |e|)^2 <= mean e^2 <= mean|e| * max|e|
# (Cauchy-Schwarz; e^2 <= |e| max|e|), an RMS obeys L1 <= RMS <= sqrt(L1 Linf),
# and the norm of the error vector over N points divided by N is RMS/sqrt(N).
# A printed value stands for the interval of numbers that print so: half a
# unit of its last digit; a bare "0" in these tables (whose squared columns
# are printed to six decimals) for [0, 5e-7].
L2_READINGS = ("MSE", "RMS", "‖e‖₂/N")


def printed_interval(s):
    """[lo, hi] of the numbers that print as the decimal string s."""
    t = s.strip().lower()
    v = float(t)
    if v == 0:
        return 0.0, 5e-7
    mant, _, ex = t.partition("e")
    dec = len(mant.split(".")[1]) if "." in mant else 0
    half = 0.5 * 10.0 ** ((int(ex) if ex else 0) - dec)
    return max(0.0, v - half), v + half


def l2_admits(l1, l2, linf, npoints):
    """{reading: bool}: which readings of a printed "L2" value l2 are
    possible beside the printed L1 and L-inf of the same cell (strings) for
    an error grid of npoints points."""
    a, b = printed_interval(l1)
    _, m = printed_interval(linf)
    lo, hi = printed_interval(l2)
    rms_hi = math.sqrt(b * m)
    bounds = {"MSE": (a * a, b * m), "RMS": (a, rms_hi),
              "‖e‖₂/N": (a / math.sqrt(npoints), rms_hi / math.sqrt(npoints))}
    return {k: hi >= bounds[k][0] and lo <= bounds[k][1] for k in L2_READINGS}


def l2_reading_table(rows, cols, key, npoints):
    """Markdown lines: per paper column, how many of its "L2" cells each
    reading admits, and the cells that no MSE can be.  rows: the paper's CSV
    rows (strings), key(row) -> the cell's name without the norm."""
    by = {}
    for r in rows:
        by.setdefault(key(r), {})[r["norm"]] = r
    head = ["paper column", "cells"] + [f"{k} possible" for k in L2_READINGS]
    body, bad = [], []
    for c in cols:
        n, cnt = 0, dict.fromkeys(L2_READINGS, 0)
        for k, norms in by.items():
            if not all(x in norms and norms[x].get(c, "") != "" for x in ("L1", "L2", "Linf")):
                continue
            ok = l2_admits(norms["L1"][c], norms["L2"][c], norms["Linf"][c], npoints)
            n += 1
            for rd in L2_READINGS:
                cnt[rd] += ok[rd]
            if not ok["MSE"]:
                bad.append(f"{k} {c}: \"L2\" {norms['L2'][c]} beside L1 {norms['L1'][c]}, "
                           f"L∞ {norms['Linf'][c]}")
        body.append([c, n] + [cnt[rd] for rd in L2_READINGS])
    return body, head, bad


def l2_is_mse(l1, l2, linf):
    """True when the printed paper cell l2 can be a mean of squared errors."""
    return l2_admits(l1, l2, linf, 1)["MSE"]
