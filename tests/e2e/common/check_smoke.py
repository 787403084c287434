#!/usr/bin/env python3
"""Reads a smoke study's field.vti with VTK's own reader and checks it
against the closed form: reference = |x - c| - r (circle or sphere),
value = (1 + scale) * reference + offset, error = value - reference,
gradient = (1 + scale) (x - c)/|x - c|.

usage: check_smoke.py FILE.vti n cx cy [cz] r scale offset
Exit 0 when everything matches, 1 with a message otherwise.  VTK logs read
failures instead of raising, so the dimensions are checked explicitly."""
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLImageDataReader


def main():
    path = sys.argv[1]
    n = int(sys.argv[2])
    rest = [float(v) for v in sys.argv[3:]]
    dim = 3 if len(rest) == 6 else 2
    c = np.array(rest[:dim])
    r, scale, offset = rest[dim:dim + 3]
    rd = vtkXMLImageDataReader()
    rd.SetFileName(path)
    rd.Update()
    img = rd.GetOutput()
    dims = img.GetDimensions()
    want = (n, n, n if dim == 3 else 1)
    if tuple(dims) != want:
        print(f"dimensions {dims} != {want}")
        return 1
    sp = img.GetSpacing()
    h = 1.0 / (n - 1)
    if any(abs(sp[d] - h) > 1e-12 for d in range(dim)):
        print(f"spacing {sp} != {h}")
        return 1
    pd = img.GetPointData()
    arrays = {pd.GetArrayName(i): vtk_to_numpy(pd.GetArray(i)) for i in range(pd.GetNumberOfArrays())}
    for name in ("value", "gradient", "grad_norm", "error", "reference"):
        if name not in arrays:
            print(f"missing array {name}; have {sorted(arrays)}")
            return 1
    npts = img.GetNumberOfPoints()
    pts = np.array([img.GetPoint(i) for i in range(npts)])[:, :dim]
    diff = pts - c
    dist = np.sqrt((diff ** 2).sum(axis=1))
    ref = dist - r
    checks = {
        "reference": (arrays["reference"], ref),
        "value": (arrays["value"], (1 + scale) * ref + offset),
        "error": (arrays["error"], scale * ref + offset),
        "grad_norm": (arrays["grad_norm"], np.full(npts, 1 + scale)),
    }
    for name, (got, exp) in checks.items():
        err = np.max(np.abs(got - exp))
        if err > 1e-12:
            print(f"{name}: max deviation {err}")
            return 1
    g = arrays["gradient"][:, :dim]
    ok = dist > 1e-9
    gexp = (1 + scale) * diff[ok] / dist[ok, None]
    err = np.max(np.abs(g[ok] - gexp))
    if err > 1e-12:
        print(f"gradient: max deviation {err}")
        return 1
    print("ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
