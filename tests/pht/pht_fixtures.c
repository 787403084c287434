#include "pht/pht_fixtures.h"

#include <stdlib.h>

#include "core/rng.h"
#include "pht/hermite.h"

void pf_random_refine(dfl_tmesh *m, dfl_pht_split rule, int rounds, double frac, uint64_t seed)
{
    for (int r = 0; r < rounds; r++) {
        size_t n = dfl_tmesh_nleaves(m), k = 0;
        const size_t *leaves = dfl_tmesh_leaves(m);
        size_t *ids = malloc(n * sizeof *ids);
        for (size_t i = 0; i < n; i++)
            if (dfl_rng_splitmix(&seed, 0, 1) < frac) ids[k++] = leaves[i];
        if (k == 0) ids[k++] = leaves[(size_t)dfl_rng_splitmix(&seed, 0, (double)n) % n];
        dfl_status st = dfl_tmesh_refine(m, k, ids, rule, NULL);
        free(ids);
        if (st != DFL_OK) abort();
    }
}

void pf_poly_random(int dim, uint64_t seed, pf_poly *p)
{
    p->dim = dim;
    int n = dim == 2 ? 16 : 64;
    for (int i = 0; i < 64; i++) p->a[i] = i < n ? dfl_rng_splitmix(&seed, -1, 1) : 0.0;
}

/* d^r/dx^r x^e */
static double mono_d(int e, int r, double x)
{
    if (r > e) return 0.0;
    double c = 1.0, v = 1.0;
    for (int i = 0; i < r; i++) c *= e - i;
    for (int i = 0; i < e - r; i++) v *= x;
    return c * v;
}

double pf_poly_deriv(const pf_poly *p, const double *x, const int *b)
{
    int n = p->dim == 2 ? 16 : 64;
    double s = 0.0;
    for (int k = 0; k < n; k++) {
        double t = p->a[k];
        for (int j = 0; j < p->dim; j++) t *= mono_d((k >> (2 * j)) & 3, b[j], x[j]);
        s += t;
    }
    return s;
}

void pf_poly_hermite(const pf_poly *p, const double *x, double *data)
{
    for (int m = 0; m < DFL_PHT_NDATA(p->dim); m++) {
        int b[3] = {m & 1, (m >> 1) & 1, (m >> 2) & 1};
        data[m] = pf_poly_deriv(p, x, b);
    }
}
