/* placements.json (docs/reef.md, "Output"): every placement with what
 * makes it again.  Seeds as decimal strings (64 bits survive JSON). */
#include <inttypes.h>
#include <stdio.h>
#include "sessile/reef/reef.h"

static cJSON *numbers(const double *v, int n, double scale) {
  cJSON *a = cJSON_CreateArray();
  for (int k = 0; a && k < n; k++)
    if (!cJSON_AddItemToArray(a, cJSON_CreateNumber(v[k] * scale))) return cJSON_Delete(a), NULL;
  return a;
}

static int one(cJSON *arr, const sessile_reef_scene *s, const sessile_reef_placement *p, const sessile_reef_gltf *g,
               uint32_t k) {
  const sessile_reef_entry *e = &s->entries[p->entry];
  cJSON *o = cJSON_CreateObject();
  if (!o || !cJSON_AddItemToArray(arr, o)) return cJSON_Delete(o), 0;
  char seed[24];
  snprintf(seed, sizeof seed, "%" PRIu64, p->seed);
  /* cJSON makes no array of no strings: an entry without parameters has [] */
  cJSON *set = e->nsettings ? cJSON_CreateStringArray((const char *const *)e->settings, e->nsettings)
                            : cJSON_CreateArray();
  int ok = cJSON_AddStringToObject(o, "entry", e->name) && cJSON_AddStringToObject(o, "generator", e->generator) &&
           set && cJSON_AddItemToObject(o, "parameters", set) && cJSON_AddStringToObject(o, "seed", seed) &&
           cJSON_AddStringToObject(o, "brush", p->stroke == UINT32_MAX ? "grown" : p->automatic ? "automatic"
                                                                                                : "standard") &&
           cJSON_AddItemToObject(o, "position", numbers(p->pos, 3, 1)) &&
           cJSON_AddItemToObject(o, "up", numbers(p->up, 3, 1)) &&
           cJSON_AddItemToObject(o, "rotation", numbers(p->angle, 3, 1)) && cJSON_AddNumberToObject(o, "size", p->size) &&
           cJSON_AddNumberToObject(o, "depth", p->depth) && cJSON_AddNumberToObject(o, "exposure", p->exposure);
  if (!set) return 0;
  if (ok && e->narguments) { /* only where given: the placements of other scenes keep their bytes */
    cJSON *args = cJSON_CreateStringArray((const char *const *)e->arguments, e->narguments);
    ok = args && cJSON_AddItemToObject(o, "arguments", args);
    if (!args) return 0;
  }
  if (ok && g) {
    /* the node matrix maps the mesh (cm) to the scene in cm: rows x, y, z to metres */
    double m[16];
    for (int i = 0; i < 16; i++) m[i] = g->nodes[k + 1].matrix[i] * (i % 4 < 3 ? 0.01 : 1);
    ok = cJSON_AddNumberToObject(o, "mesh", g->node_mesh[k]) && cJSON_AddItemToObject(o, "transform", numbers(m, 16, 1));
  }
  return ok;
}

cJSON *sessile_reef_placements_json(const sessile_reef_scene *s, const sessile_reef_placements *pl,
                                    const sessile_reef_gltf *g) {
  cJSON *root = cJSON_CreateObject(), *arr = cJSON_CreateArray();
  int ok = root && arr && cJSON_AddItemToObject(root, "units", cJSON_CreateString(
                                                    "metres, z up; transform: column-major, mesh (cm) to scene (m)")) &&
           cJSON_AddNumberToObject(root, "count", pl->n) && cJSON_AddItemToObject(root, "placements", arr);
  if (!ok) cJSON_Delete(arr);
  for (uint32_t k = 0; ok && k < pl->n; k++) ok = one(arr, s, &pl->p[k], g, k);
  if (!ok) cJSON_Delete(root);
  return ok ? root : NULL;
}
