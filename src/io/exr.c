/* OpenEXR writer/reader on the OpenEXRCore C API (3.1).
 *
 * Atomicity: the file is written under dfl_atomic_tmpname(path) in
 * EXR_WRITE_FILE_DIRECTLY mode and renamed here, rather than with the
 * library's EXR_INTERMEDIATE_TEMP_FILE, so that the temporary name is the
 * project-wide one and the temporary is always removed on failure.  The temp
 * file is first created with dfl_atomic_open, which gives an error message
 * with strerror (the library's own message would only reach its handler).
 *
 * Diagnostics: the library sends messages to error_handler_fn, and with the
 * default file I/O the context's user_data is the library's file handle, so
 * a handler cannot reach per-call storage without global state.  The handler
 * therefore drops the message; errors are reported from the result code
 * (exr_get_default_error_message) plus the step that failed.
 *
 * Half storage: the encoder converts float input to HALF when the channel's
 * user_data_type is FLOAT (DESIGN.md, verified facts), so no extra buffer is
 * needed and rounding is the library's round-to-nearest-even.
 */
#include "io/exr.h"

#include <assert.h>
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <openexr.h>

#include "io/atomic.h"

static void quiet_handler(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    (void)ctxt;
    (void)code;
    (void)msg;
}

static exr_context_initializer_t quiet_init(void)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = quiet_handler;
    return init;
}

static dfl_status exr_fail(dfl_err *err, exr_result_t rv, const char *path, const char *step)
{
    dfl_status code = rv == EXR_ERR_OUT_OF_MEMORY ? DFL_E_NOMEM : DFL_E_IO;
    return dfl_err_set(err, code, "%s: OpenEXR %s failed: %s", path, step,
                       exr_get_default_error_message(rv));
}

static dfl_status check_channels(const char *path, int width, int height,
                                 const dfl_exr_channel *ch, int nch, dfl_err *err)
{
    if (width < 1 || height < 1)
        return dfl_err_set(err, DFL_E_INPUT, "%s: image size %dx%d (must be >= 1x1)", path,
                           width, height);
    if ((size_t)width > SIZE_MAX / sizeof(float) / (size_t)height || width > INT32_MAX / 4)
        return dfl_err_set(err, DFL_E_INPUT, "%s: image %dx%d too large", path, width, height);
    if (!ch || nch <= 0) return dfl_err_set(err, DFL_E_INPUT, "%s: no channels to write", path);
    for (int i = 0; i < nch; i++) {
        if (!ch[i].name || !ch[i].name[0])
            return dfl_err_set(err, DFL_E_INPUT, "%s: channel %d has no name", path, i);
        if (strlen(ch[i].name) > 255)
            return dfl_err_set(err, DFL_E_INPUT, "%s: channel name '%.40s...' too long", path,
                               ch[i].name);
        if (!ch[i].data)
            return dfl_err_set(err, DFL_E_INPUT, "%s: channel '%s' has no data", path,
                               ch[i].name);
        for (int j = 0; j < i; j++)
            if (strcmp(ch[i].name, ch[j].name) == 0)
                return dfl_err_set(err, DFL_E_INPUT, "%s: duplicate channel name '%s'", path,
                                   ch[i].name);
    }
    return DFL_OK;
}

/* Index of the caller's channel called name; the name comes from the
 * library's channel list, built from these same names. */
static int channel_index(const dfl_exr_channel *ch, int nch, const char *name)
{
    for (int i = 0; i < nch; i++)
        if (strcmp(ch[i].name, name) == 0) return i;
    return -1;
}

/* Encodes all scanline chunks of part 0.  enc is initialized here and must
 * be destroyed by the caller (also on failure). */
static exr_result_t encode_all(exr_context_t ctx, int width, int height,
                               const dfl_exr_channel *ch, int nch, exr_encode_pipeline_t *enc,
                               const char **step)
{
    int32_t lpc = 0;
    exr_result_t rv = exr_get_scanlines_per_chunk(ctx, 0, &lpc);
    *step = "scanlines per chunk";
    if (rv) return rv;
    assert(lpc >= 1);
    int first = 1;
    for (int y = 0; y < height; y += lpc) {
        exr_chunk_info_t ci;
        *step = "chunk info";
        rv = exr_write_scanline_chunk_info(ctx, 0, y, &ci);
        if (rv) return rv;
        assert(ci.start_y == y && ci.width == width && ci.height >= 1);
        *step = "encoder setup";
        rv = first ? exr_encoding_initialize(ctx, 0, &ci, enc)
                   : exr_encoding_update(ctx, 0, &ci, enc);
        if (rv) return rv;
        assert(enc->channel_count == nch);
        for (int c = 0; c < enc->channel_count; c++) {
            exr_coding_channel_info_t *cc = &enc->channels[c];
            int k = channel_index(ch, nch, cc->channel_name);
            assert(k >= 0);
            cc->user_data_type = EXR_PIXEL_FLOAT;
            cc->user_bytes_per_element = (int16_t)sizeof(float);
            cc->user_pixel_stride = (int32_t)sizeof(float);
            cc->user_line_stride = (int32_t)sizeof(float) * width;
            cc->encode_from_ptr = (const uint8_t *)(ch[k].data + (size_t)y * (size_t)width);
        }
        if (first) {
            *step = "choose encoder";
            rv = exr_encoding_choose_default_routines(ctx, 0, enc);
            if (rv) return rv;
        }
        *step = "encode";
        rv = exr_encoding_run(ctx, 0, enc);
        if (rv) return rv;
        first = 0;
    }
    return EXR_ERR_SUCCESS;
}

static int cmp_names(const void *a, const void *b)
{
    const dfl_exr_channel *const *x = a, *const *y = b;
    return strcmp((*x)->name, (*y)->name);
}

dfl_status dfl_exr_write(const char *path, int width, int height, const dfl_exr_channel *ch,
                         int nch, int half, dfl_err *err)
{
    if (!path || !path[0]) return dfl_err_set(err, DFL_E_INPUT, "exr: empty output path");
    dfl_status st = check_channels(path, width, height, ch, nch, err);
    if (st) return st;

    /* EXR stores channels sorted by name (strcmp order). */
    const dfl_exr_channel **sorted = malloc((size_t)nch * sizeof *sorted);
    if (!sorted) return dfl_err_set(err, DFL_E_NOMEM, "%s: out of memory", path);
    for (int i = 0; i < nch; i++) sorted[i] = &ch[i];
    qsort(sorted, (size_t)nch, sizeof *sorted, cmp_names);

    dfl_atomic_file af;
    st = dfl_atomic_open(path, &af, err);
    if (st) {
        free(sorted);
        return st;
    }
    fclose(af.fp); /* the library reopens (and truncates) af.tmp itself */
    af.fp = NULL;

    exr_context_initializer_t init = quiet_init();
    exr_context_t ctx = NULL;
    const char *step = "start write";
    exr_result_t rv = exr_start_write(&ctx, af.tmp, EXR_WRITE_FILE_DIRECTLY, &init);
    if (!rv) {
        step = "add part";
        rv = exr_add_part(ctx, NULL, EXR_STORAGE_SCANLINE, NULL);
    }
    if (!rv) {
        step = "required attributes";
        rv = exr_initialize_required_attr_simple(ctx, 0, width, height, EXR_COMPRESSION_ZIP);
    }
    for (int i = 0; !rv && i < nch; i++) {
        if (strlen(sorted[i]->name) > 31) {
            step = "long names";
            rv = exr_set_longname_support(ctx, 1);
            if (rv) break;
        }
        step = "add channel";
        rv = exr_add_channel(ctx, 0, sorted[i]->name, half ? EXR_PIXEL_HALF : EXR_PIXEL_FLOAT,
                             EXR_PERCEPTUALLY_LINEAR, 1, 1);
    }
    free(sorted);
    if (!rv) {
        step = "write header";
        rv = exr_write_header(ctx);
    }
    if (!rv) {
        exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
        rv = encode_all(ctx, width, height, ch, nch, &enc, &step);
        exr_result_t drv = exr_encoding_destroy(ctx, &enc);
        if (!rv && drv) {
            rv = drv;
            step = "encoder cleanup";
        }
    }
    if (ctx) {
        /* exr_finish writes the chunk offset table and closes the file. */
        exr_result_t frv = exr_finish(&ctx);
        if (!rv && frv) {
            rv = frv;
            step = "finish";
        }
    }
    if (rv) {
        dfl_atomic_abort(&af);
        return exr_fail(err, rv, path, step);
    }
    if (rename(af.tmp, af.path) != 0) {
        int e = errno;
        dfl_atomic_abort(&af);
        return dfl_err_set(err, DFL_E_IO, "%s: cannot rename from %s: %s", path, af.tmp,
                           strerror(e));
    }
    return DFL_OK;
}

/* Decodes channel `want` of part 0 (scanline) into out (w*h floats).
 *
 * Every channel gets a FLOAT destination, the unwanted ones a scratch area:
 * OpenEXRCore 3.1.5 picks specialised HALF->FLOAT unpackers that write all
 * channels and crash on the NULL pointers its documentation allows for
 * skipped channels (found by tests/io/test_exr.c on a 3-channel HALF file). */
static exr_result_t decode_all(exr_context_t ctx, const exr_attr_box2i_t *dw, int nch,
                               const char *want, float *out, exr_decode_pipeline_t *dec,
                               const char **step)
{
    int w = dw->max.x - dw->min.x + 1;
    int32_t lpc = 0;
    *step = "scanlines per chunk";
    exr_result_t rv = exr_get_scanlines_per_chunk(ctx, 0, &lpc);
    if (rv) return rv;
    if (lpc < 1) return EXR_ERR_FILE_BAD_HEADER;
    size_t chunk_floats = (size_t)w * (size_t)lpc;
    float *scratch = malloc((size_t)nch * chunk_floats * sizeof *scratch);
    if (!scratch) return EXR_ERR_OUT_OF_MEMORY;
    int first = 1;
    rv = EXR_ERR_SUCCESS;
    for (int y = dw->min.y; y <= dw->max.y; y += lpc) {
        exr_chunk_info_t ci;
        *step = "chunk info";
        rv = exr_read_scanline_chunk_info(ctx, 0, y, &ci);
        if (rv) break;
        if (ci.start_y < dw->min.y || ci.start_y + ci.height - 1 > dw->max.y ||
            ci.width != w || ci.height > lpc) {
            rv = EXR_ERR_CORRUPT_CHUNK;
            break;
        }
        *step = "decoder setup";
        rv = first ? exr_decoding_initialize(ctx, 0, &ci, dec)
                   : exr_decoding_update(ctx, 0, &ci, dec);
        if (rv) break;
        if (dec->channel_count != nch) {
            rv = EXR_ERR_INCORRECT_CHUNK;
            break;
        }
        for (int c = 0; c < dec->channel_count; c++) {
            exr_coding_channel_info_t *cc = &dec->channels[c];
            cc->user_data_type = EXR_PIXEL_FLOAT;
            cc->user_bytes_per_element = (int16_t)sizeof(float);
            cc->user_pixel_stride = (int32_t)sizeof(float);
            cc->user_line_stride = (int32_t)sizeof(float) * w;
            float *dst = strcmp(cc->channel_name, want) == 0
                             ? out + (size_t)(ci.start_y - dw->min.y) * (size_t)w
                             : scratch + (size_t)c * chunk_floats;
            cc->decode_to_ptr = (uint8_t *)dst;
        }
        if (first) {
            *step = "choose decoder";
            rv = exr_decoding_choose_default_routines(ctx, 0, dec);
            if (rv) break;
        }
        *step = "decode";
        rv = exr_decoding_run(ctx, 0, dec);
        if (rv) break;
        first = 0;
    }
    free(scratch);
    return rv;
}

dfl_status dfl_exr_read_channel(const char *path, const char *name, int *width, int *height,
                                float **data, dfl_err *err)
{
    *width = 0;
    *height = 0;
    *data = NULL;
    if (!path || !path[0]) return dfl_err_set(err, DFL_E_INPUT, "exr: empty input path");
    if (!name || !name[0]) return dfl_err_set(err, DFL_E_INPUT, "%s: empty channel name", path);
    FILE *probe = fopen(path, "rb");
    if (!probe) return dfl_err_set(err, DFL_E_IO, "%s: cannot open for reading", path);
    fclose(probe);

    exr_context_initializer_t init = quiet_init();
    exr_context_t ctx = NULL;
    exr_result_t rv = exr_start_read(&ctx, path, &init);
    if (rv) {
        if (ctx) exr_finish(&ctx);
        return exr_fail(err, rv, path, "open");
    }
    dfl_status st = DFL_OK;
    const char *step = "storage";
    exr_storage_t storage;
    exr_attr_box2i_t dw;
    const exr_attr_chlist_t *chl = NULL;
    rv = exr_get_storage(ctx, 0, &storage);
    if (!rv && storage != EXR_STORAGE_SCANLINE) {
        st = dfl_err_set(err, DFL_E_IO, "%s: not a flat scanline image (storage %d)", path,
                         (int)storage);
    }
    if (!rv && !st) {
        step = "data window";
        rv = exr_get_data_window(ctx, 0, &dw);
    }
    if (!rv && !st) {
        step = "channel list";
        rv = exr_get_channels(ctx, 0, &chl);
    }
    int64_t w = 0, h = 0;
    if (!rv && !st) {
        w = (int64_t)dw.max.x - dw.min.x + 1;
        h = (int64_t)dw.max.y - dw.min.y + 1;
        if (w < 1 || h < 1 || w > INT32_MAX / 4 || (uint64_t)w * (uint64_t)h > SIZE_MAX / 4)
            st = dfl_err_set(err, DFL_E_IO, "%s: bad data window", path);
    }
    if (!rv && !st) {
        const exr_attr_chlist_entry_t *e = NULL;
        for (int i = 0; i < chl->num_channels; i++)
            if (strcmp(chl->entries[i].name.str, name) == 0) e = &chl->entries[i];
        if (!e)
            st = dfl_err_set(err, DFL_E_INPUT, "%s: no channel named '%s'", path, name);
        else if (e->x_sampling != 1 || e->y_sampling != 1)
            st = dfl_err_set(err, DFL_E_IO, "%s: channel '%s' is subsampled", path, name);
    }
    float *out = NULL;
    if (!rv && !st) {
        out = malloc((size_t)w * (size_t)h * sizeof *out);
        if (!out) st = dfl_err_set(err, DFL_E_NOMEM, "%s: out of memory", path);
    }
    if (!rv && !st) {
        exr_decode_pipeline_t dec = EXR_DECODE_PIPELINE_INITIALIZER;
        rv = decode_all(ctx, &dw, chl->num_channels, name, out, &dec, &step);
        exr_decoding_destroy(ctx, &dec);
    }
    exr_finish(&ctx);
    if (rv && !st) st = exr_fail(err, rv, path, step);
    if (st) {
        free(out);
        return st;
    }
    *width = (int)w;
    *height = (int)h;
    *data = out;
    return DFL_OK;
}
