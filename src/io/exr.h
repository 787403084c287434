/* OpenEXR image output (and a channel reader for tests and tools), through
 * the OpenEXR 3.1 C library (OpenEXRCore).
 *
 * Images are single-part scanline files with ZIP compression (lossless),
 * data window (0,0)-(width-1,height-1), one sample per pixel per channel.
 * Pixel (x, y) of a channel is data[y*width + x]; row 0 is the top row
 * (EXR's y axis points down).
 *
 * The library's diagnostics never reach stderr: they are swallowed and the
 * failure is reported through dfl_err instead.
 */
#ifndef DFL_IO_EXR_H
#define DFL_IO_EXR_H

#include "core/status.h"

typedef struct dfl_exr_channel {
    const char *name;  /* non-empty, unique within one image */
    const float *data; /* width*height floats, row-major, row 0 at the top */
} dfl_exr_channel;

/* Writes a scanline image width x height (both >= 1) with nch >= 1 channels.
 * half != 0 stores HALF channels (the input is still float; values are
 * rounded to nearest even half, |v| >= 65520 becomes +-inf), else FLOAT
 * (bit-exact).  Channels may be given in any order; the file lists them
 * sorted by name, as EXR requires.  The file is written under a temporary
 * name and renamed over path when complete: on failure nothing is left
 * behind and an existing file at path is untouched.
 * Errors: DFL_E_INPUT (bad sizes, NULL/empty channel list, empty or
 * duplicate name, NULL data), DFL_E_IO naming path (cannot create, write or
 * rename), DFL_E_NOMEM. */
dfl_status dfl_exr_write(const char *path, int width, int height, const dfl_exr_channel *ch,
                         int nch, int half, dfl_err *err);

/* Reads the channel called name from the first part of a scanline EXR file
 * (any pixel type and compression the library decodes) into a malloc'ed
 * float buffer of *width x *height values, row 0 at the top; the caller frees
 * *data.  The data window origin need not be (0,0): pixels are stored
 * relative to it.  Subsampled channels are rejected.
 * Errors: DFL_E_IO naming path (missing/unreadable/corrupt file, tiled or
 * deep file), DFL_E_INPUT (no channel of that name), DFL_E_NOMEM.  On error
 * *data is NULL and *width, *height are 0. */
dfl_status dfl_exr_read_channel(const char *path, const char *name, int *width, int *height,
                                float **data, dfl_err *err);

#endif
