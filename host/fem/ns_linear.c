/* The linear solve of one Newton (or Picard) step on the GPU: the block
 * Jacobian uploaded, la's preconditioner object for params.pc and la's
 * Krylov solver.  Fallbacks, reported in the step's lin_pc: ILU(0) becomes
 * Jacobi on a matrix stored in row chunks; mg (the block multigrid, on a
 * Kuhn box mesh only) becomes ILU(0) on any other mesh (or Jacobi, chunked)
 * and for a step whose hierarchy has a singular diagonal block.
 * The mg hierarchy and its pc are kept in the fluid across Newton steps and
 * solves: its masks are rebuilt only when the fixed unknowns change, its
 * operators at each setup (docs/fluid.md). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fem/ns_internal.h"
#include "sessile/la/la_ref.h"

/* The fluid's kept mg pc for these options (a new hierarchy when they changed). */
static sessile_status mg_pc(sessile_fluid *fl, const sessile_fluid_params *p, sessile_pc **out) {
  if (fl->bmg && memcmp(&fl->bmg_opt, &p->mg, sizeof p->mg)) {
    ns_mg_free(fl);
    sessile_pc_destroy(fl->mgpc);
    sessile_bmg_destroy(fl->bmg);
    fl->mgpc = NULL, fl->bmg = NULL;
  }
  if (!fl->bmg) {
    SESSILE_CALL(sessile_bmg_create(fl->la, fl->grid, &p->mg, &fl->bmg));
    fl->bmg_opt = p->mg;
  }
  if (!fl->mgpc) {
    SESSILE_CALL(sessile_pc_create_type(fl->la, SESSILE_PC_MG, &fl->mgpc));
    SESSILE_CALL(sessile_pc_mg_set_block(fl->mgpc, fl->bmg));
  }
  *out = fl->mgpc;
  return SESSILE_OK;
}

sessile_status ns_linear_solve(sessile_fluid *fl, const sessile_fluid_params *p, const uint8_t *solid,
                               const double *up, double newton, const double *r, double *du,
                               sessile_vec *b, sessile_vec *x, sessile_fluid_step *st) {
  size_t n4 = (size_t)fl->nnodes * 4;
  for (size_t k = 0; k < n4; k++) du[k] = -r[k];
  /* the device matrix of the last solve takes the new values in place; a
   * first solve, or one after the context's chunking changed, makes it */
  if (!fl->dev || sessile_mat_refill_bcsr4(fl->dev, &fl->a) != SESSILE_OK) {
    sessile_mat_destroy(fl->dev);
    fl->dev = NULL;
    SESSILE_CALL(sessile_mat_create_bcsr4(fl->la, &fl->a, &fl->dev));
  }
  sessile_mat *m = fl->dev;
  sessile_ksp_options o;
  sessile_ksp_options_default(&o);
  o.type = st->lin_ksp = p->ksp;
  st->lin_chunks = sessile_mat_chunks(m);
  sessile_pc_type t = p->pc;
  if (t == SESSILE_PC_MG && !fl->grid[0]) t = SESSILE_PC_ILU0; /* not a box: no hierarchy */
  /* la factorises ILU(0) only on a matrix stored in one piece */
  st->lin_pc = t == SESSILE_PC_ILU0 && st->lin_chunks > 1 ? SESSILE_PC_JACOBI : t;
  o.pc = st->lin_pc;
  o.rtol = st->lin_rtol; /* the Newton loop's forcing (params.forcing) */
  o.x_zero = 1;           /* x is filled with 0 below */
  o.max_it = p->linear_max;
  o.restart = p->restart;
  sessile_solve_result lr;
  sessile_pc *pc = NULL, *own = NULL;
  double tp = sessile_wall_seconds();
  sessile_status s = st->lin_pc == SESSILE_PC_MG ? mg_pc(fl, p, &pc)
                                                 : sessile_pc_create_type(fl->la, st->lin_pc, &own);
  if (own) pc = own;
  if (s == SESSILE_OK && st->lin_pc == SESSILE_PC_MG && !p->mg_galerkin)
    s = ns_mg_operators(fl, p, solid, up, newton);
  if (s == SESSILE_OK) s = sessile_vec_upload(b, du);
  if (s == SESSILE_OK) s = sessile_vec_fill(fl->la, 0.0, x);
  if (s == SESSILE_OK) s = sessile_pc_setup(pc, m);
  if (s == SESSILE_ERR_NUMERIC && st->lin_pc == SESSILE_PC_MG && st->lin_chunks == 1) {
    /* a singular block on some level: this step runs ILU(0) (recorded as such) */
    st->lin_pc = o.pc = SESSILE_PC_ILU0;
    s = sessile_pc_create_type(fl->la, SESSILE_PC_ILU0, &own);
    if (s == SESSILE_OK) s = sessile_pc_setup(pc = own, m);
  }
  st->pc_setup_s = sessile_wall_seconds() - tp;
  if (s == SESSILE_OK) s = sessile_ksp_solve_pc(fl->la, &o, m, pc, b, x, &lr);
  if (s == SESSILE_OK) s = sessile_vec_download(x, du);
  sessile_pc_destroy(own);
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
