"""Helpers shared by the bs04 space sections (spacecurves, triangle, triedge,
surface, hetero): reading slice .vti files as 2D images, and drawing them."""
import os

import dflio


def slice_image(path):
    """(image, extent, axis labels) of a slice .vti (one node along the
    normal axis) or of a 2D .vti; image rows run along the second in-plane
    axis (origin lower)."""
    dims, org, sp, arr = dflio.read_vti(path)
    axes = [a for a in range(3) if dims[a] > 1]
    a0, a1 = axes[0], axes[1]
    ext = [org[a0], org[a0] + sp[a0] * (dims[a0] - 1), org[a1], org[a1] + sp[a1] * (dims[a1] - 1)]
    img = {k: v.reshape(dims[a1], dims[a0], *v.shape[3:]) for k, v in arr.items()}
    return img, ext, ("xyz"[a0], "xyz"[a1])


def show(ax, fig, data, ext, labels, title, cmap="viridis", vmin=None, vmax=None, iso=None):
    """imshow with a colour bar and optional isolines of `iso`."""
    import numpy as np
    im = ax.imshow(data, origin="lower", extent=ext, cmap=cmap, vmin=vmin, vmax=vmax,
                   interpolation="nearest", aspect="equal")
    if iso is not None:
        x = np.linspace(ext[0], ext[1], iso.shape[1])
        y = np.linspace(ext[2], ext[3], iso.shape[0])
        ax.contour(x, y, iso, levels=12, colors="w", linewidths=0.5)
    ax.set_xlabel(labels[0], fontsize=7)
    ax.set_ylabel(labels[1], fontsize=7)
    ax.tick_params(labelsize=6)
    ax.set_title(title, fontsize=7)
    fig.colorbar(im, ax=ax, shrink=0.75).ax.tick_params(labelsize=6)


def exists(ctx, name):
    return os.path.exists(ctx.path(name))


def f(v, fmt="{:.4g}"):
    x = dflio.num(v) if isinstance(v, str) else v
    return "" if x is None else fmt.format(x)
