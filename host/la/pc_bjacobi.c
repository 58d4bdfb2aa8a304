/* "block_jacobi": M = the diagonal blocks of A.  On a 4x4 block CSR matrix
 * (a node's u and p in the Navier-Stokes system) the inverse blocks come
 * from sessile_ref_bjacobi_bcsr4 on the host, once per setup, and are
 * stored as a block-diagonal BCSR4 matrix, so an application is one block
 * SpMV (no kernel of its own; row chunks as for any matrix).  Point Jacobi
 * cannot couple a node's unknowns; this can.  Any other matrix has 1x1
 * blocks: the setup is then point Jacobi's, with its fused solver paths. */
#include <stdlib.h>
#include "pc_internal.h"
#include "sessile/la/la_ref.h"

static sessile_status bj_setup(sessile_pc *pc, const sessile_mat *a) {
  if (a->kind != MAT_BCSR4) return la_pc_jacobi_setup(pc, a);
  const sessile_bcsr4 *h = &a->hostb;
  uint32_t nb = h->nbrows;
  sessile_bcsr4 d = {0};
  SESSILE_CALL(sessile_bcsr4_alloc(nb, nb, nb, &d));
  sessile_status s = sessile_ref_bjacobi_bcsr4(h, d.val);
  for (uint32_t i = 0; i <= nb; i++) d.rowptr[i] = i;
  for (uint32_t i = 0; i < nb; i++) d.col[i] = i;
  sessile_mat *m = NULL;
  if (s == SESSILE_OK) s = sessile_mat_create_bcsr4(pc->la, &d, &m);
  sessile_bcsr4_free(&d);
  pc->data = m;
  return s;
}

static sessile_status bj_rec(const sessile_pc *pc, sessile_cmd *c, vref r, vref z, int guard) {
  if (pc->diag) return la_pc_diag_rec(pc, c, r, z, guard);
  return rec_spmv(pc->la, c, pc->data, r, z, guard);
}

static void bj_release(sessile_pc *pc) {
  if (pc->diag) la_pc_diag_release(pc);
  else sessile_mat_destroy(pc->data);
  pc->data = NULL;
}

const la_pc_ops la_pc_bjacobi_ops = {"block_jacobi", SESSILE_PC_BLOCK_JACOBI, 1, bj_setup, bj_rec,
                                     bj_release};
