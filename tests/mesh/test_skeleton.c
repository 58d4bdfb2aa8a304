/* The skeleton's tubes: every tube a closed, outward-oriented 2-manifold of
 * the right size; the volume of a tube of constant radius against the prism
 * formula (n sides: (n/2) r^2 sin(2 pi / n) L); frames made normal to the axis. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/mesh/skeleton.h"
#include "testutil.h"

int main(void) {
  sessile_skeleton sk = {0};
  const double a[3] = {1, 2, 3}, b[3] = {1.5, 2.2, 7}, up[3] = {1, 0, 0};
  t_must("add a segment", sessile_skeleton_add(&sk, a, b, 0.5, 0.5, up, 7));
  sessile_surface s = {0};
  double *val = NULL;
  const int sides = 12;
  t_must("tubes", sessile_skeleton_tubes(&sk, sides, &s, &val));
  t_true("one tube: 2 sides + 2 vertices, 4 sides triangles", s.nv == 2u * sides + 2 && s.nf == 4u * sides);
  t_true("one tube is a closed, consistently oriented 2-manifold (Euler 2)", sessile_surface_check(&s, 2, 0) == SESSILE_OK);
  sessile_surface_stats st;
  sessile_surface_stats_of(&s, &st);
  double L = sqrt(0.25 + 0.04 + 16), want = 0.5 * sides * 0.25 * sin(6.283185307179586 / sides) * L;
  t_check("tube volume against the prism's (relative; positive: faces point out)", fabs(st.volume - want) / want, 1e-12);
  int same = 1;
  for (uint32_t v = 0; v < s.nv; v++) same &= val[v] == 7;
  t_true("every vertex carries the segment's value", same);
  free(val);
  double d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  t_check("up made normal to the axis", fabs(sk.up[0] * d[0] + sk.up[1] * d[1] + sk.up[2] * d[2]), 1e-14);
  t_must("add a second segment", sessile_skeleton_add(&sk, b, (double[3]){1.5, 2.2, 9}, 0.5, 0.25, (double[3]){0, 0, 1}, 8));
  double n2 = sk.up[3] * sk.up[3] + sk.up[4] * sk.up[4] + sk.up[5] * sk.up[5];
  t_check("an up parallel to the axis replaced by a unit normal: | |up|^2 - 1 |", fabs(n2 - 1), 1e-14);
  t_check("... normal to the axis", fabs(sk.up[5]), 1e-14);
  t_must("tubes with 3 sides", sessile_skeleton_tubes(&sk, 3, &s, NULL));
  t_true("two tubes: two closed components (Euler 4)", sessile_surface_check(&s, 4, 0) == SESSILE_OK);
  double lo[3], hi[3];
  sessile_skeleton_bounds(&sk, lo, hi);
  t_true("bounds include the radii", lo[2] == 2.5 && hi[2] == 9.25 && lo[0] == 0.5 && hi[0] == 2.0);
  t_true("a zero radius is refused", sessile_skeleton_add(&sk, a, b, 0, 1, up, 0) == SESSILE_ERR_USAGE);
  t_true("2 sides are refused", sessile_skeleton_tubes(&sk, 2, &s, NULL) == SESSILE_ERR_USAGE);
  sessile_surface_free(&s);
  sessile_skeleton_free(&sk);
  return t_finish(NULL);
}
