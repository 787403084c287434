"""compare_methods: Pareto plots per shape (error vs stored bytes, query time,
build time) and the best method per budget and region."""
import math

import dflio
from sections.common.plot import pyplot

_f = dflio.cell_nan

# budgets in stored bytes: small / medium / large
BUDGETS = [("small", 64e3), ("medium", 1e6), ("large", 16e6)]
REGIONS = [("near surface", "band_linf"), ("whole box", "linf")]
AIM_BYTES = 8.6e6  # issue 18: the torus at equal stored bytes
# kinds that are distances only in a narrow band (elsewhere a background
# value): read in the near-surface band only, never in the whole box
BAND_ONLY = {"openvdb"}


def _in_region(r, col):
    return col != "linf" or r.get("kind") not in BAND_ONLY

ASSUMPTIONS = [
    "One protocol for every method (experiments/compare/compare_eval.h): per shape a node grid of "
    "its box (301² in 2D, 61³ in 3D in methods.ini), near-surface points (footpoint + t·n, "
    "|t| ≤ 0.05) and near-medial points (pht/validate.h's medial band, width 0.02); regions: "
    "whole, band |d| ≤ 0.05, off the medial band. Non-finite values are errors of +inf and "
    "counted.",
    "Stored bytes are what must be kept to evaluate (dfl_field_ops.bytes): proxies and grid "
    "peers their scalars in their storage (plus one sign byte per order-1 proxy), PHT its cell "
    "tree, boxes and coefficients, R-function fields their part records. The exact field's "
    "bytes are not counted (it is the reference).",
    "Continuity by measurement: pairs x ± 1e-9·box straddling axis planes of a 1024-per-axis "
    "grid (every face of a dyadic cell grid on the box), pairs in the medial band left out; "
    "c0_jump = max |Δu|, c1_jump = max |Δ∇u|.",
    "Query rate: best of `repeats` batched evaluations (value and gradient) of all error points "
    "on the run's threads; build time: the factory call (for grid peers and proxies it includes "
    "the exact distances they sample). Both are wall-clock measurements on a shared machine.",
    "Budgets of the regime table: small ≤ 64 kB, medium ≤ 1 MB, large ≤ 16 MB.",
    "Wuson (s_wuson) is a faceted triangle mesh that is not watertight (its inside is the "
    "generalized winding number's): its SDF has creases at every edge and vertex, where it is "
    "C0 only, and the near-surface band L∞ of every method is set there. Methods that assume "
    "smoothness (Taylor-2 grid peers, C1 PHT splines) lose their order on it; the rates table "
    "shows how far each still falls. Worse than creases: where w passes 1/2 off the mesh (the "
    "sheets that close its 2,338 open edges) the sign flips at |d| > 0, so the SDF jumps by "
    "2|d|, up to 0.1 inside the band |d| ≤ 0.05. A continuous method's band L∞ cannot fall "
    "below about half the largest jump its error points straddle, whatever its resolution; "
    "near the sheets the PHT fit stops at its max_level whatever eps, so its band L∞ on Wuson "
    "follows neither eps nor the level (a C1 spline fitted to Hermite data from both sides of "
    "a jump can overshoot), while its band L1 falls with the level.",
    "Order-2 proxies with the analytic curvature skip the meshes (skip_kinds): a mesh's SDF has "
    "no curvature at an edge or vertex footpoint (its Hessian there is 1/rounding, of either "
    "sign: such proxies flipped the sign of whole cells, errors of 2|d|), and dflab refuses "
    "it. m_proxy2_fit takes the meshes with the paper's fitted curvature (5 × 5 stencil, "
    "spacing 0.005) and two choices of dflab's, not the paper's: a cell whose fit finds fewer "
    "than 10 stencil nodes on the surface (normal lines through Wuson's holes) gets the tangent "
    "plane (curvature_fallback = plane), and fitted bends are cut to 1 + k d ≥ 0 "
    "(curvature_clamp = focal: a crease fitted at the stencil's scale otherwise puts the cell "
    "centre past the centre of curvature, and the proxy turns inside out). It runs at res ≤ 32 "
    "(about 1.5 ms of CPU per cell). The implicit surface gets order-2 proxies from its own "
    "footpoints (m_proxy2_implicit, input = implicit), the sphere and torus also from their "
    "parametric patches (m_proxy2_param).",
    "The tricubic grid peer (m_gp_tricubic, field/gridpeer.h) stores one coefficient per cell, "
    "as trilinear0 does, so the two meet at equal bytes: the C2 cubic B-spline interpolating "
    "the same samples, not-a-knot at the box faces (exact for every cubic up to and beyond "
    "them). It assumes smoothness: across a crease of the SDF (a mesh's edges, a CSG seam, "
    "the medial axis) it overshoots where the trilinear grid does not, so its whole-box L∞ "
    "can exceed trilinear's while its band error is lower.",
    "The genus-2 surface (s_genus2: geom/implicit.h's tube around Bernoulli's lemniscate, "
    "eps 0.1; its SDF through footpoints on the zero set, about 0.1–0.3 ms each) and its "
    "marching-cubes mesh (s_genus2_mc: watertight, vertices on the surface) lie in "
    "[-1.07, 1.07]² × [-0.105, 0.105]; their box is [-1.25, 1.25]² × [-0.5, 0.5] (grid "
    "methods get flat cells there, 2.5 : 1). The implicit surface runs a reduced sweep "
    "(max_values = 4 in methods.ini: each method's first four settings; the rest are skipped "
    "rows), and the SDF-input proxies skip it (an implicit shape offers footpoints, no SDF "
    "representation). The CSG scene (s_scene2: hvb25's Scene 2 "
    "stand-in, a box with a bowl cut and a ring over it) is the min/max of exact SDFs: exact "
    "outside the union, a bound inside near the seams; that min/max field is the reference "
    "every method is measured against.",
    "A method's own tolerance is a target, not a result: a PHT row's setting eps=… is the "
    "eps its fit aimed at, and the fit stops refining a cell at max_level whether or not the "
    "cell's estimate met eps. The columns target (the tolerance), target_met (1/0) and "
    "target_over (leaf cells whose estimate stayed above it) say what the fit reached; kinds "
    "without a tolerance leave them empty. A row whose target was not met is marked "
    "\"[target … not met: N cells over]\" beside its setting in the tables below and listed "
    "under them. On Wuson no eps is reachable near the sign jumps (a continuous spline errs "
    "by |d| beside a jump of 2|d|), and smooth shapes can miss a fine eps at a small "
    "max_level too (quick.ini's max_level = 6). target_met is the "
    "fit's estimate (its own sample points), not the protocol's error: a met row's L∞ over the "
    "error points can still exceed its eps. The column target_linf_met is the study's own "
    "verdict (1 when the row's L∞ over every error point is ≤ the target); a row the fit "
    "calls met whose L∞ is not is marked \"[target … met by the fit's estimate; L∞ … over "
    "the error points]\".",
    "OpenVDB (kind = openvdb) is a narrow-band level set: outside |d| < band·voxel its value is "
    "the background, so its rows enter the near-surface columns only (their band, 10 voxels in methods.ini and 8 at quick.ini's coarser voxels, "
    "covers |d| ≤ 0.05 at every voxel used), never the whole-box ones. Its bytes are OpenVDB's "
    "memUsage (tree nodes, buffers, masks).",
]


def _not_met(r):
    """True when the row's build had a target and did not meet it."""
    return (r.get("target_met") or "") == "0"


def _met_not_measured(r):
    """True when the build says it met its target and the study's L∞ over
    its error points says it did not."""
    return (r.get("target_met") or "") == "1" and (r.get("target_linf_met") or "") == "0"


def _setting(r):
    """The row's setting, marked when its target was not met, by the
    build's own estimate or by the study's L∞."""
    s = r.get("setting", "")
    if _not_met(r):
        s += (f" [target {r.get('target', '')} not met: {r.get('target_over', '?')} cells "
              "over]")
    elif _met_not_measured(r):
        s += (f" [target {r.get('target', '')} met by the fit's estimate; L∞ "
              f"{_f(r, 'linf'):.3g} over the error points]")
    return s


def _targets(rows):
    """The measured rows whose target was not met, one line each kind."""
    bad = [r for r in rows if _not_met(r)]
    est = [r for r in rows if _met_not_measured(r)]
    out = ""
    if bad:
        out += ("Targets not met (the build stopped before its own tolerance; see the "
                "assumptions): " +
                "; ".join(f"{r['method']} on {r['shape']} {r['setting']}: "
                          f"{r.get('target_over', '?')} cells over {r.get('target', '')}"
                          for r in bad) + ".\n\n")
    if est:
        out += ("Targets met by the build's own estimate but not by the study's L∞ over its "
                "error points: " +
                "; ".join(f"{r['method']} on {r['shape']} {r['setting']}: L∞ "
                          f"{_f(r, 'linf'):.3g} > {r.get('target', '')}" for r in est) +
                ".\n\n")
    return out


def _measured(rows):
    return [r for r in rows if not r.get("skipped")]


def _lines(rows):
    """method -> its rows in increasing bytes (rows with known bytes)."""
    out = {}
    for r in rows:
        if math.isnan(_f(r, "bytes")):
            continue
        out.setdefault(r["method"], []).append(r)
    for m in out:
        out[m].sort(key=lambda r: _f(r, "bytes"))
    return out


def _pareto(points):
    """Indices of the points (x, y) no other point beats in both (smaller is better)."""
    order = sorted(range(len(points)), key=lambda i: (points[i][0], points[i][1]))
    front, best = [], math.inf
    for i in order:
        if points[i][1] < best:
            front.append(i)
            best = points[i][1]
    return front


def _xval(r, axis):
    if axis == "bytes":
        return _f(r, "bytes")
    if axis == "query":
        q = _f(r, "queries_per_s")
        return 1.0 / q if q > 0 else math.nan
    return _f(r, "build_s")


AXES = [("bytes", "stored bytes"), ("query", "seconds per query"), ("build", "build seconds")]


def _plot_shape(ctx, plt, shape, rows):
    lines = _lines(rows)
    if not lines:
        return ""
    fig, axs = plt.subplots(2, 3, figsize=(15, 8.5), layout="constrained")
    for row, (rname, col) in enumerate(REGIONS):
        for k, (axis, label) in enumerate(AXES):
            ax = axs[row][k]
            pts, allr = [], []
            for m, rs in sorted(lines.items()):
                rs = [r for r in rs if _in_region(r, col)]
                if not rs:
                    continue
                xs = [_xval(r, axis) for r in rs]
                ys = [max(_f(r, col), 1e-17) for r in rs]
                ax.plot(xs, ys, "o-", ms=3, label=m)
                pts += list(zip(xs, ys))
                allr += rs
            ok = [i for i, p in enumerate(pts) if all(math.isfinite(v) and v > 0 for v in p)]
            front = [ok[i] for i in _pareto([pts[i] for i in ok])]
            if front:
                ax.plot([pts[i][0] for i in front], [pts[i][1] for i in front], "k--", lw=0.8)
                ax.scatter([pts[i][0] for i in front], [pts[i][1] for i in front], s=60,
                           facecolors="none", edgecolors="k", label="Pareto front")
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xlabel(label)
            ax.set_ylabel(f"{rname}: {col}")
            ax.grid(True, which="both", alpha=0.3)
    axs[0][0].legend(fontsize=7)
    fig.suptitle(f"{shape}: error vs cost ({ctx.config})")
    return ctx.figure(fig, f"pareto_{shape}") + "\n\n"


def _continuity(r):
    c0, c1 = _f(r, "c0_jump"), _f(r, "c1_jump")
    if c0 > 1e-6:
        return f"discontinuous (c0_jump {c0:.2g})"
    if c1 > 1e-4:
        return f"C0 with gradient jumps up to {c1:.2g}"
    if r.get("kind") == "openvdb":
        # field/vdb.h: OpenVDB's samplers give values only; the gradient is a
        # central difference of the sampler (step voxel/2), itself continuous
        # wherever the sampler is, so c1_jump measures that difference, not
        # the sampler's own derivative (trilinear: it jumps at voxel faces)
        return ("C0; its gradient, a central difference of the sampler (step voxel/2), is "
                "continuous by construction, so no C1 claim for the sampler itself")
    return "C1 by measurement"


def _best(rows, col, budget):
    cand = [r for r in rows if _f(r, "bytes") <= budget and math.isfinite(_f(r, col))
            and _in_region(r, col)]
    best = {}
    for r in cand:  # each method's best row within the budget
        m = r["method"]
        if m not in best or _f(r, col) < _f(best[m], col):
            best[m] = r
    return sorted(best.values(), key=lambda r: _f(r, col))


def _regime_table(shapes, rows):
    body = []
    for shape in shapes:
        rs = [r for r in rows if r["shape"] == shape]
        for bname, budget in BUDGETS:
            for rname, col in REGIONS:
                ranked = _best(rs, col, budget)
                if not ranked:
                    body.append([shape, bname, rname, "—", "—", "no method fits the budget"])
                    continue
                w = ranked[0]
                why = (f"{w['method']} ({_setting(w)}, {dflio.fmt(_f(w, 'bytes'))} B) has "
                       f"{col} {_f(w, col):.3g}")
                if len(ranked) > 1:
                    s = ranked[1]
                    ratio = _f(s, col) / _f(w, col) if _f(w, col) > 0 else math.inf
                    why += f", {ratio:.3g}× below the next, {s['method']} ({_f(s, col):.3g})"
                why += f"; {_continuity(w)}"
                body.append([shape, bname, rname, w["method"], f"{_f(w, col):.3g}", why])
    return dflio.md_table(["shape", "budget", "region", "best", "error", "reason"], body)


def _interp(rs, col, x):
    """col at bytes x, linear in log-log between the bracketing rows; NaN
    outside the measured range (no extrapolation)."""
    pts = [(_f(r, "bytes"), _f(r, col)) for r in rs]
    pts = [p for p in pts if p[0] > 0 and p[1] > 0 and math.isfinite(p[1])]
    for (x0, y0), (x1, y1) in zip(pts, pts[1:]):
        if x0 <= x <= x1:
            if x1 == x0:
                return y0
            t = (math.log(x) - math.log(x0)) / (math.log(x1) - math.log(x0))
            return math.exp(math.log(y0) + t * (math.log(y1) - math.log(y0)))
    return math.nan


def _aim(rows):
    rs = [r for r in rows if r["shape"] == "s_torus"]
    lines = _lines(rs)
    if not lines:
        return ""
    vals = {m: _interp(l, "band_linf", AIM_BYTES) for m, l in lines.items()}
    fin = {m: v for m, v in vals.items() if math.isfinite(v)}
    if not fin:
        return ""
    best = min(fin, key=fin.get)
    body = []
    for m in sorted(vals, key=lambda m: (not math.isfinite(vals[m]), vals[m])):
        v = vals[m]
        near = min(lines[m], key=lambda r: abs(math.log(_f(r, "bytes") / AIM_BYTES)))
        body.append([m, f"{v:.3g}" if math.isfinite(v) else "— (out of range)",
                     f"{v / fin[best]:.3g}" if math.isfinite(v) else "—",
                     f"{_setting(near)} ({dflio.fmt(_f(near, 'bytes'))} B)",
                     f"{_f(near, 'queries_per_s'):.3g}", _continuity(near)])
    md = (f"**The torus at {AIM_BYTES / 1e6:.1f} MB, band |d| ≤ 0.05** (band L∞ interpolated "
          "log-log between each method's measured sizes; '—' outside them). Best: "
          f"**{best}** ({fin[best]:.3g}).\n\n")
    return md + dflio.md_table(["method", "band_linf at 8.6 MB", "× best",
                                "nearest setting", "queries/s there", "continuity"], body) + "\n\n"


def _slope(pts):
    """Least-squares slope of log y on log x over pts [(x, y)], x, y > 0."""
    lx = [math.log(x) for x, _ in pts]
    ly = [math.log(y) for _, y in pts]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    sxx = sum((u - mx) ** 2 for u in lx)
    if sxx == 0:
        return math.nan
    return sum((u - mx) * (v - my) for u, v in zip(lx, ly)) / sxx


def _rates(shapes, rows):
    """Per shape and method: how the near-surface band L∞ falls with stored
    bytes, as the fitted exponent k of band_linf ∝ bytes^k over the
    method's settings (at least two with finite, positive error and known
    bytes), beside the first and last error."""
    body = []
    for shape in shapes:
        for m, rs in _lines([r for r in rows if r["shape"] == shape]).items():
            pts = [(_f(r, "bytes"), _f(r, "band_linf")) for r in rs]
            pts = [p for p in pts if p[0] > 0 and math.isfinite(p[1]) and p[1] > 0]
            if len(pts) < 2:
                continue
            k = _slope(pts)
            nf = sum(int(_f(r, "nonfinite")) for r in rs if math.isfinite(_f(r, "nonfinite")))
            falls = "yes" if k < 0 and pts[-1][1] < pts[0][1] else "no"
            unmet = [r["setting"] for r in rs if _not_met(r)]
            est = [r["setting"] for r in rs if _met_not_measured(r)]
            tcell = "; ".join(([("not met at " + ", ".join(unmet))] if unmet else []) +
                              ([("L∞ above it at " + ", ".join(est))] if est else [])) or "—"
            body.append([shape, m, str(len(pts)),
                         f"{dflio.fmt(pts[0][0])} → {dflio.fmt(pts[-1][0])}",
                         f"{pts[0][1]:.3g} → {pts[-1][1]:.3g}", f"{k:.3g}", falls, str(nf),
                         tcell])
    if not body:
        return ""
    return ("### How the error falls with resolution\n\nNear-surface band L∞ against stored "
            "bytes, fitted as band_linf ∝ bytes^k (least squares in log-log over each "
            "method's settings; in 3D a uniform grid's k = −2/3 means error ∝ h², −1/3 "
            "error ∝ h).\n\n" +
            dflio.md_table(["shape", "method", "settings", "bytes", "band_linf", "k",
                            "falls", "non-finite", "target"], body) + "\n\n")


def render(ctx):
    plt = pyplot()
    rows = ctx.csv()
    meas = _measured(rows)
    shapes = dflio.unique(r["shape"] for r in rows)
    skipped = [r for r in rows if r.get("skipped")]
    md = (f"{len(meas)} measured rows, {len(dflio.unique(r['method'] for r in meas))} methods, "
          f"{len(shapes)} shapes; non-finite values: "
          f"{sum(int(_f(r, 'nonfinite')) for r in meas)}.\n\n")
    if skipped:
        md += ("Not run (the method does not apply, or its build failed): " +
               "; ".join(f"{r['method']} on {r['shape']} {r['setting']}: {r['skipped']}"
                         for r in skipped) + ".\n\n")
    md += _targets(meas)
    md += "### Best method per regime\n\n" + _regime_table(shapes, meas) + "\n\n"
    md += _aim(meas)
    md += _rates(shapes, meas)
    for s in shapes:
        md += f"### {s}\n\n" + _plot_shape(ctx, plt, s, [r for r in meas if r["shape"] == s])
    return md
