/* Skeletons shared by the weld tests: one capsule, a Y junction, a ring. */
#ifndef TEST_WELD_SHAPES_H
#define TEST_WELD_SHAPES_H
#include <math.h>
#include "sessile/mesh/skeleton.h"
#include "testutil.h"

static inline void shape_capsule(sessile_skeleton *s, double r, double len) {
  const double a[3] = {0, 0, 0}, b[3] = {len, 0.3 * len, 0.1 * len}, up[3] = {0, 0, 1};
  t_must("capsule", sessile_skeleton_add(s, a, b, r, r, up, 7));
}
/* Three tapered arms from one point, not in one plane. */
static inline void shape_y(sessile_skeleton *s) {
  const double o[3] = {0, 0, 0}, up[3] = {0, 0, 1};
  const double e[3][3] = {{0, 0, -4}, {3, 0.5, 3}, {-2.5, 1, 3.2}};
  for (int i = 0; i < 3; i++) t_must("Y arm", sessile_skeleton_add(s, o, e[i], 0.8, 0.5, up, i));
}
/* n capsules around a circle of radius R: a torus-like ring (genus 1). */
static inline void shape_ring(sessile_skeleton *s, int n, double R, double r) {
  const double up[3] = {0, 0, 1};
  for (int i = 0; i < n; i++) {
    double t0 = 2 * 3.141592653589793 * i / n, t1 = 2 * 3.141592653589793 * (i + 1) / n;
    double a[3] = {R * cos(t0), R * sin(t0), 0}, b[3] = {R * cos(t1), R * sin(t1), 0};
    t_must("ring", sessile_skeleton_add(s, a, b, r, r, up, i));
  }
}
/* An L-system-like frame on the integer lattice: vertical posts, slanted
 * rungs, 45-degree tips; with round cell sizes the worst case for exactly
 * coplanar output (docs/weld.md): 3 components. */
static inline void shape_frame(sessile_skeleton *s) {
  const double up[3] = {0, 0, 1};
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      double a[3] = {i, j, 0}, b[3] = {i, j, 2}, c[3] = {i + 1, j, 1}, d[3] = {i + 0.5, j + 0.5, 2.5};
      t_must("frame", sessile_skeleton_add(s, a, b, 0.3, 0.2, up, 0));
      t_must("frame", sessile_skeleton_add(s, a, c, 0.25, 0.25, up, 1));
      t_must("frame", sessile_skeleton_add(s, b, d, 0.2, 0.1, up, 2));
    }
}
#endif
