/* The particle sponge's collision search: the GPU kernel and the host grid
 * against brute force, hit for hit (bitwise: the same float test), on random
 * clouds (particles inside, at the edges of and outside the grid), particles
 * touching vertices exactly at the radius, empty cells, an empty surface and
 * feed limits (more hits than the feed keeps: the smallest indices,
 * ascending, and the full count). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/sponge/particles.h"
#include "sessile/rng.h"
#include "testutil.h"

/* Runs all three on (vtx, part) and counts particles whose hits differ from
 * brute force; returns the total hit count (brute force) through *hits. */
static uint32_t compare(sessile_sponge_particles_gpu *col, const double *vtx, uint32_t nv, const float *part,
                        uint32_t np, float r, uint32_t feed, uint64_t *hits, uint32_t *bh, uint32_t *bc) {
  sessile_sponge_particles_grid g;
  t_must("grid", sessile_sponge_particles_grid_build(vtx, nv, r, &g));
  uint32_t *gh = t_xalloc((size_t)np * feed * 4 + 4), *gc = t_xalloc((size_t)np * 4 + 4);
  uint32_t *hh = t_xalloc((size_t)np * feed * 4 + 4), *hc = t_xalloc((size_t)np * 4 + 4);
  t_must("brute force", sessile_sponge_particles_collide_brute(part, np, g.pos4, nv, r, feed, bh, bc));
  t_must("host grid", sessile_sponge_particles_collide_grid(&g, part, np, r, feed, hh, hc));
  t_must("GPU", sessile_sponge_particles_gpu_collide(col, &g, part, np, r, feed, gh, gc, NULL));
  uint32_t diff = 0;
  *hits = 0;
  for (uint32_t i = 0; i < np; i++) {
    *hits += bc[i];
    size_t o = (size_t)feed * i;
    if (bc[i] != gc[i] || bc[i] != hc[i] || memcmp(bh + o, gh + o, feed * 4) || memcmp(bh + o, hh + o, feed * 4))
      diff++;
  }
  sessile_sponge_particles_grid_free(&g);
  free(gh), free(gc), free(hh), free(hc);
  return diff;
}

static void random_cloud(sessile_sponge_particles_gpu *col, uint64_t seed, uint32_t nv, uint32_t np, float r, uint32_t feed) {
  uint64_t rng = sessile_rng_stream(seed, 1);
  double *vtx = t_dalloc((size_t)nv * 3 + 3);
  float *part = t_xalloc((size_t)np * 16 + 16);
  for (uint32_t v = 0; v < 3 * nv; v++) vtx[v] = sessile_rng_range(&rng, -1, 1);
  /* particles over a box 30 % wider than the cloud: some outside the grid,
   * many near its faces (where a range check can be off by one cell) */
  for (uint32_t i = 0; i < np; i++) {
    for (int a = 0; a < 3; a++) part[4 * i + a] = (float)sessile_rng_range(&rng, -1.3, 1.3);
    part[4 * i + 3] = 0;
  }
  uint32_t *bh = t_xalloc((size_t)np * feed * 4 + 4), *bc = t_xalloc((size_t)np * 4 + 4);
  uint64_t hits = 0;
  uint32_t diff = compare(col, vtx, nv, part, np, r, feed, &hits, bh, bc);
  char what[160];
  snprintf(what, sizeof what, "random cloud: %u vertices, %u particles, radius %g, feed %u (%llu hits): "
           "particles differing from brute force", nv, np, (double)r, feed, (unsigned long long)hits);
  t_check(what, diff, 0);
  t_true("... the cloud has hits and misses", hits > 0 && hits < (uint64_t)np * nv);
  free(vtx), free(part), free(bh), free(bc);
}

int main(void) {
  sessile_gpu *gpu = t_gpu(0);
  sessile_sponge_particles_gpu *col = NULL;
  t_must("GPU collider", sessile_sponge_particles_gpu_create(gpu, &col));

  random_cloud(col, 1, 3000, 20000, 0.05f, 1);
  random_cloud(col, 2, 3000, 20000, 0.1f, 3);
  random_cloud(col, 3, 500, 5000, 0.3f, 16);  /* many hits per particle: the feed cuts */
  random_cloud(col, 4, 20, 5000, 0.2f, 2);    /* a sparse grid: most cells empty */

  /* Exactly at the radius (every value and product exact in float): a hit;
   * one float step further: none. */
  {
    const double vtx[6] = {0.5, 0.5, 0.5, -1, -1, -1};
    float part[16] = {0.5f, 0.5f, 0.75f, 0, /* distance 0.25 along z */
                      -1 + 0.75f, -1 + 1.0f, -1, 0, /* 0.75, 1.0, 0: distance 1.25 */
                      0.5f, 0.5f, nextafterf(0.75f, 1), 0, 0, 0, 0, 0};
    uint32_t bh[4], bc[4];
    uint64_t hits = 0;
    t_check("touching at r = 0.25: particles differing from brute force",
            compare(col, vtx, 2, part, 4, 0.25f, 1, &hits, bh, bc), 0);
    t_true("... a particle exactly r = 0.25 from a vertex touches it", bc[0] == 1 && bh[0] == 0);
    t_true("... one float step further it does not", bc[2] == 0 && bh[2] == SESSILE_SPONGE_PARTICLES_NO_HIT);
    t_check("touching at r = 1.25 (a 3-4-5 triangle): differing", compare(col, vtx, 2, part, 4, 1.25f, 1, &hits, bh, bc), 0);
    t_true("... the particle 1.25 from vertex 1 touches it", bc[1] >= 1 && bh[1] == 1);
  }

  /* Feed limits: 40 vertices within 0.1 of the origin at scattered indices
   * among 2000 far ones: count 40, and the feed smallest indices. */
  {
    uint32_t nv = 2000;
    double *vtx = t_dalloc((size_t)nv * 3);
    uint64_t rng = sessile_rng_stream(5, 2);
    uint32_t near[40], k = 0;
    for (uint32_t v = 0; v < nv; v++) {
      int close = v % 50 == 7;
      double s = close ? 0.05 : 1;
      for (int a = 0; a < 3; a++) vtx[3 * v + a] = sessile_rng_range(&rng, -s, s) + (close ? 0 : 3 * (a == 0));
      if (close) near[k++] = v;
    }
    float part[4] = {0, 0, 0, 0};
    for (uint32_t feed = 1; feed <= SESSILE_SPONGE_PARTICLES_MAX_FEED; feed += 5) {
      uint32_t bh[SESSILE_SPONGE_PARTICLES_MAX_FEED], bc[1];
      uint64_t hits = 0;
      char what[120];
      snprintf(what, sizeof what, "feed %u of 40 touching vertices: differing from brute force", feed);
      t_check(what, compare(col, vtx, nv, part, 1, 0.1f, feed, &hits, bh, bc), 0);
      int ok = bc[0] == 40;
      for (uint32_t j = 0; j < feed; j++) ok = ok && bh[j] == near[j];
      t_true("... count 40 and the feed smallest indices, ascending", ok);
    }
    free(vtx);
  }

  /* Empty cells: two clumps 10 cm apart, particles in the gap and beyond. */
  {
    uint32_t nv = 400, np = 3000;
    double *vtx = t_dalloc((size_t)nv * 3);
    float *part = t_xalloc((size_t)np * 16);
    uint64_t rng = sessile_rng_stream(6, 3);
    for (uint32_t v = 0; v < nv; v++)
      for (int a = 0; a < 3; a++) vtx[3 * v + a] = sessile_rng_range(&rng, 0, 0.5) + (a == 0 && v % 2 ? 10 : 0);
    for (uint32_t i = 0; i < np; i++)
      for (int a = 0; a < 3; a++) part[4 * i + a] = (float)sessile_rng_range(&rng, a == 0 ? -1 : -0.2, a == 0 ? 12 : 0.7);
    uint32_t *bh = t_xalloc((size_t)np * 8), *bc = t_xalloc((size_t)np * 4);
    uint64_t hits = 0;
    t_check("two clumps, the gap's cells empty: differing", compare(col, vtx, nv, part, np, 0.1f, 2, &hits, bh, bc), 0);
    uint32_t gap = 0;
    for (uint32_t i = 0; i < np; i++) gap += part[4 * i] > 1 && part[4 * i] < 9 && bc[i] != 0;
    t_true("... particles in the gap touch nothing, the clumps are touched", gap == 0 && hits > 0);
    free(vtx), free(part), free(bh), free(bc);
  }

  /* No vertices at all. */
  {
    float part[8] = {0, 0, 0, 0, 1, 1, 1, 0};
    uint32_t bh[2], bc[2];
    uint64_t hits = 1;
    t_check("an empty surface: differing", compare(col, NULL, 0, part, 2, 0.5f, 1, &hits, bh, bc), 0);
    t_true("... no hits", hits == 0 && bh[0] == SESSILE_SPONGE_PARTICLES_NO_HIT);
  }

  sessile_sponge_particles_gpu_destroy(col);
  return t_finish(gpu);
}
