/* BiCGSTAB on the device with right preconditioning by any pc object (van der Vorst):
 *   β = (ρ'/ρ)(α/ω); p = r + β(p − ω v); p̂ = M p; v = A p̂; α = ρ/(r̂0·v);
 *   s = r − α v; ŝ = M s; t = A ŝ; ω = (t·s)/(t·t); x += α p̂ + ω ŝ; r = s − ω t
 * Converged on ‖r‖ (or already on ‖s‖, the half step).  Where ρ' has fallen
 * to rounding against ‖r̂0‖ ‖r‖ the iteration restarts from r (r̂0 = p = r;
 * docs/la.md, "BiCGSTAB restarts"), as sessile_ref_bicgstab does. */
#include <math.h>
#include "pc_internal.h"

typedef struct { sessile_vec *r, *r0, *p, *v, *ph, *sv, *sh, *t; } bi_work;

static sessile_status scalar_op(sessile_la *la, sessile_cmd *c, uint32_t op) {
  op_push pc = {.op = op};
  sessile_buffer *sb[1] = {la->scalars};
  return sessile_cmd_dispatch(c, la->k[K_BICG_SCALAR], 1, sb, &pc);
}

static sessile_status record_start(sessile_la *la, sessile_cmd *c, const sessile_mat *a,
                                   const sessile_vec *b, const sessile_vec *x, bi_work *w) {
  uint32_t n = a->nrows, cnt;
  vref none = {0};
  SESSILE_CALL(sessile_cmd_begin(c));
  SESSILE_CALL(rec_spmv(la, c, a, vref_of(x), vref_of(w->t), -1));
  SESSILE_CALL(rec_vec(la, c, K_WAXPY, n, vref_of(w->t), vref_of(b), vref_of(w->r), -1, COEF_NEG, -1));
  SESSILE_CALL(rec_vec(la, c, K_COPY, n, vref_of(w->r), vref_of(w->r0), none, -1, 0, -1));
  la_scalar_set(la, S_IMM, 0.0);
  SESSILE_CALL(rec_vec(la, c, K_FILL, n, vref_of(w->p), none, none, S_IMM, 0, -1));
  SESSILE_CALL(rec_vec(la, c, K_FILL, n, vref_of(w->v), none, none, S_IMM, 0, -1));
  SESSILE_CALL(rec_dot(la, c, n, vref_of(b), vref_of(b), 0, -1, &cnt));
  SESSILE_CALL(rec_dot(la, c, n, vref_of(w->r), vref_of(w->r), 1, -1, &cnt));
  SESSILE_CALL(rec_reduce(la, c, cnt, 0, 1, S_BB, 0, -1));
  SESSILE_CALL(rec_reduce(la, c, cnt, 1, 1, BI_RR, 0, -1));
  SESSILE_CALL(rec_reduce(la, c, cnt, 1, 1, BI_RHONEW, 0, -1)); /* r0·r = r·r at the start */
  SESSILE_CALL(scalar_op(la, c, 0));
  return sessile_cmd_end(c);
}

static sessile_status record_iterations(sessile_la *la, sessile_cmd *c, const sessile_mat *a,
                                        const sessile_vec *x, const sessile_pc *pc,
                                        bi_work *w, int k) {
  uint32_t n = a->nrows, n4 = w->r->n4, cnt;
  vref none = {0};
  vec_push vp = {.n4 = n4, .n = n, .a_slot = -1, .guard = S_STOP};
  SESSILE_CALL(sessile_cmd_begin(c));
  for (int it = 0; it < k; it++) {
    SESSILE_CALL(scalar_op(la, c, 1));
    sessile_buffer *pb[5] = {la->scalars, w->r->buf, w->v->buf, w->p->buf, w->r0->buf};
    SESSILE_CALL(sessile_cmd_dispatch(c, la->k[K_BICG_P], la_groups(la, K_BICG_P, n4), pb, &vp));
    SESSILE_CALL(rec_pc(pc, c, vref_of(w->p), vref_of(w->ph), S_STOP));
    SESSILE_CALL(rec_spmv(la, c, a, vref_of(w->ph), vref_of(w->v), S_STOP));
    SESSILE_CALL(rec_dot(la, c, n, vref_of(w->r0), vref_of(w->v), 0, S_STOP, &cnt));
    SESSILE_CALL(rec_reduce(la, c, cnt, 0, 1, BI_R0V, 0, S_STOP));
    SESSILE_CALL(scalar_op(la, c, 2));
    sessile_buffer *sbuf[5] = {la->scalars, w->r->buf, w->v->buf, w->sv->buf, la->partials};
    SESSILE_CALL(sessile_cmd_dispatch(c, la->k[K_BICG_S], cnt, sbuf, &vp));
    SESSILE_CALL(rec_reduce(la, c, cnt, 0, 1, BI_SS, 0, S_STOP));
    SESSILE_CALL(rec_pc(pc, c, vref_of(w->sv), vref_of(w->sh), S_STOP));
    SESSILE_CALL(rec_spmv(la, c, a, vref_of(w->sh), vref_of(w->t), S_STOP));
    SESSILE_CALL(rec_dot(la, c, n, vref_of(w->t), vref_of(w->sv), 0, S_STOP, &cnt));
    SESSILE_CALL(rec_dot(la, c, n, vref_of(w->t), vref_of(w->t), 1, S_STOP, &cnt));
    SESSILE_CALL(rec_reduce(la, c, cnt, 0, 2, BI_TS, 0, S_STOP)); /* TS, TT */
    SESSILE_CALL(scalar_op(la, c, 3));
    sessile_buffer *xb[9] = {la->scalars, x->buf, w->ph->buf, w->sh->buf, w->sv->buf,
                             w->t->buf,   w->r->buf, w->r0->buf, la->partials};
    SESSILE_CALL(sessile_cmd_dispatch(c, la->k[K_BICG_XR], cnt, xb, &vp));
    SESSILE_CALL(rec_reduce(la, c, cnt, 0, 2, BI_RR, 0, S_STOP)); /* RR, RHONEW */
    SESSILE_CALL(scalar_op(la, c, 4));
  }
  (void)none;
  return sessile_cmd_end(c);
}

static sessile_status bi_run(sessile_la *la, const sessile_ksp_options *o, const sessile_mat *a,
                             const sessile_vec *b, sessile_vec *x, const sessile_pc *pc,
                             bi_work *w, sessile_cmd *iter, sessile_solve_result *res) {
  sessile_kernel *k;
  static const la_kernel_id ids[] = {K_BICG_SCALAR, K_BICG_P, K_BICG_S, K_BICG_XR, K_DOT,
                                     K_REDUCE, K_WAXPY, K_PMUL, K_COPY, K_FILL};
  for (size_t i = 0; i < sizeof ids / sizeof ids[0]; i++) SESSILE_CALL(la_kernel(la, ids[i], &k));
  SESSILE_CALL(la_kernel(la, a->kind == MAT_CSR ? K_SPMV_CSR : K_SPMV_BCSR4, &k));
  la_solver_reset(la, o);
  SESSILE_CALL(record_start(la, la->cmd, a, b, x, w));
  SESSILE_CALL(sessile_cmd_submit_wait(la->cmd));
  SESSILE_CALL(record_iterations(la, iter, a, x, pc, w, o->check_every));
  SESSILE_CALL(la_solver_loop(la, iter, o->check_every, o->max_it, o, "bicgstab", BI_RR, 1));
  la_solver_outcome(la, res, sqrt(fmax(la_scalar_read(la, BI_RR), 0) / la_scalar_read(la, S_BB)));
  res->restarts += (int)la_scalar_read(la, BI_RESTARTS);
  return SESSILE_OK;
}

sessile_status la_bicgstab(sessile_la *la, const sessile_ksp_options *o, const sessile_mat *a,
                           const sessile_vec *b, sessile_vec *x, const sessile_pc *pc,
                           sessile_solve_result *res) {
  bi_work w = {0};
  sessile_vec **v[] = {&w.r, &w.r0, &w.p, &w.v, &w.ph, &w.sv, &w.sh, &w.t};
  sessile_cmd *iter = NULL;
  sessile_status s = SESSILE_OK;
  for (size_t i = 0; s == SESSILE_OK && i < sizeof v / sizeof v[0]; i++)
    s = sessile_vec_create(la, a->nrows, v[i]);
  if (s == SESSILE_OK) s = sessile_cmd_create(la->gpu, &iter);
  if (s == SESSILE_OK) s = bi_run(la, o, a, b, x, pc, &w, iter, res);
  sessile_cmd_destroy(iter);
  for (size_t i = 0; i < sizeof v / sizeof v[0]; i++) sessile_vec_destroy(*v[i]);
  return s;
}
