/* The integrator on the host (the reference of the GPU's integrate kernel)
 * and the inverted-tet detection (§3.1.2). */
#include <math.h>
#include <stdlib.h>
#include "sds/sds_internal.h"

/* Semi-implicit Euler, the velocity form of position Verlet (leapfrog):
 * v_{n+1} = v_n + dt F(x_n, v_n) / m, x_{n+1} = x_n + dt v_{n+1}. */
double sessile_sds_step_ref(sessile_sds *o, const sessile_sds_params *p, double dt) {
  double *f = malloc(3 * (size_t)o->ncells * sizeof *f);
  if (!f) return NAN;
  sessile_sds_forces_ref(o, p, 1, f);
  double mv = 0;
  for (uint32_t c = 0; c < o->ncells; c++) {
    double d2 = 0;
    for (int i = 0; i < 3; i++) {
      size_t k = 3 * (size_t)c + i;
      o->v[k] += dt * f[k] / o->m[c];
      double dx = dt * o->v[k];
      o->x[k] += dx;
      d2 += dx * dx;
    }
    double mm = sqrt(d2) / o->r[c];
    if (mm > mv || mm != mm) mv = mm;
  }
  free(f);
  return mv;
}

sessile_status sessile_sds_inverted_ref(const sessile_sds *o, uint32_t **list, uint32_t *n) {
  uint32_t cnt = 0;
  for (uint32_t t = 0; t < o->ntets; t++)
    if (!(sessile_sds_tet_volume(o, t) > 0)) cnt++;
  *list = malloc((cnt ? cnt : 1) * sizeof **list);
  SESSILE_CHECK(*list, SESSILE_ERR_NO_MEMORY, "sds: out of memory for %u inverted tets", cnt);
  cnt = 0;
  for (uint32_t t = 0; t < o->ntets; t++)
    if (!(sessile_sds_tet_volume(o, t) > 0)) (*list)[cnt++] = t;
  *n = cnt;
  return SESSILE_OK;
}
