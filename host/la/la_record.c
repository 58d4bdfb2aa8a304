/* Recording helpers: turn an la operation into one dispatch with the right
 * bindings, push constants and group count. */
#include "la_internal.h"

uint32_t la_groups(sessile_la *la, la_kernel_id id, uint32_t items) {
  uint32_t local = sessile_kernel_local_size(la->k[id]);
  return (items + local - 1) / local;
}

uint32_t la_reduce_groups(sessile_la *la, uint32_t n4) {
  uint32_t g = la_groups(la, K_DOT, n4);
  if (g > MAXG) g = MAXG;
  return g ? g : 1;
}

uint32_t la_fused_groups(sessile_la *la, la_kernel_id id, uint32_t items) {
  uint32_t g = la_groups(la, id, items);
  if (g > la->fused_groups) g = la->fused_groups;
  return g ? g : 1;
}

sessile_status rec_vec(sessile_la *la, sessile_cmd *c, la_kernel_id id, uint32_t n, vref a,
                       vref b, vref w, int a_slot, uint32_t flags, int guard) {
  sessile_kernel *k;
  SESSILE_CALL(la_kernel(la, id, &k));
  sessile_buffer *bufs[4] = {la->scalars, a.buf, b.buf, w.buf};
  vec_push p = {.n4 = (n + 3) / 4, .n = n, .off0 = a.off4, .off1 = b.off4, .off2 = w.off4,
                .a_slot = a_slot, .flags = flags, .guard = guard};
  return sessile_cmd_dispatch(c, k, la_groups(la, id, p.n4), bufs, &p);
}

sessile_status rec_dot(sessile_la *la, sessile_cmd *c, uint32_t n, vref x, vref y, uint32_t set,
                       int guard, uint32_t *count) {
  sessile_kernel *k;
  SESSILE_CALL(la_kernel(la, K_DOT, &k));
  sessile_buffer *bufs[4] = {la->scalars, x.buf, y.buf, la->partials};
  vec_push p = {.n4 = (n + 3) / 4, .n = n, .off0 = x.off4, .off1 = y.off4, .off2 = set,
                .a_slot = -1, .guard = guard};
  *count = la_reduce_groups(la, p.n4);
  return sessile_cmd_dispatch(c, k, *count, bufs, &p);
}

sessile_status rec_reduce(sessile_la *la, sessile_cmd *c, uint32_t count, uint32_t first_set,
                          uint32_t nsets, int dst_slot, int sqrt_flag, int guard) {
  sessile_kernel *k;
  SESSILE_CALL(la_kernel(la, K_REDUCE, &k));
  sessile_buffer *bufs[2] = {la->scalars, la->partials};
  reduce_push p = {.count = count, .first_set = first_set, .dst_slot = dst_slot,
                   .sqrt_flag = (uint32_t)sqrt_flag, .guard = guard};
  return sessile_cmd_dispatch(c, k, nsets, bufs, &p);
}

/* Texel-buffer SpMV when the matrix allows it and x's whole buffer fits one
 * texel view (x may live inside a larger work buffer). */
static int use_texel(sessile_la *la, const sessile_mat *a, vref x) {
  return a->kind == MAT_CSR && a->texel && la_texel_fits(la, x.buf, la->real_bytes);
}

int la_texel_fits(const sessile_la *la, const sessile_buffer *b, uint32_t texel_bytes) {
  (void)la;
  return sessile_buffer_texels_fit(b, texel_bytes);
}

int la_block_texel_ok(const sessile_la *la, const mat_chunk *ch, sessile_buffer *x) {
  return la->spmv_texel && la_texel_fits(la, ch->rowptr, 4) && la_texel_fits(la, ch->col, 4) &&
         la_texel_fits(la, ch->val, 16) && la_texel_fits(la, x, 16);
}

/* One dispatch per row chunk (mat.c): the chunk's rows of y, x read whole;
 * a block chunk through texel views where they fit (the same bits). */
sessile_status rec_spmv(sessile_la *la, sessile_cmd *c, const sessile_mat *a, vref x, vref y,
                        int guard) {
  if (a->kind == MAT_STENCIL7) return rec_stencil7(la, c, a, x, y, guard, NULL);
  if (a->kind == MAT_STENCIL7_CUT) return rec_stencil7_cut(la, c, a, x, y, guard, NULL);
  la_kernel_id id = a->kind != MAT_CSR ? K_SPMV_BCSR4 : use_texel(la, a, x) ? K_SPMV_CSR_TEX : K_SPMV_CSR;
  sessile_kernel *k;
  SESSILE_CALL(la_kernel(la, id, &k));
  uint32_t per = a->kind == MAT_CSR ? a->rows_per : 1;
  uint32_t scale = a->kind == MAT_CSR ? 4 : 1; /* CSR offsets in reals, BCSR in REAL4 */
  sessile_kernel *kt = NULL;
  if (a->kind != MAT_CSR) SESSILE_CALL(la_kernel(la, K_SPMV_BCSR4_TEX, &kt));
  for (uint32_t i = 0; i < a->nchunks; i++) {
    const mat_chunk *ch = &a->chunk[i];
    sessile_buffer *bufs[6] = {la->scalars, ch->rowptr, ch->col, ch->val, x.buf, y.buf};
    spmv_push p = {.nrows = ch->nrows, .xoff = x.off4 * scale, .yoff = y.off4 * scale + ch->row0,
                   .guard = guard, .rows_per = per};
    uint32_t items = (ch->nrows + per - 1) / per;
    sessile_kernel *kc = kt && la_block_texel_ok(la, ch, x.buf) ? kt : k;
    SESSILE_CALL(sessile_cmd_dispatch(c, kc, la_groups(la, id, items), bufs, &p));
  }
  return SESSILE_OK;
}

sessile_status rec_spmv_dot(sessile_la *la, sessile_cmd *c, const sessile_mat *a, vref x, vref y,
                            int guard, uint32_t *count) {
  if (a->kind == MAT_STENCIL7) return rec_stencil7(la, c, a, x, y, guard, count);
  if (a->kind == MAT_STENCIL7_CUT) return rec_stencil7_cut(la, c, a, x, y, guard, count);
  /* Block or split matrices: SpMV, then a separate dot (the fused kernel's
   * partials cover one dispatch). */
  if (a->kind != MAT_CSR || a->nchunks > 1) {
    SESSILE_CALL(rec_spmv(la, c, a, x, y, guard));
    return rec_dot(la, c, a->nrows, x, y, 0, guard, count);
  }
  sessile_kernel *k;
  la_kernel_id id = use_texel(la, a, x) ? K_SPMV_CSR_TEX_DOT : K_SPMV_CSR_DOT;
  SESSILE_CALL(la_kernel(la, id, &k));
  const mat_chunk *ch = &a->chunk[0];
  sessile_buffer *bufs[7] = {la->scalars, ch->rowptr, ch->col, ch->val, x.buf, y.buf, la->partials};
  spmv_push p = {.nrows = a->nrows, .xoff = x.off4 * 4, .yoff = y.off4 * 4, .guard = guard,
                 .rows_per = a->rows_per};
  uint32_t items = (a->nrows + a->rows_per - 1) / a->rows_per;
  *count = la_groups(la, id, items);
  if (*count > MAXG) *count = MAXG;
  return sessile_cmd_dispatch(c, k, *count, bufs, &p);
}
