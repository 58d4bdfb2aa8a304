/* The seabed (docs/reef.md, "Seabed"): octaves of seeded value noise sampled
 * on a grid, read back bilinearly.  The lattice values hash (seed, octave,
 * i, j), so the heightfield does not depend on evaluation order. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/reef/reef.h"
#include "sessile/rng.h"

static double lattice(uint64_t seed, int octave, int64_t i, int64_t j) {
  uint64_t z = sessile_rng_mix(seed ^ sessile_rng_mix((uint64_t)octave * SESSILE_RNG_GAMMA + (uint64_t)i));
  z = sessile_rng_mix(z ^ ((uint64_t)j * 0xD1B54A32D192ED03ull));
  return (double)(z >> 11) * (2.0 / 9007199254740992.0) - 1.0;
}

static double smooth(double t) { return t * t * (3 - 2 * t); }

static double value_noise(uint64_t seed, int octave, double x, double y) {
  double fx = floor(x), fy = floor(y), u = smooth(x - fx), v = smooth(y - fy);
  int64_t i = (int64_t)fx, j = (int64_t)fy;
  double a = lattice(seed, octave, i, j), b = lattice(seed, octave, i + 1, j);
  double c = lattice(seed, octave, i, j + 1), d = lattice(seed, octave, i + 1, j + 1);
  return (a * (1 - u) + b * u) * (1 - v) + (c * (1 - u) + d * u) * v;
}

sessile_status sessile_reef_seabed_make(const sessile_reef_scene *s, sessile_reef_seabed *out) {
  memset(out, 0, sizeof *out);
  out->nx = s->res[0], out->ny = s->res[1];
  out->extent[0] = s->extent[0], out->extent[1] = s->extent[1];
  out->h = malloc((size_t)out->nx * out->ny * sizeof *out->h);
  SESSILE_CHECK(out->h, SESSILE_ERR_NO_MEMORY, "out of host memory for a %ux%u seabed", out->nx, out->ny);
  if (s->heights) {
    memcpy(out->h, s->heights, (size_t)out->nx * out->ny * sizeof *out->h);
    return SESSILE_OK;
  }
  double dx = out->extent[0] / (out->nx - 1), dy = out->extent[1] / (out->ny - 1), norm = 0;
  for (int o = 0; o < s->octaves; o++) norm += ldexp(1, -o);
  for (uint32_t j = 0; j < out->ny; j++)
    for (uint32_t i = 0; i < out->nx; i++) {
      double sum = 0;
      for (int o = 0; o < s->octaves; o++) {
        double f = ldexp(1, o) / s->wavelength;
        sum += ldexp(1, -o) * value_noise(s->seabed_seed, o, i * dx * f, j * dy * f);
      }
      out->h[(size_t)j * out->nx + i] = s->base + s->height_scale * sum / norm;
    }
  return SESSILE_OK;
}

void sessile_reef_seabed_free(sessile_reef_seabed *b) {
  if (b) free(b->h), memset(b, 0, sizeof *b);
}

int sessile_reef_seabed_at(const sessile_reef_seabed *b, double x, double y, double *z, double n[3]) {
  if (!(x >= 0 && x <= b->extent[0] && y >= 0 && y <= b->extent[1])) return 0;
  double dx = b->extent[0] / (b->nx - 1), dy = b->extent[1] / (b->ny - 1);
  double gx = x / dx, gy = y / dy;
  uint32_t i = (uint32_t)gx, j = (uint32_t)gy;
  if (i > b->nx - 2) i = b->nx - 2;
  if (j > b->ny - 2) j = b->ny - 2;
  double u = gx - i, v = gy - j;
  const double *r0 = b->h + (size_t)j * b->nx + i, *r1 = r0 + b->nx;
  double h00 = r0[0], h10 = r0[1], h01 = r1[0], h11 = r1[1];
  if (z) *z = (h00 * (1 - u) + h10 * u) * (1 - v) + (h01 * (1 - u) + h11 * u) * v;
  if (n) {
    double zx = ((1 - v) * (h10 - h00) + v * (h11 - h01)) / dx, zy = ((1 - u) * (h01 - h00) + u * (h11 - h10)) / dy;
    double l = sqrt(zx * zx + zy * zy + 1);
    n[0] = -zx / l, n[1] = -zy / l, n[2] = 1 / l;
  }
  return 1;
}
