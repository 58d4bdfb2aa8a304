/* Preconditioned conjugate gradients on the device, any symmetric pc:
 *   q = A p; α = (r·z)/(p·q); x += α p; r −= α q; z = M⁻¹ r; β = (r·z)'/(r·z); p = z + β p
 * Convergence on the unpreconditioned ‖r‖.  Two recordings: the start, and a
 * block of `check_every` iterations submitted until the device stops.
 * A diagonal pc (none, jacobi: pc->diag) is fused: per iteration the SpMV
 * with p·q, one update pass (x, r and both dots), one direction pass (z is
 * recomputed there, never stored), three tiny scalar/reduction dispatches:
 * about 11 vector passes (docs/performance.md).  Any other pc stores z:
 * the update (its r·D⁻¹r with D⁻¹ = ones unused), the test (cg_scalar op 3),
 * z = M⁻¹ r, r·z, β (op 4) and p = z + β p, as MG-PCG does. */
#include <math.h>
#include "pc_internal.h"

typedef struct { sessile_vec *r, *p, *q, *z, *ones; } cg_work; /* p starts as z = M⁻¹ r */

static sessile_kernel *kern(sessile_la *la, la_kernel_id id) { return la->k[id]; }

static sessile_status scalar_op(sessile_la *la, sessile_cmd *c, uint32_t op) {
  op_push p = {.op = op};
  sessile_buffer *sb[1] = {la->scalars};
  return sessile_cmd_dispatch(c, kern(la, K_CG_SCALAR), 1, sb, &p);
}

static sessile_status record_start(sessile_la *la, sessile_cmd *c, const sessile_mat *a,
                                   const sessile_vec *b, const sessile_vec *x,
                                   const sessile_pc *pc, cg_work *w) {
  uint32_t n = a->nrows, cnt;
  SESSILE_CALL(sessile_cmd_begin(c));
  SESSILE_CALL(rec_spmv(la, c, a, vref_of(x), vref_of(w->q), -1));
  SESSILE_CALL(rec_vec(la, c, K_WAXPY, n, vref_of(w->q), vref_of(b), vref_of(w->r), -1, COEF_NEG, -1));
  SESSILE_CALL(rec_pc(pc, c, vref_of(w->r), vref_of(w->p), -1));
  SESSILE_CALL(rec_dot(la, c, n, vref_of(b), vref_of(b), 0, -1, &cnt));
  SESSILE_CALL(rec_dot(la, c, n, vref_of(w->r), vref_of(w->p), 1, -1, &cnt));
  SESSILE_CALL(rec_dot(la, c, n, vref_of(w->r), vref_of(w->r), 2, -1, &cnt));
  SESSILE_CALL(rec_reduce(la, c, cnt, 0, 1, S_BB, 0, -1));
  SESSILE_CALL(rec_reduce(la, c, cnt, 1, 2, CG_RZNEW, 0, -1));
  SESSILE_CALL(scalar_op(la, c, 0));
  return sessile_cmd_end(c);
}

/* The second half of an iteration with a stored z (pc not diagonal): after
 * the update, the test, z = M⁻¹ r, r·z, β and p = z + β p. */
static sessile_status rec_direction_pc(sessile_la *la, sessile_cmd *c, const sessile_pc *pc,
                                       cg_work *w, uint32_t ucnt) {
  uint32_t n = w->r->n, cnt;
  SESSILE_CALL(rec_reduce(la, c, ucnt, 1, 1, CG_RR, 0, S_STOP));
  SESSILE_CALL(scalar_op(la, c, 3));
  SESSILE_CALL(rec_pc(pc, c, vref_of(w->r), vref_of(w->z), S_STOP));
  SESSILE_CALL(rec_dot(la, c, n, vref_of(w->r), vref_of(w->z), 0, S_STOP, &cnt));
  SESSILE_CALL(rec_reduce(la, c, cnt, 0, 1, CG_RZNEW, 0, S_STOP));
  SESSILE_CALL(scalar_op(la, c, 4));
  return rec_vec(la, c, K_AYPX, n, vref_of(w->z), vref_of(w->p), vref_of(w->p), CG_BETA, 0, S_STOP);
}

static sessile_status record_iterations(sessile_la *la, sessile_cmd *c, const sessile_mat *a,
                                        const sessile_vec *x, const sessile_pc *pc,
                                        cg_work *w, int k) {
  uint32_t n = a->nrows, cnt;
  const sessile_vec *dinv = pc->diag ? pc->diag : w->ones;
  SESSILE_CALL(sessile_cmd_begin(c));
  for (int it = 0; it < k; it++) {
    SESSILE_CALL(rec_spmv_dot(la, c, a, vref_of(w->p), vref_of(w->q), S_STOP, &cnt));
    SESSILE_CALL(rec_reduce(la, c, cnt, 0, 1, CG_PQ, 0, S_STOP));
    SESSILE_CALL(scalar_op(la, c, 1));
    sessile_buffer *ub[7] = {la->scalars, w->p->buf, w->q->buf, dinv->buf,
                             x->buf,      w->r->buf, la->partials};
    uint32_t ucnt = la_reduce_groups(la, w->p->n4);
    vec_push p = {.n4 = w->p->n4, .n = n, .a_slot = CG_ALPHA, .guard = S_STOP};
    SESSILE_CALL(sessile_cmd_dispatch(c, kern(la, K_CG_UPDATE), ucnt, ub, &p));
    if (!pc->diag) {
      SESSILE_CALL(rec_direction_pc(la, c, pc, w, ucnt));
      continue;
    }
    SESSILE_CALL(rec_reduce(la, c, ucnt, 0, 2, CG_RZNEW, 0, S_STOP));
    SESSILE_CALL(scalar_op(la, c, 2));
    SESSILE_CALL(rec_vec(la, c, K_CG_DIRECTION, n, vref_of(dinv), vref_of(w->r), vref_of(w->p), -1, 0, S_STOP));
  }
  return sessile_cmd_end(c);
}

static sessile_status cg_run(sessile_la *la, const sessile_ksp_options *o, const sessile_mat *a,
                             const sessile_vec *b, sessile_vec *x, const sessile_pc *pc,
                             cg_work *w, sessile_cmd *iter, sessile_solve_result *res) {
  sessile_kernel *k;
  /* Create every kernel before recording (la_groups reads their local size). */
  static const la_kernel_id ids[] = {K_CG_SCALAR, K_CG_UPDATE, K_CG_DIRECTION, K_DOT,
                                     K_REDUCE, K_WAXPY, K_PMUL, K_SPMV_CSR_DOT};
  for (size_t i = 0; i < sizeof ids / sizeof ids[0]; i++) SESSILE_CALL(la_kernel(la, ids[i], &k));
  SESSILE_CALL(la_kernel(la, a->kind == MAT_CSR ? K_SPMV_CSR : K_SPMV_BCSR4, &k));
  la_solver_reset(la, o);
  SESSILE_CALL(record_start(la, la->cmd, a, b, x, pc, w));
  SESSILE_CALL(sessile_cmd_submit_wait(la->cmd));
  SESSILE_CALL(record_iterations(la, iter, a, x, pc, w, o->check_every));
  SESSILE_CALL(la_solver_loop(la, iter, o->check_every, o->max_it, o, "cg", CG_RR, 1));
  la_solver_outcome(la, res, sqrt(fmax(la_scalar_read(la, CG_RR), 0) / la_scalar_read(la, S_BB)));
  return SESSILE_OK;
}

sessile_status la_cg(sessile_la *la, const sessile_ksp_options *o, const sessile_mat *a,
                     const sessile_vec *b, sessile_vec *x, const sessile_pc *pc,
                     sessile_solve_result *res) {
  cg_work w = {0};
  sessile_cmd *iter = NULL;
  uint32_t n = a->nrows;
  sessile_status s = sessile_vec_create(la, n, &w.r);
  if (s == SESSILE_OK) s = sessile_vec_create(la, n, &w.p);
  if (s == SESSILE_OK) s = sessile_vec_create(la, n, &w.q);
  if (s == SESSILE_OK && !pc->diag) s = sessile_vec_create(la, n, &w.z);
  if (s == SESSILE_OK && !pc->diag) s = la_ones(la, n, &w.ones);
  if (s == SESSILE_OK) s = sessile_cmd_create(la->gpu, &iter);
  if (s == SESSILE_OK) s = cg_run(la, o, a, b, x, pc, &w, iter, res);
  sessile_cmd_destroy(iter);
  sessile_vec_destroy(w.r);
  sessile_vec_destroy(w.p);
  sessile_vec_destroy(w.q);
  sessile_vec_destroy(w.z);
  sessile_vec_destroy(w.ones);
  return s;
}
