/* Error messages are kept in a fixed buffer so that reporting a failure can
 * never fail itself (no allocation on the error path). */
#include "core/status.h"

#include <stdio.h>
#include <string.h>

void dfl_err_clear(dfl_err *err)
{
    if (!err) return;
    err->code = DFL_OK;
    err->msg[0] = '\0';
}

dfl_status dfl_err_set(dfl_err *err, dfl_status code, const char *fmt, ...)
{
    if (!err) return code;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err->msg, sizeof err->msg, fmt, ap);
    va_end(ap);
    err->code = code;
    return code;
}

dfl_status dfl_err_prefix(dfl_err *err, const char *fmt, ...)
{
    if (!err) return DFL_OK;
    char head[DFL_ERR_MSG_MAX];
    char tail[DFL_ERR_MSG_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(head, sizeof head, fmt, ap);
    va_end(ap);
    memcpy(tail, err->msg, sizeof tail);
    /* Truncation is acceptable (the head is kept whole); concatenate by
     * hand so the compiler need not prove the sizes fit. */
    size_t k = 0, cap = sizeof err->msg - 1;
    for (const char *s = head; *s && k < cap; s++) err->msg[k++] = *s;
    for (const char *s = ": "; *s && k < cap; s++) err->msg[k++] = *s;
    for (const char *s = tail; *s && k < cap; s++) err->msg[k++] = *s;
    err->msg[k] = '\0';
    return err->code;
}

const char *dfl_status_name(dfl_status code)
{
    switch (code) {
    case DFL_OK: return "ok";
    case DFL_E_INPUT: return "input";
    case DFL_E_IO: return "io";
    case DFL_E_NUMERIC: return "numeric";
    case DFL_E_NOMEM: return "nomem";
    case DFL_E_INTERNAL: return "internal";
    }
    return "unknown";
}
