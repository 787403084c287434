/* The anchored sign test (geom/mesh_anchor.h): an octree of anchors with
 * known winding numbers; a query counts the crossings from its leaf's
 * anchor and bounds the boundary's field along the way. */
#include "geom/mesh_anchor.h"

#include <assert.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/vec.h"
#include "geom/mesh_bvh.h"

/* The octree's parameters, chosen on Wuson (fitted to 1.6) with the
 * bench's points (half uniform in [-1, 1]^3, half within 0.02 of a
 * vertex; shares decided, uniform / near-vertex, and one build's CPU time
 * measured by one run each):
 *   MAXD 8, no FDEPTH:            95 % / 78 %, 16 k leaves
 *   MAXD 9, FDEPTH 5:             98 % / 82 %, 53 k leaves, 0.7 s
 *   MAXD 9, FDEPTH 6:             99.4 % / 83 %, 85 k leaves, 1.0 s
 *   MAXD 10, KSPLIT 2, FDEPTH 6:  99.5 % / 88 %, 230 k leaves, 5.8 s
 * With the far edges to first order and the near edges' second chance
 * (and each leaf's nearest triangle as the closest-point hint; signed
 * query CPU time per point, closest point and sign, one thread):
 *   MAXD 8, no FDEPTH:            99.97 % / 95.8 %, 16 k leaves, 0.35 s, 2.3 us
 *   MAXD 8, FDEPTH 5:             99.97 % / 95.8 %, 31 k leaves, 0.51 s, 2.2 us
 *   MAXD 9, FDEPTH 4:             99.97 % / 96.8 %, 42 k leaves, 0.75 s, 1.7 us
 *   MAXD 9, FDEPTH 5:             99.97 % / 96.8 %, 53 k leaves, 0.88 s, 1.6 us
 *   MAXD 9, FDEPTH 6:             99.97 % / 96.8 %, 85 k leaves, 1.1 s, 1.6 us
 * (the smaller leaves pay mostly through the hint).
 * Depth of the finest cells: the root cube (side twice the mesh's largest
 * extent) over 2^MAXD. */
#define MAXD 9
/* A cell meeting more than TMAX triangles is split, down to TDEPTH. */
#define TMAX 16
#define TDEPTH 8
/* A cell whose bound G r of the change of w over its ball exceeds FSPLIT
 * is split when its nearest edge of nonzero n_e is within KSPLIT radii of
 * its ball (down to MAXD), or whatever that distance down to FDEPTH. */
#define FSPLIT 0.1
#define KSPLIT 1.0
#define FDEPTH 5
/* Edges of nonzero n_e beyond KFAR cell radii of a cell count in its far
 * bound and are not passed to its children; within KNEAR radii of a leaf
 * they are refined per query against the segment (when needed). */
#define KFAR 8.0
#define KNEAR 2.0
/* Relative tolerance of the barycentric tests. */
#define BARY 1e-9
/* The anchors' winding numbers are computed to this bound (one pass of
 * dfl_mesh_bvh_winding_budget: 0.05 cost 20 % more build time for the
 * same shares). */
#define ANCHOR_TOL 0.1
/* A leaf (high bit set) or the index of the first of 8 children. */
#define LEAF_BIT 0x80000000u

typedef struct aleaf {
    double c[3];           /* the anchor */
    double w, B;           /* w(c) within B (B = inf: no anchor) */
    double g[3];           /* the far edges' first-order term: grad w . (x - c) */
    double H;              /* the leaf's far edges' bound of |grad g| over its ball */
    double R;              /* the inherited far edges' bound of |g(y) - g| per length */
    double Fs;             /* all far edges' bound of |g| (for the rounding term) */
    uint32_t t0, nt;       /* triangles: tl[t0 .. t0 + nt) */
    uint32_t e0, ne;       /* near edges: el[e0 .. e0 + ne) */
    uint32_t nmust;        /* of which the first nmust touch the cell's ball */
    uint32_t near;         /* the triangle closest to the anchor (UINT32_MAX: none) */
} aleaf;

/* A near edge of a leaf: its distance D from the leaf's ball (a lower
 * bound of its distance from any segment in the cell) and the sum S of
 * edge_bound(D) over it and the leaf's later near edges (+inf while an
 * edge with D <= 0 is left).  Sorted by edge_bound(D), largest first. */
typedef struct nearent {
    uint32_t e;
    double D, S;
} nearent;

typedef struct dedge {
    size_t a, b;
    int n;
} dedge;

typedef struct bedge {
    uint32_t a, b; /* vertex indices, a -> b the direction of positive net count */
    double k;      /* |n_e| / (4 pi) */
    double len;
} bedge;

struct dfl_mesh_anchor {
    size_t maxnode, maxlist; /* the size caps (header) */
    int full;                /* a cap was reached: no anchors */
    const double *V;
    const size_t *T;
    double ctr[3], half; /* the root cube */
    double tol;          /* plane tolerance, 1e-9 of the mesh's scale */
    double eps;          /* widening of cells, 1e-9 of the scale */
    double scale;        /* the largest |coordinate| of the mesh and the query box */
    uint32_t *node;
    size_t nnode, capnode;
    aleaf *leaf;
    size_t nleaf, capleaf;
    uint32_t *tl;
    nearent *el;
    size_t ntl, captl, nel, capel;
    bedge *edge;
    size_t nedge;
};

static const double *tv(const dfl_mesh_anchor *a, size_t t, int k) { return a->V + 3 * a->T[3 * t + k]; }

/* ---- crossings ------------------------------------------------------------ */

/* Barycentric coordinates of p's projection on the plane of abc (n =
 * (b - a) x (c - a), nn = |n|^2): the smallest of the three. */
static double bary_min(const double *p, const double *A, const double *B, const double *C,
                       const double *n, double nn)
{
    double e[3], q[3], k[3], m = INFINITY;
    const double *P[3] = {A, B, C};
    for (int i = 0; i < 3; i++) {
        const double *u = P[i], *v = P[(i + 1) % 3];
        for (int j = 0; j < 3; j++) {
            e[j] = v[j] - u[j];
            q[j] = p[j] - u[j];
        }
        dfl_vec3_cross(e, q, k);
        m = fmin(m, dfl_vec3_dot(k, n) / nn);
    }
    return m;
}

int dfl_mesh_anchor_crossings(const double *verts, const size_t *tris, const uint32_t *list,
                              size_t n, const double *c, const double *x, double tol, int *J)
{
    int s = 0;
    for (size_t i = 0; i < n; i++) {
        const size_t t = list ? list[i] : i;
        const double *A = verts + 3 * tris[3 * t], *B = verts + 3 * tris[3 * t + 1],
                     *C = verts + 3 * tris[3 * t + 2];
        double e1[3], e2[3], nv[3], ca[3], xa[3];
        for (int j = 0; j < 3; j++) {
            e1[j] = B[j] - A[j];
            e2[j] = C[j] - A[j];
            ca[j] = c[j] - A[j];
            xa[j] = x[j] - A[j];
        }
        dfl_vec3_cross(e1, e2, nv);
        const double nn = dfl_vec3_dot(nv, nv);
        if (nn == 0.0) continue;
        const double ln = sqrt(nn);
        const double hc = dfl_vec3_dot(nv, ca) / ln, hx = dfl_vec3_dot(nv, xa) / ln;
        if ((hc > tol && hx > tol) || (hc < -tol && hx < -tol)) continue;
        if (!(fabs(hc) > tol) && !(fabs(hx) > tol)) return -1; /* NaN too */
        if (fabs(hc) <= tol && bary_min(c, A, B, C, nv, nn) >= -BARY) return -1;
        if (fabs(hx) <= tol && bary_min(x, A, B, C, nv, nn) >= -BARY) return -1;
        if (!((hc > 0.0 && hx < 0.0) || (hc < 0.0 && hx > 0.0))) continue;
        const double u = hc / (hc - hx);
        double p[3];
        for (int j = 0; j < 3; j++) p[j] = c[j] + u * (x[j] - c[j]);
        const double m = bary_min(p, A, B, C, nv, nn);
        if (m < -BARY) continue;
        if (!(m > BARY)) return -1;
        s += hc > 0.0 ? 1 : -1;
    }
    *J = s;
    return 0;
}

/* ---- distances -------------------------------------------------------------- */

static double point_seg(const double *p, const double *a, const double *b)
{
    double d[3], q[3];
    for (int j = 0; j < 3; j++) {
        d[j] = b[j] - a[j];
        q[j] = p[j] - a[j];
    }
    const double dd = dfl_vec3_dot(d, d);
    double t = dd > 0.0 ? dfl_vec3_dot(q, d) / dd : 0.0;
    t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
    double r = 0.0;
    for (int j = 0; j < 3; j++) {
        const double v = q[j] - t * d[j];
        r += v * v;
    }
    return sqrt(r);
}

static double clamp01(double t) { return t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t; }

/* A lower bound of the distance between segments [p0, p1] and [q0, q1]
 * (neither of zero length): closest points by Ericson's clamped solution
 * (Real-Time Collision Detection, 5.1.9), then the gap between the two
 * segments' projections on the direction u joining those points, which
 * bounds the distance from below whatever the rounding of the closest
 * points (any unit u separates by at most the distance); minus slack for
 * the rounding of the projections.  0 when the segments (nearly) touch. */
static double seg_seg_lower(const double *p0, const double *p1, const double *q0, const double *q1,
                            double slack)
{
    double d1[3], d2[3], r[3];
    for (int j = 0; j < 3; j++) {
        d1[j] = p1[j] - p0[j];
        d2[j] = q1[j] - q0[j];
        r[j] = p0[j] - q0[j];
    }
    const double a = dfl_vec3_dot(d1, d1), e = dfl_vec3_dot(d2, d2), f = dfl_vec3_dot(d2, r);
    const double c = dfl_vec3_dot(d1, r), b = dfl_vec3_dot(d1, d2), den = a * e - b * b;
    double s = den > 0.0 ? clamp01((b * f - c * e) / den) : 0.0;
    double t = (b * s + f) / e;
    if (t < 0.0) {
        t = 0.0;
        s = clamp01(-c / a);
    } else if (t > 1.0) {
        t = 1.0;
        s = clamp01((b - c) / a);
    }
    double u[3];
    for (int j = 0; j < 3; j++) u[j] = (q0[j] + t * d2[j]) - (p0[j] + s * d1[j]);
    const double lu = sqrt(dfl_vec3_dot(u, u));
    if (!(lu > slack)) return 0.0;
    const double pa = dfl_vec3_dot(u, p0), pb = dfl_vec3_dot(u, p1);
    const double qa = dfl_vec3_dot(u, q0), qb = dfl_vec3_dot(u, q1);
    const double g = (fmin(qa, qb) - fmax(pa, pb)) / lu - slack;
    return g > 0.0 ? g : 0.0;
}

/* One edge's bound of |grad w| at distance >= d: k min(len / d^2, 2 / d). */
static double edge_bound(const bedge *e, double d)
{
    if (!(d > 0.0)) return INFINITY;
    return e->k * fmin(e->len / (d * d), 2.0 / d);
}

/* One edge's bound of the norm of the derivative of its field at distance
 * >= d: the Jacobian of r / |r|^3 is (I - 3 rr^T / |r|^2) / |r|^3, of
 * norm 2 / |r|^3, so over the edge k min(2 len / d^3, 4 / d^2) (the
 * second: the integral of 2 / (d^2 + s^2)^(3/2) over the whole line). */
static double edge_hess_bound(const bedge *e, double d)
{
    if (!(d > 0.0)) return INFINITY;
    return e->k * fmin(2.0 * e->len / (d * d * d), 4.0 / (d * d));
}

/* Adds edge e's part of grad w at y: k (|a| + |b|) / (|a||b| (|a||b| +
 * a.b)) a x b with a = P - y, b = Q - y for the edge P -> Q (the
 * Biot-Savart field of a straight segment; sign and scale checked against
 * central differences of dfl_winding_triangle over a triangle's three
 * directed edges, tests/geom/test_mesh_anchor.c).  y off the edge's line
 * segment. */
static void edge_field_add(const dfl_mesh_anchor *a, const bedge *e, const double *y, double *g)
{
    const double *P = a->V + 3 * (size_t)e->a, *Q = a->V + 3 * (size_t)e->b;
    double u[3], v[3], w[3];
    for (int j = 0; j < 3; j++) {
        u[j] = P[j] - y[j];
        v[j] = Q[j] - y[j];
    }
    const double lu = sqrt(dfl_vec3_dot(u, u)), lv = sqrt(dfl_vec3_dot(v, v));
    dfl_vec3_cross(u, v, w);
    const double f = e->k * (lu + lv) / (lu * lv * (lu * lv + dfl_vec3_dot(u, v)));
    for (int j = 0; j < 3; j++) g[j] += f * w[j];
}

/* ---- queries ---------------------------------------------------------------- */

static const aleaf *locate(const dfl_mesh_anchor *a, const double *x)
{
    double c[3] = {a->ctr[0], a->ctr[1], a->ctr[2]}, h = a->half;
    for (int j = 0; j < 3; j++)
        if (!(fabs(x[j] - c[j]) <= h)) return NULL; /* NaN too */
    uint32_t k = 0;
    while (!(a->node[k] & LEAF_BIT)) {
        h *= 0.5;
        const uint32_t first = a->node[k];
        int i = 0;
        for (int j = 0; j < 3; j++) {
            if (x[j] >= c[j]) {
                i |= 1 << j;
                c[j] += h;
            } else {
                c[j] -= h;
            }
        }
        k = first + (uint32_t)i;
    }
    return a->leaf + (a->node[k] & ~LEAF_BIT);
}

/* The path c -> x from x's leaf anchor, shared by both estimates: the
 * leaf, d = x - c, |d|, and w(c) + J + g . d (the crossings and the far
 * edges' first-order term).  0 where the anchor refuses (no leaf or no
 * anchor, an unclear crossing). */
typedef struct apath {
    const aleaf *l;
    double d[3], dx, w;
} apath;

static int path_start(const dfl_mesh_anchor *a, const double *x, apath *p)
{
    const aleaf *l = locate(a, x);
    if (!l || !(l->B < INFINITY)) return 0;
    int J;
    if (dfl_mesh_anchor_crossings(a->V, a->T, a->tl + l->t0, l->nt, l->c, x, a->tol, &J) != 0)
        return 0;
    p->l = l;
    for (int j = 0; j < 3; j++) p->d[j] = x[j] - l->c[j];
    p->dx = sqrt(dfl_vec3_dot(p->d, p->d));
    p->w = l->w + J;
    p->w += dfl_vec3_dot(l->g, p->d); /* the far edges' first-order term */
    return 1;
}

/* w(c) + J + g . d and a margin for x on path p; with stop finite, the
 * near edges are refined (their ball distance D replaced by their distance
 * from the segment, largest bound first) only until the margin is below
 * stop: the margin returned is valid either way, only looser. */
static int estimate(const dfl_mesh_anchor *a, const double *x, const apath *p, double stop,
                    double *est, double *margin)
{
    const aleaf *l = p->l;
    const double dx = p->dx, w = p->w;
    /* in the margin the far edges' rest (H dx^2 / 2 for the leaf's, R dx
     * for the inherited, see make_leaf) and the rounding of g . d (each
     * term's few ulps, far below 1e-12 of its bound) */
    const double T = (0.5 * l->H * dx + 1e-12 * l->Fs) * dx * (1.0 + 1e-12);
    const double lim = fabs(w - 0.5) - stop - T;
    double G = l->R;
    if (dx > 0.0) {
        const nearent *ne = a->el + l->e0;
        uint32_t i = 0;
        for (; i < l->ne; i++) {
            if (i >= l->nmust && (G + ne[i].S) * dx * (1.0 + 1e-12) + l->B < lim) break;
            const bedge *e = a->edge + ne[i].e;
            const double ds = seg_seg_lower(l->c, x, a->V + 3 * (size_t)e->a, a->V + 3 * (size_t)e->b,
                                            a->eps);
            G += edge_bound(e, fmax(ds, ne[i].D));
        }
        if (i < l->ne) G += ne[i].S;
    }
    const double m = G * dx * (1.0 + 1e-12) + T + l->B;
    if (!(m < INFINITY)) return 0;
    *est = w;
    *margin = m;
    return 1;
}

int dfl_mesh_anchor_estimate(const dfl_mesh_anchor *a, const double *x, double *est, double *margin)
{
    apath p;
    return path_start(a, x, &p) && estimate(a, x, &p, INFINITY, est, margin);
}

/* The solid angle / 4 pi of the triangle of vectors u, v, t from the
 * observer (geom/winding.c's formula, Van Oosterom and Strackee) and in
 * *err a bound of its rounding error: each of num and den is a sum of
 * products of the vectors' components within 32 ulp of |u||v||t|, which
 * moves atan2 by at most that over hypot(num, den), plus atan2's own ulp.
 * An infinite *err when num and den are both that small (the observer on
 * the triangle's boundary). */
static double tri_w(const double *u, const double *v, const double *t, double *err)
{
    double vxt[3];
    dfl_vec3_cross(v, t, vxt);
    const double lu = sqrt(dfl_vec3_dot(u, u)), lv = sqrt(dfl_vec3_dot(v, v)),
                 lt = sqrt(dfl_vec3_dot(t, t));
    const double num = dfl_vec3_dot(u, vxt);
    const double den =
        lu * lv * lt + dfl_vec3_dot(u, v) * lt + dfl_vec3_dot(u, t) * lv + dfl_vec3_dot(v, t) * lu;
    const double big = 32.0 * DBL_EPSILON * lu * lv * lt, h = hypot(num, den);
    *err = h > 2.0 * big ? (2.0 * big / h + 4.0 * DBL_EPSILON) / (2.0 * DFL_PI) : INFINITY;
    return atan2(num, den) / (2.0 * DFL_PI);
}

/* The second chance of decide: as estimate, but each near edge's part of
 * w(x) - w(c) - J taken exactly (largest bound first, until the rest's
 * bound fits).  Why it is exact: along the path c + s d (s in [0, 1], d =
 * x - c) the field of the edge P -> Q integrates to the Gauss linking
 * integral of the two segments, the solid angle / 4 pi seen from c of the
 * parallelogram the edge sweeps when moved by -d (P, Q, Q - d, P - d),
 * with the opposite orientation (Klenin and Langowski, "Computation of
 * writhe in modeling of supercoiled DNA", Biopolymers 54 (2000) 307,
 * doi:10.1002/1097-0282(20001015)54:5<307::AID-BIP20>3.0.CO;2-Y; sign
 * checked against dfl_winding_triangle over a triangle's three edges,
 * tests/geom/test_mesh_anchor.c).  The parallelogram is split along P,
 * Q - d.  c lies on it exactly when the path meets the edge: then (or
 * when the gap is not certainly positive) it refuses.  Rounding: the
 * corners are P - c, Q - c, Q - x and P - x, each within an ulp of its
 * coordinates (the mesh's scale S), which moves the solid angle by at
 * most the edges' field at the gap g, 2 (2 |PQ| + 2 |d|) / (4 pi g^2),
 * times that ulp; plus tri_w's own error. */
static int estimate_near(const dfl_mesh_anchor *a, const double *x, const apath *p, double stop,
                         double *est, double *margin)
{
    const aleaf *l = p->l;
    const double dx = p->dx;
    double w = p->w;
    double m = (0.5 * l->H * dx + 1e-12 * l->Fs + l->R) * dx * (1.0 + 1e-12) + l->B;
    const nearent *ne = a->el + l->e0;
    uint32_t i = 0;
    for (; i < l->ne; i++) {
        if (i >= l->nmust && fabs(w - 0.5) - stop > m + ne[i].S * dx * (1.0 + 1e-12)) break;
        const bedge *e = a->edge + ne[i].e;
        const double *P = a->V + 3 * (size_t)e->a, *Q = a->V + 3 * (size_t)e->b;
        const double gap = seg_seg_lower(l->c, x, P, Q, a->eps);
        if (!(gap > 0.0)) return 0;
        double A[3], B[3], C[3], D[3];
        for (int j = 0; j < 3; j++) {
            A[j] = P[j] - l->c[j];
            B[j] = Q[j] - l->c[j];
            C[j] = Q[j] - x[j];
            D[j] = P[j] - x[j];
        }
        double e1, e2;
        const double v = tri_w(A, C, B, &e1) + tri_w(A, D, C, &e2);
        const double n = (double)lrint(e->k * 4.0 * DFL_PI);
        const double ulp = DBL_EPSILON * a->scale;
        w += n * v;
        m += n * (e1 + e2 + 4.0 * DBL_EPSILON * fabs(v) +
                  (4.0 * (e->len + dx) / (4.0 * DFL_PI * gap * gap)) * 2.0 * ulp);
    }
    if (i < l->ne) m += ne[i].S * dx * (1.0 + 1e-12);
    if (!(m < INFINITY)) return 0;
    *est = w;
    *margin = m;
    return 1;
}

int dfl_mesh_anchor_estimate_near(const dfl_mesh_anchor *a, const double *x, double stop,
                                  double *est, double *margin)
{
    apath p;
    return path_start(a, x, &p) && estimate_near(a, x, &p, stop, est, margin);
}

int dfl_mesh_anchor_decide(const dfl_mesh_anchor *a, const double *x, int *inside)
{
    double est, m;
    apath p; /* located and crossed once for both chances */
    if (!path_start(a, x, &p) || !estimate(a, x, &p, 1e-9, &est, &m)) return 0;
    if (!(fabs(est - 0.5) > m + 1e-9) &&
        !(estimate_near(a, x, &p, 1e-9, &est, &m) && fabs(est - 0.5) > m + 1e-9))
        return 0;
    *inside = est > 0.5;
    return 1;
}

size_t dfl_mesh_anchor_hint(const dfl_mesh_anchor *a, const double *x)
{
    const aleaf *l = locate(a, x);
    return l && l->near != UINT32_MAX ? l->near : SIZE_MAX;
}

void dfl_mesh_anchor_stats(const dfl_mesh_anchor *a, size_t *leaves, size_t *bytes)
{
    *leaves = a->nleaf;
    *bytes = a->nnode * sizeof *a->node + a->nleaf * sizeof *a->leaf + a->ntl * sizeof *a->tl +
             a->nel * sizeof *a->el + a->nedge * sizeof *a->edge;
}

void dfl_mesh_anchor_free(dfl_mesh_anchor *a)
{
    if (!a) return;
    free(a->node);
    free(a->leaf);
    free(a->tl);
    free(a->el);
    free(a->edge);
    free(a);
}

/* ---- build ------------------------------------------------------------------ */

static int dedge_cmp(const void *x, const void *y)
{
    const dedge *p = x, *q = y;
    if (p->a != q->a) return p->a < q->a ? -1 : 1;
    if (p->b != q->b) return p->b < q->b ? -1 : 1;
    return 0;
}

/* The edges of nonzero net count (and nonzero length). */
static int net_edges(dfl_mesh_anchor *a, size_t ntris)
{
    dedge *d = malloc(3 * ntris * sizeof *d);
    if (!d) return 0;
    for (size_t t = 0; t < ntris; t++)
        for (int k = 0; k < 3; k++) {
            const size_t u = a->T[3 * t + k], v = a->T[3 * t + (k + 1) % 3];
            d[3 * t + k] = (dedge){u < v ? u : v, u < v ? v : u, u < v ? 1 : -1};
        }
    qsort(d, 3 * ntris, sizeof *d, dedge_cmp);
    a->edge = malloc(3 * ntris * sizeof *a->edge);
    if (!a->edge) {
        free(d);
        return 0;
    }
    for (size_t i = 0; i < 3 * ntris;) {
        size_t j = i;
        int n = 0;
        while (j < 3 * ntris && d[j].a == d[i].a && d[j].b == d[i].b) n += d[j++].n;
        const double *p = a->V + 3 * d[i].a, *q = a->V + 3 * d[i].b;
        double e[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
        const double len = sqrt(dfl_vec3_dot(e, e));
        if (n != 0 && len > 0.0 && d[i].a != d[i].b)
            a->edge[a->nedge++] = (bedge){(uint32_t)(n > 0 ? d[i].a : d[i].b),
                                          (uint32_t)(n > 0 ? d[i].b : d[i].a),
                                          abs(n) / (4.0 * DFL_PI), len};
        i = j;
    }
    free(d);
    return 1;
}

/* Largest bound first (infinite ones, D <= 0, first). */
static int near_cmp(const void *x, const void *y)
{
    const double p = ((const nearent *)x)->S, q = ((const nearent *)y)->S;
    return p > q ? -1 : p < q ? 1 : (int)((const nearent *)x)->e - (int)((const nearent *)y)->e;
}

static int grow(void **p, size_t *cap, size_t need, size_t size)
{
    if (need <= *cap) return 1;
    size_t c = *cap ? *cap : 64;
    while (c < need) c *= 2;
    void *q = realloc(*p, c * size);
    if (!q) return 0;
    *p = q;
    *cap = c;
    return 1;
}

/* Whether triangle t may meet the box c +- h (conservative: its bounding
 * box and its plane's slab; h already widened). */
static int tri_meets_box(const dfl_mesh_anchor *a, size_t t, const double *c, double h)
{
    const double *A = tv(a, t, 0), *B = tv(a, t, 1), *C = tv(a, t, 2);
    for (int j = 0; j < 3; j++) {
        if (fmin(fmin(A[j], B[j]), C[j]) > c[j] + h) return 0;
        if (fmax(fmax(A[j], B[j]), C[j]) < c[j] - h) return 0;
    }
    double e1[3], e2[3], n[3], ca[3];
    for (int j = 0; j < 3; j++) {
        e1[j] = B[j] - A[j];
        e2[j] = C[j] - A[j];
        ca[j] = c[j] - A[j];
    }
    dfl_vec3_cross(e1, e2, n);
    const double r = h * (fabs(n[0]) + fabs(n[1]) + fabs(n[2]));
    return !(fabs(dfl_vec3_dot(n, ca)) > r * (1.0 + 1e-9) + 1e-12 * r);
}

/* What a cell inherits of the edges dropped by its ancestors (beyond KFAR
 * radii of one): the sum g of their fields, each at the centre of the
 * ancestor that dropped it, R the sum of their H r there (so that
 * |g_true(y) - g| <= R for y in the cell), F the sum of their bounds of
 * |g|. */
typedef struct inherited {
    double g[3], R, F;
} inherited;

/* A leaf's own far edges (beyond KNEAR radii): their field at the first
 * anchor candidate and their bound of |g|, until the anchor is chosen. */
typedef struct leaffar {
    double g[3], F;
} leaffar;

typedef struct bctx {
    dfl_mesh_anchor *a;
    const struct dfl_mesh_bvh *bvh;
    uint32_t *tbuf[MAXD + 1], *ebuf[MAXD + 1];
    leaffar *lf;
    size_t caplf;
} bctx;

/* Whether point p is clear of the leaf's triangles (not within tol of one). */
static int anchor_clear(const dfl_mesh_anchor *a, const uint32_t *tl, size_t nt, const double *p)
{
    int J;
    return dfl_mesh_anchor_crossings(a->V, a->T, tl, nt, p, p, a->tol * 1e3, &J) == 0;
}

/* The anchor candidates: the cell's centre plus these times its half side
 * (off any symmetry plane of the mesh), tried in order. */
static const double anchor_off[3][3] = {
    {0.0193, -0.0271, 0.0117}, {-0.2113, 0.1877, 0.1549}, {0.3371, 0.2939, -0.3167}};

static int make_leaf(bctx *x, uint32_t k, const double *c, double h, const uint32_t *tl, size_t nt,
                     const uint32_t *el, size_t ne, const inherited *in)
{
    dfl_mesh_anchor *a = x->a;
    const double r = h * sqrt(3.0) + a->eps;
    if (a->ntl + nt + a->nel + ne > a->maxlist) {
        a->full = 1;
        return 0;
    }
    if (!grow((void **)&a->leaf, &a->capleaf, a->nleaf + 1, sizeof *a->leaf)) return 0;
    if (!grow((void **)&x->lf, &x->caplf, a->nleaf + 1, sizeof *x->lf)) return 0;
    if (!grow((void **)&a->tl, &a->captl, a->ntl + nt, sizeof *a->tl)) return 0;
    if (!grow((void **)&a->el, &a->capel, a->nel + ne, sizeof *a->el)) return 0;
    aleaf *l = a->leaf + a->nleaf;
    l->t0 = (uint32_t)a->ntl;
    l->nt = (uint32_t)nt;
    if (nt) memcpy(a->tl + a->ntl, tl, nt * sizeof *tl); /* tl may still be NULL when nt = 0 */
    a->ntl += nt;
    l->e0 = (uint32_t)a->nel;
    l->ne = 0;
    nearent *ne0 = a->el + a->nel;
    /* the far edges still listed: their field at the first candidate
     * anchor (leaf_anchor folds them into F if another is taken) */
    double p0[3];
    for (int j = 0; j < 3; j++) p0[j] = c[j] + anchor_off[0][j] * h;
    leaffar *lf = x->lf + a->nleaf;
    *lf = (leaffar){{0.0, 0.0, 0.0}, 0.0};
    l->H = 0.0;
    for (size_t i = 0; i < ne; i++) {
        const bedge *e = a->edge + el[i];
        const double D = point_seg(c, a->V + 3 * (size_t)e->a, a->V + 3 * (size_t)e->b) - r;
        if (D > KNEAR * r) {
            lf->F += edge_bound(e, D);
            l->H += edge_hess_bound(e, D);
            edge_field_add(a, e, p0, lf->g);
        } else {
            ne0[l->ne++] = (nearent){el[i], D, edge_bound(e, D)};
        }
    }
    if (l->ne > 1) qsort(ne0, l->ne, sizeof *ne0, near_cmp); /* el may be NULL when empty */
    l->nmust = 0;
    double S = 0.0;
    for (uint32_t i = l->ne; i-- > 0;) {
        S += ne0[i].S;
        ne0[i].S = S;
        l->nmust += !(ne0[i].D > 0.0);
    }
    a->nel += l->ne;
    for (int j = 0; j < 3; j++) l->g[j] = in->g[j] + lf->g[j];
    l->R = in->R;
    l->Fs = in->F + lf->F;
    memcpy(l->c, c, 3 * sizeof *c); /* the cell, until leaf_anchor */
    l->w = h;
    a->node[k] = LEAF_BIT | (uint32_t)a->nleaf;
    a->nleaf++;
    return 1;
}

/* The anchor of leaf l (cell c +- h): the centre moved off any symmetry
 * plane of the mesh, clear of the leaf's triangles, w from the clustered
 * sum within ANCHOR_TOL. */
static void leaf_anchor(const dfl_mesh_anchor *a, const struct dfl_mesh_bvh *bvh, aleaf *l,
                        const leaffar *lf, const double *c, double h)
{
    l->B = INFINITY;
    l->near = UINT32_MAX;
    for (int i = 0; i < 3; i++) {
        double p[3], B;
        for (int j = 0; j < 3; j++) p[j] = c[j] + anchor_off[i][j] * h;
        if (!anchor_clear(a, a->tl + l->t0, l->nt, p)) continue;
        const double w = dfl_mesh_bvh_winding_budget(bvh, p, ANCHOR_TOL, &B);
        if (!(B < INFINITY) || !isfinite(w)) continue;
        memcpy(l->c, p, sizeof p);
        l->w = w;
        l->B = B;
        dfl_mesh_hit hit;
        dfl_mesh_bvh_closest(bvh, p, &hit);
        if (hit.tri < UINT32_MAX) l->near = (uint32_t)hit.tri;
        if (i > 0) { /* the leaf's far edges' g is the first candidate's:
                      * their plain bound instead */
            for (int j = 0; j < 3; j++) l->g[j] -= lf->g[j];
            l->R += lf->F;
            l->H = 0.0;
        }
        return;
    }
}

/* Builds node k (cell c +- h at depth) from candidate triangles and edges
 * and the far bound F inherited (edges no longer passed down). */
static int build(bctx *x, uint32_t k, const double *c, double h, int depth, const uint32_t *tin,
                 size_t ntin, const uint32_t *ein, size_t nein, const inherited *inh)
{
    dfl_mesh_anchor *a = x->a;
    const double hw = h + a->eps, r = h * sqrt(3.0) + a->eps;
    uint32_t *tl = x->tbuf[depth], *el = x->ebuf[depth];
    size_t nt = 0, ne = 0;
    for (size_t i = 0; i < ntin; i++)
        if (tri_meets_box(a, tin[i], c, hw)) tl[nt++] = tin[i];
    /* the edges dropped here: their field at the centre, kept as a
     * constant vector below (for y in the ball |g(y) - g(c)| <= H r) */
    inherited in = *inh;
    double Fc = in.F, Dmin = INFINITY; /* the cell's whole bound, its nearest edge */
    for (size_t i = 0; i < nein; i++) {
        const bedge *e = a->edge + ein[i];
        const double D = point_seg(c, a->V + 3 * (size_t)e->a, a->V + 3 * (size_t)e->b) - r;
        if (D > KFAR * r) {
            in.F += edge_bound(e, D);
            in.R += edge_hess_bound(e, D) * r;
            edge_field_add(a, e, c, in.g);
            Fc += edge_bound(e, D);
        } else {
            el[ne++] = ein[i];
            Fc += edge_bound(e, D);
        }
        Dmin = fmin(Dmin, D);
    }
    const int split = depth < MAXD && ((nt > TMAX && depth < TDEPTH) ||
                                       (!(Fc * r <= FSPLIT) && (Dmin < KSPLIT * r || depth < FDEPTH)));
    if (!split) return make_leaf(x, k, c, h, tl, nt, el, ne, &in);
    if (a->nnode + 8 > a->maxnode) {
        a->full = 1;
        return 0;
    }
    if (!grow((void **)&a->node, &a->capnode, a->nnode + 8, sizeof *a->node)) return 0;
    const uint32_t first = (uint32_t)a->nnode;
    a->nnode += 8;
    a->node[k] = first;
    const double h2 = h * 0.5;
    for (int i = 0; i < 8; i++) {
        double cc[3];
        for (int j = 0; j < 3; j++) cc[j] = i & (1 << j) ? c[j] + h2 : c[j] - h2;
        if (!build(x, first + (uint32_t)i, cc, h2, depth + 1, tl, nt, el, ne, &in)) return 0;
    }
    return 1;
}

dfl_status dfl_mesh_anchor_new(const double *verts, size_t nverts, const size_t *tris, size_t ntris,
                               const struct dfl_mesh_bvh *bvh, dfl_mesh_anchor **out, dfl_err *err)
{
    dfl_mesh_anchor *a = calloc(1, sizeof *a);
    if (!a) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    a->V = verts;
    a->T = tris;
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t t = 0; t < ntris; t++)
        for (int k = 0; k < 3; k++)
            for (int j = 0; j < 3; j++) {
                lo[j] = fmin(lo[j], tv(a, t, k)[j]);
                hi[j] = fmax(hi[j], tv(a, t, k)[j]);
            }
    double ext = 0.0, vmax = 0.0;
    for (int j = 0; j < 3; j++) {
        a->ctr[j] = 0.5 * (lo[j] + hi[j]);
        ext = fmax(ext, hi[j] - lo[j]);
        vmax = fmax(vmax, fmax(fabs(lo[j]), fabs(hi[j])));
    }
    /* with ntris < 2^23 the caps keep node indices below LEAF_BIT and the
     * list offsets in 32 bits */
    const int small = nverts <= UINT32_MAX && ntris < (1u << 23);
    a->maxnode = small ? 64 * ntris + (1u << 18) : 0;
    a->maxlist = small ? 256 * ntris + (1u << 20) : 0;
    a->half = small ? ext : -1.0; /* edges keep 32-bit vertex indices */
    a->tol = 1e-9 * fmax(ext, vmax);
    a->eps = a->tol;
    a->scale = 2.0 * fmax(ext, vmax);
    bctx x = {a, bvh, {NULL}, {NULL}, NULL, 0};
    int ok = net_edges(a, ntris) && grow((void **)&a->node, &a->capnode, 1, sizeof *a->node);
    uint32_t *t0 = malloc(ntris * sizeof *t0), *e0 = malloc((a->nedge + 1) * sizeof *e0);
    ok = ok && t0 && e0;
    for (int d = 0; d <= MAXD && ok; d++) {
        x.tbuf[d] = malloc(ntris * sizeof *x.tbuf[d]);
        x.ebuf[d] = malloc((a->nedge + 1) * sizeof *x.ebuf[d]);
        ok = x.tbuf[d] && x.ebuf[d];
    }
    if (ok) {
        for (size_t t = 0; t < ntris; t++) t0[t] = (uint32_t)t;
        for (size_t e = 0; e < a->nedge; e++) e0[e] = (uint32_t)e;
        a->nnode = 1;
        ok = a->half > 0.0 && isfinite(a->half) ? build(&x, 0, a->ctr, a->half, 0, t0, ntris, e0, a->nedge, &(inherited){{0.0, 0.0, 0.0}, 0.0, 0.0})
                                        : (a->half = -1.0, a->node[0] = 0, 1);
    }
    if (ok) {
        /* each leaf's anchor on its own: independent, read-only on bvh */
#pragma omp parallel for schedule(dynamic, 64)
        for (long i = 0; i < (long)a->nleaf; i++) {
            aleaf *l = a->leaf + i;
            double c[3];
            memcpy(c, l->c, sizeof c);
            leaf_anchor(a, bvh, l, x.lf + i, c, l->w);
        }
    }
    free(t0);
    free(e0);
    free(x.lf);
    for (int d = 0; d <= MAXD; d++) {
        free(x.tbuf[d]);
        free(x.ebuf[d]);
    }
    if (!ok && a->full) { /* too large for its caps: the traversal alone */
        dfl_mesh_anchor_free(a);
        *out = NULL;
        return DFL_OK;
    }
    if (!ok) {
        dfl_mesh_anchor_free(a);
        return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    }
    *out = a;
    return DFL_OK;
}

