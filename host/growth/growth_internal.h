/* Internal definitions of host/growth (not public API). */
#ifndef SESSILE_GROWTH_INTERNAL_H
#define SESSILE_GROWTH_INTERNAL_H

#include "sessile/growth/growth_gpu.h"
#include "sessile/growth/growth_ref.h"

/* The kernels (growth_kernel_id, sessile_growth_kernels[]), growth_push,
 * the parameter slots P_* and GROWTH_LOCAL: generated from
 * shaders/growth/kernels.def. */
#include "growth_kernels.h"

struct sessile_growth_gpu {
  sessile_la *la;
  sessile_gpu *gpu;
  uint32_t real_bytes;
  sessile_kernel *k[GK_COUNT];
  sessile_cmd *cmd;
  sessile_buffer *params; /* P_COUNT reals, mapped */
  sessile_buffer *status; /* classify overflow flag, mapped */
  /* surface */
  uint32_t nv, nf;
  sessile_buffer *pos, *tri, *vf_off, *vf, *nbr_off, *nbr;
  sessile_buffer *nrm, *probed, *ctr[2], *new_pos, *len, *dir;
  /* the vertex adjacency on the host too, for the sequential translocation */
  uint32_t *host_nbr_off, *host_nbr;
  /* classify bins per line axis (grown as needed), and the placeholder
   * bound as the fraction buffer when only the mask is wanted */
  sessile_buffer *col_off[3], *col_tri[3], *theta_dummy;
  double classify_seconds;
};

/* growth_gpu.c */
void growth_set_params(sessile_growth_gpu *g, const sessile_box *box, const sessile_growth_params *p);
growth_push growth_push_of(const sessile_growth_gpu *g, const sessile_box *box);
/* *b holds at least bytes (sessile_buffer_reserve; contents not kept). */
sessile_status growth_ensure(sessile_growth_gpu *g, sessile_buffer **b, size_t bytes);
uint32_t growth_groups(uint32_t items);
sessile_status growth_record_normals(sessile_growth_gpu *g, const sessile_box *box);

#endif
