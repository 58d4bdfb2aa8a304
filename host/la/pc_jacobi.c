/* The diagonal preconditioners: "jacobi" (M⁻¹ = 1/diag(A), computed on the
 * device for every matrix kind, sessile_mat_jacobi) and "none" (M⁻¹ = I as
 * a vector of ones).  Both hand their vector to the solvers through
 * pc->diag, so CG and GMRES keep their fused kernels (z = D⁻¹ r is never
 * stored); applied alone they are one element-wise product. */
#include "pc_internal.h"

void la_pc_diag_release(sessile_pc *pc) {
  sessile_vec_destroy(pc->data);
  pc->data = NULL;
}

static sessile_status diag_setup(sessile_pc *pc, const sessile_mat *a, int jacobi) {
  sessile_vec *d = NULL;
  SESSILE_CALL(sessile_vec_create(pc->la, a->nrows, &d));
  sessile_status s = jacobi ? sessile_mat_jacobi(pc->la, a, d) : sessile_vec_fill(pc->la, 1.0, d);
  if (s != SESSILE_OK) {
    sessile_vec_destroy(d);
    return s;
  }
  pc->data = d;
  pc->diag = d;
  return SESSILE_OK;
}

sessile_status la_pc_jacobi_setup(sessile_pc *pc, const sessile_mat *a) { return diag_setup(pc, a, 1); }
static sessile_status none_setup(sessile_pc *pc, const sessile_mat *a) { return diag_setup(pc, a, 0); }

sessile_status la_pc_diag_rec(const sessile_pc *pc, sessile_cmd *c, vref r, vref z, int guard) {
  return rec_vec(pc->la, c, K_PMUL, pc->n, vref_of(pc->diag), r, z, -1, 0, guard);
}

const la_pc_ops la_pc_none_ops = {"none", SESSILE_PC_NONE, 1, none_setup, la_pc_diag_rec, la_pc_diag_release};
const la_pc_ops la_pc_jacobi_ops = {"jacobi", SESSILE_PC_JACOBI, 1, la_pc_jacobi_setup, la_pc_diag_rec,
                                    la_pc_diag_release};
