/* bs04 fields of triangles in 3D (sec. 3.2.1).  Space-curve segments (sec.
 * 3.1) are the dim = 3 case of segment.h.
 *
 * Carrier: f = (x - A) . n, n the unit normal of the triangle ABC.
 * Trim: the three half-spaces p_i = (x - V_i) . m_i >= 0 bounded by the
 * planes through each edge orthogonal to the carrier (m_i the unit in-plane
 * normal of edge i pointing into the triangle), joined either by
 *   prism:        t = (p1 ^ p2) ^ p3 with the R0-conjunction of trim.h,
 *                 which is not differentiable on the three lines through the
 *                 vertices orthogonal to the carrier (bs04 Fig. 9a); or by
 *   conditional:  the conditional R-conjunction of eq. 15-16,
 *                 p1 ^_f p2 = p1 + p2 - sqrt(p1^2 + p2^2 + a f^k),
 *                 t = (p1 ^_f p2) ^_f p3 (a left fold, as eq. 16 is written),
 *                 which equals the prism conjunction on the carrier plane
 *                 and is analytic off it (bs04 Fig. 9b; a = 0.2, k = 2 by
 *                 default).  k must be a positive even integer so that
 *                 a f^k >= 0 and its Taylor series is a polynomial.
 * h is eq. 4 (smooth = 0) or eq. 5 (smooth = 1) of trim.h: on interior
 * points of the triangle it is |f| (every order) resp. |f| + |f|^7/(32 t^2)
 * (order 6).
 */
#ifndef DFL_RFUNC_TRI3D_H
#define DFL_RFUNC_TRI3D_H

#include "core/jet.h"
#include "core/names.h"
#include "core/status.h"

/* The triangle trims: one list from which the codes (0, 1 in this order)
 * and their config names come (core/names.h).  X(code, name, what it is). */
#define DFL_RFUNC_TRI_TRIM_LIST(X)                                            \
    X(DFL_RFUNC_TRI_PRISM, "prism", "R0-conjunction of the edge planes")      \
    X(DFL_RFUNC_TRI_CONDITIONAL, "conditional", "eq. 15-16")

typedef enum dfl_rfunc_tri_trim { DFL_RFUNC_TRI_TRIM_LIST(DFL_NAMES_CODE) } dfl_rfunc_tri_trim;

/* Number of triangle trims. */
enum { DFL_RFUNC_TRI_TRIM_COUNT = 0 DFL_RFUNC_TRI_TRIM_LIST(DFL_NAMES_ONE) };

/* Config names indexed by code (for dfl_cfg_enum-style readers). */
extern const char *const dfl_rfunc_tri_trim_names[DFL_RFUNC_TRI_TRIM_COUNT];

/* Config name of a triangle trim ("prism", "conditional"); "?" for a value
 * outside the list. */
const char *dfl_rfunc_tri_trim_name(dfl_rfunc_tri_trim trim);

/* The triangle trim whose config name is name into *out; DFL_E_INPUT
 * naming the value and the accepted names otherwise (*out untouched). */
dfl_status dfl_rfunc_tri_trim_parse(const char *name, dfl_rfunc_tri_trim *out, dfl_err *err);

typedef struct dfl_rfunc_tri_opts {
    dfl_rfunc_tri_trim trim;
    int smooth;           /* 0: eq. 4, 1: eq. 5 */
    double a;             /* conditional term weight > 0 (default 0.2) */
    int k;                /* conditional term power, even >= 2 (default 2) */
} dfl_rfunc_tri_opts;

/* The paper's defaults: conditional trim, eq. 4, a = 0.2, k = 2. */
dfl_rfunc_tri_opts dfl_rfunc_tri_defaults(void);

typedef struct dfl_rfunc_tri {
    dfl_rfunc_tri_opts o;
    double v[3][3];       /* vertices A, B, C */
    double n[3];          /* unit normal */
    double m[3][3];       /* inward unit edge normals; edge i runs v[i] -> v[(i+1)%3] */
    double scale;         /* max |coordinate| and edge length, for jet snapping */
} dfl_rfunc_tri;

/* DFL_E_INPUT for non-finite or collinear vertices (area <= 1e-12 times the
 * square of the longest edge), a <= 0 or k not even and >= 2. */
dfl_status dfl_rfunc_tri_init(const double *A, const double *B, const double *C,
                              const dfl_rfunc_tri_opts *o, dfl_rfunc_tri *out, dfl_err *err);

/* Trim function t and gradient (may be NULL). */
double dfl_rfunc_tri_trim_eval(const dfl_rfunc_tri *t, const double *x, double *grad);

/* Triangle field h >= 0 and gradient (may be NULL; 0 on the triangle). */
double dfl_rfunc_tri_eval(const dfl_rfunc_tri *t, const double *x, double *grad);

/* Jet of h along x + s dir to absolute order K (snapping as in segment.h). */
dfl_status dfl_rfunc_tri_jet(const dfl_rfunc_tri *t, const double *x, const double *dir, int K,
                             dfl_jet *out, dfl_err *err);

#endif
