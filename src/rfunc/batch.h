/* Vectorized evaluators (value and gradient) for every kind of bs04 field
 * rfield.h builds: rfield.c hands each finished field to
 * dfl_rfunc_batch_build, which finds the kernel that computes it, and the
 * field then evaluates through it (one call per block of points), so the
 * studies and `dflab probe` sample through the kernels.  What computes what:
 *
 *   R-equivalence (eq. 6) of
 *     a chain of segments, eq. 4 disk or strip trim, 2D or 3D
 *                                   batch_seg.c (the 2D disk kernel is the
 *                                   model, formulas below; the strip trim
 *                                   t = 2 p1 p2 / (p1 + p2 + |(p1, p2)|)
 *                                   takes a vector sqrt, t's division and
 *                                   one reciprocal for 1/r and 1/h^2; 3D the
 *                                   carrier f^2 = s1^2 + s2^2 with the
 *                                   library's two normals)
 *     points                        batch_point.c
 *     triangles, one eq. 4 trim     batch_tri.c (three phases through stack
 *                                   scratch; hardware roots, one division)
 *     convex regions                batch_region.c (grouped by edge count;
 *                                   u = 0 inside without a fallback)
 *     segments with an eq. 5 trim   batch_smooth.c (a second root and
 *                                   division per segment)
 *     mixed kinds, or segments that are not one chain
 *                                   batch_mixed.c (the sum of the kernels
 *                                   above over groups of parts, in a fixed
 *                                   order)
 *   R-conjunction (eq. 7) of disk- or strip-trimmed segments, 2D or 3D
 *                                   batch_rconj.c (the fold runs across
 *                                   points: a root per part)
 *   the corrected join (eq. 20), guarded and literal, of disk- or
 *   strip-trimmed segments          batch_corrected.c (vertex layouts
 *                                   whose guard reads other than the
 *                                   previous part or one of 4 kept parts
 *                                   stay per point)
 *
 * Per-point path (rfield.c) for the rest: one part (u = h exactly),
 * triangles with eq. 5 trims or conditional exponent k != 2, eq. 5 trims
 * mixed with other parts or joins.  Every kernel agrees with the per-point
 * path to rounding (tested to 1e-12 relative: tests/rfunc/test_batch*.c)
 * and falls back to it point by point where its arithmetic is not
 * trustworthy; `make bench` measures each kind against that path, a naive
 * scalar loop and numpy (tests/bench/bench_rfunc.c, which also counts the
 * operations).
 *
 * Formulas (per segment a-b, d = |b - a|, unit normal
 * n = (b_y - a_y, -(b_x - a_x))/d, w = x - a, v = x - b):
 *     f = w . n                    (eq. 2, signed line function)
 *     -t = (w . v)/d               (disk trim of eq. 3: t = ((d/2)^2 - |x - c|^2)/d)
 *     mt = max(-t, 0) = (|t| - t)/2
 *     h^2 = f^2 + mt^2             (eq. 4)
 *     h grad h = f n + mt (w + v)/d
 * and the join
 *     S = sum h_i^-p,   V = sum h_i^-(p+2) (h_i grad h_i),
 *     u = S^(-1/p),     grad u = u^(p+1) V
 * (du/dh_i = (u/h_i)^(p+1), so grad u = sum (u/h_i)^(p+1) grad h_i).
 * Even p need only 1/h^2 (one division).  Odd p need 1/h, which comes
 * from a Newton iteration for the reciprocal square root of h^2: ISO C's
 * errno semantics keep gcc from vectorizing sqrt() without
 * -fno-math-errno.
 *
 * Fallback.  The unscaled sums overflow near the polyline (h^-p) and
 * underflow far from it; a point whose sums are not comfortably inside the
 * double range (or that lies on the polyline, where u = 0 and the gradient
 * is 0 by the library's convention) is re-evaluated by the library's
 * scaled accumulator (rfunc/join.h).  That path is per point and rare.
 *
 * Thread safety: a batch is read-only after creation; eval allocates
 * nothing and may run concurrently.  Ownership: _new allocates, _free
 * releases (the field wrapper owns its batch).
 */
#ifndef DFL_RFUNC_BATCH_H
#define DFL_RFUNC_BATCH_H

#include <stdbool.h>
#include <stddef.h>

#include "core/status.h"
#include "field/field.h"
#include "rfunc/join.h"
#include "rfunc/part.h"
#include "rfunc/region.h"
#include "rfunc/segment.h"
#include "rfunc/tri3d.h"

typedef struct dfl_rfunc_batch dfl_rfunc_batch;

/* The polyline v[0..n-1] (2n coordinates; closed adds the segment
 * v[n-1] -> v[0]) with R-equivalence of order p, 1 <= p <= DFL_RFUNC_P_MAX.
 * Orders 1..8 and 12 run specialized vector code, other orders a generic
 * loop.  DFL_E_INPUT as dfl_rfield_polyline (n < 2, n < 3 when closed,
 * repeated consecutive vertices, bad p, non-finite coordinates);
 * DFL_E_NOMEM. */
dfl_status dfl_rfunc_batch_new(const double *v, size_t n, bool closed, int p,
                               dfl_rfunc_batch **out, dfl_err *err);
/* The same for a polyline of dimension dim (2 or 3; v holds n*dim
 * coordinates) with the disk or strip trim of eq. 4 (the kernels for the
 * strip trim and for 3D segments, beside the 2D disk one above).
 * DFL_E_INPUT as dfl_rfunc_batch_new and for the other trims. */
dfl_status dfl_rfunc_batch_new_opts(int dim, const double *v, size_t n, bool closed, int p,
                                    dfl_rfunc_trim trim, dfl_rfunc_batch **out, dfl_err *err);
/* R-equivalence of n >= 2 point parts c[0..n-1] (dim coordinates each;
 * rfunc/region.h's h = |x - c|) as a batch.  DFL_E_INPUT for n < 2, bad
 * dim or p, non-finite or out-of-domain coordinates; DFL_E_NOMEM. */
dfl_status dfl_rfunc_batch_points(int dim, const double *c, size_t n, int p,
                                  dfl_rfunc_batch **out, dfl_err *err);
/* R-equivalence of n >= 2 triangles t[0..n-1] (rfunc/tri3d.h) with one
 * eq. 4 trim for all: prism, or conditional with k = 2 and one weight a.
 * Per triangle two square roots (the R0-conjunctions) and one division
 * (the fold kept as fractions; batch_tri.c).  DFL_E_INPUT for other
 * options or bad p; DFL_E_NOMEM. */
dfl_status dfl_rfunc_batch_triangles(const dfl_rfunc_tri *t, size_t n, int p,
                                     dfl_rfunc_batch **out, dfl_err *err);
/* R-equivalence of n >= 2 convex regions r[0..n-1] (rfunc/region.h; 2D),
 * grouped by edge count.  Points inside a region get u = 0, grad u = 0
 * (the per-point path's values) without the fallback.  DFL_E_INPUT for
 * bad p; DFL_E_NOMEM. */
dfl_status dfl_rfunc_batch_regions(const dfl_rfunc_region *r, size_t n, int p,
                                   dfl_rfunc_batch **out, dfl_err *err);
void dfl_rfunc_batch_free(dfl_rfunc_batch *b);

/* A finished rfunc field as the batch builder reads it (rfield.c fills it
 * from its own state; everything is borrowed and must outlive the batch). */
typedef struct dfl_rfunc_batch_desc {
    int dim;                       /* 2 or 3 */
    dfl_rfunc_join join;
    int p;
    dfl_rfunc_correction corr;     /* the corrected join's form */
    const dfl_rfunc_part *parts;   /* n parts in the field's order */
    size_t n;
    const dfl_rfunc_vertex *verts; /* nv shared vertices, sorted by hi */
    size_t nv;
    const size_t *vstart;          /* n + 1 offsets into verts by hi */
    const dfl_field *slow;         /* the field's per-point path (fallback, reference) */
} dfl_rfunc_batch_desc;

/* The batch that computes the field d describes, or *out = NULL (DFL_OK)
 * when no kernel does (then the field stays on its per-point path).  The
 * kinds are tried in order: the built-in kernels above, then eq. 5 trims,
 * R-conjunction, the corrected join and mixed part kinds (batch_impl.h).
 * Errors only for what the machine did (DFL_E_NOMEM); *out NULL then. */
dfl_status dfl_rfunc_batch_build(const dfl_rfunc_batch_desc *d, dfl_rfunc_batch **out,
                                 dfl_err *err);

size_t dfl_rfunc_batch_segments(const dfl_rfunc_batch *b);
int dfl_rfunc_batch_order(const dfl_rfunc_batch *b);

/* Fast path: u at m points pts[dim i .. dim i + dim - 1] into val[i] and,
 * when grad is not NULL, its gradient into grad[dim i ...].  Serial
 * (callers parallelize over points, e.g. dfl_field_sample). */
void dfl_rfunc_batch_eval(const dfl_rfunc_batch *b, size_t m, const double *pts, double *val,
                          double *grad);

/* The library's per-point field (rfield built with the fast path off, so
 * it does not recurse into a batch) for the same polyline: the reference
 * and the fallback.  Borrowed; lives as long as b. */
const dfl_field *dfl_rfunc_batch_reference(const dfl_rfunc_batch *b);

/* Points of the last fast eval that took the fallback are not tracked;
 * this counts, for m points, how many would (a diagnostic for tests and the
 * benchmark; serial, no allocation). */
size_t dfl_rfunc_batch_fallbacks(const dfl_rfunc_batch *b, size_t m, const double *pts);

/* The polyline as a dfl_field (dim 2) whose eval is the fast path and whose
 * jets are the library's.  Errors as dfl_rfunc_batch_new. */
dfl_status dfl_rfunc_batch_field(const double *v, size_t n, bool closed, int p, dfl_field *out,
                                 dfl_err *err);

/* Vector width in doubles of the code the CPU dispatch selected for the
 * fast path (8: AVX-512, 4: AVX2, 2: SSE2), for flop-rate analysis. */
int dfl_rfunc_batch_simd_width(void);

#endif
