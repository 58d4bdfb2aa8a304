/* A jittered lattice of cells with 6-neighbour CSR adjacency, for the
 * morphogen tests (symmetric by construction). */
#ifndef SDS_MORPH_LATTICE_H
#define SDS_MORPH_LATTICE_H
#include <stdint.h>
#include <stdlib.h>
#include "sessile/rng.h"
#include "sessile/sds/sds_process.h"

typedef struct lattice {
  sessile_morph_cells cells;
  double *pos, *radius;
  uint32_t *off, *nbr;
} lattice;

/* nx*ny*nz cells at spacing h, positions jittered by +-jit*h, radii
 * 0.5 h (1 +- rjit) (seeded). */
static inline lattice lattice_make(int nx, int ny, int nz, double h, double jit, double rjit, uint64_t seed) {
  lattice L = {0};
  int n = nx * ny * nz;
  L.pos = calloc(3 * (size_t)n, sizeof(double));
  L.radius = calloc((size_t)n, sizeof(double));
  L.off = calloc((size_t)n + 1, sizeof(uint32_t));
  L.nbr = calloc(6 * (size_t)n, sizeof(uint32_t));
  if (!L.pos || !L.radius || !L.off || !L.nbr) abort();
  uint64_t s = sessile_rng_stream(seed, 1);
  uint32_t e = 0;
  for (int k = 0; k < nz; k++)
    for (int j = 0; j < ny; j++)
      for (int i = 0; i < nx; i++) {
        int c = i + nx * (j + ny * k);
        L.pos[3 * c] = h * (i + sessile_rng_range(&s, -jit, jit));
        L.pos[3 * c + 1] = h * (j + sessile_rng_range(&s, -jit, jit));
        L.pos[3 * c + 2] = h * (k + sessile_rng_range(&s, -jit, jit));
        L.radius[c] = 0.5 * h * (1 + sessile_rng_range(&s, -rjit, rjit));
        L.off[c] = e;
        int d[6][3] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
        for (int q = 0; q < 6; q++) {
          int a = i + d[q][0], b = j + d[q][1], cc = k + d[q][2];
          if (a < 0 || b < 0 || cc < 0 || a >= nx || b >= ny || cc >= nz) continue;
          L.nbr[e++] = (uint32_t)(a + nx * (b + ny * cc));
        }
      }
  L.off[n] = e;
  L.cells = (sessile_morph_cells){n, L.pos, L.radius, L.off, L.nbr, NULL};
  return L;
}

static inline void lattice_free(lattice *L) {
  free(L->pos), free(L->radius), free(L->off), free(L->nbr);
}
#endif
