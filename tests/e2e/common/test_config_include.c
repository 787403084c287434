/* End-to-end: include through `dflab run` on the smoke study, whose [shape]
 * comes from a shape file: the run equals the one with the keys written
 * out, and a bad include stops the run with exit status 2, a message naming
 * file, line and key, and no results directory. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/e2e_util.h"
#include "util/tmpdir.h"

#define SMOKE_REST                                                                             \
    "[field]\nkind = exact\n[grid]\nn = 17\nlo = 0 0\nhi = 1 1\n"                               \
    "[perturb]\nscale = 0.02\noffset = 0.005\n[metrics]\nband = 0.1\n"                         \
    "[output]\nvti = false\nexr = false\n"

static char *csv_of(const char *out)
{
    char path[700];
    snprintf(path, sizeof path, "%s/smoke.csv", out);
    char *s = e2e_slurp(path);
    cr_assert_not_null(s, "missing %s", path);
    return s;
}

Test(e2e_config_include, included_shape_runs_like_written_one)
{
    char dir[64], inc[256], plain[256], out_i[512], out_p[512];
    tmpdir_new(dir, sizeof dir);
    tmpdir_write(dir, "shapes/circle.ini",
                 "[shape]\nkind = circle\ncenter = 0.5 0.5\nradius = 0.25\n", NULL, 0);
    tmpdir_write(dir, "cfg/inc.ini",
                 "[study]\nname = smoke\n[shape]\ninclude = ../shapes/circle.ini\n"
                 "radius = 0.3\n" SMOKE_REST,
                 inc, sizeof inc);
    tmpdir_write(dir, "cfg/plain.ini",
                 "[study]\nname = smoke\n[shape]\nkind = circle\ncenter = 0.5 0.5\n"
                 "radius = 0.3\n" SMOKE_REST,
                 plain, sizeof plain);
    e2e_run_ok(inc, NULL, out_i, sizeof out_i);
    e2e_run_ok(plain, NULL, out_p, sizeof out_p);
    char *a = csv_of(out_i), *b = csv_of(out_p);
    cr_expect_str_eq(a, b);
    free(a);
    free(b);
    tmpdir_remove(dir);
}

Test(e2e_config_include, bad_include_exits_2_without_files)
{
    char dir[64], cfg[256], want[512];
    tmpdir_new(dir, sizeof dir);
    tmpdir_write(dir, "shapes/nested.ini", "[shape]\ninclude = other.ini\n", NULL, 0);
    static const struct {
        const char *shape_lines, *want;
    } cases[] = {
        {"include = ../shapes/none.ini\n", "inc.ini:4: [shape] include: "},
        {"include = ../shapes/nested.ini\n", "shapes/nested.ini:2: [shape] include: an included"},
        {"include = ../shapes/a.ini, ../shapes/b.ini\n",
         "inc.ini:4: [shape] include: expected one"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char text[1024];
        snprintf(text, sizeof text, "[study]\nname = smoke\n[shape]\n%s" SMOKE_REST,
                 cases[i].shape_lines);
        tmpdir_write(dir, "cfg/inc.ini", text, cfg, sizeof cfg);
        snprintf(want, sizeof want, "%s", cases[i].want);
        e2e_run_expect_fail(cfg, "", want);
    }
    /* --set cannot bring an include in */
    e2e_run_expect_fail("configs/smoke/smoke.ini", "--set shape.include=x.ini",
                        "--set shape.include=x.ini: include is read with the config file");
    tmpdir_remove(dir);
}
