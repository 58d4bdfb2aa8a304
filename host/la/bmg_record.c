/* Recording of one block-multigrid V-cycle (sessile/la/bmg.h) into a
 * command buffer, every dispatch guarded by the solver's stop slot.
 *
 * Level l with right-hand side b, from x = 0:
 *   pre-smoothing: x = omega D^-1 b (block Jacobi from zero, no SpMV), then
 *     `pre` sweeps (Gauss-Seidel: colours 0..7 in place; Jacobi: into r and
 *     copied back);
 *   r = b - A x; b_{l+1} = R r; the cycle on level l+1; x += P x_{l+1}
 *     (`cycle` times: 2 is a W-cycle, with the second coarse residual
 *     restricted from the fine one; once when level l+1 is solved exactly, and
 *     on the finest level for cycle 3: bmg_corrections);
 *   `post` sweeps (Gauss-Seidel: colours 7..0);
 * the coarsest level: x = A^-1 b as one dense block SpMV, or the Jacobi
 * start and coarse_sweeps sweeps alternating forward and backward.
 * Smoother and residual dispatch once per row chunk of the level's matrix;
 * a colour sweep covers only the chunk's k-slabs of its colour; both read
 * the matrix and x through texel buffers where the views fit (la_block_texel_ok).
 * The fp32 cycle in an fp64 context (mg->f32): bmg_to32 casts r in (and sets
 * the cycle's stop flag), every pass runs the kernels' f32 variants on the
 * levels' fp32 data with `s` bound to that flag (guard slot 0), bmg_to64
 * casts x out; the coarsest dense solve is the residual kernel on the
 * negated inverse: x = 0 - (-C) b. */
#include "bmg_internal.h"

/* Kernel `id` in the cycle's precision (f32: made on first use, kept in mg). */
static sessile_status bmg_kernel(const sessile_bmg *mg, la_kernel_id id, sessile_kernel **out) {
  if (!mg->f32) return la_kernel(mg->la, id, out);
  sessile_kernel **k = (sessile_kernel **)&mg->k32[id]; /* a cache, not the hierarchy's state */
  if (!*k) SESSILE_CALL(sessile_kernel_create_decl(mg->la->gpu, &sessile_la_kernels[id], 4, 0, k));
  *out = *k;
  return SESSILE_OK;
}

static uint32_t groups_of(const sessile_kernel *k, uint32_t items) {
  uint32_t local = sessile_kernel_local_size(k);
  return (items + local - 1) / local;
}

/* The cycle kernels' `s`: la's scalars, or the fp32 cycle's stop flag. */
static sessile_buffer *bmg_s(const sessile_bmg *mg) { return mg->f32 ? mg->stop32 : mg->la->scalars; }

static bmg_push grid_push(const bmg_level *v, int guard) {
  bmg_push p = {.n0 = v->n[0], .n1 = v->n[1], .n2 = v->n[2], .m0 = la_div_magic(v->n[0]),
                .m1 = la_div_magic(v->n[1]), .guard = guard, .colour = 8};
  return p;
}

/* The _tex kernels read b (and the smoother its block inverses) through
 * texels too: every view within maxTexelBufferElements (RGBA32UI). */
static int pass_texel_ok(const sessile_la *la, const mat_chunk *ch, sessile_buffer *x, sessile_buffer *b,
                         sessile_buffer *dinv) {
  return la_block_texel_ok(la, ch, x) && la_texel_fits(la, b, 16) && (!dinv || la_texel_fits(la, dinv, 16));
}

/* One pass of the smoother over level l (every chunk): colour 0..7 or 8 (all). */
static sessile_status rec_pass(const sessile_bmg *mg, sessile_cmd *c, int l, vref b, vref x, vref y,
                               uint32_t colour, uint32_t flags, int guard) {
  sessile_la *la = mg->la;
  const bmg_level *v = &mg->lv[l];
  sessile_kernel *k, *kt;
  SESSILE_CALL(bmg_kernel(mg, K_BMG_SMOOTH, &k));
  SESSILE_CALL(bmg_kernel(mg, K_BMG_SMOOTH_TEX, &kt));
  uint32_t par[3] = {colour & 1u, (colour >> 1) & 1u, (colour >> 2) & 1u};
  uint32_t sub[3] = {0, 0, 0};
  for (int a = 0; a < 3; a++) sub[a] = (v->n[a] - par[a] + 1) / 2;
  uint32_t plane = v->n[0] * v->n[1];
  for (uint32_t ci = 0; ci < v->m->nchunks; ci++) {
    const mat_chunk *ch = &v->m->chunk[ci];
    bmg_push p = grid_push(v, guard);
    p.colour = colour, p.flags = flags, p.row0 = ch->row0, p.nrows = ch->nrows;
    p.omega = sessile_push_real_of(mg->o.omega, mg->rb);
    if (colour < 8) {
      if (!sub[0] || !sub[1] || !sub[2]) continue;
      uint32_t klo = ch->row0 / plane, khi = (ch->row0 + ch->nrows - 1) / plane;
      if (khi < par[2]) continue;
      uint32_t slo = klo <= par[2] ? 0 : (klo - par[2] + 1) / 2, shi = (khi - par[2]) / 2;
      if (shi >= sub[2]) shi = sub[2] - 1;
      if (slo > shi) continue;
      p.s0 = sub[0], p.s1 = sub[1], p.ms0 = la_div_magic(sub[0]), p.ms1 = la_div_magic(sub[1]);
      p.first = slo * sub[0] * sub[1];
      p.items = (shi - slo + 1) * sub[0] * sub[1];
    } else {
      p.items = ch->nrows;
    }
    sessile_buffer *bufs[8] = {bmg_s(mg), ch->rowptr, ch->col, ch->val, v->dinvb[ci], b.buf, x.buf, y.buf};
    SESSILE_CALL(sessile_cmd_dispatch(c, pass_texel_ok(la, ch, x.buf, b.buf, v->dinvb[ci]) ? kt : k,
                                      groups_of(k, p.items), bufs, &p));
  }
  return SESSILE_OK;
}

/* The whole smoothing of a small level in one workgroup (bmg_smooth_wg.comp)
 * where it applies: Gauss-Seidel, one row chunk, texel reads, at most
 * wg_max_nodes nodes.  *done = 0 when it does not. */
static sessile_status rec_smooth_wg(const sessile_bmg *mg, sessile_cmd *c, int l, vref b, vref x, int sweeps,
                                    uint32_t flags, int guard, int *done) {
  sessile_la *la = mg->la;
  const bmg_level *v = &mg->lv[l];
  *done = 0;
  if (mg->o.smoother != SESSILE_BMG_GAUSS_SEIDEL || v->nodes > mg->o.wg_max_nodes || v->m->nchunks != 1 ||
      !pass_texel_ok(la, &v->m->chunk[0], x.buf, b.buf, v->dinvb[0]))
    return SESSILE_OK;
  sessile_kernel *k;
  SESSILE_CALL(bmg_kernel(mg, K_BMG_SMOOTH_WG, &k));
  const mat_chunk *ch = &v->m->chunk[0];
  bmg_push p = grid_push(v, guard);
  p.flags = flags, p.sweeps = (uint32_t)sweeps, p.row0 = 0, p.nrows = p.items = ch->nrows;
  p.omega = sessile_push_real_of(mg->o.omega, mg->rb);
  sessile_buffer *bufs[7] = {bmg_s(mg), ch->rowptr, ch->col, ch->val, v->dinvb[0], b.buf, x.buf};
  *done = 1;
  return sessile_cmd_dispatch(c, k, 1, bufs, &p);
}

/* x = a (n reals, whole vectors of the cycle's precision). */
static sessile_status rec_copy(const sessile_bmg *mg, sessile_cmd *c, uint32_t n, vref a, vref x, int guard) {
  vref none = {0};
  if (!mg->f32) return rec_vec(mg->la, c, K_COPY, n, a, x, none, -1, 0, guard);
  sessile_kernel *k;
  SESSILE_CALL(bmg_kernel(mg, K_COPY, &k));
  sessile_buffer *bufs[3] = {mg->stop32, a.buf, x.buf};
  vec_push p = {.n4 = (n + 3) / 4, .n = n, .a_slot = -1, .guard = guard};
  return sessile_cmd_dispatch(c, k, groups_of(k, p.n4), bufs, &p);
}

/* `sweeps` smoothing sweeps of x on level l (after the start from zero when zero). */
static sessile_status rec_smooth(const sessile_bmg *mg, sessile_cmd *c, int l, vref b, vref x, int sweeps,
                                 int zero, int backward, int guard) {
  const bmg_level *v = &mg->lv[l];
  int done;
  uint32_t flags = (zero ? BMG_ZERO : 0) | (backward ? BMG_BACKWARD : 0) | (l == mg->nl - 1 ? BMG_ALTERNATE : 0);
  SESSILE_CALL(rec_smooth_wg(mg, c, l, b, x, sweeps, flags, guard, &done));
  if (done) return SESSILE_OK;
  if (zero) SESSILE_CALL(rec_pass(mg, c, l, b, x, x, 8, BMG_ZERO, guard));
  for (int s = 0; s < sweeps; s++) {
    if (mg->o.smoother == SESSILE_BMG_JACOBI) {
      SESSILE_CALL(rec_pass(mg, c, l, b, x, v->vr, 8, 0, guard));
      SESSILE_CALL(rec_copy(mg, c, 4 * v->nodes, v->vr, x, guard));
      continue;
    }
    int back = backward ^ (s & 1 && l == mg->nl - 1); /* the coarsest alternates */
    for (int q = 0; q < 8; q++) SESSILE_CALL(rec_pass(mg, c, l, b, x, x, back ? 7 - q : q, 0, guard));
  }
  return SESSILE_OK;
}

/* y = b - M x on level l (M: the level's operator, or the fp32 cycle's
 * negated coarsest inverse). */
static sessile_status rec_residual(const sessile_bmg *mg, sessile_cmd *c, int l, const sessile_mat *m, vref b,
                                   vref x, vref y, int guard) {
  sessile_la *la = mg->la;
  const bmg_level *v = &mg->lv[l];
  sessile_kernel *k, *kt;
  SESSILE_CALL(bmg_kernel(mg, K_BMG_RESIDUAL, &k));
  SESSILE_CALL(bmg_kernel(mg, K_BMG_RESIDUAL_TEX, &kt));
  for (uint32_t ci = 0; ci < m->nchunks; ci++) {
    const mat_chunk *ch = &m->chunk[ci];
    bmg_push p = grid_push(v, guard);
    p.row0 = ch->row0, p.nrows = p.items = ch->nrows;
    sessile_buffer *bufs[7] = {bmg_s(mg), ch->rowptr, ch->col, ch->val, b.buf, x.buf, y.buf};
    SESSILE_CALL(sessile_cmd_dispatch(c, pass_texel_ok(la, ch, x.buf, b.buf, NULL) ? kt : k, groups_of(k, p.items), bufs, &p));
  }
  return SESSILE_OK;
}

/* b_{l+1} = R r_l, or x_l += P x_{l+1} (prolong). */
static sessile_status rec_transfer(const sessile_bmg *mg, sessile_cmd *c, int l, vref x, int prolong, int guard) {
  const bmg_level *f = &mg->lv[l], *cv = &mg->lv[l + 1];
  /* the _tex twin reads the fine mask and the gathered vector through texel
   * views where they fit (the same bits) */
  sessile_la *la = mg->la;
  sessile_buffer *gathered = prolong ? cv->vx.buf : f->vr.buf;
  int tex = la->spmv_texel && la_texel_fits(la, f->mask, 4) && la_texel_fits(la, gathered, 16);
  la_kernel_id id = prolong ? (tex ? K_BMG_PROLONG_TEX : K_BMG_PROLONG) : (tex ? K_BMG_RESTRICT_TEX : K_BMG_RESTRICT);
  sessile_kernel *k;
  SESSILE_CALL(bmg_kernel(mg, id, &k));
  const bmg_level *run = prolong ? f : cv, *other = prolong ? cv : f;
  bmg_push p = grid_push(run, guard);
  p.f0 = other->n[0], p.f1 = other->n[1], p.f2 = other->n[2];
  p.items = run->nodes;
  if (prolong) {
    sessile_buffer *bufs[4] = {bmg_s(mg), f->mask, gathered, x.buf};
    return sessile_cmd_dispatch(c, k, groups_of(k, p.items), bufs, &p);
  }
  sessile_buffer *bufs[5] = {bmg_s(mg), f->mask, cv->mask, gathered, cv->vb.buf};
  return sessile_cmd_dispatch(c, k, groups_of(k, p.items), bufs, &p);
}

static sessile_status rec_level(const sessile_bmg *mg, sessile_cmd *c, int l, vref b, vref x, int guard) {
  if (l == mg->nl - 1) {
    vref zero = {mg->zero32, 0};
    if (mg->cinvm && mg->f32) return rec_residual(mg, c, l, mg->cinvm, zero, b, x, guard);
    if (mg->cinvm) return rec_spmv(mg->la, c, mg->cinvm, b, x, guard);
    return rec_smooth(mg, c, l, b, x, mg->o.coarse_sweeps, 1, 0, guard);
  }
  const bmg_level *v = &mg->lv[l], *cv = &mg->lv[l + 1];
  SESSILE_CALL(rec_smooth(mg, c, l, b, x, mg->o.pre, 1, 0, guard));
  int corr = bmg_corrections(mg, l);
  for (int k = 0; k < corr; k++) {
    SESSILE_CALL(rec_residual(mg, c, l, v->m, b, x, v->vr, guard));
    SESSILE_CALL(rec_transfer(mg, c, l, x, 0, guard));
    SESSILE_CALL(rec_level(mg, c, l + 1, cv->vb, cv->vx, guard));
    SESSILE_CALL(rec_transfer(mg, c, l, x, 1, guard));
  }
  return rec_smooth(mg, c, l, b, x, mg->o.post, 0, 1, guard);
}

/* The fp32 cycle's cast in (K_BMG_TO32: r into the finest b32, and the stop
 * flag) or out (K_BMG_TO64: the finest x32 into v). */
static sessile_status rec_cast(const sessile_bmg *mg, sessile_cmd *c, la_kernel_id id, vref v, int guard) {
  sessile_la *la = mg->la;
  const bmg_level *f = &mg->lv[0];
  sessile_kernel *k;
  SESSILE_CALL(la_kernel(la, id, &k));
  bmg_cast_push p = {.n4 = f->nodes, .off4 = v.off4, .guard = guard};
  sessile_buffer *in[4] = {la->scalars, mg->stop32, v.buf, f->b32}, *out[3] = {la->scalars, f->x32, v.buf};
  return sessile_cmd_dispatch(c, k, groups_of(k, p.n4), id == K_BMG_TO32 ? in : out, &p);
}

sessile_status bmg_rec_cycle(const sessile_bmg *mg, sessile_cmd *c, vref r, vref out, int guard) {
  if (!mg->f32) return rec_level(mg, c, 0, r, out, guard);
  const bmg_level *f = &mg->lv[0];
  SESSILE_CALL(rec_cast(mg, c, K_BMG_TO32, r, guard));
  SESSILE_CALL(rec_level(mg, c, 0, f->vb, f->vx, guard < 0 ? -1 : 0));
  return rec_cast(mg, c, K_BMG_TO64, out, guard);
}
