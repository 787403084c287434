/* Provenance attached to files already written: VTK XML FieldData and
 * OpenEXR header attributes (meta_attrs.c).
 *
 * Function index
 *   dfl_vtk_add_field_data   string arrays in a .vti/.vtp's FieldData
 *   dfl_exr_add_attrs        string attributes in an .exr's header
 *
 * Both rewrite the file through a temporary file renamed on success (an
 * existing file is untouched on failure) and fail with DFL_E_IO naming the
 * path (DFL_E_NOMEM when out of memory).  Names must be non-empty; values
 * any text.
 */
#ifndef DFL_IO_META_ATTRS_H
#define DFL_IO_META_ATTRS_H

#include <stddef.h>

#include "core/status.h"

/* Inserts <FieldData> with one single-tuple String array per name (after
 * the dataset's opening tag; appended binary data is addressed relative to
 * its own start, so it stays valid).  VTK's readers give them as
 * GetFieldData().GetAbstractArray(name).GetValue(0).  A file that already
 * has FieldData is left as it is. */
dfl_status dfl_vtk_add_field_data(const char *path, size_t n, const char *const *names,
                                  const char *const *values, dfl_err *err);

/* Copies the scanline image at path with the string attributes name =
 * value added to its header (replacing attributes of the same name); the
 * pixel data chunks are copied as stored, so pixels do not change. */
dfl_status dfl_exr_add_attrs(const char *path, size_t n, const char *const *names,
                             const char *const *values, dfl_err *err);

#endif
