/* The mesh shape: Embree finds the closest triangle (geom/mesh_bvh.h), the
 * winding number decides the sign, and the closest feature gives the
 * gradient and the jets in closed form (see geom/mesh.h). */
#include "geom/mesh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geom/mesh_anchor.h"
#include "geom/mesh_bvh.h"
#include "geom/shape_impl.h"
#include "geom/trimesh.h"

typedef struct mesh_impl {
    dfl_trimesh m;
    dfl_mesh_bvh *bvh;
    dfl_mesh_distance dist;
} mesh_impl;

static const double *vert(const mesh_impl *mi, size_t t, int k)
{
    return mi->m.verts + 3 * mi->m.tris[3 * t + k];
}

/* Unit normal (b - a) x (c - a) / |.| of triangle t (non-zero: checked). */
static void tri_normal(const mesh_impl *mi, size_t t, double *n)
{
    const double *a = vert(mi, t, 0), *b = vert(mi, t, 1), *c = vert(mi, t, 2);
    double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    dfl_vec3_cross(e1, e2, n);
    const double l = dfl_vec3_norm(n);
    for (int j = 0; j < 3; j++) n[j] /= l;
}

/* -1 inside (signed mode), +1 otherwise. */
static double side(const mesh_impl *mi, const double *x)
{
    return mi->dist == DFL_MESH_SIGNED && dfl_mesh_bvh_inside(mi->bvh, x) ? -1.0 : 1.0;
}

/* d (with the side when sided and the mesh is signed, else |d|) and its
 * gradient at m points.  The side s = +-1 multiplies the closest-point
 * distance and its gradient (x - q) / d, so the unsigned output is the
 * signed one with values < 0 and their gradients negated, bit for bit
 * (shape.h's dfl_shape_eval_unsigned); d = 0 and NaN take no side. */
static void eval_points(const mesh_impl *mi, int sided, size_t m, const double *pts, double *val,
                        double *grad)
{
    /* a signed mesh builds its anchors anyway (the sign test): their
     * leaves also start the closest-point search near x */
    const struct dfl_mesh_anchor *anc =
        mi->dist == DFL_MESH_SIGNED ? dfl_mesh_bvh_anchors(mi->bvh) : NULL;
    for (size_t i = 0; i < m; i++) {
        const double *x = pts + 3 * i;
        dfl_mesh_hit h;
        dfl_mesh_bvh_closest_hint(mi->bvh, x, anc ? dfl_mesh_anchor_hint(anc, x) : SIZE_MAX, &h);
        if (isnan(h.d)) {
            val[i] = NAN;
            if (grad) grad[3 * i] = grad[3 * i + 1] = grad[3 * i + 2] = NAN;
            continue;
        }
        if (h.d == 0.0) {
            val[i] = 0.0;
            if (grad) tri_normal(mi, h.tri, grad + 3 * i);
            continue;
        }
        const double s = sided ? side(mi, x) : 1.0;
        val[i] = s * h.d;
        if (grad)
            for (int j = 0; j < 3; j++) grad[3 * i + j] = s * (x[j] - h.q[j]) / h.d;
    }
}

static void mesh_eval(const void *impl, size_t m, const double *pts, double *val, double *grad)
{
    eval_points(impl, 1, m, pts, val, grad);
}

static void mesh_eval_unsigned(const void *impl, size_t m, const double *pts, double *val,
                               double *grad)
{
    eval_points(impl, 0, m, pts, val, grad);
}

/* The two end points of an edge feature. */
static void edge_ends(const mesh_impl *mi, const dfl_mesh_hit *h, const double **e0,
                      const double **e1)
{
    int k0 = 0, k1 = 1;
    if (h->feat == DFL_TRI_EDGE_AC) k1 = 2;
    if (h->feat == DFL_TRI_EDGE_BC) k0 = 1, k1 = 2;
    *e0 = vert(mi, h->tri, k0);
    *e1 = vert(mi, h->tri, k1);
}

static dfl_status mesh_jet(const void *impl, const double *x, const double *dir, int K,
                           dfl_jet *out, dfl_err *err)
{
    const mesh_impl *mi = impl;
    dfl_mesh_hit h;
    dfl_mesh_bvh_closest(mi->bvh, x, &h);
    if (isnan(h.d)) return dfl_err_set(err, DFL_E_INPUT, "mesh jet: non-finite point");
    double r[3] = {x[0] - h.q[0], x[1] - h.q[1], x[2] - h.q[2]};
    dfl_status st = DFL_OK;
    if (h.feat == DFL_TRI_FACE) {
        double n[3];
        tri_normal(mi, h.tri, n);
        const double hgt = dfl_vec3_dot(r, n), vn = dfl_vec3_dot(dir, n);
        if (h.d == 0.0) {
            dfl_jet_linear(0.0, vn, K, out); /* the signed height across the face */
            return DFL_OK;
        }
        const double sg = hgt > 0.0 ? 1.0 : hgt < 0.0 ? -1.0 : (vn >= 0.0 ? 1.0 : -1.0);
        dfl_jet_linear(h.d, sg * vn, K, out);
    } else {
        double Pv[3];
        memcpy(Pv, dir, sizeof Pv);
        if (h.feat == DFL_TRI_EDGE_AB || h.feat == DFL_TRI_EDGE_AC || h.feat == DFL_TRI_EDGE_BC) {
            const double *e0, *e1;
            edge_ends(mi, &h, &e0, &e1);
            double e[3] = {e1[0] - e0[0], e1[1] - e0[1], e1[2] - e0[2]};
            const double l = dfl_vec3_norm(e);
            for (int j = 0; j < 3; j++) e[j] /= l;
            const double ve = dfl_vec3_dot(dir, e);
            for (int j = 0; j < 3; j++) Pv[j] -= ve * e[j];
        }
        st = jet_norm_line(3, r, Pv, K, out, err);
        if (st != DFL_OK) return st;
    }
    double s;
    if (h.d > 0.0) {
        s = side(mi, x);
    } else {
        const double dl = dfl_vec3_norm(dir);
        const double xm = dfl_vec3_norm(x);
        double y[3];
        for (int j = 0; j < 3; j++) y[j] = x[j] + (dl > 0.0 ? 1e-9 * (1.0 + xm) * dir[j] / dl : 0.0);
        s = side(mi, y);
    }
    if (s < 0.0) dfl_jet_neg(out, out);
    return st;
}

static void mesh_free(void *impl)
{
    mesh_impl *mi = impl;
    if (!mi) return;
    dfl_mesh_bvh_free(mi->bvh);
    dfl_trimesh_free(&mi->m);
    free(mi);
}

static const dfl_shape_ops mesh_ops = {"mesh", mesh_eval, mesh_jet, mesh_free,
                                        mesh_eval_unsigned};

dfl_status dfl_shape_mesh(dfl_trimesh *m, dfl_mesh_distance dist, dfl_shape *out, dfl_err *err)
{
    dfl_status st = dfl_trimesh_check(m, err);
    if (st != DFL_OK) return st;
    mesh_impl *mi = calloc(1, sizeof *mi);
    if (!mi) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    mi->m = *m;
    mi->dist = dist;
    st = dfl_mesh_bvh_new(mi->m.verts, mi->m.nverts, mi->m.tris, mi->m.ntris, &mi->bvh, err);
    if (st != DFL_OK) {
        free(mi);
        return st;
    }
    memset(m, 0, sizeof *m);
    return shape_set(3, &mesh_ops, mi, out);
}

const dfl_trimesh *dfl_shape_mesh_trimesh(const dfl_shape *s)
{
    if (!s || s->ops != &mesh_ops) return NULL;
    return &((const mesh_impl *)s->impl)->m;
}

double dfl_shape_mesh_winding(const dfl_shape *s, const double *x, double *bound)
{
    if (!s || s->ops != &mesh_ops) return NAN;
    const mesh_impl *mi = s->impl;
    return dfl_mesh_bvh_winding(mi->bvh, x, DFL_MESH_WINDING_BETA, bound);
}
