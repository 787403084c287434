/* `[field] kind = pht` (experiments/cfg/pht_cfg.c): a circle fit through the
 * field table meets eps at points off its centre; every documented bad key
 * exits with DFL_E_INPUT naming file:line and the key. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cfg_util.h"
#include "cfg/field_cfg.h"
#include "cfg/pht_cfg.h"
#include "pht/pht_field.h"

static const char *CIRCLE = "[shape]\nkind = circle\ncenter = 0.5 0.5\nradius = 0.3\n";

Test(pht_cfg, circle_field_meets_eps)
{
    char text[512];
    snprintf(text, sizeof text, "[field]\nkind = pht\neps = 1e-4\nmax_level = 16\n%s", CIRCLE);
    dfl_cfg *cfg = tu_cfg("p.ini", text);
    dfl_field f;
    dfl_err err;
    cr_assert_eq(dfl_field_from_cfg(cfg, "field", &f, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(dfl_cfg_check_used(cfg, &err), DFL_OK, "%s", err.msg);
    cr_assert_not_null(dfl_pht_field_spline(&f));
    const double pts[][2] = {{0.8, 0.5}, {0.1, 0.1}, {0.5, 0.65}, {0.95, 0.3}};
    for (int i = 0; i < 4; i++) {
        double g[2], v = dfl_field_eval1(&f, pts[i], g);
        double r = hypot(pts[i][0] - 0.5, pts[i][1] - 0.5);
        cr_expect(fabs(v - (r - 0.3)) <= 1e-4, "at %d: %g vs %g", i, v, r - 0.3);
    }
    dfl_field_destroy(&f);
    dfl_cfg_free(cfg);
}

Test(pht_cfg, options_are_read)
{
    dfl_cfg *cfg = tu_cfg("p.ini", "[field]\nkind = pht\neps = 2e-3\nmax_level = 50\n"
                                   "samples = 9\nsplit = binary\nestimator = grid\nseed = 5\n"
                                   "lo = -1 -1\nhi = 2 1\ngrade = false\n");
    dfl_pht_fit_opts o;
    dfl_err err;
    cr_assert_eq(dfl_pht_opts_from_cfg(cfg, "field", 2, &o, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(o.eps, 2e-3);
    cr_expect_eq(o.max_level, 50);
    cr_expect_eq(o.samples, 9);
    cr_expect_eq(o.split, DFL_PHT_SPLIT_BINARY);
    cr_expect_eq(o.estimator, DFL_PHT_EST_GRID);
    cr_expect_eq(o.seed, 5);
    cr_expect(o.lo[0] == -1 && o.hi[0] == 2 && o.hi[1] == 1);
    cr_expect_eq(o.grade, 0);
    cr_expect_eq(o.peaks, 1);
    dfl_cfg_free(cfg);
}

/* The field section's extra lines, the shape section, and the key the
 * error must name. */
static void bad(const char *field_lines, const char *shape, const char *key, const char *line)
{
    char text[1024];
    snprintf(text, sizeof text, "[field]\nkind = pht\n%s%s", field_lines, shape);
    dfl_cfg *cfg = tu_cfg("p.ini", text);
    dfl_field f;
    dfl_err err;
    cr_assert_eq(dfl_field_from_cfg(cfg, "field", &f, &err), DFL_E_INPUT, "%s", text);
    cr_expect(strstr(err.msg, key) && strstr(err.msg, line), "expected %s at %s: %s", key, line,
              err.msg);
    dfl_cfg_free(cfg);
}

Test(pht_cfg, bad_keys_are_named)
{
    bad("eps = 0\n", CIRCLE, "eps", "p.ini:3");
    bad("eps = -1e-3\n", CIRCLE, "eps", "p.ini:3");
    bad("max_level = 31\n", CIRCLE, "max_level", "p.ini:3");
    bad("max_level = -1\n", CIRCLE, "max_level", "p.ini:3");
    bad("split = binary\nmax_level = 61\n", CIRCLE, "max_level", "p.ini:4");
    bad("split = quad\n", CIRCLE, "split", "p.ini:3");
    bad("estimator = sobol\n", CIRCLE, "estimator", "p.ini:3");
    bad("samples = 0\n", CIRCLE, "samples", "p.ini:3");
    bad("hi = 1 0\n", CIRCLE, "hi", "p.ini:3");
    bad("shape = nowhere\n", CIRCLE, "shape", "p.ini:3");
    /* an open curve: unsigned distance, no inside */
    bad("", "[shape]\nkind = bspline_curve\norder = 4\ncontrol = 0.1 0.1; 0.5 0.9; 0.9 0.1; 0.9 0.5\n",
        "closed", "[shape]");
    bad("", "[shape]\nkind = bspline_curve\norder = 4\nclosed = false\n"
            "control = 0.1 0.1; 0.5 0.9; 0.9 0.1; 0.9 0.5\n",
        "closed", "p.ini:6");
    /* shapes without SDF derivatives or without a sign */
    bad("", "[shape]\nkind = ellipse\ncenter = 0.5 0.5\na = 0.3\nb = 0.2\n", "kind", "p.ini:4");
    bad("", "[shape]\nkind = segment\na = 0 0\nb = 1 1\n", "kind", "p.ini:4");
}

/* The inside test takes the shape's nearest point from the box centre, so a
 * closed shape in the box is accepted whatever its size or the box's (a
 * 33-point probe grid missed a 1e-3 circle between its points and a unit
 * circle in a +-1e150 box); a box the shape stays away from is refused. */
static dfl_status source_of(const char *field, const char *shape, dfl_err *err)
{
    char text[1024];
    snprintf(text, sizeof text, "[field]\nkind = pht\n%s%s", field, shape);
    dfl_cfg *cfg = tu_cfg("p.ini", text);
    dfl_shape s;
    dfl_pht_source *src = NULL;
    dfl_status st = dfl_pht_source_from_cfg(cfg, "field", &s, &src, err);
    if (st == DFL_OK) {
        dfl_pht_source_free(src);
        dfl_shape_free(&s);
    }
    dfl_cfg_free(cfg);
    return st;
}

Test(pht_cfg, inside_test_cannot_miss_a_closed_shape)
{
    dfl_err err;
    /* 1e-3 circle off the old probe grid (spacing 1/32): no grid node inside */
    const char *tiny = "[shape]\nkind = circle\ncenter = 0.515625 0.2\nradius = 1e-3\n";
    cr_expect_eq(source_of("", tiny, &err), DFL_OK, "%s", err.msg);
    /* a unit circle in a +-1e150 box (the largest the config accepts) */
    const char *unit = "[shape]\nkind = circle\ncenter = 0 0\nradius = 1\n";
    cr_expect_eq(source_of("lo = -1e150 -1e150\nhi = 1e150 1e150\n", unit, &err), DFL_OK, "%s",
                 err.msg);
    /* the box inside the circle: the centre is inside */
    cr_expect_eq(source_of("lo = -0.1 -0.1\nhi = 0.1 0.1\n", unit, &err), DFL_OK, "%s", err.msg);
    /* a sphere off the corner of the unit cube, away from its centre */
    const char *sph = "[shape]\nkind = sphere\ncenter = 0.9 0.95 0.9\nradius = 0.01\n";
    cr_expect_eq(source_of("lo = 0 0 0\nhi = 1 1 1\n", sph, &err), DFL_OK, "%s", err.msg);
    /* a circle far from the box: refused, naming the shape's kind */
    const char *far = "[shape]\nkind = circle\ncenter = 5 5\nradius = 0.1\n";
    cr_expect_eq(source_of("", far, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "no inside") != NULL, "%s", err.msg);
}

/* dfl_pht_field_target_from_cfg: the target is eps, met iff no leaf cell's
 * estimate is above it (the fit's converged / capped), none in a
 * validation pass.  max_level = 0 keeps the one cell of the unit square:
 *   - eps = 100 is met: the cell's bicubic Hermite interpolant of d takes
 *     corner values |d| <= sqrt(1/2) - 0.3 < 0.41, gradients of norm 1 and
 *     cross derivatives |d_xy| <= 1 / |x - c| < 1.5 there; the Hermite
 *     basis has h00 + h01 = 1 and |h10|, |h11| <= 4/27, so |f| < 0.41 +
 *     2 (8/27) + (8/27)^2 1.5 < 1.2 and |f - d| < 1.2 + (sqrt(1/2) + 0.3)
 *     < 3;
 *   - eps = 1e-300 (the smallest accepted) is not: a bicubic polynomial
 *     is not |x - c| - r on any open set (the SDF is not a polynomial), so
 *     the estimate at the cell's points is above 1e-300 and the one cell,
 *     at max_level, is over it. */
static dfl_status pht_target(const char *eps, int pass, dfl_field *f, dfl_field_target *tg,
                             dfl_err *err)
{
    char text[512];
    snprintf(text, sizeof text, "[field]\nkind = pht\neps = %s\nmax_level = 0\n%s", eps, CIRCLE);
    dfl_cfg *cfg = tu_cfg("t.ini", text);
    if (pass) dfl_cfg_validate_only(cfg);
    dfl_status st = dfl_pht_field_target_from_cfg(cfg, "field", f, tg, err);
    dfl_cfg_free(cfg);
    return st;
}

Test(pht_cfg, target_says_whether_eps_was_met)
{
    dfl_field f;
    dfl_field_target tg;
    dfl_err err;
    cr_assert_eq(pht_target("100", 0, &f, &tg, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(tg.value, 100.0);
    cr_expect_eq(tg.met, 1);
    cr_expect_eq(tg.over, 0);
    dfl_field_destroy(&f);
    cr_assert_eq(pht_target("1e-300", 0, &f, &tg, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(tg.value, 1e-300);
    cr_expect_eq(tg.met, 0);
    cr_expect_eq(tg.over, 1, "the one cell of max_level 0");
    dfl_field_destroy(&f);
    /* through the field table: the same record */
    dfl_cfg *cfg = tu_cfg("t.ini", "[field]\nkind = pht\neps = 1e-300\nmax_level = 0\n"
                                   "[shape]\nkind = circle\ncenter = 0.5 0.5\nradius = 0.3\n");
    cr_assert_eq(dfl_field_from_cfg_target(cfg, "field", &f, &tg, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(tg.met, 0);
    cr_expect_eq(tg.over, 1);
    dfl_field_destroy(&f);
    dfl_cfg_free(cfg);
    /* a validation pass fits nothing: no target */
    cr_assert_eq(pht_target("1e-3", 1, &f, &tg, &err), DFL_OK, "%s", err.msg);
    cr_expect(isnan(tg.value));
    cr_expect_eq(tg.met, -1);
    cr_expect_eq(tg.over, 0);
    dfl_field_destroy(&f);
    /* a failed build leaves the record untouched */
    tg.value = 7.0, tg.met = 5, tg.over = 9;
    cr_expect_eq(pht_target("-1", 0, &f, &tg, &err), DFL_E_INPUT);
    cr_expect_eq(tg.value, 7.0);
    cr_expect_eq(tg.met, 5);
    cr_expect_eq(tg.over, 9);
}
