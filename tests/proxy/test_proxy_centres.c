/* Cell centres on the surface (proxy.h "Cell centres on the surface"): a
 * plane, a box and a sphere through layers of cell centres, and shapes
 * through cell edges and corners, in every storage and position.  Every
 * cell decodes to a finite proxy and, at its own centre, to the exact
 * distance up to the documented move (2 delta) and the storage's rounding
 * (the footpoint is exact, so the proxy's value at x_c is |x_c - p|). */
#include <criterion/criterion.h>
#include <float.h>
#include <math.h>

#include "proxy/analytic_inputs.h"
#include "proxy/filter.h"
#include "proxy/proxy.h"

/* ---- a box [-a, a]^3 (order 1 only: its edges have no finite curvature) */

static void box_answer(double a, const double x[3], dfl_surfpoint *sp)
{
    double q[3], m = -INFINITY;
    int im = 0;
    for (int j = 0; j < 3; j++) {
        q[j] = fabs(x[j]) - a;
        if (q[j] > m) m = q[j], im = j;
    }
    memset(sp, 0, sizeof *sp);
    sp->certified = 1;
    if (m <= 0) { /* inside or on the surface: the nearest face */
        for (int j = 0; j < 3; j++) sp->p[j] = x[j], sp->n[j] = 0;
        sp->p[im] = copysign(a, x[im]);
        sp->n[im] = copysign(1.0, x[im]);
        sp->d = m;
        return;
    }
    double v[3], l2 = 0;
    for (int j = 0; j < 3; j++) {
        sp->p[j] = fmax(-a, fmin(a, x[j]));
        v[j] = x[j] - sp->p[j];
        l2 += v[j] * v[j];
    }
    sp->d = sqrt(l2);
    for (int j = 0; j < 3; j++) sp->n[j] = v[j] / sp->d;
}

static dfl_status box_query(const void *ctx, size_t m, const double *x, int need_curv,
                            dfl_surfpoint *out, dfl_err *err)
{
    (void)need_curv;
    (void)err;
    for (size_t i = 0; i < m; i++) box_answer(*(const double *)ctx, x + 3 * i, &out[i]);
    return DFL_OK;
}

/* ---- the check */

typedef double (*sdf_fn)(const void *ctx, const double x[3]);

static double sdf_ta(const void *ctx, const double x[3]) { return ta_sdf(ctx, x); }
static double sdf_box(const void *ctx, const double x[3])
{
    dfl_surfpoint sp;
    box_answer(*(const double *)ctx, x, &sp);
    return sp.d;
}

static double eps_of(dfl_proxy_storage s)
{
    return s == DFL_PROXY_DOUBLE ? 0x1p-52 : s == DFL_PROXY_FLOAT ? 0x1p-23 : 0x1p-10;
}

/* The header's first move length delta_0 (proxy.h). */
static double delta0(const dfl_proxy_grid *g, const double xc[3])
{
    const dfl_proxy_storage s = g->storage;
    const double e = s == DFL_PROXY_DOUBLE ? 0x1p-40 : s == DFL_PROXY_FLOAT ? 0x1p-20 : 0x1p-10;
    const double tiny = s == DFL_PROXY_DOUBLE ? DBL_MIN : s == DFL_PROXY_FLOAT ? FLT_MIN : 0x1p-14;
    double d = fmax(e * dfl_proxy_cell_size(g), tiny);
    if (g->position == DFL_PROXY_ABSOLUTE)
        d = fmax(d, 2 * eps_of(s) * fmax(fabs(xc[0]), fmax(fabs(xc[1]), fabs(xc[2]))));
    return d;
}

/* Builds the grid of `in` and checks every cell: finite decode, and at the
 * centre |phi - sdf| <= 4 delta_0 (one doubling at most in these cases)
 * plus a few roundings of the stored footpoint.  Returns the moved count
 * (the caller states how many centres lie on the surface). */
static size_t check_grid(const dfl_proxy_input *in, sdf_fn sdf, const void *ctx, int order,
                         int res, double lo, double hi, dfl_proxy_storage sto,
                         dfl_proxy_position pos, int plane)
{
    dfl_proxy_build_opts o;
    dfl_proxy_build_opts_default(&o);
    o.order = order;
    o.res = res;
    for (int j = 0; j < 3; j++) o.lo[j] = lo, o.hi[j] = hi;
    o.storage = sto;
    o.position = pos;
    dfl_proxy_grid g;
    cr_assert_eq(dfl_proxy_grid_build(in, &o, &g, NULL), DFL_OK);
    cr_expect_eq(g.stats.failed, 0);
    const double h = dfl_proxy_cell_size(&g), eps = eps_of(sto);
    size_t bad = 0;
    for (size_t c = 0; c < g.ncells; c++) {
        double xc[3];
        dfl_proxy_cell_centre(&g, c, xc);
        const double d = sdf(ctx, xc);
        const double m = fmax(fabs(xc[0]), fmax(fabs(xc[1]), fabs(xc[2])));
        const double round = 4 * eps * (fabs(d) + (pos == DFL_PROXY_ABSOLUTE ? 2 * m : 0));
        const double tol = 4 * delta0(&g, xc) + round + 1e-15;
        const double v = dfl_proxy_proxy_dist(&g, c, DFL_PROXY_CLIP_BOUND, 0, xc, NULL);
        int ok = isfinite(v) && fabs(v - d) <= tol;
        /* a plane's proxy is the plane: exact in the whole cell (with
         * absolute footpoints the moved cells' normal keeps only the
         * direction that survives rounding next to x_c, store.h) */
        if (plane && ok && pos == DFL_PROXY_DISPLACEMENT) {
            const double x[3] = {xc[0] + h / 3, xc[1] - h / 4, xc[2] + h / 5};
            const double vx = dfl_proxy_proxy_dist(&g, c, DFL_PROXY_CLIP_BOUND, 0, x, NULL);
            ok = isfinite(vx) && fabs(vx - sdf(ctx, x)) <= tol + 4 * eps * h;
        }
        if (!ok && bad++ < 3)
            cr_expect(0, "order %d res %d %s %s cell %zu: phi %.17g, sdf %.17g, tol %g", order, res,
                      dfl_proxy_storage_name(sto), dfl_proxy_position_name(pos), c, v, d, tol);
    }
    cr_expect_eq(bad, 0, "order %d res %d %s %s", order, res, dfl_proxy_storage_name(sto),
                 dfl_proxy_position_name(pos));
    const size_t moved = g.stats.moved;
    dfl_proxy_grid_free(&g);
    return moved;
}

/* The plane z = 0 at res 15 over [-1, 1]: the layer k = 7 of centres is on
 * it (225 cells). */
Test(proxy_centres, plane_z0_res15_every_storage)
{
    static const ta_shape plane = {TA_PLANE, {0, 0, 0}, {0, 0, 1}, 0, 0};
    dfl_proxy_input in;
    ta_input(&plane, &in);
    for (int order = 1; order <= 2; order++)
        for (int s = 0; s < DFL_PROXY_STORAGE_COUNT; s++)
            for (int pos = 0; pos < DFL_PROXY_POSITION_COUNT; pos++) {
                const size_t moved = check_grid(&in, sdf_ta, &plane, order, 15, -1, 1,
                                                (dfl_proxy_storage)s, (dfl_proxy_position)pos, 1);
                cr_expect_geq(moved, 225, "order %d storage %d position %d", order, s, pos);
            }
}

/* A box of half-size 0.5 at res 14: centres -1 + (k + 1/2) / 7 hit
 * +-0.5 at k = 3 and 10, so face, edge and corner points of the box are
 * cell centres (order 1). */
Test(proxy_centres, box_half05_res14_every_storage)
{
    static const double a = 0.5;
    dfl_proxy_input in = {"box", box_query, NULL, (void *)&a, 1};
    for (int s = 0; s < DFL_PROXY_STORAGE_COUNT; s++)
        for (int pos = 0; pos < DFL_PROXY_POSITION_COUNT; pos++) {
            const size_t moved = check_grid(&in, sdf_box, &a, 1, 14, -1, 1, (dfl_proxy_storage)s,
                                            (dfl_proxy_position)pos, 0);
            /* the surface holds the centres with one coordinate +-0.5 and the
             * others in [-0.5, 0.5]: 6 * 8^2 - 12 * 8 + 8 = 296 (inclusion-exclusion) */
            cr_expect_geq(moved, 296, "storage %d position %d", s, pos);
        }
}

/* A sphere centred at the centre of cell (7,7,7) of a 14^3 grid with radius
 * 3h passes through the centres of the cells 3 steps away on each axis. */
Test(proxy_centres, sphere_through_centres_every_storage)
{
    const double h = 2.0 / 14, c = -1 + 7.5 * h;
    const ta_shape sphere = {TA_SPHERE, {c, c, c}, {0, 0, 1}, 3 * h, 0};
    dfl_proxy_input in;
    ta_input(&sphere, &in);
    for (int order = 1; order <= 2; order++)
        for (int s = 0; s < DFL_PROXY_STORAGE_COUNT; s++)
            for (int pos = 0; pos < DFL_PROXY_POSITION_COUNT; pos++)
                check_grid(&in, sdf_ta, &sphere, order, 14, -1, 1, (dfl_proxy_storage)s,
                           (dfl_proxy_position)pos, 0);
}

/* Surfaces through cell faces, edges and corners: the plane z = 0 at res 16
 * (cell faces, no centre), the plane x = y (the cells' diagonal edges and
 * the centres i = j), a sphere about the grid vertex 0 through the
 * vertices (+-4h, 0, 0) and their permutations. */
Test(proxy_centres, edges_and_corners_every_storage)
{
    static const ta_shape pz = {TA_PLANE, {0, 0, 0}, {0, 0, 1}, 0, 0};
    static const ta_shape pxy = {TA_PLANE, {0, 0, 0}, {0.70710678118654752440, -0.70710678118654752440, 0}, 0, 0};
    static const ta_shape sph = {TA_SPHERE, {0, 0, 0}, {0, 0, 1}, 0.5, 0};
    const ta_shape *shapes[3] = {&pz, &pxy, &sph};
    for (int k = 0; k < 3; k++) {
        dfl_proxy_input in;
        ta_input(shapes[k], &in);
        for (int order = 1; order <= 2; order++)
            for (int s = 0; s < DFL_PROXY_STORAGE_COUNT; s++)
                for (int pos = 0; pos < DFL_PROXY_POSITION_COUNT; pos++)
                    check_grid(&in, sdf_ta, shapes[k], order, 16, -1, 1, (dfl_proxy_storage)s,
                               (dfl_proxy_position)pos, k < 2);
    }
}
