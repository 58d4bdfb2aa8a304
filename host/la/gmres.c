/* Restarted GMRES(m) on the device with right preconditioning by any pc
 * object and modified Gram-Schmidt.  The first GM_ZKEEP preconditioned
 * vectors z_j = M^-1 v_j are kept (as flexible GMRES keeps them), so a cycle
 * of at most that many iterations updates x += sum_j y_j z_j without the
 * preconditioner's application to V y that the textbook right-preconditioned
 * update takes (one multigrid cycle of the fluid's 8-9 a solve; and the
 * update is then the one the Arnoldi relation A z_j = V h_j holds for, even
 * where M^-1, an fp32 cycle, is linear only to rounding).  Longer cycles
 * take the textbook update.  The basis lives in one buffer (m+1 vectors), the
 * Hessenberg matrix, Givens rotations and the small triangular solve in the
 * scalar slots; a restart cycle is recorded in segments of iterations
 * (gm_run), each submitted while the cycle runs, so a solve that converges
 * early does not pay for the rest of the cycle's dispatches. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "pc_internal.h"

static sessile_status gm_op(sessile_la *la, sessile_cmd *c, uint32_t op, uint32_t j, uint32_t m) {
  gmres_op_push pc = {.op = op, .j = j, .m = m};
  sessile_buffer *sb[1] = {la->scalars};
  return sessile_cmd_dispatch(c, la->k[K_GMRES_SCALAR], 1, sb, &pc);
}

static int hslot(uint32_t i, uint32_t j, uint32_t m) { return GM_BASE + (int)(i + j * (m + 1)); }
/* y_i's slot (gmres_scalar.comp's Y(i)). */
static int yslot(uint32_t i, uint32_t m) { return GM_BASE + (int)((m + 1) * m + (m + 1) + 2 * m + i); }

/* The Krylov basis: m + 1 vectors one after another in one buffer, or, when
 * that buffer would exceed the per-buffer limit (maxStorageBufferRange:
 * 128 MiB on lavapipe, 2.6 GB wanted at the fluid's level 3), one buffer
 * each. */
typedef struct gm_basis {
  sessile_buffer *one;
  sessile_buffer **each;
  uint32_t n4;
} gm_basis;
static vref vj(const gm_basis *B, uint32_t j) {
  return B->one ? (vref){B->one, j * B->n4} : (vref){B->each[j], 0};
}

/* The kept z_j: at most this many (16 vectors: 0.8 GB at the fluid's
 * level 3, where its multigrid takes 9-12 iterations a solve). */
enum { GM_ZKEEP = 16 };

sessile_status la_vstore_ensure(sessile_la *la, la_vstore *v, uint32_t count, uint64_t per, int split) {
  if (split) {
    int fits = v->neach >= count;
    for (uint32_t i = 0; fits && i < count; i++) fits = sessile_buffer_size(v->each[i]) >= per;
    sessile_buffer_destroy(v->one); /* not both at once */
    v->one = NULL;
    if (fits) return SESSILE_OK;
    for (uint32_t i = 0; i < v->neach; i++) sessile_buffer_destroy(v->each[i]);
    free(v->each);
    v->neach = 0;
    v->each = calloc(count, sizeof *v->each);
    SESSILE_CHECK(v->each, SESSILE_ERR_NO_MEMORY, "out of host memory for GMRES");
    v->neach = count;
    for (uint32_t i = 0; i < count; i++)
      SESSILE_CALL(sessile_buffer_create(la->gpu, per, SESSILE_BUFFER_DEVICE, &v->each[i]));
    return SESSILE_OK;
  }
  if (v->one && sessile_buffer_size(v->one) >= (size_t)count * per) return SESSILE_OK;
  la_vstore_free(v);
  return sessile_buffer_create(la->gpu, (size_t)count * per, SESSILE_BUFFER_DEVICE, &v->one);
}

void la_vstore_free(la_vstore *v) {
  sessile_buffer_destroy(v->one);
  for (uint32_t i = 0; i < v->neach; i++) sessile_buffer_destroy(v->each[i]);
  free(v->each);
  memset(v, 0, sizeof *v);
}

/* The cycle in pieces: the start (residual, beta, v0), iterations j0..j1-1,
 * the end (back substitution, x update, the cycle's convergence test). */
#define VJ(j) vj(V, (uint32_t)(j))
/* x_zero: x is zero, r = b (b - A 0 is b, bit for bit). */
static sessile_status rec_start(sessile_la *la, sessile_cmd *c, const sessile_mat *a, const sessile_vec *b,
                                const sessile_vec *x, const gm_basis *V, uint32_t m, int x_zero) {
  uint32_t n = a->nrows, cnt;
  vref none = {0};
  if (x_zero) {
    SESSILE_CALL(rec_vec(la, c, K_COPY, n, vref_of(b), VJ(0), none, -1, 0, S_STOP));
  } else {
    SESSILE_CALL(rec_spmv(la, c, a, vref_of(x), VJ(1), S_STOP));
    SESSILE_CALL(rec_vec(la, c, K_WAXPY, n, VJ(1), vref_of(b), VJ(0), -1, COEF_NEG, S_STOP));
  }
  SESSILE_CALL(rec_dot(la, c, n, VJ(0), VJ(0), 0, S_STOP, &cnt));
  SESSILE_CALL(rec_reduce(la, c, cnt, 0, 1, GM_BETA, 1, S_STOP));
  SESSILE_CALL(gm_op(la, c, 0, 0, m));
  return rec_vec(la, c, K_SCALE, n, VJ(0), none, none, GM_INV, 0, GM_DONE);
}

/* z_j's place: kept (Z, j < nz) or the scratch z. */
static sessile_status rec_iters(sessile_la *la, sessile_cmd *c, const sessile_mat *a, const sessile_pc *pc,
                                const gm_basis *V, const gm_basis *Z, uint32_t nz, sessile_vec *z, uint32_t m,
                                uint32_t j0, uint32_t j1) {
  uint32_t n = a->nrows, cnt;
  vref none = {0};
  for (uint32_t j = j0; j < j1; j++) {
    vref zj = j < nz ? vj(Z, j) : vref_of(z);
    SESSILE_CALL(rec_pc(pc, c, VJ(j), zj, GM_DONE));
    SESSILE_CALL(rec_spmv(la, c, a, zj, VJ(j + 1), GM_DONE));
    for (uint32_t i = 0; i <= j; i++) { /* modified Gram-Schmidt */
      SESSILE_CALL(rec_dot(la, c, n, VJ(j + 1), VJ(i), 0, GM_DONE, &cnt));
      SESSILE_CALL(rec_reduce(la, c, cnt, 0, 1, hslot(i, j, m), 0, GM_DONE));
      SESSILE_CALL(rec_vec(la, c, K_AXPY, n, VJ(i), VJ(j + 1), none, hslot(i, j, m), COEF_NEG, GM_DONE));
    }
    SESSILE_CALL(rec_dot(la, c, n, VJ(j + 1), VJ(j + 1), 0, GM_DONE, &cnt));
    SESSILE_CALL(rec_reduce(la, c, cnt, 0, 1, hslot(j + 1, j, m), 1, GM_DONE));
    SESSILE_CALL(gm_op(la, c, 1, j, m));
    SESSILE_CALL(rec_vec(la, c, K_SCALE, n, VJ(j + 1), none, none, GM_INV, 0, GM_DONE));
  }
  return SESSILE_OK;
}

static sessile_status rec_end(sessile_la *la, sessile_cmd *c, const sessile_mat *a, const sessile_vec *x,
                              const sessile_pc *pc, const gm_basis *V, sessile_vec *z, const sessile_vec *ones,
                              uint32_t m) {
  uint32_t n = a->nrows, n4 = (n + 3) / 4;
  vref none = {0};
  SESSILE_CALL(gm_op(la, c, 2, 0, m));
  if (!V->one) { /* split basis: z = sum_i y_i v_i (y_i = 0 for i >= k), then as below */
    SESSILE_CALL(rec_vec(la, c, K_FILL, n, vref_of(z), none, none, GM_ZERO, 0, S_STOP));
    for (uint32_t i = 0; i < m; i++)
      SESSILE_CALL(rec_vec(la, c, K_AXPY, n, VJ(i), vref_of(z), none, yslot(i, m), 0, S_STOP));
    if (pc->diag) { /* x += D⁻¹ z */
      SESSILE_CALL(rec_vec(la, c, K_PMUL, n, vref_of(z), vref_of(pc->diag), VJ(m), -1, 0, S_STOP));
    } else { /* v_m = M⁻¹ z */
      SESSILE_CALL(rec_pc(pc, c, vref_of(z), VJ(m), S_STOP));
    }
    SESSILE_CALL(rec_vec(la, c, K_AXPY, n, VJ(m), vref_of(x), none, -1, 0, S_STOP));
    return gm_op(la, c, 3, 0, m);
  }
  vec_push p = {.n4 = n4, .n = n, .off0 = n4, .off1 = m, .a_slot = -1, .guard = S_STOP};
  if (pc->diag) { /* x += D⁻¹ V y in one pass */
    sessile_buffer *ub[4] = {la->scalars, V->one, pc->diag->buf, x->buf};
    SESSILE_CALL(sessile_cmd_dispatch(c, la->k[K_GMRES_UPDATE], la_groups(la, K_GMRES_UPDATE, n4), ub, &p));
  } else { /* z = V y (with D⁻¹ = ones), v_m = M⁻¹ z (v_m is free now), x += v_m */
    SESSILE_CALL(rec_vec(la, c, K_FILL, n, vref_of(z), none, none, GM_ZERO, 0, S_STOP));
    sessile_buffer *ub[4] = {la->scalars, V->one, ones->buf, z->buf};
    SESSILE_CALL(sessile_cmd_dispatch(c, la->k[K_GMRES_UPDATE], la_groups(la, K_GMRES_UPDATE, n4), ub, &p));
    SESSILE_CALL(rec_pc(pc, c, vref_of(z), VJ(m), S_STOP));
    SESSILE_CALL(rec_vec(la, c, K_AXPY, n, VJ(m), vref_of(x), none, -1, 0, S_STOP));
  }
  return gm_op(la, c, 3, 0, m);
}
/* The end of a cycle of at most nz iterations: x += sum_{i<nz} y_i z_i
 * (y_i = 0 for i >= k). */
static sessile_status rec_end_z(sessile_la *la, sessile_cmd *c, const sessile_mat *a, const sessile_vec *x,
                                const gm_basis *Z, uint32_t nz, const sessile_vec *ones, uint32_t m) {
  uint32_t n = a->nrows, n4 = (n + 3) / 4;
  vref none = {0};
  SESSILE_CALL(gm_op(la, c, 2, 0, m));
  if (!Z->one) {
    for (uint32_t i = 0; i < nz; i++)
      SESSILE_CALL(rec_vec(la, c, K_AXPY, n, vj(Z, i), vref_of(x), none, yslot(i, m), 0, S_STOP));
  } else { /* one pass over the k kept vectors (k <= nz: the host chose this end) */
    vec_push p = {.n4 = n4, .n = n, .off0 = n4, .off1 = m, .a_slot = -1, .guard = S_STOP};
    sessile_buffer *ub[4] = {la->scalars, Z->one, ones->buf, x->buf};
    SESSILE_CALL(sessile_cmd_dispatch(c, la->k[K_GMRES_UPDATE], la_groups(la, K_GMRES_UPDATE, n4), ub, &p));
  }
  return gm_op(la, c, 3, 0, m);
}
#undef VJ

/* A cycle's iterations are recorded in segments, submitted one after the
 * other until the cycle is done (GM_DONE): the first GM_SEG_FIRST
 * iterations with the start, then GM_SEG_NEXT at a time.  One recording of
 * all m iterations, each dispatch guarded, cost a converged solve its
 * remaining iterations' dispatches anyway (lavapipe pays ~0.1 ms a dispatch
 * that returns at once): 10 useful iterations of 50 were 17 600 dispatches
 * where 2 900 did work (docs/la.md, "GMRES").  Segments of 2: an inexact
 * Newton step's solve of 1-4 iterations paid for a first segment of 8
 * (docs/fluid.md, "Each Newton step's linear tolerance").  The same
 * operations in the same order, so the same bits. */
enum { GM_SEG_FIRST = 2, GM_SEG_NEXT = 2 };

typedef struct gm_segs {
  sessile_cmd **cmd; /* [0]: the end; [1 + k]: segment k (recorded when first needed) */
  uint8_t *done;     /* [k]: segment k is recorded */
  uint32_t nseg;
  sessile_cmd *end_z; /* the end from the kept z_j, recorded for end_nz of them (0: not yet) */
  uint32_t end_nz;
  sessile_cmd *first0; /* x_zero: the first cycle's segment 0, started from r = b */
  uint8_t first0_done;
} gm_segs;

static uint32_t seg_lo(uint32_t k, uint32_t m) {
  uint32_t j = k == 0 ? 0 : GM_SEG_FIRST + (k - 1) * GM_SEG_NEXT;
  return j < m ? j : m;
}
static uint32_t seg_hi(uint32_t k, uint32_t m) { return seg_lo(k + 1, m); }

static sessile_status gm_run(sessile_la *la, const sessile_ksp_options *o, const sessile_mat *a,
                             const sessile_vec *b, sessile_vec *x, const sessile_pc *pc,
                             const gm_basis *V, const gm_basis *Z, uint32_t nz, sessile_vec *z,
                             const sessile_vec *ones, uint32_t m, gm_segs *sg, sessile_solve_result *res) {
  sessile_kernel *k;
  static const la_kernel_id ids[] = {K_GMRES_SCALAR, K_GMRES_UPDATE, K_DOT, K_REDUCE, K_WAXPY,
                                     K_PMUL, K_AXPY, K_SCALE, K_COPY};
  for (size_t i = 0; i < sizeof ids / sizeof ids[0]; i++) SESSILE_CALL(la_kernel(la, ids[i], &k));
  SESSILE_CALL(la_kernel(la, a->kind == MAT_CSR ? K_SPMV_CSR : K_SPMV_BCSR4, &k));
  la_solver_reset(la, o);
  /* ‖b‖² for the tolerance, then cycles until the device stops. */
  uint32_t cnt;
  SESSILE_CALL(sessile_cmd_begin(la->cmd));
  SESSILE_CALL(rec_dot(la, la->cmd, a->nrows, vref_of(b), vref_of(b), 0, -1, &cnt));
  SESSILE_CALL(rec_reduce(la, la->cmd, cnt, 0, 1, S_BB, 0, -1));
  SESSILE_CALL(sessile_cmd_end(la->cmd));
  SESSILE_CALL(sessile_cmd_submit_wait(la->cmd));
  la_scalar_set(la, S_TOL2, o->rtol * o->rtol * la_scalar_read(la, S_BB));
  la_scalar_set(la, GM_ZERO, 0.0);
  SESSILE_CALL(sessile_cmd_begin(sg->cmd[0]));
  SESSILE_CALL(rec_end(la, sg->cmd[0], a, x, pc, V, z, ones, m));
  SESSILE_CALL(sessile_cmd_end(sg->cmd[0]));
  /* Each cycle advances at least one iteration until the device stops, so
   * this bound is never reached by a correct solver: it guards against hangs. */
  long bound = (long)o->max_it + 4;
  for (long cyc = 0; la_scalar_read(la, S_STOP) == STOP_RUNNING; cyc++) {
    SESSILE_CHECK(cyc < bound, SESSILE_ERR_INTERNAL, "gmres did not stop after %ld cycles (max_it %d)", cyc,
                  o->max_it);
    uint32_t ran = 0; /* the cycle's iterations are at most this */
    for (uint32_t s = 0; s < sg->nseg; s++) {
      int zero = s == 0 && cyc == 0 && o->x_zero; /* only the first cycle starts from x = 0 */
      sessile_cmd *c = zero ? sg->first0 : sg->cmd[1 + s];
      uint8_t *done = zero ? &sg->first0_done : &sg->done[s];
      if (!*done) {
        SESSILE_CALL(sessile_cmd_begin(c));
        if (s == 0) SESSILE_CALL(rec_start(la, c, a, b, x, V, m, zero));
        SESSILE_CALL(rec_iters(la, c, a, pc, V, Z, nz, z, m, seg_lo(s, m), seg_hi(s, m)));
        SESSILE_CALL(sessile_cmd_end(c));
        *done = 1;
      }
      SESSILE_CALL(sessile_cmd_submit_wait(c));
      ran = seg_hi(s, m);
      if (la_scalar_read(la, GM_DONE) != 0) break;
    }
    if (ran <= nz) { /* every z_j of the cycle is kept */
      if (sg->end_nz != ran) {
        SESSILE_CALL(sessile_cmd_begin(sg->end_z));
        SESSILE_CALL(rec_end_z(la, sg->end_z, a, x, Z, ran, ones, m));
        SESSILE_CALL(sessile_cmd_end(sg->end_z));
        sg->end_nz = ran;
      }
      SESSILE_CALL(sessile_cmd_submit_wait(sg->end_z));
    } else {
      SESSILE_CALL(sessile_cmd_submit_wait(sg->cmd[0]));
    }
    if (o->monitor)
      la_monitorf(o, "gmres %5d  |r|/|b| %.6e", (int)la_scalar_read(la, S_ITER),
                  la_scalar_read(la, GM_EST) / sqrt(la_scalar_read(la, S_BB)));
  }
  la_solver_outcome(la, res, la_scalar_read(la, GM_EST) / sqrt(la_scalar_read(la, S_BB)));
  return SESSILE_OK;
}

sessile_status la_gmres(sessile_la *la, const sessile_ksp_options *o, const sessile_mat *a,
                        const sessile_vec *b, sessile_vec *x, const sessile_pc *pc,
                        sessile_solve_result *res) {
  uint32_t n4 = (a->nrows + 3) / 4;
  uint32_t m = (uint32_t)o->restart;
  /* The basis in one buffer when it fits the per-buffer limit (the range,
   * or the la's max_matrix_chunk_bytes for tests), else one buffer a vector. */
  uint64_t per = (uint64_t)n4 * 4 * la->real_bytes;
  uint64_t range = sessile_gpu_info_of(la->gpu)->max_storage_buffer_range, lim = la_chunk_limit(la);
  SESSILE_CHECK(per <= range, SESSILE_ERR_TOO_LARGE,
                "GMRES: one basis vector of %llu bytes exceeds maxStorageBufferRange (%llu): use bicgstab",
                (unsigned long long)per, (unsigned long long)range);
  int split = (uint64_t)(m + 1) * per > lim;
  if (split)
    la_monitorf(o, "gmres: the basis (%u vectors of %llu bytes) exceeds the per-buffer limit: one buffer a vector",
                m + 1, (unsigned long long)per);
  gm_segs sg = {0};
  while (seg_lo(sg.nseg, m) < m) sg.nseg++;
  /* the basis, the kept z_j, z and ones of the last solve when they fit
   * (la_internal.h); no z_j kept for a diagonal pc (its update is one pass) */
  uint32_t nz = pc->diag || la->gm_textbook ? 0 : m < GM_ZKEEP ? m : GM_ZKEEP;
  int zsplit = (uint64_t)nz * per > lim;
  sessile_status s = la_vstore_ensure(la, &la->gm_v, m + 1, per, split);
  if (s == SESSILE_OK && nz) s = la_vstore_ensure(la, &la->gm_zs, nz, per, zsplit);
  if (s == SESSILE_OK && (!la->gm_z || la->gm_z->n != a->nrows)) {
    sessile_vec_destroy(la->gm_z);
    la->gm_z = NULL;
    s = sessile_vec_create(la, a->nrows, &la->gm_z);
  }
  if (s == SESSILE_OK && !pc->diag && (!la->gm_ones || la->gm_ones->n != a->nrows)) {
    sessile_vec_destroy(la->gm_ones);
    la->gm_ones = NULL;
    s = la_ones(la, a->nrows, &la->gm_ones);
  }
  gm_basis V = {la->gm_v.one, la->gm_v.each, n4}, Z = {la->gm_zs.one, la->gm_zs.each, n4};
  sessile_vec *z = la->gm_z, *ones = pc->diag ? NULL : la->gm_ones;
  if (s == SESSILE_OK) {
    sg.cmd = calloc(1 + (size_t)sg.nseg, sizeof *sg.cmd);
    sg.done = calloc(sg.nseg, 1);
    if (!sg.cmd || !sg.done) s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for GMRES");
  }
  for (uint32_t i = 0; s == SESSILE_OK && i <= sg.nseg; i++) s = sessile_cmd_create(la->gpu, &sg.cmd[i]);
  if (s == SESSILE_OK && nz) s = sessile_cmd_create(la->gpu, &sg.end_z);
  if (s == SESSILE_OK && o->x_zero) s = sessile_cmd_create(la->gpu, &sg.first0);
  if (s == SESSILE_OK) s = gm_run(la, o, a, b, x, pc, &V, &Z, nz, z, ones, m, &sg, res);
  for (uint32_t i = 0; sg.cmd && i <= sg.nseg; i++) sessile_cmd_destroy(sg.cmd[i]);
  sessile_cmd_destroy(sg.end_z);
  sessile_cmd_destroy(sg.first0);
  free(sg.cmd), free(sg.done);
  return s;
}
