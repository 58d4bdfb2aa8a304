/* The particle sponge's state, shared by its files in host/sponge/. */
#ifndef SESSILE_SPONGE_PARTICLES_INTERNAL_H
#define SESSILE_SPONGE_PARTICLES_INTERNAL_H
#include "sessile/sponge/particles.h"

struct sessile_sponge_particles {
  sessile_sponge_particles_params p;
  sessile_surface surf;
  uint32_t *counts;     /* nv: times each vertex was fed */
  double *ppos;         /* 3 np: live particles' centres */
  uint32_t *age;        /* np: iterations each has lived */
  uint32_t np, cap;
  uint64_t rng;         /* the spawn stream's state */
  int iteration;        /* iterations done */
  sessile_sponge_particles_gpu *col; /* NULL: the host grid */
};

sessile_status particles_reserve_particles(sessile_sponge_particles *ps, uint32_t n);
/* Remeshes (the paper's split and collapse thresholds, guarded) and carries
 * the counts over to the new vertices (particles_remesh.c).  A remesh whose
 * result intersects itself is dropped (*refused = 1): the surface stays as
 * the guarded motion left it. */
sessile_status particles_remesh(sessile_sponge_particles *ps, uint32_t *refused);
#endif
