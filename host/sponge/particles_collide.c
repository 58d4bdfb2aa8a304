/* The particle sponge's collision search on the host: the uniform grid the
 * GPU kernel reads, and the two references (brute force; the same grid walk
 * as shaders/sponge/collide.comp).  The distance test is in float, in the
 * kernel's order (dx*dx + dy*dy, then + dz*dz), so every path returns the
 * same hits bit for bit (sessile/sponge/particles.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/sponge/particles.h"

#define CELL_MARGIN SESSILE_SPONGE_PARTICLES_CELL_MARGIN
/* Cells per axis at most: keeps (x - lo) / h below 4096, where float's error
 * is far below CELL_MARGIN. */
#define MAX_DIM 4096u

void sessile_sponge_particles_grid_free(sessile_sponge_particles_grid *g) {
  if (!g) return;
  free(g->pos4);
  free(g->cell_off);
  free(g->cell_vtx);
  memset(g, 0, sizeof *g);
}

sessile_status sessile_sponge_particles_grid_build(const double *pos, uint32_t nv, double radius,
                                          sessile_sponge_particles_grid *g) {
  memset(g, 0, sizeof *g);
  SESSILE_CHECK(radius > 0 && isfinite(radius), SESSILE_ERR_USAGE, "collision grid: radius %g must be > 0",
                radius);
  g->nv = nv;
  g->pos4 = malloc(((size_t)nv * 4 + 4) * sizeof *g->pos4);
  SESSILE_CHECK(g->pos4, SESSILE_ERR_NO_MEMORY, "out of host memory for %u grid vertices", nv);
  float lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  for (uint32_t v = 0; v < nv; v++)
    for (int a = 0; a < 3; a++) {
      float x = (float)pos[3 * (size_t)v + a];
      g->pos4[4 * (size_t)v + a] = x;
      if (!isfinite(x)) {
        sessile_sponge_particles_grid_free(g);
        return sessile_error_set(SESSILE_ERR_NUMERIC, "collision grid: vertex %u is not finite", v);
      }
      if (v == 0 || x < lo[a]) lo[a] = x;
      if (v == 0 || x > hi[a]) hi[a] = x;
    }
  for (uint32_t v = 0; v < nv; v++) g->pos4[4 * (size_t)v + 3] = 0;
  /* cells of side 2r: a ball meets at most two per axis; fewer and bigger
   * cells when that would make more than 8 nv + 64 cells */
  double h = 2 * radius;
  uint64_t cap = 8 * (uint64_t)nv + 64;
  for (;;) {
    uint64_t cells = 1;
    int ok = 1;
    for (int a = 0; a < 3; a++) {
      double d = floor(((double)hi[a] - lo[a]) / h) + 1;
      if (d > MAX_DIM) ok = 0;
      g->d[a] = (uint32_t)(d > MAX_DIM ? MAX_DIM : d);
      cells *= g->d[a];
    }
    if (ok && cells <= cap) break;
    h *= 1.25;
  }
  g->h = (float)h;
  g->inv_h = (float)(1.0 / h);
  memcpy(g->lo, lo, sizeof lo);
  size_t ncell = (size_t)g->d[0] * g->d[1] * g->d[2];
  g->cell_off = calloc(ncell + 1, sizeof *g->cell_off);
  g->cell_vtx = malloc(((size_t)nv + 1) * sizeof *g->cell_vtx);
  uint32_t *cell_of = malloc(((size_t)nv + 1) * sizeof *cell_of);
  if (!g->cell_off || !g->cell_vtx || !cell_of) {
    free(cell_of);
    sessile_sponge_particles_grid_free(g);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for a %zu-cell grid", ncell);
  }
  for (uint32_t v = 0; v < nv; v++) {
    uint32_t c[3];
    for (int a = 0; a < 3; a++) {
      double x = ((double)g->pos4[4 * (size_t)v + a] - lo[a]) * g->inv_h;
      c[a] = x <= 0 ? 0 : x >= g->d[a] - 1 ? g->d[a] - 1 : (uint32_t)x;
    }
    cell_of[v] = c[0] + g->d[0] * (c[1] + g->d[1] * c[2]);
    g->cell_off[cell_of[v] + 1]++;
  }
  for (size_t c = 0; c < ncell; c++) g->cell_off[c + 1] += g->cell_off[c];
  /* a counting sort by cell, stable: each cell's vertices ascend */
  uint32_t *fill = malloc((ncell + 1) * sizeof *fill);
  if (!fill) {
    free(cell_of);
    sessile_sponge_particles_grid_free(g);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for a %zu-cell grid", ncell);
  }
  memcpy(fill, g->cell_off, (ncell + 1) * sizeof *fill);
  for (uint32_t v = 0; v < nv; v++) g->cell_vtx[fill[cell_of[v]]++] = v;
  free(fill);
  free(cell_of);
  return SESSILE_OK;
}

/* The distance test every path shares. */
static inline int touches(const float *p, const float *x, float r2) {
  float dx = p[0] - x[0], dy = p[1] - x[1], dz = p[2] - x[2];
  float d2 = dx * dx + dy * dy;
  d2 = d2 + dz * dz;
  return d2 <= r2;
}

/* Keeps best[0..*kept) the smallest indices seen, ascending, at most feed. */
static inline void keep_smallest(uint32_t *best, uint32_t *kept, uint32_t feed, uint32_t v) {
  uint32_t k = *kept;
  if (k == feed) {
    if (v >= best[feed - 1]) return;
    k = feed - 1;
  } else {
    (*kept)++;
  }
  while (k > 0 && best[k - 1] > v) {
    best[k] = best[k - 1];
    k--;
  }
  best[k] = v;
}

static sessile_status check_feed(uint32_t feed, float radius) {
  SESSILE_CHECK(feed >= 1 && feed <= SESSILE_SPONGE_PARTICLES_MAX_FEED, SESSILE_ERR_USAGE,
                "collisions: feed %u must be in 1..%d", feed, SESSILE_SPONGE_PARTICLES_MAX_FEED);
  SESSILE_CHECK(radius > 0 && isfinite(radius), SESSILE_ERR_USAGE, "collisions: radius %g must be > 0",
                (double)radius);
  return SESSILE_OK;
}

sessile_status sessile_sponge_particles_collide_brute(const float *part4, uint32_t np, const float *vtx4,
                                             uint32_t nv, float radius, uint32_t feed,
                                             uint32_t *hit, uint32_t *count) {
  SESSILE_CALL(check_feed(feed, radius));
  float r2 = radius * radius;
#pragma omp parallel for schedule(static)
  for (int64_t i = 0; i < (int64_t)np; i++) {
    uint32_t kept = 0, n = 0, *best = hit + (size_t)feed * i;
    for (uint32_t v = 0; v < nv; v++)
      if (touches(part4 + 4 * i, vtx4 + 4 * (size_t)v, r2)) {
        if (kept < feed) best[kept++] = v;
        n++;
      }
    for (uint32_t k = kept; k < feed; k++) best[k] = SESSILE_SPONGE_PARTICLES_NO_HIT;
    count[i] = n;
  }
  return SESSILE_OK;
}

/* A particle's cell range on one axis, as the kernel computes it. */
static inline int cell_range(const sessile_sponge_particles_grid *g, int a, float p, float r, uint32_t *c0,
                             uint32_t *c1) {
  float x0 = (p - r - g->lo[a]) * g->inv_h - CELL_MARGIN;
  float x1 = (p + r - g->lo[a]) * g->inv_h + CELL_MARGIN;
  float top = (float)(g->d[a] - 1);
  /* the last cell spans [d - 1, d) in cell units */
  if (!(x1 >= 0) || !(x0 < (float)g->d[a])) return 0;
  *c0 = x0 <= 0 ? 0 : (uint32_t)x0;
  *c1 = x1 >= top ? g->d[a] - 1 : (uint32_t)x1;
  return 1;
}

sessile_status sessile_sponge_particles_collide_grid(const sessile_sponge_particles_grid *g, const float *part4,
                                            uint32_t np, float radius, uint32_t feed,
                                            uint32_t *hit, uint32_t *count) {
  SESSILE_CALL(check_feed(feed, radius));
  float r2 = radius * radius;
#pragma omp parallel for schedule(static)
  for (int64_t i = 0; i < (int64_t)np; i++) {
    const float *p = part4 + 4 * i;
    uint32_t kept = 0, n = 0, *best = hit + (size_t)feed * i, c0[3], c1[3];
    int in = g->nv > 0;
    for (int a = 0; a < 3 && in; a++) in = cell_range(g, a, p[a], radius, &c0[a], &c1[a]);
    if (in)
      for (uint32_t z = c0[2]; z <= c1[2]; z++)
        for (uint32_t y = c0[1]; y <= c1[1]; y++)
          for (uint32_t x = c0[0]; x <= c1[0]; x++) {
            uint32_t c = x + g->d[0] * (y + g->d[1] * z);
            for (uint32_t e = g->cell_off[c]; e < g->cell_off[c + 1]; e++) {
              uint32_t v = g->cell_vtx[e];
              if (touches(p, g->pos4 + 4 * (size_t)v, r2)) {
                keep_smallest(best, &kept, feed, v);
                n++;
              }
            }
          }
    for (uint32_t k = kept; k < feed; k++) best[k] = SESSILE_SPONGE_PARTICLES_NO_HIT;
    count[i] = n;
  }
  return SESSILE_OK;
}
