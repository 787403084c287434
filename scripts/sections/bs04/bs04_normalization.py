"""bs04 Sec. 2.3: the normalization-order table (join x p x trim), measured with jets."""
import dflio
from sections.bs04 import bs04_common as bc
from sections.common.plot import pyplot

ASSUMPTIONS = [
    "Normalization order: measured on an open 'W' polyline of 4 segments (configs/paper/bs04/"
    "bs04_normalization.ini), at 5 interior points per segment along both normals; the "
    "table reports the minimum over these 40 rays. A Taylor coefficient a_k = d_k/k! counts as "
    "zero when |a_k| L^(k-1) <= 1e-9 with L the segment's length, d1 as 1 when |d1 - 1| <= 1e-9.",
    "Joining points are probed along the outer bisector, free end points along a fan of 9 "
    "outward directions (Rvachev's generalized normals) and along the segment's normal.",
    "R-conjunction with p = 1 is a + b - (a + b) = 0, not a join: its rows say n/a.",
]


def _ran(by, keys, shown_p):
    """(join, p, trim, row) for the keys (join, p, trim), in their order, whose
    point ran (status ok) and whose p is one of shown_p."""
    for j, p, t in keys:
        r = by.get((j, p, t))
        if r and r["status"] == "ok" and p in shown_p:
            yield j, p, t, r


def render(ctx):
    plt = pyplot()

    rows = ctx.csv()
    f = dflio.num
    jk, pk, tk = "join", "p", "trim"
    joins = dflio.unique(r[jk] for r in rows)
    trims = dflio.unique(r[tk] for r in rows)
    ps = sorted({int(float(r[pk])) for r in rows})
    by = {(r[jk], int(float(r[pk])), r[tk]): r for r in rows}
    ref = bc.facts(ctx)

    ok = [r for r in rows if r["status"] == "ok"]
    mism = [r for r in ok if r["match"] != "1"]
    md = ("bs04 claims (Sec. 2.3, eq. 6–7): R-equivalence of order p keeps normalization through "
          f"order **{ref.get('requiv_order', {}).get('value', 'p')}**, R-conjunction through "
          f"**{ref.get('rconj_order', {}).get('value', 'p-1')}**. Each cell below is the measured "
          "order (minimum over the interior rays of the 'W' polyline) / the theory; the smooth "
          "trim (eq. 5) caps the theory at 6. Join requiv_corrected is dflab's guarded eq. 20 "
          "(correction = guarded), not bs04's formula as printed (see the corrected-join section). "
          f"**{len(ok) - len(mism)} of {len(ok)} rows match the theory**"
          + (f"; mismatches: {', '.join(r[jk] + ' p=' + r[pk] + ' ' + r[tk] for r in mism)}"
             if mism else "") + ".\n\n")
    header = ["p"] + [f"{j} / {t}" for j in joins for t in trims]
    body = []
    for p in ps:
        line = [p]
        for j in joins:
            for t in trims:
                r = by.get((j, p, t))
                if not r:
                    line.append(None)
                elif r["status"] != "ok":
                    line.append("n/a (p ≥ 2)")
                else:
                    cell = f"{int(f(r['measured_order']))} / {int(f(r['order_theory']))}"
                    if r["capped"] == "1":
                        cell = "≥" + cell
                    if r["match"] != "1":
                        cell = f"**{cell} ✗**"
                    line.append(cell)
        body.append(line)
    md += dflio.md_table(header, body) + "\n\n"

    md += ("**Where the trim limits the order.** At an interior point the ray along the normal "
           "stays inside the trim region (disk: t = t0 − s²/d > 0 for small s; strip: t is "
           "constant along the normal), and there eq. 4 is h = √(f² + max(−t, 0)²) = |f| = s "
           "*exactly*: the disk and the strip limit nothing, the order is the join's. Eq. 5 "
           "replaces |t| by √(t² + f⁴): g = √(t² + f⁴) − t = f⁴/(2t) − …, "
           "h = √(f² + g²/4) = |f| + |f|⁷/(32 t²) + O(f¹¹), so the part itself is normalized "
           "to order 6 exactly, with d⁷h/ds⁷ = 7!/(32 t0²) ≠ 0; every join inherits that cap "
           "(the join's own term s^(p+1), or s^p for R-conjunction, adds to it when it also "
           "lands at s⁷). The table shows the cap at 6 in every disk_smooth column from "
           "p = 7 (R-equivalence) or p = 8 (R-conjunction) on.\n\n")

    # first non-zero coefficient
    md += ("First non-zero Taylor coefficient a_k = d_k/k! along the normal at the ray of the "
           "minimum (k = order + 1), beside its prediction from the part values at that point "
           "(R-equivalence: −C/p, C = Σ_(j≠i) h_j^(−p); dflab's guarded eq. 20: C minus the guarded vertex "
           "terms; R-conjunction: −B/p, B = u_(i−1)^(1−p) + Σ_(j>i) h_j^(1−p); eq. 5: "
           "+1/(32 t0²) at k = 7), and the largest relative difference over all 40 rays:\n\n")
    header = ["join", "trim", "p", "k", "d_k measured", "a_k measured", "a_k predicted",
              "max rel. diff (all rays)"]
    body = [[j, t, p, int(f(r["first_k"])), f(r["first_deriv"]), f(r["first_coef"]),
             f(r.get("first_coef_theory")), f(r["coef_relerr_max"])]
            for j, p, t, r in _ran(by, [(j, p, t) for j in joins for t in trims for p in ps],
                                   (2, 6, 7, 12))]
    md += dflio.md_table(header, body) + "\n\n"

    # end points and joining points
    md += ("**End points and joining points** (normalization is expected to fail there; "
           "bs04 Sec. 1.2, 2.3). Joining points, along the outer bisector: the two adjacent "
           "fields both grow like s, so d1 = 2^(−1/p) (R-equivalence), 2 − 2^(1/p) "
           "(R-conjunction), 1 (dflab's guarded eq. 20, join = requiv_corrected with correction = "
           "guarded: the guard removes one of the two terms) — "
           "but even this corrected join is normalized to order 1 only, since the trimmed fields "
           "are not exact distances beyond their end points (h = s + (w·e/d) s² + … for the disk). "
           "Free ends: d1 = 1 in every outward direction (bs04 Sec. 2.1: normalized at the end "
           "points in Rvachev's generalized sense), but only to order 1; along the segment's "
           "normal at an end the disk gives h = s + s³/(2d²) (order 2) while the strip gives "
           "h = |f| (t = 0 on the whole normal line): the join's full order.\n\n")
    header = ["join", "p", "trim", "joint d1 measured", "joint d1 theory", "joint order",
              "end d1 range", "end order (fan)", "end order along normal / theory"]
    body = [[j, p, t,
             f"{f(r['joint_d1_min']):.6f}…{f(r['joint_d1_max']):.6f}",
             f"{f(r['joint_d1_theory']):.6f}",
             f"{int(f(r['joint_order_max']))} / {int(f(r['joint_order_theory']))}",
             f"{f(r['end_d1_min']):.12f}…{f(r['end_d1_max']):.12f}",
             f"{int(f(r['end_order_min']))} / {int(f(r['end_order_theory']))}",
             f"{int(f(r['end_normal_order_min']))} / {int(f(r['end_normal_order_theory']))}"]
            for j, p, t, r in _ran(by, [(j, p, t) for j in joins for p in ps for t in trims],
                                   (1, 2, 7, 12))]
    md += dflio.md_table(header, body) + "\n\n"
    md += ("dflab's guarded eq. 20 can exceed the plain theory along an end's normal: where every "
           "vertex guard max(q_v, h_i, h_j) picks a part's field (the trimmed fields exceed the "
           "vertex distance there), the sums telescope and u = h_i along that ray; "
           "end_normal_order_theory accounts for it per ray.\n\n")

    # figure: order vs p
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.8))
    ax = axes[0]
    mk = {"requiv": "o", "rconj": "s", "requiv_corrected": "^"}
    ls = {t: s for t, s in zip(trims, ["-", "--", ":", "-."])}
    for ji, j in enumerate(joins):
        for ti, t in enumerate(trims):
            pp = [p for p in ps if by.get((j, p, t)) and by[(j, p, t)]["status"] == "ok"]
            dx = 0.09 * (ti - (len(trims) - 1) / 2)  # offsets keep coinciding curves visible
            dy = 0.09 * (ji - (len(joins) - 1) / 2)
            ax.plot([p + dx for p in pp], [f(by[(j, p, t)]["measured_order"]) + dy for p in pp],
                    ls[t], marker=mk.get(j, "x"), ms=3.5, lw=1, label=f"{j}, {t}")
    ax.plot(ps, ps, color="0.7", lw=4, alpha=0.4, zorder=0, label="p (theory, R-equivalence)")
    ax.set_xlabel("p")
    ax.set_ylabel("measured order")
    ax.legend(fontsize=6)
    ax.set_title("normalization order vs p (min over rays;\ncurves offset ±0.09 so that "
                 "coinciding ones show)\n" + ctx.config, fontsize=8)
    ax = axes[1]
    for j in joins:
        t = trims[0]
        pp = [p for p in ps if by.get((j, p, t)) and by[(j, p, t)]["status"] == "ok"]
        ax.plot(pp, [f(by[(j, p, t)]["joint_d1_min"]) for p in pp], marker=mk.get(j, "x"),
                ls="none", label=f"{j} measured")
        ax.plot(pp, [f(by[(j, p, t)]["joint_d1_theory"]) for p in pp], "-", color="0.5", lw=0.8)
    ax.set_xlabel("p")
    ax.set_ylabel("d1 at the joining points")
    ax.legend(fontsize=7)
    ax.set_title(f"first derivative along the outer bisector\nat the joining points, trim "
                 f"{trims[0]} (lines: theory)\n"
                 + ctx.config, fontsize=8)
    md += ctx.figure(fig, "orders") + "\n"
    return md
