/* experiments/cfg/vdb_cfg.h: the keys of [field] kind = openvdb, their
 * defaults, the factory's grid (band, voxel, lattice, build) and its
 * rejections naming the key. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cfg/field_cfg.h"
#include "cfg/vdb_cfg.h"
#include "cfg_util.h"

#define SPHERE "[shape]\nkind = sphere\ncenter = 0 0 0\nradius = 0.5\n"

Test(vdb_cfg, defaults)
{
    dfl_cfg *cfg = tu_cfg("v.ini", "[field]\nkind = openvdb\n" SPHERE);
    dfl_vdb_cfg c;
    dfl_err err;
    cr_assert_eq(dfl_vdb_cfg_read(cfg, "field", &c, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(c.opts.voxel, 0.05);
    cr_expect_eq(c.opts.band, 3);
    cr_expect_eq(c.opts.sampler, DFL_VDB_BOX);
    cr_expect_eq(c.build, DFL_VDB_DIRECT);
    cr_expect_eq(c.opts.lipschitz, 1);
    for (int a = 0; a < 3; a++) cr_expect(c.opts.lo[a] == -1 && c.opts.hi[a] == 1);
    cr_expect_str_eq(c.shape, "shape");
    dfl_cfg_free(cfg);
}

Test(vdb_cfg, factory_grid_has_the_keys)
{
    static const char *const smp[] = {"box", "quadratic", "staggered"};
    for (int k = 0; k < 3; k++)
        for (int b = 0; b < 2; b++) {
            char t[512];
            snprintf(t, sizeof t,
                     "[field]\nkind = openvdb\nvoxel = 0.0625\nband = 4\nsampler = %s\n"
                     "build = %s\n" SPHERE,
                     smp[k], b ? "mesh" : "direct");
            dfl_cfg *cfg = tu_cfg("v.ini", t);
            dfl_field f;
            dfl_err err;
            cr_assert_eq(dfl_field_from_cfg(cfg, "field", &f, &err), DFL_OK, "%s", err.msg);
            dfl_vdb_sampler s;
            const dfl_vdb *g = dfl_vdb_field_grid(&f, &s);
            cr_assert_not_null(g);
            cr_expect_eq(s, (dfl_vdb_sampler)k);
            cr_expect_eq(dfl_vdb_lattice_sampler(g), (dfl_vdb_sampler)k);
            cr_expect_eq(dfl_vdb_band(g), 4);
            cr_expect_eq(dfl_vdb_voxel(g), 0.0625);
            cr_expect_eq(dfl_vdb_background(g), 0.25);
            /* the mesh build makes no SDF evaluations of its own */
            cr_expect_eq(dfl_vdb_evals(g) == 0, b == 1);
            /* the voxel at the sphere's +x pole: d = 0 up to the build */
            const int ijk[3] = {8, 0, 0};
            double x[3];
            dfl_vdb_voxel_centre(g, ijk, x);
            const double d = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]) - 0.5;
            int on;
            const float v = dfl_vdb_voxel_value(g, ijk, &on);
            cr_expect(on);
            cr_expect(fabs(v - d) < 0.01, "%s %d: %g vs %g", smp[k], b, v, d);
            dfl_field_destroy(&f);
            dfl_cfg_free(cfg);
        }
}

Test(vdb_cfg, rejections_name_the_key)
{
    static const char *const bad[][2] = {
        {"[field]\nkind = openvdb\nvoxel = 0\n" SPHERE, "voxel"},
        {"[field]\nkind = openvdb\nband = 0\n" SPHERE, "band"},
        {"[field]\nkind = openvdb\nsampler = tricubic\n" SPHERE, "sampler"},
        {"[field]\nkind = openvdb\nbuild = fast\n" SPHERE, "build"},
        {"[field]\nkind = openvdb\nhi = 1 -2 1\n" SPHERE, "hi"},
        {"[field]\nkind = openvdb\nvoxel = 1e-5\n" SPHERE, "voxel"},
        {"[field]\nkind = openvdb\nshape = nowhere\n" SPHERE, "shape"},
        {"[field]\nkind = openvdb\n[shape]\nkind = circle\ncenter = 0 0\nradius = 1\n", "shape"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        dfl_cfg *cfg = tu_cfg("v.ini", bad[i][0]);
        dfl_field f;
        dfl_err err;
        cr_expect_eq(dfl_field_from_cfg(cfg, "field", &f, &err), DFL_E_INPUT, "case %zu", i);
        cr_expect(strstr(err.msg, "v.ini") && strstr(err.msg, bad[i][1]), "case %zu: %s", i,
                  err.msg);
        dfl_cfg_free(cfg);
    }
}
