/* The leaf blade (Coralize's "Shape", "Initial width", "Width increment"):
 * the region between two cubic Bézier curves from the base (0, 0) to the tip
 * (0, 1), x in widths and z in heights, scaled by the blade's width at the
 * iteration (marginal growth) and standing in the x-z plane; or, when not
 * planar ("2D" false), a box of that width, depth_ratio x width deep and
 * aspect x width high, its base centred on the root. */
#include <math.h>
#include "sessile/rng.h"
#include "venation_internal.h"

double sessile_venation_width(const sessile_venation_params *p, int it) {
  return p->initial_width + p->width_increment * it;
}

/* x at the curve's parameter t where z(t) = z (z's control values rise, so
 * bisection finds the one crossing). */
static double curve_x_at(double x1, double z1, double x2, double z2, double z) {
  double a = 0, b = 1;
  for (int it = 0; it < 60; it++) {
    double t = 0.5 * (a + b), s = 1 - t;
    double zt = 3 * s * s * t * z1 + 3 * s * t * t * z2 + t * t * t;
    if (zt < z) a = t;
    else b = t;
  }
  double t = 0.5 * (a + b), s = 1 - t;
  return 3 * s * s * t * x1 + 3 * s * t * t * x2;
}

void venation_blade_span(const sessile_venation_params *p, double z, double *xl, double *xr) {
  *xl = curve_x_at(p->left_1x, p->left_1z, p->left_2x, p->left_2z, z);
  *xr = curve_x_at(p->right_1x, p->right_1z, p->right_2x, p->right_2z, z);
}

int sessile_venation_in_blade(const sessile_venation_params *p, double w, double x, double z) {
  double hgt = p->aspect * w;
  if (!(z >= 0 && z <= hgt)) return 0;
  if (!p->planar) return fabs(x) <= 0.5 * w;
  double xl, xr;
  venation_blade_span(p, z / hgt, &xl, &xr);
  return x >= xl * w && x <= xr * w;
}

int venation_blade_sample(const sessile_venation_params *p, double w, uint64_t *rng, double q[3]) {
  double hgt = p->aspect * w;
  if (!p->planar) {
    q[0] = sessile_rng_range(rng, -0.5 * w, 0.5 * w);
    q[1] = sessile_rng_range(rng, -0.5 * p->depth_ratio * w, 0.5 * p->depth_ratio * w);
    q[2] = sessile_rng_range(rng, 0, hgt);
    return 1;
  }
  /* the convex hull of the control points bounds each curve */
  double xs[6] = {0, p->left_1x, p->left_2x, p->right_1x, p->right_2x, 0}, lo = 0, hi = 0;
  for (int k = 0; k < 6; k++) lo = xs[k] < lo ? xs[k] : lo, hi = xs[k] > hi ? xs[k] : hi;
  for (int tries = 0; tries < 64; tries++) {
    double x = sessile_rng_range(rng, lo * w, hi * w), z = sessile_rng_range(rng, 0, hgt);
    if (sessile_venation_in_blade(p, w, x, z)) {
      q[0] = x, q[1] = 0, q[2] = z;
      return 1;
    }
  }
  return 0;
}
