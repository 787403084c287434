/* Attaching provenance after the fact keeps the writers (io/vtk.c,
 * io/exr.c) and every study unaware of it: the runner adds the same
 * fields to every file a sweep point wrote. */
#include "io/meta_attrs.h"

#include <openexr.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/atomic.h"
#include "io/dirs.h"

static void put_xml_attr(FILE *fp, const char *s)
{
    for (; *s; s++) {
        if (*s == '"') fputs("&quot;", fp);
        else if (*s == '&') fputs("&amp;", fp);
        else if (*s == '<') fputs("&lt;", fp);
        else fputc(*s, fp);
    }
}

dfl_status dfl_vtk_add_field_data(const char *path, size_t n, const char *const *names,
                                  const char *const *values, dfl_err *err)
{
    size_t len = 0;
    char *text = dfl_file_read_all(path, &len);
    if (!text) return dfl_err_set(err, DFL_E_IO, "%s: cannot read", path);
    /* the header ends where appended data begins */
    char *app = strstr(text, "<AppendedData");
    if (app) *app = '\0';
    char *ds = strstr(text, "<ImageData");
    if (!ds) ds = strstr(text, "<PolyData");
    const int has = strstr(text, "<FieldData") != NULL;
    char *gt = ds ? strchr(ds, '>') : NULL;
    if (app) *app = '<';
    if (!gt || has) {
        free(text);
        return gt ? DFL_OK : dfl_err_set(err, DFL_E_IO, "%s: not a VTK XML ImageData/PolyData file",
                                         path);
    }
    dfl_atomic_file af;
    dfl_status st = dfl_atomic_open(path, &af, err);
    if (st == DFL_OK) {
        const size_t head = (size_t)(gt + 1 - text);
        fwrite(text, 1, head, af.fp);
        fputs("\n    <FieldData>\n", af.fp);
        for (size_t i = 0; i < n; i++) {
            fputs("      <DataArray type=\"String\" Name=\"", af.fp);
            put_xml_attr(af.fp, names[i]);
            fputs("\" NumberOfTuples=\"1\" format=\"ascii\">\n        ", af.fp);
            for (const unsigned char *c = (const unsigned char *)values[i]; *c; c++)
                fprintf(af.fp, "%u ", *c);
            fputs("0\n      </DataArray>\n", af.fp);
        }
        fputs("    </FieldData>", af.fp);
        fwrite(text + head, 1, len - head, af.fp);
        st = dfl_atomic_commit(&af, err);
    }
    free(text);
    return st;
}

static void quiet(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    (void)ctxt, (void)code, (void)msg;
}

/* Copies every chunk of part 0 of in to out as stored. */
static exr_result_t copy_chunks(exr_context_t in, exr_context_t out, const char **step)
{
    exr_attr_box2i_t dw;
    int32_t nchunks = 0, lpc = 0;
    *step = "read layout";
    exr_result_t rv = exr_get_data_window(in, 0, &dw);
    if (!rv) rv = exr_get_chunk_count(in, 0, &nchunks);
    if (!rv) rv = exr_get_scanlines_per_chunk(in, 0, &lpc);
    void *buf = NULL;
    size_t cap = 0;
    for (int32_t c = 0; !rv && c < nchunks; c++) {
        const int y = dw.min.y + c * lpc;
        exr_chunk_info_t ci;
        *step = "read chunk";
        rv = exr_read_scanline_chunk_info(in, 0, y, &ci);
        if (!rv && ci.packed_size > cap) {
            void *b = realloc(buf, cap = (size_t)ci.packed_size);
            if (!b) rv = EXR_ERR_OUT_OF_MEMORY;
            else buf = b;
        }
        if (!rv) rv = exr_read_chunk(in, 0, &ci, buf);
        *step = "write chunk";
        if (!rv) rv = exr_write_scanline_chunk(out, 0, y, buf, ci.packed_size);
    }
    free(buf);
    return rv;
}

dfl_status dfl_exr_add_attrs(const char *path, size_t n, const char *const *names,
                             const char *const *values, dfl_err *err)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = quiet;
    exr_context_t in = NULL, out = NULL;
    const char *step = "open";
    exr_result_t rv = exr_start_read(&in, path, &init);
    dfl_atomic_file af = {0};
    dfl_status st = DFL_OK;
    if (!rv) {
        st = dfl_atomic_open(path, &af, err);
        if (st != DFL_OK) {
            exr_finish(&in);
            return st;
        }
        fclose(af.fp); /* the library writes af.tmp itself */
        af.fp = NULL;
        step = "start write";
        rv = exr_start_write(&out, af.tmp, EXR_WRITE_FILE_DIRECTLY, &init);
    }
    if (!rv) rv = exr_add_part(out, NULL, EXR_STORAGE_SCANLINE, NULL);
    if (!rv) {
        step = "copy header";
        rv = exr_copy_unset_attributes(out, 0, in, 0);
    }
    for (size_t i = 0; !rv && i < n; i++) {
        step = "set attribute";
        rv = exr_attr_set_string(out, 0, names[i], values[i]);
    }
    if (!rv) {
        step = "write header";
        rv = exr_write_header(out);
    }
    if (!rv) rv = copy_chunks(in, out, &step);
    if (out) {
        exr_result_t frv = exr_finish(&out);
        if (!rv) rv = frv;
    }
    if (in) exr_finish(&in);
    if (rv) {
        if (af.tmp[0]) dfl_atomic_abort(&af);
        return dfl_err_set(err, rv == EXR_ERR_OUT_OF_MEMORY ? DFL_E_NOMEM : DFL_E_IO,
                           "%s: OpenEXR %s failed: %s", path, step,
                           exr_get_default_error_message(rv));
    }
    if (rename(af.tmp, af.path) != 0) {
        dfl_atomic_abort(&af);
        return dfl_err_set(err, DFL_E_IO, "%s: cannot rename from %s", path, af.tmp);
    }
    return DFL_OK;
}
