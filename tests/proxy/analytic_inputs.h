/* Test-local proxy inputs (proxy/input.h) with exact footpoints and
 * curvatures: sphere, cylinder, plane, torus.  The sphere, cylinder and
 * torus have an inside (signed d, outward n); the plane's positive side is
 * the one its normal points to (has_inside = 1 too: it is a half-space).
 * Every answer is certified; points on an axis / centre get an arbitrary
 * but finite footpoint. */
#ifndef DFL_TESTS_PROXY_ANALYTIC_INPUTS_H
#define DFL_TESTS_PROXY_ANALYTIC_INPUTS_H

#include "proxy/input.h"

typedef enum ta_kind { TA_SPHERE, TA_CYLINDER, TA_PLANE, TA_TORUS } ta_kind;

typedef struct ta_shape {
    ta_kind kind;
    double c[3];   /* centre / point on axis / point on plane */
    double a[3];   /* unit axis (cylinder, torus) or normal (plane) */
    double R, r;   /* sphere, cylinder: R; torus: major R, minor r */
} ta_shape;

/* The input (ctx points to *s, which must outlive it; destroy is NULL). */
void ta_input(const ta_shape *s, dfl_proxy_input *out);
/* One exact answer. */
void ta_answer(const ta_shape *s, const double x[3], dfl_surfpoint *out);
/* The exact signed distance. */
double ta_sdf(const ta_shape *s, const double x[3]);

#endif
