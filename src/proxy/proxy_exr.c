/* The grid's own buffer is the encoder's source and the decoder's target:
 * channels point into the cell-major array with a pixel stride of one
 * cell, so no conversion touches the bits (doubles go as two 32-bit words;
 * little-endian hosts only, checked at compile time).  Diagnostics are
 * swallowed and reported through dfl_err, as in io/exr.c. */
#include "proxy/proxy_exr.h"

#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <openexr.h>

#include "io/atomic.h"

#if !defined(__BYTE_ORDER__) || __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "proxy_exr.c assumes a little-endian host (double words as .lo/.hi)"
#endif

static const char *const scalar_names[8] = {"px", "py", "pz", "kr", "kR", "tx", "ty", "tz"};
#define MAXCH 17
#define SIDE_LINES 64

static void quiet(exr_const_context_t c, exr_result_t code, const char *msg)
{
    (void)c;
    (void)code;
    (void)msg;
}

/* One EXR channel: its name, type and where its pixels live. */
typedef struct chan {
    char name[8];
    exr_pixel_type_t type;
    uint8_t *base;   /* cell 0's pixel */
    int32_t bytes, stride;
} chan;

/* The channels of g in EXR (name) order. */
static int channels(const dfl_proxy_grid *g, chan *ch)
{
    const size_t sz = dfl_proxy_storage_size(g->storage);
    const int32_t stride = (int32_t)(sz * (size_t)g->nscalar);
    int n = 0;
    for (int q = 0; q < g->nscalar; q++)
        for (int w = 0; w < (g->storage == DFL_PROXY_DOUBLE ? 2 : 1); w++) {
            chan *c = &ch[n++];
            uint8_t *b = (uint8_t *)g->data + (size_t)q * sz;
            if (g->storage == DFL_PROXY_DOUBLE) {
                snprintf(c->name, sizeof c->name, "%s.%s", scalar_names[q], w ? "lo" : "hi");
                c->type = EXR_PIXEL_UINT;
                c->base = b + (w ? 0 : 4);
                c->bytes = 4;
            } else {
                snprintf(c->name, sizeof c->name, "%s", scalar_names[q]);
                c->type = g->storage == DFL_PROXY_FLOAT ? EXR_PIXEL_FLOAT : EXR_PIXEL_HALF;
                c->base = b;
                c->bytes = (int32_t)sz;
            }
            c->stride = stride;
        }
    if (g->side) {
        /* side bytes are widened into the HALF channel by the caller */
        chan *c = &ch[n++];
        snprintf(c->name, sizeof c->name, "side");
        c->type = EXR_PIXEL_HALF;
        c->base = NULL;
        c->bytes = 2;
        c->stride = 2;
    }
    /* EXR lists channels sorted by name */
    for (int i = 1; i < n; i++)
        for (int j = i; j > 0 && strcmp(ch[j - 1].name, ch[j].name) > 0; j--) {
            chan t = ch[j];
            ch[j] = ch[j - 1];
            ch[j - 1] = t;
        }
    return n;
}

static chan *find(chan *ch, int n, const char *name)
{
    for (int i = 0; i < n; i++)
        if (strcmp(ch[i].name, name) == 0) return &ch[i];
    return NULL;
}

static dfl_status fail(dfl_err *err, exr_result_t rv, const char *path, const char *step)
{
    return dfl_err_set(err, rv == EXR_ERR_OUT_OF_MEMORY ? DFL_E_NOMEM : DFL_E_IO,
                       "%s: OpenEXR %s failed: %s", path, step, exr_get_default_error_message(rv));
}

static exr_result_t put_attrs(exr_context_t x, const dfl_proxy_grid *g)
{
    exr_attr_v3d_t lo = {.x = g->lo[0], .y = g->lo[1], .z = g->lo[2]};
    exr_attr_v3d_t hi = {.x = g->hi[0], .y = g->hi[1], .z = g->hi[2]};
    exr_result_t rv = exr_attr_set_int(x, 0, "dflab.proxy.order", g->order);
    if (!rv) rv = exr_attr_set_int(x, 0, "dflab.proxy.res", g->res);
    if (!rv) rv = exr_attr_set_v3d(x, 0, "dflab.proxy.lo", &lo);
    if (!rv) rv = exr_attr_set_v3d(x, 0, "dflab.proxy.hi", &hi);
    if (!rv) rv = exr_attr_set_string(x, 0, "dflab.proxy.storage", dfl_proxy_storage_name(g->storage));
    if (!rv)
        rv = exr_attr_set_string(x, 0, "dflab.proxy.position", dfl_proxy_position_name(g->position));
    if (!rv) rv = exr_attr_set_int(x, 0, "dflab.proxy.has_inside", g->has_inside);
    if (!rv) rv = exr_attr_set_double(x, 0, "dflab.proxy.uncertified", (double)g->stats.uncertified);
    if (!rv) rv = exr_attr_set_double(x, 0, "dflab.proxy.failed", (double)g->stats.failed);
    if (!rv) rv = exr_attr_set_double(x, 0, "dflab.proxy.moved", (double)g->stats.moved);
    if (!rv) rv = exr_attr_set_double(x, 0, "dflab.proxy.clamped", (double)g->stats.clamped);
    return rv;
}

/* Points the coding channels of one chunk at the grid (side: at sidebuf,
 * rows from y0 on). */
static void bind(exr_coding_channel_info_t *cc, int nc, chan *ch, int n, int width, int y,
                 uint16_t *sidebuf, int y0, int encode)
{
    for (int c = 0; c < nc; c++) {
        chan *k = find(ch, n, cc[c].channel_name);
        uint8_t *p = k->base ? k->base + (size_t)y * (size_t)width * (size_t)k->stride
                             : (uint8_t *)(sidebuf + (size_t)(y - y0) * (size_t)width);
        cc[c].user_data_type = k->type;
        cc[c].user_bytes_per_element = (int16_t)k->bytes;
        cc[c].user_pixel_stride = k->stride;
        cc[c].user_line_stride = k->stride * width;
        if (encode)
            cc[c].encode_from_ptr = p;
        else
            cc[c].decode_to_ptr = p;
    }
}

static exr_result_t encode(exr_context_t x, const dfl_proxy_grid *g, chan *ch, int n,
                           uint16_t *sidebuf, const char **step)
{
    const int W = g->res, H = g->res * g->res;
    int32_t lpc = 0;
    *step = "scanlines per chunk";
    exr_result_t rv = exr_get_scanlines_per_chunk(x, 0, &lpc);
    exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
    for (int y = 0; !rv && y < H; y += lpc) {
        exr_chunk_info_t ci;
        *step = "chunk info";
        rv = exr_write_scanline_chunk_info(x, 0, y, &ci);
        if (!rv && ci.height > SIDE_LINES) rv = EXR_ERR_INVALID_ARGUMENT;
        if (rv) break;
        if (g->side)
            for (size_t i = 0; i < (size_t)W * (size_t)ci.height; i++)
                sidebuf[i] = g->side[(size_t)y * (size_t)W + i] > 0 ? 0x3C00 : 0xBC00;
        *step = "encoder setup";
        rv = y == 0 ? exr_encoding_initialize(x, 0, &ci, &enc) : exr_encoding_update(x, 0, &ci, &enc);
        if (rv) break;
        bind(enc.channels, enc.channel_count, ch, n, W, y, sidebuf, y, 1);
        if (y == 0) {
            *step = "choose encoder";
            rv = exr_encoding_choose_default_routines(x, 0, &enc);
            if (rv) break;
        }
        *step = "encode";
        rv = exr_encoding_run(x, 0, &enc);
    }
    exr_result_t drv = exr_encoding_destroy(x, &enc);
    return rv ? rv : drv;
}

dfl_status dfl_proxy_exr_save(const dfl_proxy_grid *g, const char *path, dfl_err *err)
{
    if (!g || !g->data || !path || !path[0])
        return dfl_err_set(err, DFL_E_INPUT, "proxy exr: no grid or empty path");
    if ((size_t)g->res * (size_t)g->res > INT32_MAX)
        return dfl_err_set(err, DFL_E_INPUT, "%s: grid too large for one EXR image", path);
    chan ch[MAXCH];
    const int n = channels(g, ch);
    uint16_t *sidebuf = NULL; /* one chunk: ZIP has 16 lines, at most SIDE_LINES */
    if (g->side && !(sidebuf = malloc((size_t)g->res * SIDE_LINES * 2)))
        return dfl_err_set(err, DFL_E_NOMEM, "%s: out of memory", path);
    dfl_atomic_file af;
    dfl_status st = dfl_atomic_open(path, &af, err);
    if (st) {
        free(sidebuf);
        return st;
    }
    fclose(af.fp);
    af.fp = NULL;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = quiet;
    exr_context_t x = NULL;
    const char *step = "start write";
    exr_result_t rv = exr_start_write(&x, af.tmp, EXR_WRITE_FILE_DIRECTLY, &init);
    if (!rv) rv = exr_add_part(x, NULL, EXR_STORAGE_SCANLINE, NULL), step = "add part";
    if (!rv)
        rv = exr_initialize_required_attr_simple(x, 0, g->res, g->res * g->res, EXR_COMPRESSION_ZIP),
        step = "required attributes";
    for (int i = 0; !rv && i < n; i++)
        rv = exr_add_channel(x, 0, ch[i].name, ch[i].type, EXR_PERCEPTUALLY_LINEAR, 1, 1),
        step = "add channel";
    if (!rv) rv = put_attrs(x, g), step = "attributes";
    if (!rv) rv = exr_write_header(x), step = "write header";
    if (!rv) rv = encode(x, g, ch, n, sidebuf, &step);
    if (x) {
        exr_result_t frv = exr_finish(&x);
        if (!rv && frv) rv = frv, step = "finish";
    }
    free(sidebuf);
    if (rv) {
        dfl_atomic_abort(&af);
        return fail(err, rv, path, step);
    }
    if (rename(af.tmp, af.path) != 0) {
        const int e = errno;
        dfl_atomic_abort(&af);
        return dfl_err_set(err, DFL_E_IO, "%s: cannot rename from %s: %s", path, af.tmp,
                           strerror(e));
    }
    return DFL_OK;
}

/* Reads the attributes into build options; a missing one is not a grid. */
static dfl_status get_attrs(exr_context_t x, const char *path, dfl_proxy_build_opts *o,
                            int *has_inside, dfl_proxy_stats *stats, dfl_err *err)
{
    int32_t order, res, hin;
    exr_attr_v3d_t lo, hi;
    const char *sto = NULL, *pos = NULL;
    int32_t ls = 0, lp = 0;
    double u, f, m;
    exr_result_t rv = exr_attr_get_int(x, 0, "dflab.proxy.order", &order);
    if (!rv) rv = exr_attr_get_int(x, 0, "dflab.proxy.res", &res);
    if (!rv) rv = exr_attr_get_v3d(x, 0, "dflab.proxy.lo", &lo);
    if (!rv) rv = exr_attr_get_v3d(x, 0, "dflab.proxy.hi", &hi);
    if (!rv) rv = exr_attr_get_string(x, 0, "dflab.proxy.storage", &ls, &sto);
    if (!rv) rv = exr_attr_get_string(x, 0, "dflab.proxy.position", &lp, &pos);
    if (!rv) rv = exr_attr_get_int(x, 0, "dflab.proxy.has_inside", &hin);
    if (!rv) rv = exr_attr_get_double(x, 0, "dflab.proxy.uncertified", &u);
    if (!rv) rv = exr_attr_get_double(x, 0, "dflab.proxy.failed", &f);
    if (!rv) rv = exr_attr_get_double(x, 0, "dflab.proxy.moved", &m);
    if (rv) return dfl_err_set(err, DFL_E_IO, "%s: not a dflab proxy grid (attributes)", path);
    dfl_proxy_build_opts_default(o);
    o->order = order;
    o->res = res;
    o->lo[0] = lo.x, o->lo[1] = lo.y, o->lo[2] = lo.z;
    o->hi[0] = hi.x, o->hi[1] = hi.y, o->hi[2] = hi.z;
    char s1[16], s2[16];
    snprintf(s1, sizeof s1, "%.*s", (int)ls, sto);
    snprintf(s2, sizeof s2, "%.*s", (int)lp, pos);
    if (dfl_proxy_storage_parse(s1, &o->storage, NULL) ||
        dfl_proxy_position_parse(s2, &o->position, NULL))
        return dfl_err_set(err, DFL_E_IO, "%s: not a dflab proxy grid (storage '%s', position '%s')",
                           path, s1, s2);
    *has_inside = hin != 0;
    stats->uncertified = (size_t)u;
    stats->failed = (size_t)f;
    stats->moved = (size_t)m;
    /* absent from grids written before the count existed: none clamped */
    double cl = 0;
    if (exr_attr_get_double(x, 0, "dflab.proxy.clamped", &cl) != EXR_ERR_SUCCESS) cl = 0;
    stats->clamped = (size_t)cl;
    return DFL_OK;
}

/* The file's channel list must be exactly the grid's. */
static int same_channels(exr_const_context_t x, const chan *ch, int n)
{
    const exr_attr_chlist_t *cl = NULL;
    if (exr_get_channels(x, 0, &cl) || cl->num_channels != n) return 0;
    for (int i = 0; i < n; i++) {
        const exr_attr_chlist_entry_t *e = &cl->entries[i];
        if (strcmp(e->name.str, ch[i].name) || e->pixel_type != ch[i].type ||
            e->x_sampling != 1 || e->y_sampling != 1)
            return 0;
    }
    return 1;
}

static exr_result_t decode(exr_context_t x, dfl_proxy_grid *g, chan *ch, int n,
                           uint16_t *sidebuf, const char **step)
{
    const int W = g->res, H = g->res * g->res;
    int32_t lpc = 0;
    *step = "scanlines per chunk";
    exr_result_t rv = exr_get_scanlines_per_chunk(x, 0, &lpc);
    if (!rv && (lpc < 1 || lpc > SIDE_LINES)) rv = EXR_ERR_FILE_BAD_HEADER;
    exr_decode_pipeline_t dec = EXR_DECODE_PIPELINE_INITIALIZER;
    for (int y = 0; !rv && y < H; y += lpc) {
        exr_chunk_info_t ci;
        *step = "chunk info";
        rv = exr_read_scanline_chunk_info(x, 0, y, &ci);
        if (rv) break;
        if (ci.start_y != y || ci.width != W || ci.height < 1 || ci.height > lpc) {
            rv = EXR_ERR_CORRUPT_CHUNK;
            break;
        }
        *step = "decoder setup";
        rv = y == 0 ? exr_decoding_initialize(x, 0, &ci, &dec) : exr_decoding_update(x, 0, &ci, &dec);
        if (rv) break;
        bind(dec.channels, dec.channel_count, ch, n, W, y, sidebuf, y, 0);
        if (y == 0) {
            *step = "choose decoder";
            rv = exr_decoding_choose_default_routines(x, 0, &dec);
            if (rv) break;
        }
        *step = "decode";
        rv = exr_decoding_run(x, 0, &dec);
        if (!rv && g->side)
            for (size_t i = 0; i < (size_t)W * (size_t)ci.height; i++)
                g->side[(size_t)y * (size_t)W + i] = sidebuf[i] == 0xBC00 ? -1 : 1;
    }
    exr_result_t drv = exr_decoding_destroy(x, &dec);
    return rv ? rv : drv;
}

dfl_status dfl_proxy_exr_load(const char *path, dfl_proxy_grid *out, dfl_err *err)
{
    memset(out, 0, sizeof *out);
    if (!path || !path[0]) return dfl_err_set(err, DFL_E_INPUT, "proxy exr: empty path");
    FILE *probe = fopen(path, "rb");
    if (!probe) return dfl_err_set(err, DFL_E_IO, "%s: cannot open for reading", path);
    fclose(probe);
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = quiet;
    exr_context_t x = NULL;
    exr_result_t rv = exr_start_read(&x, path, &init);
    if (rv) {
        if (x) exr_finish(&x);
        return fail(err, rv, path, "open");
    }
    dfl_proxy_build_opts o;
    int hin = 0;
    dfl_proxy_stats stats;
    dfl_proxy_grid g;
    memset(&g, 0, sizeof g);
    dfl_status st = get_attrs(x, path, &o, &hin, &stats, err);
    if (!st) {
        st = dfl_proxy_grid_alloc(&o, hin, o.order == 1 && hin, &g, err);
        if (st == DFL_E_INPUT) {
            dfl_err_prefix(err, "%s: not a dflab proxy grid", path);
            st = DFL_E_IO;
        }
    }
    chan ch[MAXCH];
    int n = 0;
    exr_attr_box2i_t dw;
    if (!st) {
        n = channels(&g, ch);
        if (exr_get_data_window(x, 0, &dw) || dw.min.x != 0 || dw.min.y != 0 ||
            dw.max.x != g.res - 1 || (int64_t)dw.max.y != (int64_t)g.res * g.res - 1 ||
            !same_channels(x, ch, n))
            st = dfl_err_set(err, DFL_E_IO, "%s: not a dflab proxy grid (size or channels)", path);
    }
    uint16_t *sidebuf = NULL;
    if (!st && g.side && !(sidebuf = malloc((size_t)g.res * SIDE_LINES * 2)))
        st = dfl_err_set(err, DFL_E_NOMEM, "%s: out of memory", path);
    const char *step = "decode";
    if (!st) {
        rv = decode(x, &g, ch, n, sidebuf, &step);
        if (rv) st = fail(err, rv, path, step);
    }
    free(sidebuf);
    exr_finish(&x);
    if (st) {
        dfl_proxy_grid_free(&g);
        return st;
    }
    g.stats = stats;
    *out = g;
    return DFL_OK;
}
