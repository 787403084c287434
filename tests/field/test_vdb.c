/* Tests for field/vdb (direct fill and samplers): voxel values are the
 * exact SDF at voxel centres rounded to float, the band is complete (brute
 * force over the index range), inactive voxels hold +-background by side,
 * BoxSampler is exact at voxel centres and on affine data, QuadraticSampler
 * on quadratic data (off the lattice), the staggered lattice, gradients of
 * both, memory against its bound and against 1/voxel, the band accessors,
 * and bad input. */
#include <criterion/criterion.h>

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "field/vdb.h"
#include "util/per_isa.h"

static const double C[3] = {0.01, -0.02, 0.03}, R = 0.5;

static dfl_shape sphere(void)
{
    dfl_shape s;
    cr_assert_eq(dfl_shape_sphere(C, R, &s, NULL), DFL_OK);
    return s;
}

static double sdf(const double x[3])
{
    const double d[3] = {x[0] - C[0], x[1] - C[1], x[2] - C[2]};
    return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) - R;
}

static dfl_vdb *build(const dfl_shape *s, double voxel, int band, dfl_vdb_sampler smp,
                      double lipschitz)
{
    dfl_vdb_opts o;
    dfl_vdb_opts_default(&o);
    o.voxel = voxel;
    o.band = band;
    o.sampler = smp;
    o.lipschitz = lipschitz;
    dfl_vdb *g = NULL;
    dfl_err err;
    cr_assert_eq(dfl_vdb_from_shape(s, &o, &g, &err), DFL_OK, "%s", err.msg);
    return g;
}

/* The index range I of [-1, 1]^3 (vdb.h: floor(l) - 1 .. ceil(u) + 1). */
static void index_range(double voxel, double shift, int *lo, int *hi)
{
    *lo = (int)floor(-1 / voxel - shift) - 1;
    *hi = (int)ceil(1 / voxel - shift) + 1;
}

/* A polynomial "shape": q(x) = c0 + g.x + x.A x (A symmetric), with a
 * Lipschitz bound supplied by the test. */
typedef struct poly {
    double c0, g[3], A[3][3];
} poly;

static double poly_at(const poly *p, const double *x)
{
    double v = p->c0;
    for (int i = 0; i < 3; i++) {
        v += p->g[i] * x[i];
        for (int j = 0; j < 3; j++) v += x[i] * p->A[i][j] * x[j];
    }
    return v;
}

static void poly_grad(const poly *p, const double *x, double *g)
{
    for (int i = 0; i < 3; i++) {
        g[i] = p->g[i];
        for (int j = 0; j < 3; j++) g[i] += 2 * p->A[i][j] * x[j];
    }
}

static void poly_eval(const void *impl, size_t m, const double *pts, double *val, double *grad)
{
    for (size_t i = 0; i < m; i++) {
        val[i] = poly_at(impl, pts + 3 * i);
        if (grad) poly_grad(impl, pts + 3 * i, grad + 3 * i);
    }
}

static const dfl_shape_ops poly_ops = {"poly", poly_eval, NULL, NULL, NULL};

/* q = 0.05 + 0.3 x + 0.2 y - 0.1 z + 0.04 x^2 - 0.03 y z + 0.02 z^2 (quadratic)
 * or its affine part.  The band search evaluates q at block centres up to
 * 128 voxels (6.4 at voxel 0.05) beyond the box, where |grad q| <=
 * |(0.3 + 0.08 * 7, 0.2 + 0.03 * 7, 0.1 + 0.03 * 7 + 0.04 * 7)| < 1.2: L = 1.5. */
static poly quad(int quadratic)
{
    poly p = {0.05, {0.3, 0.2, -0.1}, {{0}}};
    if (quadratic) {
        p.A[0][0] = 0.04;
        p.A[1][2] = p.A[2][1] = -0.015;
        p.A[2][2] = 0.02;
    }
    return p;
}

Test(vdb, direct_fill_is_the_sdf_at_voxel_centres_and_complete)
{
    dfl_shape s = sphere();
    const double h = 0.05;
    dfl_vdb *g = build(&s, h, 3, DFL_VDB_BOX, 1);
    const double b = dfl_vdb_background(g);
    cr_assert_eq(b, (double)(float)(3 * h));
    const size_t n = dfl_vdb_active_count(g);
    cr_assert_gt(n, 0);
    int *ijk = malloc(3 * n * sizeof *ijk);
    float *v = malloc(n * sizeof *v);
    cr_assert_eq(dfl_vdb_active_voxels(g, n, ijk, v), n);
    for (size_t i = 0; i < n; i++) {
        double x[3];
        dfl_vdb_voxel_centre(g, ijk + 3 * i, x);
        for (int a = 0; a < 3; a++) cr_assert_eq(x[a], ijk[3 * i + a] * h);
        const double d = sdf(x);
        cr_assert_eq(v[i], (float)d, "voxel %d %d %d: %.9g vs %.9g", ijk[3 * i], ijk[3 * i + 1],
                     ijk[3 * i + 2], v[i], d);
        cr_assert_lt(fabs(d), b);
    }
    /* brute force over I: every voxel with |d| < b is active, every other
     * one holds +-b by the sign of d */
    int lo, hi;
    index_range(h, 0, &lo, &hi);
    size_t want = 0;
    for (int i = lo; i <= hi; i++)
        for (int j = lo; j <= hi; j++)
            for (int k = lo; k <= hi; k++) {
                const int c[3] = {i, j, k};
                const double x[3] = {i * h, j * h, k * h}, d = sdf(x);
                int on;
                const float val = dfl_vdb_voxel_value(g, c, &on);
                if (fabs(d) < b) {
                    want++;
                    cr_assert(on, "voxel %d %d %d, d = %g, inactive", i, j, k, d);
                } else {
                    cr_assert(!on);
                    cr_assert_eq(val, d < 0 ? -(float)b : (float)b, "voxel %d %d %d: %g (d %g)",
                                 i, j, k, val, d);
                }
            }
    cr_assert_eq(want, n);
    /* the search evaluated far fewer points than the dense range */
    const double dense = pow(hi - lo + 1, 3);
    cr_expect_lt((double)dfl_vdb_evals(g), dense, "%zu evals vs %g", dfl_vdb_evals(g), dense);
    free(ijk);
    free(v);
    dfl_vdb_free(g);
    dfl_shape_free(&s);
}

/* voxel 1/16: x = i h and x / h are exact, so the sampler's index point
 * is the voxel itself */
Test(vdb, box_sampler_at_voxel_centres_is_the_voxel_value)
{
    dfl_shape s = sphere();
    const double h = 0.0625;
    dfl_vdb *g = build(&s, h, 3, DFL_VDB_BOX, 1);
    const size_t n = dfl_vdb_active_count(g);
    int *ijk = malloc(3 * n * sizeof *ijk);
    float *v = malloc(n * sizeof *v);
    dfl_vdb_active_voxels(g, n, ijk, v);
    for (size_t i = 0; i < n; i += 7) {
        double x[3], u, gr[3];
        dfl_vdb_voxel_centre(g, ijk + 3 * i, x);
        dfl_vdb_sample(g, DFL_VDB_BOX, 1, x, &u, gr);
        cr_assert_eq(u, (double)v[i]);
        /* the gradient at a centre: the central difference of the voxels */
        for (int a = 0; a < 3; a++) {
            int p[3] = {ijk[3 * i], ijk[3 * i + 1], ijk[3 * i + 2]}, m[3];
            memcpy(m, p, sizeof m);
            p[a]++, m[a]--;
            const double cd =
                ((double)dfl_vdb_voxel_value(g, p, NULL) - dfl_vdb_voxel_value(g, m, NULL)) /
                (2 * h);
            /* float rounding of the two half-way means: 2 ulps of b each */
            cr_assert_leq(fabs(gr[a] - cd), 4 * FLT_EPSILON * dfl_vdb_background(g) / h, "axis %d: %g vs %g", a,
                          gr[a], cd);
        }
    }
    free(ijk);
    free(v);
    dfl_vdb_free(g);
    dfl_shape_free(&s);
}

Test(vdb, outside_the_band_the_value_is_the_signed_background)
{
    dfl_shape s = sphere();
    dfl_vdb *g = build(&s, 0.05, 3, DFL_VDB_QUADRATIC, 1);
    const double b = dfl_vdb_background(g);
    /* the centre (d = -0.5), a point beyond the box's leaves, a box corner,
     * a point outside the band (d = b + 0.3: the quadratic stencil with the
     * gradient's half steps reaches 2.5 voxels per axis, 0.22 away, so
     * every voxel it reads has |d| >= b) */
    const double pts[4][3] = {{C[0], C[1], C[2]},
                              {0.97, 0.95, -0.99},
                              {1, 1, 1},
                              {C[0] + R + b + 0.3, C[1], C[2]}};
    const double sign[4] = {-1, 1, 1, 1};
    for (int smp = 0; smp < DFL_VDB_SAMPLER_COUNT; smp++)
        for (int i = 0; i < 4; i++) {
            double u, gr[3];
            dfl_vdb_sample(g, (dfl_vdb_sampler)smp, 1, pts[i], &u, gr);
            cr_assert_eq(u, sign[i] * b, "sampler %d point %d: %.9g", smp, i, u);
            for (int a = 0; a < 3; a++) cr_assert_eq(gr[a], 0);
        }
    /* far outside the box: the tree's background, +b */
    const double far[3] = {40, 0, 0};
    double u;
    dfl_vdb_sample(g, DFL_VDB_BOX, 1, far, &u, NULL);
    cr_assert_eq(u, b);
    dfl_vdb_free(g);
    dfl_shape_free(&s);
}

/* A bound of |q| over the box widened by two voxels (|x_j| <= 1.1). */
static double poly_max(const poly *p)
{
    double m = fabs(p->c0);
    for (int i = 0; i < 3; i++) {
        m += fabs(p->g[i]) * 1.1;
        for (int j = 0; j < 3; j++) m += fabs(p->A[i][j]) * 1.21;
    }
    return m;
}

/* Rounding of a sampler result: the stored floats err by 2^-24 |q| and
 * each of the 13 one-dimensional parabola (or 7 lerp) evaluations rounds
 * to float once; Lagrange weights on [0, 1) sum in magnitude to at most
 * 1.25 per axis, so errors grow by at most 1.25^3 < 2 across the three
 * stages: below 32 float epsilons of the largest |q|. */
static double sampler_tol(const poly *p) { return 32 * FLT_EPSILON * poly_max(p); }

static void check_reproduces(dfl_vdb_sampler smp, const poly *p, int expect_exact)
{
    dfl_shape s = {3, &poly_ops, (void *)p};
    const double h = 0.05;
    /* band 40 voxels = 2 > max |q| in the box: every voxel of I is active */
    dfl_vdb *g = build(&s, h, 40, smp, 1.5);
    uint64_t seed = 11;
    const double tol = sampler_tol(p);
    double worst = 0, gworst = 0;
    for (int t = 0; t < 500; t++) {
        double x[3], u, gr[3], ge[3];
        for (int a = 0; a < 3; a++) x[a] = dfl_rng_splitmix(&seed, -0.95, 0.95);
        dfl_vdb_sample(g, smp, 1, x, &u, gr);
        poly_grad(p, x, ge);
        worst = fmax(worst, fabs(u - poly_at(p, x)));
        for (int a = 0; a < 3; a++) gworst = fmax(gworst, fabs(gr[a] - ge[a]));
    }
    if (expect_exact) {
        cr_assert_leq(worst, tol, "value error %g > %g", worst, tol);
        /* central differences (step h/2) are exact on a quadratic: only the
         * two values' rounding remains, divided by h */
        cr_assert_leq(gworst, 2 * tol / h, "gradient error %g > %g", gworst, 2 * tol / h);
    } else {
        cr_assert_gt(worst, 4 * tol, "value error %g: the data were not quadratic enough", worst);
    }
    dfl_vdb_free(g);
}

Test(vdb, quadratic_sampler_reproduces_a_quadratic_off_the_lattice)
{
    const poly q = quad(1);
    check_reproduces(DFL_VDB_QUADRATIC, &q, 1);
    /* the trilinear box sampler errs by about h^2 / 8 |q''| on the same data */
    check_reproduces(DFL_VDB_BOX, &q, 0);
}

Test(vdb, box_and_staggered_reproduce_affine_data)
{
    const poly a = quad(0);
    check_reproduces(DFL_VDB_BOX, &a, 1);
    check_reproduces(DFL_VDB_STAGGERED, &a, 1);
    check_reproduces(DFL_VDB_QUADRATIC, &a, 1);
}

Test(vdb, staggered_lattice_is_shifted_by_half_a_voxel)
{
    dfl_shape s = sphere();
    const double h = 0.0625;
    dfl_vdb *g = build(&s, h, 3, DFL_VDB_STAGGERED, 1);
    cr_assert_eq(dfl_vdb_lattice_sampler(g), DFL_VDB_STAGGERED);
    const size_t n = dfl_vdb_active_count(g);
    int *ijk = malloc(3 * n * sizeof *ijk);
    float *v = malloc(n * sizeof *v);
    dfl_vdb_active_voxels(g, n, ijk, v);
    for (size_t i = 0; i < n; i++) {
        double x[3], u;
        dfl_vdb_voxel_centre(g, ijk + 3 * i, x);
        for (int a = 0; a < 3; a++) cr_assert_eq(x[a], (ijk[3 * i + a] - 0.5) * h);
        cr_assert_eq(v[i], (float)sdf(x));
        if (i % 5) continue;
        dfl_vdb_sample(g, DFL_VDB_STAGGERED, 1, x, &u, NULL);
        cr_assert_eq(u, (double)v[i]);
    }
    /* a centred grid differs there: its voxels sit half a voxel away */
    dfl_vdb *c = build(&s, h, 3, DFL_VDB_BOX, 1);
    double x[3], uc, us;
    dfl_vdb_voxel_centre(g, ijk, x);
    dfl_vdb_sample(c, DFL_VDB_BOX, 1, x, &uc, NULL);
    dfl_vdb_sample(g, DFL_VDB_BOX, 1, x, &us, NULL);
    cr_assert_neq(uc, us);
    free(ijk);
    free(v);
    dfl_vdb_free(c);
    dfl_vdb_free(g);
    dfl_shape_free(&s);
}

/* Memory: the internal nodes above the leaves are a fixed cost (a sphere
 * around the origin meets 8 of the 4096^3 nodes, 8 x 266 kB), the leaves
 * grow like the band, about 4 pi R^2 2 b / h^3 = 24 pi R^2 / h^2 voxels
 * (x4 per halving of h); every new active voxel costs at least its float. */
Test(vdb, bytes_positive_bounded_and_growing_with_resolution)
{
    dfl_shape s = sphere();
    size_t prev_bytes = 0, prev_act = 0;
    for (int l = 0; l < 3; l++) {
        const double h = 0.04 / (1 << l);
        dfl_vdb *g = build(&s, h, 3, DFL_VDB_BOX, 1);
        dfl_vdb_opts o;
        dfl_vdb_opts_default(&o);
        o.voxel = h;
        const size_t bytes = dfl_vdb_bytes(g), act = dfl_vdb_active_count(g);
        cr_assert_gt(bytes, act * sizeof(float));
        cr_assert_leq((double)bytes, dfl_vdb_bytes_bound(&o, NULL), "h %g: %zu bytes", h, bytes);
        cr_assert_gt(dfl_vdb_build_seconds(g), 0);
        if (l) {
            cr_assert_geq(bytes - prev_bytes, (act - prev_act) * sizeof(float),
                          "h %g: %zu vs %zu bytes", h, bytes, prev_bytes);
            const double r = (double)act / (double)prev_act;
            cr_assert(r > 3.5 && r < 4.5, "h %g: active ratio %g", h, r);
        }
        prev_bytes = bytes, prev_act = act;
        dfl_vdb_free(g);
    }
    dfl_shape_free(&s);
}

Test(vdb, band_accessors_and_field)
{
    dfl_shape s = sphere();
    dfl_vdb *g = build(&s, 0.04, 5, DFL_VDB_QUADRATIC, 1);
    cr_assert_eq(dfl_vdb_band(g), 5);
    cr_assert_eq(dfl_vdb_voxel(g), 0.04);
    cr_assert_eq(dfl_vdb_background(g), (double)(float)(5 * 0.04));
    dfl_vdb *keep = g;
    dfl_field f;
    cr_assert_eq(dfl_vdb_field_new(&g, DFL_VDB_QUADRATIC, &f, NULL), DFL_OK);
    cr_assert_null(g);
    dfl_vdb_sampler smp;
    cr_assert_eq(dfl_vdb_field_grid(&f, &smp), keep);
    cr_assert_eq(smp, DFL_VDB_QUADRATIC);
    cr_assert_eq(f.dim, 3);
    const double x[3] = {0.53, 0.01, 0.02};
    double u1, u2, g1[3], g2[3];
    u1 = dfl_field_eval1(&f, x, g1);
    dfl_vdb_sample(keep, DFL_VDB_QUADRATIC, 1, x, &u2, g2);
    cr_assert_eq(u1, u2);
    cr_assert_lt(fabs(u1 - sdf(x)), 1e-3);
    dfl_field e = {3, NULL, NULL};
    cr_assert_null(dfl_vdb_field_grid(&e, NULL));
    dfl_field_destroy(&f);
    dfl_shape_free(&s);
}

static void nan_eval(const void *impl, size_t m, const double *pts, double *val, double *grad)
{
    (void)impl, (void)grad;
    for (size_t i = 0; i < m; i++) val[i] = pts[3 * i] > 0.3 ? NAN : pts[3 * i] - 0.2;
}

static const dfl_shape_ops nan_ops = {"nan", nan_eval, NULL, NULL, NULL};

Test(vdb, bad_input)
{
    dfl_shape s = sphere();
    dfl_vdb_opts o;
    dfl_vdb *g = NULL;
    dfl_err err;
#define BAD(field, value, code)                                              \
    do {                                                                     \
        dfl_vdb_opts_default(&o);                                            \
        o.field = value;                                                     \
        cr_assert_eq(dfl_vdb_from_shape(&s, &o, &g, &err), code, #field);    \
        cr_assert_null(g);                                                   \
        cr_assert_eq(dfl_vdb_bytes_bound(&o, NULL), 0);                      \
    } while (0)
    BAD(voxel, 0, DFL_E_INPUT);
    BAD(voxel, -1, DFL_E_INPUT);
    BAD(voxel, NAN, DFL_E_INPUT);
    BAD(voxel, 1e-12, DFL_E_INPUT); /* 1e12 voxels from the origin */
    BAD(voxel, 2.0 / 32768, DFL_E_INPUT); /* 32768 + 3 voxels per axis */
    BAD(band, 0, DFL_E_INPUT);
    BAD(hi[1], -1, DFL_E_INPUT);
    BAD(lo[2], INFINITY, DFL_E_INPUT);
#undef BAD
    dfl_vdb_opts_default(&o);
    o.lipschitz = 0.5;
    cr_assert_eq(dfl_vdb_from_shape(&s, &o, &g, &err), DFL_E_INPUT);
    dfl_shape c;
    const double c2[2] = {0, 0};
    cr_assert_eq(dfl_shape_circle(c2, 0.5, &c, NULL), DFL_OK);
    dfl_vdb_opts_default(&o);
    cr_assert_eq(dfl_vdb_from_shape(&c, &o, &g, &err), DFL_E_INPUT);
    dfl_shape_free(&c);
    dfl_shape n = {3, &nan_ops, NULL};
    cr_assert_eq(dfl_vdb_from_shape(&n, &o, &g, &err), DFL_E_NUMERIC);
    cr_assert_null(g);
    /* meshes */
    double verts[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    size_t tris[3] = {0, 1, 3};
    dfl_trimesh m = {0};
    m.nverts = 3, m.verts = verts, m.tris = tris;
    cr_assert_eq(dfl_vdb_from_mesh(&m, &o, &g, &err), DFL_E_INPUT, "no triangles");
    m.ntris = 1;
    cr_assert_eq(dfl_vdb_from_mesh(&m, &o, &g, &err), DFL_E_INPUT, "index 3 of 3");
    tris[2] = 2;
    verts[4] = NAN;
    cr_assert_eq(dfl_vdb_from_mesh(&m, &o, &g, &err), DFL_E_INPUT, "a NaN vertex");
    cr_assert_null(g);
    cr_assert_eq(dfl_vdb_sampler_parse("quadratic", &(dfl_vdb_sampler){0}, NULL), DFL_OK);
    cr_assert_eq(dfl_vdb_sampler_parse("cubic", &(dfl_vdb_sampler){0}, NULL), DFL_E_INPUT);
    dfl_shape_free(&s);
}

/* The checks of nan_and_infinite_queries on one ISA: the number of
 * failures (printed to stderr). */
static int odd_queries(const void *ctx)
{
    (void)ctx;
    enum { M = 16 };
    dfl_shape s;
    if (dfl_shape_sphere(C, R, &s, NULL) != DFL_OK) return 1;
    int bad = 0;
    for (int smp = 0; smp < DFL_VDB_SAMPLER_COUNT; smp++) {
        dfl_vdb_opts o;
        dfl_vdb_opts_default(&o);
        o.voxel = 0.05;
        o.sampler = (dfl_vdb_sampler)smp;
        dfl_vdb *g = NULL;
        if (dfl_vdb_from_shape(&s, &o, &g, NULL) != DFL_OK) {
            bad++;
            continue;
        }
        const double b = dfl_vdb_background(g);
        double x[3 * M];
        uint64_t seed = 3;
        for (int i = 0; i < 3 * M; i++) x[i] = dfl_rng_splitmix(&seed, -0.7, 0.7);
        /* NaN on each axis; +-inf and +-1e300 on each axis: far points */
        x[3 * 1 + 0] = NAN, x[3 * 3 + 1] = -NAN, x[3 * 5 + 2] = NAN;
        x[3 * 7 + 0] = NAN, x[3 * 7 + 1] = INFINITY;
        x[3 * 2 + 0] = INFINITY, x[3 * 4 + 1] = -INFINITY, x[3 * 6 + 2] = INFINITY;
        x[3 * 8 + 0] = -INFINITY, x[3 * 9 + 1] = 1e300, x[3 * 10 + 2] = -1e300;
        x[3 * 11 + 0] = 1e12; /* index 2e13: beyond int */
        for (int sq = 0; sq < DFL_VDB_SAMPLER_COUNT; sq++)
            for (int wg = 0; wg < 2; wg++) {
                double v[M], gr[3 * M];
                dfl_vdb_sample(g, (dfl_vdb_sampler)sq, M, x, v, wg ? gr : NULL);
                for (int i = 0; i < M; i++) {
                    int nan = 0, fin = 1;
                    for (int a = 0; a < 3; a++) {
                        nan |= isnan(x[3 * i + a]);
                        fin &= fabs(x[3 * i + a]) < 2;
                    }
                    double v1, g1[3];
                    dfl_vdb_sample(g, (dfl_vdb_sampler)sq, 1, x + 3 * i, &v1, g1);
                    /* NaN: NaN value and gradient; far: the tree's background
                     * +b, gradient 0; the others what they get alone */
                    int ok = nan ? isnan(v[i]) : fin ? memcmp(&v[i], &v1, sizeof v1) == 0 : v[i] == b;
                    for (int a = 0; a < 3 && wg; a++)
                        ok &= nan ? isnan(gr[3 * i + a])
                              : fin ? memcmp(gr + 3 * i + a, g1 + a, sizeof *g1) == 0
                                    : gr[3 * i + a] == 0;
                    if (!ok) {
                        fprintf(stderr, "lattice %d sampler %d grad %d query %d: %g (b %g)\n", smp,
                                sq, wg, i, v[i], b);
                        bad++;
                    }
                }
            }
        dfl_vdb_free(g);
    }
    dfl_shape_free(&s);
    return bad;
}

/* vdb.h: a point with a NaN coordinate gets NaN value and gradient, one
 * whose index coordinate is beyond int (an infinite one, 1e300, 1e12) the
 * tree's background +b and gradient 0, like any point beyond the grid's
 * nodes (OpenVDB's samplers cast floor(p) to int, undefined there: an
 * infinity sampled 0 * inf = NaN); the other points of the batch get what
 * they get alone.  Every lattice and sampler; in a child per ISA like the
 * per-ISA kernels' checks (the adapter has one variant, so a crash fails
 * the test instead of ending the run). */
Test(vdb, nan_and_infinite_queries)
{
    cr_assert(dfl_test_per_isa(odd_queries, NULL) >= 1);
}
