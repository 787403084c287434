/* Config values that are lists of a fixed shape, shared by studies:
 *
 *   dfl_section_names_from_cfg   key = A B C        blank-separated section names
 *   dfl_points_n_from_cfg        key = x y; x y     exactly n points
 *
 * Both read through io/config.h (so the key is marked used) and fail with
 * DFL_E_INPUT naming file:line, [section] and key.
 */
#ifndef DFL_EXPERIMENTS_LIST_CFG_H
#define DFL_EXPERIMENTS_LIST_CFG_H

#include "core/status.h"
#include "io/config.h"

/* Room for one section name, terminator included. */
#define DFL_SECTION_NAME_LEN 64

/* [sec] key as blank-separated (spaces, tabs) section names into
 * names[0..*n-1], in order.  DFL_E_INPUT "expected at most <max> section
 * names of < DFL_SECTION_NAME_LEN characters" for more than max names or
 * a longer one, "expected at least one <what>" for none.  Whether the
 * sections exist is the caller's check.  *n and names may be partly
 * written on failure. */
dfl_status dfl_section_names_from_cfg(const dfl_cfg *cfg, const char *sec, const char *key,
                                      int max, char (*names)[DFL_SECTION_NAME_LEN], int *n,
                                      const char *what, dfl_err *err);

/* [sec] key as exactly n points of dimension dim into out (n * dim
 * doubles).  DFL_E_INPUT from the point reader, or "expected <what>, got
 * <count>" for another number of points; out is untouched then. */
dfl_status dfl_points_n_from_cfg(const dfl_cfg *cfg, const char *sec, const char *key, int dim,
                                 size_t n, double *out, const char *what, dfl_err *err);

#endif
