/* Currents (docs/reef.md, "Currents"; Coralize §4.3, Figure 12): the three
 * cases (inside the nutrition range: 1; between it and the hemisphere:
 * range / distance; outside: 0), a ridge that shelters, exposures adding
 * over currents, and the GPU kernel against the host reference. */
#include <math.h>
#include <stdio.h>
#include "reef_test_scene.h"
#include "sessile/rng.h"

static double flat(double x, double y) { return 0 * x * y; }
/* a 2 m ridge along y at x = 11.5 */
static double ridge(double x, double y) { return fabs(x - 11.5) < 0.3 ? 2 + 0 * y : 0; }
static double hills(double x, double y) { return 1.5 * sin(x * 0.7) * cos(y * 0.45) + 0.3 * sin(3 * y); }

static const sessile_reef_current cur = {{10, 10, 0.5}, {1, 0, 0}, 6, 1};

static void figure12(void) {
  sessile_reef_seabed b;
  rt_seabed(&b, 81, 81, 20, 20, flat);
  const double red[3] = {13, 10, 0}, green[3] = {13, 12, 0}, blue[3] = {17, 10, 0}, behind[3] = {8, 10, 0};
  t_true("inside the nutrition range: 1", sessile_reef_exposure_one(&cur, &b, red) == 1);
  t_true("between range and hemisphere: range / distance",
         sessile_reef_exposure_one(&cur, &b, green) == 1 / sqrt(4.25));
  t_true("outside the hemisphere: 0", sessile_reef_exposure_one(&cur, &b, blue) == 0);
  t_true("behind the current's origin: 0", sessile_reef_exposure_one(&cur, &b, behind) == 0);
  sessile_reef_seabed_free(&b);
  rt_seabed(&b, 81, 81, 20, 20, ridge);
  t_true("behind a ridge: sheltered, 0", sessile_reef_exposure_one(&cur, &b, red) == 0);
  const double before[3] = {11, 10, 0};
  t_true("before the ridge: 1", sessile_reef_exposure_one(&cur, &b, before) == 1);
  sessile_reef_seabed_free(&b);
}

static void gpu_vs_host(sessile_gpu *gpu) {
  sessile_reef_scene s = {0};
  sessile_reef_current c[3] = {{{2, 3, 2}, {0.6, 0.8, 0}, 15, 2}, {{18, 18, 1}, {-1, 0, 0}, 12, 0.5},
                               {{10, 1, 4}, {0, 0.6, -0.8}, 9, 3}};
  s.currents = c, s.ncurrents = 3;
  sessile_reef_seabed b;
  rt_seabed(&b, 97, 81, 20, 20, hills);
  sessile_reef_placements ref = {0}, dev = {0};
  ref.n = ref.cap = 3000;
  ref.p = t_xalloc(ref.n * sizeof *ref.p);
  uint64_t rng = 5;
  for (uint32_t k = 0; k < ref.n; k++) {
    double *p = ref.p[k].pos;
    p[0] = sessile_rng_range(&rng, 0, 20), p[1] = sessile_rng_range(&rng, 0, 20);
    sessile_reef_seabed_at(&b, p[0], p[1], &p[2], NULL);
  }
  dev = ref;
  dev.p = t_xalloc(ref.n * sizeof *ref.p);
  memcpy(dev.p, ref.p, ref.n * sizeof *ref.p);
  sessile_reef_exposure_ref(&s, &b, &ref, 0);
  t_ok("the exposure kernel", sessile_reef_exposure_gpu(gpu, &s, &b, &dev, 0));
  int fp32 = sessile_gpu_info_of(gpu)->precision == 32;
  double err = 0, flips = 0, zero = 0, full = 0;
  for (uint32_t k = 0; k < ref.n; k++) {
    double a = dev.p[k].exposure, e = ref.p[k].exposure;
    if ((a == 0) != (e == 0)) flips++;
    else err = fmax(err, fabs(a - e));
    zero += e == 0, full += e >= 1;
  }
  printf("exposure: %u organisms, %.0f unexposed, %.0f at least 1, %.0f differ in shelter\n", ref.n, zero, full,
         flips);
  t_true("the sample has sheltered, partly and fully exposed organisms", zero > 100 && full > 100 && zero < ref.n);
  t_check("GPU vs host exposure", err, fp32 ? 1e-4 : 1e-12);
  t_check("organisms sheltered on one side only", flips, fp32 ? ref.n * 0.005 : 0);
  free(ref.p), free(dev.p);
  sessile_reef_seabed_free(&b);
}

int main(void) {
  figure12();
  sessile_gpu *gpu = t_gpu(0);
  gpu_vs_host(gpu);
  return t_finish(gpu);
}
