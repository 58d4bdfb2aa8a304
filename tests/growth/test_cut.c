/* Cut fractions of closed surfaces on the box grid lines along x, y and z
 * (sessile_growth_gpu_cut, the nutrient's cut-cell boundary):
 *  - GPU == host reference: the solid mask node for node, and every
 *    fraction (the same arithmetic: tolerance 0 in fp64; 1e-5 in fp32).
 *  - Independent: wherever a fraction is below 1, the point it names lies
 *    on the surface (distance to the nearest triangle <= 1e-9 cm, brute
 *    force); every grid edge whose two nodes differ in solidity has a
 *    crossing (fraction < 1 from one end at least), unless one of its
 *    nodes lies on the surface itself; the two fractions of a crossed edge
 *    add up to at most 1 (to 1e-12).
 *  - Against the analytic sphere: a level-6 icosphere of radius R (vertices
 *    on the sphere): every crossing point lies between R cos(a/2)^2... and R,
 *    i.e. within the icosphere's sagitta of the sphere.
 *  - Shapes: a polar icosphere with poles on grid nodes (degenerate hits),
 *    radial bumps, a star with overhangs, a sphere flattened on the floor. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sessile/growth/growth_gpu.h"
#include "sessile/growth/growth_ref.h"
#include "shapes.h"
#include "testutil.h"

static sessile_la *la;
static sessile_growth_gpu *gg;
static double tol32 = 0; /* fp32: fractions may differ by rounding */

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
/* Distance from p to triangle abc by projection and edge clamping. */
static double seg_dist2(const double *p, const double *a, const double *b) {
  double ab[3], ap[3];
  for (int i = 0; i < 3; i++) ab[i] = b[i] - a[i], ap[i] = p[i] - a[i];
  double t = dot3(ab, ap) / dot3(ab, ab);
  t = t < 0 ? 0 : t > 1 ? 1 : t;
  double d2 = 0;
  for (int i = 0; i < 3; i++) d2 += (ap[i] - t * ab[i]) * (ap[i] - t * ab[i]);
  return d2;
}
static double tri_dist(const double *p, const double *a, const double *b, const double *c) {
  double ab[3], ac[3], n[3], ap[3];
  for (int i = 0; i < 3; i++) ab[i] = b[i] - a[i], ac[i] = c[i] - a[i], ap[i] = p[i] - a[i];
  n[0] = ab[1] * ac[2] - ab[2] * ac[1];
  n[1] = ab[2] * ac[0] - ab[0] * ac[2];
  n[2] = ab[0] * ac[1] - ab[1] * ac[0];
  double nn = dot3(n, n), d = dot3(ap, n) / nn, q[3];
  for (int i = 0; i < 3; i++) q[i] = p[i] - d * n[i];
  /* barycentric inside test of the projection */
  const double *v[3] = {a, b, c};
  int inside = 1;
  for (int e = 0; e < 3; e++) {
    const double *s = v[e], *t = v[(e + 1) % 3];
    double st[3], sq[3], cr[3];
    for (int i = 0; i < 3; i++) st[i] = t[i] - s[i], sq[i] = q[i] - s[i];
    cr[0] = st[1] * sq[2] - st[2] * sq[1];
    cr[1] = st[2] * sq[0] - st[0] * sq[2];
    cr[2] = st[0] * sq[1] - st[1] * sq[0];
    if (dot3(cr, n) < 0) inside = 0;
  }
  if (inside) return fabs(d) * sqrt(nn);
  double m = seg_dist2(p, a, b), m2 = seg_dist2(p, b, c), m3 = seg_dist2(p, c, a);
  m = m2 < m ? m2 : m;
  m = m3 < m ? m3 : m;
  return sqrt(m);
}
static double surf_dist(const sessile_surface *s, const double *p) {
  double best = INFINITY;
  for (uint32_t f = 0; f < s->nf; f++) {
    const uint32_t *t = s->tri + 3 * f;
    double d = tri_dist(p, s->pos + 3 * t[0], s->pos + 3 * t[1], s->pos + 3 * t[2]);
    best = d < best ? d : best;
  }
  return best;
}

/* Runs both, compares, checks the fractions against the surface.  Returns
 * the crossing points (3 per crossing, *np of them) for further checks. */
static void check(const char *name, const sessile_box *b, const sessile_surface *s, double **pts,
                  size_t *np) {
  size_t nodes = sessile_box_nodes(b);
  uint32_t *sr = malloc(nodes * 4), *sg = malloc(nodes * 4);
  double *tr = malloc(nodes * 6 * sizeof *tr), *tg = malloc(nodes * 6 * sizeof *tg);
  t_must("reference", sessile_growth_ref_cut(b, s, sr, tr));
  sessile_buffer *solid, *theta;
  sessile_gpu *g = sessile_la_gpu(la);
  uint32_t rb = sessile_la_real_bytes(la);
  t_must("solid", sessile_buffer_create(g, nodes * 4, SESSILE_BUFFER_DEVICE, &solid));
  t_must("theta", sessile_buffer_create(g, nodes * 6 * rb, SESSILE_BUFFER_DEVICE, &theta));
  t_must("upload", sessile_growth_gpu_set_surface(gg, s));
  t_must("cut", sessile_growth_gpu_cut(gg, b, solid, theta));
  t_must("download", sessile_buffer_download(solid, 0, sg, nodes * 4));
  t_must("download", sessile_buffer_download_reals(theta, 0, tg, nodes * 6));
  size_t dmask = 0;
  double dtheta = 0;
  for (size_t n = 0; n < nodes; n++) {
    dmask += sr[n] != sg[n];
    for (int d = 0; d < 6; d++) dtheta = fmax(dtheta, fabs(tr[6 * n + d] - tg[6 * n + d]));
  }
  char what[200];
  snprintf(what, sizeof what, "%s: GPU vs reference solid mask, differing nodes", name);
  t_check(what, (double)dmask, 0);
  snprintf(what, sizeof what, "%s: GPU vs reference fractions, max difference", name);
  t_check(what, dtheta, tol32);
  /* independent checks on the reference */
  double worst_on = 0, worst_sum = 0;
  size_t missing = 0, crossings = 0;
  *pts = malloc(nodes * 6 * 3 * sizeof **pts);
  *np = 0;
  for (size_t n = 0; n < nodes; n++) {
    uint32_t c[3] = {(uint32_t)(n % b->n[0]), (uint32_t)(n / b->n[0] % b->n[1]),
                     (uint32_t)(n / ((size_t)b->n[0] * b->n[1]))};
    for (int a = 0; a < 3; a++) {
      if (c[a] + 1 >= b->n[a]) continue;
      size_t m = n + (a == 0 ? 1 : a == 1 ? b->n[0] : (size_t)b->n[0] * b->n[1]);
      double tp = tr[6 * n + 2 * a + 1], tm = tr[6 * m + 2 * a];
      if (sr[n] != sr[m] && !(tp < 1 || tm < 1)) {
        /* a node exactly on the surface is a true degeneracy (the parity
         * along z and the crossing along another axis may then disagree) */
        double pn[3], pm[3];
        sessile_box_node_pos(b, (uint32_t)n, pn);
        sessile_box_node_pos(b, (uint32_t)m, pm);
        if (surf_dist(s, pn) > 1e-9 && surf_dist(s, pm) > 1e-9) missing++;
      }
      if (!(tp < 1)) continue;
      crossings++;
      double p[3];
      sessile_box_node_pos(b, (uint32_t)n, p);
      p[a] += tp * b->h;
      worst_on = fmax(worst_on, surf_dist(s, p));
      memcpy(*pts + 3 * (*np)++, p, sizeof p);
      if (sr[n] != sr[m]) worst_sum = fmax(worst_sum, fabs(tp + tm - 1) * (tp + tm > 1));
    }
  }
  snprintf(what, sizeof what, "%s: %zu crossings, max distance of a crossing from the surface (cm)",
           name, crossings);
  t_check(what, worst_on, 1e-9);
  snprintf(what, sizeof what, "%s: edges across the surface without a crossing", name);
  t_check(what, (double)missing, 0);
  snprintf(what, sizeof what, "%s: the two fractions of a crossed edge exceed 1 by", name);
  t_check(what, worst_sum, 1e-12);
  sessile_buffer_destroy(solid);
  sessile_buffer_destroy(theta);
  free(sr), free(sg), free(tr), free(tg);
}

static void shapes(void) {
  const double o[3] = {0, 0, 0};
  const uint32_t cells[3] = {16, 16, 12};
  sessile_box b;
  t_must("box", sessile_box_make(o, 1.0, cells, 1, &b));
  sessile_surface s = {0};
  double *pts;
  size_t np;
  const double c[3] = {8, 8, 6};
  /* poles on grid nodes, vertices in the grid plane x = 8 */
  shape_radial(3, 4.0, c, NULL, &s);
  check("polar icosphere", &b, &s, &pts, &np);
  free(pts);
  sessile_surface_free(&s);
  shape_radial(4, 4.0, c, bumps, &s);
  check("bumps", &b, &s, &pts, &np);
  free(pts);
  sessile_surface_free(&s);
  shape_radial(4, 4.0, c, star, &s);
  check("star", &b, &s, &pts, &np);
  free(pts);
  sessile_surface_free(&s);
  /* the analytic sphere: a level-6 icosphere off the grid's symmetry */
  const double c2[3] = {8.13, 7.91, 6.07};
  const double R = 4.3;
  t_must("icosphere", sessile_surface_icosphere(6, R, c2, &s));
  check("level-6 sphere", &b, &s, &pts, &np);
  double maxe = 0;
  for (uint32_t f = 0; f < s.nf; f++)
    for (int e = 0; e < 3; e++) {
      const double *p = s.pos + 3 * s.tri[3 * f + e], *q = s.pos + 3 * s.tri[3 * f + (e + 1) % 3];
      double d = sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                      (p[2] - q[2]) * (p[2] - q[2]));
      maxe = fmax(maxe, d);
    }
  /* a flat triangle of circumradius <= its longest edge / sqrt(3) sits at
   * least R - rc^2 / (2R) (roughly) from the centre: the sagitta bound */
  double rc = maxe / sqrt(3.0), sag = R - sqrt(R * R - rc * rc), worst = 0;
  for (size_t i = 0; i < np; i++) {
    double r = sqrt((pts[3 * i] - c2[0]) * (pts[3 * i] - c2[0]) + (pts[3 * i + 1] - c2[1]) * (pts[3 * i + 1] - c2[1]) +
                    (pts[3 * i + 2] - c2[2]) * (pts[3 * i + 2] - c2[2]));
    worst = fmax(worst, fmax(r - R, (R - sag) - r));
  }
  char what[160];
  snprintf(what, sizeof what, "level-6 sphere: crossings outside [R - sagitta, R] (sagitta %.2e cm) by", sag);
  t_check(what, fmax(worst, 0), 1e-12);
  free(pts);
  sessile_surface_free(&s);
  /* flattened on the floor (a dome, as the sponge starts) */
  const double c3[3] = {8, 8, 0};
  t_must("icosphere", sessile_surface_icosphere(4, 5.0, c3, &s));
  for (uint32_t v = 0; v < s.nv; v++)
    if (s.pos[3 * v + 2] < 0) s.pos[3 * v + 2] = 0;
  check("dome", &b, &s, &pts, &np);
  free(pts);
  sessile_surface_free(&s);
}

int main(int argc, char **argv) {
  int prec = argc > 1 && strcmp(argv[1], "--fp32") == 0 ? 32 : 0;
  sessile_gpu *g = t_gpu(prec);
  if (sessile_gpu_info_of(g)->precision == 32) tol32 = 1e-5;
  t_must("la", sessile_la_create(g, &la));
  t_must("growth gpu", sessile_growth_gpu_create(la, &gg));
  shapes();
  sessile_growth_gpu_destroy(gg);
  sessile_la_destroy(la);
  return t_finish(g);
}
