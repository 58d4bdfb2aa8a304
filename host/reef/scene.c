/* The scene file (docs/reef.md, "Scene file"): strict JSON into
 * sessile_reef_scene.  Generators and their parameters are checked by the
 * caller that knows them (the CLI); everything else here. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "reef/reef_internal.h"
#include "reef/reef_json.h"
#include "sessile/reef/reef.h"

#define BIG 1e6 /* metres: any coordinate of a scene */

static sessile_status seabed(const rj_obj *root, sessile_reef_scene *s) {
  rj_obj sb, nz;
  const cJSON *j = rj_get(root, "seabed");
  if (!j) return rj_fail(root, "seabed", "is required");
  SESSILE_CALL(rj_open(&sb, j, root->where, "seabed"));
  SESSILE_CALL(rj_known(&sb, (const char *const[]){"noise", "mesh", "image", NULL}));
  if (!!rj_get(&sb, "noise") + !!rj_get(&sb, "mesh") + !!rj_get(&sb, "image") != 1)
    return rj_fail(&sb, NULL, "needs one of \"noise\", \"mesh\" and \"image\" (the seabed's kind)");
  if (rj_get(&sb, "image")) {
    SESSILE_CALL(rj_open(&nz, rj_get(&sb, "image"), root->where, "seabed.image"));
    return reef_seabed_image(&nz, s);
  }
  if (rj_get(&sb, "mesh")) {
    SESSILE_CALL(rj_open(&nz, rj_get(&sb, "mesh"), root->where, "seabed.mesh"));
    return reef_seabed_mesh(&nz, s);
  }
  SESSILE_CALL(rj_open(&nz, rj_get(&sb, "noise"), root->where, "seabed.noise"));
  SESSILE_CALL(rj_known(&nz, (const char *const[]){"seed", "resolution", "extent", "height_scale", "base",
                                                   "wavelength", "octaves", NULL}));
  double res[2] = {129, 129};
  SESSILE_CALL(rj_seed(&nz, "seed", &s->seabed_seed));
  SESSILE_CALL(rj_nums(&nz, "resolution", 0, 2, 2, 4097, res));
  for (int a = 0; a < 2; a++) {
    if (res[a] != floor(res[a])) return rj_fail(&nz, "resolution", "must be integers");
    s->res[a] = (uint32_t)res[a];
  }
  SESSILE_CALL(rj_nums(&nz, "extent", 1, 2, 1e-3, BIG, s->extent));
  SESSILE_CALL(rj_num(&nz, "height_scale", 0, 0, BIG, &s->height_scale));
  SESSILE_CALL(rj_num(&nz, "base", 0, -BIG, BIG, &s->base));
  SESSILE_CALL(rj_num(&nz, "wavelength", 0, 1e-3, BIG, &s->wavelength));
  return rj_int(&nz, "octaves", 0, 1, 12, &s->octaves);
}

static sessile_status rotate_axes(const rj_obj *o, sessile_reef_entry *e) {
  const cJSON *j = rj_get(o, "rotate");
  if (!j) return SESSILE_OK;
  if (!cJSON_IsArray(j)) return rj_fail(o, "rotate", "must be an array of axes (\"x\", \"y\", \"z\")");
  e->rotate[2] = 0;
  for (const cJSON *a = j->child; a; a = a->next) {
    const char *v = cJSON_IsString(a) ? a->valuestring : "";
    int k = !strcmp(v, "x") ? 0 : !strcmp(v, "y") ? 1 : !strcmp(v, "z") ? 2 : -1;
    if (k < 0 || e->rotate[k] == 2) return rj_fail(o, "rotate", "axes are \"x\", \"y\", \"z\", each once");
    e->rotate[k] = 2;
  }
  for (int k = 0; k < 3; k++) e->rotate[k] = e->rotate[k] == 2;
  return SESSILE_OK;
}

/* "parameters" ("name=value" strings, kv) or "arguments" (any strings). */
static sessile_status strings(const rj_obj *o, const char *key, int kv, char ***out, int *count) {
  const char *what = kv ? "\"name=value\" strings" : "strings";
  const cJSON *j = rj_get(o, key);
  if (!j) return SESSILE_OK;
  int n = cJSON_IsArray(j) ? cJSON_GetArraySize(j) : -1;
  if (n < 0 || n > 256) return rj_fail(o, key, "must be an array of %s (at most 256)", what);
  *out = calloc((size_t)n + 1, sizeof **out);
  SESSILE_CHECK(*out, SESSILE_ERR_NO_MEMORY, "out of host memory");
  for (const cJSON *a = j->child; a; a = a->next) {
    if (!cJSON_IsString(a) || (kv && (!strchr(a->valuestring, '=') || a->valuestring[0] == '=')))
      return rj_fail(o, key, "entry %d must be a %s", *count, kv ? "\"name=value\" string (as --set)" : "string");
    SESSILE_CHECK((*out)[(*count)++] = strdup(a->valuestring), SESSILE_ERR_NO_MEMORY, "out of host memory");
  }
  return SESSILE_OK;
}

static sessile_status entry(const char *where, const cJSON *j, int k, sessile_reef_entry *e) {
  rj_obj o;
  char path[32];
  snprintf(path, sizeof path, "pool[%d]", k);
  SESSILE_CALL(rj_open(&o, j, where, path));
  SESSILE_CALL(rj_known(&o, (const char *const[]){"name", "generator", "parameters", "arguments", "colour",
                                                  "roughness", "bias", "size", "follow_terrain", "rotate", "depth",
                                                  NULL}));
  SESSILE_CALL(rj_str(&o, "name", 1, &e->name));
  SESSILE_CALL(rj_str(&o, "generator", 1, &e->generator));
  SESSILE_CALL(strings(&o, "parameters", 1, &e->settings, &e->nsettings));
  SESSILE_CALL(strings(&o, "arguments", 0, &e->arguments, &e->narguments));
  double c[4] = {0.8, 0.5, 0.4, 1}, r = 0.7, size[2] = {0.2, 0.4};
  SESSILE_CALL(rj_nums(&o, "colour", 0, 4, 0, 1, c));
  SESSILE_CALL(rj_num(&o, "roughness", 0, 0, 1, &r));
  for (int a = 0; a < 4; a++) e->rgba[a] = (float)c[a];
  e->roughness = (float)r, e->bias = 1, e->follow_terrain = 1, e->rotate[2] = 1;
  e->depth[0] = 0.5, e->depth[1] = 20;
  SESSILE_CALL(rj_num(&o, "bias", 0, 0, 100, &e->bias));
  SESSILE_CALL(rj_nums(&o, "size", 0, 2, 1e-3, 1e3, size));
  if (size[1] < size[0]) return rj_fail(&o, "size", "the range's maximum %g is below its minimum %g", size[1], size[0]);
  e->size[0] = size[0], e->size[1] = size[1];
  SESSILE_CALL(rj_bool(&o, "follow_terrain", &e->follow_terrain));
  SESSILE_CALL(rotate_axes(&o, e));
  SESSILE_CALL(rj_nums(&o, "depth", 0, 2, -BIG, BIG, e->depth));
  if (e->depth[1] < e->depth[0]) return rj_fail(&o, "depth", "the band's deepest is above its shallowest");
  return SESSILE_OK;
}

static sessile_status stroke(const char *where, const sessile_reef_scene *s, const cJSON *j, int k,
                             sessile_reef_stroke *b) {
  rj_obj o;
  char path[32];
  snprintf(path, sizeof path, "brushes[%d]", k);
  SESSILE_CALL(rj_open(&o, j, where, path));
  SESSILE_CALL(rj_known(&o, (const char *const[]){"points", "size", "density", "density_unit", "kind", NULL}));
  const cJSON *p = rj_get(&o, "points");
  int n = cJSON_IsArray(p) ? cJSON_GetArraySize(p) : 0;
  if (n < 1 || n > 100000) return rj_fail(&o, "points", "must be an array of 1 to 100000 [x, y] points (m)");
  SESSILE_CHECK(b->pts = calloc(2 * (size_t)n, sizeof *b->pts), SESSILE_ERR_NO_MEMORY, "out of host memory");
  for (const cJSON *e = p->child; e; e = e->next, b->npts++) {
    char key[48];
    snprintf(key, sizeof key, "points[%d]", b->npts);
    double *x = b->pts + 2 * b->npts;
    if (!cJSON_IsArray(e) || cJSON_GetArraySize(e) != 2 || !cJSON_IsNumber(e->child) ||
        !cJSON_IsNumber(e->child->next))
      return rj_fail(&o, key, "must be [x, y] (m)");
    x[0] = e->child->valuedouble, x[1] = e->child->next->valuedouble;
    if (!(x[0] >= 0 && x[0] <= s->extent[0] && x[1] >= 0 && x[1] <= s->extent[1]))
      return rj_fail(&o, key, "(%g, %g) is off the seabed [0, %g] x [0, %g]", x[0], x[1], s->extent[0], s->extent[1]);
  }
  b->size = 1, b->density = 1;
  SESSILE_CALL(rj_num(&o, "size", 0, 1e-3, BIG, &b->size));
  SESSILE_CALL(rj_num(&o, "density", 0, 0, 1e12, &b->density));
  const cJSON *u = rj_get(&o, "density_unit"), *kind = rj_get(&o, "kind");
  if (u && !(cJSON_IsString(u) && (!strcmp(u->valuestring, "per_point") || !strcmp(u->valuestring, "per_m2"))))
    return rj_fail(&o, "density_unit", "must be \"per_point\" or \"per_m2\"");
  b->per_m2 = u && !strcmp(u->valuestring, "per_m2");
  if (kind && !(cJSON_IsString(kind) && (!strcmp(kind->valuestring, "standard") || !strcmp(kind->valuestring, "automatic"))))
    return rj_fail(&o, "kind", "must be \"standard\" or \"automatic\"");
  b->kind = kind && !strcmp(kind->valuestring, "automatic") ? SESSILE_REEF_AUTOMATIC : SESSILE_REEF_STANDARD;
  return SESSILE_OK;
}

static sessile_status current(const char *where, const cJSON *j, int k, sessile_reef_current *c) {
  rj_obj o;
  char path[32];
  snprintf(path, sizeof path, "currents[%d]", k);
  SESSILE_CALL(rj_open(&o, j, where, path));
  SESSILE_CALL(rj_known(&o, (const char *const[]){"origin", "direction", "strength", "nutrition_range", NULL}));
  SESSILE_CALL(rj_nums(&o, "origin", 1, 3, -BIG, BIG, c->origin));
  SESSILE_CALL(rj_nums(&o, "direction", 1, 3, -BIG, BIG, c->dir));
  double n = sqrt(c->dir[0] * c->dir[0] + c->dir[1] * c->dir[1] + c->dir[2] * c->dir[2]);
  if (!(n > 1e-12)) return rj_fail(&o, "direction", "must not be zero");
  for (int a = 0; a < 3; a++) c->dir[a] /= n;
  SESSILE_CALL(rj_num(&o, "strength", 1, 1e-6, BIG, &c->strength));
  SESSILE_CALL(rj_num(&o, "nutrition_range", 1, 1e-6, BIG, &c->range));
  return SESSILE_OK;
}

/* "pool": [...] etc.: each element through one of the readers above. */
static sessile_status array(const rj_obj *root, const char *key, int required, int max, size_t size, void **out,
                            int *n) {
  const cJSON *j = rj_get(root, key);
  if (!j) return required ? rj_fail(root, key, "is required") : SESSILE_OK;
  int m = cJSON_IsArray(j) ? cJSON_GetArraySize(j) : -1;
  if (m < (required ? 1 : 0) || m > max) return rj_fail(root, key, "must be an array of %d to %d objects", required, max);
  *out = calloc((size_t)m + 1, size);
  SESSILE_CHECK(*out, SESSILE_ERR_NO_MEMORY, "out of host memory");
  *n = m;
  return SESSILE_OK;
}

static sessile_status parse(const cJSON *root, const char *where, sessile_reef_scene *s) {
  rj_obj r, g;
  SESSILE_CALL(rj_open(&r, root, where, ""));
  SESSILE_CALL(rj_known(&r, (const char *const[]){"seabed", "sea_level", "pool", "brushes", "currents", "growth",
                                                  NULL}));
  s->res[0] = s->res[1] = 129, s->height_scale = 2, s->base = -6, s->wavelength = 8, s->octaves = 4;
  s->seabed_seed = 1, s->spacing = 1;
  SESSILE_CALL(seabed(&r, s));
  SESSILE_CALL(rj_num(&r, "sea_level", 0, -BIG, BIG, &s->sea_level));
  SESSILE_CALL(array(&r, "pool", 1, 1024, sizeof *s->entries, (void **)&s->entries, &s->nentries));
  int k = 0;
  for (const cJSON *e = rj_get(&r, "pool")->child; e; e = e->next, k++)
    SESSILE_CALL(entry(where, e, k, &s->entries[k]));
  double bias = 0;
  for (k = 0; k < s->nentries; k++) bias += s->entries[k].bias;
  if (!(bias > 0)) return rj_fail(&r, "pool", "every entry's bias is 0: none could be chosen");
  SESSILE_CALL(array(&r, "brushes", 1, 100000, sizeof *s->strokes, (void **)&s->strokes, &s->nstrokes));
  k = 0;
  for (const cJSON *e = rj_get(&r, "brushes")->child; e; e = e->next, k++)
    SESSILE_CALL(stroke(where, s, e, k, &s->strokes[k]));
  SESSILE_CALL(array(&r, "currents", 0, 1024, sizeof *s->currents, (void **)&s->currents, &s->ncurrents));
  k = 0;
  for (const cJSON *e = rj_get(&r, "currents") ? rj_get(&r, "currents")->child : NULL; e; e = e->next, k++)
    SESSILE_CALL(current(where, e, k, &s->currents[k]));
  if (!rj_get(&r, "growth")) return SESSILE_OK;
  SESSILE_CALL(rj_open(&g, rj_get(&r, "growth"), where, "growth"));
  SESSILE_CALL(rj_known(&g, (const char *const[]){"steps", "spacing", NULL}));
  SESSILE_CALL(rj_int(&g, "steps", 0, 0, 10000, &s->growth_steps));
  return rj_num(&g, "spacing", 0, 1e-3, BIG, &s->spacing);
}

sessile_status sessile_reef_scene_parse(const char *text, size_t len, const char *where, sessile_reef_scene *out) {
  memset(out, 0, sizeof *out);
  SESSILE_CHECK(!memchr(text, 0, len), SESSILE_ERR_USAGE, "%s: holds a NUL byte: not a JSON scene", where);
  const char *end = NULL;
  cJSON *root = cJSON_ParseWithLengthOpts(text, len, &end, 0);
  if (!root) {
    size_t at = end && end >= text ? (size_t)(end - text) : 0;
    return sessile_error_set(SESSILE_ERR_USAGE, "%s: not valid JSON near byte %zu", where, at);
  }
  while (end < text + len && strchr(" \t\r\n", *end)) end++;
  sessile_status s = end == text + len ? parse(root, where, out)
                                       : sessile_error_set(SESSILE_ERR_USAGE, "%s: bytes after the JSON value", where);
  cJSON_Delete(root);
  if (s != SESSILE_OK) sessile_reef_scene_free(out);
  return s;
}

void sessile_reef_scene_free(sessile_reef_scene *s) {
  if (!s) return;
  for (int k = 0; s->entries && k < s->nentries; k++) {
    sessile_reef_entry *e = &s->entries[k];
    for (int i = 0; i < e->nsettings; i++) free(e->settings[i]);
    for (int i = 0; i < e->narguments; i++) free(e->arguments[i]);
    free(e->settings), free(e->arguments), free(e->name), free(e->generator);
  }
  for (int k = 0; s->strokes && k < s->nstrokes; k++) free(s->strokes[k].pts);
  free(s->entries), free(s->strokes), free(s->currents), free(s->heights);
  memset(s, 0, sizeof *s);
}
