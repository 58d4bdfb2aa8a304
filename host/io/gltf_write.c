/* glTF 2.0 binary (.glb) writer (sessile/io/gltf.h, docs/io.md "glTF"):
 * the scene is checked whole before anything is created, laid out
 * (gltf_internal.h), described in JSON (gltf_json.c), then streamed as the
 * GLB container: a 12-byte header, the JSON chunk padded with spaces, the
 * BIN chunk padded with zeros, every chunk 4-byte aligned. */
#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "gltf_internal.h"
#include "io_internal.h"
#include "sessile/mesh/surface.h"

enum { GLB_MAGIC = 0x46546C67u, GLB_JSON = 0x4E4F534Au, GLB_BIN = 0x004E4942u };

static int finite_all(const double *v, uint64_t n) {
  for (uint64_t i = 0; i < n; i++)
    if (!isfinite(v[i])) return 0;
  return 1;
}

/* "_" then upper-case letters, digits and '_' (glTF: application-specific
 * attribute semantics start with '_'). */
static int attribute_name_ok(const char *n) {
  if (!n || n[0] != '_' || !n[1] || strlen(n) > 64) return 0;
  for (const char *c = n + 1; *c; c++)
    if (!(isupper((unsigned char)*c) || isdigit((unsigned char)*c) || *c == '_')) return 0;
  return 1;
}

static sessile_status check_mesh(const sessile_gltf_scene *s, uint32_t k) {
  const sessile_gltf_mesh *m = &s->meshes[k];
  SESSILE_CHECK(m->nv > 0 && m->nt > 0 && m->pos && m->tri, SESSILE_ERR_USAGE,
                "glTF mesh %u: no vertices or no triangles", k);
  SESSILE_CHECK(m->nt <= UINT32_MAX / 3, SESSILE_ERR_USAGE, "glTF mesh %u: %u triangles are too many", k, m->nt);
  SESSILE_CHECK(finite_all(m->pos, 3ull * m->nv), SESSILE_ERR_USAGE, "glTF mesh %u: a non-finite position", k);
  SESSILE_CHECK(!m->normal || finite_all(m->normal, 3ull * m->nv), SESSILE_ERR_USAGE,
                "glTF mesh %u: a non-finite normal", k);
  for (uint64_t i = 0; i < 3ull * m->nt; i++)
    SESSILE_CHECK(m->tri[i] < m->nv, SESSILE_ERR_USAGE, "glTF mesh %u: triangle %llu names vertex %u of %u", k,
                  (unsigned long long)(i / 3), m->tri[i], m->nv);
  SESSILE_CHECK(s->nmaterials ? m->material < s->nmaterials : m->material == 0, SESSILE_ERR_USAGE,
                "glTF mesh %u: material %u of %u", k, m->material, s->nmaterials);
  SESSILE_CHECK(m->nscalars == 0 || (m->scalar_names && m->scalars), SESSILE_ERR_USAGE,
                "glTF mesh %u: %u scalars without names or values", k, m->nscalars);
  for (uint32_t q = 0; q < m->nscalars; q++) {
    const char *n = m->scalar_names[q];
    SESSILE_CHECK(attribute_name_ok(n), SESSILE_ERR_USAGE,
                  "glTF mesh %u: the attribute name '%.64s' must be '_' then A-Z, 0-9 or '_'", k, n ? n : "(null)");
    for (uint32_t p = 0; p < q; p++)
      SESSILE_CHECK(strcmp(n, m->scalar_names[p]), SESSILE_ERR_USAGE, "glTF mesh %u: attribute '%s' twice", k, n);
    SESSILE_CHECK(m->scalars[q], SESSILE_ERR_USAGE, "glTF mesh %u: attribute '%s' has no values", k, n);
    for (uint32_t v = 0; v < m->nv; v++)
      SESSILE_CHECK(isfinite(m->scalars[q][v]), SESSILE_ERR_USAGE,
                    "glTF mesh %u: attribute '%s' is not finite at vertex %u", k, n, v);
  }
  return SESSILE_OK;
}

static sessile_status check_scene(const sessile_gltf_scene *s) {
  SESSILE_CHECK(s && s->nmeshes > 0 && s->meshes, SESSILE_ERR_USAGE, "a glTF scene needs at least one mesh");
  SESSILE_CHECK(isfinite(s->metres_per_unit) && s->metres_per_unit > 0, SESSILE_ERR_USAGE,
                "glTF: metres_per_unit must be finite and above 0");
  SESSILE_CHECK(s->nmaterials == 0 || s->materials, SESSILE_ERR_USAGE, "glTF: %u materials without values",
                s->nmaterials);
  for (uint32_t k = 0; k < s->nmaterials; k++) {
    const sessile_gltf_material *m = &s->materials[k];
    int ok = m->metallic >= 0 && m->metallic <= 1 && m->roughness >= 0 && m->roughness <= 1;
    for (int c = 0; c < 4; c++) ok = ok && m->rgba[c] >= 0 && m->rgba[c] <= 1;
    SESSILE_CHECK(ok, SESSILE_ERR_USAGE, "glTF material %u: colour, metallic and roughness must be in 0..1", k);
  }
  for (uint32_t k = 0; k < s->nmeshes; k++) SESSILE_CALL(check_mesh(s, k));
  SESSILE_CHECK(s->nodes || s->nnodes == 0, SESSILE_ERR_USAGE, "glTF: %u nodes without values", s->nnodes);
  SESSILE_CHECK(!s->nodes || s->nnodes > 0, SESSILE_ERR_USAGE, "glTF: a node list of 0 nodes");
  for (uint32_t k = 0; s->nodes && k < s->nnodes; k++) {
    const sessile_gltf_node *n = &s->nodes[k];
    SESSILE_CHECK(n->mesh < s->nmeshes, SESSILE_ERR_USAGE, "glTF node %u: mesh %u of %u", k, n->mesh, s->nmeshes);
    SESSILE_CHECK(finite_all(n->matrix, 16), SESSILE_ERR_USAGE, "glTF node %u: a non-finite matrix", k);
    SESSILE_CHECK(n->matrix[3] == 0 && n->matrix[7] == 0 && n->matrix[11] == 0 && n->matrix[15] == 1,
                  SESSILE_ERR_USAGE, "glTF node %u: the matrix is not affine (last row must be 0 0 0 1)", k);
  }
  return SESSILE_OK;
}

/* The layout of every mesh and the BIN chunk's length (before padding). */
static uint64_t lay_out(const sessile_gltf_scene *s, gltf_mesh_layout *lay) {
  uint64_t off = 0;
  uint32_t acc = 0;
  for (uint32_t k = 0; k < s->nmeshes; k++) {
    const sessile_gltf_mesh *m = &s->meshes[k];
    lay[k].offset = off, lay[k].accessor = acc;
    off += (24ull + 4ull * m->nscalars) * m->nv + 12ull * m->nt;
    acc += 3 + m->nscalars;
    for (int c = 0; c < 3; c++) lay[k].min[c] = INFINITY, lay[k].max[c] = -INFINITY;
    for (uint32_t v = 0; v < m->nv; v++) {
      double p[3];
      gltf_dir(m->pos + 3ull * v, p);
      for (int c = 0; c < 3; c++) {
        double f = (float)(s->metres_per_unit * p[c]); /* the bounds of the stored floats */
        lay[k].min[c] = fmin(lay[k].min[c], f), lay[k].max[c] = fmax(lay[k].max[c], f);
      }
    }
  }
  return off;
}

/* Little-endian floats and indices through a staging buffer. */
typedef struct bin_out {
  sessile_atomic_file *af;
  uint8_t buf[1 << 16];
  size_t n;
} bin_out;

static sessile_status bin_flush(bin_out *b) {
  sessile_status st = io_write(b->af, b->buf, b->n);
  b->n = 0;
  return st;
}
static sessile_status bin_u32(bin_out *b, uint32_t v) {
  if (b->n + 4 > sizeof b->buf) SESSILE_CALL(bin_flush(b));
  io_put_u32(b->buf + b->n, v);
  b->n += 4;
  return SESSILE_OK;
}
static sessile_status bin_f32(bin_out *b, double v) {
  float f = (float)v;
  uint32_t u;
  memcpy(&u, &f, 4);
  return bin_u32(b, u);
}

/* Unit normals in sessile's frame: the caller's normalised, or area-weighted
 * ones; a zero-length one (a vertex of no triangle) is +z, so the file holds
 * unit vectors only (the validator's rule). */
static sessile_status unit_normals(const sessile_gltf_mesh *m, double **out) {
  double *n = malloc(3 * (size_t)m->nv * sizeof *n);
  SESSILE_CHECK(n, SESSILE_ERR_NO_MEMORY, "out of host memory for the normals of %u vertices", m->nv);
  if (m->normal) {
    memcpy(n, m->normal, 3 * (size_t)m->nv * sizeof *n);
  } else {
    /* sessile_surface_normals only reads the arrays */
    sessile_surface sf = {.nv = m->nv, .nf = m->nt, .pos = (double *)m->pos, .tri = (uint32_t *)m->tri};
    sessile_surface_normals(&sf, n);
  }
  for (uint32_t v = 0; v < m->nv; v++) {
    double *p = n + 3ull * v, l = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    if (!(l > 1e-300) || !isfinite(l)) p[0] = 0, p[1] = 0, p[2] = 1;
    else p[0] /= l, p[1] /= l, p[2] /= l;
  }
  *out = n;
  return SESSILE_OK;
}

static sessile_status write_mesh(bin_out *b, const sessile_gltf_mesh *m, double mpu) {
  for (uint32_t v = 0; v < m->nv; v++) {
    double p[3];
    gltf_dir(m->pos + 3ull * v, p);
    for (int c = 0; c < 3; c++) SESSILE_CALL(bin_f32(b, mpu * p[c]));
  }
  double *n = NULL;
  SESSILE_CALL(unit_normals(m, &n));
  sessile_status st = SESSILE_OK;
  for (uint32_t v = 0; st == SESSILE_OK && v < m->nv; v++) {
    double d[3];
    gltf_dir(n + 3ull * v, d);
    for (int c = 0; st == SESSILE_OK && c < 3; c++) st = bin_f32(b, d[c]);
  }
  free(n);
  SESSILE_CALL(st);
  for (uint32_t q = 0; q < m->nscalars; q++)
    for (uint32_t v = 0; v < m->nv; v++) SESSILE_CALL(bin_f32(b, m->scalars[q][v]));
  for (uint64_t i = 0; i < 3ull * m->nt; i++) SESSILE_CALL(bin_u32(b, m->tri[i]));
  return SESSILE_OK;
}

static sessile_status write_glb(sessile_atomic_file *af, const sessile_gltf_scene *s, const char *json,
                                uint64_t bin_len) {
  size_t jl = strlen(json);
  uint64_t jpad = (4 - jl % 4) % 4, bpad = (4 - bin_len % 4) % 4;
  uint64_t total = 12 + 8 + jl + jpad + 8 + bin_len + bpad;
  SESSILE_CHECK(total <= UINT32_MAX, SESSILE_ERR_USAGE, "glTF: %llu bytes are more than a GLB holds (4 GiB)",
                (unsigned long long)total);
  uint8_t head[20], *p = head;
  p = io_put_u32(io_put_u32(io_put_u32(p, GLB_MAGIC), 2), (uint32_t)total);
  io_put_u32(io_put_u32(p, (uint32_t)(jl + jpad)), GLB_JSON);
  SESSILE_CALL(io_write(af, head, sizeof head));
  SESSILE_CALL(io_write(af, json, jl));
  SESSILE_CALL(io_write(af, "   ", jpad));
  io_put_u32(io_put_u32(head, (uint32_t)(bin_len + bpad)), GLB_BIN);
  SESSILE_CALL(io_write(af, head, 8));
  bin_out *b = malloc(sizeof *b);
  SESSILE_CHECK(b, SESSILE_ERR_NO_MEMORY, "out of host memory");
  b->af = af, b->n = 0;
  sessile_status st = SESSILE_OK;
  for (uint32_t k = 0; st == SESSILE_OK && k < s->nmeshes; k++) st = write_mesh(b, &s->meshes[k], s->metres_per_unit);
  if (st == SESSILE_OK) st = bin_flush(b);
  free(b);
  static const uint8_t zeros[3];
  return st == SESSILE_OK ? io_write(af, zeros, bpad) : st; /* 0: every array is whole 4-byte words */
}

sessile_status sessile_gltf_write(const char *path, const sessile_gltf_scene *s) {
  SESSILE_CALL(check_scene(s));
  cJSON *extras = NULL;
  if (s->extras_json) {
    extras = cJSON_Parse(s->extras_json);
    int ok = cJSON_IsObject(extras);
    if (!ok) cJSON_Delete(extras);
    SESSILE_CHECK(ok, SESSILE_ERR_USAGE, "glTF: the scene's extras are not a JSON object");
  }
  gltf_mesh_layout *lay = malloc(s->nmeshes * sizeof *lay);
  cJSON *doc = NULL;
  char *json = NULL;
  if (lay) {
    uint64_t bin_len = lay_out(s, lay);
    doc = gltf_document(s, lay, bin_len, extras);
    json = doc ? cJSON_PrintUnformatted(doc) : NULL;
    if (json) {
      sessile_atomic_file af;
      sessile_status st = sessile_atomic_open(path, &af);
      if (st == SESSILE_OK) st = write_glb(&af, s, json, bin_len);
      if (st == SESSILE_OK) st = sessile_atomic_commit(&af);
      else sessile_atomic_abort(&af);
      free(json), cJSON_Delete(doc), cJSON_Delete(extras), free(lay);
      return st;
    }
  }
  free(json), cJSON_Delete(doc), cJSON_Delete(extras), free(lay);
  return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for the glTF document of '%s'", path);
}
