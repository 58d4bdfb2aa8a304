/* Internal side of the preconditioner objects (host/la/pc*.c): what one
 * implementation provides, and what the Krylov solvers read. */
#ifndef SESSILE_PC_INTERNAL_H
#define SESSILE_PC_INTERNAL_H

#include "la_internal.h"
#include "sessile/la/pc.h"

/* One preconditioner type.  setup is called on a pc with nothing built
 * (release ran before) and either builds everything or returns an error
 * after releasing what it built; rec records z = M⁻¹ r (r and z distinct)
 * into c with every dispatch guarded by `guard` (-1: none). */
typedef struct la_pc_ops {
  const char *name;
  sessile_pc_type type;
  int symmetric; /* M symmetric for a symmetric A: CG may use it */
  sessile_status (*setup)(sessile_pc *pc, const sessile_mat *a);
  sessile_status (*rec)(const sessile_pc *pc, sessile_cmd *c, vref r, vref z, int guard);
  void (*release)(sessile_pc *pc); /* frees what setup built (nothing built: no-op) */
} la_pc_ops;

struct sessile_pc {
  sessile_la *la;
  const la_pc_ops *ops;
  uint32_t n;              /* rows of the matrix it is set up for; 0: not set up */
  const sessile_vec *diag; /* diagonal pcs (none, jacobi): M⁻¹ = diag(diag), which the
                              solvers fuse into their own kernels; NULL otherwise */
  void *data;              /* what setup built, the implementation's */
  void *conf;              /* settings given before setup, kept across setups
                              (mg: the hierarchy, not owned) */
};

/* The implementations (one file each). */
extern const la_pc_ops la_pc_none_ops, la_pc_jacobi_ops; /* pc_jacobi.c */
extern const la_pc_ops la_pc_bjacobi_ops;                /* pc_bjacobi.c */
extern const la_pc_ops la_pc_ilu_ops;                    /* pc_ilu.c */
extern const la_pc_ops la_pc_mg_ops;                     /* pc_mg.c */

/* The type's operations, NULL when none is registered under it (pc.c). */
const la_pc_ops *la_pc_ops_of(sessile_pc_type t);
/* Point Jacobi's setup, recording and release (pc_jacobi.c), also block
 * Jacobi's for 1x1 blocks. */
sessile_status la_pc_jacobi_setup(sessile_pc *pc, const sessile_mat *a);
sessile_status la_pc_diag_rec(const sessile_pc *pc, sessile_cmd *c, vref r, vref z, int guard);
void la_pc_diag_release(sessile_pc *pc);

/* z = M⁻¹ r into c (pc set up). */
static inline sessile_status rec_pc(const sessile_pc *pc, sessile_cmd *c, vref r, vref z, int guard) {
  return pc->ops->rec(pc, c, r, z, guard);
}

#endif
