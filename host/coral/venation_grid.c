/* The nearest vein node of every auxin (sessile/coral/venation.h): the uniform grid
 * of nodes and the two plain-C references the kernel is tested against.  The
 * grid search is shaders/coral/nearest.comp operation by operation. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "venation_internal.h"

/* Stop once best < lb^2 (1 - tol): an unvisited node's computed squared
 * distance is at least lb^2 up to rounding, far less than tol. */
#define GRID_TOL 1e-9

static uint64_t cells_for(const double e[3], double h, uint32_t d[3]) {
  uint64_t c = 1;
  for (int a = 0; a < 3; a++) {
    double k = ceil(e[a] / h);
    d[a] = k < 1 ? 1 : k > 4096 ? 4096 : (uint32_t)k;
    c *= d[a];
  }
  return c;
}

sessile_status sessile_venation_grid_build(const double *nodes, uint32_t n, sessile_venation_grid *g) {
  memset(g, 0, sizeof *g);
  SESSILE_CHECK(n > 0, SESSILE_ERR_INTERNAL, "a vein grid needs at least one node");
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (uint32_t i = 0; i < n; i++)
    for (int a = 0; a < 3; a++) {
      double x = nodes[3 * i + a];
      lo[a] = x < lo[a] ? x : lo[a], hi[a] = x > hi[a] ? x : hi[a];
    }
  double e[3], emax = 0;
  for (int a = 0; a < 3; a++) e[a] = hi[a] - lo[a], emax = e[a] > emax ? e[a] : emax;
  /* about two nodes per cell: shrink the cell until there are n/2 cells
   * (a flat blade keeps one cell across its thickness) */
  double h = emax > 0 ? emax : 1;
  uint64_t target = n / 2 > 0 ? n / 2 : 1;
  uint32_t d[3];
  for (int k = 0; k < 200 && cells_for(e, h, d) < target; k++) h *= 0.9;
  /* a cell a little larger than needed so that hi falls inside the last one */
  h *= 1.0000001;
  cells_for(e, h, d);
  uint64_t nc = (uint64_t)d[0] * d[1] * d[2];
  g->cell_off = calloc(nc + 1, sizeof *g->cell_off);
  g->cell_node = malloc((size_t)n * sizeof *g->cell_node);
  uint32_t *cell = malloc((size_t)n * sizeof *cell);
  if (!g->cell_off || !g->cell_node || !cell) {
    free(cell);
    sessile_venation_grid_free(g);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for a vein grid of %llu cells",
                             (unsigned long long)nc);
  }
  memcpy(g->lo, lo, sizeof lo);
  memcpy(g->dims, d, sizeof d);
  g->h = h, g->ncells = (uint32_t)nc, g->n = n;
  for (uint32_t i = 0; i < n; i++) {
    uint32_t c[3];
    for (int a = 0; a < 3; a++) {
      double x = (nodes[3 * i + a] - lo[a]) / h;
      c[a] = x <= 0 ? 0 : x >= d[a] - 1 ? d[a] - 1 : (uint32_t)x;
    }
    cell[i] = c[0] + d[0] * (c[1] + d[1] * c[2]);
    g->cell_off[cell[i] + 1]++;
  }
  for (uint64_t c = 0; c < nc; c++) g->cell_off[c + 1] += g->cell_off[c];
  /* in ascending node order within each cell: ties resolve like brute force */
  uint32_t *fill = malloc(nc * sizeof *fill);
  if (!fill) {
    free(cell);
    sessile_venation_grid_free(g);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for a vein grid");
  }
  memcpy(fill, g->cell_off, nc * sizeof *fill);
  for (uint32_t i = 0; i < n; i++) g->cell_node[fill[cell[i]]++] = i;
  free(fill);
  free(cell);
  return SESSILE_OK;
}

void sessile_venation_grid_free(sessile_venation_grid *g) {
  if (!g) return;
  free(g->cell_off);
  free(g->cell_node);
  memset(g, 0, sizeof *g);
}

static inline double dist2(const double *a, const double *b) {
  double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  return dx * dx + dy * dy + dz * dz;
}

void sessile_venation_nearest_ref(const double *nodes, uint32_t n, const double *pts, uint32_t m,
                                  uint32_t *idx, double *d2) {
  for (uint32_t i = 0; i < m; i++) {
    double best = INFINITY;
    uint32_t bi = SESSILE_VENATION_NONE;
    for (uint32_t j = 0; j < n; j++) {
      double d = dist2(pts + 3 * i, nodes + 3 * j);
      if (d < best) best = d, bi = j;
    }
    if (idx) idx[i] = bi;
    if (d2) d2[i] = best;
  }
}

static void grid_one(const sessile_venation_grid *g, const double *nodes, const double *p, uint32_t *idx,
                     double *d2) {
  int c[3], d[3];
  for (int a = 0; a < 3; a++) {
    double x = (p[a] - g->lo[a]) / g->h;
    d[a] = (int)g->dims[a];
    c[a] = x <= 0 ? 0 : x >= d[a] - 1 ? d[a] - 1 : (int)x;
  }
  double best = INFINITY;
  uint32_t bi = SESSILE_VENATION_NONE;
  for (int r = 0;; r++) {
    for (int z = c[2] - r; z <= c[2] + r; z++) {
      if (z < 0 || z >= d[2]) continue;
      for (int y = c[1] - r; y <= c[1] + r; y++) {
        if (y < 0 || y >= d[1]) continue;
        /* on the shell only: the two x ends unless y or z is on it */
        int full = abs(z - c[2]) == r || abs(y - c[1]) == r;
        int step = full || r == 0 ? 1 : 2 * r;
        for (int x = c[0] - r; x <= c[0] + r; x += step) {
          if (x < 0 || x >= d[0]) continue;
          uint32_t cell = (uint32_t)x + g->dims[0] * ((uint32_t)y + g->dims[1] * (uint32_t)z);
          for (uint32_t e = g->cell_off[cell]; e < g->cell_off[cell + 1]; e++) {
            uint32_t j = g->cell_node[e];
            double dd = dist2(p, nodes + 3 * j);
            if (dd < best || (dd == best && j < bi)) best = dd, bi = j;
          }
        }
      }
    }
    /* the nearest face of the visited box that has cells beyond it */
    double lb = INFINITY;
    for (int a = 0; a < 3; a++) {
      if (c[a] - r > 0) {
        double f = p[a] - (g->lo[a] + (c[a] - r) * g->h);
        lb = f < lb ? f : lb;
      }
      if (c[a] + r + 1 < d[a]) {
        double f = g->lo[a] + (c[a] + r + 1) * g->h - p[a];
        lb = f < lb ? f : lb;
      }
    }
    if (lb == INFINITY) break;
    if (bi != SESSILE_VENATION_NONE && best < lb * lb * (1 - GRID_TOL)) break;
  }
  *idx = bi, *d2 = best;
}

void sessile_venation_nearest_grid(const sessile_venation_grid *g, const double *nodes, const double *pts,
                                   uint32_t m, uint32_t *idx, double *d2) {
#pragma omp parallel for schedule(static) if (m > 4096)
  for (uint32_t i = 0; i < m; i++) {
    uint32_t bi;
    double b;
    grid_one(g, nodes, pts + 3 * i, &bi, &b);
    if (idx) idx[i] = bi;
    if (d2) d2[i] = b;
  }
}

sessile_status venation_grid_within(const sessile_venation_grid *g, const double *nodes, const double *q,
                                    double r, uint32_t **list, uint32_t *n, uint32_t *cap) {
  *n = 0;
  int c0[3], c1[3];
  for (int a = 0; a < 3; a++) {
    double x0 = floor((q[a] - r - g->lo[a]) / g->h), x1 = floor((q[a] + r - g->lo[a]) / g->h);
    int top = (int)g->dims[a] - 1;
    c0[a] = x0 < 0 ? 0 : x0 > top ? top + 1 : (int)x0;
    c1[a] = x1 < 0 ? -1 : x1 > top ? top : (int)x1;
  }
  double r2 = r * r;
  for (int z = c0[2]; z <= c1[2]; z++)
    for (int y = c0[1]; y <= c1[1]; y++)
      for (int x = c0[0]; x <= c1[0]; x++) {
        uint32_t cell = (uint32_t)x + g->dims[0] * ((uint32_t)y + g->dims[1] * (uint32_t)z);
        for (uint32_t e = g->cell_off[cell]; e < g->cell_off[cell + 1]; e++) {
          uint32_t j = g->cell_node[e];
          if (dist2(q, nodes + 3 * j) > r2) continue;
          if (*n == *cap) {
            uint32_t nc = *cap ? 2 * *cap : 64;
            uint32_t *l = realloc(*list, (size_t)nc * sizeof *l);
            SESSILE_CHECK(l, SESSILE_ERR_NO_MEMORY, "out of host memory");
            *list = l, *cap = nc;
          }
          (*list)[(*n)++] = j;
        }
      }
  return SESSILE_OK;
}
