/* Scenes shared by the SDS collision tests: two bodies in one complex, a bar
 * bent until its ends meet, a ball on a rock. */
#ifndef SDS_COLLIDE_SCENES_H
#define SDS_COLLIDE_SCENES_H
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sessile/sds/sds.h"
#include "testutil.h"

/* Two icosphere imports (level, radius 1) centred at c0 and c1, one complex. */
static inline void two_bodies(int level, const double *c0, const double *c1, sessile_sds *out) {
  sessile_sds a = {0}, b = {0};
  t_must("body a", sessile_sds_from_icosphere(level, 1.0, c0, 0, 0, 0, 1.0, &a));
  t_must("body b", sessile_sds_from_icosphere(level, 1.0, c1, 0, 0, 0, 1.0, &b));
  uint32_t n = a.ncells + b.ncells, nt = a.ntets + b.ntets;
  double *x = t_dalloc(3 * (size_t)n);
  uint32_t *tet = t_xalloc(4 * (size_t)nt * sizeof *tet);
  memcpy(x, a.x, 3 * (size_t)a.ncells * sizeof *x);
  memcpy(x + 3 * (size_t)a.ncells, b.x, 3 * (size_t)b.ncells * sizeof *x);
  memcpy(tet, a.tet, 4 * (size_t)a.ntets * sizeof *tet);
  for (size_t k = 0; k < 4 * (size_t)b.ntets; k++) tet[4 * (size_t)a.ntets + k] = b.tet[k] + a.ncells;
  t_must("two bodies", sessile_sds_from_tets(x, n, tet, nt, 0, 0, 1.0, out));
  free(x), free(tet);
  sessile_sds_free(&a), sessile_sds_free(&b);
}

/* A level-3 sphere stretched to a bar 8 long (x), bent in the xz-plane
 * around (0, 0, 0) with bend radius 2.2 so that its two ends come within
 * `gap` of each other above the centre: a folded surface whose two end
 * sheets approach (positions only: radii and rest sizes stay the sphere's). */
static inline void bent_bar(double gap, sessile_sds *o) {
  const double ctr[3] = {0, 0, 0};
  t_must("bar", sessile_sds_from_icosphere(3, 1.0, ctr, 0, 0, 0, 1.0, o));
  /* the ends (x = +-4 at the axis) reach angle +-theta_end; their caps at
   * z = 0 meet when 2 Rb sin(pi - theta_end) = gap + ... ; chosen by angle */
  const double Rb = 2.2, theta_end = 3.14159265358979323846 - asin(0.5 * gap / Rb);
  for (uint32_t c = 0; c < o->ncells; c++) {
    double *x = o->x + 3 * (size_t)c;
    double th = theta_end * x[0], rho = Rb - 0.6 * x[2];
    x[0] = rho * sin(th), x[2] = -rho * cos(th), x[1] *= 0.6;
  }
}

/* A ball (icosphere level, radius rb) centred at (xc, 2.2 xc, zc) over a rock
 * (icosphere level 3, radius 2.4, centre (0, 0, -2.4): its top at z = 0). */
static inline void ball_and_rock(int level, double rb, double xc, double zc, sessile_sds *o, sessile_surface *rock) {
  const double ctr[3] = {xc, 2.2 * xc, zc}, rc[3] = {0, 0, -2.4};
  t_must("ball", sessile_sds_from_icosphere(level, rb, ctr, 0, 0, 0, 1.0, o));
  t_must("rock", sessile_surface_icosphere(3, 2.4, rc, rock));
}

/* Params with every force but the contacts off (the GPU force is then m x
 * the contact acceleration). */
static inline void contact_only(sessile_sds_params *p) {
  sessile_sds_params_default(p);
  p->k_edge = 0, p->k_vol = 0, p->gravity = 0, p->damp_visc = 0, p->damp_vol = 0;
}

/* Is x inside the convex closed mesh s (behind every face plane)? */
static inline int inside_convex(const sessile_surface *s, const double *x) {
  for (uint32_t f = 0; f < s->nf; f++) {
    const double *a = s->pos + 3 * (size_t)s->tri[3 * f], *b = s->pos + 3 * (size_t)s->tri[3 * f + 1],
                 *c = s->pos + 3 * (size_t)s->tri[3 * f + 2];
    double e1[3], e2[3], n[3];
    for (int i = 0; i < 3; i++) e1[i] = b[i] - a[i], e2[i] = c[i] - a[i];
    n[0] = e1[1] * e2[2] - e1[2] * e2[1], n[1] = e1[2] * e2[0] - e1[0] * e2[2], n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    if ((x[0] - a[0]) * n[0] + (x[1] - a[1]) * n[1] + (x[2] - a[2]) * n[2] >= 0) return 0;
  }
  return 1;
}
#endif
