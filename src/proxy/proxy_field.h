/* A proxy grid as a dfl_field (field/field.h): batched value + gradient
 * through a decoding filter (proxy/filter.h), for probes, samplers,
 * metrics and sphere tracing.
 *
 * Function index
 *   dfl_proxy_field_new    grid + filter options -> dfl_field (takes the grid)
 *   dfl_proxy_field_grid   the grid inside a proxy field (NULL for others)
 *   dfl_proxy_field_opts   its filter options (NULL for others)
 *
 * The field has dim 3 and no jets (dfl_field_jet gives DFL_E_INPUT).
 */
#ifndef DFL_PROXY_PROXY_FIELD_H
#define DFL_PROXY_PROXY_FIELD_H

#include "field/field.h"
#include "proxy/filter.h"
#include "proxy/proxy.h"

/* Moves *grid into a new field (on success *grid is zeroed and owned by
 * the field; on failure both are untouched).  DFL_E_INPUT when the options
 * fail dfl_proxy_filter_check or the grid is empty; DFL_E_NOMEM. */
dfl_status dfl_proxy_field_new(dfl_proxy_grid *grid, const dfl_proxy_filter_opts *o,
                               dfl_field *out, dfl_err *err);

const dfl_proxy_grid *dfl_proxy_field_grid(const dfl_field *f);
const dfl_proxy_filter_opts *dfl_proxy_field_opts(const dfl_field *f);

#endif
