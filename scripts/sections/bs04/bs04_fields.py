"""bs04 Fig. 1 (a, b, c) and Fig. 3 (b): two segment fields, their join, the trims."""
import os

import dflio
from sections.common.plot import pyplot

ASSUMPTIONS = [
    "Fig. 1 / Fig. 3: the segments are not given in bs04; ours are a 'roof' (0.15, 0.3)-(0.5, 0.6)"
    "-(0.85, 0.3) in the unit square, meeting at 99 degrees (configs/paper/bs04/bs04_fields.ini).",
    "Fig. 1 / Fig. 3: fields are sampled on 199 x 199 nodes (the paper: 99 x 99, bilinearly "
    "interpolated) and the isolines drawn by matplotlib from the nodes.",
    "Strip trim: the two lines through the end points orthogonal to the segment, joined by "
    "Rvachev's R0-conjunction t = p1 + p2 - sqrt(p1^2 + p2^2) (normalized to first order on its "
    "boundary); bs04 shows only the disk.",
]


def _row(rows, trim, field):
    for r in rows:
        if r["trim"] == trim and r["field"] == field:
            return r
    return None


def render(ctx):
    plt = pyplot()
    import numpy as np

    rows = ctx.csv()
    trims = dflio.unique(r["trim"] for r in rows)
    p = int(float(rows[0]["p"]))
    join = next(r["join"] for r in rows if r["field"] == "join")
    f = dflio.num
    md = ("Fields of two segments (a, b; each trimmed by its own region, eq. 4 or 5), their join "
          f"by {join} of order p = {p} (eq. 6; Fig. 1 c used R-equivalence of order 2), and "
          "every trim. |∇u| statistics over the nodes off the zero set, over the band "
          f"d ≤ {f(rows[0]['band']):g} of the exact distance d, and the error u − d:\n\n")
    header = ["trim", "field", "min ‖∇u‖", "mean ‖∇u‖", "max ‖∇u‖", "min ‖∇u‖ band",
              "mean ‖∇u‖ band", "max ‖∇u‖ band", "L∞ (u−d) band", "mean abs(u−d) band",
              "max abs(‖∇u‖−1) on trim region", "u/min(h_a,h_b) range"]
    body = []
    for r in rows:
        rr = ""
        if r["field"] == "join":
            rr = f"[{f(r['ratio_min']):.6f}, {f(r['ratio_max']):.6f}]"
        body.append([r["trim"], r["field"], f(r["gradnorm_min"]), f(r["gradnorm_mean"]),
                     f(r["gradnorm_max"]), f(r.get("gradnorm_min_band")),
                     f(r.get("gradnorm_mean_band")), f(r.get("gradnorm_max_band")),
                     f(r.get("linf_band")), f(r.get("l1_band")),
                     f(r.get("trim_gradnorm_maxdev")) if r["field"] != "join" else None, rr])
    md += dflio.md_table(header, body) + "\n\n"

    # theory beside measurement
    lines = []
    for t in trims:
        a = _row(rows, t, "a")
        j = _row(rows, t, "join")
        if a and f(a.get("trim_gradnorm_maxdev")) is not None:
            lines.append(f"- {t}: on the trim region (t > 0) of one segment |u − |f|| ≤ "
                         f"{f(a['trim_value_maxdev']):.1e} and ||∇u| − 1| ≤ "
                         f"{f(a['trim_gradnorm_maxdev']):.1e} over {int(f(a['trim_nodes']))} nodes")
        if j and f(j.get("ratio_lo")) is not None:
            lines.append(f"  ({t}) join: u / min(h_a, h_b) ∈ [{f(j['ratio_min']):.6f}, "
                         f"{f(j['ratio_max']):.6f}], theory [{f(j['ratio_lo']):.6f}, 1] "
                         f"(the lower end where h_a = h_b: the bisector); min |∇u| of the join "
                         f"{f(j['gradnorm_min']):.3f} (bulging)")
    segs = _segments(ctx)
    alpha = None
    if segs and segs["a"][1] == segs["b"][0]:
        v = np.array(segs["a"][1])
        a1 = np.array(segs["a"][0]) - v
        a2 = np.array(segs["b"][1]) - v
        alpha = float(np.arccos(a1 @ a2 / np.linalg.norm(a1) / np.linalg.norm(a2)))
    if alpha is not None and join == "requiv":
        # eq. 12-14 at Phi = pi/4 (h_a = h_b, the bisector): F1 = F2 = 2^(-(p+1)/p) and the
        # gradients of h_a, h_b (unit normals of the segments) make the angle pi - alpha on the
        # inner side, so |grad u| = F sqrt(2 + 2 cos(pi - alpha)) = 2^(-1/p) sin(alpha/2).
        gth = 2 ** (-1 / p) * np.sin(alpha / 2)
        jd = _row(rows, trims[0], "join")
        lines.append(f"- join at the inner bisector near the joining point (angle α = "
                     f"{np.degrees(alpha):.1f}°): eq. 12–14 give ‖∇u‖ = 2^(−1/p) sin(α/2) = "
                     f"{gth:.4f}; the grid minimum is {f(jd['gradnorm_min']):.4f} (it lies on that "
                     "bisector, Fig. 4 b)")
    md += ("Paper vs dflab. bs04 states (Sec. 2.1) that eq. 4 is exactly zero on the segment, "
           "positive elsewhere and normalized at all regular points; where t > 0 it is |f| itself, "
           "so |∇u| = 1 there. Measured:\n\n" + "\n".join(lines) + "\n\n"
           "For eq. 4 with the disk or the strip, |∇h| ≥ 1 everywhere off the segment (outside "
           "the trim region |∇t| ≥ 1 and ∇t adds to ∇f), which the min |∇u| column confirms "
           "(1 to rounding); eq. 5 (disk_smooth) departs from |f| inside the disk by "
           "|f|⁷/(32 t²) (rfunc/trim.h), hence its non-zero deviation on the trim region. "
           "The join lies below min(h_a, h_b) and above 2^(−1/p) min(h_a, h_b): that factor is the "
           "bulging of Fig. 1 (c), strongest on the bisector of the two segments. The paper gives "
           "no numbers for these figures; they are compared by eye.\n\n")

    # Fig. 1 / 3 style isolines
    levels = np.arange(0.025, 0.61, 0.025)
    names = ["a", "b", "join"]
    fig, axes = plt.subplots(len(trims), 3, figsize=(10, 3.3 * len(trims)), squeeze=False)
    for i, t in enumerate(trims):
        for c, nm in enumerate(names):
            r = _row(rows, t, nm)
            ax = axes[i][c]
            if not r or not r.get("vti"):
                ax.axis("off")
                continue
            x, y, arr = dflio.read_vti_plane(ctx.path(r["vti"]))
            ax.contour(x, y, arr["value"], levels=levels, cmap="viridis", linewidths=0.8)
            ax.contour(x, y, arr["reference"], levels=[0.1, 0.2, 0.3], colors="0.35",
                       linewidths=0.7, linestyles="dashed")
            _draw_segments(ctx, ax, nm)
            ax.set_aspect("equal")
            lab = {"a": "segment a", "b": "segment b", "join": f"{join} p={p}"}[nm]
            ax.set_title(f"{lab}, trim {t}", fontsize=8)
            ax.tick_params(labelsize=6)
    fig.suptitle("bs04 Fig. 1 (row disk: a, b, c) and Fig. 3(b) (column a: each trim); isolines "
                 "every 0.025, dotted: exact distance 0.1, 0.2, 0.3\n" + ctx.config, fontsize=9)
    md += ctx.figure(fig, "isolines") + "\n\n"

    # |grad u| of the joins: where the bulging is
    fig, axes = plt.subplots(1, len(trims), figsize=(3.6 * len(trims), 3.4), squeeze=False)
    im = None
    for i, t in enumerate(trims):
        r = _row(rows, t, "join")
        ax = axes[0][i]
        x, y, arr = dflio.read_vti_plane(ctx.path(r["vti"]))
        im = ax.imshow(arr["grad_norm"], origin="lower", extent=[x[0], x[-1], y[0], y[-1]],
                       vmin=0.5, vmax=1.5, cmap="RdBu_r")
        _draw_segments(ctx, ax, "join")
        ax.set_title(f"|∇u| of the join, trim {t}", fontsize=8)
        ax.tick_params(labelsize=6)
        ax.set_xlabel("x", fontsize=7)
        ax.set_ylabel("y", fontsize=7)
    fig.colorbar(im, ax=axes[0].tolist(), shrink=0.8, label="|∇u|")
    fig.suptitle(f"|∇u| of {join} p={p} (1 = distance-like; < 1: bulging)\n{ctx.config}",
                 fontsize=9)
    md += ctx.figure(fig, "gradnorm") + "\n"
    return md


def _segments(ctx):
    """{'a': [[x, y], [x, y]], 'b': ...} from the run's resolved config (None if swept)."""
    cfg = os.path.join(ctx.dir, "config.ini")
    segs = {}
    try:
        import configparser
        cp = configparser.ConfigParser(inline_comment_prefixes=("#",))
        cp.read(cfg)
        v = [list(map(float, q.split())) for q in cp["field"]["vertices"].split(";")]
        segs = {"a": v[0:2], "b": v[1:3]}
    except Exception:  # a swept segment: no single geometry
        return None
    return segs


def _draw_segments(ctx, ax, which):
    segs = _segments(ctx) or {}
    for nm, pts in segs.items():
        if which in (nm, "join"):
            ax.plot([pts[0][0], pts[1][0]], [pts[0][1], pts[1][1]], "r-", lw=1.5)
