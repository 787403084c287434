/* The joining-point setup of bs04 Fig. 4, 5 and 14: two segments of equal
 * length L sharing the vertex O = (0, 0), segment 1 from P1 = (L, 0) to O
 * and segment 2 from O to P2 = L (cos alpha, sin alpha), as the open
 * polyline P1, O, P2 (so the corrected join registers O as the shared
 * vertex of parts 1 and 2).
 *
 * Parts are either exact segment distances (geom/segdist.h; bs04's analysis
 * assumes them) or one of the library's trimmed segment fields
 * (rfunc/segment.h), named as in configs: "exact" or a trim's name.
 */
#ifndef DFL_EXPERIMENTS_VJOIN_H
#define DFL_EXPERIMENTS_VJOIN_H

#include <stdbool.h>

#include "core/status.h"
#include "field/field.h"
#include "io/config.h"
#include "rfunc/join.h"
#include "rfunc/segment.h"

/* Config names of the part kinds, index = dfl_vjoin.parts (0 = exact,
 * 1 + trim otherwise: the names of rfunc/segment.h's trim list). */
#define DFL_VJOIN_NPARTS (1 + DFL_RFUNC_TRIM_COUNT)
extern const char *const dfl_vjoin_part_names[DFL_VJOIN_NPARTS];

typedef struct dfl_vjoin {
    int parts;              /* 0: exact; 1 + dfl_rfunc_trim otherwise */
    double alpha;           /* radians, in (0, 2 pi) */
    double alpha_deg;       /* as given */
    double length;          /* L > 0 */
    double v[6];            /* P1, O, P2 */
    double e1[2], e2[2];    /* unit directions O -> P1, O -> P2 */
    dfl_rfunc_seg seg[2];   /* the library parts (trimmed kinds only) */
} dfl_vjoin;

/* alpha_deg in (0, 360) exclusive, length > 0 and finite, parts one of
 * the names' indices.  DFL_E_INPUT otherwise (message without file/line:
 * the caller prefixes it). */
dfl_status dfl_vjoin_init(double alpha_deg, double length, int parts, dfl_vjoin *out,
                          dfl_err *err);

/* Reads [sec] alpha (degrees), length (default 1) and parts (default
 * exact) into *out; errors name file:line and key. */
dfl_status dfl_vjoin_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_vjoin *out, dfl_err *err);

/* The joined field u (dfl_field_destroy releases it): the library's
 * dfl_rfield_polyline for trimmed parts, dfl_rfunc_exact_polyline_field for
 * exact ones.  DFL_E_INPUT for a bad p. */
dfl_status dfl_vjoin_field(const dfl_vjoin *vj, dfl_rfunc_join join, int p, dfl_field *out,
                           dfl_err *err);

/* dfl_vjoin_field with the corrected join's form corr (rfunc/join.h). */
dfl_status dfl_vjoin_field_corr(const dfl_vjoin *vj, dfl_rfunc_join join,
                                dfl_rfunc_correction corr, int p, dfl_field *out, dfl_err *err);

/* Both part fields at x: h[0..1] and, when g != NULL, their gradients
 * g[0..1] (part 1) and g[2..3] (part 2). */
void dfl_vjoin_parts(const dfl_vjoin *vj, const double *x, double *h, double *g);

/* Exact distance from x to the union of the two segments (gradient to g
 * when not NULL). */
double dfl_vjoin_dist(const dfl_vjoin *vj, const double *x, double *g);

/* 1 when x is in the hatched sector of O: the closest point of both
 * segments is O, i.e. x . e1 <= 0 and x . e2 <= 0 (exact test).  For
 * alpha = 180 degrees the sector degenerates to the line x . e1 = 0. */
bool dfl_vjoin_hatched(const dfl_vjoin *vj, const double *x);

/* Angular range [*t0, *t1] (radians, t0 <= t1, t0 in [0, 2 pi)) of the
 * hatched sector's directions: the closed wedge between the normals of the
 * two segments on the reflex side; its width is pi - alpha' (alpha' =
 * min(alpha, 2 pi - alpha)), 0 when alpha = pi (then the opposite ray
 * t0 + pi is hatched too; *nrays receives 2, else 1). */
void dfl_vjoin_hatched_range(const dfl_vjoin *vj, double *t0, double *t1, int *nrays);

/* Direction (radians in [0, 2 pi)) of the bisector of the convex sector
 * (the smaller angle alpha' between the segments): alpha/2 for alpha <= pi,
 * alpha/2 + pi otherwise.  For alpha = pi, both pi/2 and 3 pi/2 bisect; the
 * function returns pi/2. */
double dfl_vjoin_bisector(const dfl_vjoin *vj);

#endif
