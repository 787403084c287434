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

#include <embree3/rtcore.h>
#include <embree3/rtcore_builder.h>

#include "core/vec.h"
#include "geom/winding.h"

/* Relative widening of boxes and radii: 2^-20 is 16 float ulps. */
#define WIDEN 0x1p-20
/* Beyond this coordinate magnitude the float query is not used. */
#define FLOAT_SAFE 1e30

/* A winding cluster: BVH node or leaf (leaf: n > 0 triangles in prim). */
typedef struct wnode {
    double p[3], N[3], A, r;
    double M[9]; /* first moment sum_t A_t n_t (c_t - p)^T, row-major */
    struct wnode *child[2];
    unsigned n;
    unsigned prim[];
} wnode;

struct dfl_mesh_bvh {
    const double *V;
    const size_t *T;
    size_t nt;
    double vmax; /* largest |coordinate| of the mesh */
    RTCDevice dev;
    RTCScene scene;
    RTCBVH bvh;
    wnode *root;
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
    struct RTCPointQuery q = {(float)x[0], (float)x[1], (float)x[2], 0.0f, INFINITY};
    struct RTCPointQueryContext ctx;
    rtcInitPointQueryContext(&ctx);
    cp_state s = {b, x, 2.0 * WIDEN * (xm + b->vmax), hit};
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

/* Fills p, N, A, r bottom-up; returns 0 if a node is missing (out of memory
 * inside Embree). */
static int cluster_data(const dfl_mesh_bvh *b, wnode *w, int depth)
{
    if (!w || depth >= DFL_MESH_BVH_STACK / 2) return 0;
    double P[3] = {0, 0, 0}, N[3] = {0, 0, 0}, A = 0.0, r = 0.0;
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
            /* moments move: sum A n (c - P)^T = M_i + N_i (p_i - P)^T */
            for (int j = 0; j < 3; j++)
                for (int k = 0; k < 3; k++) M[3 * j + k] += c->M[3 * j + k] + c->N[j] * d[k];
        }
    }
    memcpy(w->p, P, sizeof P);
    memcpy(w->N, N, sizeof N);
    memcpy(w->M, M, sizeof M);
    w->A = A;
    w->r = r;
    return 1;
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
            /* K(p) . N + sum_jk J_jk M_jk, J = (I - 3 u u^T) / R^3, u = (p - x)/R */
            const double u[3] = {d[0] / R, d[1] / R, d[2] / R};
            const double *M = n->M;
            double uMu = 0.0;
            for (int j = 0; j < 3; j++)
                for (int k = 0; k < 3; k++) uMu += u[j] * M[3 * j + k] * u[k];
            w += (dfl_vec3_dot(n->N, d) / R + (M[0] + M[4] + M[8] - 3.0 * uMu) / R) / (4.0 * DFL_PI * R * R);
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

int dfl_mesh_bvh_inside(const dfl_mesh_bvh *b, const double *x)
{
    /* a ladder of opening ratios: doubling beta makes the bound about 10
     * times smaller (r^2 / R^4 per cluster) at about twice the cost; on
     * Wuson about half of the points are decided on the first rung and 99 %
     * by the second */
    static const double betas[] = {DFL_MESH_WINDING_BETA, 2 * DFL_MESH_WINDING_BETA,
                                   4 * DFL_MESH_WINDING_BETA};
    for (size_t k = 0; k < sizeof betas / sizeof *betas; k++) {
        double B;
        const double w = dfl_mesh_bvh_winding(b, x, betas[k], &B);
        if (fabs(w - 0.5) > B + 1e-9) return w > 0.5;
    }
    return dfl_winding_brute(b->V, b->T, b->nt, x) > 0.5;
}

/* ---- build ------------------------------------------------------------- */

void dfl_mesh_bvh_free(dfl_mesh_bvh *b)
{
    if (!b) return;
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
    b->V = verts;
    b->T = tris;
    b->nt = ntris;
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

    struct RTCBuildPrimitive *prims = malloc(ntris * sizeof *prims);
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
