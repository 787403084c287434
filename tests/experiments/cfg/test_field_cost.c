/* experiments/cfg/field_cost.h: the bytes and work of a [field] from its
 * keys alone, each expected value derived from the header's formulas. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cfg/field_cost.h"
#include "field/vdb.h"
#include "cfg_util.h"

static dfl_cost cost_of(const char *text)
{
    dfl_cfg *cfg = tu_cfg("c.ini", text);
    dfl_cost c = {0};
    dfl_err err;
    cr_assert_eq(dfl_field_cost_from_cfg(cfg, "field", &c, &err), DFL_OK, "%s", err.msg);
    dfl_cfg_free(cfg);
    return c;
}

static const char *SPHERE = "[shape]\nkind = sphere\ncenter = 0 0 0\nradius = 0.5\n";

Test(field_cost, proxy_cells_scalars_storage)
{
    char t[512];
    snprintf(t, sizeof t, "[field]\nkind = proxy\norder = 2\nres = 2048\nstorage = double\n%s",
             SPHERE);
    dfl_cost c = cost_of(t);
    const double cells = 2048.0 * 2048 * 2048;
    cr_expect_eq(c.bytes, cells * (8 * 8 + 1)); /* 8 scalars of 8 bytes and a sign byte */
    cr_expect_str_eq(c.mem_key, "res");
    cr_expect_eq(c.evals[DFL_COST_CHEAP], 2 * cells, "order 2: value and curvature per cell");
    snprintf(t, sizeof t, "[field]\nkind = proxy\nres = 10\nstorage = half\ninput = implicit\n%s",
             SPHERE);
    c = cost_of(t);
    cr_expect_eq(c.bytes, 1000.0 * (3 * 2 + 1));
    cr_expect_eq(c.evals[DFL_COST_FOOTPOINT], 1000.0);
}

Test(field_cost, gridpeer_and_pht_level_bound)
{
    char t[512];
    snprintf(t, sizeof t, "[field]\nkind = gridpeer\nmethod = taylor1\nres = 1024\n%s", SPHERE);
    dfl_cost c = cost_of(t);
    cr_expect_eq(c.bytes, 4.0 * 1024 * 1024 * 1024 * 8, "4 scalars of 8 bytes per cell");
    /* tricubic: n^3 coefficients and their (n + 2)^3 extension, doubles,
     * also for float16 storage */
    snprintf(t, sizeof t, "[field]\nkind = gridpeer\nmethod = tricubic\nstorage = float16\n"
                          "res = 100\n%s", SPHERE);
    c = cost_of(t);
    cr_expect_eq(c.bytes, (100.0 * 100 * 100 + 102.0 * 102 * 102) * 8);
    /* 2D pht, cross split: 4^L leaves, 4/3 for inner cells, DFL_PHT_CELL_BYTES each */
    c = cost_of("[field]\nkind = pht\nmax_level = 12\n"
                "[shape]\nkind = circle\ncenter = 0.5 0.5\nradius = 0.3\n");
    cr_expect_eq(c.bytes, ldexp(1.0, 24) * 4.0 / 3.0 * DFL_PHT_CELL_BYTES(2));
    cr_expect_str_eq(c.mem_key, "max_level");
    cr_expect_eq(c.evals[DFL_COST_CHEAP], ldexp(1.0, 24) * (16 + 1), "16 samples + 1 footpoint");
    /* 3D binary split: 2^L leaves, a tree of fan 2: as many inner cells */
    snprintf(t, sizeof t, "[field]\nkind = pht\nsplit = binary\nmax_level = 20\n"
                          "lo = -1 -1 -1\nhi = 1 1 1\n%s", SPHERE);
    c = cost_of(t);
    cr_expect_eq(c.bytes, ldexp(1.0, 20) * 2.0 * DFL_PHT_CELL_BYTES(3));
    /* kinds without size keys cost nothing in proportion to a key */
    c = cost_of("[field]\nkind = exact\n[shape]\nkind = circle\ncenter = 0 0\nradius = 1\n");
    cr_expect_eq(c.bytes, 0);
    cr_expect_null(c.mem_key);
}

/* openvdb: the grid bound of field/vdb.h; voxel 0.05 on [-1, 1]^3: I =
 * [-21, 21] per axis, 6 leaves of 8 per axis meet it (origins -24 .. 16);
 * the bound holds every leaf of I widened by band + 1 = 4 (origins -32 ..
 * 24: 8 per axis), so at least their float buffers */
Test(field_cost, openvdb_bound_from_the_box)
{
    char t[512];
    snprintf(t, sizeof t, "[field]\nkind = openvdb\nvoxel = 0.05\n%s", SPHERE);
    dfl_cost c = cost_of(t);
    dfl_vdb_opts o;
    dfl_vdb_opts_default(&o);
    double leaves;
    cr_expect_eq(c.bytes, dfl_vdb_bytes_bound(&o, &leaves));
    cr_expect_eq(leaves, 216);
    cr_expect_geq(c.bytes, 512 * 512 * 4.0);
    cr_expect_str_eq(c.mem_key, "voxel");
    cr_expect_eq(c.evals[DFL_COST_CHEAP], 216 * 513 + 216.0 / 4096 + 1);
    /* build = mesh adds the lattice of floor(2 / 0.05) + 3 = 43 nodes per axis */
    snprintf(t, sizeof t, "[field]\nkind = openvdb\nvoxel = 0.05\nbuild = mesh\n%s", SPHERE);
    dfl_cost m = cost_of(t);
    cr_expect_eq(m.bytes, c.bytes + 24.0 * 43 * 43 * 43);
    /* voxel 0.025: I = [-41, 41] widened to [-45, 45], leaf origins -48 ..
     * 40, 12 per axis: 1728 - 512 more leaves of at least 2048 bytes (the
     * internal nodes above them are the same 8 + 8) */
    snprintf(t, sizeof t, "[field]\nkind = openvdb\nvoxel = 0.025\n%s", SPHERE);
    cr_expect_geq(cost_of(t).bytes, c.bytes + (1728 - 512) * 2048.0);
}

Test(field_cost, bad_values_fail_as_in_the_factory)
{
    dfl_cfg *cfg = tu_cfg("c.ini", "[field]\nkind = proxy\nres = 4096\n");
    dfl_cost c = {0};
    dfl_err err;
    cr_expect_eq(dfl_field_cost_from_cfg(cfg, "field", &c, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "c.ini:3") && strstr(err.msg, "res"), "%s", err.msg);
    dfl_cfg_free(cfg);
}

Test(field_cost, shape_class_and_dim)
{
    dfl_cfg *cfg = tu_cfg("c.ini", "[a]\nkind = circle\n[b]\nkind = implicit\n"
                                   "[u]\nkind = csg\nop = union\na = a\nb = b\n"
                                   "[p]\nkind = box\ndim = 2\n[s]\nkind = segment\n"
                                   "[m]\nkind = bspline_curve\n[loop]\nkind = csg\na = loop\nb = loop\n"
                                   "[mesh]\nkind = mesh\nfile = w.obj\n");
    cr_expect_eq(dfl_shape_cost_class(cfg, "a"), DFL_COST_CHEAP);
    cr_expect_eq(dfl_shape_cost_class(cfg, "b"), DFL_COST_FOOTPOINT);
    cr_expect_eq(dfl_shape_cost_class(cfg, "u"), DFL_COST_FOOTPOINT, "csg: its dearer operand");
    cr_expect_eq(dfl_shape_cost_class(cfg, "m"), DFL_COST_FOOTPOINT, "curves: footpoints");
    cr_expect_eq(dfl_shape_cost_class(cfg, "mesh"), DFL_COST_EXACT, "meshes: exact distances");
    cr_expect_eq(dfl_shape_dim_guess(cfg, "mesh"), 3);
    cr_expect_eq(dfl_shape_cost_class(cfg, "nowhere"), DFL_COST_EXACT);
    cr_expect_eq(dfl_shape_cost_class(cfg, "loop"), DFL_COST_FOOTPOINT, "a cycle ends (depth bound)");
    cr_expect_eq(dfl_shape_dim_guess(cfg, "a"), 2);
    cr_expect_eq(dfl_shape_dim_guess(cfg, "b"), 3);
    cr_expect_eq(dfl_shape_dim_guess(cfg, "u"), 2, "csg: its a");
    cr_expect_eq(dfl_shape_dim_guess(cfg, "p"), 2);
    cr_expect_eq(dfl_shape_dim_guess(cfg, "s"), 2);
    cr_expect_eq(dfl_shape_dim_guess(cfg, "loop"), 3);
    dfl_cfg_free(cfg);
}
