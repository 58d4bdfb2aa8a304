/* Block multigrid setup: the fixed unknowns (unit rows of the fine matrix)
 * and their injection to the coarse levels, the Galerkin products R A P on
 * the host, the inverse diagonal blocks per row chunk, the dense inverse of
 * the coarsest level, and the uploads.  Only the masks depend on which
 * unknowns are fixed; the rest is rebuilt at every setup (a new Jacobian). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "bmg_internal.h"

/* Row a of block row i is the unit row e_(4i+a)? */
static int unit_row(const sessile_bcsr4 *m, uint32_t i, int a) {
  for (uint64_t k = m->rowptr[i]; k < m->rowptr[i + 1]; k++)
    for (int b = 0; b < 4; b++) {
      double v = m->val[16 * k + 4 * a + b], want = m->col[k] == i && b == a ? 1.0 : 0.0;
      if (v != want) return 0;
    }
  return 1;
}

static void free_factors(uint8_t fixed, double f[4]) {
  for (int a = 0; a < 4; a++) f[a] = (fixed >> a) & 1u ? 0.0 : 1.0;
}

/* The fixed unknowns of every level: the unit rows of level 0 and of the
 * caller's operators, injected from the finer level elsewhere (coarse node
 * I is fine node 2I); the device masks are uploaded when they changed. */
static sessile_status set_fixed(sessile_bmg *mg) {
  int changed = !mg->rebuilds;
  for (int l = 0; l < mg->nl; l++) {
    bmg_level *v = &mg->lv[l];
    for (uint32_t i = 0; i < v->nodes; i++) {
      uint8_t f = 0;
      if (l == 0 || v->given) {
        for (int q = 0; q < 4; q++)
          if (unit_row(v->ah, i, q)) f |= (uint8_t)(1u << q);
      } else {
        const bmg_level *u = &mg->lv[l - 1];
        uint32_t c0 = i % v->n[0], c1 = (i / v->n[0]) % v->n[1], c2 = i / (v->n[0] * v->n[1]);
        f = u->fixed[2 * c0 + u->n[0] * (2 * c1 + u->n[1] * 2 * c2)];
      }
      if (f != v->fixed[i]) changed = 1;
      v->fixed[i] = f;
    }
  }
  if (!changed) return SESSILE_OK;
  mg->rebuilds++;
  sessile_status s = SESSILE_OK;
  for (int l = 0; l < mg->nl && s == SESSILE_OK; l++) {
    bmg_level *v = &mg->lv[l];
    uint32_t *m = malloc((size_t)v->nodes * 4);
    if (!m) return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
    for (uint32_t i = 0; i < v->nodes; i++) m[i] = ~(uint32_t)v->fixed[i] & 15u;
    s = sessile_buffer_upload(v->mask, 0, m, (size_t)v->nodes * 4);
    free(m);
  }
  return s;
}

sessile_status sessile_bmg_set_operator(sessile_bmg *mg, int l, const sessile_bcsr4 *a) {
  SESSILE_CHECK(mg && l >= 1 && l < mg->nl, SESSILE_ERR_USAGE, "bmg: level %d has no caller operator (1..%d)", l,
                mg ? mg->nl - 1 : 0);
  SESSILE_CHECK(!a || (a->nbrows == mg->lv[l].nodes && a->nbcols == a->nbrows), SESSILE_ERR_USAGE,
                "bmg: level %d has %u nodes, the operator %u block rows", l, mg->lv[l].nodes, a ? a->nbrows : 0);
  mg->lv[l].given = a;
  mg->ready = 0;
  return SESSILE_OK;
}

static sessile_status copy_bcsr4(const sessile_bcsr4 *a, sessile_bcsr4 *out) {
  if (out->nbrows != a->nbrows || out->nnzb != a->nnzb) {
    sessile_bcsr4_free(out);
    SESSILE_CALL(sessile_bcsr4_alloc(a->nbrows, a->nbcols, a->nnzb, out));
  }
  memcpy(out->rowptr, a->rowptr, ((size_t)a->nbrows + 1) * sizeof *a->rowptr);
  memcpy(out->col, a->col, (size_t)a->nnzb * sizeof *a->col);
  memcpy(out->val, a->val, (size_t)a->nnzb * 16 * sizeof *a->val);
  return SESSILE_OK;
}

sessile_status bmg_galerkin(sessile_bmg *mg, int l) {
  const bmg_level *f = &mg->lv[l];
  bmg_level *c = &mg->lv[l + 1];
  const sessile_bcsr4 *A = f->ah;
  sessile_bcsr4 *C = &c->a;
  memset(C->val, 0, (size_t)C->nnzb * 16 * sizeof *C->val);
  long bad = -1;
#pragma omp parallel for schedule(static)
  for (uint32_t p = 0; p < c->nodes; p++) {
    long cp[3] = {p % c->n[0], (p / c->n[0]) % c->n[1], p / (c->n[0] * c->n[1])};
    double fc[4];
    free_factors(c->fixed[p], fc);
    uint64_t r0 = C->rowptr[p], r1 = C->rowptr[p + 1];
    for (int o = 0; o < BMG_NOFF; o++) {
      long fi3[3] = {2 * cp[0] + f->off[o][0], 2 * cp[1] + f->off[o][1], 2 * cp[2] + f->off[o][2]};
      if (fi3[0] < 0 || fi3[1] < 0 || fi3[2] < 0 || fi3[0] >= f->n[0] || fi3[1] >= f->n[1] || fi3[2] >= f->n[2])
        continue;
      uint32_t fi = (uint32_t)(fi3[0] + f->n[0] * (fi3[1] + (long)f->n[1] * fi3[2]));
      double w = f->off[o][0] || f->off[o][1] || f->off[o][2] ? 0.5 : 1.0, ff[4], sl[4];
      free_factors(f->fixed[fi], ff);
      for (int a = 0; a < 4; a++) sl[a] = w * ff[a] * fc[a];
      if (sl[0] == 0 && sl[1] == 0 && sl[2] == 0 && sl[3] == 0) continue;
      for (uint64_t k = A->rowptr[fi]; k < A->rowptr[fi + 1]; k++) {
        uint32_t j = A->col[k], j3[3] = {j % f->n[0], (j / f->n[0]) % f->n[1], j / (f->n[0] * f->n[1])};
        uint32_t q[2], nq = 1;
        q[0] = (j3[0] >> 1) + c->n[0] * ((j3[1] >> 1) + c->n[1] * (j3[2] >> 1));
        q[1] = ((j3[0] + 1) >> 1) + c->n[0] * (((j3[1] + 1) >> 1) + c->n[1] * ((j3[2] + 1) >> 1));
        if (q[1] != q[0]) nq = 2;
        double fj[4];
        free_factors(f->fixed[j], fj);
        const double *Ak = A->val + 16 * k;
        for (uint32_t t = 0; t < nq; t++) {
          uint64_t pos = r0;
          while (pos < r1 && C->col[pos] != q[t]) pos++;
          if (pos == r1) {
#pragma omp critical
            if (bad < 0 || (long)p < bad) bad = (long)p;
            continue;
          }
          double fq[4], sr[4], *blk = C->val + 16 * pos;
          free_factors(c->fixed[q[t]], fq);
          for (int b = 0; b < 4; b++) sr[b] = (nq == 1 ? 1.0 : 0.5) * fj[b] * fq[b];
          for (int a = 0; a < 4; a++)
            if (sl[a] != 0)
              for (int b = 0; b < 4; b++) blk[4 * a + b] += sl[a] * Ak[4 * a + b] * sr[b];
        }
      }
    }
    for (uint64_t pos = r0; pos < r1; pos++) /* fixed coarse unknowns: unit rows */
      if (C->col[pos] == p)
        for (int a = 0; a < 4; a++)
          if ((c->fixed[p] >> a) & 1u) C->val[16 * pos + 5 * a] = 1.0;
  }
  SESSILE_CHECK(bad < 0, SESSILE_ERR_USAGE,
                "block multigrid: the level-%d matrix couples node %ld's children to nodes outside the "
                "coarse Kuhn pattern (not a Kuhn box matrix?)", l, bad);
  return SESSILE_OK;
}

/* Inverse diagonal blocks of level l, uploaded per row chunk of its matrix. */
static sessile_status level_inverses(sessile_bmg *mg, int l) {
  bmg_level *v = &mg->lv[l];
  const sessile_bcsr4 *a = v->ah;
  long bad = -1;
#pragma omp parallel for schedule(static)
  for (uint32_t i = 0; i < v->nodes; i++) {
    const double *d = NULL;
    for (uint64_t k = a->rowptr[i]; k < a->rowptr[i + 1]; k++)
      if (a->col[k] == i) d = a->val + 16 * k;
    if (!d || !la_block_inverse(4, d, v->dinv + 16 * (size_t)i)) {
#pragma omp critical
      if (bad < 0 || (long)i < bad) bad = (long)i;
    }
  }
  SESSILE_CHECK(bad < 0, SESSILE_ERR_NUMERIC,
                "block multigrid: the diagonal block of node %ld on level %d is missing or singular", bad, l);
  /* the buffers of the last setup when the chunks are the same (fresh device
   * memory costs lavapipe page faults: la.h, sessile_mat_refill_bcsr4) */
  int same = v->ndinv == v->m->nchunks;
  for (uint32_t c = 0; same && c < v->ndinv; c++)
    same = v->dinvb[c] && sessile_buffer_size(v->dinvb[c]) == (size_t)v->m->chunk[c].nrows * 16 * mg->rb;
  if (!same) {
    for (uint32_t c = 0; c < v->ndinv; c++) sessile_buffer_destroy(v->dinvb[c]);
    free(v->dinvb);
    v->ndinv = 0;
    v->dinvb = calloc(v->m->nchunks, sizeof *v->dinvb);
    SESSILE_CHECK(v->dinvb, SESSILE_ERR_NO_MEMORY, "out of host memory");
    v->ndinv = v->m->nchunks;
  }
  for (uint32_t c = 0; c < v->ndinv; c++) {
    const mat_chunk *ch = &v->m->chunk[c];
    size_t n = (size_t)ch->nrows * 16;
    if (!same)
      SESSILE_CALL(sessile_buffer_create(mg->la->gpu, n * mg->rb, SESSILE_BUFFER_DEVICE, &v->dinvb[c]));
    SESSILE_CALL(la_upload_vals(mg->la, v->dinvb[c], v->dinv + 16 * (size_t)ch->row0, n, mg->rb));
  }
  return SESSILE_OK;
}

/* In-place inverse of the n x n row-major matrix a by Gauss-Jordan with
 * partial pivoting (the coarsest level: n <= 4 coarse_dense_max); 0 when singular. */
static int dense_inverse(int n, double *a, double *inv) {
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++) inv[(size_t)i * n + j] = i == j;
  for (int c = 0; c < n; c++) {
    int p = c;
    for (int r = c + 1; r < n; r++)
      if (fabs(a[(size_t)r * n + c]) > fabs(a[(size_t)p * n + c])) p = r;
    double piv = a[(size_t)p * n + c];
    if (!(fabs(piv) > 0) || !isfinite(piv)) return 0;
    if (p != c)
      for (int j = 0; j < n; j++) {
        double t = a[(size_t)p * n + j];
        a[(size_t)p * n + j] = a[(size_t)c * n + j], a[(size_t)c * n + j] = t;
        t = inv[(size_t)p * n + j];
        inv[(size_t)p * n + j] = inv[(size_t)c * n + j], inv[(size_t)c * n + j] = t;
      }
    double s = 1.0 / piv;
    for (int j = 0; j < n; j++) a[(size_t)c * n + j] *= s, inv[(size_t)c * n + j] *= s;
    /* rows in parallel (each element sees the same operations in the same
     * order: the same bits); a's row c is exactly 0 left of c (eliminated,
     * or swapped with a row that was), so its update starts at c */
#pragma omp parallel for schedule(static) if (n >= 128)
    for (int r = 0; r < n; r++) {
      double m = a[(size_t)r * n + c];
      if (r == c || m == 0) continue;
      for (int j = c; j < n; j++) a[(size_t)r * n + j] -= m * a[(size_t)c * n + j];
      for (int j = 0; j < n; j++) inv[(size_t)r * n + j] -= m * inv[(size_t)c * n + j];
    }
  }
  return 1;
}

/* *m holds a's values on the device, in the cycle's precision: refilled in
 * place when it has a's pattern (fresh device memory costs lavapipe page
 * faults), else made anew. */
static sessile_status device_operator(sessile_bmg *mg, const sessile_bcsr4 *a, sessile_mat **m) {
  if (*m && sessile_mat_refill_bcsr4(*m, a) == SESSILE_OK) return SESSILE_OK;
  sessile_mat_destroy(*m);
  *m = NULL;
  return mg->f32 ? la_mat_create_bcsr4_f32(mg->la, a, m) : sessile_mat_create_bcsr4(mg->la, a, m);
}

/* Level 0's fp32 values f from the solver's fp64 matrix a, of the same
 * pattern, on the device: one dispatch per overlap of their row chunks
 * (the fp32 chunks hold twice the rows).  A refill from the host would
 * convert and upload every value at each Newton step: at level 3 (2.8 GB of
 * fp32 values) that cost more than the fp32 cycle saved (docs/la.md). */
static sessile_status cast_fine(sessile_bmg *mg, const sessile_mat *a, sessile_mat *f) {
  sessile_la *la = mg->la;
  sessile_kernel *k = NULL, *kt = NULL;
  SESSILE_CALL(la_kernel(la, K_BMG_VALS32, &k));
  SESSILE_CALL(la_kernel(la, K_BMG_VALS32_TEX, &kt));
  const uint64_t *rp = a->hostb.rowptr;
  uint32_t local = sessile_kernel_local_size(k);
  SESSILE_CALL(sessile_cmd_begin(la->cmd));
  for (uint32_t i = 0; i < a->nchunks; i++)
    for (uint32_t j = 0; j < f->nchunks; j++) {
      const mat_chunk *ca = &a->chunk[i], *cf = &f->chunk[j];
      uint32_t r0 = ca->row0 > cf->row0 ? ca->row0 : cf->row0;
      uint32_t ea = ca->row0 + ca->nrows, ef = cf->row0 + cf->nrows, r1 = ea < ef ? ea : ef;
      if (r0 >= r1 || rp[r1] == rp[r0]) continue;
      /* 4 vec4s per 4x4 block */
      bmg_vals_push p = {.n4 = (uint32_t)(4 * (rp[r1] - rp[r0])), .src4 = (uint32_t)(4 * (rp[r0] - rp[ca->row0])),
                         .dst4 = (uint32_t)(4 * (rp[r0] - rp[cf->row0]))};
      uint32_t groups = (p.n4 + local - 1) / local;
      if (groups > 65535) groups = 65535; /* the kernel strides over the rest */
      sessile_buffer *b[] = {ca->val, cf->val};
      int tex = la->spmv_texel && la_texel_fits(la, ca->val, 16); /* the same bits */
      SESSILE_CALL(sessile_cmd_dispatch(la->cmd, tex ? kt : k, groups, b, &p));
    }
  SESSILE_CALL(sessile_cmd_end(la->cmd));
  return sessile_cmd_submit_wait(la->cmd);
}

/* The coarsest level's dense inverse as a full block matrix. */
static sessile_status coarse_inverse(sessile_bmg *mg) {
  const bmg_level *v = &mg->lv[mg->nl - 1];
  uint32_t nb = v->nodes;
  int n = (int)(4 * nb);
  double *d = calloc((size_t)n * n, sizeof *d);
  if (!mg->cinv) mg->cinv = malloc((size_t)n * n * sizeof *mg->cinv);
  sessile_bcsr4 full = {0};
  double sign = mg->f32 ? -1.0 : 1.0; /* the fp32 cycle applies it as a residual: 0 - (-C) b */
  sessile_status s = d && mg->cinv ? SESSILE_OK : sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  const sessile_bcsr4 *a = v->ah;
  for (uint32_t i = 0; s == SESSILE_OK && i < nb; i++)
    for (uint64_t k = a->rowptr[i]; k < a->rowptr[i + 1]; k++)
      for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++) d[(size_t)(4 * i + r) * n + 4 * a->col[k] + c] = a->val[16 * k + 4 * r + c];
  if (s == SESSILE_OK && !dense_inverse(n, d, mg->cinv))
    s = sessile_error_set(SESSILE_ERR_NUMERIC, "block multigrid: the coarsest level (%u nodes) is singular", nb);
  if (s == SESSILE_OK) s = sessile_bcsr4_alloc(nb, nb, (uint64_t)nb * nb, &full);
  for (uint32_t i = 0; s == SESSILE_OK && i < nb; i++) {
    full.rowptr[i + 1] = (uint64_t)(i + 1) * nb;
    for (uint32_t j = 0; j < nb; j++) {
      uint64_t k = (uint64_t)i * nb + j;
      full.col[k] = j;
      for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++) full.val[16 * k + 4 * r + c] = sign * mg->cinv[(size_t)(4 * i + r) * n + 4 * j + c];
    }
  }
  if (s == SESSILE_OK) s = device_operator(mg, &full, &mg->cinvm);
  sessile_bcsr4_free(&full);
  free(d);
  return s;
}

sessile_status sessile_bmg_setup(sessile_bmg *mg, const sessile_mat *a) {
  SESSILE_CHECK(mg && a, SESSILE_ERR_USAGE, "bmg setup needs a hierarchy and a matrix");
  SESSILE_CHECK(a->la == mg->la && a->kind == MAT_BCSR4 && a->hostb.nbrows == mg->lv[0].nodes, SESSILE_ERR_USAGE,
                "bmg setup: needs a 4x4 block matrix of %u block rows in the same la (got %u rows%s)",
                mg->lv[0].nodes, a->nrows, a->kind == MAT_BCSR4 ? "" : ", not block CSR");
  mg->ready = 0;
  bmg_level *v0 = &mg->lv[0];
  v0->ah = &a->hostb;
  v0->m = a;
  if (mg->f32) { /* the cycle's own fp32 copy of the fine values (a's stay for the solver) */
    v0->m = NULL;
    if (v0->own && v0->own->chunk_limit == la_chunk_limit(mg->la) && v0->own->hostb.nnzb == a->hostb.nnzb &&
        !memcmp(v0->own->hostb.rowptr, a->hostb.rowptr, ((size_t)a->hostb.nbrows + 1) * sizeof *a->hostb.rowptr) &&
        !memcmp(v0->own->hostb.col, a->hostb.col, (size_t)a->hostb.nnzb * sizeof *a->hostb.col))
      SESSILE_CALL(cast_fine(mg, a, v0->own)); /* the same pattern: the values cast on the device */
    else
      SESSILE_CALL(device_operator(mg, &a->hostb, &v0->own));
    v0->m = v0->own;
  }
  for (int l = 1; l < mg->nl; l++) {
    bmg_level *c = &mg->lv[l];
    c->ah = &c->a;
    if (c->given) {
      SESSILE_CALL(copy_bcsr4(c->given, &c->copy));
      c->ah = &c->copy;
    }
  }
  SESSILE_CALL(set_fixed(mg));
  for (int l = 0; l + 1 < mg->nl; l++) {
    bmg_level *c = &mg->lv[l + 1];
    if (!c->given) SESSILE_CALL(bmg_galerkin(mg, l));
    c->m = NULL;
    SESSILE_CALL(device_operator(mg, c->ah, &c->own));
    c->m = c->own;
  }
  for (int l = 0; l < mg->nl; l++) SESSILE_CALL(level_inverses(mg, l));
  if (mg->lv[mg->nl - 1].nodes <= mg->o.coarse_dense_max) SESSILE_CALL(coarse_inverse(mg));
  mg->ready = 1;
  return SESSILE_OK;
}
