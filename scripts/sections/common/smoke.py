"""Smoke studies: metrics of the affinely perturbed exact field."""
import dflio


def render(ctx):
    rows = ctx.csv()
    cols = [c for c in ("grid.n", "dim", "nodes", "l1", "mse", "rms", "linf", "graddefect_mean",
                        "l1_band", "linf_band") if c in rows[0]]
    md = dflio.md_table(cols, [[dflio.num(r[c]) for c in cols] for r in rows])
    md += ("\n\nu = (1 + scale) d + offset against the exact d; expected gradient-norm defect "
           f"= |scale| = {abs(dflio.num(rows[0]['scale'])):g}.\n")
    import glob
    import os
    vtis = sorted(glob.glob(ctx.path("field*.vti")))
    if vtis:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        import numpy as np
        dims, org, sp, arr = dflio.read_vti(vtis[-1])
        v = arr["reference"][dims[2] // 2]
        x = org[0] + sp[0] * np.arange(dims[0])
        y = org[1] + sp[1] * np.arange(dims[1])
        fig, ax = plt.subplots(figsize=(4.5, 4))
        cs = ax.contour(x, y, v, levels=15, cmap="coolwarm")
        ax.contour(x, y, v, levels=[0], colors="k", linewidths=2)
        ax.clabel(cs, fontsize=6)
        ax.set_aspect("equal")
        ax.set_title(f"exact SDF, {os.path.basename(vtis[-1])}\n{ctx.config}", fontsize=8)
        md += "\n" + ctx.figure(fig, "field") + "\n"
    return md
