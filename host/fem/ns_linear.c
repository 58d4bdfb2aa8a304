/* The linear solve of one Newton (or Picard) step on the GPU: the block
 * Jacobian uploaded, la's preconditioner object for params.pc (ILU(0) falls
 * back to Jacobi on a matrix stored in row chunks) and la's Krylov solver. */
#include <math.h>
#include <stdlib.h>

#include "fem/ns_internal.h"
#include "sessile/la/la_ref.h"
#include "sessile/la/pc.h"

sessile_status ns_linear_solve(sessile_fluid *fl, const sessile_fluid_params *p, const double *r,
                               double *du, sessile_vec *b, sessile_vec *x, sessile_fluid_step *st) {
  size_t n4 = (size_t)fl->nnodes * 4;
  for (size_t k = 0; k < n4; k++) du[k] = -r[k];
  sessile_mat *m = NULL;
  SESSILE_CALL(sessile_mat_create_bcsr4(fl->la, &fl->a, &m));
  sessile_ksp_options o;
  sessile_ksp_options_default(&o);
  o.type = st->lin_ksp = p->ksp;
  /* la factorises ILU(0) only on a matrix stored in one piece */
  st->lin_chunks = sessile_mat_chunks(m);
  st->lin_pc = p->pc == SESSILE_PC_ILU0 && st->lin_chunks > 1 ? SESSILE_PC_JACOBI : p->pc;
  o.pc = st->lin_pc;
  o.rtol = p->linear_rtol;
  o.max_it = p->linear_max;
  o.restart = p->restart;
  sessile_solve_result lr;
  sessile_pc *pc = NULL;
  sessile_status s = sessile_pc_create_type(fl->la, st->lin_pc, &pc);
  if (s == SESSILE_OK) s = sessile_vec_upload(b, du);
  if (s == SESSILE_OK) s = sessile_vec_fill(fl->la, 0.0, x);
  if (s == SESSILE_OK) s = sessile_pc_setup(pc, m);
  if (s == SESSILE_OK) s = sessile_ksp_solve_pc(fl->la, &o, m, pc, b, x, &lr);
  if (s == SESSILE_OK) s = sessile_vec_download(x, du);
  sessile_pc_destroy(pc);
  sessile_mat_destroy(m);
  if (s != SESSILE_OK) return s;
  if (p->check_linear && p->monitor) {
    double *y = malloc(n4 * sizeof *y), e = 0, nb = 0;
    SESSILE_CHECK(y, SESSILE_ERR_NO_MEMORY, "out of host memory for the linear-solve check");
    sessile_ref_spmv_bcsr4(&fl->a, du, y);
    for (size_t k = 0; k < n4; k++) { e += (y[k] + r[k]) * (y[k] + r[k]); nb += r[k] * r[k]; }
    free(y);
    ns_monitor(p, "host check |J du + r|/|r| = %g", sqrt(e / nb));
  }
  st->lin_iterations = lr.iterations;
  st->lin_relres = lr.true_relres;
  st->lin_status = lr.status;
  return SESSILE_OK;
}
