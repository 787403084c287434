/* VTK XML ImageData / PolyData writers.
 *
 * Every array goes into one appended binary block, so the XML header must
 * know each array's byte offset before any data is written.  With zlib the
 * compressed sizes are only known after compressing, hence all arrays are
 * first turned into "blobs" (raw: a pointer into the caller's data, no copy;
 * zlib: an owned buffer holding the compression header and blocks), then
 * offsets are summed, then the file is written in one pass.
 *
 * Appended layout (header_type="UInt64", VTK XML file format 1.0):
 *   raw:  [uint64 nbytes][nbytes of data]
 *   zlib: [uint64 nblocks][uint64 block size][uint64 last block size]
 *         [uint64 compressed size of each block...][compressed blocks...]
 * "last block size" is the uncompressed size of a partial last block, 0 when
 * the last block is full: vtkXMLDataParser uses the full block size when this
 * value is 0, and vtkXMLWriter writes nbytes % blocksize.
 */
#include "io/vtk.h"

#include <assert.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <zlib.h>

#include "io/atomic.h"

/* The file says byte_order="LittleEndian" and data is written from memory
 * as is. */
_Static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "dflab's VTK writer assumes a little-endian host");

typedef struct vtk_blob {
    const void *data;     /* uncompressed payload (not owned) */
    size_t nbytes;
    unsigned char *z;     /* zlib stream with header, owned; NULL when raw */
    size_t zbytes;
    uint64_t offset;      /* from the byte after '_' in <AppendedData> */
} vtk_blob;

static size_t blob_disk_bytes(const vtk_blob *b)
{
    return b->z ? b->zbytes : sizeof(uint64_t) + b->nbytes;
}

static void put_u64(unsigned char *p, uint64_t v)
{
    memcpy(p, &v, sizeof v); /* little endian host, see static assert */
}

static dfl_status blob_compress(vtk_blob *b, dfl_err *err)
{
    const size_t bs = DFL_VTK_ZLIB_BLOCK;
    size_t nblocks = (b->nbytes + bs - 1) / bs;
    size_t head = (3 + nblocks) * sizeof(uint64_t);
    size_t bound = compressBound((uLong)bs);
    unsigned char *buf = malloc(head + nblocks * bound);
    if (!buf) return dfl_err_set(err, DFL_E_NOMEM, "vtk: out of memory compressing %zu bytes", b->nbytes);
    put_u64(buf, nblocks);
    put_u64(buf + 8, bs);
    put_u64(buf + 16, b->nbytes % bs);
    size_t pos = head;
    const unsigned char *src = b->data;
    for (size_t i = 0; i < nblocks; i++) {
        size_t len = (i + 1 < nblocks || b->nbytes % bs == 0) ? bs : b->nbytes % bs;
        uLongf zlen = (uLongf)bound;
        int zr = compress2(buf + pos, &zlen, src + i * bs, (uLong)len, Z_DEFAULT_COMPRESSION);
        if (zr != Z_OK) {
            free(buf);
            return dfl_err_set(err, zr == Z_MEM_ERROR ? DFL_E_NOMEM : DFL_E_INTERNAL,
                               "vtk: zlib compress2 failed (%d)", zr);
        }
        put_u64(buf + 24 + 8 * i, (uint64_t)zlen);
        pos += zlen;
    }
    b->z = buf;
    b->zbytes = pos;
    return DFL_OK;
}

/* Compresses (if asked) and assigns offsets to all blobs.  On failure the
 * blobs already compressed are left for blobs_free. */
static dfl_status blobs_prepare(vtk_blob *blobs, int n, int compress, dfl_err *err)
{
    uint64_t off = 0;
    for (int i = 0; i < n; i++) {
        if (compress) {
            dfl_status st = blob_compress(&blobs[i], err);
            if (st) return st;
        }
        blobs[i].offset = off;
        off += blob_disk_bytes(&blobs[i]);
    }
    return DFL_OK;
}

/* Frees the compressed copies and the array itself (blobs may be NULL). */
static void blobs_free(vtk_blob *blobs, int n)
{
    if (!blobs) return;
    for (int i = 0; i < n; i++) free(blobs[i].z);
    free(blobs);
}

static void blobs_write(FILE *fp, const vtk_blob *blobs, int n)
{
    fputs("  <AppendedData encoding=\"raw\">\n   _", fp);
    for (int i = 0; i < n; i++) {
        const vtk_blob *b = &blobs[i];
        if (b->z) {
            fwrite(b->z, 1, b->zbytes, fp);
        } else {
            unsigned char h[8];
            put_u64(h, b->nbytes);
            fwrite(h, 1, sizeof h, fp);
            if (b->nbytes) fwrite(b->data, 1, b->nbytes, fp);
        }
    }
    fputs("\n  </AppendedData>\n</VTKFile>\n", fp);
}

/* Writes s as XML attribute text. */
static void xml_escaped(FILE *fp, const char *s)
{
    for (; *s; s++) {
        switch (*s) {
        case '<': fputs("&lt;", fp); break;
        case '>': fputs("&gt;", fp); break;
        case '&': fputs("&amp;", fp); break;
        case '"': fputs("&quot;", fp); break;
        case '\'': fputs("&apos;", fp); break;
        default: fputc(*s, fp);
        }
    }
}

static void xml_data_array(FILE *fp, const char *indent, const char *type, const char *name,
                           int ncomp, const vtk_blob *b)
{
    fprintf(fp, "%s<DataArray type=\"%s\" Name=\"", indent, type);
    xml_escaped(fp, name);
    fprintf(fp, "\" NumberOfComponents=\"%d\" format=\"appended\" offset=\"%llu\"/>\n", ncomp,
            (unsigned long long)b->offset);
}

static void xml_file_open(FILE *fp, const char *type, int compress)
{
    fprintf(fp,
            "<?xml version=\"1.0\"?>\n"
            "<VTKFile type=\"%s\" version=\"1.0\" byte_order=\"LittleEndian\" "
            "header_type=\"UInt64\"%s>\n",
            type, compress ? " compressor=\"vtkZLibDataCompressor\"" : "");
}

/* Writes <PointData ...> with the arrays whose blobs start at blobs[0]. */
static void xml_point_data(FILE *fp, const dfl_vtk_array *arrays, int narrays,
                           const vtk_blob *blobs)
{
    fputs("   <PointData", fp);
    for (int i = 0; i < narrays; i++)
        if (strcmp(arrays[i].name, "value") == 0) fputs(" Scalars=\"value\"", fp);
    for (int i = 0; i < narrays; i++)
        if (strcmp(arrays[i].name, "gradient") == 0 && arrays[i].ncomp == 3)
            fputs(" Vectors=\"gradient\"", fp);
    fputs(">\n", fp);
    for (int i = 0; i < narrays; i++)
        xml_data_array(fp, "    ", "Float64", arrays[i].name, arrays[i].ncomp, &blobs[i]);
    fputs("   </PointData>\n", fp);
}

static dfl_status check_arrays(const dfl_vtk_array *arrays, int narrays, size_t npoints,
                               const char *path, dfl_err *err)
{
    if (narrays < 0 || (narrays > 0 && !arrays))
        return dfl_err_set(err, DFL_E_INPUT, "%s: invalid point array list", path);
    for (int i = 0; i < narrays; i++) {
        const dfl_vtk_array *a = &arrays[i];
        if (!a->name || !a->name[0])
            return dfl_err_set(err, DFL_E_INPUT, "%s: point array %d has no name", path, i);
        if (a->ncomp < 1 || a->ncomp > 9)
            return dfl_err_set(err, DFL_E_INPUT, "%s: point array '%s' has %d components (1..9)",
                               path, a->name, a->ncomp);
        if (!a->data && npoints > 0)
            return dfl_err_set(err, DFL_E_INPUT, "%s: point array '%s' has no data", path,
                               a->name);
        if (npoints > SIZE_MAX / sizeof(double) / (size_t)a->ncomp)
            return dfl_err_set(err, DFL_E_INPUT, "%s: point array '%s' too large", path, a->name);
        for (int j = 0; j < i; j++)
            if (strcmp(arrays[j].name, a->name) == 0)
                return dfl_err_set(err, DFL_E_INPUT, "%s: duplicate point array name '%s'", path,
                                   a->name);
    }
    return DFL_OK;
}

/* Starts a file once its blobs are listed: compresses (if asked) and
 * places them, then opens path for writing.  On failure the blobs are freed
 * and nothing is left on disk. */
static dfl_status start(const char *path, vtk_blob *blobs, int nblobs, int compress,
                        dfl_atomic_file *af, dfl_err *err)
{
    dfl_status st = blobs_prepare(blobs, nblobs, compress, err);
    if (!st) st = dfl_atomic_open(path, af, err);
    if (st) blobs_free(blobs, nblobs);
    return st;
}

/* Finishes a file whose XML and data have been written to af. */
static dfl_status finish(dfl_atomic_file *af, vtk_blob *blobs, int nblobs, dfl_err *err)
{
    blobs_write(af->fp, blobs, nblobs);
    blobs_free(blobs, nblobs);
    return dfl_atomic_commit(af, err);
}

size_t dfl_vti_ncells(const int dims[3])
{
    size_t n = 1;
    for (int i = 0; i < 3; i++) n *= dims[i] > 1 ? (size_t)dims[i] - 1 : 1;
    return n;
}

dfl_status dfl_vti_write(const char *path, const int dims[3], const double origin[3],
                         const double spacing[3], const dfl_vtk_array *arrays, int narrays,
                         int compress, dfl_err *err)
{
    return dfl_vti_write_cells(path, dims, origin, spacing, arrays, narrays, NULL, 0, compress,
                               err);
}

dfl_status dfl_vti_write_cells(const char *path, const int dims[3], const double origin[3],
                               const double spacing[3], const dfl_vtk_array *arrays, int narrays,
                               const dfl_vtk_array *cells, int ncells, int compress, dfl_err *err)
{
    if (!path || !path[0]) return dfl_err_set(err, DFL_E_INPUT, "vti: empty output path");
    if (!dims || !origin || !spacing)
        return dfl_err_set(err, DFL_E_INPUT, "%s: missing grid geometry", path);
    if (!arrays || narrays <= 0)
        return dfl_err_set(err, DFL_E_INPUT, "%s: no point arrays to write", path);
    size_t npoints = 1;
    for (int i = 0; i < 3; i++) {
        if (dims[i] < 1)
            return dfl_err_set(err, DFL_E_INPUT, "%s: grid dimension %d is %d (must be >= 1)",
                               path, i, dims[i]);
        if (npoints > SIZE_MAX / (size_t)dims[i])
            return dfl_err_set(err, DFL_E_INPUT, "%s: grid too large", path);
        npoints *= (size_t)dims[i];
        if (!isfinite(origin[i]))
            return dfl_err_set(err, DFL_E_INPUT, "%s: origin[%d] is not finite", path, i);
        if (!isfinite(spacing[i]) || !(spacing[i] > 0))
            return dfl_err_set(err, DFL_E_INPUT, "%s: spacing[%d] = %g (must be finite, > 0)",
                               path, i, spacing[i]);
    }
    const size_t ncell = dfl_vti_ncells(dims);
    dfl_status st = check_arrays(arrays, narrays, npoints, path, err);
    if (!st) st = check_arrays(cells, ncells, ncell, path, err);
    for (int i = 0; !st && i < ncells; i++)
        for (int j = 0; j < narrays; j++)
            if (strcmp(cells[i].name, arrays[j].name) == 0)
                return dfl_err_set(err, DFL_E_INPUT, "%s: '%s' is both a point and a cell array",
                                   path, cells[i].name);
    if (st) return st;

    const int nb = narrays + ncells;
    vtk_blob *blobs = calloc((size_t)nb, sizeof *blobs);
    if (!blobs) return dfl_err_set(err, DFL_E_NOMEM, "%s: out of memory", path);
    for (int i = 0; i < nb; i++) {
        const dfl_vtk_array *a = i < narrays ? &arrays[i] : &cells[i - narrays];
        blobs[i].data = a->data;
        blobs[i].nbytes = (i < narrays ? npoints : ncell) * (size_t)a->ncomp * sizeof(double);
    }
    dfl_atomic_file af;
    st = start(path, blobs, nb, compress, &af, err);
    if (st) return st;

    FILE *fp = af.fp;
    char ext[128];
    snprintf(ext, sizeof ext, "0 %d 0 %d 0 %d", dims[0] - 1, dims[1] - 1, dims[2] - 1);
    xml_file_open(fp, "ImageData", compress);
    fprintf(fp, " <ImageData WholeExtent=\"%s\" Origin=\"%.17g %.17g %.17g\" "
                "Spacing=\"%.17g %.17g %.17g\" Direction=\"1 0 0 0 1 0 0 0 1\">\n",
            ext, origin[0], origin[1], origin[2], spacing[0], spacing[1], spacing[2]);
    fprintf(fp, "  <Piece Extent=\"%s\">\n", ext);
    xml_point_data(fp, arrays, narrays, blobs);
    fputs("   <CellData>\n", fp);
    for (int i = 0; i < ncells; i++)
        xml_data_array(fp, "    ", "Float64", cells[i].name, cells[i].ncomp, &blobs[narrays + i]);
    fputs("   </CellData>\n  </Piece>\n </ImageData>\n", fp);
    return finish(&af, blobs, nb, err);
}

dfl_status dfl_pvd_write(const char *path, const dfl_pvd_entry *e, size_t n, dfl_err *err)
{
    if (!path || !path[0]) return dfl_err_set(err, DFL_E_INPUT, "pvd: empty output path");
    if (n > 0 && !e) return dfl_err_set(err, DFL_E_INPUT, "%s: no data sets", path);
    for (size_t i = 0; i < n; i++)
        if (!e[i].file || !e[i].file[0] || !isfinite(e[i].time))
            return dfl_err_set(err, DFL_E_INPUT, "%s: data set %zu has no file or a non-finite "
                                                 "time", path, i);
    dfl_atomic_file af;
    dfl_status st = dfl_atomic_open(path, &af, err);
    if (st) return st;
    fputs("<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\" "
          "byte_order=\"LittleEndian\">\n <Collection>\n", af.fp);
    for (size_t i = 0; i < n; i++) {
        fprintf(af.fp, "  <DataSet timestep=\"%.17g\" group=\"\" part=\"0\" file=\"", e[i].time);
        xml_escaped(af.fp, e[i].file);
        fputs("\"/>\n", af.fp);
    }
    fputs(" </Collection>\n</VTKFile>\n", af.fp);
    return dfl_atomic_commit(&af, err);
}

static dfl_status check_vtp(const char *path, const dfl_vtp_data *d, dfl_err *err)
{
    if (d->npoints > 0 && !d->points)
        return dfl_err_set(err, DFL_E_INPUT, "%s: %zu points but no coordinates", path,
                           d->npoints);
    if (d->npoints > (size_t)INT64_MAX / 24)
        return dfl_err_set(err, DFL_E_INPUT, "%s: too many points", path);
    if (d->nlines > 0) {
        if (!d->line_offsets)
            return dfl_err_set(err, DFL_E_INPUT, "%s: %zu lines but no offsets", path, d->nlines);
        if (d->line_offsets[0] != 0)
            return dfl_err_set(err, DFL_E_INPUT, "%s: line_offsets[0] = %zu (must be 0)", path,
                               d->line_offsets[0]);
        for (size_t i = 0; i < d->nlines; i++)
            if (d->line_offsets[i + 1] < d->line_offsets[i])
                return dfl_err_set(err, DFL_E_INPUT, "%s: line_offsets decrease at line %zu",
                                   path, i);
        size_t nconn = d->line_offsets[d->nlines];
        if (nconn > 0 && !d->line_conn)
            return dfl_err_set(err, DFL_E_INPUT, "%s: lines but no connectivity", path);
        for (size_t i = 0; i < nconn; i++)
            if (d->line_conn[i] >= d->npoints)
                return dfl_err_set(err, DFL_E_INPUT,
                                   "%s: line_conn[%zu] = %zu is not a point index (< %zu)", path,
                                   i, d->line_conn[i], d->npoints);
    }
    if (d->ntris > 0) {
        if (!d->tris)
            return dfl_err_set(err, DFL_E_INPUT, "%s: %zu triangles but no indices", path,
                               d->ntris);
        if (d->ntris > (size_t)INT64_MAX / 24)
            return dfl_err_set(err, DFL_E_INPUT, "%s: too many triangles", path);
        for (size_t i = 0; i < 3 * d->ntris; i++)
            if (d->tris[i] >= d->npoints)
                return dfl_err_set(err, DFL_E_INPUT,
                                   "%s: tris[%zu] = %zu is not a point index (< %zu)", path, i,
                                   d->tris[i], d->npoints);
    }
    return check_arrays(d->point_arrays, d->narrays, d->npoints, path, err);
}

/* Point indices and cell-end offsets are written as Int64.  On LP64 hosts a
 * size_t holding a valid index (< npoints < 2^63) has the same little-endian
 * bytes as that int64, so the caller's arrays are written without a copy;
 * elsewhere they are converted into *owned. */
static dfl_status as_int64(const size_t *v, size_t n, const void **out, int64_t **owned,
                           dfl_err *err)
{
    *owned = NULL;
    if (sizeof(size_t) == sizeof(int64_t)) {
        *out = v;
        return DFL_OK;
    }
    int64_t *c = malloc((n ? n : 1) * sizeof *c);
    if (!c) return dfl_err_set(err, DFL_E_NOMEM, "vtp: out of memory");
    for (size_t i = 0; i < n; i++) c[i] = (int64_t)v[i];
    *owned = c;
    *out = c;
    return DFL_OK;
}

dfl_status dfl_vtp_write(const char *path, const dfl_vtp_data *d, int compress, dfl_err *err)
{
    if (!path || !path[0]) return dfl_err_set(err, DFL_E_INPUT, "vtp: empty output path");
    if (!d) return dfl_err_set(err, DFL_E_INPUT, "%s: no PolyData given", path);
    dfl_status st = check_vtp(path, d, err);
    if (st) return st;

    /* Blob order = order in the XML: point arrays, points, lines (conn,
     * offsets), polys (conn, offsets). */
    int na = d->narrays;
    int nblobs = na + 1 + (d->nlines ? 2 : 0) + (d->ntris ? 2 : 0);
    vtk_blob *blobs = calloc((size_t)nblobs, sizeof *blobs);
    int64_t *tri_off = NULL, *own[3] = {NULL, NULL, NULL};
    if (!blobs) return dfl_err_set(err, DFL_E_NOMEM, "%s: out of memory", path);
    int k = 0;
    for (int i = 0; i < na; i++, k++) {
        blobs[k].data = d->point_arrays[i].data;
        blobs[k].nbytes = d->npoints * (size_t)d->point_arrays[i].ncomp * sizeof(double);
    }
    blobs[k].data = d->points;
    blobs[k].nbytes = 3 * d->npoints * sizeof(double);
    k++;
    int line_blob = k;
    if (!st && d->nlines) {
        size_t nconn = d->line_offsets[d->nlines];
        st = as_int64(d->line_conn, nconn, &blobs[k].data, &own[0], err);
        blobs[k++].nbytes = nconn * sizeof(int64_t);
        if (!st) st = as_int64(d->line_offsets + 1, d->nlines, &blobs[k].data, &own[1], err);
        blobs[k++].nbytes = d->nlines * sizeof(int64_t);
    }
    int poly_blob = k;
    if (!st && d->ntris) {
        st = as_int64(d->tris, 3 * d->ntris, &blobs[k].data, &own[2], err);
        blobs[k++].nbytes = 3 * d->ntris * sizeof(int64_t);
        tri_off = malloc(d->ntris * sizeof *tri_off);
        if (!tri_off && !st) st = dfl_err_set(err, DFL_E_NOMEM, "%s: out of memory", path);
        if (tri_off)
            for (size_t i = 0; i < d->ntris; i++) tri_off[i] = 3 * (int64_t)(i + 1);
        blobs[k].data = tri_off;
        blobs[k++].nbytes = d->ntris * sizeof(int64_t);
    }
    dfl_atomic_file af;
    if (st) {
        blobs_free(blobs, nblobs);
    } else {
        assert(k == nblobs);
        st = start(path, blobs, nblobs, compress, &af, err);
    }
    if (!st) {
        FILE *fp = af.fp;
        xml_file_open(fp, "PolyData", compress);
        fputs(" <PolyData>\n", fp);
        fprintf(fp,
                "  <Piece NumberOfPoints=\"%zu\" NumberOfVerts=\"0\" NumberOfLines=\"%zu\" "
                "NumberOfStrips=\"0\" NumberOfPolys=\"%zu\">\n",
                d->npoints, d->nlines, d->ntris);
        xml_point_data(fp, d->point_arrays, na, blobs);
        fputs("   <CellData>\n   </CellData>\n   <Points>\n", fp);
        xml_data_array(fp, "    ", "Float64", "Points", 3, &blobs[na]);
        fputs("   </Points>\n", fp);
        if (d->nlines) {
            fputs("   <Lines>\n", fp);
            xml_data_array(fp, "    ", "Int64", "connectivity", 1, &blobs[line_blob]);
            xml_data_array(fp, "    ", "Int64", "offsets", 1, &blobs[line_blob + 1]);
            fputs("   </Lines>\n", fp);
        }
        if (d->ntris) {
            fputs("   <Polys>\n", fp);
            xml_data_array(fp, "    ", "Int64", "connectivity", 1, &blobs[poly_blob]);
            xml_data_array(fp, "    ", "Int64", "offsets", 1, &blobs[poly_blob + 1]);
            fputs("   </Polys>\n", fp);
        }
        fputs("  </Piece>\n </PolyData>\n", fp);
        st = finish(&af, blobs, nblobs, err);
    }
    free(tri_off);
    for (int i = 0; i < 3; i++) free(own[i]);
    return st;
}
