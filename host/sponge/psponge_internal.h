/* The particle sponge's state, shared by its files in host/sponge/. */
#ifndef SESSILE_PSPONGE_INTERNAL_H
#define SESSILE_PSPONGE_INTERNAL_H
#include "sessile/particle_sponge.h"

struct sessile_psponge {
  sessile_psponge_params p;
  sessile_surface surf;
  uint32_t *counts;     /* nv: times each vertex was fed */
  double *ppos;         /* 3 np: live particles' centres */
  uint32_t *age;        /* np: iterations each has lived */
  uint32_t np, cap;
  uint64_t rng;         /* the spawn stream's state */
  int iteration;        /* iterations done */
  sessile_psponge_gpu *col; /* NULL: the host grid */
};

sessile_status psponge_reserve_particles(sessile_psponge *ps, uint32_t n);
/* Remeshes (the paper's split and collapse thresholds, guarded) and carries
 * the counts over to the new vertices (psponge_remesh.c).  A remesh whose
 * result intersects itself is dropped (*refused = 1): the surface stays as
 * the guarded motion left it. */
sessile_status psponge_remesh(sessile_psponge *ps, uint32_t *refused);
#endif
