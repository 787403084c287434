#!/usr/bin/env python3
"""Prints a .vti as text through VTK's own reader, for the C tests
(e2e_vti_read in tests/util/e2e_util.h).

usage: vtk_dump.py FILE.vti ARRAY...
Line 1: nx ny nz ox oy oz sx sy sz npoints; then one line per point (VTK's
point order, x fastest): x y z and the named arrays' values, each printed
with 17 significant digits (read back exactly by strtod).  Exit 1 with a
message when the file does not read or an array is missing or not scalar."""
import sys

from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLImageDataReader


def g(v):
    return "%.17g" % float(v)


def main():
    path, names = sys.argv[1], sys.argv[2:]
    rd = vtkXMLImageDataReader()
    rd.SetFileName(path)
    rd.Update()
    img = rd.GetOutput()
    n = img.GetNumberOfPoints()
    if n == 0:  # VTK logs read failures instead of raising
        print(f"{path}: no points read")
        return 1
    pd = img.GetPointData()
    cols = []
    for name in names:
        a = pd.GetArray(name)
        if a is None or a.GetNumberOfComponents() != 1:
            print(f"{path}: no scalar point array '{name}'")
            return 1
        cols.append(vtk_to_numpy(a))
    out = [" ".join([str(d) for d in img.GetDimensions()] + [g(v) for v in img.GetOrigin()]
                    + [g(v) for v in img.GetSpacing()] + [str(n)])]
    for i in range(n):
        out.append(" ".join([g(v) for v in img.GetPoint(i)] + [g(c[i]) for c in cols]))
    print("\n".join(out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
