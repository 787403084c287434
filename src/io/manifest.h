/* Run manifests: what produced a results directory, as one JSON object.
 *
 * Function index
 *   dfl_manifest_new, _free            lifetime
 *   dfl_manifest_put_string/_int/_double/_strings/_raw   fields, in order
 *   dfl_manifest_write                 the object plus "files" (name, bytes, sha256)
 *   dfl_manifest_put_format            the results folder's magic and format version
 *   dfl_manifest_results_files         the "files" names of a results manifest
 *   dfl_manifest_libraries             JSON object of the linked libraries' versions
 *   dfl_json_quote                     a C string as a JSON string literal
 *   dfl_wall_seconds                   monotonic clock
 *
 * A manifest holds each key once (json.load keeps the last of duplicates,
 * so a repeated key would lose data): putting a key again replaces it.
 * Fields keep the order they were first put.  Every setter returns DFL_OK
 * or DFL_E_NOMEM.
 */
#ifndef DFL_IO_MANIFEST_H
#define DFL_IO_MANIFEST_H

#include <stddef.h>

#include "core/status.h"

#define DFL_VERSION "0.1.0"

typedef struct dfl_manifest dfl_manifest;

/* NULL when out of memory. */
dfl_manifest *dfl_manifest_new(void);
void dfl_manifest_free(dfl_manifest *m);
dfl_status dfl_manifest_put_string(dfl_manifest *m, const char *key, const char *value);
dfl_status dfl_manifest_put_int(dfl_manifest *m, const char *key, long value);
/* Printed as %.6f (wall times). */
dfl_status dfl_manifest_put_double(dfl_manifest *m, const char *key, double value);
/* A JSON array of n strings. */
dfl_status dfl_manifest_put_strings(dfl_manifest *m, const char *key, size_t n,
                                    const char *const *values);
/* json must already be valid JSON text (an object, array, number...). */
dfl_status dfl_manifest_put_raw(dfl_manifest *m, const char *key, const char *json);

/* Writes the fields and then "files": every regular file of files_dir
 * (sorted by name; manifest.json and temporary *.tmp.* files left out) with
 * its size in bytes and sha256, to path through a temporary file renamed on
 * success.  DFL_E_IO naming the file on failure. */
dfl_status dfl_manifest_write(const dfl_manifest *m, const char *path, const char *files_dir,
                              dfl_err *err);

/* A results folder's manifest.json opens with
 *   "format": "dflab-results", "format_version": 1
 * so that dflab can tell its own folders (which a run replaces whole) from
 * a folder that merely holds some file called manifest.json. */
#define DFL_RESULTS_FORMAT "dflab-results"
#define DFL_RESULTS_FORMAT_VERSION 1

/* Puts "format" and "format_version" (call before any other field, so
 * they come first).  DFL_OK or DFL_E_NOMEM. */
dfl_status dfl_manifest_put_format(dfl_manifest *m);

/* What json (a whole manifest.json, NUL-terminated) is, and the names of
 * its "files" array into *names (*n of them; malloc'ed, the caller frees
 * each and the array; NULL with *n = 0 when there are none):
 *    1  a results manifest of this format version (magic as above);
 *    0  one of dflab before the magic: no "format" field, "tool": "dflab";
 *   -1  not one strict JSON object (io/json.h: truncated, trailing bytes,
 *       duplicate keys), not dflab's, a newer or unknown format_version, or
 *       no "files" array of objects each with a string "name" (*names NULL
 *       then);
 *   -2  out of memory.
 * Any valid JSON spelling of those members is read (key order, white space
 * and escapes are free); never reads past the terminating NUL. */
int dfl_manifest_results_files(const char *json, char ***names, size_t *n);

/* {"dflab": ..., "inih": ..., "ceres": ..., "openexr": ..., "zlib": ...} into
 * buf: compile-time versions for inih and Ceres, the loaded library's own
 * for OpenEXR and zlib.  Returns buf. */
const char *dfl_manifest_libraries(char *buf, size_t size);

/* s as a quoted JSON string (escapes ", \ and control characters), malloc'ed
 * (caller frees); NULL when out of memory. */
char *dfl_json_quote(const char *s);
/* Monotonic wall clock in seconds. */
double dfl_wall_seconds(void);

#endif
