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
