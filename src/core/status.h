/* dflab status codes and error messages.
 *
 * Every fallible dflab call returns a dfl_status and, on failure, fills a
 * dfl_err with a one-line, human-readable message.  The message already names
 * the file, line and key when the failure comes from user input, so the CLI
 * prints it unchanged.  A NULL dfl_err pointer is allowed: the message is then
 * dropped (the status is still returned).
 */
#ifndef DFL_CORE_STATUS_H
#define DFL_CORE_STATUS_H

#include <stdarg.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum dfl_status {
    DFL_OK = 0,
    DFL_E_INPUT = 1,   /* bad user input: config, points file, geometry (CLI exit 2) */
    DFL_E_IO = 2,      /* cannot read or write a file */
    DFL_E_NUMERIC = 3, /* a numerical method failed (no convergence, singular system) */
    DFL_E_NOMEM = 4,   /* allocation failed */
    DFL_E_INTERNAL = 5 /* a broken invariant that is not the user's fault */
} dfl_status;

#define DFL_ERR_MSG_MAX 1024

typedef struct dfl_err {
    dfl_status code;
    char msg[DFL_ERR_MSG_MAX];
} dfl_err;

/* Resets err to DFL_OK with an empty message.  err may be NULL. */
void dfl_err_clear(dfl_err *err);

/* Records code and a printf-style message in err (if err is not NULL) and
 * returns code, so that callers can write `return dfl_err_set(err, ...)`. */
dfl_status dfl_err_set(dfl_err *err, dfl_status code, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* Prefixes the message already in err with a printf-style context string
 * followed by ": ".  Returns err->code (DFL_OK if err is NULL). */
dfl_status dfl_err_prefix(dfl_err *err, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));

/* Short name of a status code ("ok", "input", ...).  Never NULL. */
const char *dfl_status_name(dfl_status code);

#ifdef __cplusplus
}
#endif

#endif
