/* Mesh files through Assimp's C API.  Assimp parses from memory so that
 * dflab's regular-file rule (io/rfile.h) holds for meshes as for configs;
 * welding by exact position is done here, not by Assimp, because
 * JoinIdenticalVertices only merges vertices whose every attribute agrees. */
#include "io/meshfile.h"

#include <assert.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include <assimp/cimport.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include "io/atomic.h"
#include "io/path.h"
#include "io/rfile.h"

void dfl_meshfile_free(dfl_meshfile *m)
{
    if (!m) return;
    free(m->verts);
    free(m->tris);
    memset(m, 0, sizeof *m);
}

/* The extension after the last '.' of the base name ("" if none). */
static const char *path_ext(const char *path)
{
    const char *b = dfl_path_base(path), *dot = strrchr(b, '.');
    return dot ? dot + 1 : "";
}

/* A used vertex and its original index, sorted by position (then index,
 * so the first of equal positions comes first). */
typedef struct weld_rec {
    double x[3];
    size_t i;
} weld_rec;

static int weld_cmp(const void *pa, const void *pb)
{
    const weld_rec *a = pa, *b = pb;
    for (int j = 0; j < 3; j++) {
        if (a->x[j] < b->x[j]) return -1;
        if (a->x[j] > b->x[j]) return 1;
    }
    return (a->i > b->i) - (a->i < b->i);
}

/* Copies the triangles of scene (global vertex indices) into out. */
static dfl_status gather(const struct aiScene *sc, const char *path, dfl_meshfile *out,
                         dfl_err *err)
{
    size_t nv = 0, nt = 0, skipped = 0;
    for (unsigned i = 0; i < sc->mNumMeshes; i++) {
        const struct aiMesh *m = sc->mMeshes[i];
        nv += m->mNumVertices;
        for (unsigned f = 0; f < m->mNumFaces; f++) {
            if (m->mFaces[f].mNumIndices == 3) nt++;
            else skipped++;
        }
    }
    if (nt == 0)
        return dfl_err_set(err, DFL_E_INPUT, "%s: no triangles (%zu point or line faces)", path,
                           skipped);
    out->verts = malloc(3 * nv * sizeof *out->verts);
    out->tris = malloc(3 * nt * sizeof *out->tris);
    if (!out->verts || !out->tris) return dfl_err_set(err, DFL_E_NOMEM, "%s: out of memory", path);
    size_t v0 = 0, t = 0;
    for (unsigned i = 0; i < sc->mNumMeshes; i++) {
        const struct aiMesh *m = sc->mMeshes[i];
        for (unsigned v = 0; v < m->mNumVertices; v++) {
            out->verts[3 * (v0 + v) + 0] = m->mVertices[v].x;
            out->verts[3 * (v0 + v) + 1] = m->mVertices[v].y;
            out->verts[3 * (v0 + v) + 2] = m->mVertices[v].z;
        }
        for (unsigned f = 0; f < m->mNumFaces; f++) {
            const struct aiFace *F = &m->mFaces[f];
            if (F->mNumIndices != 3) continue;
            for (int k = 0; k < 3; k++) {
                size_t g = v0 + F->mIndices[k];
                for (int j = 0; j < 3; j++)
                    if (!isfinite(out->verts[3 * g + j]))
                        return dfl_err_set(err, DFL_E_INPUT,
                                           "%s: vertex %u of mesh %u (in triangle %zu) has a "
                                           "non-finite coordinate (Assimp reads floats: "
                                           "|x| < 3.4e38)",
                                           path, F->mIndices[k], i, t);
                out->tris[3 * t + k] = g;
            }
            t++;
        }
        v0 += m->mNumVertices;
    }
    out->nverts = nv;
    out->ntris = nt;
    out->nskipped = skipped;
    return DFL_OK;
}

/* Drops unused vertices and welds equal positions (see the header). */
static dfl_status weld(dfl_meshfile *m, const char *path, dfl_err *err)
{
    const size_t nv = m->nverts;
    weld_rec *rec = malloc((nv ? nv : 1) * sizeof *rec);
    size_t *map = malloc((nv ? nv : 1) * sizeof *map);
    size_t *newid = malloc((nv ? nv : 1) * sizeof *newid);
    if (!rec || !map || !newid) {
        free(rec);
        free(map);
        free(newid);
        return dfl_err_set(err, DFL_E_NOMEM, "%s: out of memory", path);
    }
    for (size_t i = 0; i < nv; i++) map[i] = SIZE_MAX;
    for (size_t t = 0; t < 3 * m->ntris; t++) map[m->tris[t]] = 0; /* used */
    size_t nu = 0;
    for (size_t i = 0; i < nv; i++)
        if (map[i] == 0) {
            memcpy(rec[nu].x, m->verts + 3 * i, sizeof rec[nu].x);
            rec[nu++].i = i;
        }
    qsort(rec, nu, sizeof *rec, weld_cmp);
    /* map: the smallest original index of each group of equal positions */
    for (size_t k = 0; k < nu;) {
        size_t e = k + 1;
        while (e < nu && rec[e].x[0] == rec[k].x[0] && rec[e].x[1] == rec[k].x[1] &&
               rec[e].x[2] == rec[k].x[2])
            e++;
        for (size_t q = k; q < e; q++) map[rec[q].i] = rec[k].i;
        k = e;
    }
    /* new numbering in the original order of the representatives */
    size_t n = 0;
    for (size_t i = 0; i < nv; i++)
        if (map[i] == i) {
            newid[i] = n;
            memmove(m->verts + 3 * n, m->verts + 3 * i, 3 * sizeof(double));
            n++;
        }
    for (size_t t = 0; t < 3 * m->ntris; t++) m->tris[t] = newid[map[m->tris[t]]];
    m->nverts = n;
    free(rec);
    free(map);
    free(newid);
    return DFL_OK;
}

dfl_status dfl_meshfile_read(const char *path, dfl_meshfile *out, dfl_err *err)
{
    memset(out, 0, sizeof *out);
    char *bytes = NULL;
    size_t len = 0;
    dfl_status st = dfl_rfile_read(path, "mesh", DFL_MESHFILE_MAX, &bytes, &len, err);
    if (st != DFL_OK) return st;
    if (len == 0) {
        free(bytes);
        return dfl_err_set(err, DFL_E_INPUT, "%s: empty file (expected a triangle mesh)", path);
    }
    const struct aiScene *sc = aiImportFileFromMemory(
        bytes, (unsigned)len,
        aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_PreTransformVertices,
        path_ext(path));
    free(bytes);
    if (!sc) {
        return dfl_err_set(err, DFL_E_INPUT, "%s: not a mesh Assimp reads (%.200s)", path,
                           aiGetErrorString());
    }
    if (sc->mNumMeshes == 0 || !sc->mMeshes) {
        aiReleaseImport(sc);
        return dfl_err_set(err, DFL_E_INPUT, "%s: no triangles (the file holds no mesh)", path);
    }
    st = gather(sc, path, out, err);
    aiReleaseImport(sc);
    if (st == DFL_OK) st = weld(out, path, err);
    if (st != DFL_OK) dfl_meshfile_free(out);
    return st;
}

dfl_status dfl_meshfile_write(const char *path, size_t nverts, const double *verts, size_t ntris,
                              const size_t *tris, dfl_err *err)
{
    const char *ext = path_ext(path);
    const int obj = strcasecmp(ext, "obj") == 0, ply = strcasecmp(ext, "ply") == 0;
    if (!obj && !ply)
        return dfl_err_set(err, DFL_E_INPUT, "%s: expected a .obj or .ply name", path);
    dfl_atomic_file af;
    dfl_status st = dfl_atomic_open(path, &af, err);
    if (st != DFL_OK) return st;
    FILE *fp = af.fp;
    if (ply)
        fprintf(fp,
                "ply\nformat ascii 1.0\nelement vertex %zu\nproperty double x\nproperty double "
                "y\nproperty double z\nelement face %zu\nproperty list uchar uint "
                "vertex_indices\nend_header\n",
                nverts, ntris);
    for (size_t i = 0; i < nverts; i++)
        fprintf(fp, "%s%.17g %.17g %.17g\n", obj ? "v " : "", verts[3 * i], verts[3 * i + 1],
                verts[3 * i + 2]);
    for (size_t t = 0; t < ntris; t++) {
        assert(tris[3 * t] < nverts && tris[3 * t + 1] < nverts && tris[3 * t + 2] < nverts);
        if (obj)
            fprintf(fp, "f %zu %zu %zu\n", tris[3 * t] + 1, tris[3 * t + 1] + 1,
                    tris[3 * t + 2] + 1);
        else
            fprintf(fp, "3 %zu %zu %zu\n", tris[3 * t], tris[3 * t + 1], tris[3 * t + 2]);
    }
    return dfl_atomic_commit(&af, err);
}
