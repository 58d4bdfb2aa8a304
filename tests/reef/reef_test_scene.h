/* Scenes and seabeds shared by the reef tests. */
#ifndef REEF_TEST_SCENE_H
#define REEF_TEST_SCENE_H
#include <stdlib.h>
#include <string.h>
#include "sessile/reef/reef.h"
#include "testutil.h"

static inline void rt_parse(const char *json, sessile_reef_scene *s) {
  t_must("parse the scene", sessile_reef_scene_parse(json, strlen(json), "scene.json", s));
}

/* A seabed of nx x ny samples over ex x ey metres with heights f(x, y). */
static inline void rt_seabed(sessile_reef_seabed *b, uint32_t nx, uint32_t ny, double ex, double ey,
                             double (*f)(double, double)) {
  b->nx = nx, b->ny = ny, b->extent[0] = ex, b->extent[1] = ey;
  b->h = t_dalloc((size_t)nx * ny);
  for (uint32_t j = 0; j < ny; j++)
    for (uint32_t i = 0; i < nx; i++) b->h[(size_t)j * nx + i] = f(i * ex / (nx - 1), j * ey / (ny - 1));
}

/* The test's own bilinear height (not the library's). */
static inline double rt_height(const sessile_reef_seabed *b, double x, double y) {
  double gx = x / (b->extent[0] / (b->nx - 1)), gy = y / (b->extent[1] / (b->ny - 1));
  int i = (int)gx < (int)b->nx - 2 ? (int)gx : (int)b->nx - 2, j = (int)gy < (int)b->ny - 2 ? (int)gy : (int)b->ny - 2;
  double u = gx - i, v = gy - j;
  const double *h = b->h;
  size_t a = (size_t)j * b->nx + i;
  return h[a] + u * (h[a + 1] - h[a]) + v * (h[a + b->nx] - h[a]) + u * v * (h[a + b->nx + 1] - h[a + 1] - h[a + b->nx] + h[a]);
}
#endif
