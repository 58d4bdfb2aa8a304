/* sessile — preconditioners as objects: z = M⁻¹ r for la's Krylov solvers.
 *
 * A pc is created by name from a small registry (like PETSc's -pc_type),
 * set up from a matrix, and then applied by the solvers inside their own
 * recorded command buffers (one recording per block of iterations, no host
 * round trip per application) or alone with sessile_pc_apply.  Registered:
 *   "none"          M = I
 *   "jacobi"        M = diag(A)
 *   "block_jacobi"  M = the 4x4 diagonal blocks of a BCSR4 matrix (on a
 *                   CSR or matrix-free stencil matrix the blocks are 1x1:
 *                   the same as jacobi)
 *   "ilu0"          ILU(0) of a CSR or BCSR4 matrix (nonsymmetric: not for CG)
 *   "mg"            one V-cycle of a sessile_mg hierarchy (sessile/la/mg.h),
 *                   given with sessile_pc_mg_set before the setup, or of a
 *                   block hierarchy for 4x4 block matrices on a Kuhn box
 *                   (sessile/la/bmg.h), given with sessile_pc_mg_set_block
 * How to add one: docs/la.md ("Preconditioners").
 *
 * Ownership: the caller owns the pc and destroys it before the la.  A pc
 * set up from a matrix may read that matrix (ilu0 reads the factors cached
 * in it): keep the matrix alive while the pc is applied. */
#ifndef SESSILE_PC_H
#define SESSILE_PC_H

#include "sessile/la/la.h"
#include "sessile/la/bmg.h"
#include "sessile/la/mg.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sessile_pc sessile_pc;

/* A pc of a registered type, not yet set up.  An unknown name is
 * SESSILE_ERR_USAGE with a message listing the registered ones. */
sessile_status sessile_pc_create(sessile_la *la, const char *type, sessile_pc **out);
sessile_status sessile_pc_create_type(sessile_la *la, sessile_pc_type type, sessile_pc **out);
/* The type registered under `name` (SESSILE_ERR_USAGE, listing the names, when none is). */
sessile_status sessile_pc_type_from_name(const char *name, sessile_pc_type *out);
/* The i-th registered name (i = 0, 1, ...); NULL past the last. */
const char *sessile_pc_registered(int i);

/* Builds what applying M⁻¹ for matrix a needs (inverse diagonal, inverse
 * blocks, factors...).  A pc may be set up again for another matrix; on
 * failure it is left not set up. */
sessile_status sessile_pc_setup(sessile_pc *pc, const sessile_mat *a);
/* y = M⁻¹ x on the device (x and y distinct, the set-up matrix's rows); waits. */
sessile_status sessile_pc_apply(sessile_pc *pc, const sessile_vec *x, sessile_vec *y);
void sessile_pc_destroy(sessile_pc *pc); /* NULL is fine */

const char *sessile_pc_name(const sessile_pc *pc);
sessile_pc_type sessile_pc_get_type(const sessile_pc *pc);
/* 1 when M is symmetric for a symmetric A (CG accepts only those). */
int sessile_pc_symmetric(const sessile_pc *pc);

/* "mg": the hierarchy whose V-cycle is M⁻¹ (not owned; keep it alive while
 * the pc exists).  The setup then checks that the matrix has the finest
 * level's rows.  SESSILE_ERR_USAGE on a pc of another type. */
sessile_status sessile_pc_mg_set(sessile_pc *pc, sessile_mg *mg);
/* "mg" on a block matrix: the block hierarchy whose V-cycle is M⁻¹ (not
 * owned); the pc's setup builds its operators from the matrix
 * (sessile_bmg_setup).  Given before the setup; replaces a scalar hierarchy.
 * The pc is then nonsymmetric (GMRES, BiCGSTAB). */
sessile_status sessile_pc_mg_set_block(sessile_pc *pc, sessile_bmg *mg);

/* sessile_ksp_solve with a set-up pc object instead of the options' pc
 * enum (pc NULL: the enum's, built and set up for a here).  CG refuses a
 * nonsymmetric pc with SESSILE_ERR_USAGE. */
sessile_status sessile_ksp_solve_pc(sessile_la *la, const sessile_ksp_options *opt,
                                    const sessile_mat *a, sessile_pc *pc, const sessile_vec *b,
                                    sessile_vec *x, sessile_solve_result *res);

#ifdef __cplusplus
}
#endif
#endif
