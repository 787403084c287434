/* Hierarchical T-meshes in 2D and 3D over an axis-aligned box (sjp10 Sec. 2).
 *
 * A T-mesh is a partition of the box [lo, hi] into axis-aligned cells made
 * by repeated splitting of the root cell (the box):
 *   cross   a cell into 2^dim equal children (4 / 8; the PHT default);
 *   binary  a cell into 2 equal halves across its longest side in world
 *           units (ties: the lowest axis), the paper's splitting step.
 * Cells are nodes of a tree; the leaves partition the box.  A cell's level
 * is its depth in the tree (cross: cell size = box / 2^level; binary: the
 * number of halvings).  Internally corners live on an integer lattice of
 * 2^DFL_TMESH_BITS steps per axis, so vertices are identified exactly.
 *
 * Vertices are the corners of the leaf cells.  They are never removed:
 * vertex ids are stable across refinement (new vertices get new ids), which
 * lets a fit keep the Hermite data of old vertices.
 *
 * Base vertices (sjp10 Sec. 2):
 *   2D: on the boundary of the box, or crossing (valency 4);
 *   3D: on a boundary edge of the box, or a crossing vertex of a boundary
 *       facet (valency 4 within the facet), or of valency 6.
 * Every other vertex lies in the interior of an edge or a face of some leaf
 * cell.  Such a vertex is "hanging": it records the coarsest such edge
 * (2 corner vertex ids, its axis) or face (4 corner ids, its normal axis),
 * from whose corners a PHT spline interpolates its Hermite data (cubic /
 * bicubic Hermite along the edge / on the face).  Where several leaves
 * contain the vertex in an edge or face interior, the element of the leaf
 * with the largest volume is recorded (the coarsest level, so dependencies
 * point to coarser vertices and cannot cycle); the C1 tests of tests/pht
 * check that this choice gives a C1 spline for both rules.
 * dfl_tmesh_order() lists the hanging vertices so that every vertex comes
 * after the corners it depends on.
 *
 * Point location walks the tree from the root: O(levels).
 *
 * Function index:
 *   dfl_tmesh_new / dfl_tmesh_free          create the one-cell mesh of a box / release
 *   dfl_tmesh_dim, _lo, _hi                 dimension and box
 *   dfl_tmesh_refine                        split a set of leaf cells (and reclassify vertices)
 *   dfl_tmesh_ncells, dfl_tmesh_cell_get    all tree nodes, one node's box/level/corners/children
 *   dfl_tmesh_nleaves, dfl_tmesh_leaves     the leaves in tree order (deterministic)
 *   dfl_tmesh_max_level                     deepest leaf level
 *   dfl_tmesh_nverts, _vertex_get           vertices: position, base/hanging, dependence
 *   dfl_tmesh_nbase                         number of base vertices
 *   dfl_tmesh_order                         hanging vertices, dependencies first
 *   dfl_tmesh_locate                        leaf containing a point (O(levels))
 *   dfl_tmesh_bytes                         memory held (for "memory ~ cells" checks)
 *   dfl_pht_split_name / _parse             names of the refinement rules
 *   dfl_tmesh_vertex_kind_name              names of the vertex kinds
 */
#ifndef DFL_PHT_TMESH_H
#define DFL_PHT_TMESH_H

#include <stddef.h>
#include <stdint.h>

#include "core/names.h"
#include "core/status.h"

/* Lattice resolution: corners are integers in [0, 2^DFL_TMESH_BITS]. */
#define DFL_TMESH_BITS 30
/* Deepest cross level (cells of box / 2^30); binary: DFL_TMESH_BITS * dim. */
#define DFL_TMESH_MAX_LEVEL DFL_TMESH_BITS

/* Refinement rules, one list (core/names.h): X(code, config name, note). */
#define DFL_PHT_SPLIT_LIST(X)                                          \
    X(DFL_PHT_SPLIT_CROSS, "cross", "a cell into 2^dim children")      \
    X(DFL_PHT_SPLIT_BINARY, "binary", "a cell into 2 along its longest side")

typedef enum dfl_pht_split { DFL_PHT_SPLIT_LIST(DFL_NAMES_CODE) } dfl_pht_split;
enum { DFL_PHT_SPLIT_COUNT = 0 DFL_PHT_SPLIT_LIST(DFL_NAMES_ONE) };

/* Config names indexed by code. */
extern const char *const dfl_pht_split_names[DFL_PHT_SPLIT_COUNT];
/* Config name of a split rule; "?" outside the list. */
const char *dfl_pht_split_name(dfl_pht_split s);
/* The rule called name (exact match) into *out; DFL_E_INPUT "unknown split
 * '<name>' (expected one of cross|binary)" otherwise (*out untouched). */
dfl_status dfl_pht_split_parse(const char *name, dfl_pht_split *out, dfl_err *err);

/* Vertex kinds, one list: X(code, name, what the vertex's data are). */
#define DFL_TMESH_VERTEX_KIND_LIST(X)                                                  \
    X(DFL_TMESH_BASE, "base", "base vertex: data come from the function")              \
    X(DFL_TMESH_EDGE, "edge", "hanging inside an edge: dep[0..1] along axis")          \
    X(DFL_TMESH_FACE, "face", "hanging inside a face (3D): dep[0..3] around normal axis")

typedef enum dfl_tmesh_vertex_kind {
    DFL_TMESH_VERTEX_KIND_LIST(DFL_NAMES_CODE)
} dfl_tmesh_vertex_kind;
enum { DFL_TMESH_VERTEX_KIND_COUNT = 0 DFL_TMESH_VERTEX_KIND_LIST(DFL_NAMES_ONE) };

/* Name of a vertex kind ("base", "edge", "face"; for messages); "?" outside. */
const char *dfl_tmesh_vertex_kind_name(dfl_tmesh_vertex_kind k);

typedef struct dfl_tmesh_vertex {
    double x[3];          /* world position (dim entries used, rest 0) */
    uint32_t key[3];      /* lattice position */
    dfl_tmesh_vertex_kind kind;
    int axis;             /* EDGE: the edge's axis; FACE: the face's normal axis; BASE: -1 */
    size_t dep[4];        /* EDGE: ends (low, high along axis); FACE: corners, index
                             bit 0 = high along the first tangential axis, bit 1 = the
                             second (tangential axes in increasing order) */
    size_t owner;         /* EDGE/FACE: the leaf whose edge/face holds the vertex
                             (the coarse cell its data come from); BASE: SIZE_MAX */
} dfl_tmesh_vertex;

typedef struct dfl_tmesh_cell {
    double lo[3], hi[3];  /* world box (dim entries used) */
    int level;            /* depth in the tree, root 0 */
    int split_axis;       /* binary split axis, -1 for cross or a leaf */
    size_t parent;        /* SIZE_MAX for the root */
    size_t child;         /* first child id, SIZE_MAX for a leaf */
    int nchild;           /* 0 (leaf), 2 (binary) or 2^dim (cross) */
    size_t corner[8];     /* leaf only: vertex ids, index bit j = high side along axis j */
} dfl_tmesh_cell;

typedef struct dfl_tmesh dfl_tmesh;

/* One-cell mesh of the box [lo, hi] (dim doubles each, lo < hi, finite),
 * dim 2 or 3.  DFL_E_INPUT for a bad box or dim, DFL_E_NOMEM. */
dfl_status dfl_tmesh_new(int dim, const double *lo, const double *hi, dfl_tmesh **out,
                         dfl_err *err);
/* m may be NULL. */
void dfl_tmesh_free(dfl_tmesh *m);

int dfl_tmesh_dim(const dfl_tmesh *m);
const double *dfl_tmesh_lo(const dfl_tmesh *m);
const double *dfl_tmesh_hi(const dfl_tmesh *m);

/* Splits the n leaf cells ids[0..n-1] by rule; duplicates are split once.
 * New cells and vertices are appended (existing ids stay valid), then all
 * vertices are reclassified.  DFL_E_INPUT if an id is not a leaf or a cell
 * is already at the lattice resolution (cross: level DFL_TMESH_MAX_LEVEL;
 * binary: its longest side is one lattice step) -- nothing is split then;
 * DFL_E_NOMEM (the mesh stays valid, possibly partly refined). */
dfl_status dfl_tmesh_refine(dfl_tmesh *m, size_t n, const size_t *ids, dfl_pht_split rule,
                            dfl_err *err);

/* All tree nodes (leaves and inner cells); ids are 0..ncells-1, root 0. */
size_t dfl_tmesh_ncells(const dfl_tmesh *m);
/* Copies node id into *out (id < ncells, asserted). */
void dfl_tmesh_cell_get(const dfl_tmesh *m, size_t id, dfl_tmesh_cell *out);
/* Leaves in depth-first tree order (borrowed; valid until the next refine). */
size_t dfl_tmesh_nleaves(const dfl_tmesh *m);
const size_t *dfl_tmesh_leaves(const dfl_tmesh *m);
int dfl_tmesh_max_level(const dfl_tmesh *m);

size_t dfl_tmesh_nverts(const dfl_tmesh *m);
/* Copies vertex v (< nverts, asserted). */
void dfl_tmesh_vertex_get(const dfl_tmesh *m, size_t v, dfl_tmesh_vertex *out);
size_t dfl_tmesh_nbase(const dfl_tmesh *m);
/* The hanging vertices in an order where every vertex follows the vertices
 * it depends on (borrowed, *n entries; valid until the next refine). */
const size_t *dfl_tmesh_order(const dfl_tmesh *m, size_t *n);

/* Leaf containing x (dim doubles; points outside the box are clamped onto
 * it).  On a shared face the cell on the high side wins, at hi the last
 * cell; with dir != NULL the cell that x + s dir enters for small s > 0
 * wins instead (for one-sided jets).  No allocation; thread-safe. */
size_t dfl_tmesh_locate(const dfl_tmesh *m, const double *x, const double *dir);

/* Bytes held by the mesh (cells, vertices, indexes). */
size_t dfl_tmesh_bytes(const dfl_tmesh *m);

#endif
