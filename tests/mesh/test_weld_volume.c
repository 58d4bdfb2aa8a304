/* The welded surface's geometry (docs/weld.md): with blend 0 its enclosed
 * volume matches the union of the capsules (analytic for one capsule and
 * one tapered round cone; Monte-Carlo with a fixed seed for a branching
 * skeleton, inside test independent of the weld's distance formula), and a
 * blend > 0 fills the junctions: the volume grows with the blend and the
 * surface stays a closed 2-manifold without self-intersection. */
#include <stdlib.h>
#include <string.h>
#include "mesh/weld_internal.h"
#include "sessile/mesh/intersect.h"
#include "sessile/rng.h"
#include "test_weld_shapes.h"

static const double PI = 3.141592653589793;

static double weld_volume(sessile_gpu *g, const sessile_skeleton *s, const sessile_weld_params *p, int check) {
  sessile_surface m = {0};
  t_must("weld", sessile_skeleton_weld(g, s, p, &m, NULL));
  sessile_surface_stats st;
  sessile_surface_stats_of(&m, &st);
  if (check) {
    char what[128];
    snprintf(what, sizeof what, "blend %.2f: closed oriented 2-manifold, Euler 2", p->blend);
    t_true(what, sessile_surface_check(&m, 2, 0) == SESSILE_OK);
    uint64_t n = 1;
    t_must("self-intersections", sessile_surface_self_intersections(&m, 0, NULL, &n));
    snprintf(what, sizeof what, "blend %.2f: self-intersecting pairs", p->blend);
    t_check(what, (double)n, 0);
  }
  sessile_surface_free(&m);
  return st.volume;
}

/* Round cone volume: cap of sphere a + frustum between the tangent circles +
 * cap of sphere b (sin = (ra - rb) / L). */
static double round_cone_volume(double ra, double rb, double L) {
  double sn = (ra - rb) / L, cs = sqrt(1 - sn * sn);
  double ha = ra * (1 + sn), hb = rb * (1 - sn), H = L + (rb - ra) * sn;
  double r1 = ra * cs, r2 = rb * cs;
  return PI * ha * ha * (3 * ra - ha) / 3 + PI * H * (r1 * r1 + r1 * r2 + r2 * r2) / 3 +
         PI * hb * hb * (3 * rb - hb) / 3;
}

/* Independent inside test: the round cone is the union of the spheres
 * centred on the segment with linearly varying radius, so p is inside when
 * min over t in [0, 1] of |p - c(t)| - r(t) <= 0 (convex in t: golden
 * section search). */
static int inside_capsule(const sessile_skeleton *s, uint32_t i, const double p[3]) {
  const double *a = s->a + 3 * i, *b = s->b + 3 * i;
  double lo = 0, hi = 1;
  const double gr = 0.6180339887498949;
  double best = INFINITY;
  for (int it = 0; it < 60; it++) {
    double t1 = hi - gr * (hi - lo), t2 = lo + gr * (hi - lo), f[2];
    double tt[2] = {t1, t2};
    for (int k = 0; k < 2; k++) {
      double d2 = 0;
      for (int c = 0; c < 3; c++) {
        double q = p[c] - (a[c] + tt[k] * (b[c] - a[c]));
        d2 += q * q;
      }
      f[k] = sqrt(d2) - (s->ra[i] + tt[k] * (s->rb[i] - s->ra[i]));
      best = fmin(best, f[k]);
    }
    if (f[0] < f[1]) hi = t2;
    else lo = t1;
  }
  for (int e = 0; e < 2; e++) { /* the ends, exactly */
    const double *c = e ? b : a;
    double d2 = 0;
    for (int k = 0; k < 3; k++) d2 += (p[k] - c[k]) * (p[k] - c[k]);
    best = fmin(best, sqrt(d2) - (e ? s->rb[i] : s->ra[i]));
  }
  return best <= 0;
}

int main(void) {
  sessile_gpu *g = t_gpu(0);

  /* one capsule: pi r^2 L + 4/3 pi r^3 */
  sessile_skeleton one = {0};
  shape_capsule(&one, 1.0, 5.0);
  double L = sqrt(25 + 2.25 + 0.25);
  double exact = PI * L + 4.0 / 3 * PI;
  sessile_weld_params p = {.cell = 0.1, .max_cells = 0, .blend = 0};
  double v = weld_volume(g, &one, &p, 1);
  printf("one capsule: volume %.5f, analytic %.5f (cell 0.1, r 1)\n", v, exact);
  t_check("one capsule: relative volume error (cell = r/10)", fabs(v - exact) / exact, 0.01);

  /* a tapered round cone: the hull of two spheres */
  sessile_skeleton cone = {0};
  const double a[3] = {0, 0, 0}, b[3] = {1, 2, 4}, up[3] = {1, 0, 0};
  t_must("cone", sessile_skeleton_add(&cone, a, b, 1.2, 0.5, up, 0));
  double Lc = sqrt(21.0);
  exact = round_cone_volume(1.2, 0.5, Lc);
  p.cell = 0.06;
  v = weld_volume(g, &cone, &p, 1);
  printf("round cone: volume %.5f, analytic %.5f\n", v, exact);
  t_check("round cone (ra 1.2, rb 0.5): relative volume error", fabs(v - exact) / exact, 0.01);

  /* a branching skeleton: Monte-Carlo estimate of the union's volume.
   * Points are drawn in the capsules' boxes (box i with probability
   * proportional to its volume) and a hit counts 1/m, m the number of boxes
   * holding the point: an unbiased estimate of the union's volume with far
   * less variance than sampling the whole bounding box. */
  sessile_skeleton tree = {0};
  t_must("tree", weld_random_tree(11, 30, 0.5, &tree));
  double *blo = t_dalloc(3 * tree.n), *bhi = t_dalloc(3 * tree.n), *cum = t_dalloc(tree.n);
  double W = 0;
  for (uint32_t i = 0; i < tree.n; i++) {
    double r = fmax(tree.ra[i], tree.rb[i]), vol = 1;
    for (int c = 0; c < 3; c++) {
      blo[3 * i + c] = fmin(tree.a[3 * i + c], tree.b[3 * i + c]) - r;
      bhi[3 * i + c] = fmax(tree.a[3 * i + c], tree.b[3 * i + c]) + r;
      vol *= bhi[3 * i + c] - blo[3 * i + c];
    }
    cum[i] = (W += vol);
  }
  uint64_t rs = sessile_rng_stream(2024, 1);
  const long N = 200000;
  double sum = 0, sum2 = 0;
  for (long k = 0; k < N; k++) {
    double u = sessile_rng_uniform(&rs) * W, q[3];
    uint32_t j = 0;
    while (j + 1 < tree.n && cum[j] <= u) j++;
    for (int c = 0; c < 3; c++) q[c] = sessile_rng_range(&rs, blo[3 * j + c], bhi[3 * j + c]);
    int m = 0, hit = 0;
    for (uint32_t i = 0; i < tree.n; i++) {
      int inb = 1;
      for (int c = 0; c < 3; c++) inb &= q[c] >= blo[3 * i + c] && q[c] <= bhi[3 * i + c];
      m += inb;
      if (inb && !hit) hit = inside_capsule(&tree, i, q);
    }
    double x = hit ? 1.0 / m : 0;
    sum += x, sum2 += x * x;
  }
  double mean = sum / N, var = sum2 / N - mean * mean;
  double mc = W * mean, se = W * sqrt(var / N);
  printf("tree of %u segments: Monte-Carlo volume %.4f +- %.4f (%.2f %%, %ld samples)\n", tree.n, mc, se,
         100 * se / mc, N);
  t_check("Monte-Carlo standard error (relative)", se / mc, 0.005);
  free(blo), free(bhi), free(cum);
  p.cell = 0.06;
  v = weld_volume(g, &tree, &p, 0);
  printf("tree: welded volume %.4f (cell 0.06, trunk radius 0.5)\n", v);
  t_check("tree, blend 0: relative volume difference to Monte-Carlo", fabs(v - mc) / mc, 0.02);

  /* blend: the Y junction fills, monotonically */
  sessile_skeleton y = {0};
  shape_y(&y);
  p.cell = 0.08;
  double prev = 0;
  const double blends[4] = {0, 0.2, 0.5, 1.0};
  for (int k = 0; k < 4; k++) {
    p.blend = blends[k];
    double vb = weld_volume(g, &y, &p, 1);
    printf("Y junction: blend %.2f, volume %.5f\n", blends[k], vb);
    if (k) {
      char what[96];
      snprintf(what, sizeof what, "Y junction: volume grows from blend %.2f to %.2f", blends[k - 1], blends[k]);
      t_true(what, vb > prev);
    }
    prev = vb;
  }
  sessile_skeleton_free(&one), sessile_skeleton_free(&cone), sessile_skeleton_free(&tree);
  sessile_skeleton_free(&y);
  return t_finish(g);
}
