/* Table columns for the error metrics of field/metrics.h, the same in
 * every study that reports them:
 *   count<sfx>, l1<sfx>, mse<sfx>, rms<sfx>, linf<sfx>,
 *   graddefect_mean<sfx>, graddefect_max<sfx>
 * in that order, in the current row.
 */
#ifndef DFL_EXPERIMENTS_METRICS_COLS_H
#define DFL_EXPERIMENTS_METRICS_COLS_H

#include "core/status.h"
#include "field/metrics.h"
#include "io/table.h"

/* Sets the columns above (sfx may be ""; column names are truncated at 95
 * characters).  Stops at the first failing setter and returns its status
 * (the table's own, without a message). */
dfl_status dfl_metrics_put(dfl_table *t, const char *sfx, const dfl_metrics *m);

#endif
