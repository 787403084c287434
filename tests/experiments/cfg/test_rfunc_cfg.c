/* The probe contract: [field] kind = rfunc -> dfl_field. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cfg_util.h"
#include "cfg/curve_cfg.h"
#include "cfg/field_cfg.h"
#include "geom/polygonize.h"
#include "io/config.h"
#include "rfunc/rfield.h"
#include "cfg/rfunc_cfg.h"
#include "rfunc/rfunc_util.h"

static dfl_status build(const char *text, dfl_field *f, dfl_err *err)
{
    dfl_cfg *cfg;
    dfl_status st = dfl_cfg_parse_string("test.ini", text, &cfg, err);
    cr_assert_eq(st, DFL_OK, "%s", err->msg);
    st = dfl_field_from_cfg(cfg, "field", f, err);
    if (st == DFL_OK) {
        dfl_err e2;
        cr_assert_eq(dfl_cfg_check_used(cfg, &e2), DFL_OK, "%s", e2.msg);
    }
    dfl_cfg_free(cfg);
    return st;
}

/* The config builds exactly the field of the library call. */
Test(rfunc_cfg, polyline_keys)
{
    const double v2[] = {0, 0, 1, 0.5, 2, 0.2, 2.5, 1.5};
    const double v3[] = {0, 0, 0, 1, 0.5, 0.2, 2, 0.2, -0.3};
    struct {
        const char *text;
        int dim;
        const double *v;
        size_t n;
        bool closed;
        dfl_rfunc_join join;
        int p;
        dfl_rfunc_trim trim;
    } cases[] = {
        {"[field]\nkind = rfunc\nvertices = 0 0; 1 0.5; 2 0.2; 2.5 1.5\n", 2, v2, 4, false,
         DFL_RFUNC_REQUIV, 2, DFL_RFUNC_TRIM_DISK},
        {"[field]\nkind = rfunc\nvertices = 0 0; 1 0.5; 2 0.2; 2.5 1.5\nclosed = true\njoin = "
         "rconj\np = 7\ntrim = strip\n",
         2, v2, 4, true, DFL_RFUNC_RCONJ, 7, DFL_RFUNC_TRIM_STRIP},
        {"[field]\nkind = rfunc\nvertices = 0 0 0; 1 0.5 0.2; 2 0.2 -0.3\njoin = "
         "requiv_corrected\np = 12\ntrim = disk_smooth\n",
         3, v3, 3, false, DFL_RFUNC_REQUIV_CORRECTED, 12, DFL_RFUNC_TRIM_DISK_SMOOTH},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        dfl_field f, g;
        dfl_err err;
        cr_assert_eq(build(cases[k].text, &f, &err), DFL_OK, "%s", err.msg);
        cr_assert_eq(f.dim, cases[k].dim);
        cr_assert_eq(dfl_rfield_polyline(cases[k].dim, cases[k].v, cases[k].n, cases[k].closed,
                                         cases[k].join, cases[k].p, cases[k].trim, &g, NULL),
                     DFL_OK);
        uint64_t rng = 5;
        for (int i = 0; i < 100; i++) {
            double x[3];
            for (int j = 0; j < 3; j++) x[j] = tu_uniform(&rng, -1, 3);
            cr_assert_eq(dfl_field_eval1(&f, x, NULL), dfl_field_eval1(&g, x, NULL));
        }
        dfl_field_destroy(&f);
        dfl_field_destroy(&g);
    }
}

static void expect_error(const char *text, const char *needle1, const char *needle2)
{
    dfl_field f;
    dfl_err err;
    cr_assert_eq(build(text, &f, &err), DFL_E_INPUT, "accepted: %s", text);
    cr_assert(strstr(err.msg, needle1) != NULL, "'%s' not in '%s'", needle1, err.msg);
    if (needle2) cr_assert(strstr(err.msg, needle2) != NULL, "'%s' not in '%s'", needle2, err.msg);
}

Test(rfunc_cfg, bad_input)
{
    expect_error("[field]\nkind = rfunc\nvertices = 0 0; 1 1\njoin = rconj\np = 1\n", "p",
                 "test.ini:5");
    expect_error("[field]\nkind = rfunc\nvertices = 0 0; 1 1; 1 1; 2 0\n", "degenerate",
                 "test.ini:3");
    expect_error("[field]\nkind = rfunc\nvertices = 0 0; 1 1\ntrim = box\n", "trim", NULL);
    expect_error("[field]\nkind = rfunc\nvertices = 0 0; 1 1\nclosed = true\n", "vertices", NULL);
    expect_error("[field]\nkind = rfunc\n", "vertices", "curve");
    expect_error("[field]\nkind = rfunc\nvertices = 0 0; 1 1\ncurve = c\neps = 0.1\n", "both",
                 NULL);
    expect_error("[field]\nkind = rfunc\nvertices = 0; 1\n", "vertices", NULL);
    expect_error("[field]\nkind = rfunc\nvertices = 0 0; 1 1\np = 0\n", "p", NULL);
    expect_error("[field]\nkind = rfunc\ncurve = nowhere\neps = 0.01\n", "nowhere", NULL);
    expect_error("[field]\nkind = rfunc\ncurve = c\n[c]\nkind = circle\ncenter = 0 0\nradius = 1\n",
                 "eps", NULL);
}

/* curve = <section>, eps: the field vanishes at the vertices of the certified
 * polygonization (points of the curve); a closed curve gives a closed
 * polyline. */
Test(rfunc_cfg, curve_polygonized)
{
    const char *curve_sec = "[c]\nkind = bspline_curve\norder = 4\ncontrol = 0 0; 1 2; 2 -1; 3 1; 4 0\n";
    char text[512];
    snprintf(text, sizeof text, "[field]\nkind = rfunc\ncurve = c\neps = 0.001\np = 3\n%s",
             curve_sec);
    dfl_field f;
    dfl_err err;
    dfl_status st = build(text, &f, &err);
    cr_assert_eq(st, DFL_OK, "%s", err.msg);
    /* The same polygonization through the library. */
    dfl_cfg *cfg;
    cr_assert_eq(dfl_cfg_parse_string("c.ini", curve_sec, &cfg, &err), DFL_OK);
    dfl_bspline c;
    cr_assert_eq(dfl_curve_from_cfg(cfg, "c", &c, &err), DFL_OK, "%s", err.msg);
    dfl_polyline pl;
    cr_assert_eq(dfl_polygonize_curve(&c, 0.001, 0, &pl, &err), DFL_OK);
    cr_assert(pl.n > 10);
    for (size_t i = 0; i < pl.n; i++) cr_assert_eq(dfl_field_eval1(&f, pl.pts + 2 * i, NULL), 0.0);
    /* Within eps of the curve the field is O(eps) (bs04 eq. 9). */
    for (int i = 0; i <= 50; i++) {
        double y[2];
        dfl_bspline_eval(&c, c.t0 + 0.02 * i * (c.t1 - c.t0), 0, y);
        cr_assert(dfl_field_eval1(&f, y, NULL) <= 2e-3);
    }
    dfl_polyline_free(&pl);
    dfl_bspline_free(&c);
    dfl_cfg_free(cfg);
    dfl_field_destroy(&f);
}

/* The parsed spec says what the section says; defaults are those of the
 * header; the field built from it is the library's polyline field. */
Test(rfunc_cfg, spec_holds_what_was_parsed)
{
    dfl_cfg *cfg = tu_cfg("s.ini",
                          "[field]\nkind = rfunc\nvertices = 0 0; 1 0.5; 2 0.2\nclosed = true\n"
                         "join = requiv_corrected\np = 5\ntrim = strip_smooth\n");
    dfl_rfunc_field_spec s;
    dfl_err err;
    cr_assert_eq(dfl_rfunc_spec_from_cfg(cfg, "field", &s, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(s.join, DFL_RFUNC_REQUIV_CORRECTED);
    cr_expect_eq(s.p, 5);
    cr_expect_eq(s.trim, DFL_RFUNC_TRIM_STRIP_SMOOTH);
    cr_expect_eq(s.dim, 2);
    cr_expect(s.closed);
    cr_assert_eq(s.n, 3);
    const double v[6] = {0, 0, 1, 0.5, 2, 0.2};
    cr_expect_arr_eq(s.v, v, sizeof v);
    cr_expect_null(s.curve);
    cr_expect_eq(s.eps, 0.0);
    dfl_field f, g;
    cr_assert_eq(dfl_rfunc_field_from_spec(cfg, "field", &s, &f, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(dfl_rfield_polyline(2, v, 3, true, DFL_RFUNC_REQUIV_CORRECTED, 5,
                                     DFL_RFUNC_TRIM_STRIP_SMOOTH, &g, NULL),
                 DFL_OK);
    const double x[2] = {0.7, -0.3};
    cr_expect_eq(dfl_field_eval1(&f, x, NULL), dfl_field_eval1(&g, x, NULL));
    dfl_field_destroy(&f);
    dfl_field_destroy(&g);
    dfl_rfunc_spec_free(&s);
    cr_expect_null(s.v);
    dfl_rfunc_spec_free(&s); /* safe twice */
    dfl_cfg_free(cfg);

    cfg = tu_cfg("s.ini", "[field]\nkind = rfunc\nvertices = 0 0 0; 1 0 1\n");
    cr_assert_eq(dfl_rfunc_spec_from_cfg(cfg, "field", &s, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(s.join, DFL_RFUNC_REQUIV);
    cr_expect_eq(s.p, 2);
    cr_expect_eq(s.trim, DFL_RFUNC_TRIM_DISK);
    cr_expect_eq(s.dim, 3);
    cr_expect_not(s.closed);
    dfl_rfunc_spec_free(&s);
    dfl_cfg_free(cfg);
}

/* With a curve the spec keeps the curve and its polygonization; a closed
 * curve drops the repeated point and closes the polyline. */
Test(rfunc_cfg, spec_of_a_curve)
{
    dfl_cfg *cfg = tu_cfg("s.ini",
                          "[field]\nkind = rfunc\ncurve = c\neps = 0.01\njoin = rconj\np = 3\n"
                         "[c]\nkind = bspline_curve\norder = 3\nclosed = true\n"
                         "control = 0 0; 1 0; 1 1; 0 1\n");
    dfl_rfunc_field_spec s;
    dfl_err err;
    cr_assert_eq(dfl_rfunc_spec_from_cfg(cfg, "field", &s, &err), DFL_OK, "%s", err.msg);
    cr_expect_str_eq(s.curve, "c");
    cr_expect_eq(s.eps, 0.01);
    cr_expect_eq(s.bspline.dim, 2);
    cr_assert(s.pl.n >= 4);
    cr_expect(s.pl.bound <= 0.01);
    cr_expect(s.closed);
    cr_expect_eq(s.n, s.pl.n - 1);
    cr_expect_arr_eq(s.v, s.pl.pts, 2 * s.n * sizeof *s.v);
    dfl_field f;
    cr_assert_eq(dfl_rfunc_field_from_spec(cfg, "field", &s, &f, &err), DFL_OK, "%s", err.msg);
    for (size_t i = 0; i < s.n; i++) cr_expect_eq(dfl_field_eval1(&f, s.v + 2 * i, NULL), 0.0);
    dfl_field_destroy(&f);
    dfl_rfunc_spec_free(&s);
    dfl_cfg_free(cfg);
}

/* rconj with p = 1 parses (a study may report it) and fails to build, at
 * key p; the spec is zeroed when parsing fails. */
Test(rfunc_cfg, pair_checked_when_built)
{
    dfl_cfg *cfg =
        tu_cfg("s.ini", "[field]\nkind = rfunc\nvertices = 0 0; 1 1\njoin = rconj\np = 1\n");
    dfl_rfunc_field_spec s;
    dfl_err err;
    cr_assert_eq(dfl_rfunc_spec_from_cfg(cfg, "field", &s, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(s.join, DFL_RFUNC_RCONJ);
    cr_expect_eq(s.p, 1);
    dfl_field f;
    cr_expect_eq(dfl_rfunc_field_from_spec(cfg, "field", &s, &f, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "s.ini:5") && strstr(err.msg, "p"), "%s", err.msg);
    dfl_rfunc_spec_free(&s);
    dfl_cfg_free(cfg);
    cfg = tu_cfg("s.ini", "[field]\nkind = rfunc\nvertices = 0 0; 1 1\ntrim = box\n");
    memset(&s, 0xff, sizeof s);
    cr_expect_eq(dfl_rfunc_spec_from_cfg(cfg, "field", &s, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "disk|disk_smooth|strip|strip_smooth"), "%s", err.msg);
    cr_expect_null(s.v);
    cr_expect_eq(s.n, 0);
    dfl_cfg_free(cfg);
    cfg = tu_cfg("s.ini", "[field]\nkind = rfunc\nvertices = 0 0; 1 1\ncurve = c\n");
    cr_expect_eq(dfl_rfunc_spec_from_cfg(cfg, "field", &s, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "s.ini:4") && strstr(err.msg, "both"), "%s", err.msg);
    dfl_cfg_free(cfg);
}

/* The shared readers of [study]-style keys. */
Test(rfunc_cfg, join_trim_tri_readers)
{
    dfl_cfg *cfg = tu_cfg("s.ini", "[a]\njoin = rconj\np = 7\ntrim = disk_smooth\n"
                         "[b]\n"
                         "[c]\njoin = rconj\np = 1\n"
                         "[d]\njoin = union\n"
                         "[e]\ntri_trim = prism\na = 0.5\nk = 4\nsmooth = true\n");
    dfl_rfunc_join j = DFL_RFUNC_REQUIV_CORRECTED;
    dfl_rfunc_trim t = DFL_RFUNC_TRIM_STRIP;
    int p = -1;
    dfl_err err;
    cr_expect_eq(dfl_rfunc_join_p_from_cfg(cfg, "a", &j, &p, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(j, DFL_RFUNC_RCONJ);
    cr_expect_eq(p, 7);
    cr_expect_eq(dfl_rfunc_trim_from_cfg(cfg, "a", &t, &err), DFL_OK);
    cr_expect_eq(t, DFL_RFUNC_TRIM_DISK_SMOOTH);
    cr_expect_eq(dfl_rfunc_join_p_from_cfg(cfg, "b", &j, &p, &err), DFL_OK);
    cr_expect_eq(j, DFL_RFUNC_REQUIV);
    cr_expect_eq(p, 2);
    cr_expect_eq(dfl_rfunc_trim_from_cfg(cfg, "b", &t, &err), DFL_OK);
    cr_expect_eq(t, DFL_RFUNC_TRIM_DISK);
    cr_expect_eq(dfl_rfunc_join_p_from_cfg(cfg, "c", &j, &p, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "s.ini:8") && strstr(err.msg, "p >= 2"), "%s", err.msg);
    cr_expect_eq(j, DFL_RFUNC_REQUIV, "untouched on failure");
    cr_expect_eq(dfl_rfunc_join_from_cfg(cfg, "c", &j, &err), DFL_OK);
    cr_expect_eq(j, DFL_RFUNC_RCONJ);
    cr_expect_eq(dfl_rfunc_join_from_cfg(cfg, "d", &j, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "s.ini:10") && strstr(err.msg, "requiv|rconj|requiv_corrected"),
              "%s", err.msg);
    dfl_rfunc_tri_opts o;
    cr_expect_eq(dfl_rfunc_tri_opts_from_cfg(cfg, "e", true, &o, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(o.trim, DFL_RFUNC_TRI_PRISM);
    cr_expect_eq(o.a, 0.5);
    cr_expect_eq(o.k, 4);
    cr_expect_eq(o.smooth, 1);
    cr_expect_eq(dfl_rfunc_tri_opts_from_cfg(cfg, "b", false, &o, &err), DFL_OK);
    const dfl_rfunc_tri_opts d = dfl_rfunc_tri_defaults();
    cr_expect_eq(o.trim, d.trim);
    cr_expect_eq(o.a, d.a);
    cr_expect_eq(o.k, d.k);
    cr_expect_eq(o.smooth, d.smooth);
    dfl_cfg_free(cfg);
}

/* surface = a [shape] kind = mesh section: the mesh's own triangles, as if
 * written in `triangles` (no eps: a mesh is not triangulated again), the
 * same values bit for bit; eps with a mesh is an unknown key. */
Test(rfunc_cfg, surface_of_a_mesh_is_its_triangles)
{
    char dir[] = "/tmp/dflab-rfunc-mesh-XXXXXX";
    cr_assert_not_null(mkdtemp(dir));
    char path[256];
    snprintf(path, sizeof path, "%s/two.obj", dir);
    FILE *fp = fopen(path, "w");
    cr_assert_not_null(fp);
    /* coordinates exact in float (the reader rounds to float) */
    fputs("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0.5 0.5 1\nf 1 2 3\nf 2 4 3\n", fp);
    fclose(fp);
    char text[1024];
    snprintf(text, sizeof text,
             "[field]\nkind = rfunc\nsurface = m\njoin = requiv\np = 3\n"
             "[m]\nkind = mesh\nfile = %s\n",
             path);
    dfl_field f, g;
    dfl_err err;
    cr_assert_eq(build(text, &f, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(build("[field]\nkind = rfunc\njoin = requiv\np = 3\n"
                       "triangles = 0 0 0; 1 0 0; 0 1 0; 1 0 0; 0.5 0.5 1; 0 1 0\n",
                       &g, &err),
                 DFL_OK, "%s", err.msg);
    cr_expect_eq(f.dim, 3);
    const double pts[][3] = {{0.2, 0.2, 0.0}, {0.3, 0.1, 0.7}, {-1, 2, 0.5}, {0.6, 0.6, 0.6}};
    for (size_t i = 0; i < sizeof pts / sizeof pts[0]; i++) {
        const double a = dfl_field_eval1(&f, pts[i], NULL), b = dfl_field_eval1(&g, pts[i], NULL);
        cr_expect_eq(a, b, "point %zu: %.17g vs %.17g", i, a, b);
    }
    cr_expect_eq(dfl_field_eval1(&f, pts[0], NULL), 0.0, "on a triangle: 0");
    dfl_field_destroy(&f);
    dfl_field_destroy(&g);
    snprintf(text, sizeof text,
             "[field]\nkind = rfunc\nsurface = m\neps = 1e-3\n[m]\nkind = mesh\nfile = %s\n",
             path);
    dfl_cfg *cfg = tu_cfg("e.ini", text);
    cr_assert_eq(dfl_field_from_cfg(cfg, "field", &f, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(dfl_cfg_check_used(cfg, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "eps"), "%s", err.msg);
    dfl_field_destroy(&f);
    dfl_cfg_free(cfg);
    remove(path);
    rmdir(dir);
}
