/* Uptake, translocation and growth of one iteration (eqs 6-10): the growth
 * kernels probe the nutrient along the normals, translocate it over the
 * surface and move each vertex; contact inhibition guards the motion
 * (grow_guard.c).  Records per-vertex summaries under "growth". */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "grow_internal.h"

/* What the surface saw and how much it grew: pv holds three blocks of nv. */
static void record_growth(cJSON *rec, const double *pv, int nv) {
  const char *names[3] = {"probed_nutrient", "translocated_nutrient", "growth_length_cm"};
  cJSON *gr = cJSON_AddObjectToObject(rec, "growth");
  for (int a = 0; a < 3; a++) {
    double lo = INFINITY, hi = -INFINITY, sum = 0;
    for (int v = 0; v < nv; v++) {
      double x = pv[a * nv + v];
      lo = x < lo ? x : lo, hi = x > hi ? x : hi, sum += x;
    }
    cJSON *st = cJSON_AddObjectToObject(gr, names[a]);
    cJSON_AddNumberToObject(st, "min", nv ? lo : 0);
    cJSON_AddNumberToObject(st, "mean", nv ? sum / nv : 0);
    cJSON_AddNumberToObject(st, "max", nv ? hi : 0);
  }
  int growing = 0;
  for (int v = 0; v < nv; v++) growing += pv[2 * nv + v] > 0;
  cJSON_AddNumberToObject(gr, "growing_vertices", growing);
}

sessile_status grow_growth_step(grow_run *r, int it, cJSON *rec, const sessile_vec *probe_field) {
  int nv = (int)r->surf.nv;
  double *np = realloc(r->newpos, (size_t)nv * 3 * sizeof *np);
  SESSILE_CHECK(np, SESSILE_ERR_NO_MEMORY, "out of host memory for %d vertices", nv);
  r->newpos = np;
  double *pv = malloc((size_t)nv * 3 * sizeof *pv);
  SESSILE_CHECK(pv, SESSILE_ERR_NO_MEMORY, "out of host memory for %d vertices", nv);
  sessile_status gs = sessile_growth_gpu_step(r->growth, &r->box, probe_field, &r->gp, r->o->seed, (uint32_t)it,
                                              np, pv, pv + nv, pv + 2 * nv);
  if (gs == SESSILE_OK) record_growth(rec, pv, nv);
  free(pv);
  SESSILE_CALL(gs);
  SESSILE_CALL(grow_guard_motion(r, it, np, rec)); /* contact inhibition: grow_guard.c */
  memcpy(r->surf.pos, np, (size_t)nv * 3 * sizeof *np);
  return SESSILE_OK;
}

sessile_status grow_normals(grow_run *r) {
  double *nn = realloc(r->normals, (size_t)(r->surf.nv ? r->surf.nv : 1) * 3 * sizeof *nn);
  SESSILE_CHECK(nn, SESSILE_ERR_NO_MEMORY, "out of host memory for %u normals", r->surf.nv);
  r->normals = nn;
  sessile_surface_normals(&r->surf, nn);
  return SESSILE_OK;
}
