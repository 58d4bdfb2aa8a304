/* Scene files (render_scene.h): the JSON beside a PLY of the parts, read
 * and checked, and written as JSON for a caller to store. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/io/io.h"
#include "sessile/render/render_scene.h"

#define SCENE_FORMAT "sessile render scene"
#define SCENE_MAX_BYTES ((size_t)1 << 30) /* ~300 bytes an instance: 10^6 organisms fit */

int sessile_render_is_scene(const char *path) {
  size_t n = strlen(path);
  return n >= 5 && !strcmp(path + n - 5, ".json");
}

void sessile_render_scene_destroy(sessile_render_scene *s) {
  if (!s) return;
  sessile_render_mesh_destroy(s->mesh);
  free(s->parts);
  free(s->inst);
  free(s);
}

/* Finite, affine (last row 0 0 0 1) and invertible: the normals' inverse
 * transpose exists.  The determinant is compared with the scale cubed. */
static int matrix_ok(const double *m) {
  double big = 0;
  for (int i = 0; i < 16; i++) {
    if (!isfinite(m[i])) return 0;
    if ((i & 3) < 3 && i < 12) big = fmax(big, fabs(m[i]));
  }
  if (m[3] != 0 || m[7] != 0 || m[11] != 0 || m[15] != 1) return 0;
  double det = m[0] * (m[5] * m[10] - m[9] * m[6]) - m[4] * (m[1] * m[10] - m[9] * m[2]) +
               m[8] * (m[1] * m[6] - m[5] * m[2]);
  return big > 0 && fabs(det) > 1e-12 * big * big * big;
}

sessile_status sessile_render_scene_check(const char *what, const sessile_render_scene *s) {
  const sessile_render_mesh *m = s->mesh;
  SESSILE_CHECK(m && s->nparts > 0 && s->ninst > 0, SESSILE_ERR_USAGE, "%s: no %s", what,
                !m ? "mesh" : s->nparts ? "instance" : "part");
  for (uint32_t p = 0; p < s->nparts; p++) {
    const sessile_render_part *t = &s->parts[p];
    SESSILE_CHECK(t->nv > 0 && t->nf > 0 && t->first_vertex <= m->nv && t->nv <= m->nv - t->first_vertex &&
                      t->first_face <= m->nf && t->nf <= m->nf - t->first_face,
                  SESSILE_ERR_USAGE, "%s: part %u (vertices %u+%u, faces %u+%u) is empty or outside the mesh "
                  "(%u vertices, %u faces)", what, p, t->first_vertex, t->nv, t->first_face, t->nf, m->nv, m->nf);
    for (size_t i = 3 * (size_t)t->first_face; i < 3 * ((size_t)t->first_face + t->nf); i++)
      SESSILE_CHECK(m->tri[i] - t->first_vertex < t->nv, SESSILE_ERR_USAGE,
                    "%s: part %u's face %zu uses vertex %u, not one of the part's", what, p, i / 3, m->tri[i]);
  }
  for (uint32_t i = 0; i < s->ninst; i++) {
    SESSILE_CHECK(s->inst[i].part < s->nparts, SESSILE_ERR_USAGE, "%s: instance %u names part %u of %u", what, i,
                  s->inst[i].part, s->nparts);
    SESSILE_CHECK(matrix_ok(s->inst[i].matrix), SESSILE_ERR_USAGE,
                  "%s: instance %u's matrix is not a finite, invertible affine transform", what, i);
  }
  return SESSILE_OK;
}

/* A whole number in 0..max, else -1. */
static double whole(const cJSON *j, double max) {
  if (!cJSON_IsNumber(j)) return -1;
  double v = j->valuedouble;
  return v >= 0 && v <= max && v == floor(v) ? v : -1;
}

static sessile_status parse_parts(const char *path, const cJSON *a, sessile_render_scene *s) {
  SESSILE_CHECK(cJSON_IsArray(a) && cJSON_GetArraySize(a) > 0, SESSILE_ERR_USAGE,
                "%s: \"parts\" must be a non-empty array", path);
  s->nparts = (uint32_t)cJSON_GetArraySize(a);
  s->parts = calloc(s->nparts, sizeof *s->parts);
  SESSILE_CHECK(s->parts, SESSILE_ERR_NO_MEMORY, "out of host memory");
  uint32_t p = 0;
  for (const cJSON *e = a->child; e; e = e->next, p++) {
    double v[4];
    int ok = cJSON_IsArray(e) && cJSON_GetArraySize(e) == 4;
    for (int k = 0; ok && k < 4; k++) ok = (v[k] = whole(cJSON_GetArrayItem(e, k), UINT32_MAX)) >= 0;
    SESSILE_CHECK(ok, SESSILE_ERR_USAGE, "%s: parts[%u] must be [first_vertex, nv, first_face, nf]", path, p);
    s->parts[p] = (sessile_render_part){(uint32_t)v[0], (uint32_t)v[1], (uint32_t)v[2], (uint32_t)v[3]};
  }
  return SESSILE_OK;
}

static sessile_status parse_instances(const char *path, const cJSON *a, sessile_render_scene *s) {
  SESSILE_CHECK(cJSON_IsArray(a) && cJSON_GetArraySize(a) > 0, SESSILE_ERR_USAGE,
                "%s: \"instances\" must be a non-empty array", path);
  s->ninst = (uint32_t)cJSON_GetArraySize(a);
  s->inst = calloc(s->ninst, sizeof *s->inst);
  SESSILE_CHECK(s->inst, SESSILE_ERR_NO_MEMORY, "out of host memory");
  uint32_t i = 0;
  for (const cJSON *e = a->child; e; e = e->next, i++) {
    const cJSON *part = cJSON_GetObjectItemCaseSensitive(e, "part");
    const cJSON *rgb = cJSON_GetObjectItemCaseSensitive(e, "rgb");
    const cJSON *mat = cJSON_GetObjectItemCaseSensitive(e, "matrix");
    double v = whole(part, UINT32_MAX);
    int ok = v >= 0 && cJSON_IsArray(rgb) && cJSON_GetArraySize(rgb) == 3 && cJSON_IsArray(mat) &&
             cJSON_GetArraySize(mat) == 16;
    sessile_render_instance *in = &s->inst[i];
    in->part = ok ? (uint32_t)v : 0;
    for (int k = 0; ok && k < 3; k++) {
      double c = whole(cJSON_GetArrayItem(rgb, k), 255);
      ok = c >= 0;
      in->rgba[k] = (unsigned char)(ok ? c : 0);
    }
    in->rgba[3] = 255;
    int k = 0;
    for (const cJSON *x = ok ? mat->child : NULL; x; x = x->next, k++)
      if (!(ok = cJSON_IsNumber(x))) break;
      else in->matrix[k] = x->valuedouble;
    SESSILE_CHECK(ok, SESSILE_ERR_USAGE,
                  "%s: instances[%u] must be {\"part\": N, \"rgb\": [0..255 x 3], \"matrix\": [16 numbers]}", path, i);
  }
  return SESSILE_OK;
}

/* The mesh's path: relative to the scene file's folder. */
static sessile_status mesh_path(const char *path, const cJSON *mesh, char *out, size_t cap) {
  SESSILE_CHECK(cJSON_IsString(mesh) && mesh->valuestring[0], SESSILE_ERR_USAGE,
                "%s: \"mesh\" must name the parts' PLY", path);
  const char *slash = strrchr(path, '/');
  int dir = slash ? (int)(slash - path + 1) : 0;
  int n = mesh->valuestring[0] == '/' ? snprintf(out, cap, "%s", mesh->valuestring)
                                      : snprintf(out, cap, "%.*s%s", dir, path, mesh->valuestring);
  SESSILE_CHECK(n > 0 && (size_t)n < cap, SESSILE_ERR_USAGE, "%s: the mesh's path is too long", path);
  return SESSILE_OK;
}

static sessile_status parse(const char *path, const cJSON *root, sessile_render_scene *s) {
  const cJSON *fmt = cJSON_GetObjectItemCaseSensitive(root, "format");
  const cJSON *ver = cJSON_GetObjectItemCaseSensitive(root, "version");
  SESSILE_CHECK(cJSON_IsString(fmt) && !strcmp(fmt->valuestring, SCENE_FORMAT) && whole(ver, 1) == 1,
                SESSILE_ERR_USAGE, "%s: not a scene file (\"format\": \"" SCENE_FORMAT "\", \"version\": 1)", path);
  char mesh[4096];
  SESSILE_CALL(mesh_path(path, cJSON_GetObjectItemCaseSensitive(root, "mesh"), mesh, sizeof mesh));
  SESSILE_CALL(parse_parts(path, cJSON_GetObjectItemCaseSensitive(root, "parts"), s));
  SESSILE_CALL(parse_instances(path, cJSON_GetObjectItemCaseSensitive(root, "instances"), s));
  SESSILE_CALL(sessile_render_mesh_read(mesh, &s->mesh));
  return sessile_render_scene_check(path, s);
}

sessile_status sessile_render_scene_read(const char *path, sessile_render_scene **out) {
  *out = NULL;
  char *text = NULL;
  size_t len = 0;
  SESSILE_CALL(sessile_read_small_file(path, SCENE_MAX_BYTES, "scene", &text, &len));
  cJSON *root = cJSON_ParseWithLength(text, len);
  free(text);
  SESSILE_CHECK(root, SESSILE_ERR_USAGE, "%s: not JSON", path);
  sessile_render_scene *s = calloc(1, sizeof *s);
  sessile_status st = s ? parse(path, root, s) : sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  cJSON_Delete(root);
  if (st != SESSILE_OK) {
    sessile_render_scene_destroy(s);
    return st;
  }
  *out = s;
  return SESSILE_OK;
}

/* Numbers printed so that they read back exactly (cJSON's own printing
 * keeps 15 digits when they read back within an epsilon): the shortest of
 * %.15g, %.16g, %.17g that does. */
static cJSON *exact_array(const double *v, int n) {
  cJSON *a = cJSON_CreateArray();
  for (int i = 0; a && i < n; i++) {
    char buf[40];
    for (int digits = 15; digits <= 17; digits++) {
      snprintf(buf, sizeof buf, "%.*g", digits, v[i]);
      if (strtod(buf, NULL) == v[i]) break;
    }
    cJSON *x = cJSON_CreateRaw(buf);
    if (!x || !cJSON_AddItemToArray(a, x)) {
      cJSON_Delete(x);
      cJSON_Delete(a);
      return NULL;
    }
  }
  return a;
}

cJSON *sessile_render_scene_json(const char *mesh_file, const sessile_render_part *parts, uint32_t nparts,
                                 const sessile_render_instance *inst, uint32_t ninst) {
  cJSON *root = cJSON_CreateObject(), *pa = cJSON_CreateArray(), *ia = cJSON_CreateArray();
  int ok = root && pa && ia && cJSON_AddStringToObject(root, "format", SCENE_FORMAT) &&
           cJSON_AddNumberToObject(root, "version", 1) && cJSON_AddStringToObject(root, "mesh", mesh_file);
  if (ok && (ok = cJSON_AddItemToObject(root, "parts", pa))) pa = NULL; /* owned by root now */
  if (ok && (ok = cJSON_AddItemToObject(root, "instances", ia))) ia = NULL;
  cJSON *parts_a = ok ? cJSON_GetObjectItemCaseSensitive(root, "parts") : NULL;
  cJSON *inst_a = ok ? cJSON_GetObjectItemCaseSensitive(root, "instances") : NULL;
  for (uint32_t p = 0; ok && p < nparts; p++) {
    const double v[4] = {parts[p].first_vertex, parts[p].nv, parts[p].first_face, parts[p].nf};
    cJSON *e = cJSON_CreateDoubleArray(v, 4);
    ok = e && cJSON_AddItemToArray(parts_a, e);
    if (!ok) cJSON_Delete(e);
  }
  for (uint32_t i = 0; ok && i < ninst; i++) {
    const int rgb[3] = {inst[i].rgba[0], inst[i].rgba[1], inst[i].rgba[2]};
    cJSON *e = cJSON_CreateObject();
    ok = e && cJSON_AddItemToArray(inst_a, e);
    if (!ok) cJSON_Delete(e);
    cJSON *c = ok ? cJSON_CreateIntArray(rgb, 3) : NULL, *m = ok ? exact_array(inst[i].matrix, 16) : NULL;
    ok = ok && cJSON_AddNumberToObject(e, "part", inst[i].part) && c && cJSON_AddItemToObject(e, "rgb", c);
    if (!ok) cJSON_Delete(c);
    ok = ok && m && cJSON_AddItemToObject(e, "matrix", m);
    if (!ok) cJSON_Delete(m);
  }
  cJSON_Delete(pa);
  cJSON_Delete(ia);
  if (!ok) cJSON_Delete(root);
  return ok ? root : NULL;
}
