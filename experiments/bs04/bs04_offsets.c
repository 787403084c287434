#include "bs04/bs04_offsets.h"

#include <stdlib.h>
#include <string.h>

dfl_status dfl_bs04_offset_opts_from_cfg(const dfl_cfg *cfg, const char *sec,
                                         dfl_bs04_offset_opts *out, dfl_err *err)
{
    long steps, rounds;
    dfl_status st;
    if ((st = dfl_cfg_double_opt(cfg, sec, "smax", 8.0, 1.0, 1e6, &out->smax, err))) return st;
    if ((st = dfl_cfg_int_opt(cfg, sec, "steps", 128, 1, DFL_CROSS_MAX_STEPS, &steps, err)))
        return st;
    if ((st = dfl_cfg_int_opt(cfg, sec, "rounds", 6, 0, 40, &rounds, err))) return st;
    if ((st = dfl_cfg_double_opt(cfg, sec, "valid_tol", 1e-6, 0.0, 0.5, &out->valid_tol, err)))
        return st;
    out->steps = (int)steps;
    out->rounds = (int)rounds;
    return DFL_OK;
}

dfl_status dfl_bs04_offsets_alloc(dfl_bs04_offsets *o, size_t m, const char *what, dfl_err *err)
{
    o->uv = malloc(m * sizeof *o->uv), o->ug = malloc(2 * m * sizeof *o->ug);
    o->dv = malloc(m * sizeof *o->dv), o->dg = malloc(2 * m * sizeof *o->dg);
    o->s = malloc(o->rays.n * sizeof *o->s), o->valid = malloc(o->rays.n * sizeof *o->valid);
    o->branch = malloc(o->rays.n * sizeof *o->branch);
    if (!o->uv || !o->ug || !o->dv || !o->dg || !o->s || !o->valid || !o->branch)
        return dfl_err_set(err, DFL_E_NOMEM, "%s: out of memory", what);
    return DFL_OK;
}

dfl_status dfl_bs04_offsets_sample(dfl_bs04_offsets *o, const dfl_grid *g, int threads,
                                   dfl_err *err)
{
    dfl_status st = dfl_field_sample(&o->u, g, threads, o->uv, o->ug, err);
    if (st == DFL_OK) st = dfl_field_sample(&o->exact, g, threads, o->dv, o->dg, err);
    return st;
}

dfl_status dfl_bs04_offsets_level(dfl_bs04_offsets *o, size_t m, double delta,
                                  const dfl_bs04_offset_opts *opts, int threads,
                                  dfl_ray_stats *rs, dfl_bandstats *bs, dfl_err *err)
{
    const dfl_cross_opts co = {opts->smax * delta, opts->steps, opts->rounds};
    const double vt = opts->valid_tol;
    dfl_status st = dfl_curveprobe_valid(&o->exact, &o->rays, delta, vt, threads, o->valid, err);
    if (st == DFL_OK) st = dfl_curveprobe_cross(&o->u, &o->rays, delta, &co, threads, o->s, err);
    if (st == DFL_OK)
        st = dfl_curveprobe_on_branch(&o->exact, &o->rays, o->s, vt, threads, o->branch, err);
    if (st == DFL_OK) dfl_curveprobe_stats(&o->rays, o->s, o->valid, o->branch, delta, rs);
    if (st == DFL_OK) st = dfl_metrics_bandstats(m, 2, o->uv, o->ug, o->dv, delta, bs, err);
    return st;
}

void dfl_bs04_offsets_free(dfl_bs04_offsets *o)
{
    dfl_field_destroy(&o->u);
    dfl_field_destroy(&o->exact);
    dfl_polyline_free(&o->pl);
    dfl_curveprobe_free(&o->rays);
    free(o->uv), free(o->ug), free(o->dv), free(o->dg), free(o->s);
    free(o->valid), free(o->branch);
    memset(o, 0, sizeof *o);
}

void dfl_bs04_offsets_cost(const char *gsec, double nodes, const char *rsec, double rays,
                           double units, size_t nlevels, const dfl_bs04_offset_opts *o,
                           dfl_cost *c)
{
    dfl_cost_add_bytes(c, gsec, "n", 48 * nodes, "u and d on %.3g nodes", nodes);
    dfl_cost_add_bytes(c, rsec, "rays", 128 * rays, "%.3g rays", rays);
    dfl_cost_add_work(c, gsec, "n", DFL_COST_CHEAP, nodes * units, "u at %.3g nodes", nodes);
    dfl_cost_add_work(c, gsec, "n", DFL_COST_FOOTPOINT, nodes, "d at %.3g nodes", nodes);
    const double n = rays * (double)nlevels;
    dfl_cost_add_work(c, rsec, "rays", DFL_COST_FOOTPOINT, 3 * n, "%.3g ray tests", n);
    dfl_cost_add_work(c, rsec, "rays", DFL_COST_CHEAP, n * (o->steps + 16.0 * o->rounds) * units,
                      "%.3g rays x %zu offsets x %d steps", rays, nlevels, o->steps);
}
