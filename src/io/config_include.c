/* Includes: `[S] include = file` merges the [shape] keys of file into [S].
 *
 * The parser only records the include lines; they are resolved here, after
 * the including file has been read whole, because "the section's own keys
 * win" must hold whether they are written before or after the include line.
 * The included keys take the place of the include line in the entry list,
 * so the resolved config.ini lists them where the include stood.  An
 * included file is parsed with includes disabled: nesting (and with it any
 * include loop) is an error, not a search. */
#define _DEFAULT_SOURCE /* realpath */
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/config_impl.h"
#include "io/path.h"

/* Checks that f, loaded for the include at via, holds [shape] keys only. */
static dfl_status check_shape_only(const dfl_cfg *f, const char *via, const char *sec,
                                   dfl_err *err)
{
    if (!dfl_cfg_has_section(f, "shape"))
        return dfl_err_set(err, DFL_E_INPUT,
                           "%s: [%s] include: %s has no [shape] section (or it is empty)", via,
                           sec, f->path);
    for (size_t i = 0; i < f->n; i++)
        if (strcmp(f->e[i].sec, "shape") != 0)
            return dfl_err_set(err, DFL_E_INPUT,
                               "%s:%d: [%s] %s: an included file holds only [shape] keys "
                               "(included as [%s] at %s)",
                               f->e[i].file, f->e[i].line, f->e[i].sec, f->e[i].key, sec, via);
    return DFL_OK;
}

/* realpath of the directory part of path ("." when it has none); NULL
 * when it does not resolve.  Caller frees. */
static char *real_dir(const char *path)
{
    char dir[4096];
    const size_t dlen = (size_t)(dfl_path_base(path) - path);
    if (dlen >= sizeof dir) return NULL;
    if (dlen == 0) snprintf(dir, sizeof dir, ".");
    else memcpy(dir, path, dlen), dir[dlen] = '\0';
    return realpath(dir, NULL);
}

/* The file an include names, as the kernel resolves it: rel below the
 * directory of the including file, where "lnk/../x.ini" is x.ini beside
 * lnk's target (as every other program reads it), not beside lnk.  The
 * lexically cleaned name (io/path.h) is kept when it names the same
 * directory (it reads better in messages: "configs/shapes/S.ini"); when a
 * symbolic link makes them differ, the real directory and rel's base name
 * are used.  When nothing resolves (a missing directory), the cleaned name
 * is tried and fails to open with its own message.  NULL when the result
 * does not fit. */
static char *include_path(const char *file, const char *rel, char *buf, size_t size)
{
    if (!dfl_path_beside(file, rel, buf, size)) return NULL;
    char raw[8200];
    const size_t dlen = rel[0] == '/' ? 0 : (size_t)(dfl_path_base(file) - file);
    if ((size_t)snprintf(raw, sizeof raw, "%.*s%s", (int)dlen, file, rel) >= sizeof raw)
        return NULL;
    char *kd = real_dir(raw), *ld = real_dir(buf);
    char *out = buf;
    if (kd && !(ld && strcmp(kd, ld) == 0)) {
        const int n = snprintf(buf, size, "%s/%s", strcmp(kd, "/") == 0 ? "" : kd,
                               dfl_path_base(raw));
        if (n < 0 || (size_t)n >= size) out = NULL;
    }
    free(kd), free(ld);
    return out;
}

dfl_status dfl_cfgi_resolve_includes(dfl_cfg *c, const dfl_cfg_include *incs, size_t n,
                                     dfl_err *err)
{
    size_t shift = 0; /* entries inserted by earlier includes */
    for (size_t k = 0; k < n; k++) {
        const dfl_cfg_include *in = &incs[k];
        char via[4200], path[4096];
        snprintf(via, sizeof via, "%s:%d", c->path, in->line);
        if (!include_path(c->path, in->value, path, sizeof path))
            return dfl_err_set(err, DFL_E_INPUT, "%s: [%s] include: file name too long", via,
                               in->sec);
        dfl_cfg *f = NULL;
        dfl_status st = dfl_cfgi_load(path, false, &f, err);
        if (st != DFL_OK) {
            dfl_err_prefix(err, "%s: [%s] include", via, in->sec);
            return st;
        }
        st = check_shape_only(f, via, in->sec, err);
        size_t at = in->at + shift;
        for (size_t i = 0; i < f->n && st == DFL_OK; i++) {
            const dfl_cfg_entry *e = &f->e[i];
            if (dfl_cfgi_find(c, in->sec, e->key) >= 0) continue; /* the section's own wins */
            st = dfl_cfgi_insert(c, at++, in->sec, e->key, e->value, e->file, e->line, via, err);
            if (st == DFL_OK) shift++;
        }
        dfl_cfg_free(f);
        if (st != DFL_OK) return st;
    }
    return DFL_OK;
}
