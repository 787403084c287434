/* End-to-end: the bs04 polygonization study, the shipped parametric shape
 * configs, and their bad-input errors.  Expected values come from the
 * library run directly on the shipped configs (the study must reproduce
 * them), from the theory (bound <= eps, exponent near -1/2) and from VTK's
 * own reader, never from a previous run. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/e2e_util.h"
#include "geom/polygonize.h"
#include "io/config.h"
#include "cfg/shape_cfg.h"

#define CFG "configs/paper/bs04/bs04_polygonization.ini"

Test(e2e_bs04_poly, study_rows_files_and_growth, .timeout = 300)
{
    char dir[256], out[512], path[700];
    e2e_tmpdir(dir, sizeof dir);
    /* 5 eps x 2 curves: 10 rows, 10 polylines + csv + config + manifest
     * + a collection (.pvd) per curve over the 5 eps
     * (the paper config sweeps all 7 fitted eps; 5 keep this test short) */
    e2e_run_table(CFG, "--set 'study.eps=1e-2, 3e-3, 1e-3, 1e-4, 1e-5'", "bs04_polygonization",
                  10, out, sizeof out, path, sizeof path);
    cr_expect_eq(e2e_count_entries(out), 13 + 2);

    dfl_bspline S, W;
    e2e_load_curve("configs/shapes/S.ini", "shape", &S);
    e2e_load_curve("configs/shapes/W.ini", "shape", &W);
    double prev[2] = {0, 0};
    for (long r = 0; r < 10; r++) {
        char *curve = e2e_csv_cell(path, r, "curve");
        cr_assert_not_null(curve);
        int isS = strcmp(curve, "S") == 0;
        cr_assert(isS || strcmp(curve, "W") == 0, "curve %s", curve);
        double eps = e2e_csv_get(path, (size_t)r, "eps");
        double seg = e2e_csv_get(path, (size_t)r, "segments");
        double bound = e2e_csv_get(path, (size_t)r, "bound");
        double meas = e2e_csv_get(path, (size_t)r, "measured");
        double fit = e2e_csv_get(path, (size_t)r, "fit_exponent");
        cr_expect(bound <= eps && meas <= bound && meas > 0.3 * eps,
                  "row %ld: eps %g bound %g measured %g", r, eps, bound, meas);
        cr_expect(fit >= -0.6 && fit <= -0.4, "row %ld: fitted exponent %g", r, fit);
        /* the study polygonizes the shipped shape configs */
        dfl_polyline p;
        cr_assert_eq(dfl_polygonize_curve(isS ? &S : &W, eps, 0, &p, NULL), DFL_OK);
        cr_expect_eq((long)seg, (long)(p.n - 1), "row %ld", r);
        cr_expect_float_eq(bound, p.bound, 1e-15);
        cr_expect(seg > prev[isS], "counts must grow as eps shrinks");
        prev[isS] = seg;
        /* the paper's counts for S where bs04 states them */
        double paper = e2e_csv_get(path, (size_t)r, "paper_segments");
        if (isS && (eps == 1e-2 || eps == 1e-3 || eps == 1e-5))
            cr_expect_eq((long)paper, eps == 1e-2 ? 56 : eps == 1e-3 ? 157 : 1499);
        else
            cr_expect(isnan(paper), "row %ld has paper_segments %g", r, paper);
        if (isS) {
            /* least-squares slope of bs04's (1e-2, 56), (1e-3, 157), (1e-5, 1499) */
            double x[3] = {log(1e-2), log(1e-3), log(1e-5)}, y[3] = {log(56), log(157), log(1499)};
            double sx = x[0] + x[1] + x[2], sy = y[0] + y[1] + y[2], sxx = 0, sxy = 0;
            for (int i = 0; i < 3; i++) sxx += x[i] * x[i], sxy += x[i] * y[i];
            double k = (3 * sxy - sx * sy) / (3 * sxx - sx * sx);
            cr_expect_float_eq(e2e_csv_get(path, (size_t)r, "paper_fit_exponent"), k, 1e-12);
        }
        /* the .vtp through VTK's reader: point count, z = 0, points on the curve */
        char *vtp = e2e_csv_cell(path, r, "vtp");
        cr_assert_not_null(vtp);
        char *py;
        const int prc = e2e_python_run(
            dir, &py,
            "-c \"import sys, vtk\n"
            "from vtkmodules.util.numpy_support import vtk_to_numpy as v\n"
            "r = vtk.vtkXMLPolyDataReader(); r.SetFileName(sys.argv[1]); r.Update()\n"
            "d = r.GetOutput(); P = v(d.GetPoints().GetData())\n"
            "t = v(d.GetPointData().GetArray('t'))\n"
            "print(d.GetNumberOfPoints(), d.GetNumberOfLines(), abs(P[:,2]).max(), "
            "(t[1:] > t[:-1]).all(), repr(P[-1,0]), repr(P[-1,1]))\" %s/%s",
            out, vtp);
        cr_assert_eq(prc, 0, "VTK check failed: %s", py);
        long np = 0, nl = 0;
        double zmax = 1, lx = 0, ly = 0;
        char mono[16] = "";
        cr_assert_eq(sscanf(py, "%ld %ld %lf %15s %lf %lf", &np, &nl, &zmax, mono, &lx, &ly), 6,
                     "%s", py);
        cr_expect_eq(np, (long)p.n);
        cr_expect_eq(nl, 1);
        cr_expect_eq(zmax, 0.0);
        cr_expect_str_eq(mono, "True");
        double e[2];
        dfl_bspline_eval(isS ? &S : &W, (isS ? &S : &W)->t1, 0, e);
        cr_expect(fabs(lx - e[0]) < 1e-14 && fabs(ly - e[1]) < 1e-14);
        free(py);
        free(vtp);
        free(curve);
        dfl_polyline_free(&p);
    }
    dfl_bspline_free(&S);
    dfl_bspline_free(&W);
}

/* every shipped shape config builds through the [shape] dispatcher */
Test(e2e_bs04_poly, shipped_shape_configs_build)
{
    const char *files[] = {"S", "W", "space1", "space2", "surface", "bezier2", "blob"};
    const int dims[] = {2, 2, 3, 3, 3, 3, 2};
    for (int i = 0; i < 7; i++) {
        char p[256];
        snprintf(p, sizeof p, "configs/shapes/%s.ini", files[i]);
        dfl_cfg *cfg;
        dfl_err err;
        cr_assert_eq(dfl_cfg_load(p, &cfg, &err), DFL_OK, "%s", err.msg);
        dfl_shape sh;
        cr_assert_eq(dfl_shape_from_cfg(cfg, "shape", &sh, &err), DFL_OK, "%s: %s", p, err.msg);
        cr_assert_eq(dfl_cfg_check_used(cfg, &err), DFL_OK, "%s", err.msg);
        cr_assert_eq(sh.dim, dims[i], "%s", p);
        double x[3] = {0.5, 0.45, 0.5}, g[3];
        double d = dfl_shape_eval1(&sh, x, g);
        double gn = sqrt(g[0] * g[0] + g[1] * g[1] + (sh.dim == 3 ? g[2] * g[2] : 0));
        cr_expect(isfinite(d) && fabs(gn - 1.0) < 1e-12, "%s: d %g |g| %g", p, d, gn);
        if (strcmp(files[i], "blob") == 0) cr_expect(d < 0, "blob: (0.5, 0.45) is inside");
        else cr_expect(d >= 0, "%s: unsigned distance", p);
        dfl_shape_free(&sh);
        dfl_cfg_free(cfg);
    }
}

/* bad input: message names file:line, [section] key and what was expected */
static void bad(const char *ini, const char *want1, const char *want2)
{
    dfl_cfg *cfg;
    dfl_err err;
    cr_assert_eq(dfl_cfg_parse_string("bad.ini", ini, &cfg, &err), DFL_OK, "%s", err.msg);
    dfl_shape sh;
    dfl_status st = dfl_shape_from_cfg(cfg, "shape", &sh, &err);
    cr_expect_eq(st, DFL_E_INPUT, "accepted: %s", ini);
    if (st == DFL_E_INPUT) {
        cr_expect(strstr(err.msg, want1) != NULL, "'%s' not in: %s", want1, err.msg);
        cr_expect(strstr(err.msg, want2) != NULL, "'%s' not in: %s", want2, err.msg);
    } else if (st == DFL_OK) {
        dfl_shape_free(&sh);
    }
    dfl_cfg_free(cfg);
}

#define CURVE "[shape]\nkind = bspline_curve\n"
#define CP4 "control = 0 0; 1 0; 1 1; 0 1\n"

Test(e2e_bs04_poly, bad_shape_input)
{
    bad(CURVE "order = 4\n" CP4 "knots = 0 0 0 0 1 1 1\n", "bad.ini:5: [shape] knots", "expected 8");
    bad(CURVE "order = 4\n" CP4 "knots = 0 0 0 0 1 0.5 1 1\n", "[shape] knots", "non-decreasing");
    bad(CURVE "order = 1\n" CP4, "[shape] order", "[2, 16]");
    bad(CURVE "order = 4\ncontrol = 1 1; 1 1; 1 1; 1 1\n", "[shape] control", "degenerate");
    bad(CURVE "order = 3\ncontrol = 0 0; 1 0; 1 0; 1 0; 2 1\n", "[shape] control", "zero speed");
    bad(CURVE "order = 4\ncontrol = 0 0; 1 0\n", "[shape] control", "at least 4");
    bad(CURVE "order = 4\ncontrol = 0 0 0 0; 1 0 0 0\n", "[shape] control", "2 (planar) or 3");
    bad(CURVE "order = 4\n" CP4 "distance = signed\n", "[shape] distance", "closed");
    bad(CURVE "order = 4\nclosed = true\n" CP4 "knots = 0 1 2 3\n", "[shape] knots", "breakpoints");
    bad(CURVE "order = 4\nclosed = true\ncontrol = 0 0; 1 0\n", "[shape] control", "at least 3");
    bad(CURVE "order = 4\n" CP4 "backend = magic\n", "[shape] backend", "newton");
    bad("[shape]\nkind = bspline_surface\nnu = 4\nnv = 4\ncontrol = 0 0 0; 1 0 0\n",
        "[shape] control", "nu x nv = 16");
    bad("[shape]\nkind = bspline_surface\nnu = 2\nnv = 4\ncontrol = 0 0 0\n", "[shape] nu",
        "[4, 100000]");
    /* a kinked pair of bilinear patches: C0 but not G1 */
    bad("[shape]\nkind = bezier_surface\norder_u = 2\norder_v = 2\npatches = 2\n"
        "continuity = G1\ncontrol = 0 0 0; 1 0 0; 0 1 0; 1 1 0; 1 0 0; 2 0 1; 1 1 0; 2 1 1\n",
        "[shape] continuity", "only C0");
    bad("[shape]\nkind = bezier_surface\norder_u = 2\norder_v = 2\npatches = 2\n"
        "continuity = C0\ncontrol = 0 0 0; 1 0 0; 0 1 0; 1 1 0; 5 0 0; 6 0 1; 5 1 0; 6 1 1\n",
        "[shape] continuity", "shares no edge");
}

Test(e2e_bs04_poly, bad_study_input_exits_2_without_files)
{
    static const char *const sets[][2] = {
        {"--set study.eps=0", "study.eps: expected a finite number in [1e-12, "},
        {"--set study.eps=1e-300", "study.eps: expected a finite number in [1e-12, "},
        {"--set study.eps=-1e-3", "study.eps"},
        {"--set study.fit_eps=1e-3", "study.fit_eps"},
        {"--set study.curves=S_X", "no section [S_X]"},
        {"--set 'S.knots=0 1 2'", "S.knots: 3 knots given, expected 13"},
        {"--set S.order=1", "S.order"},
        {"--set W.colour=red", "W.colour"},
    };
    e2e_expect_bad_runs(CFG, NULL, sets, sizeof sets / sizeof sets[0]);
}
