#!/usr/bin/env python3
"""Validate dflab's VTK XML output with VTK's own readers (python3-vtk9).

Run through /usr/bin/python3 (Debian's VTK is importable only there).

  vtk_check.py vti FILE --dims NX NY NZ --origin OX OY OZ --spacing SX SY SZ
               --linear A B C D [--gradient] [--narrays N]
      Reads FILE with vtkXMLImageDataReader and checks the grid geometry and
      that point array "value" equals A*x + B*y + C*z + D at every point,
      where (x, y, z) = origin + (i, j, k) * spacing and point (i, j, k) is
      tuple i + NX*(j + NY*k).  With --gradient, array "gradient" (3
      components) must equal (A, B, C) everywhere and be the Vectors
      attribute.  "value" must be the Scalars attribute.

  vtk_check.py vtp FILE EXPECTED
      Reads FILE with vtkXMLPolyDataReader and compares it with the text file
      EXPECTED:
          points N            then N lines "x y z"
          lines L             then L lines "n i0 ... i(n-1)"
          polys T             then T lines "n i0 ... i(n-1)"
          array NAME NCOMP    then N lines of NCOMP values (repeatable)
      Numbers must match exactly (the writer of EXPECTED uses %.17g).

VTK reports read failures through its output window, not exceptions, so all
output-window text is captured and any of it counts as a failure.
Exit status 0 when everything matches, 1 on a mismatch, 2 on usage errors,
3 when the checker itself fails.
"""
import argparse
import sys

from vtkmodules.vtkCommonCore import vtkIdList, vtkOutputWindow, vtkStringOutputWindow
from vtkmodules.vtkIOXML import vtkXMLImageDataReader, vtkXMLPolyDataReader


class Failure(Exception):
    pass


def check(cond, msg):
    if not cond:
        raise Failure(msg)


def read(reader_cls, path):
    log = vtkStringOutputWindow()
    vtkOutputWindow.SetInstance(log)
    reader = reader_cls()
    check(reader.CanReadFile(path), f"{path}: VTK cannot read this file")
    reader.SetFileName(path)
    reader.Update()
    text = log.GetOutput().strip()
    check(not text, f"{path}: VTK reported: {text}")
    check(reader.GetErrorCode() == 0, f"{path}: reader error code {reader.GetErrorCode()}")
    return reader.GetOutput()


def close(a, b, rel=1e-13):
    return abs(a - b) <= rel * max(1.0, abs(a), abs(b))


def check_vti(args):
    img = read(vtkXMLImageDataReader, args.file)
    nx, ny, nz = args.dims
    check(tuple(img.GetDimensions()) == (nx, ny, nz),
          f"dims {img.GetDimensions()} != {(nx, ny, nz)}")
    for got, want, what in ((img.GetOrigin(), args.origin, "origin"),
                            (img.GetSpacing(), args.spacing, "spacing")):
        check(all(g == w for g, w in zip(got, want)), f"{what} {got} != {tuple(want)}")
    npts = nx * ny * nz
    check(img.GetNumberOfPoints() == npts, f"{img.GetNumberOfPoints()} points != {npts}")
    pd = img.GetPointData()
    if args.narrays is not None:
        check(pd.GetNumberOfArrays() == args.narrays,
              f"{pd.GetNumberOfArrays()} point arrays != {args.narrays}")
    scal = pd.GetScalars()
    check(scal is not None and scal.GetName() == "value", "Scalars attribute is not 'value'")
    check(scal.GetNumberOfComponents() == 1 and scal.GetNumberOfTuples() == npts,
          "array 'value' has the wrong shape")
    check(scal.GetDataTypeAsString() == "double", "array 'value' is not Float64")
    grad = None
    if args.gradient:
        grad = pd.GetVectors()
        check(grad is not None and grad.GetName() == "gradient",
              "Vectors attribute is not 'gradient'")
        check(grad.GetNumberOfComponents() == 3 and grad.GetNumberOfTuples() == npts,
              "array 'gradient' has the wrong shape")
    a, b, c, d = args.linear
    ox, oy, oz = args.origin
    sx, sy, sz = args.spacing
    for k in range(nz):
        for j in range(ny):
            for i in range(nx):
                pid = i + nx * (j + ny * k)
                x, y, z = ox + i * sx, oy + j * sy, oz + k * sz
                p = img.GetPoint(pid)
                check(close(p[0], x) and close(p[1], y) and close(p[2], z),
                      f"point {pid} at {p}, expected {(x, y, z)}")
                want = a * x + b * y + c * z + d
                got = scal.GetValue(pid)
                check(close(got, want, 1e-12),
                      f"value at (i,j,k)=({i},{j},{k}) is {got!r}, expected {want!r}")
                if grad is not None:
                    g = grad.GetTuple3(pid)
                    check(g == (a, b, c), f"gradient at {pid} is {g}, expected {(a, b, c)}")
    return f"vti OK: {nx}x{ny}x{nz}, {pd.GetNumberOfArrays()} arrays"


def parse_expected(path):
    with open(path) as f:
        tok = [line.split() for line in f if line.strip()]
    pos = 0

    def header(word):
        nonlocal pos
        check(pos < len(tok) and tok[pos][0] == word, f"{path}: expected '{word}' line")
        h = tok[pos]
        pos += 1
        return h

    def rows(n):
        nonlocal pos
        r = tok[pos:pos + n]
        check(len(r) == n, f"{path}: truncated")
        pos += n
        return r

    exp = {}
    n = int(header("points")[1])
    exp["points"] = [tuple(float(v) for v in r) for r in rows(n)]
    exp["lines"] = [[int(v) for v in r[1:]] for r in rows(int(header("lines")[1]))]
    exp["polys"] = [[int(v) for v in r[1:]] for r in rows(int(header("polys")[1]))]
    exp["arrays"] = []
    while pos < len(tok):
        h = header("array")
        exp["arrays"].append((h[1], int(h[2]), [tuple(float(v) for v in r) for r in rows(n)]))
    return exp


def cells(cell_array):
    out = []
    ids = vtkIdList()
    cell_array.InitTraversal()
    while cell_array.GetNextCell(ids):
        out.append([ids.GetId(i) for i in range(ids.GetNumberOfIds())])
    return out


def check_vtp(args):
    poly = read(vtkXMLPolyDataReader, args.file)
    exp = parse_expected(args.expected)
    n = len(exp["points"])
    check(poly.GetNumberOfPoints() == n, f"{poly.GetNumberOfPoints()} points != {n}")
    check(poly.GetNumberOfLines() == len(exp["lines"]),
          f"{poly.GetNumberOfLines()} lines != {len(exp['lines'])}")
    check(poly.GetNumberOfPolys() == len(exp["polys"]),
          f"{poly.GetNumberOfPolys()} polys != {len(exp['polys'])}")
    check(poly.GetNumberOfVerts() == 0 and poly.GetNumberOfStrips() == 0,
          "unexpected verts or strips")
    if n:
        check(poly.GetPoints().GetData().GetDataTypeAsString() == "double", "points are not Float64")
    for i, want in enumerate(exp["points"]):
        got = poly.GetPoint(i)
        check(tuple(got) == want, f"point {i} is {got}, expected {want}")
    for what, got, want in (("line", cells(poly.GetLines()), exp["lines"]),
                            ("poly", cells(poly.GetPolys()), exp["polys"])):
        for i, (g, w) in enumerate(zip(got, want)):
            check(g == w, f"{what} {i} is {g}, expected {w}")
    pd = poly.GetPointData()
    check(pd.GetNumberOfArrays() == len(exp["arrays"]),
          f"{pd.GetNumberOfArrays()} point arrays != {len(exp['arrays'])}")
    for name, ncomp, values in exp["arrays"]:
        arr = pd.GetArray(name)
        check(arr is not None, f"no point array '{name}'")
        check(arr.GetNumberOfComponents() == ncomp and arr.GetNumberOfTuples() == n,
              f"array '{name}' has the wrong shape")
        for i, want in enumerate(values):
            got = arr.GetTuple(i)
            check(tuple(got) == want, f"array '{name}' tuple {i} is {got}, expected {want}")
    return (f"vtp OK: {n} points, {len(exp['lines'])} lines, {len(exp['polys'])} polys, "
            f"{len(exp['arrays'])} arrays")


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = p.add_subparsers(dest="kind", required=True)
    v = sub.add_parser("vti")
    v.add_argument("file")
    v.add_argument("--dims", type=int, nargs=3, required=True)
    v.add_argument("--origin", type=float, nargs=3, required=True)
    v.add_argument("--spacing", type=float, nargs=3, required=True)
    v.add_argument("--linear", type=float, nargs=4, required=True)
    v.add_argument("--gradient", action="store_true")
    v.add_argument("--narrays", type=int)
    t = sub.add_parser("vtp")
    t.add_argument("file")
    t.add_argument("expected")
    args = p.parse_args()
    try:
        msg = check_vti(args) if args.kind == "vti" else check_vtp(args)
    except Failure as e:
        print(f"vtk_check: FAIL: {e}", file=sys.stderr)
        return 1
    except Exception as e:  # a bug here must not pass for a detected mismatch
        print(f"vtk_check: ERROR: {type(e).__name__}: {e}", file=sys.stderr)
        return 3
    print(msg)
    return 0


if __name__ == "__main__":
    sys.exit(main())
