/* bs04 Sec. 3.2.2 / Fig. 11: two triangles sharing an edge, joined by
 * R-equivalence; the field on a section plane orthogonal to the edge and
 * |grad u| on a small circle around the edge in that plane.
 *
 * bs04: "the case of two triangles joined along a common edge in E3 is a
 * straightforward generalization of the case of two line segments joined at
 * a common point in E2"; |grad u| "remains bounded between 0 and 1, and its
 * minimum value occurs along the bisector of the dihedral angle".  Near the
 * edge (distance r much smaller than the triangles) each triangle field is
 * the exact distance to its half-plane, so in the section the theory of
 * Sec. 2.3 applies with h1, h2 the distances to two rays from the edge
 * point E at the dihedral angle theta:
 *     u = (h1^-p + h2^-p)^(-1/p),  F_i = du/dh_i = (u/h_i)^(p+1),
 *     |grad u| = |F1 grad h1 + F2 grad h2|  in  [|F1 - F2|, F1 + F2]  (eq. 13)
 * On the bisector inside the angle (theta <= 180 deg) both footpoints are
 * interior, the gradients are the unit normals at angle pi - theta, and
 *     |grad u| = 2^(-(p+1)/p) 2 sin(theta/2) = 2^(-1/p) sin(theta/2);
 * on the opposite bisector both footpoints are E, grad h1 = grad h2 and
 * |grad u| = 2^(-1/p).  The study evaluates these exact-distance formulas
 * at every circle point (independently of rfunc/) beside the field.
 *
 * Geometry (fixed frame): edge P = (0,0,0), Q = (0,0,1); apexes
 * R1 = (L, 0, zc), R2 = (L cos theta, L sin theta, zc); the section plane
 * is z = section.
 * Keys ([study]): dihedral (degrees, (0, 360), not 180), apex = L zc
 * (default 1 0.5), section (default 0.35, strictly between 0 and 1),
 * tri_trim (prism | conditional, a = 0.2, k = 2), join/p (default requiv,
 * 2), radius (1e-3), samples (3600), slices/slice_n/slice_lo/slice_hi,
 * compress; [output].
 * Rows: dihedral, tri_trim, join, p, radius, grad_min/max (circle),
 * argmin_deg/argmax_deg (angle from triangle 1), theory_min/max,
 * max_dev_theory (max | measured - theory |), eq13_violation (largest
 * amount by which a measured value leaves the eq. 13 interval),
 * bisector_in, bisector_out (measured), theory_bisector_in/out.
 * Files: triangles<tag>.vtp, edge_slice<k><tag>.vti/.exr.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bs04/bs04_space_util.h"
#include "core/vec.h"
#include "cfg/rfunc_cfg.h"
#include "harness/experiment.h"
#include "rfunc/rfield.h"
#include "rfunc/tri3d.h"
#include "cfg/slice_cfg.h"
#include "harness/field_out.h"
#include "cfg/field_cost.h"

typedef struct keys {
    double theta, L, zc, z0, radius;
    dfl_rfunc_tri_opts o;
    dfl_rfunc_join join;
    int p;
    long samples;
    dfl_bs04_space_out so;
} keys;

static dfl_status read_keys(const dfl_cfg *cfg, keys *k, dfl_err *err)
{
    const double dapex[2] = {1.0, 0.5};
    double apex[2], deg;
    dfl_status st;
    memset(k, 0, sizeof *k);
    if ((st = dfl_cfg_double(cfg, "study", "dihedral", 1e-6, 360 - 1e-6, &deg, err))) return st;
    if (fabs(deg - 180.0) < 1e-6)
        return dfl_cfg_reject(cfg, "study", "dihedral", err,
                              "180 degrees makes the triangles coplanar (no joining edge)");
    k->theta = deg * DFL_PI / 180.0;
    if ((st = dfl_cfg_vec_opt(cfg, "study", "apex", 2, dapex, apex, err))) return st;
    if (!(apex[0] > 0.0) || !(apex[1] > 0.0 && apex[1] < 1.0))
        return dfl_cfg_reject(cfg, "study", "apex", err, "expected L > 0 and 0 < zc < 1");
    k->L = apex[0];
    k->zc = apex[1];
    if ((st = dfl_cfg_double_opt(cfg, "study", "section", 0.35, 1e-9, 1 - 1e-9, &k->z0, err)))
        return st;
    if ((st = dfl_rfunc_tri_opts_from_cfg(cfg, "study", false, &k->o, err))) return st;
    if ((st = dfl_rfunc_join_p_from_cfg(cfg, "study", &k->join, &k->p, err))) return st;
    if ((st = dfl_cfg_double_opt(cfg, "study", "radius", 1e-3, 1e-12, 1e3, &k->radius, err)))
        return st;
    if ((st = dfl_cfg_int_opt(cfg, "study", "samples", 3600, 8, 10000000, &k->samples, err)))
        return st;
    return dfl_bs04_space_out_from_cfg(cfg, true, &k->so, err);
}

/* Distance from the in-plane point X to the ray from 0 in direction d, and
 * its gradient. */
static double ray_dist(const double *X, const double *d, double *g)
{
    const double s = dfl_vecn_dot(2, X, d);
    double v[2] = {X[0], X[1]};
    if (s > 0) {
        v[0] -= s * d[0];
        v[1] -= s * d[1];
    }
    const double h = hypot(v[0], v[1]);
    g[0] = v[0] / h;
    g[1] = v[1] / h;
    return h;
}

/* Exact-distance theory at X: |grad u| and the eq. 13 interval. */
static double theory(const double *X, double theta, int p, double *lo, double *hi)
{
    const double d1[2] = {1, 0}, d2[2] = {cos(theta), sin(theta)};
    double g1[2], g2[2];
    const double h1 = ray_dist(X, d1, g1), h2 = ray_dist(X, d2, g2);
    const double u = pow(pow(h1, -p) + pow(h2, -p), -1.0 / p);
    const double F1 = pow(u / h1, p + 1), F2 = pow(u / h2, p + 1);
    *lo = fabs(F1 - F2);
    *hi = F1 + F2;
    return hypot(F1 * g1[0] + F2 * g2[0], F1 * g1[1] + F2 * g2[1]);
}

static dfl_status edge_run(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_table *table,
                           dfl_err *err)
{
    keys k;
    dfl_field f = {0};
    char path[4400];
    dfl_status st = read_keys(cfg, &k, err);
    if (st == DFL_OK) st = dfl_cfg_check_used(cfg, err);
    if (st != DFL_OK) return st;
    const double P[3] = {0, 0, 0}, Q[3] = {0, 0, 1};
    const double R1[3] = {k.L, 0, k.zc}, R2[3] = {k.L * cos(k.theta), k.L * sin(k.theta), k.zc};
    dfl_rfield *rf;
    if ((st = dfl_rfield_new(3, k.join, k.p, &rf, err))) return st;
    if (!st) st = dfl_rfield_add_triangle(rf, P, Q, R1, &k.o, err);
    if (!st) st = dfl_rfield_add_triangle(rf, P, Q, R2, &k.o, err);
    if (st) {
        dfl_rfield_free(rf);
        return st;
    }
    if ((st = dfl_rfield_finish(&rf, &f, err))) return st;

    const size_t N = (size_t)k.samples;
    double gmin = INFINITY, gmax = -INFINITY, tmin = INFINITY, tmax = -INFINITY;
    double amin = 0, amax = 0, dev = 0, viol = 0;
    for (size_t i = 0; i < N; i++) {
        const double ph = 2.0 * DFL_PI * ((double)i + 0.5) / (double)N;
        const double X[2] = {k.radius * cos(ph), k.radius * sin(ph)};
        const double x[3] = {X[0], X[1], k.z0};
        double g[3], lo, hi;
        (void)dfl_field_eval1(&f, x, g);
        const double gn = dfl_vec3_norm(g);
        const double th = theory(X, k.theta, k.p, &lo, &hi);
        if (gn < gmin) gmin = gn, amin = ph;
        if (gn > gmax) gmax = gn, amax = ph;
        tmin = fmin(tmin, th);
        tmax = fmax(tmax, th);
        dev = fmax(dev, fabs(gn - th));
        viol = fmax(viol, fmax(lo - gn, gn - hi));
    }
    /* the two bisectors */
    double bis[2];
    for (int b = 0; b < 2; b++) {
        const double ph = 0.5 * k.theta + b * DFL_PI;
        const double x[3] = {k.radius * cos(ph), k.radius * sin(ph), k.z0};
        double g[3];
        (void)dfl_field_eval1(&f, x, g);
        bis[b] = dfl_vec3_norm(g);
    }
    /* inside the smaller angle: theta itself when <= 180, else the other side */
    const double half = k.theta <= DFL_PI ? 0.5 * k.theta : 0.5 * (2 * DFL_PI - k.theta);
    const double tb_in = pow(2.0, -1.0 / k.p) * sin(half), tb_out = pow(2.0, -1.0 / k.p);

    st = dfl_table_row(table, err);
    if (!st) st = dfl_table_set_double(table, "dihedral", k.theta * 180.0 / DFL_PI, err);
    if (!st)
        st = dfl_table_set_string(table, "tri_trim",
                                  dfl_rfunc_tri_trim_name(k.o.trim), err);
    if (!st) st = dfl_table_set_string(table, "join", dfl_rfunc_join_name(k.join), err);
    if (!st) st = dfl_table_set_int(table, "p", k.p, err);
    if (!st) st = dfl_table_set_double(table, "radius", k.radius, err);
    if (!st) st = dfl_table_set_double(table, "grad_min", gmin, err);
    if (!st) st = dfl_table_set_double(table, "grad_max", gmax, err);
    if (!st) st = dfl_table_set_double(table, "argmin_deg", amin * 180.0 / DFL_PI, err);
    if (!st) st = dfl_table_set_double(table, "argmax_deg", amax * 180.0 / DFL_PI, err);
    if (!st) st = dfl_table_set_double(table, "theory_min", tmin, err);
    if (!st) st = dfl_table_set_double(table, "theory_max", tmax, err);
    if (!st) st = dfl_table_set_double(table, "max_dev_theory", dev, err);
    if (!st) st = dfl_table_set_double(table, "eq13_violation", viol, err);
    /* with theta > 180 the inner bisector is phi = theta/2 + pi */
    if (!st) st = dfl_table_set_double(table, "bisector_in", k.theta <= DFL_PI ? bis[0] : bis[1], err);
    if (!st) st = dfl_table_set_double(table, "bisector_out", k.theta <= DFL_PI ? bis[1] : bis[0], err);
    if (!st) st = dfl_table_set_double(table, "theory_bisector_in", tb_in, err);
    if (!st) st = dfl_table_set_double(table, "theory_bisector_out", tb_out, err);
    if (st) goto done;

    const double verts[12] = {P[0], P[1], P[2], Q[0], Q[1], Q[2], R1[0], R1[1], R1[2],
                              R2[0], R2[1], R2[2]};
    const size_t tris[6] = {0, 1, 2, 0, 1, 3};
    st = dfl_bs04_vtp_trimesh(dfl_study_path(ctx, "triangles", "vtp", path, sizeof path), 4, verts,
                              2, tris, k.so.compress, err);
    if (st == DFL_OK) st = dfl_bs04_write_slices(ctx, &f, &k.so, "edge_slice", err);
done:
    dfl_field_destroy(&f);
    return st;
}

/* Peak memory: one slice at a time (dfl_bs04_slices_cost); the circle's
 * samples are not stored.  Work: per circle sample the two-triangle field
 * (2 + DFL_RFUNC_EVAL_UNITS CHEAP) and the theory (2); per slice node the
 * field. */
static dfl_status edge_estimate(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_cost *c,
                                dfl_err *err)
{
    (void)ctx;
    keys k;
    dfl_status st = read_keys(cfg, &k, err);
    if (st) return st;
    dfl_cost_add_work(c, "study", "samples", DFL_COST_CHEAP,
                      (2 + DFL_RFUNC_EVAL_UNITS + 2) * (double)k.samples,
                      "%ld circle samples", k.samples);
    dfl_bs04_slices_cost(&k.so, DFL_COST_CHEAP, 2 + DFL_RFUNC_EVAL_UNITS, DFL_COST_CHEAP, 0, 0, c);
    return DFL_OK;
}

DFL_STUDY_DEFINE_ESTIMATED(bs04_triedge, edge_run, edge_estimate,
                 "bs04 Fig. 11: two triangles on an edge, |grad u| around the edge vs eq. 13");
