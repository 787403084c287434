"""Reading dflab outputs from Python: CSV tables, manifests, VTK images,
the runner's per-sweep-point file names.

Used by report.py and the section renderers in scripts/sections/."""
import csv
import json
import math
import os
import re


def read_csv(path):
    """Rows of a CSV as a list of dicts (strings; use num() to convert)."""
    with open(path, newline="") as fp:
        return list(csv.DictReader(fp))


def num(s):
    """float of a CSV cell, None for an empty one."""
    if s is None or s == "":
        return None
    try:
        return float(s)
    except ValueError:
        return None


def cell(row, key):
    """float of row[key]; None when the column is absent or the cell empty."""
    return num(row.get(key))


def cell_nan(row, key):
    """float of row[key]; NaN when the column is absent or the cell empty."""
    v = num(row.get(key))
    return math.nan if v is None else v


def unique(values):
    """The distinct values in the order they first appear."""
    return list(dict.fromkeys(values))


# --- the runner's names of per-sweep-point files ---------------------------
# The C rule is dfl_study_tag (experiments/harness/experiment.h): a file
# <stem>.<ext> of sweep point i of n is named <stem><tag>.<ext> with tag ""
# when n == 1, else "_pt%03zu" (three digits at least, more from 1000 on).
# tests/e2e/common/test_sweep_tag.c checks that the two rules agree.

def sweep_tag(point, npoints):
    """The tag of sweep point `point` (0-based) of a run with `npoints` points."""
    return f"_pt{point:03d}" if npoints > 1 else ""


def sweep_name(stem, point, npoints, ext):
    """File name of stem.ext written at sweep point `point` of `npoints`."""
    return f"{stem}{sweep_tag(point, npoints)}.{ext}"


_TAGGED = re.compile(r"^(.*)_pt([0-9]{3,})$")


def sweep_split(filename):
    """(stem, point, ext) of a file name made by sweep_name (a path's directory
    is ignored): point is the sweep point, or None for an untagged name (a
    one-point run).  Only the tags sweep_tag writes count: "_pt7" or "_pt0012"
    are part of the stem."""
    root, ext = os.path.splitext(os.path.basename(filename))
    m = _TAGGED.match(root)
    if m and sweep_tag(int(m.group(2)), 2) == "_pt" + m.group(2):
        return m.group(1), int(m.group(2)), ext[1:]
    return root, None, ext[1:]


def sweep_point_of(filename):
    """The sweep point a file name carries (sweep_split), None if untagged."""
    return sweep_split(filename)[1]


def sweep_sibling(filename, stem, ext):
    """Name of stem.ext written at the same sweep point as `filename` (a tagged
    name means a run of more than one point)."""
    point = sweep_point_of(filename)
    return sweep_name(stem, point or 0, 1 if point is None else 2, ext)


def read_manifest(result_dir):
    p = os.path.join(result_dir, "manifest.json")
    if not os.path.exists(p):
        return None
    with open(p) as fp:
        return json.load(fp)


def overrides(manifest):
    """The --set overrides a run was made with (a list of "section.key=value";
    [] for none).  Manifests from before the overrides array held one "set"
    key, the last override only."""
    ov = manifest.get("overrides")
    if ov is None:
        ov = [manifest["set"]] if "set" in manifest else []
    return list(ov)


def overrides_md(manifest):
    """One markdown line naming a run's overrides."""
    ov = overrides(manifest)
    if not ov:
        return "Overrides: none (the config as written)."
    return "Overrides: " + ", ".join(f"`--set {o}`" for o in ov) + "."


def read_vti(path):
    """(dims, origin, spacing, {name: numpy array}) of a .vti, arrays
    reshaped to (nz, ny, nx[, ncomp])."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOXML import vtkXMLImageDataReader

    rd = vtkXMLImageDataReader()
    rd.SetFileName(path)
    rd.Update()
    img = rd.GetOutput()
    dims = img.GetDimensions()
    pd = img.GetPointData()
    arrays = {}
    for i in range(pd.GetNumberOfArrays()):
        a = vtk_to_numpy(pd.GetArray(i))
        shape = (dims[2], dims[1], dims[0]) + ((a.shape[1],) if a.ndim == 2 else ())
        arrays[pd.GetArrayName(i)] = a.reshape(shape)
    return dims, img.GetOrigin(), img.GetSpacing(), arrays


def read_vti_plane(path, z=0):
    """(x, y, {name: 2D array}) of one z plane of a .vti: node coordinates
    along x and y and every array at plane index z (None: the middle plane),
    rows along y."""
    import numpy as np
    dims, org, sp, arrays = read_vti(path)
    k = dims[2] // 2 if z is None else z
    x = org[0] + sp[0] * np.arange(dims[0])
    y = org[1] + sp[1] * np.arange(dims[1])
    return x, y, {name: a[k] for name, a in arrays.items()}


def is_nonfinite_error(v):
    """True for a cell that holds an error of +inf (dflab's non-finite rule:
    a point whose value was NaN or inf enters every metric as +inf), given
    as a float or as the CSV text."""
    if isinstance(v, float):
        return v == float("inf")
    return isinstance(v, str) and v.strip().lower() in ("inf", "+inf")


def nonfinite_count(row):
    """The largest count of a CSV row's columns whose name holds
    "nonfinite" (0 when none): the points that entered its metrics as +inf."""
    best = 0
    for k, v in row.items():
        if k and "nonfinite" in k:
            try:
                best = max(best, float(v))
            except (TypeError, ValueError):
                pass
    return best


def red(text):
    return f'<span style="color:red">{text}</span>' if text != "" else text


def md_table(header, rows):
    """A GitHub-flavoured markdown table.  A row holding an error of +inf
    (is_nonfinite_error) is shown in red, so that no reader takes its other
    numbers for a clean result."""
    out = ["| " + " | ".join(header) + " |", "|" + "|".join("---" for _ in header) + "|"]
    for r in rows:
        cells = [fmt(c) for c in r]
        if any(is_nonfinite_error(c) for c in r):
            cells = [red(c) for c in cells]
        out.append("| " + " | ".join(cells) + " |")
    return "\n".join(out)


def fmt(v):
    if v is None:
        return ""
    if isinstance(v, float):
        if v == 0:
            return "0"
        if abs(v) >= 1e4 or abs(v) < 1e-3:
            return f"{v:.3e}"
        return f"{v:.4g}"
    return str(v)
