/* Test shapes for the growth tests: rotated icospheres (a vertex at each
 * pole), radial bumps, a star with overhangs, a sphere flattened on the box
 * floor.  Header-only so every test program can include it. */
#ifndef SESSILE_TEST_SHAPES_H
#define SESSILE_TEST_SHAPES_H
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include "sessile/mesh/surface.h"

static inline void shape_must(sessile_status s) {
  if (s == SESSILE_OK) return;
  printf("FAIL building a test shape: %s\n", sessile_error_message());
  exit(1);
}

/* Unit icosphere rotated about x so icosahedron vertex 5, (0, 1, t)/|.|,
 * lands exactly on +z (and its antipode on -z); the poles are then set to
 * exactly (0, 0, +-1) so they lie on grid lines after scaling. */
static inline void shape_unit_polar(int level, sessile_surface *s) {
  const double c0[3] = {0, 0, 0};
  shape_must(sessile_surface_icosphere(level, 1.0, c0, s));
  const double t = (1.0 + sqrt(5.0)) / 2.0, a = atan2(1.0, t); /* angle of vertex 5 from +z */
  const double ca = cos(a), sa = sin(a);
  for (uint32_t v = 0; v < s->nv; v++) {
    double *p = s->pos + 3 * v, y = p[1], z = p[2];
    p[1] = ca * y - sa * z;
    p[2] = sa * y + ca * z;
    if (fabs(p[0]) < 1e-12 && fabs(p[1]) < 1e-12) p[0] = p[1] = 0, p[2] = p[2] > 0 ? 1 : -1;
    if (fabs(p[0]) < 1e-12) p[0] = 0; /* vertices in the plane x = 0 stay exactly there */
  }
}

/* r(theta, phi) * unit direction + centre, for the unit polar icosphere. */
static inline void shape_radial(int level, double R, const double c[3],
                         double (*rfun)(double theta, double phi), sessile_surface *s) {
  shape_unit_polar(level, s);
  for (uint32_t v = 0; v < s->nv; v++) {
    double *p = s->pos + 3 * v;
    double th = acos(p[2] < -1 ? -1 : (p[2] > 1 ? 1 : p[2])), ph = atan2(p[1], p[0]);
    double r = R * (rfun ? rfun(th, ph) : 1.0);
    for (int q = 0; q < 3; q++) p[q] = c[q] + r * p[q];
  }
}

static inline double bumps(double th, double ph) { return 1.0 + 0.4 * sin(3 * th) * cos(4 * ph); }
/* Lobes at the poles and the equator, waists at 45 degrees: vertical lines
 * through the waist region cross the surface 4 times (overhangs). */
static inline double star(double th, double ph) {
  double c = cos(2 * th);
  return 0.5 + 0.5 * c * c;
}
#endif
