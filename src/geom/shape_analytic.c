/* The analytic kinds: circle, sphere, torus, cylinder, plane, box,
 * segment and capped cone, each an exact SDF with exact jets. */
#include "geom/shape_impl.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geom/segdist.h"

/* ---- circle / sphere ----------------------------------------------------- */

typedef struct ball {
    int dim;
    double c[3];
    double r;
} ball;

/* |u| for n <= 3 components: the plain sqrt of the square sum where that
 * sum cannot overflow or underflow (the same bits as before), else scaled
 * by the largest component, so that coordinates up to DFL_COORD_MAX
 * (core/domain.h) give a finite, correctly rounded-to-a-few-ulp length. */
static double ball_len(int n, const double *u)
{
    const double s = dfl_vecn_dot(n, u, u);
    if (s > 1e-290 && s < 1e290) return sqrt(s);
    double m = 0.0;
    for (int j = 0; j < n; j++) m = fmax(m, fabs(u[j]));
    if (m == 0.0 || !isfinite(m)) return m;
    double t = 0.0;
    for (int j = 0; j < n; j++) t += (u[j] / m) * (u[j] / m);
    return m * sqrt(t);
}

static void ball_eval(const void *impl, size_t m, const double *pts, double *val, double *grad)
{
    const ball *b = impl;
    const int n = b->dim;
    for (size_t i = 0; i < m; i++) {
        const double *x = pts + i * (size_t)n;
        double u[3] = {0, 0, 0};
        for (int j = 0; j < n; j++) u[j] = x[j] - b->c[j];
        double len = ball_len(n, u);
        val[i] = len - b->r;
        if (grad) {
            double *g = grad + i * (size_t)n;
            if (len > 0.0) {
                for (int j = 0; j < n; j++) g[j] = u[j] / len;
            } else {
                /* centre: every unit vector is a one-sided gradient; pick e1 */
                for (int j = 0; j < n; j++) g[j] = (j == 0) ? 1.0 : 0.0;
            }
        }
    }
}

static dfl_status ball_jet(const void *impl, const double *x, const double *dir, int K,
                           dfl_jet *out, dfl_err *err)
{
    const ball *b = impl;
    const int n = b->dim;
    double u[3] = {0, 0, 0};
    for (int j = 0; j < n; j++) u[j] = x[j] - b->c[j];
    dfl_status st = jet_norm_line(n, u, dir, K, out, err);
    if (st != DFL_OK) return st;
    dfl_jet_add_const(out, -b->r, out);
    return DFL_OK;
}

/* Hess |q| = (I - u u^T) / |q|, u = q / |q| (0 at the centre). */
static void sphere_hess(const void *impl, const double *x, double *H)
{
    const ball *b = impl;
    double u[3] = {x[0] - b->c[0], x[1] - b->c[1], x[2] - b->c[2]};
    double l = sqrt(dfl_vec3_dot(u, u));
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            H[3 * i + j] = l > 0.0 ? ((i == j) - u[i] * u[j] / (l * l)) / l : 0.0;
}

static const dfl_shape_ops circle_ops = {"circle", ball_eval, ball_jet, free, NULL};
static const dfl_shape_ops sphere_ops = {"sphere", ball_eval, ball_jet, free, NULL};

static dfl_status make_ball(int dim, const double *c, double r, dfl_shape *out, dfl_err *err)
{
    const char *name = dim == 2 ? "circle" : "sphere";
    if (!finite_vec(dim, c)) return dfl_err_set(err, DFL_E_INPUT, "%s: centre not finite", name);
    if (!(r > 0.0) || !isfinite(r))
        return dfl_err_set(err, DFL_E_INPUT, "%s: radius must be > 0, got %g", name, r);
    ball *b = calloc(1, sizeof *b);
    if (!b) return dfl_err_set(err, DFL_E_NOMEM, "%s: out of memory", name);
    b->dim = dim;
    memcpy(b->c, c, (size_t)dim * sizeof *c);
    b->r = r;
    return shape_set(dim, dim == 2 ? &circle_ops : &sphere_ops, b, out);
}

dfl_status dfl_shape_circle(const double c[2], double r, dfl_shape *out, dfl_err *err)
{
    return make_ball(2, c, r, out, err);
}

dfl_status dfl_shape_sphere(const double c[3], double r, dfl_shape *out, dfl_err *err)
{
    return make_ball(3, c, r, out, err);
}

/* ---- torus / cylinder ---------------------------------------------------- */

typedef struct axial {
    double c[3], w[3], u[3];   /* point on axis, unit axis, fallback radial dir */
    double R, r;               /* torus: major, minor; cylinder: R = 0, r = radius */
} axial;

static void torus_eval(const void *impl, size_t m, const double *pts, double *val, double *grad)
{
    const axial *t = impl;
    for (size_t i = 0; i < m; i++) {
        const double *x = pts + 3 * i;
        double p[3] = {x[0] - t->c[0], x[1] - t->c[1], x[2] - t->c[2]}, pp[3];
        double z = split_axis(p, t->w, pp);
        double rho = sqrt(dfl_vecn_dot(3, pp, pp));
        double e[3];
        for (int j = 0; j < 3; j++) e[j] = rho > 0.0 ? pp[j] / rho : t->u[j];
        double a = rho - t->R;
        double q = sqrt(a * a + z * z);
        val[i] = q - t->r;
        if (grad) {
            double *g = grad + 3 * i;
            if (q > 0.0) {
                for (int j = 0; j < 3; j++) g[j] = (a * e[j] + z * t->w[j]) / q;
            } else {
                for (int j = 0; j < 3; j++) g[j] = e[j];
            }
        }
    }
}

/* rho(s) = |perp part of p + s dir| as a jet. */
static dfl_status rho_jet(const axial *t, const double *x, const double *dir, int K, dfl_jet *rho,
                          double *z0, double *z1, dfl_err *err)
{
    double p[3] = {x[0] - t->c[0], x[1] - t->c[1], x[2] - t->c[2]}, pp[3], dp[3];
    *z0 = split_axis(p, t->w, pp);
    *z1 = split_axis(dir, t->w, dp);
    return jet_norm_line(3, pp, dp, K, rho, err);
}

static dfl_status torus_jet(const void *impl, const double *x, const double *dir, int K,
                            dfl_jet *out, dfl_err *err)
{
    const axial *t = impl;
    dfl_jet rho, zj, q;
    double z0, z1;
    dfl_status st = rho_jet(t, x, dir, K, &rho, &z0, &z1, err);
    if (st != DFL_OK) return st;
    dfl_jet_add_const(&rho, -t->R, &rho);
    dfl_jet_mul(&rho, &rho, &q);
    dfl_jet_linear(z0, z1, K, &zj);
    dfl_jet_mul(&zj, &zj, &zj);
    dfl_jet_add(&q, &zj, &q);
    if ((st = dfl_jet_sqrt(&q, out, err)) != DFL_OK) return st;
    dfl_jet_add_const(out, -t->r, out);
    return DFL_OK;
}

static void cylinder_eval(const void *impl, size_t m, const double *pts, double *val,
                          double *grad)
{
    const axial *t = impl;
    for (size_t i = 0; i < m; i++) {
        const double *x = pts + 3 * i;
        double p[3] = {x[0] - t->c[0], x[1] - t->c[1], x[2] - t->c[2]}, pp[3];
        split_axis(p, t->w, pp);
        double rho = sqrt(dfl_vecn_dot(3, pp, pp));
        val[i] = rho - t->r;
        if (grad)
            for (int j = 0; j < 3; j++) grad[3 * i + j] = rho > 0.0 ? pp[j] / rho : t->u[j];
    }
}

static dfl_status cylinder_jet(const void *impl, const double *x, const double *dir, int K,
                               dfl_jet *out, dfl_err *err)
{
    const axial *t = impl;
    double z0, z1;
    dfl_status st = rho_jet(t, x, dir, K, out, &z0, &z1, err);
    if (st != DFL_OK) return st;
    dfl_jet_add_const(out, -t->r, out);
    return DFL_OK;
}

/* Torus: with e the radial unit vector, phi = w x e, a = rho - R and
 * q = |(a, z)|, the gradient (a e + z w)/q turns at rate 1/q along the tube
 * direction t = (-z e + a w)/q and at rate (a/q)/rho along phi:
 * H = t t^T / q + a / (q rho) phi phi^T (0 where q or rho vanish).
 * Cylinder (R = 0, the a/q factor is 1): H = phi phi^T / rho. */
static void axial_hess(const axial *t, const double *x, int torus, double *H)
{
    double p[3] = {x[0] - t->c[0], x[1] - t->c[1], x[2] - t->c[2]}, pp[3], e[3], ph[3], tt[3];
    double z = split_axis(p, t->w, pp);
    double rho = sqrt(dfl_vecn_dot(3, pp, pp));
    for (int j = 0; j < 3; j++) e[j] = rho > 0.0 ? pp[j] / rho : t->u[j];
    dfl_vec3_cross(t->w, e, ph);
    double a = rho - t->R, q = torus ? sqrt(a * a + z * z) : rho;
    double cph = rho > 0.0 && q > 0.0 ? (torus ? a / q : 1.0) / rho : 0.0;
    double ct = torus && q > 0.0 ? 1.0 / q : 0.0;
    for (int j = 0; j < 3; j++) tt[j] = q > 0.0 ? (-z * e[j] + a * t->w[j]) / q : 0.0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) H[3 * i + j] = ct * tt[i] * tt[j] + cph * ph[i] * ph[j];
}

static void torus_hess(const void *impl, const double *x, double *H) { axial_hess(impl, x, 1, H); }
static void cylinder_hess(const void *impl, const double *x, double *H)
{
    axial_hess(impl, x, 0, H);
}

static const dfl_shape_ops torus_ops = {"torus", torus_eval, torus_jet, free, NULL};
static const dfl_shape_ops cylinder_ops = {"cylinder", cylinder_eval, cylinder_jet, free, NULL};

static dfl_status make_axial(const char *name, const double c[3], const double axis[3], double R,
                             double r, const dfl_shape_ops *ops, dfl_shape *out, dfl_err *err)
{
    double w[3];
    if (!finite_vec(3, c)) return dfl_err_set(err, DFL_E_INPUT, "%s: centre not finite", name);
    dfl_status st = unit_axis(name, "axis", axis, 3, w, err);
    if (st != DFL_OK) return st;
    axial *t = calloc(1, sizeof *t);
    if (!t) return dfl_err_set(err, DFL_E_NOMEM, "%s: out of memory", name);
    memcpy(t->c, c, sizeof t->c);
    memcpy(t->w, w, sizeof t->w);
    double v[3];
    dfl_vec3_tangent_basis(w, t->u, v);
    t->R = R;
    t->r = r;
    return shape_set(3, ops, t, out);
}

dfl_status dfl_shape_torus(const double c[3], const double axis[3], double major, double minor,
                           dfl_shape *out, dfl_err *err)
{
    if (!(major > 0.0) || !isfinite(major))
        return dfl_err_set(err, DFL_E_INPUT, "torus: major radius must be > 0, got %g", major);
    if (!(minor > 0.0) || !(minor < major))
        return dfl_err_set(err, DFL_E_INPUT,
                           "torus: minor radius must be in (0, major = %g), got %g", major, minor);
    return make_axial("torus", c, axis, major, minor, &torus_ops, out, err);
}

dfl_status dfl_shape_cylinder(const double p[3], const double axis[3], double r, dfl_shape *out,
                              dfl_err *err)
{
    if (!(r > 0.0) || !isfinite(r))
        return dfl_err_set(err, DFL_E_INPUT, "cylinder: radius must be > 0, got %g", r);
    return make_axial("cylinder", p, axis, 0.0, r, &cylinder_ops, out, err);
}

/* ---- plane --------------------------------------------------------------- */

typedef struct plane {
    int dim;
    double p[3], n[3];   /* n unit */
} plane;

static void plane_eval(const void *impl, size_t m, const double *pts, double *val, double *grad)
{
    const plane *pl = impl;
    const int n = pl->dim;
    for (size_t i = 0; i < m; i++) {
        const double *x = pts + i * (size_t)n;
        double d = 0.0;
        for (int j = 0; j < n; j++) d += (x[j] - pl->p[j]) * pl->n[j];
        val[i] = d;
        if (grad)
            for (int j = 0; j < n; j++) grad[i * (size_t)n + j] = pl->n[j];
    }
}

static dfl_status plane_jet(const void *impl, const double *x, const double *dir, int K,
                            dfl_jet *out, dfl_err *err)
{
    (void)err;
    const plane *pl = impl;
    double d = 0.0;
    for (int j = 0; j < pl->dim; j++) d += (x[j] - pl->p[j]) * pl->n[j];
    dfl_jet_linear(d, dfl_vecn_dot(pl->dim, dir, pl->n), K, out);
    return DFL_OK;
}

static void plane_hess(const void *impl, const double *x, double *H)
{
    (void)impl;
    (void)x;
    for (int j = 0; j < 9; j++) H[j] = 0.0;
}

static const dfl_shape_ops plane_ops = {"plane", plane_eval, plane_jet, free, NULL};

dfl_status dfl_shape_plane(int dim, const double *p, const double *n, dfl_shape *out,
                           dfl_err *err)
{
    if (dim != 2 && dim != 3)
        return dfl_err_set(err, DFL_E_INPUT, "plane: dim must be 2 or 3, got %d", dim);
    if (!finite_vec(dim, p)) return dfl_err_set(err, DFL_E_INPUT, "plane: point not finite");
    double w[3] = {0, 0, 0};
    dfl_status st = unit_axis("plane", "normal", n, dim, w, err);
    if (st != DFL_OK) return st;
    plane *pl = calloc(1, sizeof *pl);
    if (!pl) return dfl_err_set(err, DFL_E_NOMEM, "plane: out of memory");
    pl->dim = dim;
    memcpy(pl->p, p, (size_t)dim * sizeof *p);
    memcpy(pl->n, w, sizeof pl->n);
    return shape_set(dim, &plane_ops, pl, out);
}

/* ---- box ----------------------------------------------------------------- */

typedef struct box {
    int dim;
    double c[3], h[3];
} box;

static void box_eval(const void *impl, size_t m, const double *pts, double *val, double *grad)
{
    const box *b = impl;
    const int n = b->dim;
    for (size_t i = 0; i < m; i++) {
        const double *x = pts + i * (size_t)n;
        double q[3], sg[3], out2 = 0.0, qmax = -HUGE_VAL;
        int jmax = 0;
        for (int j = 0; j < n; j++) {
            double u = x[j] - b->c[j];
            sg[j] = u < 0.0 ? -1.0 : 1.0;
            q[j] = fabs(u) - b->h[j];
            if (q[j] > 0.0) out2 += q[j] * q[j];
            if (q[j] > qmax) { qmax = q[j]; jmax = j; }
        }
        double d = qmax > 0.0 ? sqrt(out2) : qmax;
        val[i] = d;
        if (grad) {
            double *g = grad + i * (size_t)n;
            for (int j = 0; j < n; j++) {
                if (qmax > 0.0)
                    g[j] = q[j] > 0.0 ? sg[j] * q[j] / d : 0.0;
                else
                    g[j] = j == jmax ? sg[j] : 0.0;
            }
        }
    }
}

/* Inside (every q_j <= 0 at 0+): d is the largest q_j, linear.  Outside:
 * d = |positive part of q|; with one positive q_j that is q_j itself, kept
 * linear so a point on a face has no sqrt of rounding residue. */
static dfl_status box_jet(const void *impl, const double *x, const double *dir, int K,
                          dfl_jet *out, dfl_err *err)
{
    const box *b = impl;
    const int n = b->dim;
    double q0[3], q1[3];
    int npos = 0, jpos = -1, jmax = 0;
    for (int j = 0; j < n; j++) {
        double u0 = x[j] - b->c[j], u1 = dir[j];
        double sg = lin_sign(u0, u1) < 0 ? -1.0 : 1.0;
        q0[j] = sg * u0 - b->h[j];
        q1[j] = sg * u1;
        if (lin_sign(q0[j], q1[j]) > 0) { npos++; jpos = j; }
        if (q0[j] > q0[jmax] || (q0[j] == q0[jmax] && q1[j] > q1[jmax])) jmax = j;
    }
    if (npos == 0) {
        dfl_jet_linear(q0[jmax], q1[jmax], K, out);
        return DFL_OK;
    }
    if (npos == 1) {
        dfl_jet_linear(q0[jpos], q1[jpos], K, out);
        return DFL_OK;
    }
    double a0 = 0.0, a1 = 0.0, a2 = 0.0;
    for (int j = 0; j < n; j++) {
        if (lin_sign(q0[j], q1[j]) <= 0) continue;
        a0 += q0[j] * q0[j];
        a1 += 2.0 * q0[j] * q1[j];
        a2 += q1[j] * q1[j];
    }
    return jet_sqrt_quad(a0, a1, a2, K, out, err);
}

static const dfl_shape_ops box_ops = {"box", box_eval, box_jet, free, NULL};

dfl_status dfl_shape_box(int dim, const double *c, const double *h, dfl_shape *out,
                         dfl_err *err)
{
    if (dim != 2 && dim != 3)
        return dfl_err_set(err, DFL_E_INPUT, "box: dim must be 2 or 3, got %d", dim);
    if (!finite_vec(dim, c)) return dfl_err_set(err, DFL_E_INPUT, "box: centre not finite");
    for (int j = 0; j < dim; j++)
        if (!(h[j] > 0.0) || !isfinite(h[j]))
            return dfl_err_set(err, DFL_E_INPUT, "box: half size %d must be > 0, got %g", j,
                               h[j]);
    box *b = calloc(1, sizeof *b);
    if (!b) return dfl_err_set(err, DFL_E_NOMEM, "box: out of memory");
    b->dim = dim;
    memcpy(b->c, c, (size_t)dim * sizeof *c);
    memcpy(b->h, h, (size_t)dim * sizeof *h);
    return shape_set(dim, &box_ops, b, out);
}

/* ---- segment (unsigned) -------------------------------------------------- */

typedef struct segment {
    int dim;
    double a[3], e[3], ee;   /* e = b - a, ee = |e|^2 */
    double nrm[3];           /* unit normal used as gradient on the segment */
} segment;

static void segment_eval(const void *impl, size_t m, const double *pts, double *val,
                         double *grad)
{
    const segment *sg = impl;
    const int n = sg->dim;
    for (size_t i = 0; i < m; i++) {
        const double *x = pts + i * (size_t)n;
        double u[3];
        double d = dfl_segdist_residual(n, sg->a, sg->e, sg->ee, x, u);
        val[i] = d;
        if (grad)
            for (int j = 0; j < n; j++) grad[i * (size_t)n + j] = d > 0.0 ? u[j] / d : sg->nrm[j];
    }
}

static dfl_status segment_jet(const void *impl, const double *x, const double *dir, int K,
                              dfl_jet *out, dfl_err *err)
{
    const segment *sg = impl;
    const int n = sg->dim;
    double u[3] = {0, 0, 0};
    for (int j = 0; j < n; j++) u[j] = x[j] - sg->a[j];
    double t0 = dfl_vecn_dot(n, u, sg->e) / sg->ee, t1 = dfl_vecn_dot(n, dir, sg->e) / sg->ee;
    if (lin_sign(t0, t1) < 0) {
        t0 = 0.0;
        t1 = 0.0;
    } else if (lin_sign(t0 - 1.0, t1) > 0) {
        t0 = 1.0;
        t1 = 0.0;
    }
    double w0[3] = {0, 0, 0}, w1[3] = {0, 0, 0};
    for (int j = 0; j < n; j++) {
        w0[j] = u[j] - t0 * sg->e[j];
        w1[j] = dir[j] - t1 * sg->e[j];
    }
    /* A point on the segment up to rounding is on it: the distance has a
     * kink there, and only an exactly zero offset gives the jet module the
     * valuation that makes the one-sided jet |w1| s exact. */
    if (dfl_vecn_dot(n, w0, w0) <= 1e-28 * (dfl_vecn_dot(n, u, u) + sg->ee))
        for (int j = 0; j < n; j++) w0[j] = 0.0;
    return jet_norm_line(n, w0, w1, K, out, err);
}

static const dfl_shape_ops segment_ops = {"segment", segment_eval, segment_jet, free, NULL};

dfl_status dfl_shape_segment(int dim, const double *a, const double *b, dfl_shape *out,
                             dfl_err *err)
{
    if (dim != 2 && dim != 3)
        return dfl_err_set(err, DFL_E_INPUT, "segment: dim must be 2 or 3, got %d", dim);
    if (!finite_vec(dim, a) || !finite_vec(dim, b))
        return dfl_err_set(err, DFL_E_INPUT, "segment: end point not finite");
    segment *sg = calloc(1, sizeof *sg);
    if (!sg) return dfl_err_set(err, DFL_E_NOMEM, "segment: out of memory");
    sg->dim = dim;
    memcpy(sg->a, a, (size_t)dim * sizeof *a);
    for (int j = 0; j < dim; j++) sg->e[j] = b[j] - a[j];
    sg->ee = dfl_vecn_dot(dim, sg->e, sg->e);
    if (!(sg->ee > 0.0)) {
        free(sg);
        return dfl_err_set(err, DFL_E_INPUT, "segment: end points coincide");
    }
    double w[3] = {0, 0, 0};
    for (int j = 0; j < dim; j++) w[j] = sg->e[j] / sqrt(sg->ee);
    if (dim == 2) {
        sg->nrm[0] = -w[1];
        sg->nrm[1] = w[0];
    } else {
        double v[3];
        dfl_vec3_tangent_basis(w, sg->nrm, v);
    }
    return shape_set(dim, &segment_ops, sg, out);
}

/* ---- capped cone --------------------------------------------------------- */

/* Rotational symmetry reduces the cone to its profile in the half-plane
 * (rho >= 0, y) through the axis and the query point: the trapezoid
 * V0 (0,0), V1 (ra,0), V2 (rb,h), V3 (0,h), counter-clockwise.  The axis edge
 * V3V0 is not boundary.  A boundary point in another half-plane is never
 * closer (rotating it into the query's half-plane shortens the distance),
 * so the 3D distance is the profile distance to the edges V0V1, V1V2, V2V3.
 * The full axial section is convex, hence inside d = max of the three edge
 * line functions (the mirrored side is never closer); outside d = min of
 * the distances to the edge segments. */
typedef struct cone {
    double a[3], w[3], u[3];
    double V[4][2];
    double en[3][2];    /* outward unit normals of edges i: V[i] -> V[i+1] */
    double ed[3][2];    /* edge vectors */
    double el2[3];      /* squared lengths (0 for a degenerate edge) */
} cone;

static void cone_profile(const cone *k, const double *x, double *rho, double *y, double e[3])
{
    double p[3] = {x[0] - k->a[0], x[1] - k->a[1], x[2] - k->a[2]}, pp[3];
    *y = split_axis(p, k->w, pp);
    *rho = sqrt(dfl_vecn_dot(3, pp, pp));
    for (int j = 0; j < 3; j++) e[j] = *rho > 0.0 ? pp[j] / *rho : k->u[j];
}

static void cone_eval(const void *impl, size_t m, const double *pts, double *val, double *grad)
{
    const cone *k = impl;
    for (size_t i = 0; i < m; i++) {
        double rho, y, e[3];
        cone_profile(k, pts + 3 * i, &rho, &y, e);
        double lmax = -HUGE_VAL, gl[2] = {0, 0};
        for (int t = 0; t < 3; t++) {
            if (k->el2[t] == 0.0) continue;
            double l = k->en[t][0] * (rho - k->V[t][0]) + k->en[t][1] * (y - k->V[t][1]);
            if (l > lmax) { lmax = l; gl[0] = k->en[t][0]; gl[1] = k->en[t][1]; }
        }
        double d, g2[2] = {0.0, 0.0};
        if (lmax <= 0.0) {
            d = lmax;
            g2[0] = gl[0];
            g2[1] = gl[1];
        } else {
            d = HUGE_VAL;
            for (int t = 0; t < 3; t++) {
                if (k->el2[t] == 0.0) continue;
                double q0 = rho - k->V[t][0], q1 = y - k->V[t][1];
                double s = (q0 * k->ed[t][0] + q1 * k->ed[t][1]) / k->el2[t];
                s = s < 0.0 ? 0.0 : (s > 1.0 ? 1.0 : s);
                q0 -= s * k->ed[t][0];
                q1 -= s * k->ed[t][1];
                double dd = sqrt(q0 * q0 + q1 * q1);
                if (dd < d) {
                    d = dd;
                    g2[0] = dd > 0.0 ? q0 / dd : k->en[t][0];
                    g2[1] = dd > 0.0 ? q1 / dd : k->en[t][1];
                }
            }
        }
        val[i] = d;
        if (grad)
            for (int j = 0; j < 3; j++) grad[3 * i + j] = g2[0] * e[j] + g2[1] * k->w[j];
    }
}

static dfl_status cone_jet(const void *impl, const double *x, const double *dir, int K,
                           dfl_jet *out, dfl_err *err)
{
    const cone *k = impl;
    double p[3] = {x[0] - k->a[0], x[1] - k->a[1], x[2] - k->a[2]}, pp[3], dp[3];
    double y0 = split_axis(p, k->w, pp), y1 = split_axis(dir, k->w, dp);
    dfl_jet rho, y, l[3], best;
    dfl_status st = jet_norm_line(3, pp, dp, K, &rho, err);
    if (st != DFL_OK) return st;
    dfl_jet_linear(y0, y1, K, &y);
    int imax = -1;
    for (int t = 0; t < 3; t++) {
        if (k->el2[t] == 0.0) continue;
        dfl_jet a, b;
        dfl_jet_add_const(&rho, -k->V[t][0], &a);
        dfl_jet_scale(&a, k->en[t][0], &a);
        dfl_jet_add_const(&y, -k->V[t][1], &b);
        dfl_jet_scale(&b, k->en[t][1], &b);
        dfl_jet_add(&a, &b, &l[t]);
        if (imax < 0 || jet_cmp(&l[t], &l[imax]) > 0) imax = t;
    }
    assert(imax >= 0);
    if (jet_sign(&l[imax]) <= 0) {
        *out = l[imax];
        return DFL_OK;
    }
    int have = 0;
    for (int t = 0; t < 3; t++) {
        if (k->el2[t] == 0.0) continue;
        dfl_jet q0, q1, s, dist;
        dfl_jet_add_const(&rho, -k->V[t][0], &q0);
        dfl_jet_add_const(&y, -k->V[t][1], &q1);
        dfl_jet a, b;
        dfl_jet_scale(&q0, k->ed[t][0] / k->el2[t], &a);
        dfl_jet_scale(&q1, k->ed[t][1] / k->el2[t], &b);
        dfl_jet_add(&a, &b, &s);
        dfl_jet one;
        dfl_jet_const(1.0, K, &one);
        if (jet_sign(&s) >= 0 && jet_cmp(&s, &one) <= 0) {
            /* foot inside the edge: the distance is the line function, no sqrt */
            dfl_jet_abs(&l[t], &dist);
        } else {
            int end = jet_sign(&s) < 0 ? t : t + 1;
            dfl_jet_add_const(&rho, -k->V[end][0], &q0);
            dfl_jet_add_const(&y, -k->V[end][1], &q1);
            dfl_jet_mul(&q0, &q0, &q0);
            dfl_jet_mul(&q1, &q1, &q1);
            dfl_jet_add(&q0, &q1, &q0);
            if ((st = dfl_jet_sqrt(&q0, &dist, err)) != DFL_OK) return st;
        }
        if (!have || jet_cmp(&dist, &best) < 0) best = dist;
        have = 1;
    }
    *out = best;
    return DFL_OK;
}

static const dfl_shape_ops cone_ops = {"cone", cone_eval, cone_jet, free, NULL};

dfl_status dfl_shape_cone(const double a[3], const double b[3], double ra, double rb,
                          dfl_shape *out, dfl_err *err)
{
    if (!finite_vec(3, a) || !finite_vec(3, b))
        return dfl_err_set(err, DFL_E_INPUT, "cone: end point not finite");
    if (!(ra >= 0.0) || !(rb >= 0.0) || !isfinite(ra) || !isfinite(rb) || !(ra + rb > 0.0))
        return dfl_err_set(err, DFL_E_INPUT,
                           "cone: radii must be >= 0 and not both 0, got %g and %g", ra, rb);
    double e[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double h = sqrt(dfl_vecn_dot(3, e, e));
    if (!(h > 0.0)) return dfl_err_set(err, DFL_E_INPUT, "cone: end points coincide");
    cone *k = calloc(1, sizeof *k);
    if (!k) return dfl_err_set(err, DFL_E_NOMEM, "cone: out of memory");
    memcpy(k->a, a, sizeof k->a);
    for (int j = 0; j < 3; j++) k->w[j] = e[j] / h;
    double v[3];
    dfl_vec3_tangent_basis(k->w, k->u, v);
    double V[4][2] = {{0, 0}, {ra, 0}, {rb, h}, {0, h}};
    memcpy(k->V, V, sizeof V);
    for (int t = 0; t < 3; t++) {
        double dx = V[t + 1][0] - V[t][0], dy = V[t + 1][1] - V[t][1];
        k->ed[t][0] = dx;
        k->ed[t][1] = dy;
        k->el2[t] = dx * dx + dy * dy;
        double len = sqrt(k->el2[t]);
        if (len > 0.0) {
            k->en[t][0] = dy / len;
            k->en[t][1] = -dx / len;
        }
    }
    return shape_set(3, &cone_ops, k, out);
}

/* ---- closed-form Hessians (geom/shape.h's dfl_shape_hessian) ------------ */

int dfl_shape_analytic_hess(const dfl_shape *s, const double *x, double *H)
{
    if (s->ops == &sphere_ops) sphere_hess(s->impl, x, H);
    else if (s->ops == &torus_ops) torus_hess(s->impl, x, H);
    else if (s->ops == &cylinder_ops) cylinder_hess(s->impl, x, H);
    else if (s->ops == &plane_ops && s->dim == 3) plane_hess(s->impl, x, H);
    else return 0;
    return 1;
}
