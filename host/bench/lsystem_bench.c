/* The L-system benchmark (sessile bench coral lsystem): about `target`
 * turtle modules derived, interpreted and meshed as tubes, each stage timed.
 * All three stages are host code (no device kernel to compare with a
 * reference), so it prints each stage's time and rate; the target is 3 s
 * for the three together at 1 M modules. */
#include <stdio.h>
#include <string.h>
#include <time.h>
#include "sessile/bench/bench.h"
#include "sessile/coral/lsystem.h"
#include "sessile/rng.h"
#include "sessile/mesh/skeleton.h"

/* A lophelia-like stochastic parametric grammar (conditions, weights,
 * variance, thickening): each polyp buds one or two daughters. */
static const char *grammar =
    "angle: 25\n"
    "ignore: +-/\\!\n"
    "axiom: !(1) F A(0)\n"
    "A(n) : n >= 0 -(0.6)-> !(0.6) F(1, 0.2) [ +(35, 8) A(n + 1) ] /(137.5, 20) -(10, 5) A(n + 1)\n"
    "A(n) : n >= 0 -(0.4)-> !(0.6) F(1, 0.2) /(90, 20) +(10, 5) A(n + 1)\n"
    "!(w) -> !(w + 0.1)\n";

static double now_s(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + ts.tv_nsec * 1e-9;
}

sessile_status sessile_coral_lsystem_bench(uint32_t target, FILE *out) {
  sessile_lsys *lsys = NULL;
  SESSILE_CALL(sessile_lsys_parse(grammar, strlen(grammar), "bench.lsys", 0, NULL, NULL, &lsys));
  sessile_lsys_string a = {0}, b = {0};
  sessile_skeleton sk = {0};
  sessile_surface mesh = {0};
  uint64_t rng = sessile_rng_stream(1, 1);
  int steps = 0;
  uint64_t rewritten = 0;
  double t0 = now_s();
  sessile_status s = sessile_lsys_derive(lsys, 0, &rng, 50000000, &a);
  while (s == SESSILE_OK && a.n < target && steps < 100) {
    rewritten += a.n;
    s = sessile_lsys_step(lsys, &a, &rng, 50000000, &b);
    sessile_lsys_string t = a;
    a = b, b = t;
    steps++;
  }
  double t1 = now_s(), t2 = t1, t3 = t1;
  sessile_turtle_params tp = {.step = 0.5, .angle = 25, .thickness = 0.2, .thickness_variance = 0.1,
                              .width_factor = 0.8, .tropism = {0, 0, 1}, .tropism_strength = 0.1, .min_radius = 0.01, .taper = 1};
  uint64_t trng = sessile_rng_stream(1, 2);
  sessile_turtle_stats st = {0};
  if (s == SESSILE_OK) s = sessile_turtle_interpret(&a, &tp, &trng, &sk, &st);
  t2 = now_s();
  if (s == SESSILE_OK) s = sessile_skeleton_tubes(&sk, 8, &mesh, NULL);
  t3 = now_s();
  if (s == SESSILE_OK) {
    fprintf(out, "coral lsystem: %u modules after %d steps (%llu modules rewritten), %u segments, %u triangles\n",
            a.n, steps, (unsigned long long)rewritten, st.segments, mesh.nf);
    fprintf(out, "  derive     %7.3f s  (%.3g modules rewritten/s)\n", t1 - t0, rewritten / (t1 - t0));
    fprintf(out, "  turtle     %7.3f s  (%.3g modules/s)\n", t2 - t1, a.n / (t2 - t1));
    fprintf(out, "  tubes      %7.3f s  (8 sides, %.3g segments/s)\n", t3 - t2, st.segments / (t3 - t2));
    fprintf(out, "  total      %7.3f s  (target 3 s for 1 M modules; all host code: no device stage to compare)\n",
            t3 - t0);
  }
  sessile_surface_free(&mesh);
  sessile_skeleton_free(&sk);
  sessile_lsys_string_free(&a);
  sessile_lsys_string_free(&b);
  sessile_lsys_destroy(lsys);
  return s;
}
