"""sjp10 Fig. 1: the curves, their T-meshes and the graph surfaces of the fitted SDF."""
import math
import os

import dflio
from sections.common.plot import pyplot
from sections.sjp10 import sjp10_common as sc

_f = dflio.cell_nan

ASSUMPTIONS = [
    "Curves (sjp10 shows its curves only as pictures): ours in configs/shapes/sjp10_*.ini, all "
    "periodic cubic B-splines in the unit square except the circle — a convex egg, a non-convex "
    "peanut (waist with two dents), a teardrop whose curvature varies from −1.3 to 82 (sharp tip), "
    "and the circle of the peers' protocol (centre (0.5, 0.5), r 0.3). Box: the unit square (sjp10 "
    "Fig. 2 caption).",
    "Fit: cross refinement (a cell into 4, the PHT default; sjp10 describes binary splits of a box "
    "into two, available as split = binary), the paper's cell error (max |f − d| over m = 16 seeded "
    "random points per cell; sjp10 leaves m to the user) with dflab's two changes below, max_level "
    "10, eps = 1e-4 for Fig. 1 (sjp10 gives no value). eps is a target: at max_level 10 the kink "
    "error of the finest cells (~0.3 h, h = 1/1024) is ~2.9e-4, so no fit here reaches 1e-4 on the "
    "whole square.",
    sc.DEPARTURES,
    "Footpoints: geom's robust multi-start Newton with step control (geom/footpoint.h), not the "
    "paper's bare Newton from k ≤ 3 sampled starts; Hermite data (f, fx, fy, fxy) from the closed "
    "forms through the footpoint's curvature (pht/hermite.c derives sjp10 eq. 2–7).",
    sc.VALIDATION,
    sc.SIGN_NOTE,
]


def _panels(ctx, rows):
    plt = pyplot()
    import numpy as np
    from matplotlib.collections import PolyCollection

    n = len(rows)
    fig = plt.figure(figsize=(3.2 * n, 9.6))
    for i, r in enumerate(rows):
        vti = ctx.path(r["image_vti"]) if r.get("image_vti") else None
        x = y = arr = None
        if vti and os.path.exists(vti):
            x, y, arr = dflio.read_vti_plane(vti)
        ax = fig.add_subplot(3, n, i + 1)
        if arr is not None:
            ax.contour(x, y, arr["reference"], levels=[0], colors="k", linewidths=1.2)
        ax.set_aspect("equal")
        ax.set_xlim(0, 1), ax.set_ylim(0, 1)
        ax.set_title(f"{r['case']} ({r['kind']})", fontsize=8)
        ax = fig.add_subplot(3, n, n + i + 1)
        cells = dflio.read_csv(ctx.path(r["mesh_csv"]))
        polys = [[(float(c["lo_x"]), float(c["lo_y"])), (float(c["hi_x"]), float(c["lo_y"])),
                  (float(c["hi_x"]), float(c["hi_y"])), (float(c["lo_x"]), float(c["hi_y"]))]
                 for c in cells]
        lev = np.array([int(c["level"]) for c in cells])
        pc = PolyCollection(polys, array=lev, cmap="viridis", edgecolors="k", linewidths=0.1)
        ax.add_collection(pc)
        if arr is not None:
            ax.contour(x, y, arr["reference"], levels=[0], colors="w", linewidths=0.6)
        ax.set_aspect("equal")
        ax.set_xlim(0, 1), ax.set_ylim(0, 1)
        ax.set_title(f"T-mesh: {len(cells)} cells, levels {lev.min()}–{lev.max()}", fontsize=8)
        ax.set_xlabel("x", fontsize=7)
        ax.set_ylabel("y", fontsize=7)
        ax.tick_params(labelsize=6)
        cb = fig.colorbar(pc, ax=ax, fraction=0.046, pad=0.03)
        cb.set_label("level", fontsize=7, labelpad=1)
        cb.ax.tick_params(labelsize=6)
        ax = fig.add_subplot(3, n, 2 * n + i + 1, projection="3d")
        if arr is not None:
            X, Y = np.meshgrid(x, y)
            st = max(1, len(x) // 80)
            ax.plot_surface(X[::st, ::st], Y[::st, ::st], arr["value"][::st, ::st], cmap="coolwarm",
                            linewidth=0, antialiased=False)
            ax.set_title("graph of the fitted SDF f", fontsize=8)
            ax.tick_params(labelsize=5)
    fig.suptitle(f"sjp10 Fig. 1: curve, T-mesh (cells coloured by level), graph surface of the PHT "
                 f"fit (dflab sign: negative inside)\n{ctx.config}", fontsize=9)
    return ctx.figure(fig, "panels")


def render(ctx):
    rows = ctx.csv()
    fc = sc.facts(ctx)
    md = ("Adaptive C1 bicubic PHT fits of each curve's signed distance (eps = "
          f"{_f(rows[0], 'eps'):g}, {rows[0]['split']} splits, {int(_f(rows[0], 'samples'))} random "
          "estimator points per cell), with dflab's rule and with the paper's rule alone. Errors: "
          "the per-cell protocol (whole square, in the medial band, off it, near-medial points, share "
          "of points above eps) and, for comparison, the 301² grid + midpoints.\n\n")
    header = ["case", "rule", "cells", "dofs (4/vertex)", "deepest level", "met eps",
              "estimator max", "max (per cell)", "in band", "off band", "near-medial", "share > eps",
              "grid max", "grid off band", "time s (footpoints / spline / mesh)"]
    body = []
    for r in rows:
        body.append([r["case"], sc.rule(r), int(_f(r, "cells")), int(_f(r, "dofs")),
                     int(_f(r, "max_cell_level")), sc.met(r), _f(r, "est_max"), _f(r, "cv_max"),
                     _f(r, "cv_band_max"), _f(r, "cv_off_max"), _f(r, "cv_medial_max"),
                     _f(r, "cv_above_eps"), _f(r, "val_max"), _f(r, "val_off_max"),
                     f"{_f(r, 't_total'):.2f} ({_f(r, 't_foot'):.2f} / {_f(r, 't_spline'):.2f} / "
                     f"{_f(r, 't_mesh'):.2f})"])
    md += dflio.md_table(header, body) + "\n\n"
    pairs = []
    for c in dflio.unique(r["case"] for r in rows):
        d = [r for r in rows if r["case"] == c and sc.rule(r) == "dflab"]
        p = [r for r in rows if r["case"] == c and sc.rule(r) == "paper"]
        if d and p:
            pairs.append(f"{c}: {int(_f(p[0], 'dofs'))} dofs / off-band {sc.fmt(_f(p[0], 'cv_off_max'))} "
                         f"with the paper's rule, {int(_f(d[0], 'dofs'))} / {sc.fmt(_f(d[0], 'cv_off_max'))} "
                         "with dflab's")
    if pairs:
        md += ("**What grade and peaks buy** (same eps, same max_level): " + "; ".join(pairs)
               + ". The whole-square maximum is the kink's at max_level under either rule.\n\n")
    worst = max(_f(r, "t_total") for r in rows)
    slow = [r["case"] for r in rows if _f(r, "t_total") > 10]
    md += (f"**Timing.** {sc.quote(fc, 'timing')}. Here the slowest fit of Fig. 1 takes "
           f"{worst:.2f} s wall time on this machine (2 cores shared with other jobs, so wall times "
           "include waiting) — "
           + (f"{', '.join(slow)} above the paper's 10 s" if slow else "every example under the paper's 10 s")
           + " (a 2010 PC; the hardware differs, so this is an order of magnitude, not a speed-up "
           "claim). The dominant part is the footpoint work (Hermite data and the exact distances "
           "of the estimator's points), which grows with the cells along the medial axis.\n\n")
    md += ("The T-meshes refine towards the medial axis of the interior (and, for the non-convex "
           "peanut, the exterior one beyond its dents), where the SDF has a gradient jump and no "
           "polynomial fits it: sjp10's observation that the fit 'correctly identifies these regions "
           "and refines the T-mesh accordingly' is reproduced. The circle's medial axis is one point, "
           "so its mesh refines around the centre only. Off the band the errors fall to about eps; "
           "in the band they stay at the kink's O(h) error of the deepest cells, which the 301² grid "
           "undersamples (its maximum is up to 3.5× lower than the per-cell one on the circle) — no "
           "fit here meets eps = 1e-4 on the whole square.\n\n")
    dflab_rows = [r for r in rows if sc.rule(r) == "dflab"] or rows
    md += _panels(ctx, dflab_rows) + "\n"
    return md
