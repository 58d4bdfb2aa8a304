/* "ilu0": ILU(0) of a CSR or BCSR4 matrix.  The factors are those cached in
 * the matrix (ilu.c: factorised once per matrix on the host, applied as one
 * dispatch per level of L and of U), so a pc set up again for the same
 * matrix, or sessile_mat_ilu0_apply on it, does not factorise again; the pc
 * only points at them.  Nonsymmetric: CG refuses it. */
#include "pc_internal.h"

static sessile_status ilu_setup(sessile_pc *pc, const sessile_mat *a) {
  const la_ilu *f;
  SESSILE_CALL(la_ilu_get(pc->la, a, &f));
  pc->data = (void *)f;
  return SESSILE_OK;
}

static sessile_status ilu_rec(const sessile_pc *pc, sessile_cmd *c, vref r, vref z, int guard) {
  return rec_ilu(pc->la, c, pc->data, r, z, guard);
}

static void ilu_release(sessile_pc *pc) { pc->data = NULL; /* the matrix owns the factors */ }

const la_pc_ops la_pc_ilu_ops = {"ilu0", SESSILE_PC_ILU0, 0, ilu_setup, ilu_rec, ilu_release};
