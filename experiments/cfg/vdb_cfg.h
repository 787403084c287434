/* `[field] kind = openvdb`: an OpenVDB narrow-band level set of the
 * [shape] (field/vdb.h).
 *
 *   voxel   = voxel size > 0                       (default 0.05)
 *   band    = half-width in voxels, 1 .. 1000      (default 3, OpenVDB's)
 *   sampler = box | quadratic | staggered          (default box)
 *   build   = direct | mesh                        (default direct)
 *   lo, hi  = box corners                          (default -1 -1 -1, 1 1 1)
 *   shape   = <section>                            (default shape)
 *
 * build = direct fills the band from the shape's exact SDF (coarse-to-fine
 * band search, field/vdb.h); build = mesh hands openvdb::tools::
 * meshToLevelSet the marching-cubes mesh of the SDF on the voxel lattice of
 * the box (field/iso_mesh.h, 30 refinement rounds), so OpenVDB builds the
 * band itself.  Outside |d| < band * voxel the field's value is +-band *
 * voxel (the background): it is a distance only in the band, and
 * dfl_vdb_field_grid / dfl_vdb_background give the band to restrict
 * metrics to.
 *
 * Errors: DFL_E_INPUT naming file:line and key (voxel <= 0, band < 1, an
 * unknown sampler or build, lo >= hi, a box over 2^15 voxels per axis or
 * beyond 2^30 from the origin, a 2D shape).
 */
#ifndef DFL_EXPERIMENTS_VDB_CFG_H
#define DFL_EXPERIMENTS_VDB_CFG_H

#include "core/status.h"
#include "field/field.h"
#include "field/vdb.h"
#include "io/config.h"

typedef struct dfl_vdb_cfg {
    dfl_vdb_opts opts;
    dfl_vdb_build build;
    const char *shape;     /* the shape section (borrowed from cfg) */
} dfl_vdb_cfg;

/* The keys of [sec] into *out (no build): what the factory and the cost
 * estimate share. */
dfl_status dfl_vdb_cfg_read(const dfl_cfg *cfg, const char *sec, dfl_vdb_cfg *out, dfl_err *err);

/* Builds the field of [sec] (kind = openvdb). */
dfl_status dfl_vdb_field_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_field *out,
                                  dfl_err *err);

#endif
