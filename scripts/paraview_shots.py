"""Screenshots of dflab volumes with ParaView (pvpython), headless.

usage: xvfb-run -a pvpython scripts/paraview_shots.py VOLUME.vti OUT.png [--cells]

Shows the zero level set of `value` (the field's surface; a signed field's,
e.g. hvb25_accuracy with `[field] signed = true`) coloured by |error|
(value - reference), over a slice at z = 0 coloured by `error`; with --cells the
slice is coloured by the cell data `level` instead (sjp10_3d's T-mesh level of
each voxel) and the surface is shown grey.  The title names the file.  Needs
Debian's `paraview` and `python3-paraview` (which replace `python3-vtk9`, see
the README) and `xvfb`.
"""
import os
import sys

from paraview.simple import (Calculator, ColorBy, Contour, CreateView, GetColorTransferFunction,
                             GetScalarBar, OpenDataFile, ResetCamera, SaveScreenshot, Show,
                             Slice, Text)


def main(argv):
    args = [a for a in argv if not a.startswith("--")]
    if len(args) != 2:
        print(__doc__)
        return 2
    vti, png = args
    cells = "--cells" in argv
    src = OpenDataFile(vti)
    if src is None:
        print(f"paraview_shots: {vti}: cannot open", file=sys.stderr)
        return 2
    view = CreateView("RenderView")
    view.ViewSize = [1000, 800]
    view.OrientationAxesVisibility = 1
    if hasattr(view, "UseColorPaletteForBackground"):
        view.UseColorPaletteForBackground = 0
    view.Background = [1, 1, 1]
    iso = Contour(Input=src, ContourBy=["POINTS", "value"], Isosurfaces=[0.0])
    if cells:
        d = Show(iso, view)
        ColorBy(d, None)
        d.DiffuseColor = [0.75, 0.75, 0.75]
        d.Opacity = 0.45
        sl = Slice(Input=src)
        sl.SliceType.Normal = [0, 0, 1]
        s = Show(sl, view)
        ColorBy(s, ("CELLS", "level"))
        bar_of = "level"
    else:
        mag = Calculator(Input=iso, ResultArrayName="abs_error", Function="abs(error)")
        d = Show(mag, view)
        ColorBy(d, ("POINTS", "abs_error"))
        sl = Slice(Input=src)
        sl.SliceType.Normal = [0, 0, 1]
        s = Show(sl, view)
        ColorBy(s, ("POINTS", "error"))
        s.RescaleTransferFunctionToDataRange(True, False)
        s.Opacity = 0.6
        bar_of = "abs_error"
    lut = GetColorTransferFunction(bar_of)
    if not cells:
        d.RescaleTransferFunctionToDataRange(True, False)
    else:
        s.RescaleTransferFunctionToDataRange(True, False)
    bar = GetScalarBar(lut, view)
    bar.Title = bar_of
    bar.ComponentTitle = ""
    bar.TitleColor = [0, 0, 0]
    bar.LabelColor = [0, 0, 0]
    bar.Visibility = 1
    title = Text(Text=os.path.basename(vti))
    t = Show(title, view)
    t.FontSize = 14
    t.Color = [0, 0, 0]
    view.CameraPosition = [2.2, -2.6, 2.0]
    view.CameraFocalPoint = [0, 0, 0]
    view.CameraViewUp = [0, 0, 1]
    ResetCamera(view)
    SaveScreenshot(png, view, ImageResolution=[1000, 800])
    print(f"paraview_shots: wrote {png}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
