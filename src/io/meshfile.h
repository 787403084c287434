/* Triangle mesh files: reading any format Assimp reads (OBJ, PLY, STL, OFF,
 * AC3D, ...; Assimp's C API, libassimp-dev) and writing OBJ or PLY.
 *
 * Function index
 *   dfl_meshfile_read    every triangle of a file, vertices welded by position
 *   dfl_meshfile_write   vertices and triangles as .obj or .ply (by extension)
 *   dfl_meshfile_free
 *
 * Reading.  The file must be a regular file (io/rfile.h: a FIFO never
 * blocks) of at most DFL_MESHFILE_MAX bytes; Assimp parses the bytes
 * (aiImportFileFromMemory, the file's extension as the format hint, so a
 * format's side files such as an OBJ's .mtl are not read: only geometry is
 * used) with aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
 * aiProcess_PreTransformVertices: polygons become triangles and the node
 * transforms are applied, so every mesh of the scene is in one coordinate
 * frame.  Faces that are points or lines are skipped and counted
 * (nskipped).  Vertices of all meshes are then welded where their
 * coordinates are equal as doubles (so seams that Assimp keeps apart for
 * different normals or texture coordinates are shared edges); the first
 * occurrence keeps its index order.  Triangle orientation is the file's.
 * Assimp (Debian's build) stores coordinates as floats: a file's numbers
 * are rounded to float on reading, and a coordinate beyond float range
 * reads as infinite (refused).  Meshes written by dfl_meshfile_write
 * therefore read back rounded to float.
 *
 * Refused with DFL_E_INPUT, the message starting "PATH: ": not a regular
 * file or unreadable, empty file, larger than DFL_MESHFILE_MAX, not a mesh
 * (Assimp's own message), no triangles, a non-finite vertex coordinate of
 * a triangle.  DFL_E_NOMEM.  Not checked here: degenerate triangles (the
 * mesh shape, geom/mesh.h, decides).
 *
 * Writing.  Plain ASCII, every coordinate in the shortest form that reads
 * back to the same double ("%.17g"), triangles 1-based (OBJ "f a b c") or
 * 0-based (PLY "3 a b c"), through an atomic file (io/atomic.h): a failed
 * write leaves nothing.  DFL_E_INPUT for another extension, DFL_E_IO. */
#ifndef DFL_IO_MESHFILE_H
#define DFL_IO_MESHFILE_H

#include <stddef.h>

#include "core/status.h"

#define DFL_MESHFILE_MAX ((size_t)1 << 30)

typedef struct dfl_meshfile {
    size_t nverts;
    double *verts;   /* 3 * nverts (only vertices used by a triangle) */
    size_t ntris;
    size_t *tris;    /* 3 * ntris indices into verts */
    size_t nskipped; /* point and line faces left out */
} dfl_meshfile;

/* Reads path into *out (caller frees with dfl_meshfile_free); *out is
 * zeroed on failure. */
dfl_status dfl_meshfile_read(const char *path, dfl_meshfile *out, dfl_err *err);

/* Writes the mesh to path (.obj or .ply, case-insensitive).  Indices must
 * be < nverts (asserted). */
dfl_status dfl_meshfile_write(const char *path, size_t nverts, const double *verts, size_t ntris,
                              const size_t *tris, dfl_err *err);

/* Frees and zeroes *m (NULL or zeroed is fine). */
void dfl_meshfile_free(dfl_meshfile *m);

#endif
