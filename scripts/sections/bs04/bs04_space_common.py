"""Helpers shared by the bs04 space sections (spacecurves, triangle, triedge,
surface, hetero): reading slice .vti files as 2D images, and drawing them
with colour bars."""
import os

import dflio
from sections.common.plot import pyplot


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


def show(ax, fig, data, ext, labels, title, cmap="viridis", vmin=None, vmax=None, iso=None,
         bar=None):
    """imshow with a colour bar (labelled bar, default: the title) and
    optional isolines of `iso`."""
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
    cb = fig.colorbar(im, ax=ax, shrink=0.75)
    cb.ax.tick_params(labelsize=6)
    cb.set_label(bar or title, fontsize=6)


def show_grad(ax, fig, img, ext, labels, title="|∇u| (white = 1)"):
    """The image's grad_norm on a diverging scale around 1 (white), 0 to 2."""
    show(ax, fig, img["grad_norm"], ext, labels, title, cmap="RdBu_r", vmin=0, vmax=2)


def show_error(ax, fig, err, ext, labels, title):
    """A signed error on a diverging scale symmetric about 0 (white)."""
    import numpy as np
    m = float(np.nanmax(np.abs(err))) or 1.0
    show(ax, fig, err, ext, labels, title, cmap="RdBu_r", vmin=-m, vmax=m)


def exists(ctx, name):
    return os.path.exists(ctx.path(name))


def point_slice(ctx, stem, point, npoints):
    """slice_image of <stem>.vti at a sweep point (dflio.sweep_name), None
    when the run wrote no such file."""
    fn = dflio.sweep_name(stem, point, npoints, "vti")
    return slice_image(ctx.path(fn)) if exists(ctx, fn) else None


def point_columns(ctx, rows, stem, nax, width, height):
    """A figure with a column of nax axes per row of `rows` (one row per
    sweep point, in point order), width inches a column, and, for every point
    whose slice <stem>.vti exists, (axes of its column, row, image, extent,
    labels) as from slice_image.  Returns (fig, that list)."""
    n = len(rows)
    fig, axs = pyplot().subplots(nax, n, figsize=(width * n, height), squeeze=False,
                                 constrained_layout=True)
    cols = []
    for i, r in enumerate(rows):
        sl = point_slice(ctx, stem, i, n)
        if sl is not None:
            cols.append(([axs[k][i] for k in range(nax)], r) + sl)
    return fig, cols


def f(v, fmt="{:.4g}"):
    x = dflio.num(v) if isinstance(v, str) else v
    return "" if x is None else fmt.format(x)
