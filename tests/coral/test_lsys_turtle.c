/* The turtle (host/coral/turtle.c): positions and frames for known strings
 * (start at the origin, heading +z, left +y, up -x), branch depth as the
 * value, radii from # and !, parameter variance, rotation-minimising
 * normals (no twist on a planar bend or under rolls; equal to the minimal
 * rotation computed independently by Rodrigues' formula), tropism. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/coral/lsystem.h"
#include "sessile/mesh/skeleton.h"
#include "testutil.h"

static const double TOL = 1e-12;

static sessile_turtle_params defaults(void) {
  sessile_turtle_params p = {.step = 1, .angle = 90, .thickness = 0.1, .thickness_variance = 0,
                             .width_factor = 0.5, .tropism = {0, 0, 1}, .tropism_strength = 0, .min_radius = 1e-6,
                             .taper = 1};
  return p;
}

/* The axiom of a one-line grammar, drawn. */
static void draw(const char *axiom, const sessile_turtle_params *p, sessile_skeleton *sk) {
  char text[2048];
  snprintf(text, sizeof text, "axiom: %s\n", axiom);
  sessile_lsys *g = NULL;
  t_must("parse", sessile_lsys_parse(text, strlen(text), "t.lsys", 0, NULL, NULL, &g));
  sessile_lsys_string s = {0};
  uint64_t rng = 1;
  t_must("derive", sessile_lsys_derive(g, 0, &rng, 1000, &s));
  sessile_skeleton_free(sk);
  rng = 2;
  t_must("interpret", sessile_turtle_interpret(&s, p, &rng, sk, NULL));
  sessile_lsys_string_free(&s);
  sessile_lsys_destroy(g);
}

static double dist3(const double *a, const double *b) {
  return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

/* max distance of the segments' ends from the expected (a, b) pairs */
static double seg_err(const sessile_skeleton *sk, int n, const double (*want)[6]) {
  if ((int)sk->n != n) return INFINITY;
  double e = 0;
  for (int i = 0; i < n; i++) e = fmax(e, fmax(dist3(sk->a + 3 * i, want[i]), dist3(sk->b + 3 * i, want[i] + 3)));
  return e;
}

static void rodrigues(double *v, const double *d0, const double *d1) {
  double k[3] = {d0[1] * d1[2] - d0[2] * d1[1], d0[2] * d1[0] - d0[0] * d1[2], d0[0] * d1[1] - d0[1] * d1[0]};
  double s = sqrt(k[0] * k[0] + k[1] * k[1] + k[2] * k[2]), c = d0[0] * d1[0] + d0[1] * d1[1] + d0[2] * d1[2];
  if (s < 1e-15) return;
  for (int i = 0; i < 3; i++) k[i] /= s;
  double a = atan2(s, c), kv[3] = {k[1] * v[2] - k[2] * v[1], k[2] * v[0] - k[0] * v[2], k[0] * v[1] - k[1] * v[0]};
  double kd = k[0] * v[0] + k[1] * v[1] + k[2] * v[2];
  for (int i = 0; i < 3; i++) v[i] = v[i] * cos(a) + kv[i] * sin(a) + k[i] * kd * (1 - cos(a));
}

int main(void) {
  sessile_skeleton sk = {0};
  sessile_turtle_params p = defaults();

  draw("F+F", &p, &sk);
  static const double w1[2][6] = {{0, 0, 0, 0, 0, 1}, {0, 0, 1, 0, 1, 1}};
  t_check("F+F (90 deg): + turns toward left (+y)", seg_err(&sk, 2, w1), TOL);

  draw("F[&F]F", &p, &sk);
  static const double w2[3][6] = {{0, 0, 0, 0, 0, 1}, {0, 0, 1, 1, 0, 1}, {0, 0, 1, 0, 0, 2}};
  t_check("F[&F]F: & pitches toward -up (+x), ] restores the state", seg_err(&sk, 3, w2), TOL);
  t_true("... values are the branch depth 0, 1, 0", sk.n == 3 && sk.value[0] == 0 && sk.value[1] == 1 && sk.value[2] == 0);

  draw("F\\(90)+(90)F", &p, &sk);
  static const double w3[2][6] = {{0, 0, 0, 0, 0, 1}, {0, 0, 1, -1, 0, 1}};
  t_check("F\\(90)+(90)F: roll left turns left into up (-x)", seg_err(&sk, 2, w3), TOL);
  draw("F/(90)+(90)F", &p, &sk);
  static const double w4[2][6] = {{0, 0, 0, 0, 0, 1}, {0, 0, 1, 1, 0, 1}};
  t_check("F/(90)+(90)F: roll right turns left into -up (+x)", seg_err(&sk, 2, w4), TOL);
  draw("F^(90)F-(90)F|F", &p, &sk);
  static const double w5[4][6] = {{0, 0, 0, 0, 0, 1}, {0, 0, 1, -1, 0, 1}, {-1, 0, 1, -1, -1, 1}, {-1, -1, 1, -1, 0, 1}};
  t_check("F^(90)F-(90)F|F: pitch up, turn right, turn around", seg_err(&sk, 4, w5), TOL);
  draw("F(2.5)f(1)F(0.5)", &p, &sk);
  static const double w6[2][6] = {{0, 0, 0, 0, 0, 2.5}, {0, 0, 3.5, 0, 0, 4}};
  t_check("F(2.5) f(1) F(0.5): lengths, f moves without drawing", seg_err(&sk, 2, w6), TOL);

  draw("!(2)F#F!F!(3)F", &p, &sk);
  {
    static const double ra[4] = {0.2, 0.2, 0.4, 0.2}, rb[4] = {0.2, 0.4, 0.2, 0.3};
    double er = sk.n == 4 ? 0 : INFINITY;
    for (uint32_t i = 0; i < sk.n && i < 4; i++) er = fmax(er, fmax(fabs(sk.ra[i] - ra[i]), fabs(sk.rb[i] - rb[i])));
    t_check("radii (taper): !(2) = 2 thickness, # divides by width_factor, ! multiplies, !(3) sets; each "
            "segment starts where the previous ended",
            er, TOL);
    p.taper = 0;
    draw("!(2)F#F!F!(3)F", &p, &sk);
    er = sk.n == 4 ? 0 : INFINITY;
    for (uint32_t i = 0; i < sk.n && i < 4; i++) er = fmax(er, fmax(fabs(sk.ra[i] - rb[i]), fabs(sk.rb[i] - rb[i])));
    t_check("radii without taper: cylinders of the current radius", er, TOL);
    p.taper = 1;
    draw("!(2)F[!(1)F]!(3)F", &p, &sk);
    t_true("a branch's first segment starts at its parent's radius; the parent goes on from its own",
           sk.n == 3 && fabs(sk.ra[1] - 0.2) < TOL && fabs(sk.rb[1] - 0.1) < TOL && fabs(sk.ra[2] - 0.2) < TOL &&
               fabs(sk.rb[2] - 0.3) < TOL);
  }

  /* RMF: a planar bend keeps the normal of its plane (-x, the turtle's up) */
  draw("F+(30)F+(30)F+(30)F-(70)F", &p, &sk);
  double e = 0;
  for (uint32_t i = 0; i < sk.n; i++) e = fmax(e, dist3(sk.up + 3 * i, (const double[3]){-1, 0, 0}));
  t_check("RMF on a planar bend: the normal stays the plane's normal (no twist)", e, TOL);
  draw("F\\(50)F\\(50)F/(170)F", &p, &sk);
  e = 0;
  for (uint32_t i = 0; i < sk.n; i++) e = fmax(e, dist3(sk.up + 3 * i, (const double[3]){-1, 0, 0}));
  t_check("RMF under rolls: the normal does not follow the turtle's roll", e, TOL);
  /* a space curve: each normal is the previous one turned by the minimal
   * rotation between the segments' directions */
  draw("F&(30)F+(40)F\\(25)^(60)F[-(80)F]F", &p, &sk);
  e = 0;
  for (uint32_t i = 1; i < sk.n; i++) {
    uint32_t j = i == 5 ? 3 : i - 1; /* after the branch, F continues from segment 3 */
    double d0[3], d1[3], r[3] = {sk.up[3 * j], sk.up[3 * j + 1], sk.up[3 * j + 2]};
    for (int k = 0; k < 3; k++) d0[k] = sk.b[3 * j + k] - sk.a[3 * j + k], d1[k] = sk.b[3 * i + k] - sk.a[3 * i + k];
    double l0 = sqrt(d0[0] * d0[0] + d0[1] * d0[1] + d0[2] * d0[2]), l1 = sqrt(d1[0] * d1[0] + d1[1] * d1[1] + d1[2] * d1[2]);
    for (int k = 0; k < 3; k++) d0[k] /= l0, d1[k] /= l1;
    rodrigues(r, d0, d1);
    e = fmax(e, dist3(r, sk.up + 3 * i));
    double dot = r[0] * d1[0] + r[1] * d1[1] + r[2] * d1[2];
    e = fmax(e, fabs(dot));
  }
  t_check("RMF on a space curve with a branch: the minimal rotation (Rodrigues) between segments", e, 1e-12);

  /* tropism: T = +x, e = 0.3; H turns by e |H x T| after each F */
  p.tropism[0] = 1, p.tropism[1] = 0, p.tropism[2] = 0, p.tropism_strength = 0.3;
  draw("FFF", &p, &sk);
  double th1 = 0.3, th2 = th1 + 0.3 * cos(th1);
  double want_d[3][3] = {{0, 0, 1}, {sin(th1), 0, cos(th1)}, {sin(th2), 0, cos(th2)}};
  e = sk.n == 3 ? 0 : INFINITY;
  for (uint32_t i = 0; i < sk.n && i < 3; i++) {
    double d[3] = {sk.b[3 * i] - sk.a[3 * i], sk.b[3 * i + 1] - sk.a[3 * i + 1], sk.b[3 * i + 2] - sk.a[3 * i + 2]};
    e = fmax(e, dist3(d, want_d[i]));
  }
  t_check("tropism toward +x with e = 0.3: headings 0, e, e + e cos e from +z", e, TOL);

  /* variance: F(5,1) moves uniformly in [4, 6]; +(90,10) turns in [80, 100] */
  p = defaults();
  char ax[1024] = "";
  for (int i = 0; i < 60; i++) strcat(ax, "[F(5,1)]");
  draw(ax, &p, &sk);
  double lo = INFINITY, hi = -INFINITY, mean = 0;
  for (uint32_t i = 0; i < sk.n; i++) {
    double l = dist3(sk.a + 3 * i, sk.b + 3 * i);
    lo = fmin(lo, l), hi = fmax(hi, l), mean += l / sk.n;
  }
  printf("  F(5,1) x %u: min %.3f max %.3f mean %.3f\n", sk.n, lo, hi, mean);
  t_true("F(5,1): lengths within [4, 6] and spread over it (min < 4.3, max > 5.7)",
         sk.n == 60 && lo >= 4 && hi <= 6 && lo < 4.3 && hi > 5.7);
  t_check("... mean near 5 (3 sigma of 60 uniform draws = 0.22)", fabs(mean - 5), 0.22);
  p.thickness_variance = 0.3;
  ax[0] = 0;
  for (int i = 0; i < 60; i++) strcat(ax, "[!(1)F]");
  draw(ax, &p, &sk);
  lo = INFINITY, hi = -INFINITY;
  for (uint32_t i = 0; i < sk.n; i++) lo = fmin(lo, sk.ra[i]), hi = fmax(hi, sk.ra[i]);
  printf("  thickness variance 0.3: radii in [%.4f, %.4f]\n", lo, hi);
  t_true("thickness variance 0.3: radii within 0.1 (1 +- 0.3) and spread", lo >= 0.07 && hi <= 0.13 && hi - lo > 0.04);
  sessile_skeleton_free(&sk);
  return t_finish(NULL);
}
