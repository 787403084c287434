/* Small helpers shared by the rfunc tests (header-only, static). */
#ifndef DFL_TESTS_RFUNC_UTIL_H
#define DFL_TESTS_RFUNC_UTIL_H

#include <math.h>
#include <stdint.h>

#include "core/jet.h"
#include "core/rng.h"
#include "core/vec.h"
#include "field/field.h"

/* Deterministic uniform numbers in [lo, hi): core/rng.h's SplitMix64
 * sequence under the name the rfunc and rfunc-config tests use. */
static inline double tu_uniform(uint64_t *state, double lo, double hi)
{
    return dfl_rng_splitmix(state, lo, hi);
}

/* Central finite-difference gradient with step hstep. */
static inline void tu_fd_grad(const dfl_field *f, const double *x, double hstep, double *g)
{
    for (int j = 0; j < f->dim; j++) {
        double xp[3] = {x[0], x[1], f->dim == 3 ? x[2] : 0.0};
        double xm[3] = {x[0], x[1], f->dim == 3 ? x[2] : 0.0};
        xp[j] += hstep;
        xm[j] -= hstep;
        /* The actual step after rounding of the coordinates. */
        const double hh = xp[j] - xm[j];
        g[j] = (dfl_field_eval1(f, xp, NULL) - dfl_field_eval1(f, xm, NULL)) / hh;
    }
}

static inline double tu_norm(int dim, const double *v) { return sqrt(dfl_vecn_dot(dim, v, v)); }

/* Taylor coefficient of s^k (d_k / k!). */
static inline double tu_coeff(const dfl_jet *j, int k) { return dfl_jet_coeff(j, k); }

#endif
