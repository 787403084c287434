/* `dflab probe`: evaluate the field of a config's [field] section at points
 * read from a CSV file.
 *
 * Input CSV: a header naming columns x,y[,z] and, with jet order K > 0,
 * dx,dy[,dz] (any order, no other columns); one point per row; blank lines
 * ignored.  Output CSV (to out, only after every point succeeded):
 * x,y,z,value,gx,gy,gz[,d1..dK] with z = gz = 0 for 2D fields, %.17g;
 * dk = d^k/ds^k u(x + s*dir) at s = 0+, exact (jets).
 *
 * Checks (exit status 2, naming the file and point): the file's text and
 * format (io/points.h); every coordinate inside dflab's domain |x| <= 1e150
 * (core/domain.h); with --jet a direction with |d_j| <= 1e150 that is not
 * zero.  A value, gradient or derivative that is not finite at a point
 * inside the domain is DFL_E_NUMERIC (exit 1) naming the point and the
 * column: nothing is printed then, so stdout never holds inf or nan.
 */
#ifndef DFL_EXPERIMENTS_PROBE_H
#define DFL_EXPERIMENTS_PROBE_H

#include <stdio.h>

#include "core/status.h"

typedef struct dfl_probe_opts {
    const char *config;
    const char *points;
    int jet;                    /* 0: no derivatives */
    const char *const *sets;
    int nsets;
} dfl_probe_opts;

dfl_status dfl_probe(const dfl_probe_opts *o, FILE *out, dfl_err *err);

#endif
