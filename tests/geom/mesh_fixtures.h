/* Small closed meshes with known geometry for the mesh tests, malloc'ed
 * into a dfl_trimesh (free with dfl_trimesh_free).
 *
 *   mf_octahedron(m)   |x|_1 = 1: 6 vertices, 8 triangles, CCW from outside
 *   mf_cube(m)         [-1, 1]^3: 8 vertices, 12 triangles (2 per face), CCW from outside
 *   WUSON              Debian assimp-testmodels' Wuson (AC3D)
 */
#ifndef DFL_TESTS_MESH_FIXTURES_H
#define DFL_TESTS_MESH_FIXTURES_H

#include <stdlib.h>
#include <string.h>

#include "geom/polygonize.h"

#define WUSON "/usr/share/assimp/models/AC/Wuson.ac"

static inline void mf_take(const double *v, size_t nv, const size_t *t, size_t nt, dfl_trimesh *m)
{
    memset(m, 0, sizeof *m);
    m->nverts = nv;
    m->verts = malloc(3 * nv * sizeof *m->verts);
    memcpy(m->verts, v, 3 * nv * sizeof *m->verts);
    m->ntris = nt;
    m->tris = malloc(3 * nt * sizeof *m->tris);
    memcpy(m->tris, t, 3 * nt * sizeof *m->tris);
}

static inline void mf_octahedron(dfl_trimesh *m)
{
    static const double v[] = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1};
    /* faces s.x = 1 for s in {+-1}^3, each (x-vertex, y-vertex, z-vertex)
     * ordered so that the normal has the direction of s */
    static const size_t t[] = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4,
                               2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
    mf_take(v, 6, t, 8, m);
}

static inline void mf_cube(dfl_trimesh *m)
{
    static const double v[] = {-1, -1, -1, 1, -1, -1, 1, 1, -1, -1, 1, -1,
                               -1, -1, 1,  1, -1, 1,  1, 1, 1,  -1, 1, 1};
    static const size_t t[] = {0, 2, 1, 0, 3, 2, /* z = -1 */ 4, 5, 6, 4, 6, 7, /* z = 1 */
                               0, 1, 5, 0, 5, 4, /* y = -1 */ 3, 6, 2, 3, 7, 6, /* y = 1 */
                               0, 4, 7, 0, 7, 3, /* x = -1 */ 1, 2, 6, 1, 6, 5 /* x = 1 */};
    mf_take(v, 8, t, 12, m);
}

#endif
