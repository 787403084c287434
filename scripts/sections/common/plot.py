"""Plotting helpers shared by the report sections of every paper."""


def pyplot():
    """matplotlib.pyplot on the Agg backend: report figures are files, never
    windows, and the report runs without a display."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def _is_field_image(artist):
    """An image drawn through a colour map (not an RGB(A) picture)."""
    import numpy as np
    arr = artist.get_array()
    return arr is not None and np.ndim(arr) != 3


def _mappables(ax):
    """The colour-mapped field artists of an axes: images, mesh plots and
    filled contours."""
    from matplotlib.collections import QuadMesh, PolyCollection
    if ax.name == "3d":  # a surface graph: its colour repeats its height
        return []
    out = [im for im in ax.images if _is_field_image(im) and im.get_gid() != "overlay"]
    out += [c for c in ax.collections if isinstance(c, (QuadMesh, PolyCollection))
            and c.get_array() is not None and c.get_cmap() is not None
            and c.get_gid() != "overlay"]
    return out


def figure_problems(fig):
    """What breaks the report's figure rules, as a list of sentences (empty:
    none).  The rules (issue-level promises of every report figure):
      - an axes that shows a colour-mapped field and has its axis drawn names
        both axes (x and y labels);
      - every such field has a colour bar with a label, its own or one shared
        with a field of the same colour map and limits;
      - no axis label, colour-bar label or axes title lies over another axes
        (a neighbouring panel) by more than a fifth of its area, nor over
        another axes' label or title by more than 2 pixels each way;
      - legend text is at least 6 pt.
    Not fields: RGB(A) pictures, 3D surface graphs and artists marked
    gid="overlay" (a mask drawn over a field, e.g. where it is undefined)."""
    probs = []
    bars = []  # (cmap name, clim) of mappables with a colour bar
    fields = []
    for ax in fig.axes:
        if ax.get_label() == "<colorbar>":
            continue
        for m in _mappables(ax):
            fields.append((ax, m))
            cb = getattr(m, "colorbar", None)
            if cb is not None:
                bars.append((m.get_cmap().name, tuple(m.get_clim())))
                if not (cb.ax.get_ylabel() or cb.ax.get_xlabel()):
                    probs.append(f"axes '{ax.get_title()}': its colour bar has no label")
    for ax, m in fields:
        if ax.axison and not (ax.get_xlabel() and ax.get_ylabel()):
            probs.append(f"axes '{ax.get_title()}': a field image without x and y labels")
        if getattr(m, "colorbar", None) is None and \
                (m.get_cmap().name, tuple(m.get_clim())) not in bars:
            probs.append(f"axes '{ax.get_title()}': a field image without a colour bar")
    fig.canvas.draw()
    r = fig.canvas.get_renderer()
    boxes = [(a, a.get_window_extent(r)) for a in fig.axes if a.get_visible()]
    texts = [(ax, t, t.get_window_extent(r)) for ax in fig.axes
             for t in (ax.xaxis.label, ax.yaxis.label, ax.title)
             if t.get_text() and t.get_visible()]

    def over(tb, ob):
        # a text grazing a neighbour by a pixel or two still reads; a fifth
        # of it under another panel or text does not
        inter = tb.intersection(tb, ob)
        return inter is not None and inter.width * inter.height > 0.2 * tb.width * tb.height

    for ax, t, tb in texts:
        for other, ob in boxes:
            if other is not ax and over(tb, ob):
                probs.append(f"label '{t.get_text()}' overlaps the axes "
                             f"'{other.get_title() or other.get_label()}'")
        for other, u, ub in texts:  # text over text is unreadable at any size
            inter = tb.intersection(tb, ub)
            if other is not ax and id(t) < id(u) and inter is not None and \
                    inter.width > 2 and inter.height > 2:
                probs.append(f"label '{t.get_text()}' overlaps the label '{u.get_text()}'")
    for ax in fig.axes:
        leg = ax.get_legend()
        if leg is not None:
            for t in leg.get_texts():
                if t.get_fontsize() < 6:
                    probs.append(f"axes '{ax.get_title()}': legend text {t.get_fontsize()} pt < 6")
                    break
    return probs
