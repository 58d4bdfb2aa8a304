/* Regression: split triangles lying side by side in one plane are no
 * crossing.  A remesh whose split points end on the chord (the split
 * guard's fallback) re-triangulates each old triangle in its own plane;
 * the children meet at the new midpoint along collinear edges and their
 * coplanarity is only as good as the midpoint's rounding.  The pair test
 * read such a child's edge as crossing the other child's plane at one end
 * and then trusted line-edge signs that are meaningless for a line lying in
 * that plane: it reported pairs (0 before the remesh, some after), which made
 * sessile_remesh return a "crossing" surface (docs/intersection.md,
 * docs/remesh.md).  Pure C. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/mesh/intersect.h"
#include "sessile/rng.h"
#include "sessile/mesh/surface.h"
#include "testutil.h"

static const double ORIGIN[3] = {0, 0, 0};

static uint64_t pairs_of(const sessile_surface *s) {
  uint64_t n = 0;
  t_ok("self-intersections", sessile_surface_self_intersections(s, 0, NULL, &n));
  return n;
}

static void load(const char *hex, double out[9]) {
  char *end = (char *)hex;
  for (int i = 0; i < 9; i++) out[i] = strtod(end, &end);
}

/* Pairs found in the particle sponge's failing remesh (seed 1, iteration
 * 42): the children of one triangle whose split points were all put back on
 * the chord; ids as in the remeshed surface (one shared vertex each). */
static void saved_pairs(void) {
  static const struct {
    const char *a, *b;
    uint32_t va[3], vb[3];
  } c[] = {
      {"0x1.10b034c9ab9f4p-2 0x1.76c2340ccf33p+0 0x1.2fd01c93c8dd8p+1 0x1.11d5db7234853p-2 "
       "0x1.5bf627e1d6e9ep+0 0x1.3677ce770fe21p+1 0x1.09e36d9baf7d2p-2 0x1.70f341ad74b46p+0 "
       "0x1.2b992f46b4a78p+1",
       "0x1.0f8a8e2122b96p-2 0x1.918e4037c77c2p+0 0x1.29286ab081d9p+1 0x1.09e36d9baf7d2p-2 "
       "0x1.70f341ad74b46p+0 0x1.2b992f46b4a78p+1 0x1.01f0ffc52a752p-2 0x1.85f05b79127eep+0 "
       "0x1.20ba9016596cfp+1",
       {5967, 2670, 5966}, {3860, 5966, 3582}},
      {"-0x1.27a9a82868276p-4 0x1.cf5e5fe36d05ep+0 0x1.359c3a1832b62p+1 0x1.1452ed0cef9a2p-6 "
       "0x1.d75ef37a15d9ep+0 0x1.2fb5597542ce2p+1 -0x1.8b681be758eeep-4 0x1.d6ba3df4b8c8cp+0 "
       "0x1.2f2afb1cde20cp+1",
       "-0x1.4a3405ca061aap-3 0x1.c75dcc4cc431dp+0 0x1.3b831abb229e3p+1 -0x1.8b681be758eeep-4 "
       "0x1.d6ba3df4b8c8cp+0 0x1.2f2afb1cde20cp+1 -0x1.adf27988f6e22p-3 0x1.d615886f5bb7bp+0 "
       "0x1.2ea09cc479735p+1",
       {1, 2, 3}, {4, 3, 5}},
      {"-0x1.ae0619fdbd3ap-5 0x1.c20f41c4efc2cp+0 0x1.3a99e9668bd5ep+1 0x1.1452ed0cef9a2p-6 "
       "0x1.d75ef37a15d9ep+0 0x1.2fb5597542ce2p+1 -0x1.27a9a82868276p-4 0x1.cf5e5fe36d05ep+0 "
       "0x1.359c3a1832b62p+1",
       "-0x1.f31ad540f9209p-4 0x1.acbf900fc9abbp+0 0x1.457e7957d4dd9p+1 -0x1.ae0619fdbd3ap-5 "
       "0x1.c20f41c4efc2cp+0 0x1.3a99e9668bd5ep+1 -0x1.4a3405ca061aap-3 0x1.c75dcc4cc431dp+0 "
       "0x1.3b831abb229e3p+1",
       {1, 2, 3}, {4, 1, 5}},
  };
  for (size_t i = 0; i < sizeof c / sizeof *c; i++) {
    double a[9], b[9];
    load(c[i].a, a), load(c[i].b, b);
    /* the shared corner must really be one point (the ids say so) */
    int sh = 0;
    for (int p = 0; p < 3; p++)
      for (int q = 0; q < 3; q++)
        if (c[i].va[p] == c[i].vb[q]) sh += !memcmp(a + 3 * p, b + 3 * q, 3 * sizeof *a);
    t_true("saved pair: one shared corner", sh == 1);
    t_true("saved pair: side by side in one plane, no crossing",
           !sessile_triangles_intersect(a, c[i].va, b, c[i].vb));
  }
}

/* A jittered sphere split with one normal for every vertex: the curve point
 * of an edge is then its chord midpoint (the (w1 n1 - w0 n0)/8 term is 0),
 * so every split stays in its old triangle's plane, the same configuration
 * the guard's fallback makes.  The surface is clean before, and in exact
 * arithmetic after; the count must say so for every seed. */
static void flat_splits(void) {
  uint64_t total = 0;
  int bad = 0;
  for (uint64_t seed = 1; seed <= 24; seed++) {
    sessile_surface s = {0};
    t_must("icosphere", sessile_surface_icosphere(3, 2.5, ORIGIN, &s));
    uint64_t st = sessile_rng_stream(seed, 0x5711);
    for (uint32_t i = 0; i < 3 * s.nv; i++) s.pos[i] += sessile_rng_range(&st, -0.06, 0.06);
    double *n = t_dalloc((size_t)s.nv * 3);
    double u[3] = {sessile_rng_normal(&st), sessile_rng_normal(&st), sessile_rng_normal(&st)};
    double l = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    for (uint32_t v = 0; v < s.nv; v++)
      for (int k = 0; k < 3; k++) n[3 * v + k] = u[k] / l;
    uint64_t before = pairs_of(&s);
    sessile_remesh_options o;
    sessile_remesh_options_default(&o);
    o.insert_len = 0.2, o.fuse_len = 0, o.min_area = 0; /* splits only, two sweeps */
    sessile_remesh_stats rs;
    t_ok("remesh", sessile_remesh(&s, n, &o, &rs));
    uint64_t after = pairs_of(&s);
    total += after;
    bad += before != 0 || after != 0 || rs.chord_splits != 0 ||
           sessile_surface_check(&s, 2, 0) != SESSILE_OK;
    free(n);
    sessile_surface_free(&s);
  }
  printf("     24 jittered spheres split flat: %llu pairs after\n", (unsigned long long)total);
  t_check("flat splits: pairs after (sum over 24 seeds)", (double)total, 0);
  t_true("flat splits: every surface clean before and after, a manifold, no chord fallback", !bad);
}

/* The in-plane fallback must not lose crossings: a triangle tilted 1e-13
 * out of another's plane that passes through it is still a pair; the same
 * one moved beside it is not. */
static void near_coplanar(void) {
  const double t[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const double in[9] = {0.2, 0.2, -1e-13, 0.6, 0.2, 1e-13, 0.2, 0.6, 1e-13};
  const double out[9] = {2.2, 0.2, -1e-13, 2.6, 0.2, 1e-13, 2.2, 0.6, 1e-13};
  t_true("near coplanar: crossing inside is found", sessile_triangles_intersect(t, NULL, in, NULL));
  t_true("near coplanar: beside is no pair", !sessile_triangles_intersect(t, NULL, out, NULL));
}

int main(void) {
  saved_pairs();
  near_coplanar();
  flat_splits();
  return t_finish(NULL);
}
