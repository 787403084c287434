/* bs04 Sec. 3.2.1 / Figs. 9-10: the field h of one triangle and |grad h| on
 * a small sphere around a vertex.
 *
 * bs04 states that the trim t (prism: R0-conjunction of the three edge
 * planes; conditional: eq. 15-16) is normalized except at the vertices,
 * where |grad t| "varies but remains positive and bounded depending on the
 * direction", and that |grad h| near a vertex "depends on the direction of
 * approach but remains bounded in a relatively tight range" (Fig. 10b).
 * The study measures min/max/mean of |grad h| (and |grad t|) over
 * `samples` points of the sphere of radius r around the vertex, and over
 * the exterior arc of its great circle in the triangle's plane.
 *
 * Closed form for the plane (derived here; limit r -> 0).  In the frame
 * e1 = (B - A)/|B - A|, e2 in the plane towards C, with interior angle
 * alpha at A, a point A + r (cos th, sin th) has edge-plane values
 * p1 = r sin th and p2 = r sin(alpha - th) (inward unit normals m1 = e2,
 * m2 = (sin alpha, -cos alpha), m1 . m2 = -cos alpha); the third plane is
 * at distance ~ height > 0, and x ^ y with y >> |x| has dx = 1 - O(r),
 * dy = O(r^2), so t -> p1 ^ p2 = p1 + p2 - rho, rho = sqrt(p1^2 + p2^2),
 * with grad t = a m1 + b m2, a = 1 - p1/rho, b = 1 - p2/rho:
 *     |grad t|^2 = a^2 + b^2 - 2 a b cos(alpha).
 * On the plane outside the triangle h = max(-t, 0) = -t (eq. 4), so
 * |grad h| = |grad t|.  Off the plane, for the prism trim (t independent of
 * the normal coordinate f, grad t . n = 0):
 *     |grad h|^2 = (f^2 + m^2 |grad t|^2) / (f^2 + m^2),  m = max(-t, 0),
 * a weighted mean of 1 and |grad t|^2: over the whole sphere |grad h| lies
 * in [min(1, min |grad t|), max(1, max |grad t|)] with the extremes on the
 * plane.  The conditional trim adds a f^k under the root of eq. 15, which
 * for k = 2 is of the same order r^2 as p_i^2 near the vertex: no closed
 * form; it is measured.
 *
 * Keys.  [field] kind = rfunc (rfunc_cfg.h; the field of Fig. 9-10, so
 * `dflab probe` evaluates it) with one triangle:
 *   triangles = x y z; x y z; x y z  vertices A, B, C
 *   tri_trim = conditional | prism   trim volume (tri3d.h); a = 0.2, k = 2
 *                                    (eq. 15-16), smooth = false (eq. 4)
 *   join, p                          (one part: u = h for every join)
 * [study]:
 *   vertices = 0 1 2                 vertices (0, 1, 2) the spheres are around
 *                                    (default all three)
 *   radii    = 1e-2 1e-3             sphere radii (> 0; up to 8; default 1e-2)
 *   samples  = 4000                  Fibonacci points on the sphere (>= 10)
 *   theory_samples = 100000          angles for the closed form
 *   slices, slice_n, slice_lo, slice_hi   section planes of h (Fig. 9c)
 *   compress = true                  [output] see field_out.h
 * Rows (one per vertex and radius): vertex, tri_trim, radius, alpha_deg, grad_min/mean/max (sphere),
 * tgrad_min/max (|grad t| on the sphere), plane_grad_min/max (exterior
 * arc of the in-plane circle), theory_plane_min/max (closed form above),
 * theory_sphere_min/max (prism only: min(1, .), max(1, .)), argmin/argmax
 * directions (unit vectors from the vertex), files.
 * Files: sphere_v<vertex>_r<radius index><tag>.vtp (the sphere samples with
 * point data grad_norm),
 * triangle_slice<k><tag>.vti/.exr.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bs04/bs04_space_util.h"
#include "core/vec.h"
#include "cfg/list_cfg.h"
#include "cfg/rfunc_cfg.h"
#include "harness/experiment.h"
#include "field/field.h"
#include "rfunc/rfield.h"
#include "rfunc/tri3d.h"
#include "cfg/slice_cfg.h"
#include "harness/field_out.h"
#include "cfg/field_cost.h"

#define MAX_RADII 8

typedef struct keys {
    dfl_rfunc_field_spec spec; /* [field] (owned) */
    double v[9];
    int vertices[3], nvert;
    dfl_rfunc_tri_opts o;
    double radii[MAX_RADII];
    int nradii;
    long samples, theory_samples;
    dfl_bs04_space_out so;
} keys;

static dfl_status read_keys(const dfl_cfg *cfg, keys *k, dfl_err *err)
{
    dfl_status st;
    memset(k, 0, sizeof *k);
    if ((st = dfl_rfunc_spec_from_kind_cfg(cfg, "field", "bs04_triangle", &k->spec, err)))
        return st;
    if (k->spec.ntris != 1 || k->spec.surface || k->spec.n || k->spec.npoints)
        return dfl_err_set(err, DFL_E_INPUT,
                           "%s: [field] of bs04_triangle: expected one triangle (triangles = 3"
                           " vertices), nothing else",
                           dfl_cfg_path(cfg));
    memcpy(k->v, k->spec.tris, sizeof k->v);
    k->o = k->spec.tri;
    double *list = NULL;
    size_t nl = 0;
    if (!dfl_cfg_has(cfg, "study", "vertices")) {
        k->nvert = 3;
        for (int i = 0; i < 3; i++) k->vertices[i] = i;
    } else if ((st = dfl_cfg_doubles(cfg, "study", "vertices", 1, &list, &nl, err))) {
        return st;
    }
    for (size_t i = 0; i < nl; i++) {
        const int vi = (int)list[i];
        if (nl > 3 || (double)vi != list[i] || vi < 0 || vi > 2) {
            free(list);
            return dfl_cfg_reject(cfg, "study", "vertices", err,
                                  "expected up to 3 vertex indices 0, 1, 2");
        }
        k->vertices[k->nvert++] = vi;
    }
    free(list);
    dfl_rfunc_tri tri;
    if ((st = dfl_rfunc_tri_init(k->v, k->v + 3, k->v + 6, &k->o, &tri, err))) {
        dfl_cfg_err_at(cfg, "field", "triangles", st, err);
        return st;
    }
    nl = 0;
    if (!dfl_cfg_has(cfg, "study", "radii")) {
        k->nradii = 1;
        k->radii[0] = 1e-2;
    } else if ((st = dfl_cfg_doubles(cfg, "study", "radii", 1, &list, &nl, err))) {
        return st;
    }
    for (size_t i = 0; i < nl; i++) {
        if (nl > MAX_RADII || !(list[i] > 0.0)) {
            free(list);
            return dfl_cfg_reject(cfg, "study", "radii", err, "expected up to %d radii > 0",
                                  MAX_RADII);
        }
        k->radii[k->nradii++] = list[i];
    }
    free(list);
    if ((st = dfl_cfg_int_opt(cfg, "study", "samples", 4000, 10, 10000000, &k->samples, err)))
        return st;
    if ((st = dfl_cfg_int_opt(cfg, "study", "theory_samples", 100000, 100, 100000000,
                              &k->theory_samples, err)))
        return st;
    return dfl_bs04_space_out_from_cfg(cfg, true, &k->so, err);
}

static void sub3(const double *a, const double *b, double *c)
{
    for (int j = 0; j < 3; j++) c[j] = a[j] - b[j];
}
static void unit3(double *a)
{
    const double n = dfl_vec3_norm(a);
    for (int j = 0; j < 3; j++) a[j] /= n;
}

/* The closed-form |grad t| of the limit r -> 0 at angle th (see the top). */
static double plane_theory(double alpha, double th)
{
    const double p1 = sin(th), p2 = sin(alpha - th), rho = hypot(p1, p2);
    const double a = 1.0 - p1 / rho, b = 1.0 - p2 / rho;
    return sqrt(fmax(0.0, a * a + b * b - 2.0 * a * b * cos(alpha)));
}

/* Vertex frame: A, e1, e2 (in plane, towards C), n; interior angle. */
typedef struct frame {
    double A[3], e1[3], e2[3], n[3], alpha;
} frame;

static frame vertex_frame(const double *v, int vi)
{
    frame f;
    const double *A = v + 3 * vi, *B = v + 3 * ((vi + 1) % 3), *C = v + 3 * ((vi + 2) % 3);
    double ac[3];
    memcpy(f.A, A, sizeof f.A);
    sub3(B, A, f.e1);
    unit3(f.e1);
    sub3(C, A, ac);
    const double c = dfl_vec3_dot(ac, f.e1);
    for (int j = 0; j < 3; j++) f.e2[j] = ac[j] - c * f.e1[j];
    unit3(f.e2);
    dfl_vec3_cross(f.e1, f.e2, f.n);
    f.alpha = atan2(dfl_vec3_dot(ac, f.e2), c);
    return f;
}

/* One row: |grad h| on the sphere of radius r around vertex vi. */
static dfl_status do_sphere(const keys *k, const dfl_rfunc_tri *tri, int vi, int ri,
                            const dfl_study_ctx *ctx, dfl_table *table, dfl_err *err)
{
    const frame fr = vertex_frame(k->v, vi);
    const double r = k->radii[ri];
    const size_t N = (size_t)k->samples;
    char path[4400], stem[64];
    dfl_status st = DFL_OK;
    double *sph = malloc(3 * N * sizeof *sph), *gn = malloc(N * sizeof *gn);
    if (!sph || !gn) {
        st = dfl_err_set(err, DFL_E_NOMEM, "out of memory");
        goto done;
    }
    /* sphere: Fibonacci points (uniform in area) */
    const double golden = DFL_PI * (3.0 - sqrt(5.0));
    double gmin = INFINITY, gmax = -INFINITY, gsum = 0, tmin = INFINITY, tmax = -INFINITY;
    double dmin[3] = {0, 0, 0}, dmax[3] = {0, 0, 0};
    size_t cnt = 0;
    for (size_t i = 0; i < N; i++) {
        const double z = 1.0 - (2.0 * (double)i + 1.0) / (double)N, rr = sqrt(1.0 - z * z);
        const double ph = golden * (double)i;
        const double d[3] = {rr * cos(ph), rr * sin(ph), z};
        double *x = sph + 3 * i, g[3], gt[3];
        for (int j = 0; j < 3; j++) x[j] = fr.A[j] + r * d[j];
        const double h = dfl_rfunc_tri_eval(tri, x, g);
        (void)dfl_rfunc_tri_trim_eval(tri, x, gt);
        gn[i] = sqrt(dfl_vec3_dot(g, g));
        const double tn = sqrt(dfl_vec3_dot(gt, gt));
        tmin = fmin(tmin, tn);
        tmax = fmax(tmax, tn);
        if (!(h > 0.0)) continue; /* on the triangle: no gradient */
        if (gn[i] < gmin) gmin = gn[i], memcpy(dmin, d, sizeof d);
        if (gn[i] > gmax) gmax = gn[i], memcpy(dmax, d, sizeof d);
        gsum += gn[i];
        cnt++;
    }
    /* the exterior arc of the in-plane circle, and the closed form */
    double pmin = INFINITY, pmax = -INFINITY, qmin = INFINITY, qmax = -INFINITY;
    for (size_t i = 0; i < N; i++) {
        const double th = fr.alpha + (2 * DFL_PI - fr.alpha) * ((double)i + 0.5) / (double)N;
        double x[3], g[3];
        for (int j = 0; j < 3; j++) x[j] = fr.A[j] + r * (cos(th) * fr.e1[j] + sin(th) * fr.e2[j]);
        (void)dfl_rfunc_tri_eval(tri, x, g);
        const double q = sqrt(dfl_vec3_dot(g, g));
        pmin = fmin(pmin, q);
        pmax = fmax(pmax, q);
    }
    for (long i = 0; i < k->theory_samples; i++) {
        const double th =
            fr.alpha + (2 * DFL_PI - fr.alpha) * ((double)i + 0.5) / (double)k->theory_samples;
        const double q = plane_theory(fr.alpha, th);
        qmin = fmin(qmin, q);
        qmax = fmax(qmax, q);
    }

    st = dfl_table_row(table, err);
    if (!st) st = dfl_table_set_int(table, "vertex", vi, err);
    if (!st)
        st = dfl_table_set_string(table, "tri_trim",
                                  dfl_rfunc_tri_trim_name(k->o.trim), err);
    if (!st) st = dfl_table_set_double(table, "radius", r, err);
    if (!st) st = dfl_table_set_double(table, "alpha_deg", fr.alpha * 180.0 / DFL_PI, err);
    if (!st) st = dfl_table_set_int(table, "samples", (long)cnt, err);
    if (!st) st = dfl_table_set_double(table, "grad_min", gmin, err);
    if (!st) st = dfl_table_set_double(table, "grad_mean", gsum / (double)cnt, err);
    if (!st) st = dfl_table_set_double(table, "grad_max", gmax, err);
    if (!st) st = dfl_table_set_double(table, "tgrad_min", tmin, err);
    if (!st) st = dfl_table_set_double(table, "tgrad_max", tmax, err);
    if (!st) st = dfl_table_set_double(table, "plane_grad_min", pmin, err);
    if (!st) st = dfl_table_set_double(table, "plane_grad_max", pmax, err);
    if (!st) st = dfl_table_set_double(table, "theory_plane_min", qmin, err);
    if (!st) st = dfl_table_set_double(table, "theory_plane_max", qmax, err);
    if (!st && k->o.trim == DFL_RFUNC_TRI_PRISM) {
        st = dfl_table_set_double(table, "theory_sphere_min", fmin(1.0, qmin), err);
        if (!st) st = dfl_table_set_double(table, "theory_sphere_max", fmax(1.0, qmax), err);
    }
    /* directions in the vertex frame (e1, e2, n) */
    const char *cols[6] = {"argmin_e1", "argmin_e2", "argmin_n",
                           "argmax_e1", "argmax_e2", "argmax_n"};
    const double vals[6] = {dfl_vec3_dot(dmin, fr.e1), dfl_vec3_dot(dmin, fr.e2),
                            dfl_vec3_dot(dmin, fr.n),  dfl_vec3_dot(dmax, fr.e1),
                            dfl_vec3_dot(dmax, fr.e2), dfl_vec3_dot(dmax, fr.n)};
    for (int c = 0; c < 6 && !st; c++) st = dfl_table_set_double(table, cols[c], vals[c], err);
    snprintf(stem, sizeof stem, "sphere_v%d_r%d", vi, ri);
    if (!st)
        st = dfl_bs04_vtp_points(dfl_study_path(ctx, stem, "vtp", path, sizeof path), N, sph,
                                 "grad_norm", gn, k->so.compress, err);
    if (!st) st = dfl_study_put_file(table, "sphere_vtp", ctx, stem, "vtp", true, err);
done:
    free(sph);
    free(gn);
    return st;
}

static dfl_status tri_run(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_table *table,
                          dfl_err *err)
{
    keys k;
    dfl_field fld = {0};
    dfl_status st = read_keys(cfg, &k, err);
    if (st == DFL_OK) st = dfl_rfunc_field_from_spec(cfg, "field", &k.spec, &fld, err);
    if (st == DFL_OK) st = dfl_cfg_check_used(cfg, err);
    if (st != DFL_OK) goto done;
    dfl_rfunc_tri tri;
    if ((st = dfl_rfunc_tri_init(k.v, k.v + 3, k.v + 6, &k.o, &tri, err))) return st;
    for (int a = 0; a < k.nvert && !st; a++)
        for (int b = 0; b < k.nradii && !st; b++)
            st = do_sphere(&k, &tri, k.vertices[a], b, ctx, table, err);
    if (st) goto done;

    /* section planes of the triangle's field ([field]) */
    st = dfl_bs04_write_slices(ctx, &fld, &k.so, "triangle_slice", err);
done:
    dfl_field_destroy(&fld);
    dfl_rfunc_spec_free(&k.spec);
    return st;
}

/* Peak memory: one sphere at a time: its samples (point and |grad h|: 32
 * bytes) and the .vtp writer's connectivity, offsets and zlib copies (96
 * more), 128 bytes a sample; or one slice (dfl_bs04_slices_cost).  Work:
 * per vertex and radius 3 triangle evaluations a sample (h and t on the
 * sphere, h on the arc; 1 + DFL_RFUNC_EVAL_UNITS CHEAP each) and
 * theory_samples closed forms (CHEAP); one evaluation per slice node. */
static dfl_status tri_estimate(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_cost *c,
                               dfl_err *err)
{
    (void)ctx;
    keys k;
    dfl_status st = read_keys(cfg, &k, err);
    if (!st) {
        const double spheres = (double)k.nvert * k.nradii;
        dfl_cost_add_bytes(c, "study", "samples", 128.0 * (double)k.samples,
                           "a sphere of %ld samples", k.samples);
        dfl_cost_add_work(c, "study", "samples", DFL_COST_CHEAP,
                          3 * (1 + DFL_RFUNC_EVAL_UNITS) * spheres * (double)k.samples,
                          "%.3g spheres of %ld samples", spheres, k.samples);
        dfl_cost_add_work(c, "study", "theory_samples", DFL_COST_CHEAP,
                          spheres * (double)k.theory_samples, "%.3g x %ld closed forms", spheres,
                          k.theory_samples);
        dfl_cost one;
        memset(&one, 0, sizeof one);
        dfl_bs04_slices_cost(&k.so, DFL_COST_CHEAP, 1 + DFL_RFUNC_EVAL_UNITS, DFL_COST_CHEAP, 0, 0,
                             &one);
        dfl_cost_add_step(c, &one);
    }
    dfl_rfunc_spec_free(&k.spec);
    return st;
}

DFL_STUDY_DEFINE_ESTIMATED(bs04_triangle, tri_run, tri_estimate,
                 "bs04 Figs. 9-10: one triangle's field, |grad h| on a small sphere at a vertex");
