/* Proxy inputs (hvb25 Sec. 5): what a proxy grid asks of the surface it
 * approximates, whatever represents it (parametric, SDF or implicit).
 *
 * Function index
 *   dfl_surfpoint          one answer: footpoint, normal, signed distance,
 *                          principal curvatures and directions, certificate
 *   dfl_proxy_input        an input: a batched query function and its context
 *   dfl_proxy_input_query  answer a batch of query points
 *   dfl_proxy_input_free   release an input
 *   dfl_curvature_set_nan  the "not asked for / not available" curvature
 *
 * Conventions: curvatures and directions follow geom/curvature.h (the
 * eigenvalues of dn for the normal n stored here; a sphere with outward
 * normal has kappa = +1/r).  n points to the side of positive signed
 * distance: outward where the shape has an inside (negative inside, as
 * everywhere in dflab), else towards x.  x = p + d n up to the footpoint
 * solver's tolerance.
 *
 * Constructors live beside each representation (proxy/input_*.h); this
 * header is the one interface the proxy grid builder (proxy/proxy.h) uses.
 */
#ifndef DFL_PROXY_INPUT_H
#define DFL_PROXY_INPUT_H

#include <stddef.h>

#include "core/status.h"
#include "geom/curvature.h"

typedef struct dfl_surfpoint {
    double p[3];         /* footpoint: the closest surface point found */
    double n[3];         /* unit normal at p (see the convention above) */
    double d;            /* signed distance from p to x along n */
    dfl_curvature curv;  /* at p, w.r.t. n; all NAN when curvature was not asked for */
    int certified;       /* 1: p is certified (or, for inputs without a certificate,
                            claimed) the closest point; 0: the solver failed or
                            could not certify it (p, n, d are then its best guess,
                            finite, or NAN when it has none) */
} dfl_surfpoint;

/* Answers the queries x[3i..3i+2], i < m, into out[i].  need_curv = 0 lets
 * the input skip curvature (order-1 proxies).  Must be thread-safe for a
 * shared ctx (the builder calls it from OpenMP threads on disjoint chunks)
 * and must not allocate per point.  Returns DFL_OK when every point got an
 * answer, certified or not; an error status only when the machine failed or
 * the input is unusable (err filled). */
typedef dfl_status (*dfl_proxy_query_fn)(const void *ctx, size_t m, const double *x,
                                         int need_curv, dfl_surfpoint *out, dfl_err *err);

typedef struct dfl_proxy_input {
    const char *name;          /* "parametric", "sdf" or "implicit" (static string) */
    dfl_proxy_query_fn query;
    void (*destroy)(void *ctx); /* may be NULL */
    void *ctx;                 /* owned by the input */
    int has_inside;            /* 1 when the shape is closed and d is signed */
} dfl_proxy_input;

/* Calls in->query; DFL_E_INPUT when in or in->query is NULL. */
dfl_status dfl_proxy_input_query(const dfl_proxy_input *in, size_t m, const double *x,
                                 int need_curv, dfl_surfpoint *out, dfl_err *err);

/* Sets every field of *c to NAN (what inputs write when curvature was not
 * asked for or could not be computed). */
void dfl_curvature_set_nan(dfl_curvature *c);

/* Releases ctx and zeroes *in.  in may be NULL or already freed. */
void dfl_proxy_input_free(dfl_proxy_input *in);

#endif
