/* `dflab help STUDY [CONFIG] [--columns]` through the binary: every key of
 * every study, as every config under configs/ makes the study read it,
 * has a meaning (experiments/harness/meaning.h) -- a getter added without
 * one fails here; CONFIG is the config read; a swept key shows its list;
 * an unknown study or command exits 2; the column glossary explains the
 * columns. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

#include "util/e2e_util.h"

static const char *bin(void)
{
    const char *b = getenv("DFL_DFLAB");
    return b && *b ? b : "build/dflab";
}

/* The [study] name of a config (the first `name =` in [study]), or "". */
static void study_of(const char *path, char *out, size_t size)
{
    cr_assert_geq(size, 256);
    FILE *fp = fopen(path, "r");
    out[0] = '\0';
    if (!fp) return;
    char line[1024];
    int in = 0;
    while (fgets(line, sizeof line, fp)) {
        if (line[0] == '[') in = strncmp(line, "[study]", 7) == 0;
        else if (in && strncmp(line, "name", 4) == 0 && strchr(line, '=')) {
            if (sscanf(strchr(line, '=') + 1, " %255s", out) != 1) out[0] = '\0';
            break;
        }
    }
    fclose(fp);
}

Test(help_meaning, every_key_of_every_config_has_a_meaning, .timeout = 300)
{
    FILE *p = popen("find configs -name '*.ini' | LC_ALL=C sort", "r");
    cr_assert(p);
    char path[1024], study[256], cmd[4096], line[4096];
    int configs = 0, keys = 0;
    while (fgets(path, sizeof path, p)) {
        path[strcspn(path, "\n")] = '\0';
        study_of(path, study, sizeof study);
        if (!study[0]) continue; /* a shape file */
        snprintf(cmd, sizeof cmd, "'%s' help %s '%s' 2>&1", bin(), study, path);
        FILE *h = popen(cmd, "r");
        cr_assert(h);
        char prev[4096] = "";
        int got_header = 0;
        while (fgets(line, sizeof line, h)) {
            if (strstr(line, "as read from ") && strstr(line, path)) got_header = 1;
            if (strstr(line, "(no meaning given)") || strstr(line, "dflab: error"))
                cr_expect(0, "%s: %s%s", path, prev, line);
            /* a key line: two blanks then section.key */
            if (strncmp(line, "  ", 2) == 0 && line[2] != ' ' && strchr(line, '.')) keys++;
            snprintf(prev, sizeof prev, "%s", line);
        }
        cr_expect_eq(pclose(h), 0, "%s", cmd);
        cr_expect(got_header, "help %s %s does not say it read %s", study, path, path);
        configs++;
    }
    pclose(p);
    /* every paper config and the smoke config took part */
    cr_expect_gt(configs, 40, "%d configs", configs);
    cr_expect_gt(keys, 1000, "%d keys", keys);
}

static char *run(const char *args, int *rc)
{
    char dir[256], cmd[4096], path[512];
    e2e_tmpdir(dir, sizeof dir);
    snprintf(cmd, sizeof cmd, "'%s' %s > '%s/out.txt' 2>&1", bin(), args, dir);
    const int st = system(cmd);
    *rc = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    snprintf(path, sizeof path, "%s/out.txt", dir);
    char *out = e2e_slurp(path);
    e2e_rmtree(dir);
    return out;
}

Test(help_meaning, config_argument_swept_lists_unknown_and_columns, .timeout = 120)
{
    int rc;
    /* the config given is read: its swept res shows the whole list */
    char *out = run("help hvb25_accuracy configs/paper/hvb25/hvb25_convergence_torus.ini", &rc);
    cr_assert_eq(rc, 0, "%s", out);
    cr_expect(strstr(out, "as read from configs/paper/hvb25/hvb25_convergence_torus.ini"), "%s", out);
    cr_expect(strstr(out, "field.res                    8, 16, 32, 64 "), "%s", out);
    cr_expect(strstr(out, "in cell sizes") || strstr(out, "cells per axis"), "%s", out);
    free(out);
    /* the clip radius's unit, which the getter's range cannot say */
    out = run("help hvb25_accuracy configs/paper/hvb25/hvb25_clip.ini", &rc);
    cr_assert_eq(rc, 0, "%s", out);
    const char *c = strstr(out, "field.clip_radius");
    cr_expect(c && strstr(c, "in cell sizes"), "%s", out);
    free(out);
    out = run("help nosuch", &rc);
    cr_expect_eq(rc, 2, "%s", out);
    cr_expect(strstr(out, "dflab: error: help: no command or study 'nosuch'"), "%s", out);
    free(out);
    out = run("help sjp10_3d nosuch.ini", &rc);
    cr_expect_eq(rc, 2, "%s", out);
    cr_expect(strstr(out, "nosuch.ini"), "%s", out);
    free(out);
    out = run("help sjp10_3d --columns", &rc);
    cr_assert_eq(rc, 0, "%s", out);
    cr_expect(strstr(out, "levels") && strstr(out, "can exceed max_level"), "%s", out);
    cr_expect(strstr(out, "point ") && strstr(out, "vti "), "%s", out);
    free(out);
    out = run("help run", &rc);
    cr_expect_eq(rc, 0);
    free(out);
}
