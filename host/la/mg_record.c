/* Recording of the V-cycle and of MG-preconditioned CG.
 *
 * V-cycle on level l with right-hand side b (finest: CG's r), from x = 0:
 *   pre_smooth damped-Jacobi sweeps (the first, from zero, is pointwise and
 *   fused into whatever wrote b: CG's update on the finest level, the
 *   restriction on coarser ones), the residual, its restriction R = P^T,
 *   the V-cycle on level l+1, x += P x_{l+1}, post_smooth sweeps; on the
 *   coarsest level coarse_sweeps sweeps from zero.  Sweeps alternate between
 *   two buffers; the residual goes to the free one.  Per finest-level CG
 *   iteration: the operator with p·Ap, the update with the first sweep and
 *   r·r, the second pre-sweep, the residual, the restriction (reading the
 *   fine residual), the prolongation, 2 post-sweeps (the last with r·z) and
 *   the direction update: 9 fine-grid passes, plus 1/8 of the V-cycle's per
 *   coarser level.
 *
 * CG (as cg.c, on the unpreconditioned residual), recorded so that every
 * submit ends at a convergence test: the start ends with the first half of
 * iteration 1 (q = A p, the update, the test), and the recording submitted
 * per iteration is the second half of iteration k (the V-cycle, β, p) and
 * the first half of k+1 (cg_scalar.comp ops 3 and 4).  So the last
 * iteration has no V-cycle and nothing runs past convergence: on lavapipe a
 * dispatch guarded off by S_STOP costs nearly what it does when it runs
 * (llvmpipe executes the masked-off invocations anyway; docs/la.md), which
 * makes blocks of guarded iterations the dearer choice here. */
#include "mg_internal.h"

static mg_push level_push(const sessile_mg *mg, int l, uint32_t flags, uint32_t set, int guard) {
  const mg_level *v = &mg->lv[l];
  uint32_t rb = mg->la->real_bytes;
  mg_push p = {.n0 = v->n[0], .n1 = v->n[1], .n2 = v->n[2], .m0 = la_div_magic(v->n[0]),
               .m1 = la_div_magic(v->n[1]), .guard = guard, .flags = flags, .set = set,
               .h = sessile_push_real_of(v->h, rb), .omega = sessile_push_real_of(mg->o.omega, rb)};
  return p;
}

/* y = S(x, b) on level l; with count, also the partials of b·y into `set`. */
static sessile_status rec_sweep(sessile_mg *mg, sessile_cmd *c, int l, vref x, vref b, vref y,
                                uint32_t flags, uint32_t set, uint32_t *count, int guard) {
  sessile_la *la = mg->la;
  const mg_level *v = &mg->lv[l];
  mg_push p = level_push(mg, l, flags, set, guard);
  if (v->coef) { /* the advective operator: no fused dot (it serves BiCGSTAB and GMRES, not CG) */
    SESSILE_CHECK(!count, SESSILE_ERR_INTERNAL, "multigrid: a fused dot on an advective level");
    sessile_buffer *abufs[7] = {la->scalars, v->mask, v->diag->buf, v->coef->buf, x.buf, b.buf, y.buf};
    return sessile_cmd_dispatch(c, la->k[K_MG_SMOOTH_ADV], la_groups(la, K_MG_SMOOTH_ADV, v->nodes),
                                abufs, &p);
  }
  sessile_buffer *bufs[6] = {la->scalars, v->mask, v->diag->buf, x.buf, b.buf, y.buf};
  if (!count)
    return sessile_cmd_dispatch(c, la->k[K_MG_SMOOTH], la_groups(la, K_MG_SMOOTH, v->nodes), bufs, &p);
  sessile_buffer *dbufs[7] = {la->scalars, v->mask, v->diag->buf, x.buf, b.buf, y.buf, la->partials};
  *count = la_fused_groups(la, K_MG_SMOOTH_DOT, v->nodes);
  return sessile_cmd_dispatch(c, la->k[K_MG_SMOOTH_DOT], *count, dbufs, &p);
}

static sessile_status rec_residual(sessile_mg *mg, sessile_cmd *c, int l, vref x, vref b, vref y,
                                   int guard) {
  sessile_la *la = mg->la;
  const mg_level *v = &mg->lv[l];
  mg_push p = level_push(mg, l, 0, 0, guard);
  if (v->coef) {
    sessile_buffer *abufs[7] = {la->scalars, v->mask, v->diag->buf, v->coef->buf, x.buf, b.buf, y.buf};
    return sessile_cmd_dispatch(c, la->k[K_MG_RESIDUAL_ADV],
                                la_groups(la, K_MG_RESIDUAL_ADV, v->nodes), abufs, &p);
  }
  sessile_buffer *bufs[6] = {la->scalars, v->mask, v->diag->buf, x.buf, b.buf, y.buf};
  return sessile_cmd_dispatch(c, la->k[K_MG_RESIDUAL], la_groups(la, K_MG_RESIDUAL, v->nodes), bufs, &p);
}

/* Level l+1's b = R r and its first sweep into x. */
static sessile_status rec_restrict(sessile_mg *mg, sessile_cmd *c, int l, vref r, vref x, int guard) {
  sessile_la *la = mg->la;
  const mg_level *f = &mg->lv[l], *v = &mg->lv[l + 1];
  mg_push p = level_push(mg, l + 1, 0, 0, guard);
  p.f0 = f->n[0];
  p.f1 = f->n[1];
  p.f2 = f->n[2];
  sessile_buffer *bufs[6] = {la->scalars, r.buf, v->mask, v->diag->buf, v->b->buf, x.buf};
  return sessile_cmd_dispatch(c, la->k[K_MG_RESTRICT], la_groups(la, K_MG_RESTRICT, v->nodes), bufs, &p);
}

/* Level l's x += P xc (xc on level l+1). */
static sessile_status rec_prolong(sessile_mg *mg, sessile_cmd *c, int l, vref xc, vref x, int guard) {
  sessile_la *la = mg->la;
  const mg_level *f = &mg->lv[l], *v = &mg->lv[l + 1];
  mg_push p = level_push(mg, l, 0, 0, guard);
  p.f0 = v->n[0];
  p.f1 = v->n[1];
  p.f2 = v->n[2];
  sessile_buffer *bufs[5] = {la->scalars, f->mask, xc.buf, x.buf, x.buf};
  return sessile_cmd_dispatch(c, la->k[K_MG_PROLONG], la_groups(la, K_MG_PROLONG, f->nodes), bufs, &p);
}

/* Sweeps on level l after its first one, which is in *cur.  Ends with the
 * result in *cur.  dot: fuse b·x into the last sweep of this level. */
typedef struct { uint32_t set, *count; } dot_req;

static void swap(vref *a, vref *b) {
  vref t = *a;
  *a = *b;
  *b = t;
}

static sessile_status rec_sweeps(sessile_mg *mg, sessile_cmd *c, int l, int n, vref b, vref *cur,
                                 vref *oth, const dot_req *dot, int guard) {
  for (int s = 0; s < n; s++) {
    int last = s == n - 1;
    SESSILE_CALL(rec_sweep(mg, c, l, *cur, b, *oth, 0, dot ? dot->set : 0,
                           last && dot ? dot->count : NULL, guard));
    swap(cur, oth);
  }
  return SESSILE_OK;
}

static sessile_status rec_level(sessile_mg *mg, sessile_cmd *c, int l, vref b, vref *cur,
                                vref *oth, const dot_req *dot, int guard) {
  if (l == mg->nl - 1) return rec_sweeps(mg, c, l, mg->o.coarse_sweeps - 1, b, cur, oth, dot, guard);
  SESSILE_CALL(rec_sweeps(mg, c, l, mg->o.pre_smooth - 1, b, cur, oth, NULL, guard));
  SESSILE_CALL(rec_residual(mg, c, l, *cur, b, *oth, guard));
  mg_level *v = &mg->lv[l + 1];
  vref ccur = vref_of(v->x), coth = vref_of(v->t);
  SESSILE_CALL(rec_restrict(mg, c, l, *oth, ccur, guard));
  SESSILE_CALL(rec_level(mg, c, l + 1, vref_of(v->b), &ccur, &coth, NULL, guard));
  SESSILE_CALL(rec_prolong(mg, c, l, ccur, *cur, guard));
  return rec_sweeps(mg, c, l, mg->o.post_smooth, b, cur, oth, dot, guard);
}

/* Sweeps after the first on the finest level: odd means the first must go
 * to the other buffer for the last to land in `out`. */
static int finest_flips(const sessile_mg *mg) {
  return mg->nl == 1 ? mg->o.coarse_sweeps - 1 : mg->o.pre_smooth - 1 + mg->o.post_smooth;
}

vref mg_first_target(const sessile_mg *mg, vref out) {
  return finest_flips(mg) % 2 ? vref_of(mg->lv[0].t) : out;
}

sessile_status mg_rec_vcycle(sessile_mg *mg, sessile_cmd *c, vref r, vref out, int first_done,
                             uint32_t set, uint32_t *count, int guard) {
  vref cur = mg_first_target(mg, out);
  vref oth = cur.buf == out.buf ? vref_of(mg->lv[0].t) : out;
  if (!first_done) SESSILE_CALL(rec_sweep(mg, c, 0, r, r, cur, MG_ZERO, 0, NULL, guard)); /* x unread */
  dot_req dot = {set, count};
  SESSILE_CALL(rec_level(mg, c, 0, r, &cur, &oth, count ? &dot : NULL, guard));
  SESSILE_CHECK(cur.buf == out.buf, SESSILE_ERR_INTERNAL, "V-cycle ended outside its output");
  /* A single level swept once has no later sweep to carry the dot. */
  if (count && finest_flips(mg) == 0) return rec_dot(mg->la, c, mg->lv[0].nodes, r, out, set, guard, count);
  return SESSILE_OK;
}

static sessile_status scalar_op(sessile_la *la, sessile_cmd *c, uint32_t op) {
  op_push p = {.op = op};
  sessile_buffer *sb[1] = {la->scalars};
  return sessile_cmd_dispatch(c, la->k[K_CG_SCALAR], 1, sb, &p);
}

static sessile_status rec_update(sessile_mg *mg, sessile_cmd *c, const sessile_vec *x, vref z,
                                 uint32_t set, uint32_t *count) {
  sessile_la *la = mg->la;
  vec_push p = {.n4 = mg->r->n4, .n = mg->r->n, .off2 = set, .a_slot = -1, .guard = S_STOP};
  sessile_buffer *bufs[8] = {la->scalars, mg->p->buf, mg->q->buf, mg->w->buf,
                             x->buf,      mg->r->buf, z.buf,      la->partials};
  *count = la_fused_groups(la, K_MG_UPDATE, mg->r->n4);
  return sessile_cmd_dispatch(c, la->k[K_MG_UPDATE], *count, bufs, &p);
}

/* w = omega / (h diag) on free finest nodes, 1 on Dirichlet ones: the
 * Jacobi kernel with h / omega (diag and mask may change between solves). */
static sessile_status rec_weights(sessile_mg *mg, sessile_cmd *c) {
  sessile_la *la = mg->la;
  const mg_level *v = &mg->lv[0];
  cut_push p = {.n0 = v->n[0], .n1 = v->n[1], .n2 = v->n[2], .guard = -1,
                .h = sessile_push_real_of(v->h / mg->o.omega, la->real_bytes)};
  sessile_buffer *bufs[4] = {la->scalars, v->mask, v->diag->buf, mg->w->buf};
  return sessile_cmd_dispatch(c, la->k[K_STENCIL7_CUT_JACOBI],
                              la_groups(la, K_STENCIL7_CUT_JACOBI, v->nodes), bufs, &p);
}

/* The first half of an iteration: q = A p with p·q, α, the update with the
 * first sweep and r·r, the convergence test (op 3). */
static sessile_status rec_half_a(sessile_mg *mg, sessile_cmd *c, const sessile_vec *x) {
  sessile_la *la = mg->la;
  uint32_t cnt;
  SESSILE_CALL(rec_spmv_dot(la, c, mg->lv[0].a, vref_of(mg->p), vref_of(mg->q), S_STOP, &cnt));
  SESSILE_CALL(rec_reduce(la, c, cnt, 0, 1, CG_PQ, 0, S_STOP));
  SESSILE_CALL(scalar_op(la, c, 1));
  SESSILE_CALL(rec_update(mg, c, x, mg_first_target(mg, vref_of(mg->z)), 1, &cnt));
  SESSILE_CALL(rec_reduce(la, c, cnt, 1, 1, CG_RR, 0, S_STOP));
  return scalar_op(la, c, 3);
}

/* The second half: the rest of the V-cycle with r·z, β (op 4), p = z + β p. */
static sessile_status rec_half_b(sessile_mg *mg, sessile_cmd *c) {
  sessile_la *la = mg->la;
  uint32_t cnt;
  vref z = vref_of(mg->z);
  SESSILE_CALL(mg_rec_vcycle(mg, c, vref_of(mg->r), z, 1, 0, &cnt, S_STOP));
  SESSILE_CALL(rec_reduce(la, c, cnt, 0, 1, CG_RZNEW, 0, S_STOP));
  SESSILE_CALL(scalar_op(la, c, 4));
  return rec_vec(la, c, K_AYPX, mg->r->n, z, vref_of(mg->p), vref_of(mg->p), CG_BETA, 0, S_STOP);
}

/* r = b - A x, ||b||^2, ||r||^2, p = M r, r·p, and the start test (op 0). */
static sessile_status rec_start(sessile_mg *mg, sessile_cmd *c, const sessile_vec *b,
                                const sessile_vec *x) {
  sessile_la *la = mg->la;
  const sessile_mat *a = mg->lv[0].a;
  uint32_t n = a->nrows, cnt;
  SESSILE_CALL(sessile_cmd_begin(c));
  SESSILE_CALL(rec_weights(mg, c));
  SESSILE_CALL(rec_spmv(la, c, a, vref_of(x), vref_of(mg->q), -1));
  SESSILE_CALL(rec_vec(la, c, K_WAXPY, n, vref_of(mg->q), vref_of(b), vref_of(mg->r), -1, COEF_NEG, -1));
  SESSILE_CALL(rec_dot(la, c, n, vref_of(b), vref_of(b), 0, -1, &cnt));
  SESSILE_CALL(rec_reduce(la, c, cnt, 0, 1, S_BB, 0, -1));
  SESSILE_CALL(rec_dot(la, c, n, vref_of(mg->r), vref_of(mg->r), 0, -1, &cnt));
  SESSILE_CALL(rec_reduce(la, c, cnt, 0, 1, CG_RR, 0, -1));
  SESSILE_CALL(mg_rec_vcycle(mg, c, vref_of(mg->r), vref_of(mg->p), 0, 0, &cnt, -1));
  SESSILE_CALL(rec_reduce(la, c, cnt, 0, 1, CG_RZNEW, 0, -1));
  SESSILE_CALL(scalar_op(la, c, 0));
  SESSILE_CALL(rec_half_a(mg, c, x));
  return sessile_cmd_end(c);
}

/* ||b - A x|| into S_TRUE (q is scratch). */
static sessile_status rec_true_residual(sessile_mg *mg, sessile_cmd *c, const sessile_vec *b,
                                        const sessile_vec *x) {
  sessile_la *la = mg->la;
  const sessile_mat *a = mg->lv[0].a;
  uint32_t n = a->nrows, cnt;
  SESSILE_CALL(sessile_cmd_begin(c));
  SESSILE_CALL(rec_spmv(la, c, a, vref_of(x), vref_of(mg->q), -1));
  SESSILE_CALL(rec_vec(la, c, K_WAXPY, n, vref_of(mg->q), vref_of(b), vref_of(mg->q), -1, COEF_NEG, -1));
  SESSILE_CALL(rec_dot(la, c, n, vref_of(mg->q), vref_of(mg->q), 0, -1, &cnt));
  SESSILE_CALL(rec_reduce(la, c, cnt, 0, 1, S_TRUE, 1, -1));
  return sessile_cmd_end(c);
}

sessile_status mg_record(sessile_mg *mg, const sessile_vec *b, const sessile_vec *x) {
  mg->rec_b = mg->rec_x = 0; /* invalid until all three are recorded */
  SESSILE_CALL(rec_start(mg, mg->start, b, x));
  SESSILE_CALL(sessile_cmd_begin(mg->iter));
  SESSILE_CALL(rec_half_b(mg, mg->iter));
  SESSILE_CALL(rec_half_a(mg, mg->iter, x));
  SESSILE_CALL(sessile_cmd_end(mg->iter));
  SESSILE_CALL(rec_true_residual(mg, mg->resid, b, x));
  mg->rec_b = b->serial;
  mg->rec_x = x->serial;
  mg->recordings++;
  return SESSILE_OK;
}
