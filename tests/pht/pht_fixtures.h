/* Shared helpers of the pht tests: seeded random refinement of T-meshes and
 * tensor-product cubic polynomials in world coordinates with their exact
 * derivatives. */
#ifndef DFL_TESTS_PHT_FIXTURES_H
#define DFL_TESTS_PHT_FIXTURES_H

#include <stdint.h>

#include "pht/tmesh.h"

/* `rounds` rounds; each splits every leaf with probability frac (at least
 * one leaf per round), by rule.  Deterministic for seed. */
void pf_random_refine(dfl_tmesh *m, dfl_pht_split rule, int rounds, double frac, uint64_t seed);

/* P(x) = sum a[i + 4j + 16k] x^i y^j z^k (4^dim coefficients). */
typedef struct pf_poly {
    int dim;
    double a[64];
} pf_poly;

void pf_poly_random(int dim, uint64_t seed, pf_poly *p);
/* d^b P at x, b a derivative multi-index (orders per axis, each 0..3). */
double pf_poly_deriv(const pf_poly *p, const double *x, const int *b);
/* Hermite data in mask order (pht/hermite.h) at x. */
void pf_poly_hermite(const pf_poly *p, const double *x, double *data);

#endif
