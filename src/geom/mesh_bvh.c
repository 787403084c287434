/* Embree glue for the mesh shape.  Embree prunes in float; every decision
 * that fixes a value is taken in double by dflab's own functions
 * (geom/tridist.h, geom/winding.h), so Embree's precision only costs
 * visits, never accuracy (see the header for the widening). */
#include "geom/mesh_bvh.h"

#include <assert.h>
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <pthread.h>
#include <stdatomic.h>

#include <embree3/rtcore.h>
#include <embree3/rtcore_builder.h>

#include "core/vec.h"
#include "geom/mesh_anchor.h"
#include "geom/winding.h"

/* Relative widening of boxes and radii: 2^-20 is 16 float ulps. */
#define WIDEN 0x1p-20
/* Beyond this coordinate magnitude the float query is not used. */
#define FLOAT_SAFE 1e30

/* A winding cluster: BVH node or leaf (leaf: n > 0 triangles in prim). */
typedef struct wnode {
    double p[3], N[3], A, r;
    double M[9]; /* first moment sum_t A_t n_t (c_t - p)^T, row-major */
    double I2;   /* second moment sum_t int_t |y - p|^2 dA(y) <= A r^2 */
    double rx;   /* max over the cluster's vertices of |v - p| (<= r) */
    double lo[3], hi[3]; /* the box of the cluster's vertices */
    struct wnode *child[2];
    unsigned n;
    unsigned prim[];
} wnode;

struct dfl_mesh_bvh {
    const double *V;
    const size_t *T;
    size_t nt, nv;
    double vmax; /* largest |coordinate| of the mesh */
    RTCDevice dev;
    RTCScene scene;
    RTCBVH bvh;
    wnode *root;
    /* the fast path of the inside test, built by the first query that
     * needs it (anchors_ready), under lock: building it costs ~100x the
     * BVH (0.7 s on Wuson), which a shape built only to be validated, or
     * queried unsigned, never pays */
    dfl_mesh_anchor *anchor;
    pthread_mutex_t lock;
    atomic_int anchors_ready; /* 0: not tried; 1: tried (anchor may be NULL) */
};

static const double *tv(const dfl_mesh_bvh *b, size_t t, int k) { return b->V + 3 * b->T[3 * t + k]; }

/* ---- closest point ---------------------------------------------------- */

static void bounds_cb(const struct RTCBoundsFunctionArguments *args)
{
    const dfl_mesh_bvh *b = args->geometryUserPtr;
    const size_t t = args->primID;
    double lo[3], hi[3];
    for (int j = 0; j < 3; j++) {
        lo[j] = fmin(fmin(tv(b, t, 0)[j], tv(b, t, 1)[j]), tv(b, t, 2)[j]);
        hi[j] = fmax(fmax(tv(b, t, 0)[j], tv(b, t, 1)[j]), tv(b, t, 2)[j]);
    }
    const double w = WIDEN * b->vmax;
    struct RTCBounds *o = args->bounds_o;
    o->lower_x = nextafterf((float)(lo[0] - w), -INFINITY);
    o->lower_y = nextafterf((float)(lo[1] - w), -INFINITY);
    o->lower_z = nextafterf((float)(lo[2] - w), -INFINITY);
    o->upper_x = nextafterf((float)(hi[0] + w), INFINITY);
    o->upper_y = nextafterf((float)(hi[1] + w), INFINITY);
    o->upper_z = nextafterf((float)(hi[2] + w), INFINITY);
}

typedef struct cp_state {
    const dfl_mesh_bvh *b;
    const double *x;
    double pad; /* the widening of the radius */
    dfl_mesh_hit *hit;
} cp_state;

/* Keeps the closer triangle (ties: the smaller index). */
static int consider(const dfl_mesh_bvh *b, const double *x, size_t t, dfl_mesh_hit *hit)
{
    double q[3];
    dfl_tri_feature f;
    double d = dfl_tridist_closest(x, tv(b, t, 0), tv(b, t, 1), tv(b, t, 2), q, &f);
    if (d < hit->d || (d == hit->d && t < hit->tri)) {
        hit->d = d;
        memcpy(hit->q, q, sizeof q);
        hit->tri = t;
        hit->feat = f;
        return 1;
    }
    return 0;
}

static bool query_cb(struct RTCPointQueryFunctionArguments *args)
{
    cp_state *s = args->userPtr;
    if (!consider(s->b, s->x, args->primID, s->hit)) return false;
    args->query->radius = nextafterf((float)(s->hit->d + s->pad), INFINITY);
    return true;
}

void dfl_mesh_bvh_closest(const dfl_mesh_bvh *b, const double *x, dfl_mesh_hit *hit)
{
    dfl_mesh_bvh_closest_hint(b, x, SIZE_MAX, hit);
}

/* The hint's distance starts the radius small, so Embree prunes from the
 * first node on; the minimum and its tie rule do not depend on the order
 * in which triangles are considered. */
void dfl_mesh_bvh_closest_hint(const dfl_mesh_bvh *b, const double *x, size_t t0, dfl_mesh_hit *hit)
{
    hit->d = INFINITY;
    hit->tri = SIZE_MAX;
    hit->feat = DFL_TRI_FACE;
    hit->q[0] = hit->q[1] = hit->q[2] = NAN;
    const double xm = fmax(fmax(fabs(x[0]), fabs(x[1])), fabs(x[2]));
    if (!(isfinite(x[0]) && isfinite(x[1]) && isfinite(x[2]))) { /* fmax drops NaN: test each */
        hit->d = NAN;
        return;
    }
    if (xm > FLOAT_SAFE || b->vmax > FLOAT_SAFE) {
        for (size_t t = 0; t < b->nt; t++) consider(b, x, t, hit);
        return;
    }
    cp_state s = {b, x, 2.0 * WIDEN * (xm + b->vmax), hit};
    float r0 = INFINITY;
    if (t0 < b->nt) {
        consider(b, x, t0, hit);
        r0 = nextafterf((float)(hit->d + s.pad), INFINITY);
    }
    struct RTCPointQuery q = {(float)x[0], (float)x[1], (float)x[2], 0.0f, r0};
    struct RTCPointQueryContext ctx;
    rtcInitPointQueryContext(&ctx);
    rtcPointQuery(b->scene, &q, &ctx, query_cb, &s);
    assert(hit->tri != SIZE_MAX);
}

/* ---- winding clusters ---------------------------------------------------- */

static void *create_node(RTCThreadLocalAllocator alloc, unsigned int n, void *user)
{
    (void)n;
    (void)user;
    wnode *w = rtcThreadLocalAlloc(alloc, sizeof(wnode), 16);
    if (w) memset(w, 0, sizeof *w);
    return w;
}

static void set_children(void *node, void **children, unsigned int n, void *user)
{
    (void)user;
    wnode *w = node;
    for (unsigned i = 0; i < n && i < 2; i++) w->child[i] = children[i];
}

static void set_bounds(void *node, const struct RTCBounds **bounds, unsigned int n, void *user)
{
    (void)node;
    (void)bounds;
    (void)n;
    (void)user;
}

static void *create_leaf(RTCThreadLocalAllocator alloc, const struct RTCBuildPrimitive *prims,
                         size_t n, void *user)
{
    (void)user;
    wnode *w = rtcThreadLocalAlloc(alloc, sizeof(wnode) + n * sizeof(unsigned), 16);
    if (!w) return NULL;
    memset(w, 0, sizeof *w);
    w->n = (unsigned)n;
    for (size_t i = 0; i < n; i++) w->prim[i] = prims[i].primID;
    return w;
}

/* max over the vertices of w's subtree of |v - P|. */
static double subtree_radius(const dfl_mesh_bvh *b, const wnode *w, const double *P)
{
    if (w->n == 0)
        return fmax(subtree_radius(b, w->child[0], P), subtree_radius(b, w->child[1], P));
    double r = 0.0;
    for (unsigned i = 0; i < w->n; i++)
        for (int k = 0; k < 3; k++) {
            const double *v = tv(b, w->prim[i], k);
            double d[3] = {v[0] - P[0], v[1] - P[1], v[2] - P[2]};
            r = fmax(r, dfl_vec3_norm(d));
        }
    return r;
}

/* Fills p, N, A, r, M, I2, rx and the box bottom-up; returns 0 if a node
 * is missing (out of memory inside Embree). */
static int cluster_data(const dfl_mesh_bvh *b, wnode *w, int depth)
{
    if (!w || depth >= DFL_MESH_BVH_STACK / 2) return 0;
    double P[3] = {0, 0, 0}, N[3] = {0, 0, 0}, A = 0.0, r = 0.0, I2 = 0.0;
    double M[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    if (w->n > 0) {
        for (unsigned i = 0; i < w->n; i++) {
            const size_t t = w->prim[i];
            const double *a = tv(b, t, 0), *bb = tv(b, t, 1), *c = tv(b, t, 2);
            double e1[3], e2[3], n[3];
            for (int j = 0; j < 3; j++) {
                e1[j] = bb[j] - a[j];
                e2[j] = c[j] - a[j];
            }
            dfl_vec3_cross(e1, e2, n);
            const double at = 0.5 * dfl_vec3_norm(n);
            for (int j = 0; j < 3; j++) {
                N[j] += 0.5 * n[j];
                P[j] += at * (a[j] + bb[j] + c[j]) / 3.0;
                for (int k = 0; k < 3; k++) {
                    lo[j] = fmin(lo[j], tv(b, t, k)[j]);
                    hi[j] = fmax(hi[j], tv(b, t, k)[j]);
                }
            }
            A += at;
        }
        for (int j = 0; j < 3; j++) P[j] = A > 0.0 ? P[j] / A : 0.5 * (lo[j] + hi[j]);
        for (unsigned i = 0; i < w->n; i++) {
            const size_t t = w->prim[i];
            const double *a = tv(b, t, 0), *bb = tv(b, t, 1), *c = tv(b, t, 2);
            double e1[3], e2[3], n[3];
            for (int j = 0; j < 3; j++) {
                e1[j] = bb[j] - a[j];
                e2[j] = c[j] - a[j];
            }
            dfl_vec3_cross(e1, e2, n); /* 2 A_t n_t */
            for (int j = 0; j < 3; j++)
                for (int k = 0; k < 3; k++)
                    M[3 * j + k] += 0.5 * n[j] * ((a[k] + bb[k] + c[k]) / 3.0 - P[k]);
            /* A_t (|c_t - P|^2 + sum_i |v_i - c_t|^2 / 12) */
            double ct[3], s2 = 0.0, cp = 0.0;
            for (int j = 0; j < 3; j++) {
                ct[j] = (a[j] + bb[j] + c[j]) / 3.0;
                cp += (ct[j] - P[j]) * (ct[j] - P[j]);
            }
            for (int k = 0; k < 3; k++)
                for (int j = 0; j < 3; j++) s2 += (tv(b, t, k)[j] - ct[j]) * (tv(b, t, k)[j] - ct[j]);
            I2 += 0.5 * dfl_vec3_norm(n) * (cp + s2 / 12.0);
            for (int k = 0; k < 3; k++) {
                const double *v = tv(b, t, k);
                double d[3] = {v[0] - P[0], v[1] - P[1], v[2] - P[2]};
                r = fmax(r, dfl_vec3_norm(d));
            }
        }
    } else {
        for (int i = 0; i < 2; i++)
            if (!cluster_data(b, w->child[i], depth + 1)) return 0;
        const wnode *c0 = w->child[0], *c1 = w->child[1];
        A = c0->A + c1->A;
        for (int j = 0; j < 3; j++) {
            N[j] = c0->N[j] + c1->N[j];
            P[j] = A > 0.0 ? (c0->A * c0->p[j] + c1->A * c1->p[j]) / A : 0.5 * (c0->p[j] + c1->p[j]);
        }
        for (int i = 0; i < 2; i++) {
            const wnode *c = w->child[i];
            double d[3] = {c->p[0] - P[0], c->p[1] - P[1], c->p[2] - P[2]};
            r = fmax(r, dfl_vec3_norm(d) + c->r);
            /* parallel axes: int (y - p_i) dA = 0 over child i */
            I2 += c->I2 + c->A * dfl_vec3_dot(d, d);
            for (int j = 0; j < 3; j++) {
                lo[j] = fmin(lo[j], c->lo[j]);
                hi[j] = fmax(hi[j], c->hi[j]);
            }
            /* moments move: sum A n (c - P)^T = M_i + N_i (p_i - P)^T */
            for (int j = 0; j < 3; j++)
                for (int k = 0; k < 3; k++) M[3 * j + k] += c->M[3 * j + k] + c->N[j] * d[k];
        }
    }
    memcpy(w->p, P, sizeof P);
    memcpy(w->N, N, sizeof N);
    memcpy(w->M, M, sizeof M);
    memcpy(w->lo, lo, sizeof lo);
    memcpy(w->hi, hi, sizeof hi);
    w->A = A;
    w->r = r;
    w->I2 = I2;
    w->rx = subtree_radius(b, w, P);
    return 1;
}

/* The first-order far field of cluster n at x (the header's expansion),
 * d = p - x, R = |d| > 0. */
static double far_field(const wnode *n, const double *d, double R)
{
    /* K(p) . N + sum_jk J_jk M_jk, J = (I - 3 u u^T) / R^3, u = (p - x)/R */
    const double u[3] = {d[0] / R, d[1] / R, d[2] / R};
    const double *M = n->M;
    double uMu = 0.0;
    for (int j = 0; j < 3; j++)
        for (int k = 0; k < 3; k++) uMu += u[j] * M[3 * j + k] * u[k];
    return (dfl_vec3_dot(n->N, d) / R + (M[0] + M[4] + M[8] - 3.0 * uMu) / R) / (4.0 * DFL_PI * R * R);
}

/* Double-checked: the acquire load pairs with the release store, so a
 * thread that sees 1 sees the finished octree.  A failed build (out of
 * memory) leaves NULL: the traversal answers alone, the same answers. */
const dfl_mesh_anchor *dfl_mesh_bvh_anchors(const dfl_mesh_bvh *cb)
{
    dfl_mesh_bvh *b = (dfl_mesh_bvh *)cb; /* the lazy member only */
    if (atomic_load_explicit(&b->anchors_ready, memory_order_acquire)) return b->anchor;
    pthread_mutex_lock(&b->lock);
    if (!atomic_load_explicit(&b->anchors_ready, memory_order_relaxed)) {
        dfl_mesh_anchor *a = NULL;
        if (dfl_mesh_anchor_new(b->V, b->nv, b->T, b->nt, b, &a, NULL) != DFL_OK) a = NULL;
        b->anchor = a;
        atomic_store_explicit(&b->anchors_ready, 1, memory_order_release);
    }
    pthread_mutex_unlock(&b->lock);
    return b->anchor;
}

static double leaf_exact(const dfl_mesh_bvh *b, const wnode *n, const double *x)
{
    double w = 0.0;
    for (unsigned i = 0; i < n->n; i++) {
        const size_t t = n->prim[i];
        w += dfl_winding_triangle(x, tv(b, t, 0), tv(b, t, 1), tv(b, t, 2));
    }
    return w;
}

double dfl_mesh_bvh_winding(const dfl_mesh_bvh *b, const double *x, double beta, double *bound)
{
    const wnode *stack[DFL_MESH_BVH_STACK];
    int top = 0;
    stack[top++] = b->root;
    double w = 0.0, B = 0.0;
    while (top > 0) {
        const wnode *n = stack[--top];
        double d[3] = {n->p[0] - x[0], n->p[1] - x[1], n->p[2] - x[2]};
        const double R = dfl_vec3_norm(d);
        if (R > beta * n->r) {
            w += far_field(n, d, R);
            const double g = R - n->r;
            B += 3.0 * n->A * n->r * n->r / (4.0 * DFL_PI * g * g * g * g);
        } else if (n->n > 0) {
            for (unsigned i = 0; i < n->n; i++) {
                const size_t t = n->prim[i];
                w += dfl_winding_triangle(x, tv(b, t, 0), tv(b, t, 1), tv(b, t, 2));
            }
        } else {
            assert(top + 2 <= DFL_MESH_BVH_STACK);
            stack[top++] = n->child[1];
            stack[top++] = n->child[0];
        }
    }
    if (bound) *bound = B;
    return w;
}

/* ---- certified inside test: one adaptive traversal ---------------------- */

/* A cluster of the frontier: its far-field value and bound (key of the
 * max-heap), or key = +inf for a cluster whose bound is not used (x within
 * its ball and its box, or a bound above OPEN_ALWAYS) and whose value is
 * then not in the sum. */
typedef struct wfront {
    double key, w;
    const wnode *n;
} wfront;

/* Frontier capacity (on the stack, 24 bytes each).  When it would be
 * exceeded the exact sum decides (a slow path, never a different answer;
 * on 100000 of the bench's Wuson points the largest frontier held 593
 * and none fell back). */
#define FRONT 1024
/* Bounds above this are never added to the running sums: such a cluster
 * is opened before any decision.  This keeps every term added to (and
 * later subtracted from) W and B below about 1 in magnitude, so the
 * rounding of the running sums stays near 1e-16 per operation, far below
 * the 1e-9 margin (a term of 1e10 subtracted again would leave 1e-6). */
#define OPEN_ALWAYS 1.0

static void heap_push(wfront *h, int *nh, wfront e)
{
    int i = (*nh)++;
    while (i > 0) {
        const int p = (i - 1) / 2;
        if (h[p].key >= e.key) break;
        h[i] = h[p];
        i = p;
    }
    h[i] = e;
}

static wfront heap_pop(wfront *h, int *nh)
{
    const wfront top = h[0], last = h[--*nh];
    int i = 0;
    for (;;) {
        int c = 2 * i + 1;
        if (c >= *nh) break;
        if (c + 1 < *nh && h[c + 1].key > h[c].key) c++;
        if (h[c].key <= last.key) break;
        h[i] = h[c];
        i = c;
    }
    if (*nh > 0) h[i] = last;
    return top;
}

/* The remainder bound of the adaptive traversal, sharper than the
 * ladder's 3 A r^2 / (4 pi (R - r)^4) and proved the same way.  Per point
 * y of the cluster, Taylor's theorem with integral remainder gives
 *   |n . K(y) - n . K(p) - n . DK(p) (y - p)| <= 1/2 sup |D^2 K| |y - p|^2
 * with the sup over the segment [p, y], and |D^2 K| <= 3! / dist^4
 * (header).  Every such segment lies in the ball of radius rx about p
 * (rx: the farthest vertex; the triangles are the vertices' convex hulls)
 * and in the box of the vertices (p, a convex combination of the
 * triangles' centroids, lies in it), both convex, so dist >= g =
 * max(R - rx, dist(x, box)).  Integrating over the cluster,
 *   |error| <= 3 I2 / (4 pi g^4),   I2 = sum_t int_t |y - p|^2 dA
 *                                       = sum_t A_t (|c_t - p|^2 + sum_i |v_i - c_t|^2 / 12)
 * (a triangle's second moment about its centroid), and I2 <= A r^2,
 * R - rx >= R - r.  Usable when g > 0.  The rounding of I2, rx and the box
 * (relative 1e-15) moves the bound far less than the 1e-9 margin.
 * The distance from x to the surface (the unsigned distance the shape
 * has already computed) is NOT a valid g: the segments [p, y] leave the
 * surface and may pass closer to x than any triangle does.
 * Also tried on Wuson and left out: the second-order term of Barill et
 * al. with the remainder 4 rx I2 / (4 pi g^5) (12 % fewer clusters
 * opened, no faster: the extra 18 moments cost what the clusters save),
 * and far fields of single triangles inside opened leaves (slower: more
 * heap entries than exact triangles saved). */
static double tight_bound(const wnode *n, const double *x, double R)
{
    double e = 0.0;
    for (int j = 0; j < 3; j++) {
        const double lo = n->lo[j] - x[j], hi = x[j] - n->hi[j];
        const double t = lo > hi ? lo : hi;
        if (t > 0.0) e += t * t;
    }
    const double gb = sqrt(e);
    double g = R - n->rx;
    if (gb > g) g = gb;
    if (!(g > 0.0)) return INFINITY; /* NaN x lands here too */
    const double g2 = g * g;
    return (3.0 / (4.0 * DFL_PI)) * n->I2 / (g2 * g2);
}

/* far_field with one division (the traversal's decisions do not depend on
 * the last bits of a far field: the bounds and the margin cover them). */
static double far_field_fast(const wnode *n, const double *d, double R)
{
    const double *M = n->M;
    double dMd = 0.0;
    for (int j = 0; j < 3; j++) dMd += d[j] * (M[3 * j] * d[0] + M[3 * j + 1] * d[1] + M[3 * j + 2] * d[2]);
    const double iR = 1.0 / R, iR2 = iR * iR;
    return (n->N[0] * d[0] + n->N[1] * d[1] + n->N[2] * d[2] + M[0] + M[4] + M[8] - 3.0 * dMd * iR2) *
           (iR * iR2 * (1.0 / (4.0 * DFL_PI)));
}

/* The best-first traversal behind dfl_mesh_bvh_inside and
 * dfl_mesh_bvh_winding_within.  At every step
 *   w(x) = W + sum over the frontier of (exact - far field) of its clusters
 *          + the exact values of the unused (key = inf) clusters,
 * and every finite-key term is within its bound, so with no unused cluster
 * left |w(x) - W| <= B.  It stops when that holds and either (sign)
 * |W - 1/2| > B + 1e-9 (*state = 1), or (!sign) B <= tol (*state = 1);
 * otherwise it opens the frontier cluster of largest bound (best first:
 * the bound it removes is the largest available); a leaf is replaced by
 * its exact sum.  The frontier starts from a depth-first pass (PRE_BOUND)
 * rather than from the root alone.  *state = 0 when everything is exact and the rule still
 * does not hold, -1 when the frontier would exceed FRONT. */
/* Restores the heap order below i. */
static void sift_down(wfront *h, int nh, int i)
{
    const wfront v = h[i];
    for (;;) {
        int c = 2 * i + 1;
        if (c >= nh) break;
        if (c + 1 < nh && h[c + 1].key > h[c].key) c++;
        if (h[c].key <= v.key) break;
        h[i] = h[c];
        i = c;
    }
    h[i] = v;
}

/* The first pass's opening threshold: on Wuson's bench points a pass
 * that opens every cluster above 0.01 and then refines best first took
 * about 2/3 of the time of best first from the root (the heap's cost per
 * cluster is then paid only where the decision is close); 0.005 to 0.04
 * were within 10 % of it. */
#define PRE_BOUND 0.01

static double adaptive(const dfl_mesh_bvh *b, const double *x, int sign, double tol, double *bound,
                       int *state)
{
    wfront h[FRONT];
    int nh = 0, unused = 0;
    double W = 0.0, B = 0.0;
    *state = 0;
    /* the first pass, depth first without the heap: every cluster whose
     * bound is unusable or above PRE_BOUND is opened (a leaf summed
     * exactly), the others form the frontier, made a heap at once */
    const wnode *stack[DFL_MESH_BVH_STACK];
    int top = 0;
    stack[top++] = b->root;
    while (top > 0) {
        const wnode *n = stack[--top];
        double d[3] = {n->p[0] - x[0], n->p[1] - x[1], n->p[2] - x[2]};
        const double R = dfl_vec3_norm(d);
        const double bn = tight_bound(n, x, R);
        if (bn <= PRE_BOUND) {
            if (nh == FRONT) {
                *state = -1;
                *bound = INFINITY;
                return W;
            }
            h[nh] = (wfront){bn, far_field_fast(n, d, R), n};
            W += h[nh].w;
            B += bn;
            nh++;
        } else if (n->n > 0) {
            W += leaf_exact(b, n, x);
        } else {
            assert(top + 2 <= DFL_MESH_BVH_STACK);
            stack[top++] = n->child[1];
            stack[top++] = n->child[0];
        }
    }
    for (int i = nh / 2 - 1; i >= 0; i--) sift_down(h, nh, i);
    /* then best first */
    const wnode *open[2] = {NULL, NULL};
    int nopen = 0;
    for (;;) {
        if (nh + nopen > FRONT) {
            *state = -1;
            break;
        }
        for (int i = 0; i < nopen; i++) {
            const wnode *n = open[i];
            double d[3] = {n->p[0] - x[0], n->p[1] - x[1], n->p[2] - x[2]};
            const double R = dfl_vec3_norm(d);
            wfront e = {INFINITY, 0.0, n};
            const double bn = tight_bound(n, x, R);
            if (bn <= OPEN_ALWAYS) {
                e.key = bn;
                e.w = far_field_fast(n, d, R);
                W += e.w;
                B += bn;
            }
            unused += e.key == INFINITY;
            heap_push(h, &nh, e);
        }
        if (unused == 0 && (sign ? fabs(W - 0.5) > B + 1e-9 : B <= tol)) {
            *state = 1;
            break;
        }
        if (nh == 0) {
            B = 0.0; /* everything exact: only the rounding of the subtractions was left */
            break;
        }
        const wfront e = heap_pop(h, &nh);
        if (e.key == INFINITY) {
            unused--;
        } else {
            W -= e.w;
            B -= e.key;
        }
        if (e.n->n > 0) {
            W += leaf_exact(b, e.n, x);
            nopen = 0;
        } else {
            open[0] = e.n->child[0];
            open[1] = e.n->child[1];
            nopen = 2;
        }
    }
    *bound = unused == 0 ? fmax(B, 0.0) : INFINITY;
    return W;
}

/* One depth-first pass: a cluster's far field is used when its bound
 * (tight_bound) is at most its share tol A_n / A_root of the budget, so
 * the bounds add up to at most tol without a heap or a second pass. */
double dfl_mesh_bvh_winding_budget(const dfl_mesh_bvh *b, const double *x, double tol, double *bound)
{
    const wnode *stack[DFL_MESH_BVH_STACK];
    int top = 0;
    stack[top++] = b->root;
    const double per_area = b->root->A > 0.0 ? tol / b->root->A : 0.0;
    double W = 0.0, B = 0.0;
    while (top > 0) {
        const wnode *n = stack[--top];
        double d[3] = {n->p[0] - x[0], n->p[1] - x[1], n->p[2] - x[2]};
        const double R = dfl_vec3_norm(d);
        const double bn = tight_bound(n, x, R);
        if (bn <= per_area * n->A) {
            W += far_field_fast(n, d, R);
            B += bn;
        } else if (n->n > 0) {
            W += leaf_exact(b, n, x);
        } else {
            assert(top + 2 <= DFL_MESH_BVH_STACK);
            stack[top++] = n->child[1];
            stack[top++] = n->child[0];
        }
    }
    if (bound) *bound = B;
    return W;
}

double dfl_mesh_bvh_winding_within(const dfl_mesh_bvh *b, const double *x, double tol,
                                   double *bound)
{
    int state;
    double B;
    const double w = adaptive(b, x, 0, tol, &B, &state);
    if (state < 0) {
        if (bound) *bound = 0.0;
        return dfl_winding_brute(b->V, b->T, b->nt, x);
    }
    if (bound) *bound = B;
    return w;
}

/* When the traversal cannot decide, the exact sum over every triangle in
 * index order does, as the ladder did: the answer is the exact sum's. */
int dfl_mesh_bvh_inside(const dfl_mesh_bvh *b, const double *x)
{
    int in;
    const dfl_mesh_anchor *a = dfl_mesh_bvh_anchors(b);
    if (a && dfl_mesh_anchor_decide(a, x, &in)) return in;
    return dfl_mesh_bvh_inside_traversal(b, x);
}

int dfl_mesh_bvh_inside_traversal(const dfl_mesh_bvh *b, const double *x)
{
    int state;
    double B;
    const double w = adaptive(b, x, 1, 0.0, &B, &state);
    if (state > 0) return w > 0.5;
    return dfl_winding_brute(b->V, b->T, b->nt, x) > 0.5;
}

/* ---- build ------------------------------------------------------------- */

void dfl_mesh_bvh_free(dfl_mesh_bvh *b)
{
    if (!b) return;
    dfl_mesh_anchor_free(b->anchor);
    pthread_mutex_destroy(&b->lock);
    if (b->bvh) rtcReleaseBVH(b->bvh);
    if (b->scene) rtcReleaseScene(b->scene);
    if (b->dev) rtcReleaseDevice(b->dev);
    free(b);
}

static dfl_status embree_fail(dfl_mesh_bvh *b, const char *what, dfl_err *err)
{
    enum RTCError e = b->dev ? rtcGetDeviceError(b->dev) : RTC_ERROR_UNKNOWN;
    dfl_mesh_bvh_free(b);
    if (e == RTC_ERROR_OUT_OF_MEMORY) return dfl_err_set(err, DFL_E_NOMEM, "embree: %s: out of memory", what);
    return dfl_err_set(err, DFL_E_NUMERIC, "embree: %s failed (error %d)", what, (int)e);
}

dfl_status dfl_mesh_bvh_new(const double *verts, size_t nverts, const size_t *tris, size_t ntris,
                            dfl_mesh_bvh **out, dfl_err *err)
{
    if (ntris == 0) return dfl_err_set(err, DFL_E_INPUT, "mesh has no triangles");
    if (ntris >= UINT32_MAX)
        return dfl_err_set(err, DFL_E_INPUT, "mesh has %zu triangles (at most %u)", ntris,
                           UINT32_MAX - 1);
    dfl_mesh_bvh *b = calloc(1, sizeof *b);
    if (!b) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    if (pthread_mutex_init(&b->lock, NULL) != 0) {
        free(b);
        return dfl_err_set(err, DFL_E_NOMEM, "out of memory (mutex)");
    }
    atomic_init(&b->anchors_ready, 0);
    b->V = verts;
    b->T = tris;
    b->nt = ntris;
    b->nv = nverts;
    for (size_t i = 0; i < 3 * nverts; i++) b->vmax = fmax(b->vmax, fabs(verts[i]));
    b->dev = rtcNewDevice(NULL);
    if (!b->dev) return embree_fail(b, "device", err);
    b->scene = rtcNewScene(b->dev);
    RTCGeometry g = rtcNewGeometry(b->dev, RTC_GEOMETRY_TYPE_USER);
    if (!b->scene || !g) return embree_fail(b, "scene", err);
    rtcSetGeometryUserPrimitiveCount(g, (unsigned)ntris);
    rtcSetGeometryUserData(g, b);
    rtcSetGeometryBoundsFunction(g, bounds_cb, b);
    rtcCommitGeometry(g);
    rtcAttachGeometry(b->scene, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(b->scene);
    if (rtcGetDeviceError(b->dev) != RTC_ERROR_NONE) return embree_fail(b, "scene build", err);

    /* RTCBuildPrimitive is declared 32-byte aligned (RTC_ALIGN(32)) and
     * malloc promises only 16: a store through a 16-aligned pointer is
     * undefined (UBSan names it), so the array comes from aligned_alloc,
     * whose size sizeof *prims, a multiple of 32, keeps a valid multiple. */
    _Static_assert(sizeof(struct RTCBuildPrimitive) % 32 == 0, "RTCBuildPrimitive size");
    struct RTCBuildPrimitive *prims = aligned_alloc(32, ntris * sizeof *prims);
    if (!prims) {
        dfl_mesh_bvh_free(b);
        return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    }
    for (size_t t = 0; t < ntris; t++) {
        float lo[3], hi[3];
        for (int j = 0; j < 3; j++) {
            lo[j] = (float)fmin(fmin(tv(b, t, 0)[j], tv(b, t, 1)[j]), tv(b, t, 2)[j]);
            hi[j] = (float)fmax(fmax(tv(b, t, 0)[j], tv(b, t, 1)[j]), tv(b, t, 2)[j]);
        }
        prims[t] = (struct RTCBuildPrimitive){lo[0], lo[1], lo[2], 0, hi[0], hi[1], hi[2],
                                              (unsigned)t};
    }
    b->bvh = rtcNewBVH(b->dev);
    struct RTCBuildArguments a = rtcDefaultBuildArguments();
    a.buildQuality = RTC_BUILD_QUALITY_MEDIUM;
    a.maxBranchingFactor = 2;
    a.maxDepth = DFL_MESH_BVH_STACK / 2 - 2;
    a.minLeafSize = 1;
    a.maxLeafSize = 8;
    a.bvh = b->bvh;
    a.primitives = prims;
    a.primitiveCount = ntris;
    a.primitiveArrayCapacity = ntris;
    a.createNode = create_node;
    a.setNodeChildren = set_children;
    a.setNodeBounds = set_bounds;
    a.createLeaf = create_leaf;
    b->root = b->bvh ? rtcBuildBVH(&a) : NULL;
    free(prims);
    if (!b->root || !cluster_data(b, b->root, 0)) return embree_fail(b, "winding BVH", err);
    *out = b;
    return DFL_OK;
}
