/* OpenVDB narrow-band level sets as dflab fields: the peer that stores a
 * float per voxel near the surface and nothing elsewhere.
 *
 * A thin extern "C" adapter over OpenVDB 10's C++ API (vdb.cc):
 * openvdb::FloatGrid of class GRID_LEVEL_SET, background b = band * voxel
 * (OpenVDB's convention: a level set's background is its narrow-band
 * half-width in world units).  Ken Museth: "VDB: High-resolution sparse
 * volumes with dynamic topology", ACM Transactions on Graphics 32(3), 27,
 * 2013, doi:10.1145/2487228.2487235.
 *
 * Function index
 *   dfl_vdb_sampler        box | quadratic | staggered (X-macro names)
 *   dfl_vdb_build          direct | mesh
 *   dfl_vdb_from_shape     direct fill from a shape's SDF (or any 1/L-
 *                          Lipschitz function given as a shape)
 *   dfl_vdb_from_mesh      openvdb::tools::meshToLevelSet of a dfl_trimesh
 *   dfl_vdb_free
 *   dfl_vdb_voxel, _band, _background   lattice and band
 *   dfl_vdb_bytes          grid->memUsage()
 *   dfl_vdb_active_count, dfl_vdb_active_voxels   the active voxels
 *   dfl_vdb_build_seconds, dfl_vdb_evals   what the build cost
 *   dfl_vdb_voxel_value, dfl_vdb_voxel_centre     one voxel
 *   dfl_vdb_sample         batched sampler values and gradients
 *   dfl_vdb_field_new      the grid as a dfl_field (owns the grid)
 *   dfl_vdb_field_grid     the grid and sampler of a vdb field
 *   dfl_vdb_bytes_bound    the memory bound from the box and the voxel
 *
 * Lattice.  Voxel (i, j, k) has its centre at (i, j, k) * voxel in world
 * units (OpenVDB's linear transform, cell-centred index space), except on a
 * staggered grid (sampler = staggered at build), where it sits at
 * ((i, j, k) - 1/2) * voxel: OpenVDB's staggered (MAC) grids put the x
 * component of voxel ijk at the face (i - 1/2, j, k), and its
 * StaggeredBoxSampler reads that component by BoxSampler at the index point
 * + (1/2, 0, 0).  A scalar has no components, so dflab's scalar staggered
 * grid stores voxel ijk at its corner (i, j, k) - 1/2, where the three faces
 * meet, and reads it by BoxSampler at index point + (1/2, 1/2, 1/2): the
 * staggered lattice is the centred one shifted by half a voxel on every
 * axis.  (openvdb::tools::StaggeredBoxSampler itself reads .x() .y() .z()
 * of a vector value and does not compile for a float grid.)
 *
 * The box [lo, hi] covers the index range I = [floor(l) - 1, ceil(u) + 1]
 * per axis, l, u the index coordinates of lo, hi, so that both samplers'
 * stencils around every point of the box lie in I.  The grid holds every 8^3
 * leaf (OpenVDB's leaf node, aligned at multiples of 8) that meets I.
 *
 * Values.  A voxel is active iff |f(centre)| < b; its value is
 * (float)f(centre) (direct) or OpenVDB's distance to the mesh (mesh).
 * Every other voxel of a held leaf, and every voxel outside them within the
 * 128^3 blocks meeting I, is inactive with value +b or -b, the sign of f
 * (OpenVDB's level set rule: outside the band the value is the background,
 * its sign the side); beyond those blocks the value is the tree's
 * background +b whatever the side.  So the field is a distance only within
 * the band |d| < b: metrics must be restricted to it (dfl_vdb_band,
 * field/metrics.h's band rule with band < b - (stencil reach), see
 * dfl_vdb_sample), never taken over the whole box unannounced.
 *
 * Direct fill: band search, coarse to fine.  With L the Lipschitz constant
 * of f (1 for an exact SDF: opts.lipschitz), a block of voxel centres with
 * centre c and half-diagonal r (world units) holds no active voxel when
 * |f(c)| - L r >= b (1 + 1e-9), and then every voxel of it has the sign of
 * f(c).  The search evaluates f at the centres of the 128^3 blocks meeting
 * I, then at the centres of the 8^3 leaves of every block not ruled out,
 * then at all 512 voxel centres of every leaf not ruled out; ruled-out
 * blocks and leaves inside the shape become inactive tiles of value -b.
 * Each level is one batched dfl_shape eval per block or leaf (OpenMP over
 * leaves; the tree is assembled serially).  Cost: the blocks + 4096 per
 * kept block + 512 per kept leaf evaluations; for a surface of area A a
 * kept leaf lies within b + L sqrt(3) 7/2 voxel of it, so about
 * A (2 b + 12 voxel) / (8 voxel)^3 leaves are kept, i.e. about
 * A (2 band + 12) / voxel^2 evaluations, and at most the dense count of I
 * (plus the block and leaf centres).  dfl_vdb_evals reports the count
 * (measured: 1.64 evaluations per active voxel on the torus R = 0.6,
 * r = 0.25 at voxel 0.0109, band 10).
 *
 * Mesh build: openvdb::tools::meshToLevelSet<FloatGrid>(transform, points,
 * triangles, band) of the mesh's vertices (rounded to float) and
 * triangles: OpenVDB's own exact narrow band (unsigned distance to the
 * nearest triangle in the band, sign by its flood fill, so the mesh must
 * be closed).  Its active voxels are those OpenVDB marks; the box only sets
 * where the mesh is expected (the mesh is not clipped).  Within distance
 * b - voxel of the mesh the values are the exact mesh distance up to float
 * rounding (tested: 8 float epsilons); in the outermost voxel layer they
 * come from OpenVDB's approximate band extension (on a sphere at voxel
 * 0.05 up to 0.17 voxel off, either way).
 *
 * Samplers (dfl_vdb_sample), x in world units, p = x / voxel (+ 1/2 on a
 * staggered grid) in index space:
 *   box        openvdb::tools::BoxSampler: trilinear interpolation of the 8
 *              voxels around p (continuous; reproduces affine functions)
 *   quadratic  openvdb::tools::QuadraticSampler: per axis the parabola
 *              through the voxels floor(p) - 1, floor(p), floor(p) + 1,
 *              evaluated at the fraction p - floor(p) in [0, 1): reproduces
 *              quadratics (and their tensor products) exactly, but jumps
 *              where p crosses an integer (OpenVDB marks it not
 *              "consistent")
 *   staggered  BoxSampler on the staggered lattice (see Lattice)
 * Computed as OpenVDB does, in float (weights in double); the result is
 * converted to double.  A value is a distance where the whole stencil is
 * active: box reaches one voxel, quadratic one voxel further below floor(p),
 * so within |d| < b - 2 voxel (L = 1) both are.
 * Gradient: central differences of the same sampler with step s = voxel / 2
 * along each axis, g_j = (S(x + s e_j) - S(x - s e_j)) / (2 s): exact for a
 * sampler that reproduces a quadratic (central differences are exact on
 * quadratics), so exact for affine data with box and quadratic data with
 * quadratic; at a voxel centre with box it is the classical central
 * difference (v_{i+1} - v_{i-1}) / (2 voxel).  Six more samples per point.
 *
 * Memory (dfl_vdb_bytes): OpenVDB's memUsage of the grid's tree (nodes,
 * buffers, masks).  dfl_vdb_bytes_bound gives an upper bound from the box
 * alone (every leaf meeting I allocated, with its internal nodes): a band
 * may meet every leaf (a fine lattice of surfaces), so nothing smaller
 * holds for every shape; a narrow band of area A takes about
 * A (2 b + 12 voxel) / voxel^3 (4 + 1/8) bytes plus the internal nodes.
 *
 * Threads: builds use `threads` OpenMP threads (direct) or OpenVDB's TBB
 * (mesh); dfl_vdb_sample is thread-safe on a shared grid and does not
 * allocate (an unregistered value accessor per call).  Every C++ exception
 * is caught and turned into a status.
 */
#ifndef DFL_FIELD_VDB_H
#define DFL_FIELD_VDB_H

#include <stddef.h>

#include "core/names.h"
#include "core/status.h"
#include "field/field.h"
#include "geom/polygonize.h"
#include "geom/shape.h"

#ifdef __cplusplus
extern "C" {
#endif

#define DFL_VDB_SAMPLER_LIST(X)                                        \
    X(DFL_VDB_BOX, "box", "openvdb::tools::BoxSampler (trilinear)")    \
    X(DFL_VDB_QUADRATIC, "quadratic", "openvdb::tools::QuadraticSampler") \
    X(DFL_VDB_STAGGERED, "staggered", "BoxSampler on the half-voxel lattice")

typedef enum dfl_vdb_sampler { DFL_VDB_SAMPLER_LIST(DFL_NAMES_CODE) } dfl_vdb_sampler;
enum { DFL_VDB_SAMPLER_COUNT = 0 DFL_VDB_SAMPLER_LIST(DFL_NAMES_ONE) };

#define DFL_VDB_BUILD_LIST(X)                                   \
    X(DFL_VDB_DIRECT, "direct", "fill the band from the SDF")   \
    X(DFL_VDB_MESH, "mesh", "openvdb::tools::meshToLevelSet")

typedef enum dfl_vdb_build { DFL_VDB_BUILD_LIST(DFL_NAMES_CODE) } dfl_vdb_build;
enum { DFL_VDB_BUILD_COUNT = 0 DFL_VDB_BUILD_LIST(DFL_NAMES_ONE) };

extern const char *const dfl_vdb_sampler_names[DFL_VDB_SAMPLER_COUNT];
extern const char *const dfl_vdb_build_names[DFL_VDB_BUILD_COUNT];
const char *dfl_vdb_sampler_name(dfl_vdb_sampler s);
dfl_status dfl_vdb_sampler_parse(const char *s, dfl_vdb_sampler *out, dfl_err *err);
const char *dfl_vdb_build_name(dfl_vdb_build b);
dfl_status dfl_vdb_build_parse(const char *s, dfl_vdb_build *out, dfl_err *err);

typedef struct dfl_vdb_opts {
    double voxel;              /* voxel size, world units, > 0 */
    int band;                  /* narrow-band half-width in voxels, >= 1 (OpenVDB: 3) */
    dfl_vdb_sampler sampler;   /* the field's sampler; staggered shifts the lattice */
    double lo[3], hi[3];       /* the box, lo < hi */
    double lipschitz;          /* direct: L >= 1 bound of |grad f| (1 for an SDF) */
    int threads;               /* direct: OpenMP threads (<= 0: the default) */
} dfl_vdb_opts;

/* voxel 0.05, band 3, box, [-1, 1]^3, lipschitz 1, threads 0. */
void dfl_vdb_opts_default(dfl_vdb_opts *o);

typedef struct dfl_vdb dfl_vdb;

/* Direct fill (see the top) of shape (3D; borrowed during the call).
 * Errors: DFL_E_INPUT for voxel not finite and > 0, band < 1, lo >= hi, a
 * non-finite box, lipschitz < 1 or not finite, a 2D shape, an index range
 * beyond +-2^30 voxels or over 2^15 voxels per axis; DFL_E_NUMERIC for a non-finite f at a point the
 * search evaluates; DFL_E_NOMEM.  *out untouched on failure. */
dfl_status dfl_vdb_from_shape(const dfl_shape *shape, const dfl_vdb_opts *o, dfl_vdb **out,
                              dfl_err *err);

/* meshToLevelSet of m (borrowed; verts and tris only are read).  Errors:
 * DFL_E_INPUT as above (lipschitz unused), for a mesh without triangles, a
 * vertex index out of range or a non-finite vertex; DFL_E_NOMEM;
 * DFL_E_INTERNAL for an OpenVDB exception.  *out untouched on failure. */
dfl_status dfl_vdb_from_mesh(const dfl_trimesh *m, const dfl_vdb_opts *o, dfl_vdb **out,
                             dfl_err *err);

/* Releases g (NULL is fine). */
void dfl_vdb_free(dfl_vdb *g);

double dfl_vdb_voxel(const dfl_vdb *g);
int dfl_vdb_band(const dfl_vdb *g);               /* half-width in voxels */
/* The background b as stored (float band * voxel, as double): the band
 * half-width in world units.  Values with |d| >= b are not distances. */
double dfl_vdb_background(const dfl_vdb *g);
dfl_vdb_sampler dfl_vdb_lattice_sampler(const dfl_vdb *g); /* opts.sampler at build */
size_t dfl_vdb_bytes(const dfl_vdb *g);           /* grid->memUsage() */
size_t dfl_vdb_active_count(const dfl_vdb *g);    /* active voxels */
size_t dfl_vdb_leaf_count(const dfl_vdb *g);      /* allocated 8^3 leaves */
double dfl_vdb_build_seconds(const dfl_vdb *g);   /* wall time of the build */
/* direct: evaluations of f the band search made (blocks, leaves, voxels);
 * mesh: 0 */
size_t dfl_vdb_evals(const dfl_vdb *g);

/* The first min(cap, active count) active voxels in OpenVDB's iteration
 * order: ijk[3 n] and value[n] (either may be NULL).  Returns the count
 * written. */
size_t dfl_vdb_active_voxels(const dfl_vdb *g, size_t cap, int *ijk, float *value);

/* Value of voxel ijk (the tree's value, active or not) and *active (may be
 * NULL) whether it is active. */
float dfl_vdb_voxel_value(const dfl_vdb *g, const int ijk[3], int *active);

/* World position of voxel ijk's sample point (see Lattice). */
void dfl_vdb_voxel_centre(const dfl_vdb *g, const int ijk[3], double x[3]);

/* Sampler s at m points pts[3 i ..] (world units): val[i] and, when grad
 * is not NULL, grad[3 i ..] (see Samplers).  box and staggered are the same
 * code (BoxSampler at the grid's index point); a grid is sampled with any
 * s.  A point with a NaN coordinate gets NaN value and gradient (the
 * samplers are not called: they cast floor(p) to int); an index coordinate
 * p beyond +-(2^31 - 2^20) (an infinite one too) is clamped to it, where
 * only the tree's background is read: value +b, gradient 0, as at any
 * point beyond the grid's nodes.  Thread-safe, no allocation. */
void dfl_vdb_sample(const dfl_vdb *g, dfl_vdb_sampler s, size_t m, const double *pts,
                    double *val, double *grad);

/* The grid as a 3D field sampled with s (no jets).  Takes ownership of *g
 * (set to NULL) on success; on failure (DFL_E_NOMEM) g stays the caller's. */
dfl_status dfl_vdb_field_new(dfl_vdb **g, dfl_vdb_sampler s, dfl_field *out, dfl_err *err);

/* The grid of a vdb field (borrowed) and its sampler into *s (may be
 * NULL); NULL when f is not a vdb field. */
const dfl_vdb *dfl_vdb_field_grid(const dfl_field *f, dfl_vdb_sampler *s);

/* Upper bound of dfl_vdb_bytes of any grid built with o (direct or mesh
 * whose mesh lies in the box): every leaf meeting I, every internal node
 * above them, the root, from OpenVDB's own node sizes.  Fills *leaves (may
 * be NULL) with the number of leaves meeting I.  0 when o is invalid (see
 * dfl_vdb_from_shape); +inf-like values saturate at 1e300. */
double dfl_vdb_bytes_bound(const dfl_vdb_opts *o, double *leaves);

#ifdef __cplusplus
}
#endif

#endif
