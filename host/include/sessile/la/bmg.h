/* sessile — block geometric multigrid for 4x4 block systems on a structured
 * box (the Navier-Stokes Newton Jacobian: ux, uy, uz, p per node).
 *
 * The unknowns live on the nodes of an n0 x n1 x n2 box (node i + n0 (j +
 * n1 k)) cut into Kuhn tets (6 per cube around the (1,1,1) diagonal,
 * sessile_box_tet); the matrix couples nodes that share a tet.  Level l+1
 * takes every other node of level l (n_{l+1} = (n_l - 1)/2 + 1 per axis),
 * and the fine Kuhn tets refine the coarse ones, so
 *  - P is P1 interpolation: a fine node is its coarse node, or the mean of
 *    the two ends of the coarse edge it halves; R = P^T;
 *  - coarse operators are Galerkin products A_{l+1} = R A_l P, computed on
 *    the host (same 15-point block pattern on every level), or the
 *    caller's (sessile_bmg_set_operator: a rediscretisation);
 *  - a row of A equal to a unit row (e_i: the fluid's Dirichlet rows) marks
 *    unknown i as fixed: P carries no correction to it, and a coarse node
 *    inherits its fine node's fixed unknowns (injection) as unit rows;
 *  - smoother: 8-colour block Gauss-Seidel (colour = parity of i, j, k:
 *    nodes of one colour share no tet) or damped block Jacobi, with the
 *    inverse 4x4 diagonal blocks; the coarsest level is solved with a dense
 *    inverse (up to coarse_dense_max nodes) or by sweeps.
 * Every pass over a level runs on the device (shaders/la/bmg_*.comp), per
 * row chunk of the level's matrix, so matrices over maxStorageBufferRange
 * work.  One V-cycle is a fixed linear operator: the right preconditioner
 * of GMRES as la's pc "mg" (sessile_pc_mg_set_block, sessile/la/pc.h).
 * Decisions and measurements: docs/la.md, "Block multigrid". */
#ifndef SESSILE_BMG_H
#define SESSILE_BMG_H

#include <stdint.h>
#include "sessile/la/la.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sessile_bmg sessile_bmg;

typedef enum { SESSILE_BMG_GAUSS_SEIDEL = 0, SESSILE_BMG_JACOBI = 1 } sessile_bmg_smoother;

typedef struct sessile_bmg_options {
  sessile_bmg_smoother smoother; /* default Gauss-Seidel (8 colours) */
  int pre, post;                 /* sweeps before and after the coarse correction (default 2, 2) */
  int cycle;                     /* coarse corrections per level: 1 V-cycle, 2 W-cycle (default 2),
                                    3 one on the finest level and two below (V at the top, W under) */
  double omega;                  /* damping (default 0.9 for Gauss-Seidel; ~0.6 for Jacobi) */
  int max_levels;                /* at most this many levels (default 16; 2 = two-grid) */
  uint32_t coarse_dense_max;     /* the coarsest level is inverted densely when it has at
                                    most this many nodes (default 160) ... */
  int coarse_sweeps;             /* ... else this many sweeps (default 20) */
  uint32_t wg_max_nodes;         /* Gauss-Seidel on a level of at most this many nodes (in one
                                    row chunk) runs all its sweeps in one workgroup, one dispatch
                                    (default 1024; 0: never); the same bits either way */
  int precision;                 /* 64 (default): the cycle in the context's precision; 32: in an
                                    fp64 context the whole cycle (every level's matrix values,
                                    inverse diagonal blocks, coarsest inverse, vectors) in fp32,
                                    cast from and to the fp64 r and z; in an fp32 context the same
                                    as 64 (docs/la.md, "Block multigrid", "The cycle in fp32") */
} sessile_bmg_options;

void sessile_bmg_options_default(sessile_bmg_options *o);

/* A hierarchy for the n[0] x n[1] x n[2] box: levels while every axis
 * halves (n - 1 even, n >= 3) and the level is above coarse_dense_max nodes.
 * SESSILE_ERR_USAGE for a bad grid or options. */
sessile_status sessile_bmg_create(sessile_la *la, const uint32_t n[3], const sessile_bmg_options *o,
                                  sessile_bmg **out);
void sessile_bmg_destroy(sessile_bmg *mg); /* NULL is fine */
int sessile_bmg_levels(const sessile_bmg *mg);
uint32_t sessile_bmg_level_nodes(const sessile_bmg *mg, int l);

/* Level l's operator (1 <= l < levels) given by the caller instead of the
 * Galerkin product: a rediscretisation on the coarse box (copied at the next
 * setup; its unit rows are that level's fixed unknowns).  NULL: Galerkin
 * again.  The fluid rediscretises (docs/fluid.md, "Multigrid"). */
sessile_status sessile_bmg_set_operator(sessile_bmg *mg, int l, const sessile_bcsr4 *a);

/* The operators of every level for the block matrix a (the box's nodes):
 * the fixed unknowns (unit rows), the Galerkin products, the inverse
 * diagonal blocks, the coarsest inverse, uploaded.  The fixed-unknown masks
 * and what depends on them are rebuilt only when they changed (reported by
 * sessile_bmg_rebuilds).  a must stay alive while the V-cycle is applied
 * (level 0 is a itself; precision 32 in an fp64 context: an fp32 copy of a's
 * values, made here, so a setup must follow every change of a's values).
 * SESSILE_ERR_NUMERIC for a singular diagonal block. */
sessile_status sessile_bmg_setup(sessile_bmg *mg, const sessile_mat *a);
unsigned sessile_bmg_rebuilds(const sessile_bmg *mg);

/* z = one V-cycle applied to r (set up; distinct vectors of 4 nodes reals); waits. */
sessile_status sessile_bmg_vcycle(sessile_bmg *mg, const sessile_vec *r, sessile_vec *z);

/* The same V-cycle in plain C and double (the reference the device is tested
 * against; for precision 32 within fp32 rounding: docs/la.md). */
sessile_status sessile_ref_bmg_vcycle(const sessile_bmg *mg, const double *r, double *z);

#ifdef __cplusplus
}
#endif
#endif
