/* Tests for solve/lsq (the Ceres adapter).  Expected minimizers are known in
 * closed form: Rosenbrock's (1, 1); a quadratic whose unconstrained minimum
 * lies outside the box, so the solution is the minimum's projection; a
 * nonlinear fit with an active bound whose 1D optimum is solved here by
 * bisection on the derivative. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "solve/lsq.h"

static int rosenbrock(void *user, const double *x, double *r, double *J)
{
    (void)user;
    r[0] = 10 * (x[1] - x[0] * x[0]);
    r[1] = 1 - x[0];
    if (J) {
        J[0] = -20 * x[0];
        J[1] = 10;
        J[2] = -1;
        J[3] = 0;
    }
    return 0;
}

Test(lsq, rosenbrock)
{
    dfl_lsq_ctx *ctx;
    dfl_err err;
    cr_assert_eq(dfl_lsq_ctx_new(&ctx, &err), DFL_OK, "%s", err.msg);
    double x[2] = {-1.2, 1.0};
    dfl_lsq_result res;
    cr_assert_eq(dfl_lsq_solve(ctx, 2, 2, rosenbrock, NULL, NULL, NULL, NULL, x, &res, &err),
                 DFL_OK, "%s", err.msg);
    cr_assert(fabs(x[0] - 1) < 1e-10 && fabs(x[1] - 1) < 1e-10, "x = %.17g %.17g", x[0], x[1]);
    cr_assert(res.converged);
    cr_assert(res.final_cost < 1e-20);
    cr_assert(res.iterations > 1);
    dfl_lsq_ctx_free(ctx);
}

/* r = (x - 2, y + 1, 0.5 (x + y - 7)): with x <= 1 and y >= 0.  The cost
 * (x-2)^2 + (y+1)^2 + (x+y-7)^2/4 has, at x = 1 fixed, d/dy =
 * 2 (y + 1) + (y - 6)/2 = 2.5 y - 1 = 0 -> y = 0.4 > 0 (bound inactive), and
 * d/dx at (1, 0.4) = 2 (1 - 2) + (1 + 0.4 - 7)/2 = -4.8 < 0, so x = 1 is
 * active (KKT). */
static int quad(void *user, const double *x, double *r, double *J)
{
    (void)user;
    r[0] = x[0] - 2;
    r[1] = x[1] + 1;
    r[2] = 0.5 * (x[0] + x[1] - 7);
    if (J) {
        double j[6] = {1, 0, 0, 1, 0.5, 0.5};
        memcpy(J, j, sizeof j);
    }
    return 0;
}

Test(lsq, bound_is_active)
{
    dfl_lsq_ctx *ctx;
    cr_assert_eq(dfl_lsq_ctx_new(&ctx, NULL), DFL_OK);
    double x[2] = {0.0, 0.5}, lo[2] = {-HUGE_VAL, 0.0}, hi[2] = {1.0, HUGE_VAL};
    dfl_lsq_result res;
    dfl_err err;
    cr_assert_eq(dfl_lsq_solve(ctx, 2, 3, quad, NULL, lo, hi, NULL, x, &res, &err), DFL_OK, "%s",
                 err.msg);
    cr_assert(fabs(x[0] - 1.0) < 1e-10 && fabs(x[1] - 0.4) < 1e-10, "x = %.17g %.17g", x[0], x[1]);
    dfl_lsq_ctx_free(ctx);
}

/* Fit y = a exp(b t) to data from a = 2, b = -1.5, with b bounded to
 * b >= -1: the constrained optimum has b = -1 and a minimizing
 * sum (a e^{-t} - y)^2, i.e. a = sum y e^{-t} / sum e^{-2t} (linear in a). */
static const double T[6] = {0, 0.2, 0.5, 0.9, 1.4, 2.0};
static int expfit(void *user, const double *x, double *r, double *J)
{
    (void)user;
    for (int i = 0; i < 6; i++) {
        double y = 2 * exp(-1.5 * T[i]), e = exp(x[1] * T[i]);
        r[i] = x[0] * e - y;
        if (J) {
            J[2 * i] = e;
            J[2 * i + 1] = x[0] * T[i] * e;
        }
    }
    return 0;
}

Test(lsq, nonlinear_fit_with_active_bound)
{
    dfl_lsq_ctx *ctx;
    cr_assert_eq(dfl_lsq_ctx_new(&ctx, NULL), DFL_OK);
    double x[2] = {1.0, 0.0}, lo[2] = {-HUGE_VAL, -1.0}, hi[2] = {HUGE_VAL, HUGE_VAL};
    dfl_lsq_options opt;
    dfl_lsq_options_default(&opt);
    cr_assert_eq(opt.max_iterations, 100);
    cr_assert_eq(dfl_lsq_solve(ctx, 2, 6, expfit, NULL, lo, hi, &opt, x, NULL, NULL), DFL_OK);
    double num = 0, den = 0;
    for (int i = 0; i < 6; i++) {
        num += 2 * exp(-1.5 * T[i]) * exp(-T[i]);
        den += exp(-2 * T[i]);
    }
    cr_assert(fabs(x[1] + 1.0) < 1e-10, "b = %.17g", x[1]);
    cr_assert(fabs(x[0] - num / den) < 1e-10, "a = %.17g want %.17g", x[0], num / den);
    /* without the bound the data are fitted exactly */
    double y[2] = {1.0, 0.0};
    cr_assert_eq(dfl_lsq_solve(ctx, 2, 6, expfit, NULL, NULL, NULL, NULL, y, NULL, NULL), DFL_OK);
    cr_assert(fabs(y[0] - 2) < 1e-10 && fabs(y[1] + 1.5) < 1e-10);
    dfl_lsq_ctx_free(ctx);
}

static int fails(void *user, const double *x, double *r, double *J)
{
    (void)user;
    (void)x;
    (void)r;
    (void)J;
    return 1;
}

Test(lsq, bad_input_and_failures_are_statuses)
{
    dfl_lsq_ctx *ctx;
    cr_assert_eq(dfl_lsq_ctx_new(&ctx, NULL), DFL_OK);
    dfl_err err;
    double x[2] = {2.0, 0.0}, lo[2] = {0, 0}, hi[2] = {1, 1};
    cr_assert_eq(dfl_lsq_solve(ctx, 2, 3, quad, NULL, lo, hi, NULL, x, NULL, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "outside"));
    cr_assert_eq(dfl_lsq_solve(ctx, 0, 3, quad, NULL, NULL, NULL, NULL, x, NULL, &err), DFL_E_INPUT);
    cr_assert_eq(dfl_lsq_solve(ctx, 2, 65, quad, NULL, NULL, NULL, NULL, x, NULL, &err), DFL_E_INPUT);
    double y[2] = {0.5, 0.5};
    dfl_status st = dfl_lsq_solve(ctx, 2, 3, fails, NULL, NULL, NULL, NULL, y, NULL, &err);
    cr_assert_eq(st, DFL_E_NUMERIC, "status %d: %s", st, err.msg);
    dfl_lsq_ctx_free(ctx);
}

/* Ceres must print nothing: capture fds 1 and 2 around solves, including
 * one whose residual turns NaN. */
static int nan_later(void *user, const double *x, double *r, double *J)
{
    (void)user;
    r[0] = x[0] > 3 ? NAN : x[0] - 5;
    if (J) J[0] = 1;
    return 0;
}

Test(lsq, silent)
{
    dfl_lsq_ctx *ctx;
    cr_assert_eq(dfl_lsq_ctx_new(&ctx, NULL), DFL_OK);
    char path[] = "/tmp/dfl_lsq_silentXXXXXX";
    int fd = mkstemp(path);
    cr_assert(fd >= 0);
    fflush(stdout);
    fflush(stderr);
    int o1 = dup(1), o2 = dup(2);
    dup2(fd, 1);
    dup2(fd, 2);
    double x[2] = {-1.2, 1.0}, z = 0.0;
    dfl_lsq_solve(ctx, 2, 2, rosenbrock, NULL, NULL, NULL, NULL, x, NULL, NULL);
    dfl_lsq_solve(ctx, 1, 1, nan_later, NULL, NULL, NULL, NULL, &z, NULL, NULL);
    fflush(stdout);
    fflush(stderr);
    dup2(o1, 1);
    dup2(o2, 2);
    close(o1);
    close(o2);
    off_t size = lseek(fd, 0, SEEK_END);
    close(fd);
    unlink(path);
    cr_assert_eq(size, 0, "Ceres wrote %ld bytes", (long)size);
    dfl_lsq_ctx_free(ctx);
}

Test(lsq, shared_context_across_threads)
{
    dfl_lsq_ctx *ctx;
    cr_assert_eq(dfl_lsq_ctx_new(&ctx, NULL), DFL_OK);
    int bad = 0;
#pragma omp parallel for reduction(+ : bad)
    for (int i = 0; i < 64; i++) {
        double x[2] = {-2.0 + 0.05 * i, 1.5 - 0.03 * i};
        if (dfl_lsq_solve(ctx, 2, 2, rosenbrock, NULL, NULL, NULL, NULL, x, NULL, NULL) != DFL_OK ||
            fabs(x[0] - 1) > 1e-10 || fabs(x[1] - 1) > 1e-10)
            bad++;
    }
    cr_assert_eq(bad, 0);
    dfl_lsq_ctx_free(ctx);
}

/* The defaults lsq.h documents. */
Test(lsq, documented_defaults)
{
    dfl_lsq_options o;
    dfl_lsq_options_default(&o);
    cr_expect_eq(o.max_iterations, 100);
    cr_expect_eq(o.function_tolerance, 1e-16);
    cr_expect_eq(o.gradient_tolerance, 1e-16);
    cr_expect_eq(o.parameter_tolerance, 1e-14);
}

/* r_i = x_(i mod 16) - (i mod 16), i < 64: the least-squares solution is
 * x_j = j.  Sizes n <= 16, m <= 64 are inclusive (lsq.h). */
static int sixteen(void *user, const double *x, double *r, double *J)
{
    const int n = *(const int *)user;
    for (int i = 0; i < 64; i++) {
        r[i] = x[i % n] - i % n;
        if (J)
            for (int j = 0; j < n; j++) J[i * n + j] = j == i % n;
    }
    return 0;
}

Test(lsq, largest_sizes_are_accepted)
{
    dfl_lsq_ctx *ctx;
    cr_assert_eq(dfl_lsq_ctx_new(&ctx, NULL), DFL_OK);
    dfl_err err;
    int n = 16;
    double x[17] = {0};
    cr_assert_eq(dfl_lsq_solve(ctx, 16, 64, sixteen, &n, NULL, NULL, NULL, x, NULL, &err), DFL_OK,
                 "%s", err.msg);
    for (int j = 0; j < 16; j++) cr_expect(fabs(x[j] - j) < 1e-10, "x%d = %.17g", j, x[j]);
    n = 17;
    cr_expect_eq(dfl_lsq_solve(ctx, 17, 64, sixteen, &n, NULL, NULL, NULL, x, NULL, &err),
                 DFL_E_INPUT);
    dfl_lsq_ctx_free(ctx);
}

/* The box is inclusive, lo[j] <= x[j] <= hi[j] (lsq.h), and is checked for
 * every coordinate: a start on the bound is inside (quad's solution is
 * (1, 0.4) from there too), a start outside in the second coordinate only
 * is DFL_E_INPUT naming x[1]. */
Test(lsq, start_on_the_bound_and_every_coordinate_checked)
{
    dfl_lsq_ctx *ctx;
    cr_assert_eq(dfl_lsq_ctx_new(&ctx, NULL), DFL_OK);
    dfl_err err;
    double lo[2] = {-HUGE_VAL, 0.0}, hi[2] = {1.0, HUGE_VAL};
    double x[2] = {1.0, 0.0}; /* both coordinates on their bound */
    cr_assert_eq(dfl_lsq_solve(ctx, 2, 3, quad, NULL, lo, hi, NULL, x, NULL, &err), DFL_OK, "%s",
                 err.msg);
    cr_expect(fabs(x[0] - 1.0) < 1e-10 && fabs(x[1] - 0.4) < 1e-10, "x = %.17g %.17g", x[0],
              x[1]);
    /* y[1] = 2 lies in x[0]'s box [0, 10] but not in its own [3, 4] */
    double blo[2] = {0, 3}, bhi[2] = {10, 4}, y[2] = {0.5, 2.0};
    cr_expect_eq(dfl_lsq_solve(ctx, 2, 3, quad, NULL, blo, bhi, NULL, y, NULL, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "x[1]"), "%s", err.msg);
    dfl_lsq_ctx_free(ctx);
}

/* lo[j] == hi[j] is a box of one point, not an empty one (lo <= x <= hi,
 * lsq.h): it must not be refused as an empty bound.  When the solve
 * succeeds, y is held at 0.4 and x takes its constrained optimum, which for
 * quad at y = 0.4 is x = 1 (d/dx at x = 1 is -4.8 < 0, see quad).  (Today
 * Ceres itself refuses lower == upper as an infeasible bound, so the solve
 * ends in DFL_E_NUMERIC "Ceres failed": a bug of the adapter, which should
 * hold such a coordinate fixed instead of passing the bounds on.) */
Test(lsq, equal_bounds_are_not_empty)
{
    dfl_lsq_ctx *ctx;
    cr_assert_eq(dfl_lsq_ctx_new(&ctx, NULL), DFL_OK);
    dfl_err err;
    dfl_err_clear(&err);
    double lo[2] = {-HUGE_VAL, 0.4}, hi[2] = {1.0, 0.4}, x[2] = {0.0, 0.4};
    /* lsq.h: lo == hi holds the coordinate.  With x1 = 0.4 the cost
     * (x0 - 2)^2 + (x0 - 6.6)^2 / 4 falls until x0 = 2.92, so the bound
     * x0 <= 1 is active: x = (1, 0.4) */
    const dfl_status st = dfl_lsq_solve(ctx, 2, 3, quad, NULL, lo, hi, NULL, x, NULL, &err);
    cr_assert_eq(st, DFL_OK, "%s", err.msg);
    cr_expect_eq(x[1], 0.4);
    cr_expect(fabs(x[0] - 1.0) < 1e-10, "x = %.17g", x[0]);
    /* every coordinate held: 0 iterations, the cost at x, r = (-1, 1.4, -2.8):
     * 0.5 (1 + 1.96 + 7.84) = 5.4 */
    double lo2[2] = {1.0, 0.4}, hi2[2] = {1.0, 0.4}, x2[2] = {1.0, 0.4};
    dfl_lsq_result res;
    cr_assert_eq(dfl_lsq_solve(ctx, 2, 3, quad, NULL, lo2, hi2, NULL, x2, &res, &err), DFL_OK,
                 "%s", err.msg);
    cr_expect(x2[0] == 1.0 && x2[1] == 0.4);
    cr_expect_eq(res.iterations, 0);
    cr_expect(res.converged);
    cr_expect(fabs(res.final_cost - 5.4) < 1e-14, "cost %.17g", res.final_cost);
    dfl_lsq_ctx_free(ctx);
}

/* converged is 1 only when Ceres reports CONVERGENCE (lsq.h): one
 * iteration from Rosenbrock's standard start cannot reach (1, 1).
 * final_cost is 0.5 |r|^2 at the returned x. */
Test(lsq, converged_and_final_cost_mean_what_they_say)
{
    dfl_lsq_ctx *ctx;
    cr_assert_eq(dfl_lsq_ctx_new(&ctx, NULL), DFL_OK);
    dfl_err err;
    dfl_lsq_options o;
    dfl_lsq_options_default(&o);
    o.max_iterations = 1;
    double x[2] = {-1.2, 1.0}, r[3];
    dfl_lsq_result res;
    cr_assert_eq(dfl_lsq_solve(ctx, 2, 2, rosenbrock, NULL, NULL, NULL, &o, x, &res, &err), DFL_OK,
                 "%s", err.msg);
    cr_expect_eq(res.converged, 0);
    rosenbrock(NULL, x, r, NULL);
    double want = 0.5 * (r[0] * r[0] + r[1] * r[1]);
    cr_expect(fabs(res.final_cost - want) <= 1e-12 * want, "%.17g vs %.17g", res.final_cost, want);
    /* a bounded solve: the cost at the constrained optimum */
    double lo[2] = {-HUGE_VAL, 0.0}, hi[2] = {1.0, HUGE_VAL}, y[2] = {0.0, 0.5};
    cr_assert_eq(dfl_lsq_solve(ctx, 2, 3, quad, NULL, lo, hi, NULL, y, &res, &err), DFL_OK, "%s",
                 err.msg);
    quad(NULL, y, r, NULL);
    want = 0.5 * (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
    cr_expect(fabs(res.final_cost - want) <= 1e-12 * want, "%.17g vs %.17g", res.final_cost, want);
    cr_expect_eq(res.converged, 1);
    dfl_lsq_ctx_free(ctx);
}

/* res->iterations counts the Ceres iterations of every round of a bounded
 * solve, not only the last one.  Ceres evaluates the residuals alone (no
 * Jacobian) once at a round's start and once per trial step, and each of
 * these is one entry of its iteration summary; the adapter's own KKT
 * evaluations ask for the Jacobian.  So iterations >= the callback's
 * evaluations without J over the whole solve.  Rosenbrock with x0 <= 0.5
 * makes the first round long (from (-1.2, 1)) and the last one short (x0
 * fixed, the rest linear in x1), so the last round alone falls short. */
static int rosenbrock_counted(void *user, const double *x, double *r, double *J)
{
    if (!J) ++*(int *)user;
    return rosenbrock(NULL, x, r, J);
}

Test(lsq, iterations_count_every_round)
{
    dfl_lsq_ctx *ctx;
    cr_assert_eq(dfl_lsq_ctx_new(&ctx, NULL), DFL_OK);
    dfl_err err;
    int plain = 0;
    double lo[2] = {-HUGE_VAL, -HUGE_VAL}, hi[2] = {0.5, HUGE_VAL}, x[2] = {-1.2, 1.0};
    dfl_lsq_result res;
    cr_assert_eq(dfl_lsq_solve(ctx, 2, 2, rosenbrock_counted, &plain, lo, hi, NULL, x, &res, &err),
                 DFL_OK, "%s", err.msg);
    /* the constrained optimum: x0 = 0.5 on its bound, x1 = x0^2 */
    cr_expect(fabs(x[0] - 0.5) < 1e-10 && fabs(x[1] - 0.25) < 1e-10, "x = %.17g %.17g", x[0],
              x[1]);
    cr_expect_geq(res.iterations, plain, "%d iterations, %d evaluations without J",
                  res.iterations, plain);
    dfl_lsq_ctx_free(ctx);
}
