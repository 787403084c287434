/* `dflab probe`: evaluate the field of a config's [field] section (or the
 * section --field names) at points read from a CSV file.
 *
 *   dfl_probe                  the command
 *   dfl_probe_sections_check   the runner's check of the probe's sections
 *
 * The probe's sections.  [field] is read by the studies that draw one
 * field; a config may add [field] (when its study does not read it) and
 * named [field_NAME] sections (no study reads those) for `dflab probe
 * --field SECTION`: what a figure shows, for studies that build their
 * geometry from a sweep or draw several fields.  The runner defers these
 * sections in dfl_cfg_check_used (io/config.h) and, after the study ran,
 * builds each one that still has unread keys (dfl_probe_sections_check),
 * so their keys are checked like any other and a study never sees them.
 *
 * Input CSV: a header naming columns x,y[,z] and, with jet order K > 0,
 * dx,dy[,dz] (any order, no other columns); one point per row; blank lines
 * ignored.  Output CSV (to out, only after every point succeeded):
 * x,y,z,value,gx,gy,gz[,d1..dK] with z = gz = 0 for 2D fields, every number in the
 * shortest form that reads back exactly (io/table.h, as the CSVs);
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
#include "io/config.h"

typedef struct dfl_probe_opts {
    const char *config;
    const char *points;
    const char *field;          /* the section to build; NULL: "field" */
    int jet;                    /* 0: no derivatives */
    const char *const *sets;
    int nsets;
} dfl_probe_opts;

/* DFL_E_INPUT naming the section when --field names a section the config
 * does not have. */
dfl_status dfl_probe(const dfl_probe_opts *o, FILE *out, dfl_err *err);

/* Marks [field] and [field_*] deferred in c (dfl_cfg_defer_sections); call
 * before the study runs. */
void dfl_probe_sections_defer(dfl_cfg *c);
/* Builds (and drops) the field of every deferred [field] / [field_*]
 * section that still has unread keys after the study ran: its factory's
 * errors, or "unknown key" for a key the factory did not read. */
dfl_status dfl_probe_sections_check(const dfl_cfg *c, dfl_err *err);

#endif
