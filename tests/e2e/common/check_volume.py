#!/usr/bin/env python3
"""Checks a volume of a 3D study (harness/field_out.h) through VTK's own
reader, for the e2e tests.

usage: check_volume.py FILE.vti|FILE.pvd [options]
  --sphere cx cy cz r     the reference is the sphere's SDF |x - c| - r
  --unsigned              ... its absolute value (an unsigned decoding)
  --cell NAME LO HI       a cell array NAME with integer values in [LO, HI]
  --cell-const NAME V     a cell array NAME equal to V in every cell
  --n N                   N nodes per axis
  --max-error E           |error| <= E in every node
A .pvd: every data set it lists opens and passes the checks, and their
timesteps are 0, 1, ... in order.  What is checked of every volume: point
arrays value, reference, error, grad_norm (scalars) and gradient (3
components); error = value - reference and grad_norm = |gradient| in every
node (as the writer computes them); finite reference.  Prints one line per
failure and exits 1; prints "ok N" (volumes checked) otherwise."""
import os
import sys
import xml.etree.ElementTree as ET

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLImageDataReader


def fail(msg):
    print(msg)
    sys.exit(1)


def arr(data, name, ncomp, path):
    a = data.GetArray(name)
    if a is None:
        fail(f"{path}: no array '{name}'")
    if a.GetNumberOfComponents() != ncomp:
        fail(f"{path}: '{name}' has {a.GetNumberOfComponents()} components, not {ncomp}")
    return vtk_to_numpy(a).astype(np.float64)


def check_vti(path, o):
    rd = vtkXMLImageDataReader()
    rd.SetFileName(path)
    rd.Update()
    img = rd.GetOutput()
    n = img.GetNumberOfPoints()
    if n == 0:
        fail(f"{path}: no points read")
    dims = img.GetDimensions()
    if o["n"] is not None and tuple(dims) != (o["n"],) * 3:
        fail(f"{path}: dimensions {dims}, expected {o['n']}^3")
    pd = img.GetPointData()
    u, ref, e = (arr(pd, k, 1, path) for k in ("value", "reference", "error"))
    gn, g = arr(pd, "grad_norm", 1, path), arr(pd, "gradient", 3, path)
    if not np.array_equal(e, u - ref, equal_nan=True):
        fail(f"{path}: error != value - reference at {np.sum(e != u - ref)} nodes")
    want = np.sqrt(g[:, 0] * g[:, 0] + g[:, 1] * g[:, 1] + g[:, 2] * g[:, 2])
    if not np.array_equal(gn, want, equal_nan=True):
        fail(f"{path}: grad_norm != |gradient|")
    if not np.all(np.isfinite(ref)):
        fail(f"{path}: reference not finite")
    x = np.array([img.GetPoint(i) for i in range(n)])
    if o["sphere"] is not None:
        c, r = np.array(o["sphere"][:3]), o["sphere"][3]
        d = np.linalg.norm(x - c, axis=1) - r
        if o["unsigned"]:
            d = np.abs(d)
        if np.max(np.abs(ref - d)) > 1e-14:
            fail(f"{path}: reference differs from the sphere's SDF by {np.max(np.abs(ref - d))}")
    if o["emax"] is not None and not np.max(np.abs(e)) <= o["emax"]:
        fail(f"{path}: max |error| {np.max(np.abs(e))} > {o['emax']}")
    cd = img.GetCellData()
    ncell = img.GetNumberOfCells()
    for name, lo, hi in o["cells"]:
        a = arr(cd, name, 1, path)
        if a.size != ncell:
            fail(f"{path}: cell array '{name}' has {a.size} tuples, not {ncell}")
        if not (np.all(a == np.floor(a)) and a.min() >= lo and a.max() <= hi):
            fail(f"{path}: cell array '{name}' not integers in [{lo}, {hi}]: "
                 f"{a.min()}..{a.max()}")
    for name, v in o["const"]:
        a = arr(cd, name, 1, path)
        if a.size != ncell or not np.all(a == v):
            fail(f"{path}: cell array '{name}' is not {v} everywhere")


def main():
    a = sys.argv[1:]
    path = a.pop(0)
    o = {"sphere": None, "unsigned": False, "cells": [], "const": [], "n": None, "emax": None}
    while a:
        k = a.pop(0)
        if k == "--sphere":
            o["sphere"] = [float(a.pop(0)) for _ in range(4)]
        elif k == "--unsigned":
            o["unsigned"] = True
        elif k == "--cell":
            o["cells"].append((a.pop(0), float(a.pop(0)), float(a.pop(0))))
        elif k == "--cell-const":
            o["const"].append((a.pop(0), float(a.pop(0))))
        elif k == "--max-error":
            o["emax"] = float(a.pop(0))
        elif k == "--n":
            o["n"] = int(a.pop(0))
        else:
            fail(f"unknown option {k}")
    files = [path]
    if path.endswith(".pvd"):
        root = ET.parse(path).getroot()
        sets = root.findall("./Collection/DataSet")
        if root.get("type") != "Collection" or not sets:
            fail(f"{path}: not a collection of data sets")
        times = [float(s.get("timestep")) for s in sets]
        if times != list(range(len(sets))):
            fail(f"{path}: timesteps {times}, expected 0..{len(sets) - 1}")
        files = [os.path.join(os.path.dirname(path), s.get("file")) for s in sets]
    for f in files:
        check_vti(f, o)
    print(f"ok {len(files)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
