"""Smoke studies: metrics of the affinely perturbed exact field."""
import glob
import os

import dflio
from sections.common.plot import pyplot


def render(ctx):
    rows = ctx.csv()
    cols = [c for c in ("grid.n", "dim", "nodes", "l1", "mse", "rms", "linf", "graddefect_mean",
                        "l1_band", "linf_band") if c in rows[0]]
    md = dflio.md_table(cols, [[dflio.num(r[c]) for c in cols] for r in rows])
    md += ("\n\nu = (1 + scale) d + offset against the exact d; expected gradient-norm defect "
           f"= |scale| = {abs(dflio.num(rows[0]['scale'])):g}.\n")
    vtis = sorted(glob.glob(ctx.path("field*.vti")))
    if vtis:
        plt = pyplot()
        x, y, arr = dflio.read_vti_plane(vtis[-1], z=None)
        v = arr["reference"]
        fig, ax = plt.subplots(figsize=(4.5, 4))
        cs = ax.contour(x, y, v, levels=15, cmap="coolwarm")
        ax.contour(x, y, v, levels=[0], colors="k", linewidths=2)
        ax.clabel(cs, fontsize=6)
        ax.set_aspect("equal")
        ax.set_title(f"exact SDF, {os.path.basename(vtis[-1])}\n{ctx.config}", fontsize=8)
        md += "\n" + ctx.figure(fig, "field") + "\n"
    return md
