"""Helpers shared by the sjp10 sections: the paper's facts, the peers'
measured figures (results/reference/sjp10_peers_measured.csv), the FITPACK
peer's table (results/sjp10_peers/, scripts/peers/sjp10_fitpack.py),
log-log slopes, equal-error interpolation and .vtp reading."""
import math
import os

import dflio

_f = dflio.cell_nan

SIGN_NOTE = ("Signs: dflab's signed distance is negative inside, sjp10's positive inside; errors are "
             "absolute values and do not depend on it, offsets δ are given in dflab's sign "
             "(δ < 0 inside; sjp10's δ is −δ).")


def facts(ctx):
    """sjp10_facts.csv rows by id."""
    return {r["id"]: r for r in ctx.ref("sjp10_facts.csv")}


def quote(fc, key):
    if key not in fc:
        return ""
    return f"Paper (sjp10 {fc[key]['where']}): *{fc[key]['statement']}* ({fc[key]['value']})"


def peers(ctx, protocol=None):
    rows = ctx.ref("sjp10_peers_measured.csv")
    return [r for r in rows if protocol is None or r["protocol"] == protocol]


def fitpack_rows(ctx):
    """Rows of the FITPACK peer run in the same results tree, [] if absent."""
    path = os.path.join(os.path.dirname(ctx.dir.rstrip("/")), "sjp10_peers", "sjp10_fitpack.csv")
    if not os.path.exists(path):
        return []
    return dflio.read_csv(path)


def slope(xs, ys):
    """Least-squares slope of log10 y against log10 x (NaN for < 2 usable points)."""
    pts = [(math.log10(x), math.log10(y)) for x, y in zip(xs, ys)
           if x and y and x > 0 and y > 0 and math.isfinite(x) and math.isfinite(y)]
    if len(pts) < 2:
        return math.nan
    mx = sum(p[0] for p in pts) / len(pts)
    my = sum(p[1] for p in pts) / len(pts)
    sxx = sum((p[0] - mx) ** 2 for p in pts)
    if sxx == 0:
        return math.nan
    return sum((p[0] - mx) * (p[1] - my) for p in pts) / sxx


def size_at_error(pairs, err):
    """The size (dofs, scalars) a method needs for error err, by log-log
    interpolation between its measured (size, error) pairs sorted by size,
    taking the first crossing of err from above; None when the method never
    gets below err in the measured range (no extrapolation)."""
    pts = sorted((s, e) for s, e in pairs if s > 0 and e > 0 and math.isfinite(e))
    if not pts:
        return None
    if pts[0][1] <= err:
        return pts[0][0]
    for (s0, e0), (s1, e1) in zip(pts, pts[1:]):
        if e0 > err >= e1:
            t = (math.log(err) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(s0) + t * (math.log(s1) - math.log(s0)))
    return None


def read_vtp(path):
    """(points (n, 3), [index arrays of polylines], triangles (m, 3), {name: array})."""
    import numpy as np
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader

    rd = vtkXMLPolyDataReader()
    rd.SetFileName(path)
    rd.Update()
    pd = rd.GetOutput()
    pts = vtk_to_numpy(pd.GetPoints().GetData()) if pd.GetPoints() else np.zeros((0, 3))
    lines = []
    ca = pd.GetLines()
    if ca and ca.GetNumberOfCells():
        off = vtk_to_numpy(ca.GetOffsetsArray())
        conn = vtk_to_numpy(ca.GetConnectivityArray())
        lines = [conn[off[i]:off[i + 1]] for i in range(len(off) - 1)]
    tris = np.zeros((0, 3), int)
    pa = pd.GetPolys()
    if pa and pa.GetNumberOfCells():
        tris = vtk_to_numpy(pa.GetConnectivityArray()).reshape(-1, 3)
    arrays = {}
    for i in range(pd.GetPointData().GetNumberOfArrays()):
        arrays[pd.GetPointData().GetArrayName(i)] = vtk_to_numpy(pd.GetPointData().GetArray(i))
    return pts, lines, tris, arrays


def fmt(v, d=3):
    return dflio.fmt(v) if v is not None and not (isinstance(v, float) and math.isnan(v)) else "—"


DEPARTURES = (
    "Departures of dflab's fit from sjp10's rule, both on by default and named by their config keys: "
    "`peaks` — the estimator takes the max of |f − d| over the m = 16 seeded random points per cell "
    "(the paper's) plus the cell centre and its 2·dim face centres (where the cubic Hermite "
    "interpolation error peaks); `grade` — when a cell is split, the coarse owner of each of its "
    "hanging corners is split too if it is ≥ 2 levels coarser (the data at a hanging corner are the "
    "coarse neighbour's polynomial). Every sjp10 study runs twice: rule = dflab (grade = peaks = 1) and "
    "rule = paper (grade = peaks = 0, the paper's rule alone), so the tables show what the two "
    "changes buy.")

VALIDATION = (
    "Validation (sjp10 reports only its estimator): two protocols. The grid: 301² nodes + 300² cell "
    "midpoints of the square (val_ columns; uniform, so its mean is an area mean). Per cell "
    "(cv_ columns, pht/validate.h): every leaf cell gets its own points — the 3^dim nodes of its "
    "halving (corners, edge midpoints, centre; in 3D face centres), 4 seeded random points — and a "
    "cell within 2 diagonals of the medial axis also gets a 5² (3D: 4³) sub-grid and near-medial "
    "points: the crossing of a node's normal line with the medial axis, found by bisection on the "
    "footpoint jump, and points at e·2^−k and ¾·e·2^−k (k = 1..8, e the cell's edge) on both sides. "
    "The grid misses the finest cells at the kink; the per-cell maximum is within 1 % of a dense "
    "brute-force probe (33² points per cell) on the circle at eps = 1e-4 (2.86e-4 vs 2.89e-4). "
    "'Off band' excludes points whose normal line meets the medial axis within w = 0.02. "
    "'Met eps' judges eps against the per-cell maximum: a fit that does not reach eps gives "
    "converged = 0 and a reason (level_cap: cells above eps at max_level stopped it; estimator: the "
    "estimator met eps but the validation maximum is above it).")


def rule(r):
    """The row's fit rule ('dflab' for tables written before the column)."""
    return r.get("rule") or "dflab"


def met(r):
    """'yes' or 'no (reason)' from a row's converged / reason columns."""
    if _f(r, "converged") == 1:
        return "yes"
    return f"no ({r.get('reason') or 'level_cap'})"
