/* The common field interface.
 *
 * A field is a scalar function u of a point in R^2 or R^3 (dim) that gives
 * its value and gradient in batches and, optionally, exact derivatives along
 * a ray through a jet.  Batches keep dispatch out of the per-point loop: the
 * samplers call eval once per chunk of points, in parallel chunks, so an
 * eval implementation must only read ctx (thread-safe) and must not allocate.
 *
 * Distances are in the units of the configuration; signed distance is
 * negative inside (bs04's unsigned fields are >= 0 everywhere).
 */
#ifndef DFL_FIELD_FIELD_H
#define DFL_FIELD_FIELD_H

#include <stddef.h>

#include "core/jet.h"
#include "core/status.h"

typedef struct dfl_field_ops {
    const char *name;
    /* Values at m points pts[i*dim + j]; writes val[i] and, when grad is not
     * NULL, grad[i*dim + j].  Must be thread-safe for a shared ctx. */
    void (*eval)(const void *ctx, size_t m, const double *pts, double *val, double *grad);
    /* Jet of s -> u(x + s dir) (core/jet.h's dfl_dir_jet_fn); NULL when the
     * field has no jets. */
    dfl_dir_jet_fn jet;
    /* Frees ctx.  May be NULL. */
    void (*destroy)(void *ctx);
    /* Stored bytes: what must be kept to evaluate the field (coefficients,
     * samples, proxies, cell tree, parameters), not scratch or caches of
     * the build.  NULL: unknown (dfl_field_bytes says so). */
    size_t (*bytes)(const void *ctx);
} dfl_field_ops;

typedef struct dfl_field {
    int dim;                  /* 2 or 3 */
    const dfl_field_ops *ops;
    void *ctx;                /* owned by the field; freed by dfl_field_destroy */
} dfl_field;

/* Value (and gradient when g != NULL) at one point: a convenience for tests
 * and slow paths, not for hot loops. */
double dfl_field_eval1(const dfl_field *f, const double *x, double *g);

/* Jet along dir; DFL_E_INPUT if the field has no jets or K is outside
 * [0, DFL_JET_MAX] (dfl_jet_dir_call). */
dfl_status dfl_field_jet(const dfl_field *f, const double *x, const double *dir, int K,
                         dfl_jet *out, dfl_err *err);

/* The stored bytes of f (ops->bytes) into *out and 1; 0 (out untouched)
 * when the field's kind does not say (ops->bytes NULL). */
int dfl_field_bytes(const dfl_field *f, size_t *out);

/* A placeholder of dimension dim (2 or 3) for a validation pass
 * (io/config.h dfl_cfg_validating): what a factory returns in place of a
 * field it did not build.  Its ops->name is "placeholder"; eval writes NaN
 * to every value and gradient component (a number nobody may take for a
 * result: an error of +inf), no jets, bytes unknown, nothing to free.
 * Never fails. */
void dfl_field_placeholder(int dim, dfl_field *out);

/* Releases ctx and zeroes *f.  f may be NULL or already destroyed. */
void dfl_field_destroy(dfl_field *f);

#endif
