/* The one way config glue rejects a value that parsed but cannot be used
 * (out of range for this study, degenerate geometry, a section that does
 * not exist): a DFL_E_INPUT message that starts where the key was written.
 *
 *   dfl_cfg_reject(cfg, sec, key, err, fmt, ...)   "<where>: <fmt ...>"
 *
 * For a library error about such a value, prefix it with io/config.h's
 * dfl_cfg_err_at instead.  A key the getters could not parse is already
 * reported by them (io/config.h). */
#ifndef DFL_EXPERIMENTS_CFG_ERR_H
#define DFL_EXPERIMENTS_CFG_ERR_H

#include "core/status.h"
#include "io/config.h"

/* Sets err (may be NULL) to DFL_E_INPUT with "<where>: <message>", where
 * is dfl_cfg_where(cfg, sec, key) ("file:line: [sec] key", or the include
 * or --set that gave it) and the message is fmt formatted as printf does;
 * the whole is truncated to DFL_ERR_MSG_MAX - 1 characters.  Returns
 * DFL_E_INPUT, so that callers write `return dfl_cfg_reject(...)`. */
dfl_status dfl_cfg_reject(const dfl_cfg *cfg, const char *sec, const char *key, dfl_err *err,
                          const char *fmt, ...) __attribute__((format(printf, 5, 6)));

#endif
