/* The storage range (store.h "Range"): no stored proxy decodes to a
 * non-finite value, whatever the input's curvatures (0 to 1e300, both
 * signs, subnormal), the shape's scale (a 1e5 and a 1e-9 sphere) or the
 * footpoint noise (1e10), in every storage and position; capped cells are
 * counted in stats.clamped. */
#include <criterion/criterion.h>
#include <float.h>
#include <math.h>

#include "proxy/analytic_inputs.h"
#include "proxy/filter.h"
#include "proxy/proxy.h"

/* A sphere's footpoints with the curvatures replaced by (k1, k2). */
typedef struct curv_ctx {
    ta_shape s;
    double k1, k2;
} curv_ctx;

static dfl_status curv_query(const void *ctx, size_t m, const double *x, int need_curv,
                             dfl_surfpoint *out, dfl_err *err)
{
    (void)need_curv;
    (void)err;
    const curv_ctx *c = ctx;
    for (size_t i = 0; i < m; i++) {
        ta_answer(&c->s, x + 3 * i, &out[i]);
        out[i].curv.k1 = c->k1;
        out[i].curv.k2 = c->k2;
    }
    return DFL_OK;
}

/* Every cell of g: decoded footpoint, frame and curvatures finite, and the
 * proxy's distance finite at the centre and the 8 corners of the cell.
 * Returns the number of cells that are not. */
static size_t nonfinite_cells(const dfl_proxy_grid *g)
{
    const double h = dfl_proxy_cell_size(g);
    size_t bad = 0;
    for (size_t c = 0; c < g->ncells; c++) {
        dfl_proxy_geom pg;
        dfl_proxy_cell_decode(g, c, &pg);
        int ok = isfinite(pg.kr) && isfinite(pg.kR);
        for (int j = 0; j < 3; j++)
            ok = ok && isfinite(pg.p[j]) && isfinite(pg.n[j]) && isfinite(pg.t[j]) &&
                 isfinite(pg.b[j]);
        double xc[3];
        dfl_proxy_cell_centre(g, c, xc);
        for (int q = 0; q < 9 && ok; q++) {
            double x[3], gr[3];
            for (int j = 0; j < 3; j++)
                x[j] = xc[j] + (q == 8 ? 0.0 : ((q >> j) & 1 ? 0.5 : -0.5) * h);
            const double v = dfl_proxy_proxy_dist(g, c, DFL_PROXY_CLIP_BOUND, 0, x, gr);
            ok = isfinite(v) && isfinite(gr[0]) && isfinite(gr[1]) && isfinite(gr[2]);
        }
        bad += !ok;
    }
    return bad;
}

static void build(const dfl_proxy_input *in, int order, int res, double lo, double hi,
                  dfl_proxy_storage s, dfl_proxy_position pos, double noise, dfl_proxy_grid *g)
{
    dfl_proxy_build_opts o;
    dfl_proxy_build_opts_default(&o);
    o.order = order;
    o.res = res;
    for (int j = 0; j < 3; j++) o.lo[j] = lo, o.hi[j] = hi;
    o.storage = s;
    o.position = pos;
    o.noise = noise;
    o.seed = 11;
    cr_assert_eq(dfl_proxy_grid_build(in, &o, g, NULL), DFL_OK);
}

Test(proxy_range, extreme_curvatures_decode_finite)
{
    static const double mag[] = {0,    4.9e-324, 1e-310, 1e-300, 1e-3, 1,     1e3,   65504,
                                 65520, 1e5,     1e10,   3e38,   1e39, 1e150, 1e300, DBL_MAX};
    const int nm = (int)(sizeof mag / sizeof mag[0]);
    curv_ctx cc = {{TA_SPHERE, {0.02, -0.03, 0.01}, {0, 0, 1}, 0.5, 0}, 0, 0};
    dfl_proxy_input in = {"curv", curv_query, NULL, &cc, 1};
    size_t clamped_half = 0;
    for (int a = 0; a < 2 * nm; a++)
        for (int b = 0; b < 2 * nm; b++) {
            cc.k1 = (a % 2 ? -1 : 1) * mag[a / 2];
            cc.k2 = (b % 2 ? -1 : 1) * mag[b / 2];
            for (int s = 0; s < DFL_PROXY_STORAGE_COUNT; s++)
                for (int pos = 0; pos < DFL_PROXY_POSITION_COUNT; pos++) {
                    dfl_proxy_grid g;
                    build(&in, 2, 3, -1, 1, (dfl_proxy_storage)s, (dfl_proxy_position)pos, 0, &g);
                    cr_expect_eq(g.stats.failed, 0);
                    const size_t bad = nonfinite_cells(&g);
                    cr_expect_eq(bad, 0, "k1 %g k2 %g %s %s: %zu cells", cc.k1, cc.k2,
                                 dfl_proxy_storage_name(g.storage),
                                 dfl_proxy_position_name(g.position), bad);
                    /* a curvature beyond half's 65504 is capped and counted */
                    const int over = fmax(fabs(cc.k1), fabs(cc.k2)) > 65504;
                    if (s == DFL_PROXY_HALF) {
                        cr_expect_eq(g.stats.clamped, over ? g.ncells : 0, "k1 %g k2 %g", cc.k1,
                                     cc.k2);
                        clamped_half += g.stats.clamped;
                    }
                    dfl_proxy_grid_free(&g);
                }
        }
    cr_expect_gt(clamped_half, 0);
}

/* Curvatures that fit the storage are stored as they are (no cap below
 * the storage's range for an ordinary cell size). */
Test(proxy_range, curvatures_in_range_kept)
{
    curv_ctx cc = {{TA_SPHERE, {0.02, -0.03, 0.01}, {0, 0, 1}, 0.5, 0}, -65504, 1e3};
    dfl_proxy_input in = {"curv", curv_query, NULL, &cc, 1};
    dfl_proxy_grid g;
    build(&in, 2, 3, -1, 1, DFL_PROXY_HALF, DFL_PROXY_DISPLACEMENT, 0, &g);
    cr_expect_eq(g.stats.clamped, 0);
    dfl_proxy_geom pg;
    dfl_proxy_cell_decode(&g, 13, &pg);
    cr_expect_eq(pg.kr, -65504.0);
    cr_expect_eq(pg.kR, 1000.0);
    dfl_proxy_grid_free(&g);
    cc.k1 = 1e15; /* below float's range and 2^64 / h */
    build(&in, 2, 3, -1, 1, DFL_PROXY_FLOAT, DFL_PROXY_DISPLACEMENT, 0, &g);
    cr_expect_eq(g.stats.clamped, 0);
    dfl_proxy_cell_decode(&g, 13, &pg);
    cr_expect_eq(pg.kr, (double)1e15f);
    dfl_proxy_grid_free(&g);
}

/* Huge and tiny shapes and huge noise: every storage, position, order. */
Test(proxy_range, scales_and_noise_decode_finite)
{
    static const ta_shape big = {TA_SPHERE, {1e3, -2e3, 5e2}, {0, 0, 1}, 1e5, 0};
    static const ta_shape tiny = {TA_SPHERE, {1e-11, 0, -2e-11}, {0, 0, 1}, 1e-9, 0};
    static const ta_shape unit = {TA_SPHERE, {0.02, -0.03, 0.01}, {0, 0, 1}, 0.5, 0};
    const struct {
        const ta_shape *s;
        double lo, hi, noise;
    } cases[] = {{&big, -2e5, 2e5, 0}, {&tiny, -2e-9, 2e-9, 0}, {&unit, -1, 1, 1e10},
                 {&big, -2e5, 2e5, 1e10}, {&tiny, -2e-9, 2e-9, 1e-8}};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        dfl_proxy_input in;
        ta_input(cases[k].s, &in);
        for (int order = 1; order <= 2; order++)
            for (int s = 0; s < DFL_PROXY_STORAGE_COUNT; s++)
                for (int pos = 0; pos < DFL_PROXY_POSITION_COUNT; pos++) {
                    dfl_proxy_grid g;
                    build(&in, order, 8, cases[k].lo, cases[k].hi, (dfl_proxy_storage)s,
                          (dfl_proxy_position)pos, cases[k].noise, &g);
                    cr_expect_eq(g.stats.failed, 0, "case %zu order %d %s %s", k, order,
                                 dfl_proxy_storage_name(g.storage),
                                 dfl_proxy_position_name(g.position));
                    const size_t bad = nonfinite_cells(&g);
                    cr_expect_eq(bad, 0, "case %zu order %d %s %s: %zu cells", k, order,
                                 dfl_proxy_storage_name(g.storage),
                                 dfl_proxy_position_name(g.position), bad);
                    dfl_proxy_grid_free(&g);
                }
    }
}
