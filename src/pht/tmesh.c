/* Hierarchical T-mesh (tmesh.h).
 *
 * Cells and vertices live on an integer lattice of 2^30 steps per axis, so
 * positions compare exactly and a vertex is found by its key in a hash
 * table.  Classification (after each refinement) looks at the leaves in the
 * 2^dim orthants around each vertex (one tree descent each, with the
 * orthant's signs breaking ties on cell faces):
 *   - base iff the vertex is a corner of every leaf around it.  In 2D this
 *     is the paper's rule (boundary or valency 4: a boundary vertex is always
 *     a corner of the cells touching it, and an interior vertex with edges in
 *     all four directions cannot lie inside a cell's edge).  In 3D it is the
 *     paper's rule read as "crossing in every coordinate plane": boundary-
 *     edge vertices and crossing vertices of a boundary facet are corners of
 *     all their cells, and an interior vertex inside the face of some leaf
 *     (even with six edges from the cells on the other side) is determined by
 *     that face's polynomial and cannot carry free data.
 *   - otherwise hanging on the edge / face of the largest such leaf.
 */
#include "pht/tmesh.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define LAT ((uint32_t)1 << DFL_TMESH_BITS)
#define NONE SIZE_MAX

typedef struct tnode {
    uint32_t lo[3], sz[3];
    int level, split_axis, nchild;
    size_t parent, child;
    size_t corner[8];
} tnode;

typedef struct tvert {
    uint32_t key[3];
    int kind, axis;
    size_t dep[4];
    size_t owner;
} tvert;

struct dfl_tmesh {
    int dim;
    double lo[3], hi[3];
    tnode *cell;
    size_t ncell, ccap;
    tvert *vert;
    size_t nvert, vcap;
    size_t *hash;   /* vertex ids, NONE = empty; hcap a power of 2 */
    size_t hcap;
    size_t *leaf, nleaf;
    size_t *order, norder;
    size_t nbase;
};

DFL_NAMES_DEFINE(dfl_pht_split, DFL_PHT_SPLIT_LIST, DFL_PHT_SPLIT_COUNT, dfl_pht_split_names,
                 dfl_pht_split_name, dfl_pht_split_parse, "split")

static const char *const vertex_kind_names[DFL_TMESH_VERTEX_KIND_COUNT] = {
    DFL_TMESH_VERTEX_KIND_LIST(DFL_NAMES_NAME)};

const char *dfl_tmesh_vertex_kind_name(dfl_tmesh_vertex_kind k)
{
    return dfl_names_at(vertex_kind_names, DFL_TMESH_VERTEX_KIND_COUNT, (int)k);
}

static size_t key_hash(const uint32_t *k)
{
    uint64_t h = (uint64_t)k[0] * 0x9E3779B97F4A7C15ull;
    h ^= (uint64_t)k[1] * 0xC2B2AE3D27D4EB4Full + (h >> 29);
    h ^= (uint64_t)k[2] * 0x165667B19E3779F9ull + (h >> 31);
    h ^= h >> 33;
    h *= 0xFF51AFD7ED558CCDull;
    h ^= h >> 33;
    return (size_t)h;
}

static size_t hash_find(const dfl_tmesh *m, const uint32_t *k)
{
    size_t mask = m->hcap - 1;
    for (size_t i = key_hash(k) & mask;; i = (i + 1) & mask) {
        size_t v = m->hash[i];
        if (v == NONE) return NONE;
        const uint32_t *q = m->vert[v].key;
        if (q[0] == k[0] && q[1] == k[1] && q[2] == k[2]) return v;
    }
}

static int hash_grow(dfl_tmesh *m)
{
    size_t cap = m->hcap ? 2 * m->hcap : 64;
    size_t *h = malloc(cap * sizeof *h);
    if (!h) return -1;
    for (size_t i = 0; i < cap; i++) h[i] = NONE;
    for (size_t v = 0; v < m->nvert; v++) {
        size_t i = key_hash(m->vert[v].key) & (cap - 1);
        while (h[i] != NONE) i = (i + 1) & (cap - 1);
        h[i] = v;
    }
    free(m->hash);
    m->hash = h;
    m->hcap = cap;
    return 0;
}

/* The vertex at key k, created if new; NONE on allocation failure. */
static size_t vert_get(dfl_tmesh *m, const uint32_t *k)
{
    size_t v = hash_find(m, k);
    if (v != NONE) return v;
    if (m->nvert == m->vcap) {
        size_t cap = m->vcap ? 2 * m->vcap : 64;
        tvert *nv = realloc(m->vert, cap * sizeof *nv);
        if (!nv) return NONE;
        m->vert = nv;
        m->vcap = cap;
    }
    if (2 * (m->nvert + 1) > m->hcap && hash_grow(m) != 0) return NONE;
    v = m->nvert++;
    tvert *t = &m->vert[v];
    memcpy(t->key, k, sizeof t->key);
    t->kind = DFL_TMESH_BASE;
    t->axis = -1;
    t->owner = NONE;
    for (int i = 0; i < 4; i++) t->dep[i] = NONE;
    size_t i = key_hash(k) & (m->hcap - 1);
    while (m->hash[i] != NONE) i = (i + 1) & (m->hcap - 1);
    m->hash[i] = v;
    return v;
}

static int cells_reserve(dfl_tmesh *m, size_t extra)
{
    if (m->ncell + extra <= m->ccap) return 0;
    size_t cap = m->ccap ? m->ccap : 16;
    while (cap < m->ncell + extra) cap *= 2;
    tnode *c = realloc(m->cell, cap * sizeof *c);
    if (!c) return -1;
    m->cell = c;
    m->ccap = cap;
    return 0;
}

/* Corner vertices of cell id; -1 on allocation failure. */
static int cell_corners(dfl_tmesh *m, size_t id)
{
    int nc = 1 << m->dim;
    for (int c = 0; c < nc; c++) {
        uint32_t k[3] = {0, 0, 0};
        for (int j = 0; j < m->dim; j++)
            k[j] = m->cell[id].lo[j] + ((c >> j) & 1 ? m->cell[id].sz[j] : 0);
        size_t v = vert_get(m, k);
        if (v == NONE) return -1;
        m->cell[id].corner[c] = v;
    }
    return 0;
}

static double lat_to_world(const dfl_tmesh *m, int j, uint32_t k)
{
    if (k == LAT) return m->hi[j];
    return m->lo[j] + (m->hi[j] - m->lo[j]) * ((double)k / (double)LAT);
}

/* Depth-first leaves; the tree depth is at most 3 * DFL_TMESH_BITS. */
static int collect_leaves(dfl_tmesh *m)
{
    size_t *leaf = realloc(m->leaf, m->ncell * sizeof *leaf);
    if (!leaf) return -1;
    m->leaf = leaf;
    m->nleaf = 0;
    size_t stack[3 * DFL_TMESH_BITS * 8 + 8];
    size_t top = 0;
    stack[top++] = 0;
    while (top) {
        size_t id = stack[--top];
        const tnode *c = &m->cell[id];
        if (c->nchild == 0) {
            m->leaf[m->nleaf++] = id;
            continue;
        }
        for (int i = c->nchild - 1; i >= 0; i--) stack[top++] = c->child + (size_t)i;
    }
    return 0;
}

/* Leaf holding lattice point k, ties on a splitting plane broken by the sign
 * pos[j] (1: high side). */
static size_t descend(const dfl_tmesh *m, const uint32_t *k, const int *pos)
{
    size_t id = 0;
    while (m->cell[id].nchild) {
        const tnode *c = &m->cell[id];
        int idx = 0;
        if (c->split_axis < 0) {
            for (int j = 0; j < m->dim; j++) {
                uint32_t mid = c->lo[j] + c->sz[j] / 2;
                if (k[j] > mid || (k[j] == mid && pos[j])) idx |= 1 << j;
            }
        } else {
            int a = c->split_axis;
            uint32_t mid = c->lo[a] + c->sz[a] / 2;
            idx = k[a] > mid || (k[a] == mid && pos[a]);
        }
        id = c->child + (size_t)idx;
    }
    return id;
}

static void classify_vertex(dfl_tmesh *m, size_t v)
{
    tvert *t = &m->vert[v];
    int best_vol = -1;
    size_t best = NONE;
    int ncorner = 1 << m->dim;
    for (int o = 0; o < ncorner; o++) {
        int pos[3] = {0, 0, 0}, out = 0;
        for (int j = 0; j < m->dim; j++) {
            pos[j] = (o >> j) & 1;
            if ((pos[j] && t->key[j] == LAT) || (!pos[j] && t->key[j] == 0)) out = 1;
        }
        if (out) continue;
        size_t id = descend(m, t->key, pos);
        const tnode *c = &m->cell[id];
        int inner = 0, vol = 0;
        for (int j = 0; j < m->dim; j++) {
            if (t->key[j] > c->lo[j] && t->key[j] < c->lo[j] + c->sz[j]) inner++;
            vol += __builtin_ctz(c->sz[j]);
        }
        if (inner && vol > best_vol) {
            best_vol = vol;
            best = id;
        }
    }
    t->axis = -1;
    t->owner = best;
    for (int i = 0; i < 4; i++) t->dep[i] = NONE;
    if (best == NONE) {
        t->kind = DFL_TMESH_BASE;
        return;
    }
    const tnode *c = &m->cell[best];
    int ax[3], na = 0, fixed = -1;
    for (int j = 0; j < m->dim; j++) {
        if (t->key[j] > c->lo[j] && t->key[j] < c->lo[j] + c->sz[j]) ax[na++] = j;
        else fixed = j;
    }
    uint32_t k[3];
    if (na == 1) {
        t->kind = DFL_TMESH_EDGE;
        t->axis = ax[0];
        for (int e = 0; e < 2; e++) {
            memcpy(k, t->key, sizeof k);
            k[ax[0]] = c->lo[ax[0]] + (e ? c->sz[ax[0]] : 0);
            t->dep[e] = hash_find(m, k);
            assert(t->dep[e] != NONE);
        }
        return;
    }
    assert(na == 2 && m->dim == 3);
    t->kind = DFL_TMESH_FACE;
    t->axis = fixed;
    for (int e = 0; e < 4; e++) {
        memcpy(k, t->key, sizeof k);
        k[ax[0]] = c->lo[ax[0]] + ((e & 1) ? c->sz[ax[0]] : 0);
        k[ax[1]] = c->lo[ax[1]] + ((e & 2) ? c->sz[ax[1]] : 0);
        t->dep[e] = hash_find(m, k);
        assert(t->dep[e] != NONE);
    }
}

/* Appends v after its dependencies (state: 0 new, 1 on the path, 2 done). */
static void order_visit(dfl_tmesh *m, size_t v, unsigned char *state)
{
    if (state[v] == 2) return;
    assert(state[v] != 1 && "cyclic hanging-vertex dependencies");
    state[v] = 1;
    const tvert *t = &m->vert[v];
    int nd = t->kind == DFL_TMESH_EDGE ? 2 : 4;
    for (int i = 0; i < nd; i++)
        if (m->vert[t->dep[i]].kind != DFL_TMESH_BASE) order_visit(m, t->dep[i], state);
    state[v] = 2;
    m->order[m->norder++] = v;
}

/* Classifies the vertices v >= from and those whose owner is marked (NULL:
 * all), then recounts and reorders.  Splitting a cell C changes the leaves
 * around a vertex only if C was one of them: C's corners stay corners (of
 * C's children), a vertex owned by another, at least as large leaf keeps
 * that owner, so only new vertices and those owned by C can change. */
static int classify(dfl_tmesh *m, size_t from, const unsigned char *mark)
{
    m->nbase = 0;
    for (size_t v = 0; v < m->nvert; v++) {
        if (v >= from || !mark || (m->vert[v].owner != NONE && mark[m->vert[v].owner]))
            classify_vertex(m, v);
        if (m->vert[v].kind == DFL_TMESH_BASE) m->nbase++;
    }
    size_t *order = realloc(m->order, (m->nvert ? m->nvert : 1) * sizeof *order);
    unsigned char *state = calloc(m->nvert ? m->nvert : 1, 1);
    if (!order || !state) {
        if (order) m->order = order;
        free(state);
        return -1;
    }
    m->order = order;
    m->norder = 0;
    for (size_t v = 0; v < m->nvert; v++)
        if (m->vert[v].kind != DFL_TMESH_BASE) order_visit(m, v, state);
    free(state);
    return 0;
}

dfl_status dfl_tmesh_new(int dim, const double *lo, const double *hi, dfl_tmesh **out,
                         dfl_err *err)
{
    if (dim != 2 && dim != 3)
        return dfl_err_set(err, DFL_E_INPUT, "T-mesh: dimension %d (expected 2 or 3)", dim);
    for (int j = 0; j < dim; j++)
        if (!isfinite(lo[j]) || !isfinite(hi[j]) || !(lo[j] < hi[j]))
            return dfl_err_set(err, DFL_E_INPUT,
                               "T-mesh: box side %d is [%g, %g] (expected finite lo < hi)", j,
                               lo[j], hi[j]);
    dfl_tmesh *m = calloc(1, sizeof *m);
    if (!m) return dfl_err_set(err, DFL_E_NOMEM, "T-mesh: out of memory");
    m->dim = dim;
    for (int j = 0; j < dim; j++) {
        m->lo[j] = lo[j];
        m->hi[j] = hi[j];
    }
    if (cells_reserve(m, 1) != 0 || hash_grow(m) != 0) goto nomem;
    tnode *r = &m->cell[0];
    memset(r, 0, sizeof *r);
    for (int j = 0; j < dim; j++) r->sz[j] = LAT;
    r->split_axis = -1;
    r->parent = NONE;
    r->child = NONE;
    m->ncell = 1;
    if (cell_corners(m, 0) != 0 || collect_leaves(m) != 0 || classify(m, 0, NULL) != 0)
        goto nomem;
    *out = m;
    return DFL_OK;
nomem:
    dfl_tmesh_free(m);
    return dfl_err_set(err, DFL_E_NOMEM, "T-mesh: out of memory");
}

void dfl_tmesh_free(dfl_tmesh *m)
{
    if (!m) return;
    free(m->cell);
    free(m->vert);
    free(m->hash);
    free(m->leaf);
    free(m->order);
    free(m);
}

int dfl_tmesh_dim(const dfl_tmesh *m) { return m->dim; }
const double *dfl_tmesh_lo(const dfl_tmesh *m) { return m->lo; }
const double *dfl_tmesh_hi(const dfl_tmesh *m) { return m->hi; }

/* The binary split axis of c: the longest side in world units, ties to the
 * lowest axis; -1 if that side is one lattice step. */
static int binary_axis(const dfl_tmesh *m, const tnode *c)
{
    int a = 0;
    double best = -1.0;
    for (int j = 0; j < m->dim; j++) {
        double len = (double)c->sz[j] * (m->hi[j] - m->lo[j]);
        if (len > best) {
            best = len;
            a = j;
        }
    }
    return c->sz[a] >= 2 ? a : -1;
}

static int split_cell(dfl_tmesh *m, size_t id, dfl_pht_split rule)
{
    int nch = rule == DFL_PHT_SPLIT_CROSS ? 1 << m->dim : 2;
    if (cells_reserve(m, (size_t)nch) != 0) return -1;
    tnode *c = &m->cell[id];
    int axis = rule == DFL_PHT_SPLIT_CROSS ? -1 : binary_axis(m, c);
    size_t first = m->ncell;
    for (int i = 0; i < nch; i++) {
        tnode *k = &m->cell[first + (size_t)i];
        memset(k, 0, sizeof *k);
        for (int j = 0; j < m->dim; j++) {
            int half = axis < 0 || axis == j;
            int hi = axis < 0 ? (i >> j) & 1 : i;
            k->sz[j] = half ? c->sz[j] / 2 : c->sz[j];
            k->lo[j] = c->lo[j] + (half && hi ? k->sz[j] : 0);
        }
        k->level = c->level + 1;
        k->split_axis = -1;
        k->parent = id;
        k->child = NONE;
    }
    c->child = first;
    c->nchild = nch;
    c->split_axis = axis;
    m->ncell += (size_t)nch;
    for (int i = 0; i < nch; i++)
        if (cell_corners(m, first + (size_t)i) != 0) return -1;
    return 0;
}

dfl_status dfl_tmesh_refine(dfl_tmesh *m, size_t n, const size_t *ids, dfl_pht_split rule,
                            dfl_err *err)
{
    if ((int)rule < 0 || (int)rule >= DFL_PHT_SPLIT_COUNT)
        return dfl_err_set(err, DFL_E_INPUT, "T-mesh: unknown split rule %d", (int)rule);
    for (size_t i = 0; i < n; i++) {
        if (ids[i] >= m->ncell || m->cell[ids[i]].nchild)
            return dfl_err_set(err, DFL_E_INPUT, "T-mesh: cell %zu is not a leaf", ids[i]);
        const tnode *c = &m->cell[ids[i]];
        int ok = rule == DFL_PHT_SPLIT_BINARY ? binary_axis(m, c) >= 0 : 1;
        for (int j = 0; rule == DFL_PHT_SPLIT_CROSS && j < m->dim; j++)
            if (c->sz[j] < 2) ok = 0;
        if (!ok)
            return dfl_err_set(err, DFL_E_INPUT,
                               "T-mesh: cell %zu (level %d) is at the lattice resolution", ids[i],
                               c->level);
    }
    size_t from = m->nvert;
    unsigned char *mark = calloc(m->ncell ? m->ncell : 1, 1);
    if (!mark) return dfl_err_set(err, DFL_E_NOMEM, "T-mesh: out of memory");
    for (size_t i = 0; i < n; i++) mark[ids[i]] = 1;
    for (size_t i = 0; i < n; i++)
        if (m->cell[ids[i]].nchild == 0 && split_cell(m, ids[i], rule) != 0) goto nomem;
    if (collect_leaves(m) != 0 || classify(m, from, mark) != 0) goto nomem;
    free(mark);
    return DFL_OK;
nomem:
    /* keep the mesh valid: whatever was split is a proper tree */
    free(mark);
    collect_leaves(m);
    classify(m, 0, NULL);
    return dfl_err_set(err, DFL_E_NOMEM, "T-mesh: out of memory");
}

size_t dfl_tmesh_ncells(const dfl_tmesh *m) { return m->ncell; }

void dfl_tmesh_cell_get(const dfl_tmesh *m, size_t id, dfl_tmesh_cell *out)
{
    assert(id < m->ncell);
    const tnode *c = &m->cell[id];
    memset(out, 0, sizeof *out);
    for (int j = 0; j < m->dim; j++) {
        out->lo[j] = lat_to_world(m, j, c->lo[j]);
        out->hi[j] = lat_to_world(m, j, c->lo[j] + c->sz[j]);
    }
    out->level = c->level;
    out->split_axis = c->nchild ? c->split_axis : -1;
    out->parent = c->parent;
    out->child = c->child;
    out->nchild = c->nchild;
    for (int i = 0; i < 8; i++) out->corner[i] = i < (1 << m->dim) ? c->corner[i] : NONE;
}

size_t dfl_tmesh_nleaves(const dfl_tmesh *m) { return m->nleaf; }
const size_t *dfl_tmesh_leaves(const dfl_tmesh *m) { return m->leaf; }

int dfl_tmesh_max_level(const dfl_tmesh *m)
{
    int l = 0;
    for (size_t i = 0; i < m->nleaf; i++)
        if (m->cell[m->leaf[i]].level > l) l = m->cell[m->leaf[i]].level;
    return l;
}

size_t dfl_tmesh_nverts(const dfl_tmesh *m) { return m->nvert; }

void dfl_tmesh_vertex_get(const dfl_tmesh *m, size_t v, dfl_tmesh_vertex *out)
{
    assert(v < m->nvert);
    const tvert *t = &m->vert[v];
    memset(out, 0, sizeof *out);
    for (int j = 0; j < m->dim; j++) out->x[j] = lat_to_world(m, j, t->key[j]);
    memcpy(out->key, t->key, sizeof out->key);
    out->kind = t->kind;
    out->axis = t->axis;
    memcpy(out->dep, t->dep, sizeof out->dep);
    out->owner = t->owner;
}

size_t dfl_tmesh_nbase(const dfl_tmesh *m) { return m->nbase; }

const size_t *dfl_tmesh_order(const dfl_tmesh *m, size_t *n)
{
    *n = m->norder;
    return m->order;
}

size_t dfl_tmesh_locate(const dfl_tmesh *m, const double *x, const double *dir)
{
    size_t id = 0;
    while (m->cell[id].nchild) {
        const tnode *c = &m->cell[id];
        int idx = 0;
        for (int j = 0; j < m->dim; j++) {
            if (c->split_axis >= 0 && c->split_axis != j) continue;
            double mid = lat_to_world(m, j, c->lo[j] + c->sz[j] / 2);
            int hi = x[j] > mid || (x[j] == mid && !(dir && dir[j] < 0));
            if (hi) idx |= c->split_axis >= 0 ? 1 : 1 << j;
        }
        id = c->child + (size_t)idx;
    }
    return id;
}

size_t dfl_tmesh_bytes(const dfl_tmesh *m)
{
    return sizeof *m + m->ccap * sizeof *m->cell + m->vcap * sizeof *m->vert +
           m->hcap * sizeof *m->hash + m->ncell * sizeof *m->leaf +
           m->nvert * sizeof *m->order;
}
