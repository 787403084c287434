/* The page's C API (dflweb.h).  Thin on purpose: the page must show what
 * `dflab run` and `dflab probe` compute, so each entry point is one or two
 * library calls; what is added here is only bookkeeping (the scene owns
 * its field and a copy of the vertices the exact distance needs). */
#include "web/dflweb.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/jet.h"
#include "core/status.h"
#include "field/curveprobe.h"
#include "field/exact.h"
#include "field/field.h"
#include "field/normorder.h"
#include "geom/bspline.h"
#include "geom/footpoint.h"
#include "geom/param_shape.h"
#include "geom/polygonize.h"
#include "geom/segdist.h"
#include "rfunc/exact_polyline.h"
#include "rfunc/gradbound.h"
#include "rfunc/join.h"
#include "rfunc/rfield.h"
#include "rfunc/segment.h"

struct dflw_scene {
    dfl_field f;   /* f.ops == NULL: no field */
    double *v;     /* 2n vertices of the polyline */
    int n;
    dfl_bspline curve; /* dflw_scene_curve's curve (zeroed otherwise) */
    dfl_polyline pl;   /* and its polygonization (parameters of the vertices) */
    dfl_err err;
};

dflw_scene *dflw_scene_new(void)
{
    return calloc(1, sizeof(dflw_scene));
}

static void scene_clear(dflw_scene *s)
{
    dfl_field_destroy(&s->f);
    dfl_bspline_free(&s->curve);
    dfl_polyline_free(&s->pl);
    memset(&s->curve, 0, sizeof s->curve);
    memset(&s->pl, 0, sizeof s->pl);
    free(s->v);
    s->v = NULL;
    s->n = 0;
}

void dflw_scene_free(dflw_scene *s)
{
    if (!s) return;
    scene_clear(s);
    free(s);
}

const char *dflw_scene_error(const dflw_scene *s)
{
    return s->err.msg;
}

void dflw_two_segments(double alpha_deg, double *v)
{
    const double pi = 3.14159265358979323846;
    if (!(alpha_deg >= 10.0)) alpha_deg = 10.0;
    if (alpha_deg > 350.0) alpha_deg = 350.0;
    const double h = 0.5 * alpha_deg * pi / 180.0, L = 0.4, cx = 0.5, cy = 0.6;
    v[0] = cx - L * sin(h), v[1] = cy - L * cos(h);
    v[2] = cx, v[3] = cy;
    v[4] = cx + L * sin(h), v[5] = cy - L * cos(h);
}

void dflw_two_bisector(double alpha_deg, double *dir)
{
    dir[0] = 0.0;
    dir[1] = alpha_deg > 180.0 ? -1.0 : 1.0; /* clamping to [10, 350] keeps the side */
}

static int check_codes(dflw_scene *s, int join, int trim)
{
    if (join < 0 || join >= DFL_RFUNC_JOIN_COUNT)
        return dfl_err_set(&s->err, DFL_E_INPUT, "join code %d: expected 0..%d", join,
                           DFL_RFUNC_JOIN_COUNT - 1);
    if (trim < 0 || trim >= DFL_RFUNC_TRIM_COUNT)
        return dfl_err_set(&s->err, DFL_E_INPUT, "trim code %d: expected 0..%d", trim,
                           DFL_RFUNC_TRIM_COUNT - 1);
    return DFL_OK;
}

/* trim < 0: the exact distances of dflw_scene_exact. */
static int scene_build(dflw_scene *s, const double *v, int n, int join, int p, int trim)
{
    dfl_err_clear(&s->err);
    scene_clear(s);
    dfl_status st = check_codes(s, join, trim < 0 ? 0 : trim);
    if (st) return st;
    if (n < 2) return dfl_err_set(&s->err, DFL_E_INPUT, "polyline: %d vertices, need >= 2", n);
    s->v = malloc(2 * (size_t)n * sizeof *s->v);
    if (!s->v) return dfl_err_set(&s->err, DFL_E_NOMEM, "out of memory");
    memcpy(s->v, v, 2 * (size_t)n * sizeof *v);
    if (trim < 0)
        st = dfl_rfunc_exact_polyline_field(2, v, (size_t)n, (dfl_rfunc_join)join, p, &s->f,
                                            &s->err);
    else
        st = dfl_rfield_polyline(2, v, (size_t)n, false, (dfl_rfunc_join)join, p,
                                 (dfl_rfunc_trim)trim, &s->f, &s->err);
    if (st) {
        free(s->v);
        s->v = NULL;
        return st;
    }
    s->n = n;
    return DFL_OK;
}

int dflw_scene_polyline(dflw_scene *s, const double *v, int n, int join, int p, int trim)
{
    if (trim < 0) {
        dfl_err_clear(&s->err);
        scene_clear(s);
        return dfl_err_set(&s->err, DFL_E_INPUT, "trim code %d: expected 0..%d", trim,
                           DFL_RFUNC_TRIM_COUNT - 1);
    }
    return scene_build(s, v, n, join, p, trim);
}

int dflw_scene_exact(dflw_scene *s, const double *v, int n, int join, int p)
{
    return scene_build(s, v, n, join, p, -1);
}

int dflw_scene_curve(dflw_scene *s, const double *cp, int ncp, int order, double eps, int join,
                     int p, int trim)
{
    dfl_err_clear(&s->err);
    scene_clear(s);
    dfl_bspline c = {0};
    dfl_polyline pl = {0};
    dfl_status st = dfl_bspline_init(2, order, (size_t)(ncp < 0 ? 0 : ncp), cp, NULL, 0, &c,
                                     &s->err);
    if (!st) st = dfl_polygonize_curve(&c, eps, 100000, &pl, &s->err);
    if (!st) st = dflw_scene_polyline(s, pl.pts, (int)pl.n, join, p, trim);
    if (!st) {
        s->curve = c;  /* kept for the ray measure */
        s->pl = pl;
        return DFL_OK;
    }
    dfl_polyline_free(&pl);
    dfl_bspline_free(&c);
    return st;
}

/* The steps of experiments/bs04/bs04_offsets.c's level measure, with the
 * exact distance of the B-spline itself (footpoints), as the study has it. */
int dflw_curve_bulge(dflw_scene *s, double delta, int nside, int ncap, double *out)
{
    dfl_err_clear(&s->err);
    for (int i = 0; i < 4; i++) out[i] = NAN;
    if (!s->f.ops || !s->curve.cp || s->pl.n < 2)
        return dfl_err_set(&s->err, DFL_E_INPUT, "curve bulge: the scene has no curve");
    dfl_bspline c = {0};
    dfl_shape shape;
    dfl_field exact = {0};
    dfl_rayset rs = {0};
    dfl_foot_opts fo;
    dfl_foot_opts_default(&fo);
    double *sv = NULL;
    int *valid = NULL, *branch = NULL;
    const dfl_cross_opts co = {8 * delta, 128, 6};
    dfl_status st = dfl_bspline_copy(&s->curve, &c, &s->err);
    if (!st) st = dfl_shape_param_curve(&c, &fo, 0, &shape, &s->err);
    if (!st) {
        st = dfl_field_exact_new(&shape, &exact, &s->err);
        if (st) dfl_shape_free(&shape);
    }
    if (!st)
        st = dfl_curveprobe_rays(&s->curve, (size_t)nside, (size_t)ncap, s->pl.t + 1,
                                 s->pl.n - 2, &rs, &s->err);
    if (!st) {
        sv = malloc(rs.n * sizeof *sv);
        valid = malloc(rs.n * sizeof *valid);
        branch = malloc(rs.n * sizeof *branch);
        if (!sv || !valid || !branch) st = dfl_err_set(&s->err, DFL_E_NOMEM, "out of memory");
    }
    if (!st) st = dfl_curveprobe_valid(&exact, &rs, delta, 1e-6, 1, valid, &s->err);
    if (!st) st = dfl_curveprobe_cross(&s->f, &rs, delta, &co, 1, sv, &s->err);
    if (!st) st = dfl_curveprobe_on_branch(&exact, &rs, sv, 1e-6, 1, branch, &s->err);
    if (!st) {
        dfl_ray_stats r;
        dfl_curveprobe_stats(&rs, sv, valid, branch, delta, &r);
        out[0] = r.max, out[1] = r.joint_max, out[2] = r.side_max, out[3] = r.cap_max;
    }
    free(sv), free(valid), free(branch);
    dfl_curveprobe_free(&rs);
    dfl_field_destroy(&exact);
    dfl_bspline_free(&c);
    return st;
}

int dflw_scene_nvertices(const dflw_scene *s)
{
    return s->f.ops ? s->n : 0;
}

const double *dflw_scene_vertices(const dflw_scene *s)
{
    return s->v;
}

void dflw_eval(const dflw_scene *s, int m, const double *pts, double *val, double *grad)
{
    for (int i = 0; i < m; i++) {
        double g[2] = {NAN, NAN};
        val[i] = s->f.ops ? dfl_field_eval1(&s->f, pts + 2 * i, g) : NAN;
        if (grad) grad[2 * i] = g[0], grad[2 * i + 1] = g[1];
    }
}

static double poly_dist(const dflw_scene *s, const double *x)
{
    double dm = INFINITY;
    for (int q = 0; q + 1 < s->n; q++) {
        double e = dfl_point_segment_dist(2, x, s->v + 2 * q, s->v + 2 * q + 2);
        if (e < dm) dm = e;
    }
    return dm;
}

void dflw_dist(const dflw_scene *s, int m, const double *pts, double *d)
{
    for (int i = 0; i < m; i++) d[i] = s->f.ops ? poly_dist(s, pts + 2 * i) : NAN;
}

/* Rows go through the field's batch eval (the fast path where it
 * applies), one row at a time so that the scratch stays small. */
void dflw_grid(const dflw_scene *s, int nx, int ny, double x0, double y0, double x1, double y1,
               float *u, float *d, float *gnorm)
{
    double *pts = malloc((size_t)nx * 5 * sizeof *pts);
    if (!pts) return;
    double *val = pts + 2 * (size_t)nx, *g = val + nx;
    const double hx = (x1 - x0) / nx, hy = (y1 - y0) / ny;
    for (int j = 0; j < ny; j++) {
        const double y = y1 - (j + 0.5) * hy;
        for (int i = 0; i < nx; i++) pts[2 * i] = x0 + (i + 0.5) * hx, pts[2 * i + 1] = y;
        if (s->f.ops) s->f.ops->eval(s->f.ctx, (size_t)nx, pts, val, g);
        for (int i = 0; i < nx; i++) {
            const size_t k = (size_t)j * nx + i;
            if (u) u[k] = s->f.ops ? (float)val[i] : NAN;
            if (gnorm) gnorm[k] = s->f.ops ? (float)hypot(g[2 * i], g[2 * i + 1]) : NAN;
            if (d) d[k] = (float)poly_dist(s, pts + 2 * i);
        }
    }
    free(pts);
}

static int scene_jet(dflw_scene *s, const double *x, const double *dir, int K, dfl_jet *j)
{
    dfl_err_clear(&s->err);
    if (!s->f.ops) return dfl_err_set(&s->err, DFL_E_INPUT, "no field");
    dfl_status st = dfl_jet_check_order(K, &s->err);
    if (!st) st = dfl_field_jet(&s->f, x, dir, K, j, &s->err);
    return st;
}

int dflw_jet(dflw_scene *s, const double *x, const double *dir, int K, double *d)
{
    dfl_jet j;
    dfl_status st = scene_jet(s, x, dir, K, &j);
    if (st) return st;
    for (int k = 1; k <= K; k++) d[k - 1] = dfl_jet_deriv(&j, k);
    return DFL_OK;
}

int dflw_order(dflw_scene *s, const double *x, const double *dir, int K, double L, double tol,
               int *k_first)
{
    dfl_jet j;
    dfl_normorder o;
    if (scene_jet(s, x, dir, K, &j)) return -2;
    if (dfl_normorder_measure(&j, 1.0, L, tol, &o, &s->err)) return -2;
    if (k_first) *k_first = o.k;
    return o.order;
}

int dflw_bounds(dflw_scene *s, int join, int p, int n, double *lo, double *hi)
{
    const double pi = 3.14159265358979323846;
    dfl_err_clear(&s->err);
    if (join < 0 || join >= DFL_RFUNC_JOIN_COUNT || n < 2)
        return dfl_err_set(&s->err, DFL_E_INPUT, "bounds: bad join %d or n %d", join, n);
    dfl_status st = dfl_gradbound_check((dfl_rfunc_join)join, p, &s->err);
    if (st) return st;
    for (int i = 0; i < n; i++) {
        double F1, F2, phi = i * (pi / 2) / (n - 1);
        dfl_gradbound_partials((dfl_rfunc_join)join, p, phi, &F1, &F2);
        dfl_gradbound_band(F1, F2, 1.0, 1.0, lo + i, hi + i);
    }
    return DFL_OK;
}

void dflw_ring(const dflw_scene *s, const double *c, double r, int n, double *g, double *phi)
{
    const double pi = 3.14159265358979323846;
    for (int i = 0; i < n; i++) {
        const double t = 2 * pi * i / n, x[2] = {c[0] + r * cos(t), c[1] + r * sin(t)};
        double gr[2] = {NAN, NAN};
        if (s->f.ops) dfl_field_eval1(&s->f, x, gr);
        g[i] = hypot(gr[0], gr[1]);
        if (phi) {
            phi[i] = NAN;
            if (s->f.ops && s->n == 3) {
                double h1 = dfl_point_segment_dist(2, x, s->v, s->v + 2);
                double h2 = dfl_point_segment_dist(2, x, s->v + 2, s->v + 4);
                phi[i] = atan2(h2, h1);
            }
        }
    }
}

double dflw_bulge(const dflw_scene *s, const double *v, const double *dir, double c, double tmax)
{
    if (!s->f.ops || !(c > 0)) return NAN;
    double lo = 0, hi = tmax, x[2] = {v[0] + tmax * dir[0], v[1] + tmax * dir[1]};
    if (!(dfl_field_eval1(&s->f, x, NULL) >= c)) return NAN;
    for (int it = 0; it < 200 && hi - lo > 1e-15 * tmax; it++) {
        const double t = 0.5 * (lo + hi);
        x[0] = v[0] + t * dir[0], x[1] = v[1] + t * dir[1];
        if (dfl_field_eval1(&s->f, x, NULL) < c) lo = t;
        else hi = t;
    }
    return 0.5 * (lo + hi) / c - 1.0;
}
