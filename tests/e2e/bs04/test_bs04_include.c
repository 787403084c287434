/* End-to-end: the shipped bs04 configs take their shapes by include.  The
 * config.ini a run writes holds the merged keys (each equal to the shape
 * file's, no include line), and rerunning that config.ini alone gives the
 * same CSV byte for byte; --set on an included key shows in it. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/config.h"
#include "util/config_util.h"
#include "util/e2e_util.h"

#define CFG "configs/paper/bs04/bs04_polygonization.ini"

/* Every [shape] key of shape_file has the same value in [sec] of cfg, and
 * [sec] has no key of its own beyond them (they are the included ones). */
static void expect_merged(const dfl_cfg *cfg, const char *sec, const char *shape_file,
                          const char *set_key, const char *set_value)
{
    dfl_cfg *shape = cfgu_load(shape_file);
    static const char *const keys[] = {"kind", "order", "control", "closed", "knots"};
    int n = 0;
    for (int k = 0; k < 5; k++) {
        if (!dfl_cfg_has(shape, "shape", keys[k])) {
            cr_expect(!dfl_cfg_has(cfg, sec, keys[k]), "[%s] %s not in %s", sec, keys[k],
                      shape_file);
            continue;
        }
        n++;
        const char *want = cfgu_string(shape, "shape", keys[k]);
        if (set_key && strcmp(keys[k], set_key) == 0) want = set_value;
        cr_expect_str_eq(cfgu_string(cfg, sec, keys[k]), want, "[%s] %s", sec, keys[k]);
    }
    cr_assert_geq(n, 3, "%s: too few keys to compare", shape_file);
    /* nothing else was read from the shape file, nothing else is in [sec] */
    dfl_err err;
    cr_expect_eq(dfl_cfg_check_used_in(shape, "shape", &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(dfl_cfg_check_used_in(cfg, sec, &err), DFL_OK, "%s", err.msg);
    dfl_cfg_free(shape);
}

static char *read_in(const char *dir, const char *name)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    char *s = e2e_slurp(path);
    cr_assert_not_null(s, "missing %s", path);
    return s;
}

Test(e2e_bs04_include, resolved_config_holds_merged_keys_and_reruns)
{
    char a[512], b[512], c[512], path[700];
    e2e_run_ok(CFG, NULL, a, sizeof a);
    char *ini = read_in(a, "config.ini");
    cr_expect_null(strstr(ini, "include"), "config.ini still includes:\n%s", ini);
    snprintf(path, sizeof path, "%s/config.ini", a);
    dfl_cfg *resolved = cfgu_load(path);
    expect_merged(resolved, "S", "configs/shapes/S.ini", NULL, NULL);
    expect_merged(resolved, "W", "configs/shapes/W.ini", NULL, NULL);
    dfl_cfg_free(resolved);

    /* the resolved file alone reruns to the same table and the same keys */
    e2e_run_ok(path, NULL, b, sizeof b);
    char *csv_a = read_in(a, "bs04_polygonization.csv");
    char *csv_b = read_in(b, "bs04_polygonization.csv");
    cr_expect_str_eq(csv_a, csv_b, "rerun of config.ini gives another table");
    char *ini_b = read_in(b, "config.ini");
    cr_expect_str_eq(strchr(ini_b, '\n'), strchr(ini, '\n'), "rerun config.ini differs");

    /* --set overrides an included key; the merged file shows it */
    e2e_run_ok(CFG, "--set S.order=3", c, sizeof c);
    snprintf(path, sizeof path, "%s/config.ini", c);
    resolved = cfgu_load(path);
    expect_merged(resolved, "S", "configs/shapes/S.ini", "order", "3");
    expect_merged(resolved, "W", "configs/shapes/W.ini", NULL, NULL);
    dfl_cfg_free(resolved);
    char *csv_c = read_in(c, "bs04_polygonization.csv");
    cr_expect_str_neq(csv_c, csv_a, "S.order=3 changed nothing");
    free(csv_c);
    free(ini_b);
    free(csv_b);
    free(csv_a);
    free(ini);
}
