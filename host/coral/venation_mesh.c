/* From the vein graph to a skeleton (sessile/mesh/skeleton.h): radii from the
 * thickness index through the thickness curve (Coralize §3.2, Fig. 5), and
 * rotation-minimising frames carried from each node to its children by the
 * double reflection method (Wang et al. 2008), so tubes do not twist. */
#include <math.h>
#include <stdlib.h>
#include "venation_internal.h"

double sessile_venation_radius(const sessile_venation_params *p, double t) {
  t = t < 0 ? 0 : t > 1 ? 1 : t;
  double x = 3 * t;
  int k = x >= 3 ? 2 : (int)x;
  double f = x - k;
  return p->thickness[k] + f * (p->thickness[k + 1] - p->thickness[k]);
}

static void unit(double v[3]) {
  double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (l > 0) v[0] /= l, v[1] /= l, v[2] /= l;
}
static double dot(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* Frame (t0, r0) at x0 carried to x1: the new tangent t1 = unit(x1 - x0) and
 * the reflected normal r1 (double reflection). */
static void transport(const double x0[3], const double t0[3], const double r0[3], const double x1[3], double t1[3],
                      double r1[3]) {
  double v1[3] = {x1[0] - x0[0], x1[1] - x0[1], x1[2] - x0[2]};
  for (int a = 0; a < 3; a++) t1[a] = v1[a];
  unit(t1);
  double c1 = dot(v1, v1), rl[3], tl[3];
  if (c1 <= 0) {
    for (int a = 0; a < 3; a++) r1[a] = r0[a];
    return;
  }
  double fr = 2 * dot(v1, r0) / c1, ft = 2 * dot(v1, t0) / c1;
  for (int a = 0; a < 3; a++) rl[a] = r0[a] - fr * v1[a], tl[a] = t0[a] - ft * v1[a];
  double v2[3] = {t1[0] - tl[0], t1[1] - tl[1], t1[2] - tl[2]}, c2 = dot(v2, v2);
  double f2 = c2 > 1e-300 ? 2 * dot(v2, rl) / c2 : 0;
  for (int a = 0; a < 3; a++) r1[a] = rl[a] - f2 * v2[a];
  /* remove rounding drift: exactly normal to the tangent */
  double d = dot(r1, t1);
  for (int a = 0; a < 3; a++) r1[a] -= d * t1[a];
  unit(r1);
}

sessile_status sessile_venation_skeleton(const sessile_venation *v, const sessile_venation_params *p,
                                         sessile_skeleton *sk) {
  double *tan = malloc((size_t)3 * v->n * sizeof *tan), *up = malloc((size_t)3 * v->n * sizeof *up);
  double *rad = malloc((size_t)v->n * sizeof *rad);
  if (!tan || !up || !rad) {
    free(tan), free(up), free(rad);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for %u vein frames", v->n);
  }
  /* the root: upright, its normal along x */
  tan[0] = 0, tan[1] = 0, tan[2] = 1, up[0] = 1, up[1] = 0, up[2] = 0;
  double root = v->ti[0];
  for (uint32_t i = 0; i < v->n; i++) rad[i] = sessile_venation_radius(p, v->ti[i] / root);
  sessile_status s = SESSILE_OK;
  /* parents precede children: one pass in index order */
  for (uint32_t i = 1; i < v->n && s == SESSILE_OK; i++) {
    uint32_t a = v->parent[i];
    transport(v->pos + 3 * a, tan + 3 * a, up + 3 * a, v->pos + 3 * i, tan + 3 * i, up + 3 * i);
    s = sessile_skeleton_add(sk, v->pos + 3 * a, v->pos + 3 * i, rad[a], rad[i], up + 3 * i, v->ti[a]);
  }
  for (uint32_t e = 0; e < v->ne && s == SESSILE_OK; e++) {
    uint32_t a = v->edge[2 * e], b = v->edge[2 * e + 1];
    double t1[3], r1[3];
    transport(v->pos + 3 * a, tan + 3 * a, up + 3 * a, v->pos + 3 * b, t1, r1);
    s = sessile_skeleton_add(sk, v->pos + 3 * a, v->pos + 3 * b, rad[a], rad[b], r1, v->ti[a]);
  }
  free(tan), free(up), free(rad);
  return s;
}
