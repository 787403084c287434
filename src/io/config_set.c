/* `--set section.key=value` overrides, applied after the file (and its
 * includes) has been read: a key that exists takes the new value and the
 * origin "--set"; a new key is appended.  Axes are recomputed, since the
 * value may start or end a sweep. */
#include <stdlib.h>
#include <string.h>

#include "io/config_impl.h"

dfl_status dfl_cfg_set(dfl_cfg *c, const char *assignment, dfl_err *err)
{
    const char *eq = strchr(assignment, '=');
    const char *dot = strchr(assignment, '.');
    if (!eq || !dot || dot > eq || dot == assignment || eq == dot + 1)
        return dfl_err_set(err, DFL_E_INPUT,
                           "--set %s: expected section.key=value", assignment);
    char sec[256], key[256];
    size_t ls = (size_t)(dot - assignment), lk = (size_t)(eq - dot - 1);
    if (ls >= sizeof sec || lk >= sizeof key)
        return dfl_err_set(err, DFL_E_INPUT, "--set %s: section or key too long", assignment);
    memcpy(sec, assignment, ls);
    sec[ls] = '\0';
    memcpy(key, dot + 1, lk);
    key[lk] = '\0';
    char *s = dfl_cfgi_trim(sec), *k = dfl_cfgi_trim(key);
    if (strcmp(k, "include") == 0)
        return dfl_err_set(err, DFL_E_INPUT,
                           "--set %s: include is read with the config file; --set the "
                           "included keys themselves (e.g. %s.order=3)",
                           assignment, s);
    char *val = strdup(eq + 1);
    if (!val) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    char *v = dfl_cfgi_trim(val);
    if (*v == '\0') {
        free(val);
        return dfl_err_set(err, DFL_E_INPUT, "--set %s: empty value", assignment);
    }
    ssize_t i = dfl_cfgi_find(c, s, k);
    dfl_status st = i >= 0 ? dfl_cfgi_set_value(&c->e[i], v, "--set", 0, err)
                           : dfl_cfgi_add(c, s, k, v, "--set", 0, NULL, err);
    free(val);
    if (st != DFL_OK) return st;
    return dfl_cfgi_find_axes(c, err);
}
