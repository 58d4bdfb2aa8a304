/* Internal definitions of host/growth (not public API). */
#ifndef SESSILE_GROWTH_INTERNAL_H
#define SESSILE_GROWTH_INTERNAL_H

#include "sessile/growth_gpu.h"
#include "sessile/growth_ref.h"

/* Real parameter slots, shared with shaders/growth/growth_common.glsl. */
enum {
  P_OX = 0, P_OY, P_OZ, P_H, P_MX, P_MY, P_MZ, P_OFFSET, P_TGIVE, P_NTHR, P_GTHR, P_GR,
  P_LMAX, P_N, P_K, P_MAXG, P_R, P_COUNT
};

/* Push constants of every growth kernel (growth_common.glsl). */
typedef struct {
  uint32_t nv, nf, n0, n1, n2, samples, halichondrid, seed_lo, seed_hi, iteration, ncols, pad;
} growth_push;

/* The kernel table (X-macro): id, embedded name, buffers. */
#define SESSILE_GROWTH_KERNELS(X)          \
  X(GK_CLASSIFY, "growth/classify", 7)     \
  X(GK_NORMALS, "growth/normals", 6)       \
  X(GK_PROBE, "growth/probe", 5)           \
  X(GK_TRANSLOCATE, "growth/translocate", 5) \
  X(GK_GROW, "growth/grow", 7)

typedef enum {
#define X(id, name, nb) id,
  SESSILE_GROWTH_KERNELS(X)
#undef X
  GK_COUNT
} growth_kernel_id;

enum { GROWTH_LOCAL = 64 };

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
  /* classify bins (grown as needed) */
  sessile_buffer *col_off, *col_tri;
  size_t col_off_bytes, col_tri_bytes;
  double classify_seconds;
};

/* growth_gpu.c */
void growth_set_params(sessile_growth_gpu *g, const sessile_box *box, const sessile_growth_params *p);
growth_push growth_push_of(const sessile_growth_gpu *g, const sessile_box *box);
/* (Re)creates *b when it is missing or smaller than bytes; *have tracks its size. */
sessile_status growth_ensure(sessile_growth_gpu *g, sessile_buffer **b, size_t *have, size_t bytes);
uint32_t growth_groups(uint32_t items);
sessile_status growth_record_normals(sessile_growth_gpu *g, const sessile_box *box);

#endif
