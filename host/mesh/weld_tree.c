/* A random branching skeleton for the weld's tests and benchmark: tips grow
 * breadth-first, each step bending a little and sometimes forking; every
 * draw from one splitmix64 stream of the seed (sessile/rng.h). */
#include <math.h>
#include "sessile/rng.h"
#include <stdlib.h>
#include "weld_internal.h"

typedef struct tip {
  double p[3], d[3], r;
} tip;

static void bend(uint64_t *rs, const double d[3], double amount, double out[3]) {
  double l = 0;
  for (int k = 0; k < 3; k++) out[k] = d[k] + amount * sessile_rng_normal(rs), l += out[k] * out[k];
  out[2] += 0.15 * amount; /* a slight upward tropism keeps the tree off the floor */
  l = sqrt(out[0] * out[0] + out[1] * out[1] + out[2] * out[2]);
  for (int k = 0; k < 3; k++) out[k] /= l;
}

sessile_status weld_random_tree(uint64_t seed, uint32_t nseg, double r0, sessile_skeleton *s) {
  uint64_t rs = sessile_rng_stream(seed, 0x77656c64ull /* "weld" */);
  tip *q = malloc(((size_t)nseg * 2 + 2) * sizeof *q);
  SESSILE_CHECK(q, SESSILE_ERR_NO_MEMORY, "out of host memory for a tree of %u segments", nseg);
  size_t head = 0, tail = 0;
  q[tail++] = (tip){{0, 0, 0}, {0, 0, 1}, r0};
  sessile_status st = SESSILE_OK;
  const double up[3] = {1, 0, 0};
  while (s->n < nseg && head < tail && st == SESSILE_OK) {
    tip t = q[head++];
    double len = 4 * t.r + 2 * r0 * sessile_rng_uniform(&rs);
    double rb = fmax(t.r * 0.97, 0.3 * r0);
    double b[3] = {t.p[0] + len * t.d[0], t.p[1] + len * t.d[1], t.p[2] + len * t.d[2]};
    st = sessile_skeleton_add(s, t.p, b, t.r, rb, up, (double)s->n);
    tip c = {{b[0], b[1], b[2]}, {0, 0, 0}, rb};
    bend(&rs, t.d, 0.25, c.d);
    q[tail++] = c;
    if (sessile_rng_uniform(&rs) < 0.3) {
      tip f = {{b[0], b[1], b[2]}, {0, 0, 0}, rb * 0.8};
      bend(&rs, t.d, 0.9, f.d);
      q[tail++] = f;
    }
  }
  free(q);
  return st;
}
