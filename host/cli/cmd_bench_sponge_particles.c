/* `sessile bench sponge particles`: one particle-sponge collision pass, 100 k
 * particles against a sponge-sized surface, on the device (the kernel, and
 * the whole call with its transfers), by the host grid (the kernel's plain-C
 * twin, OpenMP) and by brute force (measured on a sample of particles and
 * scaled: the full pass would take minutes), with the hits compared. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "cli.h"
#include "sessile/sponge/particles.h"
#include "sessile/rng.h"

sessile_status bench_sponge_particles(sessile_gpu *g, const bench_section_opts *o, FILE *out) {
  /* a bumpy sphere of radius 2 cm, icosphere level 7 (40962 vertices; level
   * 5 quick), and particles of radius 0.05 cm in its bounding box, half of
   * them near the surface so that the pass does real work */
  int level = o->quick ? 5 : 7;
  uint32_t np = o->quick ? 10000 : 100000, feed = 4, sample = o->quick ? 500 : 2000;
  float radius = o->quick ? 0.1f : 0.05f;
  sessile_surface s = {0};
  const double c[3] = {0, 0, 0};
  SESSILE_CALL(sessile_surface_icosphere(level, 2.0, c, &s));
  uint64_t rng = sessile_rng_stream(7, 1);
  for (uint32_t v = 0; v < s.nv; v++) {
    double k = 1 + 0.1 * sessile_rng_range(&rng, -1, 1);
    for (int a = 0; a < 3; a++) s.pos[3 * v + a] *= k;
  }
  float *part = malloc((size_t)np * 16);
  uint32_t *hg = malloc((size_t)np * feed * 4), *cg = malloc((size_t)np * 4);
  uint32_t *hh = malloc((size_t)np * feed * 4), *ch = malloc((size_t)np * 4);
  uint32_t *hb = malloc((size_t)sample * feed * 4), *cb = malloc((size_t)sample * 4);
  sessile_sponge_particles_grid grid = {0};
  sessile_sponge_particles_gpu *col = NULL;
  sessile_status st = part && hg && cg && hh && ch && hb && cb
                          ? SESSILE_OK
                          : sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for the bench");
  if (st == SESSILE_OK) {
    for (uint32_t i = 0; i < np; i++) {
      if (i % 2 == 0) { /* near a random vertex */
        uint32_t v = (uint32_t)(sessile_rng_next(&rng) % s.nv);
        for (int a = 0; a < 3; a++)
          part[4 * i + a] = (float)(s.pos[3 * v + a] + sessile_rng_range(&rng, -2.0, 2.0) * radius);
      } else {
        for (int a = 0; a < 3; a++) part[4 * i + a] = (float)sessile_rng_range(&rng, -2.2, 2.2);
      }
      part[4 * i + 3] = 0;
    }
    double t0 = sessile_wall_seconds();
    st = sessile_sponge_particles_grid_build(s.pos, s.nv, radius, &grid);
    double tgrid = sessile_wall_seconds() - t0;
    if (st == SESSILE_OK) st = sessile_sponge_particles_gpu_create(g, &col);
    double kns = 0, tcall = 0, thost = 0, tbrute = 0;
    if (st == SESSILE_OK) /* warm-up: pipeline and buffers */
      st = sessile_sponge_particles_gpu_collide(col, &grid, part, np, radius, feed, hg, cg, &kns);
    if (st == SESSILE_OK) {
      t0 = sessile_wall_seconds();
      st = sessile_sponge_particles_gpu_collide(col, &grid, part, np, radius, feed, hg, cg, &kns);
      tcall = sessile_wall_seconds() - t0;
    }
    if (st == SESSILE_OK) {
      t0 = sessile_wall_seconds();
      st = sessile_sponge_particles_collide_grid(&grid, part, np, radius, feed, hh, ch);
      thost = sessile_wall_seconds() - t0;
    }
    if (st == SESSILE_OK) {
      t0 = sessile_wall_seconds();
      st = sessile_sponge_particles_collide_brute(part, sample, grid.pos4, grid.nv, radius, feed, hb, cb);
      tbrute = (sessile_wall_seconds() - t0) * ((double)np / sample);
    }
    if (st == SESSILE_OK) {
      uint64_t hits = 0, diff = 0;
      for (uint32_t i = 0; i < np; i++) {
        hits += cg[i];
        int d = cg[i] != ch[i] || memcmp(hg + (size_t)feed * i, hh + (size_t)feed * i, feed * 4);
        if (i < sample) d |= cb[i] != cg[i] || memcmp(hb + (size_t)feed * i, hg + (size_t)feed * i, feed * 4);
        if (d && diff < 3)
          fprintf(out, "  particle %u (%.9g %.9g %.9g) differs: GPU %u hits (first %u), host grid %u (first %u)\n", i,
                  (double)part[4 * i], (double)part[4 * i + 1], (double)part[4 * i + 2], cg[i], hg[(size_t)feed * i],
                  ch[i], hh[(size_t)feed * i]);
        diff += d;
      }
      double kms = kns * 1e-6;
      fprintf(out, "particles: %u particles (radius %g cm) vs %u vertices, feed %u; grid %ux%ux%u (built %.1f ms)\n",
              np, (double)radius, s.nv, feed, grid.d[0], grid.d[1], grid.d[2], tgrid * 1e3);
      fprintf(out, "  hits: %llu in all; particles differing between GPU, host grid and brute force: %llu\n",
              (unsigned long long)hits, (unsigned long long)diff);
      fprintf(out, "  GPU kernel %.2f ms (call with transfers %.2f ms); host grid %.2f ms; brute force %.0f ms "
                   "(%u particles measured, scaled)\n",
              kms, tcall * 1e3, thost * 1e3, tbrute * 1e3, sample);
      fprintf(out, "  ratios: host grid / GPU kernel %.1fx, brute force / GPU kernel %.0fx, brute force / host grid %.0fx\n",
              thost * 1e3 / kms, tbrute * 1e3 / kms, tbrute / thost);
      if (diff) st = sessile_error_set(SESSILE_ERR_INTERNAL, "bench sponge particles: %llu particles' hits differ "
                                                             "between the GPU and the references: a bug",
                                       (unsigned long long)diff);
    }
  }
  sessile_sponge_particles_gpu_destroy(col);
  sessile_sponge_particles_grid_free(&grid);
  sessile_surface_free(&s);
  free(part), free(hg), free(cg), free(hh), free(ch), free(hb), free(cb);
  return st;
}
