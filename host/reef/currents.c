/* Exposure to water currents (Coralize §4.3, Figure 12; docs/reef.md,
 * "Currents"): the host reference of shaders/reef/exposure.comp, operation
 * by operation. */
#include <math.h>
#include "reef/reef_internal.h"
#include "reef_kernels.h"

/* Whether a sample of the segment from p to the source o lies below the
 * seabed (the endpoints are not sampled: the base lies on the seabed). */
static int sheltered(const sessile_reef_seabed *b, const double p[3], const double o[3]) {
  double dx = b->extent[0] / (b->nx - 1), dy = b->extent[1] / (b->ny - 1);
  double ax = fabs(o[0] - p[0]) / dx, ay = fabs(o[1] - p[1]) / dy;
  double steps = ceil(2 * fmax(ax, ay));
  uint32_t n = (uint32_t)fmin(steps, RC_MAX_MARCH) + 1;
  if (n < 2) n = 2;
  for (uint32_t k = 1; k < n; k++) {
    double t = (double)k / (double)n, z;
    double x = p[0] + t * (o[0] - p[0]), y = p[1] + t * (o[1] - p[1]), zr = p[2] + t * (o[2] - p[2]);
    if (sessile_reef_seabed_at(b, x, y, &z, NULL) && z > zr + 1e-6) return 1;
  }
  return 0;
}

double sessile_reef_exposure_one(const sessile_reef_current *c, const sessile_reef_seabed *b, const double p[3]) {
  double vx = p[0] - c->origin[0], vy = p[1] - c->origin[1], vz = p[2] - c->origin[2];
  double along = vx * c->dir[0] + vy * c->dir[1] + vz * c->dir[2];
  double d2 = vx * vx + vy * vy + vz * vz;
  if (d2 > c->strength * c->strength || along < 0) return 0;
  double g2 = fmax(d2 - along * along, 0);
  double e = g2 <= c->range * c->range ? 1 : c->range / sqrt(g2);
  return sheltered(b, p, c->origin) ? 0 : e;
}

void sessile_reef_exposure_ref(const sessile_reef_scene *s, const sessile_reef_seabed *b,
                               sessile_reef_placements *pl, uint32_t first) {
  for (uint32_t k = first; k < pl->n; k++) {
    double sum = 0;
    for (int c = 0; c < s->ncurrents; c++) sum += sessile_reef_exposure_one(&s->currents[c], b, pl->p[k].pos);
    pl->p[k].exposure = sum;
  }
}
