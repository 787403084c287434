/* The read record: the getters know each key's type, range and default,
 * so recording their reads gives, without a second table, the resolved
 * configuration a manifest stores (defaults included) and the key list
 * `dflab help STUDY` prints.  A validation pass runs a study with
 * validate_only set: dfl_cfg_check_used, which every study calls right
 * after reading its keys, then stops it before it computes anything. */
#include <stdlib.h>
#include <string.h>

#include "io/config_impl.h"

void dfl_cfgi_log(const dfl_cfg *c, const char *sec, const char *key, const char *expect,
                  const char *def)
{
    dfl_cfg_log *l = c->log;
    if (!l) return;
    for (size_t i = 0; i < l->n; i++)
        if (strcmp(l->r[i].sec, sec) == 0 && strcmp(l->r[i].key, key) == 0) return;
    if (l->n == l->cap) {
        size_t cap = l->cap ? 2 * l->cap : 32;
        dfl_cfg_readrec *r = realloc(l->r, cap * sizeof *r);
        if (!r) return;
        l->r = r;
        l->cap = cap;
    }
    dfl_cfg_readrec rec = {strdup(sec), strdup(key), strdup(expect ? expect : "a value"),
                           def ? strdup(def) : NULL};
    if (!rec.sec || !rec.key || !rec.expect || (def && !rec.def)) {
        free(rec.sec), free(rec.key), free(rec.expect), free(rec.def);
        return;
    }
    l->r[l->n++] = rec;
}

void dfl_cfgi_free_log(dfl_cfg *c)
{
    if (!c->log) return;
    for (size_t i = 0; i < c->log->n; i++) {
        dfl_cfg_readrec *r = &c->log->r[i];
        free(r->sec), free(r->key), free(r->expect), free(r->def);
    }
    free(c->log->r);
    free(c->log);
    c->log = NULL;
}

size_t dfl_cfg_reads(const dfl_cfg *c) { return c->log ? c->log->n : 0; }

bool dfl_cfg_read_at(const dfl_cfg *c, size_t i, dfl_cfg_read *out)
{
    if (!c->log || i >= c->log->n) return false;
    const dfl_cfg_readrec *r = &c->log->r[i];
    out->sec = r->sec;
    out->key = r->key;
    out->expect = r->expect;
    out->is_default = r->def != NULL;
    if (r->def) {
        out->value = r->def;
    } else {
        ssize_t k = dfl_cfgi_find(c, r->sec, r->key);
        out->value = k >= 0 ? c->e[k].value : "";
    }
    return true;
}

void dfl_cfg_validate_only(dfl_cfg *c)
{
    if (c->log) c->log->validate_only = 1;
}

bool dfl_cfg_validated(const dfl_cfg *c) { return c->log && c->log->validated; }

bool dfl_cfg_validating(const dfl_cfg *c) { return c->log && c->log->validate_only; }

dfl_status dfl_cfgi_stop_if_validating(const dfl_cfg *c, dfl_err *err)
{
    if (!c->log || !c->log->validate_only) return DFL_OK;
    c->log->validated = 1;
    return dfl_err_set(err, DFL_E_INTERNAL, "%s: validation pass: stopped after reading the config",
                       c->path);
}
