/* Tests for src/io/config_include.c: `[S] include = file` merges file's
 * [shape] keys into [S] (rules in io/config.h).  Every case writes its own
 * files into a fresh temporary tree:
 *
 *   <dir>/paper/x.ini      the including config
 *   <dir>/shapes/NAME.ini  the shape files, included as ../shapes/NAME.ini
 */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "io/config.h"
#include "util/config_util.h"
#include "util/e2e_util.h"
#include "util/tmpdir.h"

#define SHAPE_S                                                                                \
    "# a shape file\n"                                                                         \
    "[shape]\n"                                                                                \
    "kind = bspline_curve\n"                                                                   \
    "order = 4\n"                                                                              \
    "control = 0 0; 1 0;\n"                                                                    \
    "  1 1; 0 1\n"

typedef struct tree {
    char dir[64];
    char cfg[256];   /* <dir>/paper/x.ini */
    char shape[256]; /* <dir>/shapes/S.ini */
} tree;

/* A fresh tree with shapes/S.ini = SHAPE_S and paper/x.ini = text, and
 * paper/x.ini loaded (asserted to succeed; tree_end frees it). */
static dfl_cfg *tree_new(tree *t, const char *text)
{
    tmpdir_new(t->dir, sizeof t->dir);
    tmpdir_write(t->dir, "shapes/S.ini", SHAPE_S, t->shape, sizeof t->shape);
    tmpdir_write(t->dir, "paper/x.ini", text, t->cfg, sizeof t->cfg);
    return cfgu_load(t->cfg);
}

/* Frees c (may be NULL) and removes the tree. */
static void tree_end(tree *t, dfl_cfg *c)
{
    dfl_cfg_free(c);
    tmpdir_remove(t->dir);
}

/* The resolved INI text of c, as dfl_cfg_write gives it (caller frees). */
static char *written(const dfl_cfg *c, const tree *t)
{
    char path[300];
    snprintf(path, sizeof path, "%s/config.ini", t->dir);
    dfl_err err;
    cr_assert_eq(dfl_cfg_write(c, NULL, path, &err), DFL_OK, "%s", err.msg);
    char *s = e2e_slurp(path);
    cr_assert_not_null(s);
    return s;
}

Test(config_include, keys_merge_where_the_include_stood)
{
    tree t;
    dfl_cfg *c =
        tree_new(&t, "[study]\nname = s\n\n[S]\ninclude = ../shapes/S.ini\n\n[grid]\nn = 3\n");
    cr_assert_str_eq(cfgu_string(c, "S", "kind"), "bspline_curve");
    cr_assert_str_eq(cfgu_string(c, "S", "order"), "4");
    cr_assert_str_eq(cfgu_string(c, "S", "control"), "0 0; 1 0; 1 1; 0 1");
    cr_assert(!dfl_cfg_has(c, "S", "include"));
    cr_assert(!dfl_cfg_has_section(c, "shape"));
    /* messages about an included key name the shape file's line and the include */
    char w[512], want[512];
    snprintf(want, sizeof want, "%s/shapes/S.ini:4: [shape] order (included as [S] at %s:5)",
             t.dir, t.cfg);
    cr_assert_str_eq(dfl_cfg_where(c, "S", "order", w, sizeof w), want);
    long order;
    dfl_err err;
    cr_assert_eq(dfl_cfg_int(c, "S", "order", 5, 9, &order, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, want), "%s", err.msg);
    /* the resolved file lists the keys in place of the include line */
    char *text = written(c, &t);
    char expect[1024];
    snprintf(expect, sizeof expect,
             "# resolved configuration of %s\n[study]\nname = s\n\n[S]\nkind = bspline_curve\n"
             "order = 4\ncontrol = 0 0; 1 0; 1 1; 0 1\n\n[grid]\nn = 3\n",
             t.cfg);
    cr_assert_str_eq(text, expect);
    free(text);
    tree_end(&t, c);
}

/* The section's own keys win, whether written before or after the include,
 * and keep their own place and origin; new keys are added. */
Test(config_include, own_keys_override)
{
    tree t;
    dfl_cfg *c = tree_new(
        &t, "[S]\norder = 3\ninclude = ../shapes/S.ini\nkind = bezier\nclosed = true\n");
    cr_assert_str_eq(cfgu_string(c, "S", "order"), "3");
    cr_assert_str_eq(cfgu_string(c, "S", "kind"), "bezier");
    cr_assert_str_eq(cfgu_string(c, "S", "closed"), "true");
    cr_assert_str_eq(cfgu_string(c, "S", "control"), "0 0; 1 0; 1 1; 0 1");
    char w[512], want[512];
    snprintf(want, sizeof want, "%s:2: [S] order", t.cfg);
    cr_assert_str_eq(dfl_cfg_where(c, "S", "order", w, sizeof w), want);
    snprintf(want, sizeof want, "%s:4: [S] kind", t.cfg);
    cr_assert_str_eq(dfl_cfg_where(c, "S", "kind", w, sizeof w), want);
    char *text = written(c, &t);
    char expect[1024];
    snprintf(expect, sizeof expect,
             "# resolved configuration of %s\n[S]\norder = 3\ncontrol = 0 0; 1 0; 1 1; 0 1\n"
             "kind = bezier\nclosed = true\n",
             t.cfg);
    cr_assert_str_eq(text, expect);
    free(text);
    /* an own key written twice is still a duplicate */
    dfl_cfg_free(c);
    tmpdir_write(t.dir, "paper/y.ini", "[S]\ninclude = ../shapes/S.ini\norder = 3\norder = 5\n",
                 NULL, 0);
    char y[300];
    snprintf(y, sizeof y, "%s/paper/y.ini", t.dir);
    const char *dup[] = {":4: [S] order: duplicate key (first at line 3)"};
    cfgu_expect_fail(y, dup, 1, NULL);
    tree_end(&t, NULL);
}

/* --set overrides an included key like any other; sweeps over included
 * keys work and keep the include in their messages. */
Test(config_include, set_and_sweep)
{
    tree t;
    dfl_cfg *c = tree_new(&t, "[S]\ninclude = ../shapes/S.ini\n");
    dfl_err err;
    cr_assert_eq(dfl_cfg_set(c, "S.order=2, 3", &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(dfl_cfg_sweep_axes(c), 1);
    cr_assert_str_eq(dfl_cfg_sweep_axis_name(c, 0), "S.order");
    dfl_cfg *p;
    cr_assert_eq(dfl_cfg_sweep_point(c, 1, &p, &err), DFL_OK, "%s", err.msg);
    cr_assert_str_eq(cfgu_string(p, "S", "order"), "3");
    char w[512], want[512];
    cr_assert_str_eq(dfl_cfg_where(p, "S", "order", w, sizeof w), "--set S.order");
    snprintf(want, sizeof want, "%s/shapes/S.ini:5: [shape] control (included as [S] at %s:2)",
             t.dir, t.cfg);
    cr_assert_str_eq(dfl_cfg_where(p, "S", "control", w, sizeof w), want);
    /* an included key nobody reads is an unknown key, named at its line */
    cr_assert_eq(dfl_cfg_check_used_in(p, "S", &err), DFL_E_INPUT);
    snprintf(want, sizeof want, "%s/shapes/S.ini:3: [shape] kind (included as [S] at %s:2)",
             t.dir, t.cfg);
    cr_assert(strstr(err.msg, want), "%s", err.msg);
    dfl_cfg_free(p);
    dfl_cfg_free(c);

    /* a sweep written in the shape file is a sweep of [S] */
    tmpdir_write(t.dir, "shapes/T.ini", "[shape]\nkind = disk\nradius = 0.1, 0.2\n", NULL, 0);
    tmpdir_write(t.dir, "paper/x.ini", "[T]\ninclude = ../shapes/T.ini\n", NULL, 0);
    c = cfgu_load(t.cfg);
    cr_assert_eq(dfl_cfg_sweep_points(c), 2);
    cr_assert_str_eq(dfl_cfg_sweep_axis_name(c, 0), "T.radius");
    tree_end(&t, c);
}

/* A resolved config.ini has no include and reloads to the same keys with
 * nothing left to resolve (it reruns standalone). */
Test(config_include, resolved_file_stands_alone)
{
    tree t;
    dfl_cfg *c = tree_new(
        &t, "[A]\ninclude = ../shapes/S.ini\n[B]\ninclude = ../shapes/S.ini\norder = 2\n");
    char *text = written(c, &t);
    cr_assert_null(strstr(text, "include"), "%s", text);
    /* rename the shapes away: the resolved file must not need them */
    char from[300], to[300], path[300];
    snprintf(from, sizeof from, "%s/shapes", t.dir);
    snprintf(to, sizeof to, "%s/gone", t.dir);
    cr_assert_eq(rename(from, to), 0);
    snprintf(path, sizeof path, "%s/config.ini", t.dir);
    dfl_cfg *r = cfgu_load(path);
    static const char *const keys[] = {"kind", "order", "control"};
    for (int s = 0; s < 2; s++)
        for (int k = 0; k < 3; k++) {
            const char *sec = s ? "B" : "A";
            cr_assert_str_eq(cfgu_string(r, sec, keys[k]), cfgu_string(c, sec, keys[k]), "%s.%s",
                             sec, keys[k]);
        }
    cr_assert_str_eq(cfgu_string(r, "B", "order"), "2");
    cr_assert_str_eq(cfgu_string(r, "A", "order"), "4");
    cr_assert_eq(dfl_cfg_check_used(r, NULL), DFL_OK);
    free(text);
    dfl_cfg_free(r);
    tree_end(&t, c);
}

/* An include path is resolved against the including file's directory; an
 * absolute one is taken as is; for text parsed from memory the "file" is
 * its name. */
Test(config_include, path_resolution)
{
    tree t;
    dfl_cfg_free(tree_new(&t, ""));
    char text[512];
    snprintf(text, sizeof text, "[S]\ninclude = %s\n", t.shape);
    tmpdir_write(t.dir, "paper/x.ini", text, NULL, 0);
    dfl_cfg *c = cfgu_load(t.cfg);
    cr_assert_str_eq(cfgu_string(c, "S", "order"), "4");
    dfl_cfg_free(c);
    /* from another directory the relative include still finds its file */
    tmpdir_write(t.dir, "paper/deep/z.ini", "[S]\ninclude = ../../shapes/./S.ini\n", NULL, 0);
    char z[300];
    snprintf(z, sizeof z, "%s/paper/deep/z.ini", t.dir);
    c = cfgu_load(z);
    char w[512], want[512];
    snprintf(want, sizeof want, "%s/shapes/S.ini:3: [shape] kind (included as [S] at %s:2)",
             t.dir, z);
    cr_assert_str_eq(dfl_cfg_where(c, "S", "kind", w, sizeof w), want);
    dfl_cfg_free(c);
    char name[300];
    snprintf(name, sizeof name, "%s/paper/mem.ini", t.dir);
    dfl_err err;
    cr_assert_eq(dfl_cfg_parse_string(name, "[S]\ninclude = ../shapes/S.ini\n", &c, &err), DFL_OK,
                 "%s", err.msg);
    cr_assert_str_eq(cfgu_string(c, "S", "kind"), "bspline_curve");
    tree_end(&t, c);
}

/* Each rejected include gives DFL_E_INPUT naming the including file and
 * line, the key, and (where it has one) the included file's line. */
Test(config_include, errors_name_file_line_and_key)
{
    tree t;
    dfl_cfg_free(tree_new(&t, ""));
    tmpdir_write(t.dir, "shapes/noshape.ini", "[curve]\norder = 4\n", NULL, 0);
    tmpdir_write(t.dir, "shapes/empty.ini", "# nothing\n[shape]\n", NULL, 0);
    tmpdir_write(t.dir, "shapes/extra.ini", "[shape]\norder = 4\n\n[grid]\nn = 3\n", NULL, 0);
    tmpdir_write(t.dir, "shapes/nested.ini", "[shape]\norder = 4\ninclude = S.ini\n", NULL, 0);
    tmpdir_write(t.dir, "shapes/self.ini", "[shape]\ninclude = self.ini\n", NULL, 0);
    tmpdir_write(t.dir, "shapes/syntax.ini", "[shape]\norder = 4\norder = 5\n", NULL, 0);
    char sh[200];
    snprintf(sh, sizeof sh, "%s/shapes/", t.dir);
    static const struct {
        const char *text;
        const char *want[2];
    } cases[] = {
        {"[a]\nx = 1\n[S]\ninclude = ../shapes/none.ini\n",
         {"x.ini:4: [S] include: ", "shapes/none.ini: cannot open config: No such file"}},
        {"[S]\ninclude = ../shapes/noshape.ini\n",
         {"x.ini:2: [S] include: ", "shapes/noshape.ini has no [shape] section"}},
        {"[S]\ninclude = ../shapes/empty.ini\n",
         {"x.ini:2: [S] include: ", "shapes/empty.ini has no [shape] section (or it is empty)"}},
        {"[S]\ninclude = ../shapes/extra.ini\n",
         {"shapes/extra.ini:5: [grid] n: an included file holds only [shape] keys",
          "(included as [S] at "}},
        {"[S]\ninclude = ../shapes/nested.ini\n",
         {"x.ini:2: [S] include: ",
          "shapes/nested.ini:3: [shape] include: an included file cannot include another "
          "(one level only)"}},
        {"[shape]\ninclude = ../shapes/self.ini\n",
         {"x.ini:2: [shape] include: ", "shapes/self.ini:2: [shape] include: an included file"}},
        {"[S]\ninclude = ../shapes/syntax.ini\n",
         {"x.ini:2: [S] include: ", "shapes/syntax.ini:3: [shape] order: duplicate key"}},
        {"[S]\ninclude = ../shapes/S.ini\ninclude = ../shapes/S.ini\n",
         {"x.ini:3: [S] include: duplicate key (first at line 2; one include per section)", ""}},
        {"[S]\ninclude = ../shapes/S.ini\n  ../shapes/T.ini\n",
         {"x.ini:3: [S] include: continuation line", ""}},
        {"[S]\ninclude = ../shapes/S.ini, ../shapes/T.ini\n",
         {"x.ini:2: [S] include: expected one file name, got '../shapes/S.ini, ../shapes/T.ini'",
          "(an include cannot be a sweep)"}},
        {"[S]\ninclude =\n", {"x.ini:2: [S] include: expected a file name", ""}},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        tmpdir_write(t.dir, "paper/x.ini", cases[i].text, NULL, 0);
        char msg[DFL_ERR_MSG_MAX];
        cfgu_expect_fail(t.cfg, cases[i].want, 2, msg);
        /* the including file is named by its full path */
        cr_assert(strstr(msg, t.cfg), "case %zu: '%s'", i, msg);
        /* and the included file, when the error is about one */
        if (strstr(cases[i].want[1], "shapes/"))
            cr_assert(strstr(msg, sh), "case %zu: '%s'", i, msg);
    }
    tree_end(&t, NULL);
}

/* A FIFO named by include (nobody writes it) is refused at once, naming
 * the include line, instead of blocking the run forever. */
Test(config_include, fifo_include_is_refused_at_once, .timeout = 10)
{
    char dir[64], fifo[128], path[128];
    tmpdir_file(dir, sizeof dir, "shape.ini", fifo, sizeof fifo);
    cr_assert_eq(mkfifo(fifo, 0600), 0);
    tmpdir_write(dir, "main.ini", "[study]\nname = smoke\n[shape]\ninclude = shape.ini\n", path,
                 sizeof path);
    dfl_cfg *c = NULL;
    dfl_err err = {0};
    cr_expect_eq(dfl_cfg_load(path, &c, &err), DFL_E_INPUT);
    cr_expect_null(c);
    cr_expect(strstr(err.msg, "main.ini:4"), "%s", err.msg);
    cr_expect(strstr(err.msg, "not a regular file (a FIFO)"), "%s", err.msg);
    tmpdir_remove(dir);
}

/* `include = lnk/../x.ini` where lnk is a symbolic link to real/sub: the
 * file read is real/x.ini (the kernel's resolution), not the x.ini beside
 * lnk that a lexical "lnk/.." cancellation would pick. */
Test(config_include, dotdot_after_a_symlink_is_the_kernels)
{
    char dir[256], p[600], lnk[600];
    tmpdir_new(dir, sizeof dir);
    tmpdir_write(dir, "real/sub/keep", "", NULL, 0);
    tmpdir_write(dir, "real/x.ini", "[shape]\nkind = circle\nradius = 0.25\n", NULL, 0);
    tmpdir_write(dir, "x.ini", "[shape]\nkind = circle\nradius = 0.75\n", NULL, 0);
    snprintf(p, sizeof p, "%s/real/sub", dir);
    snprintf(lnk, sizeof lnk, "%s/lnk", dir);
    cr_assert_eq(symlink(p, lnk), 0);
    tmpdir_write(dir, "main.ini", "[S]\ninclude = lnk/../x.ini\n", NULL, 0);
    snprintf(p, sizeof p, "%s/main.ini", dir);
    dfl_cfg *c = cfgu_load(p);
    cr_expect_str_eq(cfgu_string(c, "S", "radius"), "0.25");
    char w[1024], want[1024];
    snprintf(want, sizeof want, "/real/x.ini:3: [shape] radius (included as [S] at %s:2)", p);
    cr_expect(strstr(dfl_cfg_where(c, "S", "radius", w, sizeof w), want) != NULL, "%s", w);
    dfl_cfg_free(c);
    tmpdir_remove(dir);
}
