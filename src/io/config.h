/* INI configuration with includes, sweeps and typed, checked getters.
 *
 * Function index (one concern per file, src/io/config_*.c):
 *   loading        config_parse.c    dfl_cfg_load, dfl_cfg_parse_string
 *   includes       config_include.c  (the `include` key, see below)
 *   storage        config_store.c    dfl_cfg_free, dfl_cfg_path, dfl_cfg_has,
 *                                    dfl_cfg_has_section, dfl_cfg_section_name,
 *                                    dfl_cfg_write
 *   overrides      config_set.c      dfl_cfg_set
 *   sweeps         config_sweep.c    dfl_cfg_sweep_axes, dfl_cfg_sweep_points,
 *                                    dfl_cfg_sweep_axis_name, dfl_cfg_sweep_point,
 *                                    dfl_cfg_axis_value, dfl_cfg_sweep_hash
 *   typed getters  config_get.c      dfl_cfg_string/int/double/bool/enum/vec[_opt],
 *                                    dfl_cfg_points, dfl_cfg_doubles, dfl_cfg_point_dim
 *   locations      config_where.c    dfl_cfg_where, dfl_cfg_err_at, dfl_cfg_reject,
 *                                    dfl_cfg_check_used, dfl_cfg_check_used_in,
 *                                    dfl_cfg_used,
 *                                    dfl_cfg_claim_section, dfl_cfg_claim_read,
 *                                    dfl_cfg_defer_sections, dfl_cfg_unused_deferred
 *   read record    config_log.c      dfl_cfg_reads, dfl_cfg_read_at,
 *                                    dfl_cfg_validate_only, dfl_cfg_validated,
 *                                    dfl_cfg_validating
 *
 * A configuration file is parsed by libinih into (section, key, value, line)
 * entries; `--set section.key=value` overrides are applied on top.  A value
 * containing a comma is a sweep axis: dfl_cfg_sweep_* enumerates the
 * cartesian product of all axes, in file order, last axis fastest, and gives
 * one single-valued dfl_cfg per sweep point.
 *
 * Includes.  `include = FILE` in a section [S] makes the keys of FILE's
 * [shape] section keys of [S], e.g.
 *
 *     [S]
 *     include = ../../shapes/S.ini     # configs/paper/bs04/x.ini -> configs/shapes/S.ini
 *     order = 3                        # overrides the included order
 *
 *   - FILE is resolved against the directory of the including file (an
 *     absolute FILE is taken as is), so a config reads the same from any
 *     working directory; for dfl_cfg_parse_string the "file" is its name.
 *   - Keys written in [S] itself win over included ones, before or after the
 *     include line; `--set S.key=value` overrides included keys like any key.
 *   - The included keys stand where the include line stood; dfl_cfg_write
 *     writes them as plain keys of [S] (no include line), so a resolved
 *     config.ini reruns on its own.  A getter's message about an included key
 *     names the shape file's line and the include:
 *     "S.ini:8: [shape] order (included as [S] at x.ini:40): expected ...".
 *   - One level only: FILE must hold a non-empty [shape] section and nothing
 *     else, and may not include another file (so no loops).  One include per
 *     section; FILE is one name on one line (no sweep, no continuation);
 *     `--set S.include=...` is refused.  Each of these, a missing or
 *     unreadable FILE and FILE's own syntax errors are DFL_E_INPUT messages
 *     naming the including file and line, and FILE's line where it has one.
 *
 * Text rules (io/lines.h, the same for the points CSV): lines of at most
 * 65534 bytes (refused after reading one byte more, so /dev/zero or an
 * endless line ends at once), at most 100000 lines and 16 MiB per file; a
 * UTF-8 BOM at the start is skipped; NUL bytes, control characters (but
 * TAB and a CR before the line end) and invalid UTF-8 are refused naming
 * the line and column.  Section and key names longer than 49 characters
 * are refused (libinih would cut them).
 *
 * Duplicates: a key written twice in a section and a section header
 * written twice in a file are both DFL_E_INPUT naming the first line --
 * sections are never merged, so what a reader sees in one [grid] block is
 * all of [grid].  (Included keys and --set are the two documented ways to
 * add keys to a section from elsewhere.)
 *
 * Sizes: a sweep may have at most 10^8 points (the product of the list
 * lengths, checked when the axes are found, so no count overflows).
 *
 * Getters validate type and range and mark the key as used; after a study
 * has read everything it needs, dfl_cfg_check_used() rejects keys nobody
 * read ("unknown key"), so a typo never goes unnoticed.  Every message
 * names file:line, [section] key, what was expected and what was found.
 *
 * Syntax of typed values:
 *   int, double      decimal / C strtod syntax, finite only
 *   bool             true/false, yes/no, on/off, 1/0
 *   enum             one of a fixed list of names
 *   vector           "x y" or "x y z" (blank-separated doubles; vectors,
 *                    point lists and double lists are coordinates, so each
 *                    number must satisfy |v| <= 1e150, core/domain.h)
 *   point list       "x0 y0; x1 y1; ..." (';'-separated vectors of one dim)
 *   double list      "a b c" (blank-separated), for knots and the like
 *
 * Lifetimes: a dfl_cfg owns its strings; pointers returned by getters stay
 * valid until dfl_cfg_free.  Arrays returned by the list getters are
 * malloc'ed and owned by the caller.
 */
#ifndef DFL_IO_CONFIG_H
#define DFL_IO_CONFIG_H

#include <stdbool.h>
#include <stddef.h>

#include "core/status.h"

typedef struct dfl_cfg dfl_cfg;

/* Parses path and its includes.  DFL_E_INPUT with "path:line: ..." on
 * failure (DFL_E_NOMEM when out of memory); *out is NULL then. */
dfl_status dfl_cfg_load(const char *path, dfl_cfg **out, dfl_err *err);
/* Parses INI text held in memory; name is used in messages and as the
 * "file" that relative includes are resolved against. */
dfl_status dfl_cfg_parse_string(const char *name, const char *text, dfl_cfg **out, dfl_err *err);
/* Applies "section.key=value".  The key need not exist in the file; an
 * included key is overridden like any other.  A key `kind` whose new value
 * shares no comma item with its old one switches kind: every other key of
 * the section not itself given by --set is dropped (it was the old kind's;
 * set the new kind's keys after the switch).
 * "section=@FILE" replaces every key of [section] (any origin) by the keys
 * of FILE's [section] (FILE loaded as dfl_cfg_load does, includes read,
 * relative to the working directory; its other sections are not taken),
 * in place of the first key removed (or at the end), with FILE's origins.
 * Dropped values are remembered as values the config named, so sections
 * they named are unselected for dfl_cfg_check_used, not unknown.
 * DFL_E_INPUT for a malformed assignment, an empty value, the key
 * `include`, a FILE that cannot be loaded or has no [section]; c is then
 * unchanged. */
dfl_status dfl_cfg_set(dfl_cfg *c, const char *assignment, dfl_err *err);
void dfl_cfg_free(dfl_cfg *c);

/* Name of the file the configuration came from (as given). */
const char *dfl_cfg_path(const dfl_cfg *c);

/* ---- sweeps ---------------------------------------------------------- */
/* Number of sweep axes and of sweep points (product of axis lengths; 1 when
 * there is no axis). */
size_t dfl_cfg_sweep_axes(const dfl_cfg *c);
size_t dfl_cfg_sweep_points(const dfl_cfg *c);
/* "section.key" of axis a (static for the life of c). */
const char *dfl_cfg_sweep_axis_name(const dfl_cfg *c, size_t a);
/* Single-valued configuration of sweep point i (0 <= i < points).  The
 * caller frees it.  Used-key marks are shared with nothing. */
dfl_status dfl_cfg_sweep_point(const dfl_cfg *c, size_t i, dfl_cfg **out, dfl_err *err);
/* Value of axis a in a point configuration made by dfl_cfg_sweep_point. */
const char *dfl_cfg_axis_value(const dfl_cfg *point, size_t a);
/* SHA-256 (hex) of every (section, key, value) in entry order: equal for
 * the same keys and values, wherever they were written.  For a point
 * configuration it covers the point's single values. */
void dfl_cfg_sweep_hash(const dfl_cfg *c, char hex[65]);

/* ---- getters (all mark the key used) ---------------------------------- */
bool dfl_cfg_has(const dfl_cfg *c, const char *sec, const char *key);
bool dfl_cfg_has_section(const dfl_cfg *c, const char *sec);
/* The configuration's own copy of section name sec (valid while c lives:
 * for what must outlive a caller's buffer, e.g. a dfl_cost's key), or
 * NULL when c has no such section (or sec is NULL). */
const char *dfl_cfg_section_name(const dfl_cfg *c, const char *sec);

/* Raw string; required. */
dfl_status dfl_cfg_string(const dfl_cfg *c, const char *sec, const char *key, const char **out,
                          dfl_err *err);
/* Raw string with default when absent. */
dfl_status dfl_cfg_string_opt(const dfl_cfg *c, const char *sec, const char *key, const char *def,
                              const char **out, dfl_err *err);

/* A file name; required.  A relative name is resolved like an include
 * (io/path.h's dfl_path_beside, lexically): against the directory of the
 * file the key was written in (the config itself or the included shape
 * file that brought it), a --set value against the working directory.
 * The resolved name goes to buf (size bytes); DFL_E_INPUT naming the key
 * for an empty or too long value.  The file itself is not opened.  Only the
 * keys of DFL_CFG_PATH_KEYS are file names (asserted): dfl_cfg_write writes
 * their values resolved, so a run's config.ini names the same file from
 * its own folder. */
#define DFL_CFG_PATH_KEYS {"file"}
dfl_status dfl_cfg_path_value(const dfl_cfg *c, const char *sec, const char *key, char *buf,
                              size_t size, dfl_err *err);

/* Integer in [lo, hi]; the _opt form returns def when the key is absent. */
dfl_status dfl_cfg_int(const dfl_cfg *c, const char *sec, const char *key, long lo, long hi,
                       long *out, dfl_err *err);
dfl_status dfl_cfg_int_opt(const dfl_cfg *c, const char *sec, const char *key, long def, long lo,
                           long hi, long *out, dfl_err *err);
/* Finite double in [lo, hi]. */
dfl_status dfl_cfg_double(const dfl_cfg *c, const char *sec, const char *key, double lo, double hi,
                          double *out, dfl_err *err);
dfl_status dfl_cfg_double_opt(const dfl_cfg *c, const char *sec, const char *key, double def,
                              double lo, double hi, double *out, dfl_err *err);
dfl_status dfl_cfg_bool(const dfl_cfg *c, const char *sec, const char *key, bool *out,
                        dfl_err *err);
dfl_status dfl_cfg_bool_opt(const dfl_cfg *c, const char *sec, const char *key, bool def,
                            bool *out, dfl_err *err);
/* One of names[0..count-1]; *out receives the index. */
dfl_status dfl_cfg_enum(const dfl_cfg *c, const char *sec, const char *key,
                        const char *const *names, int count, int *out, dfl_err *err);
dfl_status dfl_cfg_enum_opt(const dfl_cfg *c, const char *sec, const char *key,
                            const char *const *names, int count, int def, int *out, dfl_err *err);
/* Exactly dim blank-separated finite doubles. */
dfl_status dfl_cfg_vec(const dfl_cfg *c, const char *sec, const char *key, int dim, double *out,
                       dfl_err *err);
dfl_status dfl_cfg_vec_opt(const dfl_cfg *c, const char *sec, const char *key, int dim,
                           const double *def, double *out, dfl_err *err);
/* Point list of dimension dim, at least min_count points; *out is
 * malloc'ed (count*dim doubles) and owned by the caller. */
dfl_status dfl_cfg_points(const dfl_cfg *c, const char *sec, const char *key, int dim,
                          size_t min_count, double **out, size_t *count, dfl_err *err);
/* Blank-separated finite doubles, at least min_count; *out malloc'ed. */
dfl_status dfl_cfg_doubles(const dfl_cfg *c, const char *sec, const char *key, size_t min_count,
                           double **out, size_t *count, dfl_err *err);

/* Formats "file:line: [sec] key" of an existing key into buf (for messages
 * about a value that parsed but is unusable, e.g. degenerate geometry). */
const char *dfl_cfg_where(const dfl_cfg *c, const char *sec, const char *key, char *buf,
                          size_t size);

/* Prefixes the message in err with "file:line: [sec] key" (for a library
 * error about a value that parsed, e.g. degenerate geometry) and returns
 * st, so that callers can write `return dfl_cfg_err_at(...)`. */
dfl_status dfl_cfg_err_at(const dfl_cfg *c, const char *sec, const char *key, dfl_status st,
                          dfl_err *err);

/* The one way to reject a value that parsed but cannot be used (out of
 * range for this study, degenerate geometry, a section that does not
 * exist): sets err (may be NULL) to DFL_E_INPUT with "<where>: <message>",
 * where is dfl_cfg_where(c, sec, key) ("file:line: [sec] key", or the
 * include or --set that gave it) and the message is fmt formatted as
 * printf does; the whole is truncated to DFL_ERR_MSG_MAX - 1 characters.
 * Returns DFL_E_INPUT, so that callers write `return dfl_cfg_reject(...)`.
 * For a library error about such a value use dfl_cfg_err_at instead. */
dfl_status dfl_cfg_reject(const dfl_cfg *c, const char *sec, const char *key, dfl_err *err,
                          const char *fmt, ...) __attribute__((format(printf, 5, 6)));

/* Number of blank-separated values in the first point of a point-list
 * value ("x y; ..." -> 2): tells 2D from 3D lists before parsing them. */
int dfl_cfg_point_dim(const char *value);

/* DFL_E_INPUT naming the first key (in file order) no getter has read.
 * A section none of whose keys was read is the config's, not a typo, when a
 * key that was read names it (a word of its value, split at blanks, commas
 * and semicolons), or named it before: the list a --set replaced, a sweep's
 * other items (e.g. `--set study.cases=circle` leaves the other cases
 * unselected, not unknown); and so is a section named by a key of a section
 * so excused, to any depth (the shape section of an unselected case, the
 * operands of a CSG shape the run did not select). */
dfl_status dfl_cfg_check_used(const dfl_cfg *c, dfl_err *err);
/* Same, restricted to section sec (for commands that read only part of a
 * study config, such as `dflab probe` reading [field] and [shape]). */
dfl_status dfl_cfg_check_used_in(const dfl_cfg *c, const char *sec, dfl_err *err);
/* True when [sec] key is in c and a getter has read it (false when it is
 * not in c).  Marks nothing. */
bool dfl_cfg_used(const dfl_cfg *c, const char *sec, const char *key);
/* Marks every key of section sec read (none: nothing happens), for a
 * caller that hands the section to a reader working on a copy (a sweep
 * point of c, changed by dfl_cfg_set) and checks the copy's section with
 * dfl_cfg_check_used_in itself.  Records nothing in the read record. */
void dfl_cfg_claim_section(const dfl_cfg *c, const char *sec);
/* Marks read in c every key a reader read in point, a sweep point of c
 * (dfl_cfg_sweep_point): for a caller that hands a reader the copy and
 * cannot name every section it follows (a CSG shape's operands, a mesh's
 * polygonized section).  Entries are matched by position, section and key;
 * those a dfl_cfg_set added to point are not c's and are skipped.  Appends
 * to c's read record (below) point's records of keys c holds and of
 * defaults (keys absent from both), after c's own, the first read
 * counting: `dflab help` and the manifest then show what the copy's reader
 * read; a key point added is not recorded. */
void dfl_cfg_claim_read(const dfl_cfg *c, const dfl_cfg *point);
/* Defers the sections named `name` and `name_*` (name: at most 40 bytes;
 * NULL or "" undoes it): dfl_cfg_check_used skips their keys, which another
 * reader checks later (dflab's runner: the probe's [field] and [field_*]
 * sections, experiments/harness/probe.h).  Not copied by sweep points. */
void dfl_cfg_defer_sections(dfl_cfg *c, const char *name);
/* The first deferred section, in entry order, holding a key nobody has read
 * yet, or NULL. */
const char *dfl_cfg_unused_deferred(const dfl_cfg *c);

/* ---- read record ----------------------------------------------------- */
/* Every getter records the key it reads (the first read counts), what it
 * expects (the text its error messages use: type and range) and, for an
 * _opt getter of an absent key, the default it returned.  dfl_cfg_has
 * alone records nothing. */
typedef struct dfl_cfg_read {
    const char *sec, *key;
    const char *value;  /* as written, or the default's text */
    const char *expect; /* e.g. "an integer in [1, 64]" */
    bool is_default;
} dfl_cfg_read;
/* Number of keys read so far; the i-th in first-read order (false when
 * i >= dfl_cfg_reads).  Strings live until dfl_cfg_free. */
size_t dfl_cfg_reads(const dfl_cfg *c);
bool dfl_cfg_read_at(const dfl_cfg *c, size_t i, dfl_cfg_read *out);
/* Makes c a validation pass: once dfl_cfg_check_used finds every key
 * known, it marks c validated and returns DFL_E_INTERNAL instead of DFL_OK,
 * so that a study (which calls it right after reading its keys) stops
 * before computing.  dfl_cfg_validated tells such a stop from a failure. */
void dfl_cfg_validate_only(dfl_cfg *c);
bool dfl_cfg_validated(const dfl_cfg *c);
/* True when c is a validation pass (dfl_cfg_validate_only was called on it):
 * a field factory then reads and checks every key it would read, builds
 * only what is cheap (the shape, the input), and returns a placeholder in
 * place of what computes (a fit, a grid of samples or proxies, a level
 * set), so that validating every point of a sweep costs no build. */
bool dfl_cfg_validating(const dfl_cfg *c);

/* Writes the configuration (single-valued or not) as INI text to path,
 * through a temporary file renamed on success: a first comment line
 * "# resolved configuration of ORIGIN" (origin NULL: the path the config
 * was loaded from, dfl_cfg_path; a byte dfl_text_escape would not print
 * written as \xNN, so a newline in a path cannot end the comment), then
 * each section once, at its first entry, holding every key of it as
 * written, set or included, in entry order, without include lines (a --set
 * of a key new to an earlier section is written in that section: the
 * loader refuses a repeated section header); the value of a file-name
 * key (DFL_CFG_PATH_KEYS) resolved as dfl_cfg_path_value resolves it, then
 * made absolute (realpath when the file exists, else against the working
 * directory), each item of a sweep list on its own. */
dfl_status dfl_cfg_write(const dfl_cfg *c, const char *origin, const char *path, dfl_err *err);

#endif
