/* Internal definitions of the block multigrid (host/la/bmg*.c, pc_bmg.c). */
#ifndef SESSILE_BMG_INTERNAL_H
#define SESSILE_BMG_INTERNAL_H

#include "la_internal.h"
#include "sessile/la/bmg.h"

#define BMG_MAX_LEVELS 16
#define BMG_NOFF 15 /* a node and its 14 Kuhn neighbours */

typedef struct {
  uint32_t n[3], nodes;
  int off[BMG_NOFF][3];    /* the Kuhn offsets, sorted by index displacement (row order) */
  sessile_bcsr4 a;         /* l >= 1: R A P (the Kuhn pattern, built at creation) */
  const sessile_bcsr4 *given; /* l >= 1: the caller's operator (copied into a at setup) or NULL */
  sessile_bcsr4 copy;      /* the copy of given */
  const sessile_bcsr4 *ah; /* the host operator: l = 0 the caller's, else &a */
  const sessile_mat *m;    /* the device operator: l = 0 the caller's (fp32 cycle: own), else own */
  sessile_mat *own;        /* fp32 cycle: values in fp32 (la_mat_create_bcsr4_f32), level 0 too */
  double *dinv;            /* 16 per node: inverse diagonal blocks */
  sessile_buffer **dinvb;  /* dinv per row chunk of m */
  uint32_t ndinv;
  uint8_t *fixed;          /* per node: bit a = unknown a is fixed (unit row) */
  sessile_buffer *mask;    /* uint per node: bit a = unknown a is free */
  sessile_vec *x, *b;      /* l >= 1: the correction and the restricted residual */
  sessile_vec *r;          /* the residual (and the Jacobi sweeps' other buffer) */
  sessile_buffer *x32, *b32, *r32; /* fp32 cycle: the same in fp32 (every level, l = 0 too) */
  vref vx, vb, vr;         /* what the cycle records: x, b, r or x32, b32, r32 */
} bmg_level;

struct sessile_bmg {
  sessile_la *la;
  sessile_bmg_options o;
  int nl;
  bmg_level lv[BMG_MAX_LEVELS];
  double *cinv;            /* dense coarsest inverse (4N x 4N, row-major) or NULL: sweeps */
  sessile_mat *cinvm;      /* the same as a full block matrix (f32: its negative, in fp32) */
  uint32_t rb;             /* bytes of the cycle's reals: la->real_bytes, or 4 (precision 32) */
  int f32;                 /* the cycle in fp32 inside an fp64 context: f32 kernels (k32), the
                              casts in and out, level 0's own fp32 copy of the matrix */
  sessile_kernel *k32[K_COUNT]; /* f32: the f32 variants, made on first use */
  sessile_buffer *stop32;  /* f32: the cycle's stop flag, the f32 kernels' `s` (bmg_to32.comp) */
  sessile_buffer *zero32;  /* f32: zeros of the coarsest level (its dense solve: x = 0 - (-C) b) */
  int ready;               /* set up */
  unsigned rebuilds;       /* times the fixed masks changed */
};

/* The Kuhn offsets of a grid, in row order (bmg.c). */
void bmg_offsets(const uint32_t n[3], int off[BMG_NOFF][3]);
/* Records out = V-cycle(r) into c (bmg_record.c); r and out vectors of the
 * finest level, distinct, in the context's precision: whole vectors, or (the
 * fp32 cycle, mg->f32, which casts them in and out) anywhere in a buffer. */
sessile_status bmg_rec_cycle(const sessile_bmg *mg, sessile_cmd *c, vref r, vref out, int guard);
/* Coarse corrections level l < nl - 1 takes (`cycle`; once when level l + 1 is
 * solved exactly or for cycle 3 on the finest level); the device and the reference share it. */
static inline int bmg_corrections(const sessile_bmg *mg, int l) {
  if ((l + 2 == mg->nl && mg->cinvm) || (l == 0 && mg->o.cycle == 3)) return 1;
  return mg->o.cycle == 1 ? 1 : 2;
}
/* Galerkin product of level l + 1 from level l, masks applied (bmg_setup.c). */
sessile_status bmg_galerkin(sessile_bmg *mg, int l);

#endif
