/* experiments/cfg/field_cost.h: the bytes and work of a [field] from its
 * keys alone, each expected value derived from the header's formulas. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cfg/field_cost.h"
#include "field/gridpeer.h"
#include "field/vdb.h"
#include "cfg_util.h"
#include "util/tmpdir.h"

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

/* ---- a mesh shape's own cost (field_cost.h: dfl_shape_cost) ---- */

#define MB_TRI (DFL_MESH_TRI_BYTES)
#define MB_SIGNED_TRI (DFL_MESH_TRI_BYTES + DFL_MESH_ANCHOR_TRI_BYTES)

Test(field_cost, mesh_bytes_bound_formula)
{
    cr_expect_eq(dfl_mesh_bytes_bound(1000, 0), 1000 * 2048.0 + 33554432.0);
    cr_expect_eq(dfl_mesh_bytes_bound(1000, 1),
                 1000 * (2048.0 + 16384.0) + 33554432.0 + 67108864.0);
    cr_expect_eq(dfl_mesh_bytes_bound(0, 0), 33554432.0, "the fixed part alone");
    /* the anchors' caps (mesh_anchor.h): 64 n + 2^18 nodes of 4 + 112 + 32
     * bytes, 256 n + 2^20 list entries of 24 bytes, 320 bytes of edges and
     * buffers a triangle: within the anchors' terms */
    cr_expect_geq(DFL_MESH_ANCHOR_TRI_BYTES, 64 * (4 + 112 + 32) + 256 * 24 + 320);
    cr_expect_geq(DFL_MESH_ANCHOR_FIXED_BYTES, 262144.0 * (4 + 112 + 32) + 1048576.0 * 24);
}

static double tris_of(const char *dir, const char *name, const char *text, size_t len,
                      double *size)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "wb");
    cr_assert_not_null(f);
    cr_assert_eq(fwrite(text, 1, len, f), len);
    fclose(f);
    double t, s;
    dfl_err err;
    cr_assert_eq(dfl_mesh_file_tris_bound(path, &t, &s, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(s, (double)len, "%s: the file's size", name);
    if (size) *size = s;
    return t;
}

Test(field_cost, mesh_file_triangles_by_format)
{
    char dir[64];
    tmpdir_new(dir, sizeof dir);
    /* binary STL: 84 + 50 t bytes with the header's count t: exactly t */
    unsigned char stl[84 + 7 * 50];
    memset(stl, 0, sizeof stl);
    stl[80] = 7;
    cr_expect_eq(tris_of(dir, "b.stl", (const char *)stl, sizeof stl, NULL), 7.0);
    /* the same size with a count that does not match: an ASCII STL's
     * 36 bytes a triangle, floor(434 / 36) */
    stl[80] = 9;
    cr_expect_eq(tris_of(dir, "c.STL", (const char *)stl, sizeof stl, NULL), 12.0);
    /* OBJ: a quad (2) and a triangle (1), a pentagon continued over a
     * line (3), "fo" counted as a face (1), not the vertices or a comment */
    const char *obj = "v 0 0 0\nv 1 0 0\n# f 1 2 3\nf 1 2 3 4\n  f 1/1 2//2 3\n"
                      "f 1 2 \\\n 3 4 5\nfo 1 2 3\n";
    cr_expect_eq(tris_of(dir, "m.obj", obj, strlen(obj), NULL), 7.0);
    /* the count, when below size / 2 = 8 (17 bytes) */
    cr_expect_eq(tris_of(dir, "t.obj", "f 1 2 3 4 5 6 7 8", 17, NULL), 6.0);
    /* AC3D: refs k gives k - 2 (a 4-gon, a triangle, a line of 2) */
    const char *ac = "AC3Db\nOBJECT poly\nnumsurf 3\nSURF 0x10\nrefs 4\n0 0 0\n1 0 0\n2 0 0\n"
                     "3 0 0\nSURF 0x10\nrefs 3\n0 0 0\n1 0 0\n2 0 0\nSURF 0x12\nrefs 2\n0 0 0\n"
                     "1 0 0\n";
    cr_expect_eq(tris_of(dir, "m.ac", ac, strlen(ac), NULL), 3.0);
    /* subdiv 2: each k-gon k quads, then 4 of each: 2 (4 + 3 + 2) 4 = 72,
     * above the size's bound */
    char acs[512];
    snprintf(acs, sizeof acs, "%ssubdiv 2\n", ac);
    cr_expect_eq(tris_of(dir, "s.ac", acs, strlen(acs), NULL), 72.0);
    /* OFF: 2 bytes a triangle, floor(11 / 2) */
    cr_expect_eq(tris_of(dir, "m.OFF", "OFF\n3 1 0\n0 ", 11, NULL), 5.0);
    /* a count that is not a plain number: the size's bound, floor(8 / 6) */
    cr_expect_eq(tris_of(dir, "x.ac", "refs 3x\n", 8, NULL), 1.0);
    cr_expect_eq(tris_of(dir, "y.ac", "refs 30\n", 8, NULL), 1.0, "the smaller: size");
    cr_expect_eq(tris_of(dir, "z.ac", "refs 3\nrefs 3\n\n\n\n\n\n\n", 20, NULL), 2.0,
                 "the smaller: refs (size: 3)");
    /* any other format: a byte a triangle */
    cr_expect_eq(tris_of(dir, "m.ply", "ply\nformat binary_little_endian 1.0\n", 34, NULL), 34.0);
    double t, s;
    dfl_err err;
    char path[512];
    snprintf(path, sizeof path, "%s/none.obj", dir);
    cr_expect_eq(dfl_mesh_file_tris_bound(path, &t, &s, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "none.obj") != NULL, "%s", err.msg);
    cr_expect_eq(dfl_mesh_file_tris_bound(dir, &t, &s, &err), DFL_E_INPUT, "a directory");
    tmpdir_remove(dir);
}

static const char *const QUAD_OBJ = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";

Test(field_cost, mesh_file_charged_with_every_field_on_it)
{
    char dir[64], path[512], t[2048];
    tmpdir_new(dir, sizeof dir);
    tmpdir_write(dir, "q.obj", QUAD_OBJ, path, sizeof path);
    const double size = (double)strlen(QUAD_OBJ), n = 2; /* a quad: 2 triangles */
    /* exact, signed (the default) */
    snprintf(t, sizeof t, "[field]\nkind = exact\n[shape]\nkind = mesh\nfile = %s\n", path);
    dfl_cost c = cost_of(t);
    cr_expect_eq(c.bytes, size + n * MB_SIGNED_TRI + 33554432.0 + 67108864.0);
    cr_expect_str_eq(c.mem_sec, "shape");
    cr_expect_str_eq(c.mem_key, "file");
    cr_expect_eq(c.evals[DFL_COST_EXACT], n + 512 * n + 1048576, "reading, BVH, anchors");
    /* unsigned: no anchors */
    snprintf(t, sizeof t,
             "[field]\nkind = exact\nshape = m\n[m]\nkind = mesh\nfile = %s\ndistance = unsigned\n",
             path);
    c = cost_of(t);
    cr_expect_eq(c.bytes, size + n * MB_TRI + 33554432.0);
    cr_expect_eq(c.evals[DFL_COST_EXACT], n);
    /* a grid peer on it: its grid and the shape, held together */
    snprintf(t, sizeof t,
             "[field]\nkind = gridpeer\nres = 4\n[shape]\nkind = mesh\nfile = %s\n"
             "distance = unsigned\n",
             path);
    c = cost_of(t);
    cr_expect_eq(c.bytes, 8.0 * dfl_gridpeer_scalars(DFL_GRIDPEER_TAYLOR1, 4) + size +
                              n * MB_TRI + 33554432.0);
    cr_expect_eq(c.evals[DFL_COST_EXACT], 125.0 + n, "5^3 distances and the triangles");
    /* a CSG of two meshes: both */
    snprintf(t, sizeof t,
             "[field]\nkind = exact\n[shape]\nkind = csg\nop = union\na = m\nb = m\n"
             "[m]\nkind = mesh\nfile = %s\ndistance = unsigned\n",
             path);
    c = cost_of(t);
    cr_expect_eq(c.bytes, 2 * (size + n * MB_TRI + 33554432.0));
    /* R-functions over a mesh section's triangles: a part each, and the
     * mesh shape read for them (not max_tris' 200000) */
    snprintf(t, sizeof t,
             "[field]\nkind = rfunc\nsurface = m\n[m]\nkind = mesh\nfile = %s\n"
             "distance = unsigned\n",
             path);
    c = cost_of(t);
    cr_expect_eq(c.bytes, n * DFL_RFUNC_PART_BYTES + size + n * MB_TRI + 33554432.0);
    dfl_cfg *cfg = tu_cfg("c.ini", t);
    double parts;
    const char *key;
    dfl_err err;
    cr_expect_eq(dfl_rfunc_parts_bound(cfg, "field", &parts, &key, &err), DFL_OK);
    cr_expect_eq(parts, n);
    cr_expect_str_eq(key, "surface");
    cr_expect_eq(dfl_mesh_tris_bound(cfg, "m", &parts, &err), DFL_OK);
    cr_expect_eq(parts, n);
    dfl_cfg_free(cfg);
    /* a file that cannot be read: nothing (the reader names it) */
    snprintf(t, sizeof t, "[field]\nkind = exact\n[shape]\nkind = mesh\nfile = %s/no.obj\n", dir);
    c = cost_of(t);
    cr_expect_eq(c.bytes, 0.0);
    cfg = tu_cfg("c.ini", t);
    cr_expect_eq(dfl_mesh_tris_bound(cfg, "shape", &parts, &err), DFL_OK);
    cr_expect_eq(parts, -1.0, "unknown");
    dfl_cfg_free(cfg);
    tmpdir_remove(dir);
}

Test(field_cost, mesh_polygonize_lattice_and_allowance)
{
    /* resolution 8 on [-1, 1]^3: 8 nodes, 7 cubes a side; 12 (3 * 49)
     * triangles; refine 8 rounds over 7 vertices per node of the sphere */
    dfl_cost c = cost_of("[field]\nkind = exact\n[shape]\nkind = mesh\npolygonize = s\n"
                         "resolution = 8\n[s]\nkind = sphere\ncenter = 0 0 0\nradius = 0.5\n");
    const double nodes = 512, tris = 12.0 * 3 * 49;
    cr_expect_eq(c.bytes, 24 * nodes + tris * MB_SIGNED_TRI + 33554432.0 + 67108864.0);
    cr_expect_str_eq(c.mem_key, "resolution");
    cr_expect_eq(c.evals[DFL_COST_CHEAP], nodes * (1 + 7 * 8));
    cr_expect_eq(c.evals[DFL_COST_EXACT], tris + 512 * tris + 1048576);
    /* a flat box: resolution 11 along the longest side (2), the short one
     * (0.4) ceil(0.2 * 10) + 1 = 3 nodes: 10 x 10 x 2 cubes */
    c = cost_of("[field]\nkind = exact\n[shape]\nkind = mesh\npolygonize = s\nresolution = 11\n"
                "lo = -1 -1 -0.2\nhi = 1 1 0.2\ndistance = unsigned\n"
                "[s]\nkind = sphere\ncenter = 0 0 0\nradius = 0.5\n");
    cr_expect_eq(c.bytes, 24 * 11.0 * 11 * 3 + 12.0 * (100 + 20 + 20) * MB_TRI + 33554432.0);
    /* an implicit surface sampled through its defining function: CHEAP */
    c = cost_of("[field]\nkind = exact\n[shape]\nkind = mesh\npolygonize = s\nresolution = 8\n"
                "refine = 0\n[s]\nkind = implicit\n");
    cr_expect_eq(c.evals[DFL_COST_CHEAP], nodes);
    cr_expect_eq(c.evals[DFL_COST_FOOTPOINT], 0.0);
    dfl_cfg *cfg = tu_cfg("c.ini", "[field]\nkind = exact\n[shape]\nkind = mesh\npolygonize = s\n"
                                   "resolution = 7\n[s]\nkind = sphere\n");
    dfl_err err;
    c = (dfl_cost){0};
    cr_expect_eq(dfl_field_cost_from_cfg(cfg, "field", &c, &err), DFL_E_INPUT,
                 "resolution below 8, as the reader");
    cr_expect(strstr(err.msg, "resolution") != NULL, "%s", err.msg);
    dfl_cfg_free(cfg);
}
