#include "cfg/vdb_cfg.h"

#include <math.h>

#include "cfg/shape_cfg.h"
#include "field/exact.h"
#include "field/isomesh.h"
#include "geom/mesh.h"

dfl_status dfl_vdb_cfg_read(const dfl_cfg *cfg, const char *sec, dfl_vdb_cfg *out, dfl_err *err)
{
    static const double dlo[3] = {-1, -1, -1}, dhi[3] = {1, 1, 1};
    dfl_vdb_opts_default(&out->opts);
    int sampler = DFL_VDB_BOX, build = DFL_VDB_DIRECT;
    long band = 3;
    dfl_status st = dfl_cfg_double_opt(cfg, sec, "voxel", 0.05, 0, 1e150, &out->opts.voxel, err);
    if (!st && !(out->opts.voxel > 0))
        return dfl_cfg_reject(cfg, sec, "voxel", err, "expected a voxel size > 0");
    if (!st) st = dfl_cfg_int_opt(cfg, sec, "band", 3, 1, 1000, &band, err);
    if (!st) st = dfl_cfg_enum_opt(cfg, sec, "sampler", dfl_vdb_sampler_names,
                                   DFL_VDB_SAMPLER_COUNT, sampler, &sampler, err);
    if (!st) st = dfl_cfg_enum_opt(cfg, sec, "build", dfl_vdb_build_names, DFL_VDB_BUILD_COUNT,
                                   build, &build, err);
    if (!st) st = dfl_cfg_vec_opt(cfg, sec, "lo", 3, dlo, out->opts.lo, err);
    if (!st) st = dfl_cfg_vec_opt(cfg, sec, "hi", 3, dhi, out->opts.hi, err);
    if (!st) st = dfl_cfg_string_opt(cfg, sec, "shape", "shape", &out->shape, err);
    if (st) return st;
    for (int a = 0; a < 3; a++)
        if (!(out->opts.lo[a] < out->opts.hi[a]))
            return dfl_cfg_reject(cfg, sec, "hi", err, "expected hi > lo on axis %d", a);
    out->opts.band = (int)band;
    out->opts.sampler = (dfl_vdb_sampler)sampler;
    out->build = (dfl_vdb_build)build;
    /* the lattice limits of field/vdb.h: at most 2^15 voxels per axis,
     * within 2^30 of the origin */
    if (dfl_vdb_bytes_bound(&out->opts, NULL) == 0)
        return dfl_cfg_reject(cfg, sec, "voxel", err,
                              "voxel %g: the box spans more than 2^15 voxels per axis or reaches"
                              " beyond 2^30 voxels from the origin",
                              out->opts.voxel);
    return DFL_OK;
}

/* build = mesh: meshToLevelSet of a mesh shape's own triangles (OpenVDB's
 * build of the user's mesh), else of the shape's marching-cubes mesh on the
 * voxel lattice of the box (field/isomesh.h). */
static dfl_status mesh_build(dfl_shape *shape, const dfl_vdb_opts *o, dfl_vdb **g, dfl_err *err)
{
    const dfl_trimesh *own = dfl_shape_mesh_trimesh(shape);
    if (own) return dfl_vdb_from_mesh(own, o, g, err);
    const double sh = o->sampler == DFL_VDB_STAGGERED ? -0.5 : 0.0;
    dfl_grid grid = {3, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    for (int a = 0; a < 3; a++) {
        const double l = floor(o->lo[a] / o->voxel - sh), u = ceil(o->hi[a] / o->voxel - sh);
        grid.n[a] = (int)(u - l) + 1;
        grid.lo[a] = (l + sh) * o->voxel;
        grid.hi[a] = (u + sh) * o->voxel;
    }
    dfl_trimesh m;
    dfl_status st = dfl_shape_isomesh(shape, &grid, 30, o->threads, &m, NULL, err);
    if (!st) st = dfl_vdb_from_mesh(&m, o, g, err);
    dfl_trimesh_free(&m);
    return st;
}

dfl_status dfl_vdb_field_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_field *out,
                                  dfl_err *err)
{
    dfl_vdb_cfg c;
    dfl_status st = dfl_vdb_cfg_read(cfg, sec, &c, err);
    if (st) return st;
    if (!dfl_cfg_has_section(cfg, c.shape))
        return dfl_cfg_reject(cfg, sec, "shape", err, "no section [%s]", c.shape);
    dfl_shape shape;
    if ((st = dfl_shape_from_cfg(cfg, c.shape, &shape, err))) return st;
    if (shape.dim != 3) {
        dfl_shape_free(&shape);
        return dfl_cfg_reject(cfg, sec, "shape", err, "expected a 3D shape, [%s] is %dD", c.shape,
                              shape.dim);
    }
    if (dfl_cfg_validating(cfg)) { /* keys read and checked: no level set (io/config.h) */
        dfl_shape_free(&shape);
        dfl_field_placeholder(3, out);
        return DFL_OK;
    }
    dfl_vdb *g = NULL;
    if (c.build == DFL_VDB_MESH)
        st = mesh_build(&shape, &c.opts, &g, err); /* takes the shape */
    else
        st = dfl_vdb_from_shape(&shape, &c.opts, &g, err);
    dfl_shape_free(&shape);
    if (!st) st = dfl_vdb_field_new(&g, c.opts.sampler, out, err);
    dfl_vdb_free(g);
    if (st == DFL_E_INPUT) return dfl_cfg_err_at(cfg, sec, "build", st, err);
    return st;
}
