/* bs04 fields of straight line segments in 2D (sec. 2.1) and 3D (space
 * curves, sec. 3.1).
 *
 * Carrier.  2D: the signed line function of eq. 2,
 *     f = ((x - x1)(y2 - y1) - (y - y1)(x2 - x1)) / d,   d = |b - a|,
 * i.e. f = (x - a) . n with the unit normal n = (y2 - y1, -(x2 - x1)) / d.
 * 3D: f = sqrt(s^2 + q^2) with s, q the normal functions of two orthogonal
 * planes through the line (unit normals n1, n2 perpendicular to b - a).
 * Only f^2 enters h, so both dimensions share the code.
 *
 * Trims (t >= 0 inside, normalized to first order on the boundary):
 *   disk / sphere (eq. 3): t = ((d/2)^2 - |x - c|^2) / d, c = (a + b) / 2.
 *     Evaluated as t = -((x - a) . (x - b)) / d, the same polynomial
 *     (|x - c|^2 - (d/2)^2 = (x - a) . (x - b)), which is exactly 0 at the
 *     end points;
 *   strip / slab: the two lines (planes) orthogonal to the segment through
 *     its end points, p1 = (x - a) . e >= 0 and p2 = (b - x) . e >= 0
 *     (e = (b - a) / d), joined by the R0-conjunction (trim.h):
 *     t = p1 + p2 - sqrt(p1^2 + p2^2) = d - sqrt(p1^2 + p2^2)
 *     (p1 + p2 = d); |grad t| = |p2 - p1| / sqrt(p1^2 + p2^2) = 1 at p1 = 0
 *     and at p2 = 0.
 * The field is h of eq. 4 (trims *_DISK, *_STRIP) or eq. 5 (*_SMOOTH); see
 * trim.h for its normalization: every order for eq. 4, order 6 for eq. 5 at
 * interior points of the segment.
 */
#ifndef DFL_RFUNC_SEGMENT_H
#define DFL_RFUNC_SEGMENT_H

#include "core/jet.h"
#include "core/names.h"
#include "core/status.h"

/* The trims: one list from which the codes (0, 1, ... in this order),
 * their config names and their two properties come (core/names.h).
 * X(code, name, smooth: eq. 5 rather than eq. 4, strip: rather than disk). */
#define DFL_RFUNC_TRIM_LIST(X)                                    \
    X(DFL_RFUNC_TRIM_DISK, "disk", 0, 0)                          \
    X(DFL_RFUNC_TRIM_DISK_SMOOTH, "disk_smooth", 1, 0)            \
    X(DFL_RFUNC_TRIM_STRIP, "strip", 0, 1)                        \
    X(DFL_RFUNC_TRIM_STRIP_SMOOTH, "strip_smooth", 1, 1)

typedef enum dfl_rfunc_trim { DFL_RFUNC_TRIM_LIST(DFL_NAMES_CODE) } dfl_rfunc_trim;

/* Number of trims. */
enum { DFL_RFUNC_TRIM_COUNT = 0 DFL_RFUNC_TRIM_LIST(DFL_NAMES_ONE) };

/* Config names indexed by code (for dfl_cfg_enum-style readers: names,
 * DFL_RFUNC_TRIM_COUNT). */
extern const char *const dfl_rfunc_trim_names[DFL_RFUNC_TRIM_COUNT];

/* Config name of a trim ("disk", "disk_smooth", "strip", "strip_smooth");
 * "?" for a value outside the list. */
const char *dfl_rfunc_trim_name(dfl_rfunc_trim trim);

/* The trim whose config name is name (exact match) into *out; DFL_E_INPUT
 * naming the value and the accepted names otherwise (*out untouched). */
dfl_status dfl_rfunc_trim_parse(const char *name, dfl_rfunc_trim *out, dfl_err *err);

/* 1 for the eq. 5 trims (*_smooth: normalized to order 6 at interior
 * points), 0 for eq. 4 and for values outside the list. */
int dfl_rfunc_trim_smooth(dfl_rfunc_trim trim);

/* 1 for the strip (slab) trims, 0 for the disk (sphere) ones and for
 * values outside the list. */
int dfl_rfunc_trim_strip(dfl_rfunc_trim trim);

typedef struct dfl_rfunc_seg {
    int dim;              /* 2 or 3 */
    dfl_rfunc_trim trim;
    double a[3], b[3];    /* end points */
    double d;             /* length |b - a| > 0 */
    double e[3];          /* (b - a) / d */
    double n1[3];         /* 2D: eq. 2's unit normal; 3D: unit, perpendicular to e */
    double n2[3];         /* 3D: e x n1; unused in 2D */
    double scale;         /* max |coordinate| of a, b and d: for jet snapping */
} dfl_rfunc_seg;

/* Sets up the segment a-b.  DFL_E_INPUT for dim not 2/3, non-finite
 * coordinates, an unknown trim, or a degenerate segment (|b - a| <= 1e-12
 * times the size of the coordinates). */
dfl_status dfl_rfunc_seg_init(int dim, const double *a, const double *b, dfl_rfunc_trim trim,
                              dfl_rfunc_seg *out, dfl_err *err);

/* Carrier: 2D returns eq. 2's signed f, 3D the unsigned sqrt(s^2 + q^2);
 * gradient (dim doubles, may be NULL; 3D: 0 on the line). */
double dfl_rfunc_seg_line(const dfl_rfunc_seg *s, const double *x, double *grad);

/* Trim function t of the segment's trim region (disk or strip). */
double dfl_rfunc_seg_trim(const dfl_rfunc_seg *s, const double *x, double *grad);

/* Segment field h >= 0 and its gradient (may be NULL; 0 on the segment). */
double dfl_rfunc_seg_eval(const dfl_rfunc_seg *s, const double *x, double *grad);

/* Jet of h(x + s dir) at s = 0+ to absolute order K (0..DFL_JET_MAX).
 * Values that vanish in exact arithmetic (f at points of the line, t on
 * the trim boundary, f's slope along the line) are snapped to 0 within
 * DFL_RFUNC_SNAP_TOL relative, so that on the segment h has valuation 1 and
 * h^(-p) is exact. */
dfl_status dfl_rfunc_seg_jet(const dfl_rfunc_seg *s, const double *x, const double *dir, int K,
                             dfl_jet *out, dfl_err *err);

#endif
