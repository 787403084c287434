/* An in-memory result table written as long-format CSV.
 *
 * Columns appear in the order they are first set.  A study begins a row,
 * sets named cells, and the runner writes the table once the whole study
 * has succeeded.  Prefix cells (the swept keys of the current sweep point)
 * are copied into every new row, so each row is traceable to its config.
 * Doubles print with %.17g; absent cells print empty.
 */
#ifndef DFL_IO_TABLE_H
#define DFL_IO_TABLE_H

#include <stddef.h>

#include "core/status.h"

typedef struct dfl_table dfl_table;

dfl_table *dfl_table_new(void);
void dfl_table_free(dfl_table *t);

/* Replaces the prefix cells copied into each new row. */
dfl_status dfl_table_prefix_clear(dfl_table *t);
dfl_status dfl_table_prefix_string(dfl_table *t, const char *col, const char *value);

/* Starts a new row (with the prefix cells). */
dfl_status dfl_table_row(dfl_table *t);
/* Sets a cell of the current row; creates the column on first use. */
dfl_status dfl_table_set_double(dfl_table *t, const char *col, double v);
dfl_status dfl_table_set_int(dfl_table *t, const char *col, long v);
dfl_status dfl_table_set_string(dfl_table *t, const char *col, const char *v);

size_t dfl_table_rows(const dfl_table *t);
size_t dfl_table_cols(const dfl_table *t);
const char *dfl_table_col_name(const dfl_table *t, size_t j);
/* Cell text of row i, column col ("" when absent, NULL for unknown col). */
const char *dfl_table_get(const dfl_table *t, size_t i, const char *col);

/* Writes the CSV through a temporary file renamed on success. */
dfl_status dfl_table_write_csv(const dfl_table *t, const char *path, dfl_err *err);

#endif
