/* sessile io — a surface (a union of parts, as the PLY writer takes it) as
 * VTK XML PolyData (.vtp): what ParaView and VTK open with every per-vertex
 * value as a named point array and the run's facts as field data.
 *
 * Encoding: the .vtu's (appended raw, zlib blocks, header_type UInt64;
 * vtu.c's encoder), so a snapshot's surface costs about what its PLY does
 * and both files hold the same float32 numbers.  docs/io.md, "Surfaces for
 * ParaView". */
#include <math.h>
#include <stdlib.h>
#include "io_internal.h"

/* The union flattened: what the arrays' fill functions read. */
typedef struct vtp_flat {
  float *pos, *nrm, *fields; /* 3 tv, 3 tv (or NULL), nfields tv */
  uint32_t *tri;             /* 3 tf, indices into the union */
} vtp_flat;

static void fill_f32(const vtu_array *a, uint64_t first, uint64_t count, uint8_t *dst) {
  const float *src = (const float *)a->user + first * (uint64_t)a->components;
  for (uint64_t q = 0; q < count * (uint64_t)a->components; q++) dst = io_put_f32(dst, src[q]);
}

static void fill_connectivity(const vtu_array *a, uint64_t first, uint64_t count, uint8_t *dst) {
  const uint32_t *tri = a->user;
  for (uint64_t q = first; q < first + count; q++) dst = a->wide ? io_put_u64(dst, tri[q]) : io_put_u32(dst, tri[q]);
}

static void fill_offsets(const vtu_array *a, uint64_t first, uint64_t count, uint8_t *dst) {
  for (uint64_t t = first; t < first + count; t++)
    dst = a->wide ? io_put_u64(dst, 3 * (t + 1)) : io_put_u32(dst, (uint32_t)(3 * (t + 1)));
}

static sessile_status flatten(const char *path, int nparts, const sessile_mesh_part *parts, int nfields,
                              uint32_t tv, uint32_t tf, int normals, vtp_flat *f) {
  f->pos = malloc((size_t)tv * 3 * sizeof(float) + 1);
  f->nrm = normals ? malloc((size_t)tv * 3 * sizeof(float) + 1) : NULL;
  f->fields = malloc((size_t)tv * (size_t)nfields * sizeof(float) + 1);
  f->tri = malloc((size_t)tf * 3 * sizeof(uint32_t) + 1);
  SESSILE_CHECK(f->pos && (f->nrm || !normals) && f->fields && f->tri, SESSILE_ERR_NO_MEMORY,
                "out of memory writing '%s' (%u vertices)", path, tv);
  size_t v0 = 0, t0 = 0;
  for (int k = 0; k < nparts; k++) {
    const sessile_mesh_part *m = &parts[k];
    for (size_t q = 0; q < 3 * (size_t)m->nv; q++) {
      f->pos[3 * v0 + q] = (float)m->pos[q];
      if (normals) f->nrm[3 * v0 + q] = (float)m->normals[q];
    }
    for (int p = 0; p < nfields; p++)
      for (uint32_t v = 0; v < m->nv; v++) f->fields[(size_t)p * tv + v0 + v] = (float)m->fields[p][v];
    for (size_t q = 0; q < 3 * (size_t)m->nf; q++) f->tri[3 * t0 + q] = (uint32_t)v0 + m->tri[q];
    v0 += m->nv;
    t0 += m->nf;
  }
  return SESSILE_OK;
}

/* A one-tuple string of field data: its bytes as numbers, 0 at the end (VTK's
 * ASCII form of a vtkStringArray). */
static sessile_status field_string(sessile_atomic_file *af, const char *name, const char *value) {
  if (!value) return SESSILE_OK;
  SESSILE_CALL(io_printf(af, "      <Array type=\"String\" Name=\"%s\" NumberOfTuples=\"1\" format=\"ascii\">", name));
  for (const unsigned char *c = (const unsigned char *)value; *c; c++) SESSILE_CALL(io_printf(af, "%u ", *c));
  return io_printf(af, "0</Array>\n");
}

static sessile_status field_data(sessile_atomic_file *af, const sessile_mesh_info *info) {
  if (!info) return SESSILE_OK;
  SESSILE_CALL(io_printf(af, "    <FieldData>\n"));
  if (info->time_unit)
    SESSILE_CALL(io_printf(af, "      <DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" "
                               "format=\"ascii\">%.17g</DataArray>\n", info->time));
  if (info->iteration >= 0)
    SESSILE_CALL(io_printf(af, "      <DataArray type=\"Int32\" Name=\"iteration\" NumberOfTuples=\"1\" "
                               "format=\"ascii\">%d</DataArray>\n", info->iteration));
  const char *names[] = {"generator", "version", "commit", "seed", "length_unit", "time_unit", "state", "main_scalar"};
  const char *values[] = {info->generator, info->version, info->commit, info->seed, info->length_unit,
                          info->time_unit, info->state, info->color_by};
  for (size_t k = 0; k < sizeof names / sizeof names[0]; k++) SESSILE_CALL(field_string(af, names[k], values[k]));
  return io_printf(af, "    </FieldData>\n");
}

/* arr: nfields fields, [Normals], Points, connectivity, offsets. */
static sessile_status write_file(const char *path, uint32_t tv, uint32_t tf, int nfields, int normals,
                                 const vtu_array *arr, int narr, const sessile_mesh_info *info) {
  uint64_t off[SESSILE_VTU_MAX_FIELDS + 4], o = 0;
  for (int q = 0; q < narr; q++) off[q] = o, o += arr[q].blob_bytes;
  sessile_atomic_file af;
  SESSILE_CALL(sessile_atomic_open(path, &af));
  sessile_status st = io_printf(&af, "<?xml version=\"1.0\"?>\n"
                                     "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" "
                                     "header_type=\"UInt64\" compressor=\"vtkZLibDataCompressor\">\n"
                                     "  <PolyData>\n");
  if (st == SESSILE_OK) st = field_data(&af, info);
  if (st == SESSILE_OK)
    st = io_printf(&af, "    <Piece NumberOfPoints=\"%u\" NumberOfVerts=\"0\" NumberOfLines=\"0\" "
                        "NumberOfStrips=\"0\" NumberOfPolys=\"%u\">\n      <PointData", tv, tf);
  if (st == SESSILE_OK && info && info->color_by) {
    st = io_printf(&af, " Scalars=\"");
    if (st == SESSILE_OK) st = io_xml_escaped(&af, info->color_by);
    if (st == SESSILE_OK) st = io_printf(&af, "\"");
  }
  if (st == SESSILE_OK && normals) st = io_printf(&af, " Normals=\"Normals\"");
  if (st == SESSILE_OK) st = io_printf(&af, ">\n");
  int pts = nfields + (normals ? 1 : 0);
  for (int q = 0; q < pts && st == SESSILE_OK; q++) st = io_vtk_array_tag(&af, &arr[q], off[q]);
  if (st == SESSILE_OK) st = io_printf(&af, "      </PointData>\n      <Points>\n");
  if (st == SESSILE_OK) st = io_vtk_array_tag(&af, &arr[pts], off[pts]);
  if (st == SESSILE_OK) st = io_printf(&af, "      </Points>\n      <Polys>\n");
  for (int q = pts + 1; q < narr && st == SESSILE_OK; q++) st = io_vtk_array_tag(&af, &arr[q], off[q]);
  if (st == SESSILE_OK)
    st = io_printf(&af, "      </Polys>\n    </Piece>\n  </PolyData>\n  <AppendedData encoding=\"raw\">\n   _");
  for (int q = 0; q < narr && st == SESSILE_OK; q++) st = io_write(&af, arr[q].blob, arr[q].blob_bytes);
  if (st == SESSILE_OK) st = io_printf(&af, "\n  </AppendedData>\n</VTKFile>\n");
  if (st != SESSILE_OK) {
    sessile_atomic_abort(&af);
    return st;
  }
  return sessile_atomic_commit(&af);
}

sessile_status sessile_write_vtp(const char *path, int nparts, const sessile_mesh_part *parts, int nfields,
                                 const char *const *field_names, const sessile_mesh_info *info) {
  uint32_t tv, tf;
  int normals, main_field;
  SESSILE_CALL(io_check_parts(path, nparts, parts, nfields, field_names, &tv, &tf, &normals));
  SESSILE_CALL(io_mesh_info_check(path, info, nfields, field_names, &main_field));
  for (int p = 0; p < nfields; p++)
    SESSILE_CHECK(strcmp(field_names[p], "Normals"), SESSILE_ERR_USAGE,
                  "cannot write '%s': a field named 'Normals' would hide the normals", path);
  vtp_flat f = {0};
  vtu_array arr[SESSILE_VTU_MAX_FIELDS + 4];
  int narr = 0;
  sessile_status st = flatten(path, nparts, parts, nfields, tv, tf, normals, &f);
  int wide = 3ull * tf > INT32_MAX || (uint64_t)tv > INT32_MAX;
  const char *itype = wide ? "Int64" : "Int32";
  size_t isz = wide ? 8 : 4;
  for (int p = 0; p < nfields; p++)
    arr[narr++] = (vtu_array){"Float32", field_names[p], 1, tv, 4, fill_f32, .user = f.fields + (size_t)p * tv};
  if (normals) arr[narr++] = (vtu_array){"Float32", "Normals", 3, tv, 12, fill_f32, .user = f.nrm};
  arr[narr++] = (vtu_array){"Float32", NULL, 3, tv, 12, fill_f32, .user = f.pos};
  arr[narr++] = (vtu_array){itype, "connectivity", 1, 3ull * tf, isz, fill_connectivity, .wide = wide, .user = f.tri};
  arr[narr++] = (vtu_array){itype, "offsets", 1, tf, isz, fill_offsets, .wide = wide};
  for (int q = 0; q < narr && st == SESSILE_OK; q++) st = io_vtk_compress(path, &arr[q]);
  if (st == SESSILE_OK) st = write_file(path, tv, tf, nfields, normals, arr, narr, info);
  for (int q = 0; q < narr; q++) free(arr[q].blob);
  free(f.pos), free(f.nrm), free(f.fields), free(f.tri);
  return st;
}
