/* Run manifests: what produced a results directory.
 *
 * manifest.json records the dflab version, the git revision it was built
 * from (when known), the UTC date, the command line, the wall time of each
 * step and every file in the directory with its size in bytes.
 */
#ifndef DFL_IO_MANIFEST_H
#define DFL_IO_MANIFEST_H

#include <stddef.h>

#include "core/status.h"

#define DFL_VERSION "0.1.0"

typedef struct dfl_manifest dfl_manifest;

dfl_manifest *dfl_manifest_new(const char *config_path, const char *study);
void dfl_manifest_free(dfl_manifest *m);
/* Records a finished step and its wall time in seconds. */
dfl_status dfl_manifest_step(dfl_manifest *m, const char *name, double seconds);
/* Records an extra key (e.g. the command line). */
dfl_status dfl_manifest_note(dfl_manifest *m, const char *key, const char *value);
/* Writes <dir>/manifest.json listing every regular file in dir (including
 * the manifest itself, whose size is that of the final file). */
dfl_status dfl_manifest_write(const dfl_manifest *m, const char *dir, dfl_err *err);

/* Monotonic wall clock in seconds. */
double dfl_wall_seconds(void);

#endif
