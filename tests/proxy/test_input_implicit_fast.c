/* The robust implicit footpoint's fast path: the square-system Newton
 * reaches the sphere's exact footpoint, the fast path answers away from the
 * centre, and at the centre (every point a footpoint) the cap test hands
 * the point to the full search. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "core/rng.h"
#include "core/vec.h"
#include "proxy/input_implicit.h"
#include "proxy/input_implicit_fast.h"

Test(input_implicit_fast, sphere)
{
    const double c[3] = {0, 0, 0};
    dfl_implicit *s;
    cr_assert_eq(dfl_implicit_sphere(c, 0.5, NULL, &s, NULL), DFL_OK);
    double x[3] = {0.6, 0.3, -0.2}, p[3] = {0.45, 0.2, -0.1}, d;
    cr_assert(dfl_imp_square_newton(s, x, p, dfl_implicit_scale(s)));
    double l = dfl_vec3_norm(x);
    for (int j = 0; j < 3; j++) cr_assert(fabs(p[j] - 0.5 * x[j] / l) < 1e-14);
    dfl_imp_index *ix = dfl_imp_index_new(s);
    cr_assert_not_null(ix);
    cr_assert(dfl_imp_fast_foot(ix, x, p, &d));
    cr_assert(fabs(d - (l - 0.5)) < 1e-14);
    /* near the centre the far side is nearly as close: if the fast path
     * answers at all, it answers right */
    double y[3] = {0.01, -0.02, 0.005};
    if (dfl_imp_fast_foot(ix, y, p, &d)) cr_assert(fabs(d - (dfl_vec3_norm(y) - 0.5)) < 1e-14);
    double o[3] = {0, 0, 0};
    cr_assert(!dfl_imp_fast_foot(ix, o, p, &d));
    dfl_imp_index_free(ix);
    dfl_implicit_free(s);
}

/* The fast path's answer from its definition, without buckets: the
 * nearest sample (by brute force: at points inside the samples' box the
 * bucket search is exact, and ties at random points have probability 0),
 * Newton and the certificate as the fast path runs them, then the cap test
 * over every sample one at a time in the header's terms.  1 with p and d
 * when it answers. */
static int reference_fast_foot(const dfl_implicit *s, const double x[3], double p[3], double *d)
{
    size_t ns, bi = 0;
    const double *sp = dfl_implicit_samples(s, &ns);
    const double scale = dfl_implicit_scale(s), h = dfl_implicit_spacing(s);
    double best = HUGE_VAL;
    for (size_t t = 0; t < ns; t++) {
        double u[3] = {x[0] - sp[3 * t], x[1] - sp[3 * t + 1], x[2] - sp[3 * t + 2]};
        if (dfl_vec3_dot(u, u) < best) best = dfl_vec3_dot(u, u), bi = t;
    }
    for (int a = 0; a < 3; a++) p[a] = sp[3 * bi + a];
    if (!dfl_imp_square_newton(s, x, p, scale)) return 0;
    double G[3];
    const double gx = dfl_implicit_g(s, x, NULL, NULL);
    dfl_implicit_g(s, p, G, NULL);
    double u[3] = {x[0] - p[0], x[1] - p[1], x[2] - p[2]}, gn = dfl_vec3_norm(G);
    if (!(gn > 0)) return 0;
    const double dd = dfl_vec3_dot(u, G) / gn;
    if (fabs(dd) > 1e-12 * scale && (gx > 0) != (dd > 0)) return 0;
    if (!dfl_proxy_implicit_certify(s, x, p, dd)) return 0;
    const double rb = fabs(dd) + 2 * h;
    for (size_t t = 0; t < ns; t++) {
        const double *q0 = sp + 3 * t;
        double n[3], w[3] = {x[0] - q0[0], x[1] - q0[1], x[2] - q0[2]};
        double q[3] = {p[0] - q0[0], p[1] - q0[1], p[2] - q0[2]};
        if (dfl_vec3_dot(w, w) > rb * rb || dfl_vec3_dot(q, q) <= 4 * h * h) continue;
        dfl_implicit_g(s, q0, n, NULL);
        const double nl = dfl_vec3_norm(n);
        for (int a = 0; a < 3; a++) n[a] = nl > 0 ? n[a] / nl : 0.0;
        double tt[3], wn = dfl_vec3_dot(w, n);
        for (int a = 0; a < 3; a++) tt[a] = w[a] - wn * n[a];
        const double tl = dfl_vec3_norm(tt), ql = dfl_vec3_norm(q);
        if (!(dfl_vec3_dot(tt, q) >= 0.5 * tl * ql) || !(tl > 0)) return 0;
    }
    *d = dd;
    return 1;
}

/* The fast path (buckets, the cap test's lanes) answers as its definition
 * does, bit for bit, at random points inside the torus' box (inside and
 * outside the solid), on its axis and at its centre (where the cap test
 * must refuse) and at NaN; both answers and refusals occur. */
Test(input_implicit_fast, answers_as_its_definition)
{
    const double c[3] = {0.01, -0.02, 0.03}, ax[3] = {0, 0, 1};
    dfl_implicit *s;
    cr_assert_eq(dfl_implicit_torus(c, ax, 0.6, 0.25, NULL, &s, NULL), DFL_OK);
    dfl_imp_index *ix = dfl_imp_index_new(s);
    cr_assert_not_null(ix);
    uint64_t seed = 1919;
    int yes = 0, no = 0;
    enum { NQ = 400 };
    for (int k = 0; k < NQ + 3; k++) {
        double x[3] = {c[0] + dfl_rng_splitmix(&seed, -0.75, 0.75),
                       c[1] + dfl_rng_splitmix(&seed, -0.75, 0.75),
                       c[2] + dfl_rng_splitmix(&seed, -0.2, 0.2)};
        if (k == NQ) memcpy(x, c, sizeof x);                             /* centre */
        if (k == NQ + 1) for (int a = 0; a < 3; a++) x[a] = c[a] + 0.1 * ax[a]; /* axis */
        if (k == NQ + 2) x[1] = NAN;
        double p[3] = {0}, pr[3] = {0}, d = 0, dr = 0;
        const int f = dfl_imp_fast_foot(ix, x, p, &d), r = reference_fast_foot(s, x, pr, &dr);
        cr_assert_eq(f, r, "(%.17g %.17g %.17g): fast %d, definition %d", x[0], x[1], x[2], f, r);
        if (f) cr_assert(memcmp(p, pr, sizeof p) == 0 && memcmp(&d, &dr, sizeof d) == 0,
                         "(%.17g %.17g %.17g): d %.17g vs %.17g", x[0], x[1], x[2], d, dr);
        if (k >= NQ) cr_assert(!f, "point %d: the cap test must refuse", k - NQ);
        yes += f;
        no += !f;
    }
    cr_assert(yes > NQ / 4 && no > 10, "answered %d, refused %d", yes, no);
    dfl_imp_index_free(ix);
    dfl_implicit_free(s);
}
