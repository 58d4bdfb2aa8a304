/* sessile io — tetrahedral meshes as VTK XML UnstructuredGrid (.vtu) and
 * ParaView's .pvd collection.  Two entry points share one encoder: the
 * structured box (sessile_write_vtu, its Kuhn tets generated on the fly) and
 * any tetrahedral mesh given as arrays (sessile_write_vtu_tets, with point
 * and cell data).
 *
 * Size matters: the default box (65 x 65 x 49 nodes) has 1.18 M tets, and a
 * field file is written every few iterations.  So the data are appended
 * binary, zlib-compressed in independent blocks (vtkZLibDataCompressor,
 * header_type UInt64), connectivity and offsets are Int32 whenever they fit
 * (Int64 otherwise), and cell types are UInt8.  The box's mesh arrays are
 * never stored whole: each block is generated from the box and compressed on
 * its own, blocks in parallel (OpenMP); the output does not depend on the
 * thread count because every block is compressed independently.  docs/io.md
 * has the measured sizes and times. */
#include <math.h>
#include <stdlib.h>
#include <zlib.h>
#include "io_internal.h"

enum { VTK_TETRA = 10, ZLEVEL = 1, BLOCK_TARGET = 1 << 18 /* bytes of raw data per block */ };

static void fill_points_box(const vtu_array *a, uint64_t first, uint64_t count, uint8_t *dst) {
  for (uint64_t t = first; t < first + count; t++) {
    double p[3];
    sessile_box_node_pos(a->mesh->box, (uint32_t)t, p);
    for (int c = 0; c < 3; c++) dst = io_put_f64(dst, p[c]);
  }
}

static void fill_points_xyz(const vtu_array *a, uint64_t first, uint64_t count, uint8_t *dst) {
  for (uint64_t q = 3 * first; q < 3 * (first + count); q++) dst = io_put_f64(dst, a->mesh->xyz[q]);
}

static void fill_connectivity_box(const vtu_array *a, uint64_t first, uint64_t count, uint8_t *dst) {
  const sessile_box *b = a->mesh->box;
  uint64_t cx = b->n[0] - 1, cy = b->n[1] - 1;
  for (uint64_t t = first; t < first + count; t++) {
    uint64_t cube = t / 6;
    uint32_t nodes[4];
    sessile_box_tet(b, (uint32_t)(cube % cx), (uint32_t)((cube / cx) % cy), (uint32_t)(cube / (cx * cy)),
                    (int)(t % 6), nodes);
    for (int q = 0; q < 4; q++) dst = a->wide ? io_put_u64(dst, nodes[q]) : io_put_u32(dst, nodes[q]);
  }
}

static void fill_connectivity_tets(const vtu_array *a, uint64_t first, uint64_t count, uint8_t *dst) {
  const uint32_t *tets = a->mesh->tets;
  for (uint64_t q = 4 * first; q < 4 * (first + count); q++)
    dst = a->wide ? io_put_u64(dst, tets[q]) : io_put_u32(dst, tets[q]);
}

static void fill_offsets(const vtu_array *a, uint64_t first, uint64_t count, uint8_t *dst) {
  for (uint64_t t = first; t < first + count; t++)
    dst = a->wide ? io_put_u64(dst, 4 * (t + 1)) : io_put_u32(dst, (uint32_t)(4 * (t + 1)));
}

static void fill_types(const vtu_array *a, uint64_t first, uint64_t count, uint8_t *dst) {
  (void)a, (void)first;
  memset(dst, VTK_TETRA, (size_t)count);
}

static void fill_field(const vtu_array *a, uint64_t first, uint64_t count, uint8_t *dst) {
  const sessile_vtu_field *d = a->field;
  uint64_t nc = (uint64_t)a->components;
  if (d->u8) {
    memcpy(dst, d->u8 + first * nc, (size_t)(count * nc));
    return;
  }
  for (uint64_t q = first * nc; q < (first + count) * nc; q++)
    dst = d->f64 ? io_put_f64(dst, d->f64[q]) : io_put_u32(dst, (uint32_t)d->i32[q]);
}

sessile_status io_vtk_compress(const char *path, vtu_array *a) {
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

sessile_status io_vtk_array_tag(sessile_atomic_file *af, const vtu_array *a, uint64_t offset) {
  SESSILE_CALL(io_printf(af, "        <DataArray type=\"%s\"", a->xml_type));
  if (a->name) {
    SESSILE_CALL(io_printf(af, " Name=\""));
    SESSILE_CALL(io_xml_escaped(af, a->name));
    SESSILE_CALL(io_printf(af, "\""));
  }
  return io_printf(af, " NumberOfComponents=\"%d\" format=\"appended\" offset=\"%llu\"/>\n",
                   a->components, (unsigned long long)offset);
}

/* arr: npf point fields, ncf cell fields, then Points, connectivity, offsets,
 * types (the order of the appended blobs). */
static sessile_status write_vtu_file(const char *path, uint32_t npoints, int npf, int ncf,
                                     const vtu_array *arr, int narr) {
  uint64_t *off = malloc((size_t)narr * sizeof *off), o = 0;
  SESSILE_CHECK(off, SESSILE_ERR_NO_MEMORY, "out of memory writing '%s'", path);
  for (int q = 0; q < narr; q++) off[q] = o, o += arr[q].blob_bytes;
  sessile_atomic_file af;
  sessile_status st = sessile_atomic_open(path, &af);
  if (st != SESSILE_OK) {
    free(off);
    return st;
  }
  uint64_t ncells = arr[narr - 1].ntuples;
  int pts = npf + ncf;
  st = io_printf(&af,
                 "<?xml version=\"1.0\"?>\n"
                 "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
                 "header_type=\"UInt64\" compressor=\"vtkZLibDataCompressor\">\n"
                 "  <UnstructuredGrid>\n"
                 "    <Piece NumberOfPoints=\"%u\" NumberOfCells=\"%llu\">\n      <PointData>\n",
                 npoints, (unsigned long long)ncells);
  for (int q = 0; q < npf && st == SESSILE_OK; q++) st = io_vtk_array_tag(&af, &arr[q], off[q]);
  if (st == SESSILE_OK) st = io_printf(&af, "      </PointData>\n");
  if (ncf > 0 && st == SESSILE_OK) {
    st = io_printf(&af, "      <CellData>\n");
    for (int q = npf; q < pts && st == SESSILE_OK; q++) st = io_vtk_array_tag(&af, &arr[q], off[q]);
    if (st == SESSILE_OK) st = io_printf(&af, "      </CellData>\n");
  }
  if (st == SESSILE_OK) st = io_printf(&af, "      <Points>\n");
  if (st == SESSILE_OK) st = io_vtk_array_tag(&af, &arr[pts], off[pts]);
  if (st == SESSILE_OK) st = io_printf(&af, "      </Points>\n      <Cells>\n");
  for (int q = pts + 1; q < narr && st == SESSILE_OK; q++) st = io_vtk_array_tag(&af, &arr[q], off[q]);
  if (st == SESSILE_OK)
    st = io_printf(&af, "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n"
                        "  <AppendedData encoding=\"raw\">\n   _");
  for (int q = 0; q < narr && st == SESSILE_OK; q++) st = io_write(&af, arr[q].blob, arr[q].blob_bytes);
  if (st == SESSILE_OK) st = io_printf(&af, "\n  </AppendedData>\n</VTKFile>\n");
  free(off);
  if (st != SESSILE_OK) {
    sessile_atomic_abort(&af);
    return st;
  }
  return sessile_atomic_commit(&af);
}

/* Checks one list of fields ("point" or "cell" data). */
static sessile_status check_fields(const char *path, const char *kind, int n, const sessile_vtu_field *f) {
  SESSILE_CHECK(n >= 0 && n <= SESSILE_VTU_MAX_FIELDS && (n == 0 || f), SESSILE_ERR_USAGE,
                "cannot write '%s': %d %s data arrays (0..%d allowed)", path, n, kind,
                SESSILE_VTU_MAX_FIELDS);
  for (int q = 0; q < n; q++) {
    const sessile_vtu_field *d = &f[q];
    int arrays = !!d->f64 + !!d->u8 + !!d->i32;
    SESSILE_CHECK(d->name && d->name[0] && arrays == 1, SESSILE_ERR_USAGE,
                  "cannot write '%s': %s data %d needs a name and exactly one of f64, u8, i32", path,
                  kind, q);
    SESSILE_CHECK(d->components == 1 || d->components == 3, SESSILE_ERR_USAGE,
                  "cannot write '%s': %s data '%s' has %d components (1 or 3)", path, kind, d->name,
                  d->components);
    for (int r = 0; r < q; r++)
      SESSILE_CHECK(strcmp(d->name, f[r].name) != 0, SESSILE_ERR_USAGE,
                    "cannot write '%s': %s data name '%s' appears twice", path, kind, d->name);
  }
  return SESSILE_OK;
}

static vtu_array field_array(const sessile_vtu_field *d, uint64_t ntuples, const vtu_mesh *mesh) {
  size_t el = d->f64 ? 8 : d->i32 ? 4 : 1;
  return (vtu_array){d->f64 ? "Float64" : d->i32 ? "Int32" : "UInt8", d->name, d->components, ntuples,
                     el * (size_t)d->components, fill_field, mesh, d, 0, NULL, 0, NULL};
}

/* The shared encoder: fields, then the mesh arrays from mesh (box or explicit). */
static sessile_status write_vtu_mesh(const char *path, const vtu_mesh *mesh, uint32_t nv, uint64_t nt,
                                     int npf, const sessile_vtu_field *pf, int ncf,
                                     const sessile_vtu_field *cf) {
  /* offsets reach 4 nt, node indices nv - 1 */
  int wide = 4 * nt > INT32_MAX || (uint64_t)nv - 1 > INT32_MAX;
  const char *itype = wide ? "Int64" : "Int32";
  size_t isz = wide ? 8 : 4;
  int narr = npf + ncf + 4;
  vtu_array *arr = calloc((size_t)narr, sizeof *arr);
  SESSILE_CHECK(arr, SESSILE_ERR_NO_MEMORY, "out of memory writing '%s'", path);
  int k = 0;
  for (int q = 0; q < npf; q++) arr[k++] = field_array(&pf[q], nv, mesh);
  for (int q = 0; q < ncf; q++) arr[k++] = field_array(&cf[q], nt, mesh);
  arr[k++] = (vtu_array){"Float64", NULL, 3, nv, 24, mesh->box ? fill_points_box : fill_points_xyz,
                         mesh, NULL, 0, NULL, 0, NULL};
  arr[k++] = (vtu_array){itype, "connectivity", 1, nt, 4 * isz,
                         mesh->box ? fill_connectivity_box : fill_connectivity_tets, mesh, NULL, wide, NULL, 0, NULL};
  arr[k++] = (vtu_array){itype, "offsets", 1, nt, isz, fill_offsets, mesh, NULL, wide, NULL, 0, NULL};
  arr[k++] = (vtu_array){"UInt8", "types", 1, nt, 1, fill_types, mesh, NULL, 0, NULL, 0, NULL};

  sessile_status st = SESSILE_OK;
  for (int q = 0; q < narr && st == SESSILE_OK; q++) st = io_vtk_compress(path, &arr[q]);
  if (st == SESSILE_OK) st = write_vtu_file(path, nv, npf, ncf, arr, narr);
  for (int q = 0; q < narr; q++) free(arr[q].blob);
  free(arr);
  return st;
}

sessile_status sessile_write_vtu(const char *path, const sessile_box *box, int ndata,
                                 const sessile_point_data *data) {
  SESSILE_CHECK(path && path[0], SESSILE_ERR_USAGE, "cannot write a VTU file: no path given");
  SESSILE_CHECK(box && box->n[0] >= 2 && box->n[1] >= 2 && box->n[2] >= 2, SESSILE_ERR_USAGE,
                "cannot write '%s': the box needs at least 2 nodes per axis", path);
  SESSILE_CHECK(ndata >= 0 && ndata <= 64 && (ndata == 0 || data), SESSILE_ERR_USAGE,
                "cannot write '%s': %d point data arrays (0..64 allowed)", path, ndata);
  sessile_vtu_field f[64];
  for (int q = 0; q < ndata; q++) {
    const sessile_point_data *d = &data[q];
    SESSILE_CHECK(d->name && d->name[0] && (d->f64 || d->u8), SESSILE_ERR_USAGE,
                  "cannot write '%s': point data %d needs a name and values", path, q);
    SESSILE_CHECK(d->components == 1 || (d->components == 3 && d->f64), SESSILE_ERR_USAGE,
                  "cannot write '%s': point data '%s' has %d components (1, or 3 for doubles)", path,
                  d->name, d->components);
    f[q] = (sessile_vtu_field){.name = d->name, .f64 = d->f64, .u8 = d->f64 ? NULL : d->u8,
                               .components = d->components};
  }
  uint64_t nodes = sessile_box_nodes(box);
  uint64_t ntets = 6ull * (box->n[0] - 1) * (box->n[1] - 1) * (box->n[2] - 1);
  SESSILE_CHECK(nodes <= UINT32_MAX, SESSILE_ERR_TOO_LARGE, "cannot write '%s': %llu nodes", path,
                (unsigned long long)nodes);
  vtu_mesh mesh = {.box = box};
  return write_vtu_mesh(path, &mesh, (uint32_t)nodes, ntets, ndata, f, 0, NULL);
}

sessile_status sessile_write_vtu_tets(const char *path, const double *xyz, uint32_t nv,
                                      const uint32_t *tets, uint32_t nt, int npoint,
                                      const sessile_vtu_field *pf, int ncell,
                                      const sessile_vtu_field *cf) {
  SESSILE_CHECK(path && path[0], SESSILE_ERR_USAGE, "cannot write a VTU file: no path given");
  SESSILE_CHECK(nv > 0 && nt > 0, SESSILE_ERR_USAGE,
                "cannot write '%s': the mesh has %u points and %u tets (at least 1 of each needed)", path,
                nv, nt);
  SESSILE_CHECK(xyz && tets, SESSILE_ERR_USAGE, "cannot write '%s': no point or tet array given", path);
  SESSILE_CALL(check_fields(path, "point", npoint, pf));
  SESSILE_CALL(check_fields(path, "cell", ncell, cf));
  for (uint64_t q = 0; q < 3ull * nv; q++)
    SESSILE_CHECK(isfinite(xyz[q]), SESSILE_ERR_USAGE,
                  "cannot write '%s': point %llu has a non-finite coordinate (%g)", path,
                  (unsigned long long)(q / 3), xyz[q]);
  for (uint64_t q = 0; q < 4ull * nt; q++)
    SESSILE_CHECK(tets[q] < nv, SESSILE_ERR_USAGE, "cannot write '%s': tet %llu refers to point %u of %u",
                  path, (unsigned long long)(q / 4), tets[q], nv);
  vtu_mesh mesh = {.xyz = xyz, .tets = tets};
  return write_vtu_mesh(path, &mesh, nv, nt, npoint, pf, ncell, cf);
}

/* The collection: integer steps (steps) or simulated times (times, exact in
 * %.17g; an integer prints as %d would print it). */
static sessile_status write_pvd(const char *path, int n, const int *steps, const double *times,
                                const char *const *files) {
  SESSILE_CHECK(n >= 0 && (n == 0 || ((steps || times) && files)), SESSILE_ERR_USAGE,
                "cannot write '%s': %d entries", path, n);
  for (int q = 0; q < n; q++) {
    SESSILE_CHECK(files[q] && files[q][0], SESSILE_ERR_USAGE, "cannot write '%s': entry %d has no file",
                  path, q);
    SESSILE_CHECK(!times || isfinite(times[q]), SESSILE_ERR_USAGE,
                  "cannot write '%s': entry %d's time is not finite", path, q);
  }
  sessile_atomic_file af;
  SESSILE_CALL(sessile_atomic_open(path, &af));
  sessile_status st = io_printf(&af, "<?xml version=\"1.0\"?>\n"
                                     "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
                                     "  <Collection>\n");
  for (int q = 0; q < n && st == SESSILE_OK; q++) {
    if (times) st = io_printf(&af, "    <DataSet timestep=\"%.17g\" group=\"\" part=\"0\" file=\"", times[q]);
    else st = io_printf(&af, "    <DataSet timestep=\"%d\" group=\"\" part=\"0\" file=\"", steps[q]);
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

sessile_status sessile_write_pvd(const char *path, int n, const int *timesteps,
                                 const char *const *files) {
  return write_pvd(path, n, timesteps, NULL, files);
}

sessile_status sessile_write_pvd_times(const char *path, int n, const double *times,
                                       const char *const *files) {
  return write_pvd(path, n, NULL, times, files);
}
