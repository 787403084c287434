"""The FITPACK part of the sjp10 Fig. 2 section: the peer's table
(results/sjp10_peers/sjp10_fitpack.csv, scripts/peers/sjp10_fitpack.py) and
where the adaptive PHT fit wins and loses against it at equal error.  Every
number is read from the CSVs of the same results tree: the PHT errors from
the sjp10_cells rows, FITPACK's from the peer's rows."""
import math

import dflio
from sections.sjp10 import sjp10_common as sc

_f = dflio.cell_nan

METHODS = [("fitpack_s0", "s = 0 on n² sub-grids"),
           ("fitpack_smooth", "s = N r² on all data (FITPACK's knots)"),
           ("lsq_graded", "least squares on graded knots")]

# The PHT rows' error columns, newest protocol first: a results tree written
# before the per-cell validation has only the grid's val_max / val_off_max.
_PHT_COLS = {"whole": ("cv_max", "max_whole", "val_max_whole", "val_cell_max", "val_max"),
             "off": ("cv_off_max", "max_off", "val_max_off", "val_cell_off_max", "val_off_max")}
_FP_COLS = {"whole": "max_whole", "off": "max_off"}


def pht_err(r, which):
    """The PHT row's max error, whole square ('whole') or off the band ('off')."""
    for c in _PHT_COLS[which]:
        if c in r and r[c] not in ("", None):
            return _f(r, c)
    return math.nan


def pht_err_column(rows, which):
    """The column pht_err reads in these rows (for the text)."""
    for c in _PHT_COLS[which]:
        if rows and c in rows[0]:
            return c
    return "?"


def usable(fp):
    """The peer's rows whose fit is determined by its data (least-squares
    rows with a rank deficiency are left out of every comparison)."""
    return [r for r in fp if not r.get("rank_deficiency") or _f(r, "rank_deficiency") == 0]


def scalars(r):
    """Stored doubles: coefficients + knots."""
    return _f(r, "coefficients") + _f(r, "knots")


def assumption():
    return ("FITPACK peer (scripts/peers/sjp10_fitpack.py, SciPy 1.10, bicubic): the exact SDF on "
            "1201² nodes (spacing 1/1200; sample_s = the time of that probe, charged to every fit of "
            "the shape); RectBivariateSpline s = 0 on n² sub-grids (n = 9..1201), RectBivariateSpline "
            "s = N r² on all data (FITPACK places its own knots, r = 1e-4..5e-7), and the tensor "
            "least-squares spline on m interior knots per axis graded towards the medial axis' "
            "median coordinate (power p; only where the medial axis projects to a point on that axis, "
            "else uniform; knots finer than the data are dropped until the problem is well-posed; "
            "the same solution as LSQBivariateSpline). Errors on a dense 401² probe plus multi-scale "
            "points around the medial axis and near the surface (the same points for every fit); "
            "stored scalars = coefficients + knots.")


def table(fp):
    """All of the peer's rows, by shape and method."""
    body = []
    for r in fp:
        body.append([r["shape"], r["method"], r["setting"], int(_f(r, "coefficients")),
                     int(_f(r, "knots")), _f(r, "fit_s"), _f(r, "sample_s"), _f(r, "max_whole"),
                     _f(r, "max_band"), _f(r, "max_off"), _f(r, "near_medial_max"),
                     _f(r, "share_above_eps")])
    eps = _f(fp[0], "eps") if fp else math.nan
    return ("**FITPACK peer** (one row per fit; errors over the dense probe and the near-medial and "
            f"near-surface points; share above eps = {eps:g}):\n\n"
            + dflio.md_table(["shape", "method", "setting", "coefficients", "knots", "fit s", "sample s",
                              "max whole", "max in band", "max off band", "near-medial max",
                              "share > eps"], body) + "\n\n")


def _span(v, f="{:.2f}"):
    lo, hi = f.format(min(v)), f.format(max(v))
    return lo if lo == hi else f"{lo}–{hi}"


def best_at(fp, shape, which, err):
    """(scalars, method) of the smallest FITPACK fit of `shape` reaching
    `err`, each method interpolated in log-log between its measured points
    (sc.size_at_error, no extrapolation); (None, None) if none reaches it."""
    best = (None, None)
    for m, _ in METHODS:
        pairs = [(scalars(r), _f(r, _FP_COLS[which])) for r in fp if r["shape"] == shape and r["method"] == m]
        s = sc.size_at_error(pairs, err)
        if s is not None and (best[0] is None or s < best[0]):
            best = (s, m)
    return best


def verdict(pht_by_case, fp):
    """Markdown: at each PHT fit's error, the FITPACK size that reaches it,
    and per shape and error kind where PHT wins (fewer stored scalars) and
    where it loses; from the CSV numbers only."""
    fp = usable(fp)
    lines, body = [], []
    for which, label in (("whole", "whole square"), ("off", "off the medial band")):
        for c, ph in pht_by_case.items():
            if not any(r["shape"] == c for r in fp):
                continue
            win, lose, unreached = [], [], []
            for r in ph:
                e, d = pht_err(r, which), _f(r, "dofs")
                if not (e > 0 and math.isfinite(e)):
                    continue
                s, m = best_at(fp, c, which, e)
                body.append([c, label, f"{_f(r, 'eps'):g}", e, int(d), s, m or "—",
                             d / s if s else None])
                if s is None:
                    unreached.append((r, e))
                elif d < s:
                    win.append(d / s)
                else:
                    lose.append(d / s)
            fmin = min((_f(r, _FP_COLS[which]) for r in fp if r["shape"] == c), default=math.nan)
            fbest = min((r for r in fp if r["shape"] == c), key=lambda r: _f(r, _FP_COLS[which]))
            pmin = min((pht_err(r, which) for r in ph), default=math.nan)
            txt = f"{c}, {label}: "
            parts = []
            if win:
                parts.append(f"PHT needs fewer stored scalars at {len(win)} of its errors "
                             f"(PHT / FITPACK {_span(win)})")
            if lose:
                parts.append(f"FITPACK needs fewer at {len(lose)} (PHT / FITPACK "
                             f"{_span(lose)})")
            aim = 0.5 if c == "circle" else 0.1
            both = win + lose
            if both:
                parts.append(f"aim PHT / FITPACK ≤ {aim:g} where both reach the error: "
                             + ("met" if min(both) <= aim else "not met") + f" (best {min(both):.2f})")
            if unreached:
                parts.append(f"{len(unreached)} PHT error(s) ({_span([e for _, e in unreached], '{:.3g}')}) "
                             "lie below every FITPACK fit here")
            parts.append(f"smallest error PHT {pmin:.3g}, FITPACK {fmin:.3g} "
                         f"({fbest['method']} {fbest['setting']}, {int(scalars(fbest))} scalars)")
            lines.append(txt + "; ".join(parts))
    md = ("**PHT against the best FITPACK at equal error**: for each PHT fit, the smallest FITPACK "
          "fit (over the three methods, log-log interpolation between measured sizes, no "
          "extrapolation) that reaches the PHT fit's max error; sizes in stored scalars (PHT dofs; "
          "FITPACK coefficients + knots).\n\n")
    md += dflio.md_table(["shape", "error over", "eps", "PHT error", "PHT dofs", "FITPACK scalars",
                          "FITPACK method", "PHT / FITPACK"], body) + "\n\n"
    if lines:
        md += ("**Where PHT wins and where it loses** (from the numbers above):\n\n"
               + "\n".join(f"- {t}" for t in lines) + "\n\n")
    return md


def timing(fp, shape="circle"):
    """One sentence: FITPACK's fit times plus its sample cost on a shape."""
    rows = [r for r in fp if r["shape"] == shape]
    if not rows:
        return ""
    samp = _f(rows[0], "sample_s")
    fits = [_f(r, "fit_s") for r in rows if r["method"] == "fitpack_smooth"]
    return (f"; FITPACK on the {shape}: sampling the exact SDF on its data {samp:.2f} s (charged to "
            f"every fit), smoothing fits " + ", ".join(f"{v:.2f}" for v in fits) + " s")
