/* The sponge surface: icosphere counts, the invariant check on good meshes
 * and on hand-broken ones (one per kind of violation), normals against the
 * analytic sphere normal.  Pure C: no GPU. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/mesh/surface.h"
#include "testutil.h"

static const double C0[3] = {0.5, -1.0, 2.0};

/* check() must fail, with a message containing `word`. */
static void expect_violation(const char *what, const sessile_surface *s, int euler,
                             double min_area, const char *word) {
  sessile_status r = sessile_surface_check(s, euler, min_area);
  const char *msg = sessile_error_message();
  printf("     %s -> %s\n", what, r == SESSILE_OK ? "(accepted)" : msg);
  char buf[160];
  snprintf(buf, sizeof buf, "check detects %s", what);
  t_true(buf, r == SESSILE_ERR_INTERNAL && strstr(msg, word) != NULL);
}

/* A copy of the level-2 icosphere with room to append. */
static void base(sessile_surface *s) {
  t_ok("icosphere", sessile_surface_icosphere(2, 1.0, C0, s));
  t_ok("reserve", sessile_surface_reserve(s, 2 * s->nv + 8, 2 * s->nf + 8));
}

static void broken_meshes(void) {
  sessile_surface s = {0};
  base(&s);
  t_ok("the unbroken base mesh passes", sessile_surface_check(&s, 2, 0));

  s.tri[4] = s.nv + 3;
  expect_violation("an index out of range", &s, 2, 0, "only");
  base(&s);
  s.tri[4] = s.tri[3];
  expect_violation("a triangle repeating a vertex", &s, 2, 0, "repeats a vertex");
  base(&s);
  { uint32_t t = s.tri[7]; s.tri[7] = s.tri[8]; s.tri[8] = t; } /* flip triangle 2 */
  expect_violation("a flipped triangle", &s, 2, 0, "flipped");
  base(&s);
  s.nf--; /* a hole */
  expect_violation("a hole (missing triangle)", &s, 2, 0, "hole");
  base(&s);
  { /* a third triangle on edge (t0, t1) makes it non-manifold */
    uint32_t *t = s.tri + 3 * s.nf, *u = s.tri;
    double *p = s.pos + 3 * s.nv;
    memcpy(p, C0, sizeof C0);
    t[0] = u[0], t[1] = u[1], t[2] = s.nv;
    s.nv++, s.nf++;
  }
  expect_violation("an edge in three triangles", &s, 2, 0, "directed edge");
  base(&s);
  { /* a two-triangle pillow: every edge fine, the triangles duplicate */
    uint32_t v = s.nv, *t = s.tri + 3 * s.nf;
    for (int i = 0; i < 3; i++) {
      double *p = s.pos + 3 * (v + i);
      p[0] = 5 + i, p[1] = i == 2, p[2] = 0;
    }
    t[0] = v, t[1] = v + 1, t[2] = v + 2, t[3] = v, t[4] = v + 2, t[5] = v + 1;
    s.nv += 3, s.nf += 2;
  }
  expect_violation("duplicate triangles", &s, 2, 0, "same vertices");
  base(&s);
  s.pos[3 * s.nv] = 9, s.pos[3 * s.nv + 1] = 9, s.pos[3 * s.nv + 2] = 9;
  s.nv++;
  expect_violation("an unreferenced vertex", &s, 2, 0, "in no triangle");
  base(&s);
  { /* a second sphere: a valid manifold, but Euler characteristic 4 */
    uint32_t nv = s.nv, nf = s.nf;
    memcpy(s.pos + 3 * nv, s.pos, nv * 3 * sizeof *s.pos);
    for (uint32_t i = 0; i < nv; i++) s.pos[3 * (nv + i)] += 10;
    for (uint32_t k = 0; k < 3 * nf; k++) s.tri[3 * nf + k] = s.tri[k] + nv;
    s.nv *= 2, s.nf *= 2;
  }
  expect_violation("a second component (Euler 4)", &s, 2, 0, "Euler");
  t_ok("two spheres pass with euler = 4", sessile_surface_check(&s, 4, 0));
  base(&s);
  memcpy(s.pos + 3 * s.tri[0], s.pos + 3 * s.tri[1], 3 * sizeof *s.pos); /* zero-area triangle */
  expect_violation("a zero-area triangle", &s, 2, 0, "area");
  base(&s);
  expect_violation("a triangle below min_area", &s, 2, 0.2, "area");
  base(&s);
  s.pos[5] = NAN;
  expect_violation("a NaN position", &s, 2, 0, "area");
  sessile_surface_free(&s);
  sessile_surface_free(&s); /* free twice: the struct is zeroed */
}

/* Largest angle (radians) between the area-weighted and the radial normal. */
static double normal_error(int level, double *h) {
  sessile_surface s = {0};
  t_ok("icosphere", sessile_surface_icosphere(level, 2.0, C0, &s));
  double *n = malloc(s.nv * 3 * sizeof *n), worst = 0;
  sessile_surface_normals(&s, n);
  for (uint32_t v = 0; v < s.nv; v++) {
    double r[3], l = 0, dot = 0;
    for (int a = 0; a < 3; a++) r[a] = s.pos[3 * v + a] - C0[a], l += r[a] * r[a];
    for (int a = 0; a < 3; a++) dot += n[3 * v + a] * r[a] / sqrt(l);
    double ang = acos(fmin(1.0, dot));
    if (ang > worst) worst = ang;
  }
  sessile_surface_stats st;
  sessile_surface_stats_of(&s, &st);
  *h = st.edge_max / 2.0; /* the edge in units of the radius */
  free(n);
  sessile_surface_free(&s);
  return worst;
}

int main(void) {
  for (int level = 1; level <= 5; level++) {
    sessile_surface s = {0};
    t_ok("icosphere", sessile_surface_icosphere(level, 2.0, C0, &s));
    uint32_t p = 1u << (2 * (level - 1));
    char w[128];
    snprintf(w, sizeof w, "icosphere level %d: %u vertices, %u triangles", level, 10 * p + 2,
             20 * p);
    t_true(w, s.nv == 10 * p + 2 && s.nf == 20 * p);
    snprintf(w, sizeof w, "icosphere level %d passes check (Euler 2, area > 0)", level);
    sessile_status r = sessile_surface_check(&s, 2, 0);
    t_true(w, r == SESSILE_OK);
    if (r) printf("     %s\n", sessile_error_message());
    sessile_surface_stats st;
    sessile_surface_stats_of(&s, &st);
    snprintf(w, sizeof w, "level %d: V - E + F from stats", level);
    t_check(w, fabs((double)st.nv - st.ne + st.nf - 2), 0);
    double rmax = 0;
    for (uint32_t v = 0; v < s.nv; v++) {
      double l = 0;
      for (int a = 0; a < 3; a++) l += pow(s.pos[3 * v + a] - C0[a], 2);
      rmax = fmax(rmax, fabs(sqrt(l) - 2.0));
    }
    snprintf(w, sizeof w, "level %d: vertices on the sphere (|r - R|)", level);
    t_check(w, rmax, 1e-12);
    /* An inscribed polyhedron: its volume is below the ball's, by at most
     * the cap volume over each face, ~ (3/2)(h/R)^2 relative for edge h. */
    double vball = 4.0 / 3.0 * acos(-1.0) * 8.0, rel = (vball - st.volume) / vball;
    double h = st.edge_max / 2.0;
    snprintf(w, sizeof w, "level %d: volume deficit (ball - mesh)/ball in [0, 1.5 (h/R)^2]", level);
    t_check(w, rel < 0 ? INFINITY : rel, 1.5 * h * h);
    if (level == 4) t_true("level 4 is Table 1's sponge: 642 vertices, 1280 triangles",
                           s.nv == 642 && s.nf == 1280);
    sessile_surface_free(&s);
  }
  /* Normals: the area-weighted normal of a vertex on a sphere differs from the
   * radial one by O(h^2) at regular vertices, O(h) at the irregular
   * (valence-5) ones only through asymmetric neighbour areas; tolerance
   * 0.15 h (h = longest edge / R; measured 0.073 h, first order, halving per
   * level), checked on levels 3..5 so the trend shows. */
  for (int level = 3; level <= 5; level++) {
    double h, e = normal_error(level, &h);
    char w[128];
    snprintf(w, sizeof w, "level %d: angle(area normal, radial) [rad], tol 0.15 h, h=%.3f", level,
             h);
    t_check(w, e, 0.15 * h);
  }
  broken_meshes();
  return t_finish(NULL);
}
