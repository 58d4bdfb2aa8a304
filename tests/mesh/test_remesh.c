/* The remesher (§4.6): the curve midpoint on a sphere, a scaled-up sphere
 * (every edge too long), the fixed point (no oscillation), determinism, a
 * seeded stress test of growth-like deformations with a floor, the enclosed
 * volume under pure remeshing, and the time for ~50k triangles.  Pure C. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "sessile/mesh/surface.h"
#include "testutil.h"

static const double ORIGIN[3] = {0, 0, 0};

/* CPU time of this process: the machine is shared, wall time is noisy. */
static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

static uint64_t rng_state = 0x9E3779B97F4A7C15ull;
static double urand(void) { /* splitmix64 -> [0, 1) */
  uint64_t z = (rng_state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return (double)((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
}

static double max_edge(const sessile_surface *s) {
  sessile_surface_stats st;
  sessile_surface_stats_of(s, &st);
  return st.edge_max;
}

static double volume(const sessile_surface *s) {
  sessile_surface_stats st;
  sessile_surface_stats_of(s, &st);
  return st.volume;
}

static int same(const sessile_surface *a, const sessile_surface *b) {
  return a->nv == b->nv && a->nf == b->nf &&
         !memcmp(a->pos, b->pos, (size_t)a->nv * 3 * sizeof *a->pos) &&
         !memcmp(a->tri, b->tri, (size_t)a->nf * 3 * sizeof *a->tri);
}

/* Remeshing the output again must change nothing (bit for bit). */
static int is_fixed_point(const sessile_surface *s, const sessile_remesh_options *o) {
  sessile_surface c = {0};
  sessile_remesh_stats st;
  t_ok("copy", sessile_surface_copy(s, &c));
  t_ok("second remesh", sessile_remesh(&c, NULL, o, &st));
  int ok = same(s, &c) && st.splits == 0 && st.fusions == 0 && st.area_collapses == 0;
  sessile_surface_free(&c);
  return ok;
}

static void curve_midpoint(void) {
  /* Unit circle in a tilted plane: ends at angle +-phi from the axis m with
   * exact normals; the midpoint lies on m at distance cos(phi)(1 + sin^2(phi)/2). */
  const double m[3] = {0.6, 0.0, 0.8}, u[3] = {0.0, 1.0, 0.0};
  double worst_formula = 0, worst_ratio = 0;
  for (double phi = 0.05; phi <= 0.41; phi += 0.05) {
    double p0[3], p1[3], q[3];
    for (int a = 0; a < 3; a++) {
      p0[a] = cos(phi) * m[a] - sin(phi) * u[a];
      p1[a] = cos(phi) * m[a] + sin(phi) * u[a];
    }
    sessile_surface_curve_midpoint(p0, p0, p1, p1, q);
    double r = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
    double expect = cos(phi) * (1 + 0.5 * sin(phi) * sin(phi));
    worst_formula = fmax(worst_formula, fabs(r - expect));
    double ratio = fabs(r - 1) / (1 - cos(phi)); /* curve error / chord error */
    worst_ratio = fmax(worst_ratio, ratio);
    double side = fabs(q[1]); /* stays on the bisector */
    worst_formula = fmax(worst_formula, side);
  }
  t_check("curve midpoint on the circle = cos(phi)(1 + sin^2(phi)/2)", worst_formula, 1e-14);
  t_check("curve midpoint error / chord midpoint error, phi <= 0.4 (0.75 phi^2)", worst_ratio,
          0.75 * 0.4 * 0.4);
  /* Flat: coplanar ends with the plane's normal give the chord midpoint. */
  double a[3] = {0, 0, 0}, b[3] = {0.6, 0.2, 0}, n[3] = {0, 0, -1}, q[3];
  sessile_surface_curve_midpoint(a, n, b, n, q);
  t_check("curve midpoint on a plane = chord midpoint", fabs(q[0] - 0.3) + fabs(q[1] - 0.1) +
          fabs(q[2]), 1e-16);
}

static void scaled_sphere(void) {
  /* Level 3 icosphere blown up to radius 3: edges 0.66..0.79, all > 0.6. */
  const double R = 3.0;
  sessile_surface s = {0}, s2 = {0};
  t_ok("icosphere", sessile_surface_icosphere(3, R, ORIGIN, &s));
  sessile_surface_stats st0;
  sessile_surface_stats_of(&s, &st0);
  printf("     input: %u vertices, %u triangles, edges %.3f..%.3f\n", s.nv, s.nf, st0.edge_min,
         st0.edge_max);
  double *n = malloc(s.nv * 3 * sizeof *n);
  for (uint32_t i = 0; i < 3 * s.nv; i++) n[i] = s.pos[i] / R; /* exact normals */
  sessile_remesh_options o;
  sessile_remesh_options_default(&o);
  sessile_remesh_stats st;
  t_ok("copy", sessile_surface_copy(&s, &s2));
  t_ok("remesh", sessile_remesh(&s, n, &o, &st));
  printf("     remesh: %u splits, %u fusions, %u area collapses, %u refused -> %u vertices, %u "
         "triangles\n", st.splits, st.fusions, st.area_collapses, st.rejected, s.nv, s.nf);
  t_true("scaled sphere: every edge was split", st.splits >= st0.ne);
  t_check("scaled sphere: longest edge after remesh (tol insert_len)", max_edge(&s), o.insert_len);
  sessile_status r = sessile_surface_check(&s, 2, 0);
  if (r) printf("     %s\n", sessile_error_message());
  t_true("scaled sphere: invariants hold after remesh", r == SESSILE_OK);
  /* Splitting every edge once gives the level-4 icosphere's connectivity;
   * its new vertices sit on the arc midpoints, ours on the curve midpoints,
   * which are off the sphere by at most 0.375 R phi^4 (phi: half the angle
   * of the longest input edge; test above). */
  double phi = asin(st0.edge_max / (2 * R));
  double bound = R * (1 - cos(phi) * (1 + 0.5 * sin(phi) * sin(phi))) * (1 + 1e-6);
  double worst = 0;
  for (uint32_t v = 0; v < s.nv; v++) {
    double l = sqrt(s.pos[3 * v] * s.pos[3 * v] + s.pos[3 * v + 1] * s.pos[3 * v + 1] +
                    s.pos[3 * v + 2] * s.pos[3 * v + 2]);
    worst = fmax(worst, fabs(l - R));
  }
  t_check("scaled sphere: max |r - R| [cm] (tol: the longest edge's curve error)", worst, bound);
  sessile_surface ico = {0};
  t_ok("icosphere 4", sessile_surface_icosphere(4, R, ORIGIN, &ico));
  double V0 = volume(&s2), V1 = volume(&s), V4 = volume(&ico);
  printf("     volume: input %.4f, remeshed %.4f, level-4 icosphere %.4f, ball %.4f\n", V0, V1, V4,
         4.0 / 3.0 * acos(-1.0) * R * R * R);
  t_true("scaled sphere: 642 vertices, 1280 triangles (the level-4 counts)",
         s.nv == 642 && s.nf == 1280);
  t_check("scaled sphere: volume vs the level-4 icosphere (relative; tol 3 bound / R)",
          fabs(V1 - V4) / V4, 3 * bound / R);
  sessile_surface_free(&ico);
  t_true("scaled sphere: remesh is a fixed point", is_fixed_point(&s, &o));
  /* determinism: the same input twice */
  t_ok("remesh copy", sessile_remesh(&s2, n, &o, &st));
  t_true("scaled sphere: same input, same output (bit for bit)", same(&s, &s2));
  free(n);
  sessile_surface_free(&s);
  sessile_surface_free(&s2);
}

static void smooth_volume(void) {
  /* A fine smooth sphere (level 5, radius 4: edges 0.26..0.33, all short):
   * pure remeshing fuses many vertices; the volume must stay within 0.5% of
   * the input's (the input itself is 0.2% below the ball). */
  sessile_surface s = {0};
  t_ok("icosphere", sessile_surface_icosphere(5, 4.0, ORIGIN, &s));
  double V0 = volume(&s);
  sessile_remesh_options o;
  sessile_remesh_options_default(&o);
  sessile_remesh_stats st;
  t_ok("remesh", sessile_remesh(&s, NULL, &o, &st));
  double V1 = volume(&s);
  printf("     %u fusions, %u area collapses, %u refused: %u triangles; volume %.4f -> %.4f\n",
         st.fusions, st.area_collapses, st.rejected, s.nf, V0, V1);
  t_true("smooth sphere: vertices were fused", st.fusions + st.area_collapses > 0);
  t_check("smooth sphere: relative volume change under remeshing", fabs(V1 - V0) / V0, 5e-3);
  sessile_status r = sessile_surface_check(&s, 2, 0);
  if (r) printf("     %s\n", sessile_error_message());
  t_true("smooth sphere: invariants hold", r == SESSILE_OK);
  t_true("smooth sphere: remesh is a fixed point", is_fixed_point(&s, &o));
  sessile_surface_free(&s);
}

static void stress(void) {
  /* Growth-like rounds on a sphere resting on a floor z >= 0: random outward
   * displacement along the normals, now and then an anisotropic stretch,
   * noise, clamping to the floor; every invariant after every remesh. */
  const double z0 = 0.0;
  sessile_surface s = {0};
  const double c[3] = {0.2, -0.1, 1.6};
  t_ok("icosphere", sessile_surface_icosphere(4, 2.0, c, &s));
  sessile_remesh_options o;
  sessile_remesh_options_default(&o);
  o.clamp_lo[2] = z0;
  for (uint32_t v = 0; v < s.nv; v++) s.pos[3 * v + 2] = fmax(s.pos[3 * v + 2], z0);
  int rounds = 60, bad_inv = 0, bad_len = 0, bad_floor = 0, bad_fixed = 0;
  uint64_t splits = 0, fusions = 0, areas = 0, refused = 0;
  uint32_t floor_min = UINT32_MAX;
  double *n = NULL;
  for (int it = 0; it < rounds; it++) {
    n = realloc(n, (size_t)s.nv * 3 * sizeof *n);
    sessile_surface_normals(&s, n);
    double g = 0.03 + 0.07 * urand();
    for (uint32_t v = 0; v < s.nv; v++) {
      double d = g * (0.5 + urand());
      for (int a = 0; a < 3; a++)
        s.pos[3 * v + a] += d * n[3 * v + a] + 0.02 * (urand() - 0.5);
    }
    if (it % 7 == 3) { /* stretch along x or y about the centre */
      int ax = it % 2;
      for (uint32_t v = 0; v < s.nv; v++) s.pos[3 * v + ax] = c[ax] + 1.15 * (s.pos[3 * v + ax] - c[ax]);
    }
    for (uint32_t v = 0; v < s.nv; v++) s.pos[3 * v + 2] = fmax(s.pos[3 * v + 2], z0);
    sessile_remesh_stats st;
    sessile_status r = sessile_remesh(&s, n, &o, &st);
    if (r) {
      printf("     round %d: remesh failed: %s\n", it, sessile_error_message());
      bad_inv++;
      break;
    }
    splits += st.splits, fusions += st.fusions, areas += st.area_collapses, refused += st.rejected;
    r = sessile_surface_check(&s, 2, 0);
    if (r && bad_inv++ < 3) printf("     round %d: %s\n", it, sessile_error_message());
    if (max_edge(&s) > o.insert_len) bad_len++;
    uint32_t on_floor = 0;
    for (uint32_t v = 0; v < s.nv; v++) {
      if (s.pos[3 * v + 2] < z0) bad_floor++;
      on_floor += s.pos[3 * v + 2] == z0;
    }
    if (on_floor < floor_min) floor_min = on_floor;
    if (!is_fixed_point(&s, &o)) bad_fixed++;
  }
  sessile_surface_stats st;
  sessile_surface_stats_of(&s, &st);
  printf("     %d rounds: %llu splits, %llu fusions, %llu area collapses, %llu refused; final %u "
         "vertices, %u triangles, edges %.3f..%.3f, smallest area %.4f, >= %u vertices on the floor\n",
         rounds, (unsigned long long)splits, (unsigned long long)fusions,
         (unsigned long long)areas, (unsigned long long)refused, s.nv, s.nf, st.edge_min,
         st.edge_max, st.tri_area_min, floor_min);
  t_check("stress: rounds breaking an invariant (check, Euler 2, area > 0)", bad_inv, 0);
  t_check("stress: rounds with an edge > insert_len", bad_len, 0);
  t_check("stress: vertices below the floor (all rounds)", bad_floor, 0);
  t_check("stress: rounds whose output is not a fixed point", bad_fixed, 0);
  t_true("stress: the floor keeps vertices on it", floor_min > 0);
  t_true("stress: splits and fusions both happened", splits > 0 && fusions + areas > 0);
  free(n);
  sessile_surface_free(&s);
}

static void time_remesh(const char *what, sessile_surface *s) {
  sessile_remesh_options o;
  sessile_remesh_options_default(&o);
  sessile_remesh_stats st;
  uint32_t nf0 = s->nf;
  double t0 = now();
  t_ok("remesh", sessile_remesh(s, NULL, &o, &st));
  double t1 = now();
  printf("     TIME remesh %s, %u -> %u triangles: %.1f ms CPU (%u splits, %u fusions, %u area "
         "collapses, %u refused)\n", what, nf0, s->nf, 1e3 * (t1 - t0), st.splits, st.fusions,
         st.area_collapses, st.rejected);
  double t2 = now();
  sessile_status r = sessile_surface_check(s, 2, 0);
  printf("     TIME check of %u triangles: %.1f ms CPU\n", s->nf, 1e3 * (now() - t2));
  t_true("large sphere: invariants hold after remesh", r == SESSILE_OK);
  t_check("large sphere: longest edge (tol insert_len)", max_edge(s), o.insert_len);
}

static void timing(void) {
  /* ~50k triangles, timed only (printed, not asserted): a level-6 icosphere
   * (20480 triangles) blown up so that most edges are too long; then that
   * remeshed surface grown by 3% (one growth step); and a bigger blow-up. */
  sessile_surface s = {0};
  t_ok("icosphere", sessile_surface_icosphere(6, 16.64, ORIGIN, &s));
  time_remesh("level 6 at R = 16.64", &s);
  for (uint32_t i = 0; i < 3 * s.nv; i++) s.pos[i] *= 1.03;
  time_remesh("of that grown by 3%", &s);
  t_ok("icosphere", sessile_surface_icosphere(6, 21.0, ORIGIN, &s));
  time_remesh("level 6 at R = 21 (all edges long)", &s);
  sessile_surface_free(&s);
}

static void errors(void) {
  sessile_surface s = {0};
  t_ok("icosphere", sessile_surface_icosphere(2, 1.0, ORIGIN, &s));
  sessile_remesh_options o;
  sessile_remesh_options_default(&o);
  o.insert_len = -1;
  t_true("remesh rejects a negative insert_len", sessile_remesh(&s, NULL, &o, NULL) ==
                                                    SESSILE_ERR_USAGE);
  sessile_remesh_options_default(&o);
  s.pos[4] = NAN;
  t_true("remesh rejects a NaN position", sessile_remesh(&s, NULL, &o, NULL) ==
                                             SESSILE_ERR_NUMERIC);
  printf("     %s\n", sessile_error_message());
  sessile_surface_free(&s);
}

int main(void) {
  curve_midpoint();
  scaled_sphere();
  smooth_volume();
  stress();
  timing();
  errors();
  return t_finish(NULL);
}
