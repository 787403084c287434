#include "cfg/cfg_err.h"

#include <stdarg.h>
#include <stdio.h>

dfl_status dfl_cfg_reject(const dfl_cfg *cfg, const char *sec, const char *key, dfl_err *err,
                          const char *fmt, ...)
{
    char w[1024], msg[DFL_ERR_MSG_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return dfl_err_set(err, DFL_E_INPUT, "%s: %s", dfl_cfg_where(cfg, sec, key, w, sizeof w), msg);
}
