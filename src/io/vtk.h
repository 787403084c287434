/* VTK XML writers: .vti (ImageData) for sampled fields, .vtp (PolyData) for
 * polylines and triangulations, .pvd (Collection) for a sequence of them.
 *
 * Files are VTK XML version 1.0, little endian, header_type UInt64, with all
 * arrays in one binary <AppendedData encoding="raw"> block, so ParaView and
 * VTK's vtkXMLImageDataReader / vtkXMLPolyDataReader open them directly.
 * With compress != 0 every array is zlib-compressed in blocks of
 * DFL_VTK_ZLIB_BLOCK bytes (vtkZLibDataCompressor layout).
 *
 * Both writers go through a temporary file that is renamed over path when
 * complete: on any failure nothing is left at path (an existing file there is
 * untouched) and no temporary file remains.
 *
 * Errors: DFL_E_INPUT for invalid arguments (message says which), DFL_E_IO
 * (message names path) when the file cannot be written, DFL_E_NOMEM.
 * The writers allocate only per call (conversion and compression buffers)
 * and free everything before returning; they are safe to call concurrently
 * on different paths.
 */
#ifndef DFL_IO_VTK_H
#define DFL_IO_VTK_H

#include <stddef.h>

#include "core/status.h"

/* Uncompressed size of one zlib block in compressed files (bytes). */
#define DFL_VTK_ZLIB_BLOCK 32768

typedef struct dfl_vtk_array {
    const char *name;     /* e.g. "value", "gradient"; non-empty, XML-escaped on output */
    int ncomp;            /* 1 (scalar) or 3 (vector; 2D gradients are padded with 0 by the caller);
                             any value in 1..9 is accepted */
    const double *data;   /* npoints*ncomp values, point-major (tuple i at data[i*ncomp]) */
} dfl_vtk_array;

/* Writes ImageData with dims[0]*dims[1]*dims[2] points, x fastest (point
 * (i,j,k) is tuple i + dims[0]*(j + dims[1]*k), at origin + (i,j,k)*spacing).
 * 2D grids use dims[2] = 1.  Arrays are written as Float64 point data,
 * binary appended (raw), zlib-compressed when compress != 0.  The point data
 * gets Scalars="value" if an array named "value" exists and
 * Vectors="gradient" if an array named "gradient" with 3 components exists.
 * Requires: dims[i] >= 1, origin finite, spacing finite and > 0, arrays
 * non-NULL with narrays >= 1, each array valid (see dfl_vtk_array), names
 * unique.  Values may be any double (NaN/inf are written as is). */
dfl_status dfl_vti_write(const char *path, const int dims[3], const double origin[3],
                         const double spacing[3], const dfl_vtk_array *arrays, int narrays,
                         int compress, dfl_err *err);

/* The number of cells of ImageData with dims points: the product over the
 * axes of dims[i] - 1, an axis of one point counting 1 (a 2D image's cells
 * are its squares).  dims[i] >= 1. */
size_t dfl_vti_ncells(const int dims[3]);

/* dfl_vti_write with cell data too: ncells arrays (cells may be NULL when
 * ncells == 0) of dfl_vti_ncells(dims) tuples each, cell (i,j,k) at tuple
 * i + c0*(j + c1*k) with c = the per-axis cell counts, written as Float64
 * <CellData>.  Cell array names are unique among themselves and distinct
 * from the point arrays' (DFL_E_INPUT otherwise). */
dfl_status dfl_vti_write_cells(const char *path, const int dims[3], const double origin[3],
                               const double spacing[3], const dfl_vtk_array *arrays, int narrays,
                               const dfl_vtk_array *cells, int ncells, int compress, dfl_err *err);

/* One data set of a ParaView collection: file (relative to the .pvd's
 * folder, as ParaView resolves it) at time `time` (finite). */
typedef struct dfl_pvd_entry {
    const char *file;
    double time;
} dfl_pvd_entry;

/* Writes a VTK Collection (.pvd) listing the n data sets in order, each a
 * <DataSet timestep=time file=...> (the time is what ParaView's time
 * slider scrubs through).  n may be 0.  DFL_E_INPUT for an empty path, a
 * missing file name or a non-finite time; DFL_E_IO naming path.  Atomic as
 * the other writers. */
dfl_status dfl_pvd_write(const char *path, const dfl_pvd_entry *e, size_t n, dfl_err *err);

typedef struct dfl_vtp_data {
    size_t npoints; const double *points;          /* 3*npoints */
    size_t nlines;  const size_t *line_offsets;     /* nlines+1 offsets into line_conn (first 0) */
    const size_t *line_conn;                        /* point indices of polylines */
    size_t ntris;   const size_t *tris;             /* 3*ntris point indices */
    const dfl_vtk_array *point_arrays; int narrays; /* optional point data (npoints tuples) */
} dfl_vtp_data;

/* Writes PolyData: Points (Float64), Lines (polyline i = line_conn[
 * line_offsets[i] .. line_offsets[i+1]-1]) and Polys (triangles), with
 * Int64 connectivity/offsets (offsets are cell ends, as VTK requires), and
 * optional Float64 point data (Scalars/Vectors attributes as in
 * dfl_vti_write).  Pointers may be NULL when the matching count is 0
 * (line_offsets may be NULL when nlines == 0).  Requires line_offsets[0] == 0,
 * non-decreasing offsets, every point index < npoints, unique array names.
 * Cells are not otherwise checked (a polyline of one point is allowed). */
dfl_status dfl_vtp_write(const char *path, const dfl_vtp_data *d, int compress, dfl_err *err);

#endif
