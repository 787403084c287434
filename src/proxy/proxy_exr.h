/* Proxy grids as OpenEXR files (the paper's 3D textures, one file each).
 *
 * Function index
 *   dfl_proxy_exr_save   grid -> EXR file (atomic: temp file + rename)
 *   dfl_proxy_exr_load   EXR file -> grid (decodes bit-identically)
 *
 * Layout: one scanline part, ZIP (lossless), width N, height N^2; pixel
 * (i, j + N k) is cell (i, j, k).  One channel per stored scalar: px py pz
 * (the footpoint's 3 scalars, displacement or absolute), and for order 2
 * kr kR tx ty tz; half storage gives HALF channels, float FLOAT, and double
 * two UINT channels per scalar, <name>.hi and <name>.lo (the upper and
 * lower 32 bits of the IEEE bits), since EXR has no 64-bit float.  Order 1
 * grids with an inside add a HALF channel `side` (+1 / -1).  Attributes
 * (prefix dflab.proxy.): order, res (int), lo, hi (v3d), storage,
 * position (string), has_inside (int), uncertified, failed, moved
 * (double, exact counts).  The stored bits pass unchanged both ways, so a
 * loaded grid's data and decoded values are identical to the saved grid's.
 */
#ifndef DFL_PROXY_PROXY_EXR_H
#define DFL_PROXY_PROXY_EXR_H

#include "proxy/proxy.h"

/* Errors: DFL_E_INPUT (empty grid or path), DFL_E_IO naming path (cannot
 * write or rename; nothing is left behind), DFL_E_NOMEM. */
dfl_status dfl_proxy_exr_save(const dfl_proxy_grid *g, const char *path, dfl_err *err);

/* *out receives a new grid (free with dfl_proxy_grid_free).  Errors:
 * DFL_E_IO naming path (missing, unreadable or not a dflab proxy grid:
 * missing attribute or channel, wrong size or pixel type), DFL_E_NOMEM;
 * *out is then zeroed. */
dfl_status dfl_proxy_exr_load(const char *path, dfl_proxy_grid *out, dfl_err *err);

#endif
