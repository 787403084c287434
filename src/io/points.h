/* Points files: the CSV that `dflab probe` reads.
 *
 * Function index
 *   dfl_points_read(fp, name, dim, want_dir, &p, err)   parse a whole file
 *   dfl_points_free(&p)                                  release it
 *
 * Format: a header naming the columns x,y[,z] and, when want_dir is set,
 * dx,dy[,dz] (any order, each once, no other column); then one point per
 * row, each cell a finite number (C strtod syntax, blanks around a cell
 * allowed); blank lines are skipped.  The text rules are io/lines.h's (a
 * line holds at most DFL_POINTS_LINE_MAX bytes, the last one needs no
 * newline, a BOM is skipped, NUL bytes, control characters and invalid
 * UTF-8 are refused naming line and column), as for INI files.  At most
 * DFL_POINTS_MAX rows.
 *
 * Result: p->v holds p->n rows of 6 doubles (x y z dx dy dz; absent
 * columns 0), malloc'ed, freed by dfl_points_free; p->n >= 1 on success.
 * Failure: DFL_E_INPUT "name:line: ..." naming the column (DFL_E_NOMEM,
 * DFL_E_IO for a read error); p is then empty.
 */
#ifndef DFL_IO_POINTS_H
#define DFL_IO_POINTS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "core/status.h"

#define DFL_POINTS_LINE_MAX 4095
#define DFL_POINTS_MAX (1L << 22)

typedef struct dfl_points {
    double *v; /* rows of 6: x y z dx dy dz */
    size_t n, cap;
} dfl_points;

dfl_status dfl_points_read(FILE *fp, const char *name, int dim, bool want_dir, dfl_points *p,
                           dfl_err *err);
void dfl_points_free(dfl_points *p);

#endif
