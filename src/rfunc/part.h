/* The parts of an rfunc field (rfield.h) as one tagged type, shared by the
 * field (rfield.c, the per-point path) and the batched kernels (batch.h),
 * which read a finished field's parts and vertices to decide whether a
 * kernel computes it.
 *
 * Index:
 *   dfl_rfunc_part_kind  segment, triangle, point, region
 *   dfl_rfunc_part       one part: its kind and its data (the part modules')
 *   dfl_rfunc_vertex     a shared vertex of the corrected join (eq. 20)
 */
#ifndef DFL_RFUNC_PART_H
#define DFL_RFUNC_PART_H

#include <stddef.h>

#include "rfunc/region.h"
#include "rfunc/segment.h"
#include "rfunc/tri3d.h"

typedef enum dfl_rfunc_part_kind {
    DFL_RFUNC_PART_SEGMENT,  /* segment.h: 2D line piece or 3D space-curve piece */
    DFL_RFUNC_PART_TRIANGLE, /* tri3d.h: 3D only */
    DFL_RFUNC_PART_POINT,    /* region.h: h = |x - c| */
    DFL_RFUNC_PART_REGION    /* region.h: convex polygon, 2D only */
} dfl_rfunc_part_kind;

typedef struct dfl_rfunc_part {
    dfl_rfunc_part_kind kind;
    union {
        dfl_rfunc_seg seg;
        dfl_rfunc_tri tri;
        dfl_rfunc_point pt;
        dfl_rfunc_region reg;
    } u;
} dfl_rfunc_part;

/* A shared vertex x of the corrected join; lo < hi are its two adjacent
 * parts (indices in the field's part order).  The per-point loop handles
 * it right after part hi, when h_hi is at hand and h_lo is the previous
 * part, the first one, or re-evaluated. */
typedef struct dfl_rfunc_vertex {
    double x[3];
    size_t lo, hi;
} dfl_rfunc_vertex;

#endif
