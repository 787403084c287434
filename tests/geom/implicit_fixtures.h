/* Fixtures of the implicit-surface tests: the torus of every file and
 * points in its frame.  Header-only (static), one rng sequence per test
 * process. */
#ifndef DFL_TESTS_GEOM_IMPLICIT_FIXTURES_H
#define DFL_TESTS_GEOM_IMPLICIT_FIXTURES_H

#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>

#include "core/rng.h"
#include "core/vec.h"
#include "geom/implicit.h"

static uint64_t rng_state = 0x9E3779B97F4A7C15ULL;
static inline double urand(double lo, double hi) { return dfl_rng_xorshift(&rng_state, lo, hi); }

static const double TC[3] = {0.1, -0.2, 0.05}, TAX[3] = {1, -1, 2}, TR = 0.5, Tr = 0.2;

static inline dfl_implicit *make_torus(dfl_foot_backend b)
{
    dfl_implicit_options opt;
    dfl_implicit_options_default(&opt);
    opt.backend = b;
    dfl_implicit *s = NULL;
    dfl_err err;
    cr_assert_eq(dfl_implicit_torus(TC, TAX, TR, Tr, &opt, &s, &err), DFL_OK, "%s", err.msg);
    return s;
}

/* A point at local cylindrical coordinates (rho, phi, z) of the torus frame. */
static inline void torus_point(double rho, double phi, double z, double x[3])
{
    double w[3], u[3], v[3], l = sqrt(dfl_vec3_dot(TAX, TAX));
    for (int j = 0; j < 3; j++) w[j] = TAX[j] / l;
    double t[3] = {1, 0, 0}, tw = dfl_vec3_dot(t, w);
    for (int j = 0; j < 3; j++) u[j] = t[j] - tw * w[j];
    l = sqrt(dfl_vec3_dot(u, u));
    for (int j = 0; j < 3; j++) u[j] /= l;
    dfl_vec3_cross(w, u, v);
    for (int j = 0; j < 3; j++)
        x[j] = TC[j] + rho * (cos(phi) * u[j] + sin(phi) * v[j]) + z * w[j];
}

#endif
