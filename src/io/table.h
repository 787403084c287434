/* An in-memory result table written as long-format CSV.
 *
 * Columns appear in the order they are first set.  A study begins a row,
 * sets named cells, and the runner writes the table once the whole study
 * has succeeded.  Prefix cells (the swept keys of the current sweep point)
 * are copied into every new row, so each row is traceable to its config.
 * Doubles print in the shortest form that reads back to the same double
 * (0.1, not 0.10000000000000001); absent cells print empty.
 */
#ifndef DFL_IO_TABLE_H
#define DFL_IO_TABLE_H

#include <stddef.h>

#include "core/status.h"

typedef struct dfl_table dfl_table;

/* Function index
 *   dfl_table_new, dfl_table_free          lifetime
 *   dfl_table_prefix_clear, _prefix_string  cells copied into each new row
 *   dfl_table_row                           starts a row
 *   dfl_table_set_double, _int, _string     cells of the current row
 *   dfl_table_add_col                       a column ahead of any cell
 *   dfl_table_rows, _cols, _col_name, _get  reading back
 *   dfl_table_write_csv                     the CSV file
 *   dfl_table_format_double                 the text a double cell gets
 *   dfl_table_csv_prepend                   leading columns for a CSV file
 *   dfl_table_append_csv                    a CSV file read back into rows
 *
 * Failure behaviour of the setters (prefix_string, row, set_*): they return
 * DFL_OK, or DFL_E_NOMEM ("table: out of memory ...") or DFL_E_INTERNAL
 * (a cell set before the first row) with a message naming the column in err
 * (err may be NULL).  After a failure the table is still valid and freeable:
 * the failed cell is absent, the cells already set are kept. */

/* A new empty table, or NULL when out of memory.  Free with dfl_table_free. */
dfl_table *dfl_table_new(void);
/* Frees t and every cell; t may be NULL. */
void dfl_table_free(dfl_table *t);

/* Drops the prefix cells (rows already started keep theirs).  Cannot fail. */
void dfl_table_prefix_clear(dfl_table *t);
/* Adds a prefix cell col = value (both copied). */
dfl_status dfl_table_prefix_string(dfl_table *t, const char *col, const char *value,
                                   dfl_err *err);

/* Starts a new row (with the prefix cells). */
dfl_status dfl_table_row(dfl_table *t, dfl_err *err);
/* Sets a cell of the current row (replacing an earlier value of the same
 * column); creates the column on first use.  Doubles print as
 * dfl_table_format_double gives them,
 * integers with %ld, strings as given (quoted in the CSV when needed). */
dfl_status dfl_table_set_double(dfl_table *t, const char *col, double v, dfl_err *err);
dfl_status dfl_table_set_int(dfl_table *t, const char *col, long v, dfl_err *err);
dfl_status dfl_table_set_string(dfl_table *t, const char *col, const char *v, dfl_err *err);

/* Creates column col (at the end) unless it exists; no row needed (for
 * rebuilding a table from its CSV with the same column order). */
dfl_status dfl_table_add_col(dfl_table *t, const char *col, dfl_err *err);

size_t dfl_table_rows(const dfl_table *t);
size_t dfl_table_cols(const dfl_table *t);
const char *dfl_table_col_name(const dfl_table *t, size_t j);
/* Cell text of row i, column col ("" when absent, NULL for unknown col). */
const char *dfl_table_get(const dfl_table *t, size_t i, const char *col);

/* The shortest %.Ng text (N in 1..17) that strtod reads back to exactly v
 * (on equal length the fewer digits: 10 rather than 1e+01, 1e+300);
 * NaN, infinities and zeros print as %.17g does ("nan", "inf", "0", "-0").
 * buf needs 32 bytes; returns buf. */
const char *dfl_table_format_double(double v, char *buf, size_t size);

/* Writes the CSV through a temporary file renamed on success. */
dfl_status dfl_table_write_csv(const dfl_table *t, const char *path, dfl_err *err);

/* Rewrites the CSV file at path (through a temporary file) with n leading
 * columns: cols[k] in the header, values[k] in every other record, each
 * quoted when needed; a column the header already has is left out (so a
 * second call changes nothing), an empty file stays empty.  Records are
 * split at newlines outside quotes.  DFL_E_IO naming path on failure. */
dfl_status dfl_table_csv_prepend(const char *path, size_t n, const char *const *cols,
                                 const char *const *values, dfl_err *err);

/* Appends the CSV file at path (as dfl_table_write_csv writes it: a header
 * record, RFC 4180 quotes, "\n" records) to t: its header's columns are
 * added (dfl_table_add_col), then one row per record with its non-empty
 * cells; cells beyond the header are ignored.  DFL_E_IO "PATH: cannot
 * read" when the file is not a readable regular file, DFL_E_NOMEM; rows
 * appended before a failure stay. */
dfl_status dfl_table_append_csv(dfl_table *t, const char *path, dfl_err *err);

#endif
