/* ILU(0) on the device.  The factors come from the host (sessile_ref_ilu0_*,
 * double, once per matrix); here they are split into the strict lower part L
 * and the upper part U, each row grouped by its level in the dependency graph
 * (level scheduling: a row's level is 1 + the largest level of the rows it
 * reads, 0 when it reads none), and uploaded in the context precision.
 *
 * Device layout, one set per triangle, rows in level order (position p):
 *   order[p]  the row solved at position p
 *   rowptr[p] its entries, col/val (BCSR4: a value is a 4x4 block, 4 REAL4 rows)
 * U rows start with the inverse pivot (1/u_ii, or the dense inverse of the
 * 4x4 pivot block), then the strict upper entries.  An application z = (LU)⁻¹ r
 * is one dispatch per level of L (r -> z) then one per level of U (z -> z in
 * place: a row reads only its own y_i and the x_j of earlier levels). */
#include <stdlib.h>
#include <string.h>
#include "la_internal.h"
#include "sessile/la/la_ref.h"

typedef struct {
  uint32_t nlev;
  uint32_t *levptr; /* host: nlev + 1 positions */
  sessile_buffer *order, *rowptr, *col, *val;
} ilu_tri;

struct la_ilu {
  int bs;       /* 1: CSR, 4: BCSR4 */
  uint32_t n;   /* rows (block rows for BCSR4) */
  ilu_tri t[2]; /* 0: L, 1: U */
  double seconds;
};

void la_ilu_destroy(la_ilu *f) {
  if (!f) return;
  for (int i = 0; i < 2; i++) {
    free(f->t[i].levptr);
    sessile_buffer_destroy(f->t[i].order);
    sessile_buffer_destroy(f->t[i].rowptr);
    sessile_buffer_destroy(f->t[i].col);
    sessile_buffer_destroy(f->t[i].val);
  }
  free(f);
}

static sessile_status upload_u32(sessile_la *la, const uint32_t *v, size_t n, sessile_buffer **b) {
  size_t bytes = (n ? n : 1) * sizeof *v;
  SESSILE_CALL(sessile_buffer_create(la->gpu, bytes, SESSILE_BUFFER_DEVICE, b));
  return n ? sessile_buffer_upload(*b, 0, v, n * sizeof *v) : SESSILE_OK;
}

/* Builds one triangle (upper = 0: strict lower part; 1: inverse pivot and
 * strict upper part) from the factors `lu` in the pattern (rowptr, col). */
static sessile_status build_tri(sessile_la *la, la_ilu *f, int upper, const uint64_t *rowptr,
                                const uint32_t *col, const double *lu, uint64_t limit, ilu_tri *t) {
  const uint32_t n = f->n;
  const int b2 = f->bs * f->bs;
  uint32_t *lev = malloc(((size_t)n + 1) * sizeof *lev);
  uint32_t *order = malloc(((size_t)n + 1) * sizeof *order);
  uint32_t *rp = malloc(((size_t)n + 1) * sizeof *rp);
  uint32_t *cnt = NULL, *c = NULL;
  double *v = NULL;
  sessile_status s = SESSILE_OK;
  if (!lev || !order || !rp) s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "ILU(0): out of host memory");
  /* Levels: L rows in increasing order, U rows in decreasing order. */
  uint32_t nlev = 0;
  uint64_t total = 0;
  for (uint32_t q = 0; s == SESSILE_OK && q < n; q++) {
    uint32_t i = upper ? n - 1 - q : q, l = 0;
    for (uint64_t k = rowptr[i]; k < rowptr[i + 1]; k++) {
      uint32_t j = col[k];
      if (upper ? j > i : j < i) {
        if (lev[j] + 1 > l) l = lev[j] + 1;
        total++;
      }
    }
    lev[i] = l;
    if (l + 1 > nlev) nlev = l + 1;
  }
  if (upper) total += n; /* the inverse pivots */
  if (s == SESSILE_OK && total >= UINT32_MAX / 16)
    s = sessile_error_set(SESSILE_ERR_TOO_LARGE, "ILU(0): too many entries for 32-bit indices");
  /* The factors are not split into row chunks (their level-scheduled solves
   * would need a chunk lookup per row): refuse what exceeds the matrix's
   * per-buffer limit rather than fail inside buffer creation. */
  if (s == SESSILE_OK && (uint64_t)total * b2 * la->real_bytes > limit)
    s = sessile_error_set(SESSILE_ERR_TOO_LARGE,
                          "ILU(0): the %s factor needs %llu bytes of values, over the per-buffer "
                          "limit of %llu bytes (maxStorageBufferRange, or "
                          "max_matrix_chunk_bytes when set); ILU(0) factors are not split "
                          "into row chunks: use Jacobi for this matrix",
                          upper ? "upper" : "lower",
                          (unsigned long long)((uint64_t)total * b2 * la->real_bytes),
                          (unsigned long long)limit);
  if (s == SESSILE_OK) {
    cnt = calloc((size_t)nlev + 2, sizeof *cnt);
    c = malloc((size_t)(total ? total : 1) * sizeof *c);
    v = malloc((size_t)(total ? total : 1) * b2 * sizeof *v);
    t->levptr = malloc(((size_t)nlev + 1) * sizeof *t->levptr);
    if (!cnt || !c || !v || !t->levptr)
      s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "ILU(0): out of host memory");
  }
  if (s == SESSILE_OK) {
    /* Counting sort by level, stable in row index. */
    for (uint32_t i = 0; i < n; i++) cnt[lev[i] + 1]++;
    for (uint32_t l = 0; l < nlev; l++) cnt[l + 1] += cnt[l];
    memcpy(t->levptr, cnt, ((size_t)nlev + 1) * sizeof *cnt);
    for (uint32_t i = 0; i < n; i++) order[cnt[lev[i]]++] = i;
    t->nlev = nlev;
    uint32_t e = 0;
    for (uint32_t p = 0; p < n && s == SESSILE_OK; p++) {
      uint32_t i = order[p];
      rp[p] = e;
      if (upper) { /* the inverse pivot first */
        uint64_t d = rowptr[i];
        while (col[d] != i) d++; /* present: the factorisation checked it */
        if (f->bs == 1) v[e] = 1.0 / lu[d];
        else if (!la_block_inverse(4, lu + d * 16, v + (size_t)e * 16))
          s = sessile_error_set(SESSILE_ERR_NUMERIC, "ILU(0): singular 4x4 pivot block at block row %u", i);
        c[e++] = i;
      }
      for (uint64_t k = rowptr[i]; k < rowptr[i + 1]; k++) {
        uint32_t j = col[k];
        if (upper ? j > i : j < i) {
          c[e] = j;
          memcpy(v + (size_t)e * b2, lu + k * b2, (size_t)b2 * sizeof *v);
          e++;
        }
      }
    }
    rp[n] = e;
  }
  if (s == SESSILE_OK) s = upload_u32(la, order, n, &t->order);
  if (s == SESSILE_OK) s = upload_u32(la, rp, (size_t)n + 1, &t->rowptr);
  if (s == SESSILE_OK) s = upload_u32(la, c, total, &t->col);
  if (s == SESSILE_OK) {
    size_t nr = (size_t)(total ? total : 1) * b2;
    s = sessile_buffer_create(la->gpu, nr * la->real_bytes, SESSILE_BUFFER_DEVICE, &t->val);
    if (s == SESSILE_OK && total) s = sessile_buffer_upload_reals(t->val, 0, v, (size_t)total * b2);
  }
  free(lev);
  free(order);
  free(rp);
  free(cnt);
  free(c);
  free(v);
  return s;
}

static sessile_status ilu_build(sessile_la *la, const sessile_mat *a, la_ilu **out) {
  *out = NULL;
  SESSILE_CHECK(a->kind == MAT_CSR || a->kind == MAT_BCSR4, SESSILE_ERR_USAGE,
                "ILU(0) needs an assembled CSR or BCSR4 matrix; the 7-point stencil operator is "
                "matrix-free (use Jacobi)");
  double t0 = sessile_wall_seconds();
  la_ilu *f = calloc(1, sizeof *f);
  SESSILE_CHECK(f, SESSILE_ERR_NO_MEMORY, "ILU(0): out of host memory");
  const uint64_t *rowptr;
  const uint32_t *col;
  uint64_t nvals;
  if (a->kind == MAT_CSR) {
    f->bs = 1, f->n = a->host.nrows, rowptr = a->host.rowptr, col = a->host.col, nvals = a->host.nnz;
  } else {
    f->bs = 4, f->n = a->hostb.nbrows, rowptr = a->hostb.rowptr, col = a->hostb.col,
    nvals = a->hostb.nnzb * 16;
  }
  double *lu = malloc((size_t)(nvals ? nvals : 1) * sizeof *lu);
  sessile_status s = lu ? SESSILE_OK : sessile_error_set(SESSILE_ERR_NO_MEMORY, "ILU(0): out of host memory");
  if (s == SESSILE_OK)
    s = a->kind == MAT_CSR ? sessile_ref_ilu0_csr(&a->host, lu) : sessile_ref_ilu0_bcsr4(&a->hostb, lu);
  if (s == SESSILE_OK) s = build_tri(la, f, 0, rowptr, col, lu, a->chunk_limit, &f->t[0]);
  if (s == SESSILE_OK) s = build_tri(la, f, 1, rowptr, col, lu, a->chunk_limit, &f->t[1]);
  free(lu);
  if (s != SESSILE_OK) {
    la_ilu_destroy(f);
    return s;
  }
  f->seconds = sessile_wall_seconds() - t0;
  *out = f;
  return SESSILE_OK;
}

sessile_status la_ilu_get(sessile_la *la, const sessile_mat *a, const la_ilu **out) {
  if (!a->ilu) {
    la_ilu *f;
    SESSILE_CALL(ilu_build(la, a, &f));
    ((sessile_mat *)a)->ilu = f; /* a cache: the matrix values never change */
  }
  *out = a->ilu;
  return SESSILE_OK;
}

sessile_status rec_ilu(sessile_la *la, sessile_cmd *c, const la_ilu *f, vref r, vref z, int guard) {
  la_kernel_id id = f->bs == 1 ? K_ILU_CSR : K_ILU_BCSR4;
  sessile_kernel *k;
  SESSILE_CALL(la_kernel(la, id, &k));
  uint32_t scale = f->bs == 1 ? 4 : 1; /* CSR offsets in reals, BCSR4 in REAL4 */
  for (int u = 0; u < 2; u++) {
    const ilu_tri *t = &f->t[u];
    vref in = u ? z : r;
    sessile_buffer *bufs[7] = {la->scalars, t->order, t->rowptr, t->col, t->val, in.buf, z.buf};
    for (uint32_t l = 0; l < t->nlev; l++) {
      ilu_push p = {.first = t->levptr[l], .count = t->levptr[l + 1] - t->levptr[l],
                    .xoff = in.off4 * scale, .yoff = z.off4 * scale, .guard = guard,
                    .diag = (uint32_t)u};
      SESSILE_CALL(sessile_cmd_dispatch(c, k, la_groups(la, id, p.count), bufs, &p));
    }
  }
  return SESSILE_OK;
}

sessile_status sessile_mat_ilu0(sessile_la *la, const sessile_mat *a, sessile_ilu0_info *info) {
  const la_ilu *f;
  SESSILE_CALL(la_ilu_get(la, a, &f));
  if (info) {
    info->levels_lower = f->t[0].nlev;
    info->levels_upper = f->t[1].nlev;
    info->seconds = f->seconds;
  }
  return SESSILE_OK;
}

sessile_status sessile_mat_ilu0_apply(sessile_la *la, const sessile_mat *a, const sessile_vec *r,
                                      sessile_vec *z) {
  SESSILE_CHECK(r->n == a->nrows && z->n == a->nrows && r != z, SESSILE_ERR_USAGE,
                "ILU(0) apply: matrix has %u rows, r %u and z %u entries (r and z distinct)",
                a->nrows, r->n, z->n);
  const la_ilu *f;
  SESSILE_CALL(la_ilu_get(la, a, &f));
  SESSILE_CALL(sessile_cmd_begin(la->cmd));
  SESSILE_CALL(rec_ilu(la, la->cmd, f, vref_of(r), vref_of(z), -1));
  SESSILE_CALL(sessile_cmd_end(la->cmd));
  return sessile_cmd_submit_wait(la->cmd);
}
