/* Meshes for rendering: reading by extension, the checks every input gets
 * (finite coordinates, indices in range, not empty), normals, bounds. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "mesh_internal.h"
#include "sessile/io/io_read.h"

void sessile_render_mesh_destroy(sessile_render_mesh *m) {
  if (!m) return;
  for (int i = 0; i < m->nprops; i++) {
    free(m->prop_names[i]);
    free(m->props[i]);
  }
  free(m->prop_names);
  free(m->props);
  free(m->pos);
  free(m->normal);
  free(m->tri);
  free(m);
}

const float *sessile_render_mesh_property(const sessile_render_mesh *m, const char *name) {
  for (int i = 0; i < m->nprops; i++)
    if (m->prop_names[i] && strcmp(m->prop_names[i], name) == 0) return m->props[i];
  return NULL;
}

void mesh_bounds_(const sessile_render_mesh *m, double lo[3], double hi[3]) {
  for (int k = 0; k < 3; k++) {
    lo[k] = INFINITY;
    hi[k] = -INFINITY;
  }
  for (uint32_t v = 0; v < m->nv; v++)
    for (int k = 0; k < 3; k++) {
      double x = m->pos[3 * v + k];
      if (x < lo[k]) lo[k] = x;
      if (x > hi[k]) hi[k] = x;
    }
}

/* Area-weighted vertex normals: each face adds its cross product (length
 * twice its area) to its three vertices; the sums are normalised.  A vertex
 * of only degenerate faces gets +z. */
static void compute_normals(sessile_render_mesh *m) {
  double *acc = calloc((size_t)m->nv * 3, sizeof(double));
  if (!acc) return; /* the caller checks m->normal */
  for (uint32_t f = 0; f < m->nf; f++) {
    const uint32_t *t = m->tri + 3 * f;
    const float *a = m->pos + 3 * t[0], *b = m->pos + 3 * t[1], *c = m->pos + 3 * t[2];
    double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    for (int k = 0; k < 3; k++)
      for (int j = 0; j < 3; j++) acc[3 * (size_t)t[k] + j] += n[j];
  }
  for (uint32_t v = 0; v < m->nv; v++) {
    double *n = acc + 3 * (size_t)v;
    double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int j = 0; j < 3; j++) m->normal[3 * v + j] = l > 0 ? (float)(n[j] / l) : (j == 2 ? 1.0f : 0.0f);
  }
  free(acc);
}

sessile_status mesh_finish_(const char *what, sessile_render_mesh *m) {
  SESSILE_CHECK(m->nv > 0, SESSILE_ERR_USAGE, "%s: the mesh has no vertices", what);
  SESSILE_CHECK(m->nf > 0, SESSILE_ERR_USAGE, "%s: the mesh has no faces", what);
  for (uint32_t v = 0; v < m->nv; v++)
    SESSILE_CHECK(isfinite(m->pos[3 * v]) && isfinite(m->pos[3 * v + 1]) && isfinite(m->pos[3 * v + 2]),
                  SESSILE_ERR_USAGE, "%s: vertex %u has a non-finite coordinate (%g, %g, %g)", what, v,
                  m->pos[3 * v], m->pos[3 * v + 1], m->pos[3 * v + 2]);
  for (size_t i = 0; i < 3 * (size_t)m->nf; i++)
    SESSILE_CHECK(m->tri[i] < m->nv, SESSILE_ERR_USAGE,
                  "%s: face %zu refers to vertex %u but the mesh has %u", what, i / 3, m->tri[i], m->nv);
  double lo[3], hi[3];
  mesh_bounds_(m, lo, hi);
  SESSILE_CHECK(hi[0] > lo[0] || hi[1] > lo[1] || hi[2] > lo[2], SESSILE_ERR_USAGE,
                "%s: all %u vertices are at one point: nothing to draw", what, m->nv);
  if (m->has_file_normals) {
    /* The file's normals, normalised; a zero or non-finite one is recomputed. */
    int bad = 0;
    for (uint32_t v = 0; v < m->nv; v++) {
      float *n = m->normal + 3 * v;
      double l = sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
      if (!(l > 0) || !isfinite(l)) bad = 1;
      else for (int j = 0; j < 3; j++) n[j] = (float)(n[j] / l);
    }
    if (bad) m->has_file_normals = 0;
  }
  if (!m->has_file_normals) {
    if (!m->normal) m->normal = malloc((size_t)m->nv * 3 * sizeof(float) + 1);
    SESSILE_CHECK(m->normal, SESSILE_ERR_NO_MEMORY, "%s: out of host memory for normals", what);
    compute_normals(m);
  }
  return SESSILE_OK;
}

static int ends_with(const char *s, const char *suf) {
  size_t a = strlen(s), b = strlen(suf);
  if (a < b) return 0;
  for (size_t i = 0; i < b; i++) {
    char c = s[a - b + i];
    if (c >= 'A' && c <= 'Z') c = (char)(c - 'A' + 'a');
    if (c != suf[i]) return 0;
  }
  return 1;
}

/* A mesh read by the io readers, moved into m: positions as float. */
static sessile_status take_mesh(const char *path, sessile_mesh_in *in, sessile_render_mesh *m) {
  m->pos = malloc((size_t)in->nv * 3 * sizeof(float) + 1);
  SESSILE_CHECK(m->pos, SESSILE_ERR_NO_MEMORY, "%s: out of host memory for %u vertices", path, in->nv);
  for (size_t i = 0; i < 3 * (size_t)in->nv; i++) m->pos[i] = (float)in->pos[i];
  m->nv = in->nv, m->nf = in->nf, m->tri = in->tri, m->normal = in->normal;
  m->has_file_normals = in->normal != NULL;
  m->nprops = in->nprops, m->prop_names = in->prop_names, m->props = in->props;
  free(in->pos);
  *in = (sessile_mesh_in){0};
  return SESSILE_OK;
}

sessile_status sessile_render_mesh_read(const char *path, sessile_render_mesh **out) {
  *out = NULL;
  int ply = ends_with(path, ".ply"), obj = ends_with(path, ".obj");
  SESSILE_CHECK(ply || obj, SESSILE_ERR_USAGE, "%s: unknown mesh format (use .ply or .obj)", path);
  const sessile_mesh_read_opts o = {.keep_props = 1};
  sessile_mesh_in in;
  SESSILE_CALL(ply ? sessile_read_ply(path, &o, &in) : sessile_read_obj(path, &o, &in));
  sessile_render_mesh *m = calloc(1, sizeof *m);
  sessile_status s = m ? take_mesh(path, &in, m) : sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  sessile_mesh_in_free(&in);
  if (s == SESSILE_OK) s = mesh_finish_(path, m);
  if (s != SESSILE_OK) {
    sessile_render_mesh_destroy(m);
    return s;
  }
  *out = m;
  return SESSILE_OK;
}

sessile_status sessile_render_mesh_from_arrays(const double *pos, uint32_t nv, const uint32_t *tri,
                                               uint32_t nf, sessile_render_mesh **out) {
  *out = NULL;
  sessile_render_mesh *m = calloc(1, sizeof *m);
  SESSILE_CHECK(m, SESSILE_ERR_NO_MEMORY, "out of host memory");
  m->nv = nv;
  m->nf = nf;
  m->pos = malloc((size_t)nv * 3 * sizeof(float) + 1);
  m->tri = malloc((size_t)nf * 3 * sizeof(uint32_t) + 1);
  sessile_status s = SESSILE_OK;
  if (!m->pos || !m->tri) s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  if (s == SESSILE_OK) {
    for (size_t i = 0; i < 3 * (size_t)nv; i++) m->pos[i] = (float)pos[i];
    if (nf) memcpy(m->tri, tri, (size_t)nf * 3 * sizeof(uint32_t));
    s = mesh_finish_("mesh", m);
  }
  if (s != SESSILE_OK) {
    sessile_render_mesh_destroy(m);
    return s;
  }
  *out = m;
  return SESSILE_OK;
}
