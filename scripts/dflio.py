"""Reading dflab outputs from Python: CSV tables, manifests, VTK images.

Used by report.py and the section renderers in scripts/sections/."""
import csv
import json
import os


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


def read_manifest(result_dir):
    p = os.path.join(result_dir, "manifest.json")
    if not os.path.exists(p):
        return None
    with open(p) as fp:
        return json.load(fp)


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


def md_table(header, rows):
    """A GitHub-flavoured markdown table."""
    out = ["| " + " | ".join(header) + " |", "|" + "|".join("---" for _ in header) + "|"]
    for r in rows:
        out.append("| " + " | ".join(fmt(c) for c in r) + " |")
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
