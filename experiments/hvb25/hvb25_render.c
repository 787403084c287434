/* hvb25 Table 4 (right): the time of one sphere-traced frame of a proxy
 * field per decoding filter (field/trace.h), with the frames written as EXR
 * (channels depth, normal.x/y/z, steps; the report shows them as PNG).
 *
 * Keys.  [study]
 *   filters = nearest trilinear hermite   proxy fields: one frame per filter
 *             (each with its default clip, proxy/filter.h, or [field]
 *             clip_radius when given, and [field] clip's kind); absent: one
 *             frame of the field as [field] configures it
 *   reps    = 3          frames traced per filter; the best time is kept
 *   false_hit_tol = 0.5  a hit x whose true distance |d(x)| (the proxy
 *             truth of [field] and [shape], experiments/cfg/
 *             proxy_input_cfg.h) exceeds this many cell sizes is a false
 *             hit: a surface the field invents (the paper's Fig. 10
 *             "floating artifacts"); proxy fields only
 * [camera] eye = 1.6 -2.2 1.4, target = 0 0 0, up = 0 0 1, fov = 40,
 *          width = 256, height = 256
 * [trace]  tmax = 8, eps = 1e-4, step_scale = 1, max_steps = 256,
 *          box = true: clip rays to the proxy grid's box ([-1, 1]^3 for
 *          other fields)
 * Rows: one per frame: the build (order, res, gen_seconds), filter, clip
 * radius and kind, frame time, hits / misses / exhausted pixels, false
 * hits (-1 for a field without cells), field evaluations, mean
 * steps per pixel, ns per evaluation, and the frame's file name.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cfg/field_cfg.h"
#include "cfg/proxy_input_cfg.h"
#include "field/trace.h"
#include "harness/experiment.h"
#include "hvb25/hvb25.h"
#include "hvb25/hvb25_eval.h"
#include "io/manifest.h"
#include "proxy/proxy_field.h"

typedef struct render_keys {
    int nfilters;
    dfl_proxy_filter filters[HVB25_MAX_DECODINGS];
    long reps;
    double false_tol;   /* in cell sizes */
    dfl_camera cam;
    dfl_trace_opts tr;
} render_keys;

static dfl_status read_camera(const dfl_cfg *cfg, dfl_camera *c, dfl_err *err)
{
    static const double eye[3] = {1.6, -2.2, 1.4}, tgt[3] = {0, 0, 0}, up[3] = {0, 0, 1};
    long w, h;
    dfl_status st = dfl_cfg_vec_opt(cfg, "camera", "eye", 3, eye, c->eye, err);
    if (!st) st = dfl_cfg_vec_opt(cfg, "camera", "target", 3, tgt, c->target, err);
    if (!st) st = dfl_cfg_vec_opt(cfg, "camera", "up", 3, up, c->up, err);
    if (!st) st = dfl_cfg_double_opt(cfg, "camera", "fov", 40, 1e-3, 179, &c->fov_deg, err);
    if (!st) st = dfl_cfg_int_opt(cfg, "camera", "width", 256, 1, 16384, &w, err);
    if (!st) st = dfl_cfg_int_opt(cfg, "camera", "height", 256, 1, 16384, &h, err);
    if (st) return st;
    c->width = (int)w, c->height = (int)h;
    dfl_err e2;
    if (dfl_camera_check(c, &e2)) return dfl_cfg_reject(cfg, "camera", "up", err, "%s", e2.msg);
    return DFL_OK;
}

static dfl_status read_keys(const dfl_cfg *cfg, render_keys *k, dfl_err *err)
{
    memset(k, 0, sizeof *k);
    /* set before any getter: every error path below stores them too */
    long steps = 256;
    bool box = true;
    dfl_status st = hvb25_filters_from_cfg(cfg, "study", "filters", k->filters, &k->nfilters, err);
    if (!st) st = dfl_cfg_int_opt(cfg, "study", "reps", 3, 1, 100, &k->reps, err);
    if (!st)
        st = dfl_cfg_double_opt(cfg, "study", "false_hit_tol", 0.5, 1e-6, 1e6, &k->false_tol, err);
    if (!st) st = read_camera(cfg, &k->cam, err);
    if (!st) st = dfl_cfg_double_opt(cfg, "trace", "tmax", 8, 1e-300, 1e300, &k->tr.tmax, err);
    if (!st) st = dfl_cfg_double_opt(cfg, "trace", "eps", 1e-4, 1e-300, 1e300, &k->tr.eps, err);
    if (!st) st = dfl_cfg_double_opt(cfg, "trace", "step_scale", 1, 1e-3, 1, &k->tr.step_scale, err);
    if (!st) st = dfl_cfg_int_opt(cfg, "trace", "max_steps", 256, 1, 1000000, &steps, err);
    if (!st) st = dfl_cfg_bool_opt(cfg, "trace", "box", true, &box, err);
    k->tr.max_steps = (int)steps;
    k->tr.use_box = box;
    return st;
}

typedef struct frame_job {
    const dfl_field *f;
    const render_keys *k;
    dfl_frame fr;
    double best;
    long false_hits;    /* -1: not counted */
} frame_job;

/* Hits whose true distance exceeds tol: the hit points eye + depth dir of
 * the frame's pixels, their truth in batches of one image row. */
static dfl_status count_false(const dfl_field *ref, const dfl_camera *cam, const dfl_frame *fr,
                              double tol, long *out, dfl_err *err)
{
    double *x = malloc(3 * sizeof(double) * (size_t)fr->width);
    double *d = malloc(sizeof(double) * (size_t)fr->width);
    if (!x || !d) {
        free(x), free(d);
        return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    }
    long n = 0;
    for (int py = 0; py < fr->height; py++) {
        size_t m = 0;
        for (int px = 0; px < fr->width; px++) {
            const double t = fr->depth[(size_t)py * fr->width + px];
            if (!isfinite(t)) continue;
            double dir[3];
            dfl_camera_ray(cam, px, py, dir);
            for (int j = 0; j < 3; j++) x[3 * m + j] = cam->eye[j] + t * dir[j];
            m++;
        }
        if (m) ref->ops->eval(ref->ctx, m, x, d, NULL);
        for (size_t i = 0; i < m; i++) n += !(fabs(d[i]) <= tol);
    }
    free(x), free(d);
    *out = n;
    return DFL_OK;
}

static dfl_status trace_best(frame_job *j, dfl_err *err)
{
    j->best = INFINITY;
    for (long r = 0; r < j->k->reps; r++) {
        dfl_frame_free(&j->fr);
        const double t0 = dfl_wall_seconds();
        dfl_status st = dfl_trace_frame(j->f, &j->k->cam, &j->k->tr, &j->fr, err);
        const double t = dfl_wall_seconds() - t0;
        if (st) return st;
        if (t < j->best) j->best = t;
    }
    return DFL_OK;
}

static dfl_status put_row(dfl_table *t, const dfl_field *f, const dfl_proxy_filter_opts *o,
                          double gen, const frame_job *j, const dfl_study_ctx *ctx,
                          const char *stem, dfl_err *err)
{
    const dfl_proxy_grid *g = dfl_proxy_field_grid(f);
    const dfl_frame *fr = &j->fr;
    const double np = (double)fr->width * fr->height;
    dfl_status st = dfl_table_row(t, err);
    if (!st) st = dfl_table_set_string(t, "field_kind", f->ops->name, err);
    if (!st) st = dfl_table_set_int(t, "order", g ? g->order : 0, err);
    if (!st) st = dfl_table_set_int(t, "res", g ? g->res : 0, err);
    if (!st) st = dfl_table_set_double(t, "gen_seconds", gen, err);
    if (!st) st = dfl_table_set_string(t, "filter", o ? dfl_proxy_filter_name(o->filter) : "", err);
    if (!st) st = dfl_table_set_double(t, "clip", o ? o->clip : NAN, err);
    if (!st)
        st = dfl_table_set_string(t, "clip_kind",
                                  o ? dfl_proxy_clip_name(o->clip > 0 ? o->clip_kind
                                                                      : DFL_PROXY_CLIP_OFF)
                                    : "", err);
    if (!st) st = dfl_table_set_int(t, "width", fr->width, err);
    if (!st) st = dfl_table_set_int(t, "height", fr->height, err);
    if (!st) st = dfl_table_set_double(t, "frame_seconds", j->best, err);
    if (!st) st = dfl_table_set_double(t, "frame_ms", 1e3 * j->best, err);
    if (!st) st = dfl_table_set_int(t, "hits", (long)fr->hits, err);
    if (!st) st = dfl_table_set_int(t, "false_hits", j->false_hits, err);
    if (!st) st = dfl_table_set_int(t, "misses", (long)fr->misses, err);
    if (!st) st = dfl_table_set_int(t, "exhausted", (long)fr->exhausted, err);
    if (!st) st = dfl_table_set_int(t, "evals", (long)fr->evals, err);
    if (!st) st = dfl_table_set_double(t, "steps_mean", (double)fr->evals / np, err);
    if (!st) st = dfl_table_set_double(t, "ns_per_eval",
                                       fr->evals ? 1e9 * j->best / (double)fr->evals : NAN, err);
    if (!st) st = dfl_study_put_file(t, "frame_exr", ctx, stem, "exr", true, err);
    return st;
}

static dfl_status render_run(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_table *table,
                             dfl_err *err)
{
    render_keys k;
    dfl_field f = {0};
    dfl_status st = read_keys(cfg, &k, err);
    const double t0 = dfl_wall_seconds();
    if (!st) st = dfl_field_from_cfg(cfg, "field", &f, err);
    const double gen = dfl_wall_seconds() - t0;
    if (!st && f.dim != 3) st = dfl_cfg_reject(cfg, "field", "kind", err, "a 3D field is required");
    const dfl_proxy_grid *g = st ? NULL : dfl_proxy_field_grid(&f);
    if (!st && k.nfilters && !g)
        st = dfl_cfg_reject(cfg, "study", "filters", err, "filters need a proxy field");
    dfl_field ref = {0};
    if (!st && g) st = dfl_proxy_truth_from_cfg(cfg, "field", "shape", &ref, err);
    if (!st) st = dfl_cfg_check_used(cfg, err);
    k.tr.threads = ctx->threads;
    for (int a = 0; a < 3; a++) {
        k.tr.box_lo[a] = g ? g->lo[a] : -1;
        k.tr.box_hi[a] = g ? g->hi[a] : 1;
    }
    const int n = k.nfilters ? k.nfilters : 1;
    for (int i = 0; !st && i < n; i++) {
        hvb25_view v = {g, {0}};
        const dfl_proxy_filter_opts *op = g ? dfl_proxy_field_opts(&f) : NULL;
        dfl_field view = {0};
        const dfl_field *use = &f;
        if (k.nfilters) {
            dfl_proxy_filter_opts_default(k.filters[i], g, &v.o);
            v.o.is_signed = op->is_signed;
            /* [field] clip_radius, when given, is every filter's clip */
            if (dfl_cfg_has(cfg, "field", "clip_radius")) v.o.clip = op->clip;
            /* and [field] clip its formula (off: no radius at all) */
            v.o.clip_kind = op->clip_kind;
            if (op->clip_kind == DFL_PROXY_CLIP_OFF) v.o.clip = 0;
            op = &v.o;
            hvb25_view_field(&v, &view);
            use = &view;
        }
        frame_job j = {use, &k, {0}, 0, -1};
        char stem[64], path[4096];
        snprintf(stem, sizeof stem, "frame_%s", op ? dfl_proxy_filter_name(op->filter) : "field");
        st = trace_best(&j, err);
        if (!st && g)
            st = count_false(&ref, &k.cam, &j.fr, k.false_tol * dfl_proxy_cell_size(g),
                             &j.false_hits, err);
        if (!st) st = dfl_frame_write_exr(dfl_study_path(ctx, stem, "exr", path, sizeof path),
                                          &j.fr, err);
        if (!st) st = put_row(table, &f, op, gen, &j, ctx, stem, err);
        dfl_frame_free(&j.fr);
    }
    dfl_field_destroy(&ref);
    dfl_field_destroy(&f);
    return st;
}

/* Peak memory: the field ([field]'s cost) and one frame with the tracer's
 * per-pixel state (about 200 bytes: rays, positions, values, gradients,
 * flags, the frame's depth and normals and the EXR's channels).  Work: every
 * pixel may march max_steps decodes in each of reps frames per filter. */
static dfl_status render_estimate(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_cost *c,
                                  dfl_err *err)
{
    render_keys k;
    dfl_status st = read_keys(cfg, &k, err);
    if (!st) st = dfl_study_estimate_default(cfg, ctx, c, err);
    if (st) return st;
    const double px = (double)k.cam.width * k.cam.height;
    const int frames = k.nfilters ? k.nfilters : 1;
    dfl_cost_add_bytes(c, "camera", k.cam.width >= k.cam.height ? "width" : "height", 200 * px,
                       "a frame of %dx%d pixels", k.cam.width, k.cam.height);
    const double n = px * k.tr.max_steps * (double)k.reps * frames;
    dfl_cost_add_work(c, "trace", "max_steps", DFL_COST_DECODE, n,
                      "%.3g pixels x %d steps x %ld reps x %d filters", px, k.tr.max_steps,
                      k.reps, frames);
    return DFL_OK;
}

DFL_STUDY_DEFINE_ESTIMATED(hvb25_render, render_run, render_estimate,
                 "hvb25 Table 4: one sphere-traced frame of a proxy field per filter (EXR, time)");
