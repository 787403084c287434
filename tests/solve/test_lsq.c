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
