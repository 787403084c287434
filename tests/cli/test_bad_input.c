/* Bad input never crashes and never leaves files: each case runs the real
 * binary and checks exit status 2, a one-line message naming what the
 * contract says it must name, and an output directory that does not exist
 * afterwards. */
#include <criterion/criterion.h>
#include <criterion/parameterized.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/e2e_util.h"

#define SMOKE_HEAD "[study]\nname = smoke\n"
#define SHAPE "[shape]\nkind = circle\ncenter = 0.5 0.5\nradius = 0.3\n"
#define FIELD "[field]\nkind = exact\n"
#define GRID "[grid]\nn = 8\n"
#define GOOD SMOKE_HEAD SHAPE FIELD GRID

typedef struct bad_case {
    const char *name;
    const char *ini;     /* written to bad.ini (NULL: no file) */
    const char *points;  /* written to pts.csv (NULL: no file) */
    const char *args;    /* after "dflab"; {D} = the case directory */
    const char *want1;   /* substrings the one-line message must contain */
    const char *want2;
} bad_case;

static const bad_case cases[] = {
    {"missing config", NULL, NULL, "run {D}/nope.ini --out {D}/o", "nope.ini", "cannot open"},
    {"unknown key", GOOD "nn = 5\n", NULL, "run {D}/bad.ini --out {D}/o", "bad.ini:11", "[grid] nn"},
    {"unknown section", GOOD "[gird]\nn = 5\n", NULL, "run {D}/bad.ini --out {D}/o", "bad.ini:12", "[gird] n"},
    {"int wrong type", SMOKE_HEAD SHAPE FIELD "[grid]\nn = abc\n", NULL, "run {D}/bad.ini --out {D}/o", "bad.ini:10", "integer"},
    {"int out of range", SMOKE_HEAD SHAPE FIELD "[grid]\nn = 1\n", NULL, "run {D}/bad.ini --out {D}/o", "[grid] n", "[2, 4096]"},
    {"empty list item", SMOKE_HEAD SHAPE FIELD "[grid]\nn = 16,,32\n", NULL, "run {D}/bad.ini --out {D}/o", "bad.ini:10", "empty item"},
    {"nan value", SMOKE_HEAD "[shape]\nkind = circle\ncenter = 0.5 0.5\nradius = nan\n" FIELD GRID, NULL, "run {D}/bad.ini --out {D}/o", "bad.ini:6", "radius"},
    {"inf value", SMOKE_HEAD "[shape]\nkind = circle\ncenter = inf 0.5\nradius = 0.3\n" FIELD GRID, NULL, "run {D}/bad.ini --out {D}/o", "bad.ini:5", "center"},
    {"unknown study", "[study]\nname = nosuch\n" SHAPE FIELD GRID, NULL, "run {D}/bad.ini --out {D}/o", "bad.ini:2", "unknown study"},
    {"missing study", SHAPE FIELD GRID, NULL, "run {D}/bad.ini --out {D}/o", "[study] name", "missing"},
    {"short vector", SMOKE_HEAD "[shape]\nkind = circle\ncenter = 0.5\nradius = 0.3\n" FIELD GRID, NULL, "run {D}/bad.ini --out {D}/o", "bad.ini:5", "2 blank-separated"},
    {"bad bool", GOOD "[output]\nvti = maybe\n", NULL, "run {D}/bad.ini --out {D}/o", "bad.ini:12", "boolean"},
    {"unknown field kind", SMOKE_HEAD SHAPE "[field]\nkind = magic\n" GRID, NULL, "run {D}/bad.ini --out {D}/o", "bad.ini:8", "exact"},
    {"unknown shape kind", SMOKE_HEAD "[shape]\nkind = blob\n" FIELD GRID, NULL, "run {D}/bad.ini --out {D}/o", "bad.ini:4", "[shape] kind"},
    {"negative radius", SMOKE_HEAD "[shape]\nkind = circle\ncenter = 0.5 0.5\nradius = -1\n" FIELD GRID, NULL, "run {D}/bad.ini --out {D}/o", "bad.ini:6", "radius"},
    {"hi below lo", GOOD "lo = 0 0\nhi = 1 -1\n", NULL, "run {D}/bad.ini --out {D}/o", "bad.ini:12", "hi > lo"},
    {"syntax error", GOOD "this is not ini\n", NULL, "run {D}/bad.ini --out {D}/o", "bad.ini:11", "syntax"},
    {"duplicate key", GOOD "n = 9\n", NULL, "run {D}/bad.ini --out {D}/o", "bad.ini:11", "duplicate"},
    {"key outside section", "n = 3\n" GOOD, NULL, "run {D}/bad.ini --out {D}/o", "bad.ini:1", "outside"},
    {"malformed --set", GOOD, NULL, "run {D}/bad.ini --set grid.n --out {D}/o", "--set grid.n", "section.key=value"},
    {"--set unknown key", GOOD, NULL, "run {D}/bad.ini --set grid.foo=1 --out {D}/o", "grid.foo", "unknown key"},
    {"--set out of range", GOOD, NULL, "run {D}/bad.ini --set grid.n=0 --out {D}/o", "grid.n", "[2, 4096]"},
    {"bad sweep point", SMOKE_HEAD SHAPE FIELD "[grid]\nn = 8, 1\n", NULL, "run {D}/bad.ini --out {D}/o", "sweep point 1", "[grid] n"},
    {"study name sweep", "[study]\nname = smoke, smoke\n" SHAPE FIELD GRID, NULL, "run {D}/bad.ini --out {D}/o", "study", "sweep"},
    {"unknown run option", GOOD, NULL, "run {D}/bad.ini --frobnicate", "--frobnicate", "unknown option"},
    {"grid too large", "[study]\nname = smoke\n[shape]\nkind = sphere\ncenter = 0 0 0\nradius = 1\n" FIELD "[grid]\nn = 100000\n", NULL, "run {D}/bad.ini --out {D}/o", "[grid] n", "[2, 512]"},
    {"probe missing points", GOOD, NULL, "probe {D}/bad.ini --points {D}/none.csv", "none.csv", "cannot open"},
    {"probe no --points", GOOD, NULL, "probe {D}/bad.ini", "--points", "missing"},
    {"probe wrong field count", GOOD, "x,y\n0.1,0.2\n0.3\n", "probe {D}/bad.ini --points {D}/pts.csv", "pts.csv:3", "expected 2 fields"},
    {"probe nan point", GOOD, "x,y\n0.1,nan\n", "probe {D}/bad.ini --points {D}/pts.csv", "pts.csv:2", "finite"},
    {"probe not a number", GOOD, "x,y\n0.1,abc\n", "probe {D}/bad.ini --points {D}/pts.csv", "pts.csv:2", "column 'y'"},
    {"probe unknown column", GOOD, "x,y,w\n0.1,0.2,3\n", "probe {D}/bad.ini --points {D}/pts.csv", "pts.csv:1", "unknown column 'w'"},
    {"probe missing column", GOOD, "x\n0.1\n", "probe {D}/bad.ini --points {D}/pts.csv", "pts.csv:1", "missing column 'y'"},
    {"probe z for 2D", GOOD, "x,y,z\n0.1,0.2,0.3\n", "probe {D}/bad.ini --points {D}/pts.csv", "pts.csv:1", "'z'"},
    {"probe empty file", GOOD, "", "probe {D}/bad.ini --points {D}/pts.csv", "pts.csv", "empty"},
    {"probe no rows", GOOD, "x,y\n", "probe {D}/bad.ini --points {D}/pts.csv", "pts.csv", "no points"},
    {"probe jet no direction", GOOD, "x,y\n0.1,0.2\n", "probe {D}/bad.ini --points {D}/pts.csv --jet 2", "pts.csv:1", "missing column 'dx'"},
    {"probe jet too high", GOOD, "x,y,dx,dy\n0.1,0.2,1,0\n", "probe {D}/bad.ini --points {D}/pts.csv --jet 99", "--jet 99", "[0, 24]"},
    {"probe sweep config", SMOKE_HEAD "[shape]\nkind = circle\ncenter = 0.5 0.5\nradius = 0.3, 0.2\n" FIELD GRID, "x,y\n0.1,0.2\n", "probe {D}/bad.ini --points {D}/pts.csv", "shape.radius", "sweep"},
    {"probe unknown field key", SMOKE_HEAD SHAPE "[field]\nkind = exact\nfoo = 1\n" GRID, "x,y\n0.1,0.2\n", "probe {D}/bad.ini --points {D}/pts.csv", "bad.ini:9", "[field] foo"},
};

/* Criterion may run each parameter in a freshly exec'ed worker where the
 * addresses of string literals differ, so the parameters are indices. */
#define NCASES (sizeof cases / sizeof cases[0])
static int case_index[NCASES];

ParameterizedTestParameters(bad_input, table)
{
    for (size_t i = 0; i < NCASES; i++) case_index[i] = (int)i;
    return cr_make_param_array(int, case_index, NCASES);
}

static void expand(const char *tmpl, const char *dir, char *out, size_t size)
{
    size_t k = 0;
    for (const char *s = tmpl; *s && k + 1 < size; s++) {
        if (strncmp(s, "{D}", 3) == 0) {
            k += (size_t)snprintf(out + k, size - k, "%s", dir);
            s += 2;
        } else {
            out[k++] = *s;
        }
    }
    out[k] = '\0';
}

ParameterizedTest(const int *ci, bad_input, table)
{
    const bad_case *c = &cases[*ci];
    char dir[256], path[512], args[2048];
    e2e_tmpdir(dir, sizeof dir);
    cr_assert(dir[0], "mkdtemp");
    if (c->ini) e2e_write(dir, "bad.ini", c->ini, path, sizeof path);
    if (c->points) e2e_write(dir, "pts.csv", c->points, path, sizeof path);
    expand(c->args, dir, args, sizeof args);
    int rc = e2e_dflab(dir, args);
    char *msg = e2e_err_text(dir);
    cr_assert_not_null(msg);
    cr_expect_eq(rc, 2, "[%s] exit status %d, stderr: %s", c->name, rc, msg);
    cr_expect(strstr(msg, c->want1) != NULL, "[%s] message lacks '%s': %s", c->name, c->want1, msg);
    cr_expect(strstr(msg, c->want2) != NULL, "[%s] message lacks '%s': %s", c->name, c->want2, msg);
    /* exactly one error line, and it is the last thing printed (progress
     * lines of `run` may come before it) */
    const char *e = strstr(msg, "dflab: error: ");
    cr_expect(e != NULL && (e == msg || e[-1] == '\n'), "[%s] no dflab error line: %s", c->name, msg);
    if (e) {
        const char *nl = strchr(e, '\n');
        cr_expect(nl && nl[1] == '\0', "[%s] error is not one final line: %s", c->name, msg);
        cr_expect(strstr(e + 1, "dflab: error: ") == NULL, "[%s] several errors: %s", c->name, msg);
    }
    snprintf(path, sizeof path, "%s/o", dir);
    cr_expect_eq(e2e_count_entries(path), -1, "[%s] output directory left behind", c->name);
    snprintf(path, sizeof path, "%s/out.txt", dir);
    char *out = e2e_slurp(path);
    cr_expect(out && out[0] == '\0', "[%s] stdout not empty: %s", c->name, out ? out : "");
    /* nothing else (no stage dirs, no temp files) may appear in the case dir */
    int expected = 2 + (c->ini ? 1 : 0) + (c->points ? 1 : 0);
    cr_expect_eq(e2e_count_entries(dir), expected, "[%s] stray files in %s", c->name, dir);
    free(msg);
    free(out);
    if (e2e_rmtree(dir) != 0) cr_log_warn("cleanup of %s failed", dir);
}
