/* sessile io — the box's tetrahedra as a VTK XML UnstructuredGrid (.vtu)
 * and ParaView's .pvd collection.
 *
 * Size matters: the default box (65 x 65 x 49 nodes) has 1.18 M tets, and a
 * field file is written every few iterations.  So the data are appended
 * binary, zlib-compressed in independent blocks (vtkZLibDataCompressor,
 * header_type UInt64), connectivity and offsets are Int32 whenever they fit
 * (Int64 otherwise), and cell types are UInt8.  The mesh arrays are never
 * stored whole: each block is generated from the box and compressed on its
 * own, blocks in parallel (OpenMP); the output does not depend on the thread
 * count because every block is compressed independently.  docs/io.md has the
 * measured sizes and times. */
#include <stdlib.h>
#include <zlib.h>
#include "io_internal.h"

enum { VTK_TETRA = 10, ZLEVEL = 1, BLOCK_TARGET = 1 << 18 /* bytes of raw data per block */ };

/* One appended array: ntuples tuples of tuple_bytes bytes, produced by fill. */
typedef struct vtu_array {
  const char *xml_type, *name; /* name may be NULL (Points) */
  int components;
  uint64_t ntuples;
  size_t tuple_bytes;
  void (*fill)(const struct vtu_array *a, uint64_t first, uint64_t count, uint8_t *dst);
  const sessile_box *box;
  const sessile_point_data *data;
  int wide; /* Int64 connectivity / offsets */
  /* result: header + compressed blocks */
  uint8_t *blob;
  size_t blob_bytes;
} vtu_array;

static void fill_points(const vtu_array *a, uint64_t first, uint64_t count, uint8_t *dst) {
  for (uint64_t t = first; t < first + count; t++) {
    double p[3];
    sessile_box_node_pos(a->box, (uint32_t)t, p);
    for (int c = 0; c < 3; c++) dst = io_put_f64(dst, p[c]);
  }
}

static void fill_connectivity(const vtu_array *a, uint64_t first, uint64_t count, uint8_t *dst) {
  const sessile_box *b = a->box;
  uint64_t cx = b->n[0] - 1, cy = b->n[1] - 1;
  for (uint64_t t = first; t < first + count; t++) {
    uint64_t cube = t / 6;
    uint32_t nodes[4];
    sessile_box_tet(b, (uint32_t)(cube % cx), (uint32_t)((cube / cx) % cy), (uint32_t)(cube / (cx * cy)),
                    (int)(t % 6), nodes);
    for (int q = 0; q < 4; q++) dst = a->wide ? io_put_u64(dst, nodes[q]) : io_put_u32(dst, nodes[q]);
  }
}

static void fill_offsets(const vtu_array *a, uint64_t first, uint64_t count, uint8_t *dst) {
  for (uint64_t t = first; t < first + count; t++)
    dst = a->wide ? io_put_u64(dst, 4 * (t + 1)) : io_put_u32(dst, (uint32_t)(4 * (t + 1)));
}

static void fill_types(const vtu_array *a, uint64_t first, uint64_t count, uint8_t *dst) {
  memset(dst, VTK_TETRA, (size_t)count);
}

static void fill_data(const vtu_array *a, uint64_t first, uint64_t count, uint8_t *dst) {
  const sessile_point_data *d = a->data;
  if (!d->f64) {
    memcpy(dst, d->u8 + first, (size_t)count);
    return;
  }
  int nc = a->components;
  for (uint64_t q = first * nc; q < (first + count) * nc; q++) dst = io_put_f64(dst, d->f64[q]);
}

/* Compresses array a into a->blob: the UInt64 header (blocks, block size,
 * size of a partial last block or 0, compressed size of each block) followed
 * by the zlib streams. */
static sessile_status compress_array(const char *path, vtu_array *a) {
  uint64_t per = (BLOCK_TARGET + a->tuple_bytes - 1) / a->tuple_bytes; /* tuples per block */
  uint64_t block_bytes = per * a->tuple_bytes, total = a->ntuples * a->tuple_bytes;
  uint64_t nb = (a->ntuples + per - 1) / per;
  uLong bound = compressBound((uLong)block_bytes);
  uint8_t **out = calloc(nb ? nb : 1, sizeof *out);
  uLongf *len = calloc(nb ? nb : 1, sizeof *len);
  int failed = 0;
  if (!out || !len) failed = Z_MEM_ERROR;
#pragma omp parallel if (nb > 1 && !failed)
  {
    uint8_t *raw = failed ? NULL : malloc((size_t)block_bytes);
    if (!raw && !failed) {
#pragma omp atomic write
      failed = Z_MEM_ERROR;
    }
#pragma omp for schedule(dynamic)
    for (int64_t b = 0; b < (int64_t)nb; b++) {
      if (!raw) continue;
      uint64_t first = (uint64_t)b * per, count = a->ntuples - first < per ? a->ntuples - first : per;
      a->fill(a, first, count, raw);
      out[b] = malloc(bound);
      len[b] = bound;
      int zr = out[b] ? compress2(out[b], &len[b], raw, (uLong)(count * a->tuple_bytes), ZLEVEL) : Z_MEM_ERROR;
      if (zr != Z_OK) {
#pragma omp atomic write
        failed = zr;
      }
    }
    free(raw);
  }
  size_t bytes = 8 * (3 + (size_t)nb);
  for (uint64_t b = 0; !failed && b < nb; b++) bytes += len[b];
  a->blob = failed ? NULL : malloc(bytes);
  if (a->blob) {
    uint8_t *w = a->blob;
    w = io_put_u64(w, nb);
    w = io_put_u64(w, block_bytes);
    w = io_put_u64(w, total % block_bytes);
    for (uint64_t b = 0; b < nb; b++) w = io_put_u64(w, len[b]);
    for (uint64_t b = 0; b < nb; b++) {
      memcpy(w, out[b], len[b]);
      w += len[b];
    }
    a->blob_bytes = bytes;
  }
  for (uint64_t b = 0; out && b < nb; b++) free(out[b]);
  free(out);
  free(len);
  if (failed && failed != Z_MEM_ERROR)
    return sessile_error_set(SESSILE_ERR_INTERNAL, "writing '%s': zlib failed (%d) on array %s", path,
                             failed, a->name ? a->name : "Points");
  SESSILE_CHECK(a->blob, SESSILE_ERR_NO_MEMORY, "out of memory compressing '%s'", path);
  return SESSILE_OK;
}

static sessile_status write_array_tag(sessile_atomic_file *af, const vtu_array *a, uint64_t offset) {
  SESSILE_CALL(io_printf(af, "        <DataArray type=\"%s\"", a->xml_type));
  if (a->name) {
    SESSILE_CALL(io_printf(af, " Name=\""));
    SESSILE_CALL(io_xml_escaped(af, a->name));
    SESSILE_CALL(io_printf(af, "\""));
  }
  return io_printf(af, " NumberOfComponents=\"%d\" format=\"appended\" offset=\"%llu\"/>\n",
                   a->components, (unsigned long long)offset);
}

static sessile_status write_vtu_file(const char *path, const sessile_box *box, int ndata,
                                     vtu_array *arr, int narr) {
  sessile_atomic_file af;
  SESSILE_CALL(sessile_atomic_open(path, &af));
  uint64_t off[64 + 4], o = 0;
  for (int q = 0; q < narr; q++) off[q] = o, o += arr[q].blob_bytes;
  uint64_t ncells = arr[narr - 1].ntuples;
  sessile_status st = io_printf(
      &af,
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\" compressor=\"vtkZLibDataCompressor\">\n"
      "  <UnstructuredGrid>\n"
      "    <Piece NumberOfPoints=\"%u\" NumberOfCells=\"%llu\">\n      <PointData>\n",
      sessile_box_nodes(box), (unsigned long long)ncells);
  /* arrays: ndata point data, then Points, connectivity, offsets, types */
  for (int q = 0; q < ndata && st == SESSILE_OK; q++) st = write_array_tag(&af, &arr[q], off[q]);
  if (st == SESSILE_OK) st = io_printf(&af, "      </PointData>\n      <Points>\n");
  if (st == SESSILE_OK) st = write_array_tag(&af, &arr[ndata], off[ndata]);
  if (st == SESSILE_OK) st = io_printf(&af, "      </Points>\n      <Cells>\n");
  for (int q = ndata + 1; q < narr && st == SESSILE_OK; q++) st = write_array_tag(&af, &arr[q], off[q]);
  if (st == SESSILE_OK)
    st = io_printf(&af, "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n"
                        "  <AppendedData encoding=\"raw\">\n   _");
  for (int q = 0; q < narr && st == SESSILE_OK; q++) st = io_write(&af, arr[q].blob, arr[q].blob_bytes);
  if (st == SESSILE_OK) st = io_printf(&af, "\n  </AppendedData>\n</VTKFile>\n");
  if (st != SESSILE_OK) {
    sessile_atomic_abort(&af);
    return st;
  }
  return sessile_atomic_commit(&af);
}

sessile_status sessile_write_vtu(const char *path, const sessile_box *box, int ndata,
                                 const sessile_point_data *data) {
  SESSILE_CHECK(box && box->n[0] >= 2 && box->n[1] >= 2 && box->n[2] >= 2, SESSILE_ERR_USAGE,
                "cannot write '%s': the box needs at least 2 nodes per axis", path);
  SESSILE_CHECK(ndata >= 0 && ndata <= 64 && (ndata == 0 || data), SESSILE_ERR_USAGE,
                "cannot write '%s': %d point data arrays (0..64 allowed)", path, ndata);
  for (int q = 0; q < ndata; q++) {
    const sessile_point_data *d = &data[q];
    SESSILE_CHECK(d->name && d->name[0] && (d->f64 || d->u8), SESSILE_ERR_USAGE,
                  "cannot write '%s': point data %d needs a name and values", path, q);
    SESSILE_CHECK(d->components == 1 || (d->components == 3 && d->f64), SESSILE_ERR_USAGE,
                  "cannot write '%s': point data '%s' has %d components (1, or 3 for doubles)", path,
                  d->name, d->components);
  }
  uint64_t nodes = sessile_box_nodes(box);
  uint64_t ntets = 6ull * (box->n[0] - 1) * (box->n[1] - 1) * (box->n[2] - 1);
  int wide = 4 * ntets > INT32_MAX; /* offsets reach 4 ntets; node indices fit Int32 (box_make) */
  const char *itype = wide ? "Int64" : "Int32";
  size_t isz = wide ? 8 : 4;

  vtu_array arr[64 + 4];
  int narr = 0;
  memset(arr, 0, sizeof arr);
  for (int q = 0; q < ndata; q++)
    arr[narr++] = (vtu_array){data[q].f64 ? "Float64" : "UInt8", data[q].name, data[q].components, nodes,
                              data[q].f64 ? 8 * (size_t)data[q].components : 1, fill_data, box, &data[q],
                              0, NULL, 0};
  arr[narr++] = (vtu_array){"Float64", NULL, 3, nodes, 24, fill_points, box, NULL, 0, NULL, 0};
  arr[narr++] = (vtu_array){itype, "connectivity", 1, ntets, 4 * isz, fill_connectivity, box, NULL, wide, NULL, 0};
  arr[narr++] = (vtu_array){itype, "offsets", 1, ntets, isz, fill_offsets, box, NULL, wide, NULL, 0};
  arr[narr++] = (vtu_array){"UInt8", "types", 1, ntets, 1, fill_types, box, NULL, 0, NULL, 0};

  sessile_status st = SESSILE_OK;
  for (int q = 0; q < narr && st == SESSILE_OK; q++) st = compress_array(path, &arr[q]);
  if (st == SESSILE_OK) st = write_vtu_file(path, box, ndata, arr, narr);
  for (int q = 0; q < narr; q++) free(arr[q].blob);
  return st;
}

sessile_status sessile_write_pvd(const char *path, int n, const int *timesteps,
                                 const char *const *files) {
  SESSILE_CHECK(n >= 0 && (n == 0 || (timesteps && files)), SESSILE_ERR_USAGE,
                "cannot write '%s': %d entries", path, n);
  for (int q = 0; q < n; q++)
    SESSILE_CHECK(files[q] && files[q][0], SESSILE_ERR_USAGE, "cannot write '%s': entry %d has no file",
                  path, q);
  sessile_atomic_file af;
  SESSILE_CALL(sessile_atomic_open(path, &af));
  sessile_status st = io_printf(&af, "<?xml version=\"1.0\"?>\n"
                                     "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
                                     "  <Collection>\n");
  for (int q = 0; q < n && st == SESSILE_OK; q++) {
    st = io_printf(&af, "    <DataSet timestep=\"%d\" group=\"\" part=\"0\" file=\"", timesteps[q]);
    if (st == SESSILE_OK) st = io_xml_escaped(&af, files[q]);
    if (st == SESSILE_OK) st = io_printf(&af, "\"/>\n");
  }
  if (st == SESSILE_OK) st = io_printf(&af, "  </Collection>\n</VTKFile>\n");
  if (st != SESSILE_OK) {
    sessile_atomic_abort(&af);
    return st;
  }
  return sessile_atomic_commit(&af);
}
