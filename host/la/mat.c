/* GPU matrices.  CSR is stored as sliced ELL with slices of 8 rows (SELL-8),
 * each row padded to its slice's width in chunks of 4 entries, so the SpMV
 * kernel loads uvec4 columns and REAL4 values and the 8 lanes of a subgroup
 * read consecutive chunks (docs/performance.md has the measurements); block-CSR
 * stores each 4x4 block as four REAL4 rows.  A host copy in double is kept for
 * the Jacobi diagonal and for fp32 iterative-refinement residuals. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "la_internal.h"
#include "sessile/la/la_ref.h"

static sessile_status copy_csr(const sessile_csr *a, sessile_csr *out) {
  SESSILE_CALL(sessile_csr_alloc(a->nrows, a->ncols, a->nnz, out));
  memcpy(out->rowptr, a->rowptr, ((size_t)a->nrows + 1) * sizeof *a->rowptr);
  memcpy(out->col, a->col, (size_t)a->nnz * sizeof *a->col);
  memcpy(out->val, a->val, (size_t)a->nnz * sizeof *a->val);
  return SESSILE_OK;
}

static sessile_status check_csr(const sessile_csr *a) {
  SESSILE_CHECK(a->nrows > 0 && a->nrows == a->ncols, SESSILE_ERR_USAGE,
                "matrix must be square and non-empty (got %u x %u)", a->nrows, a->ncols);
  SESSILE_CHECK(a->rowptr[0] == 0 && a->rowptr[a->nrows] == a->nnz, SESSILE_ERR_USAGE,
                "CSR row pointers do not span the %llu entries", (unsigned long long)a->nnz);
  for (uint32_t r = 0; r < a->nrows; r++) {
    SESSILE_CHECK(a->rowptr[r] <= a->rowptr[r + 1], SESSILE_ERR_USAGE,
                  "CSR row pointers decrease at row %u", r);
    for (uint64_t k = a->rowptr[r]; k < a->rowptr[r + 1]; k++)
      SESSILE_CHECK(a->col[k] < a->ncols, SESSILE_ERR_USAGE,
                    "CSR column %u in row %u is out of range (ncols %u)", a->col[k], r, a->ncols);
  }
  return SESSILE_OK;
}

uint64_t la_chunk_limit(const sessile_la *la) {
  uint64_t lim = sessile_gpu_info_of(la->gpu)->max_storage_buffer_range;
  if (la->max_chunk_bytes > 0 && la->max_chunk_bytes < lim) lim = la->max_chunk_bytes;
  return lim;
}

#define LIMIT_TEXT "the per-buffer limit of %llu bytes (maxStorageBufferRange, or the la's " \
                   "max_matrix_chunk_bytes when set)"

static sessile_status alloc_chunks(sessile_mat *m, uint32_t n) {
  m->chunk = calloc(n, sizeof *m->chunk);
  SESSILE_CHECK(m->chunk, SESSILE_ERR_NO_MEMORY, "out of host memory");
  m->nchunks = n;
  return SESSILE_OK;
}

/* SELL-8 upload of the rows of slices s0..s1-1 (see shaders/la/spmv_csr.comp):
 * slice s of rows 8s..8s+7 holds width_s chunks of 4 entries per row,
 * width_s = w[s] (the widest row's chunk count); chunk t of row 8s+j sits at
 * ptr[s] + 8t + j, ptr counted from the chunk's first slice. */
static sessile_status upload_csr_chunk(sessile_la *la, const sessile_csr *a, const uint32_t *w,
                                       uint32_t s0, uint32_t s1, mat_chunk *ch) {
  uint32_t nsl = s1 - s0;
  ch->row0 = s0 * 8;
  ch->nrows = (s1 * 8 < a->nrows ? s1 * 8 : a->nrows) - ch->row0;
  uint32_t *sp = malloc(((size_t)nsl + 1) * sizeof *sp);
  SESSILE_CHECK(sp, SESSILE_ERR_NO_MEMORY, "out of host memory");
  uint64_t chunks = 0;
  sp[0] = 0;
  for (uint32_t sl = 0; sl < nsl; sl++) {
    chunks += 8 * (uint64_t)w[s0 + sl];
    sp[sl + 1] = (uint32_t)chunks; /* < 2^32: chunks * 16 bytes is within the limit */
  }
  if (chunks == 0) chunks = 1; /* an all-empty chunk still needs non-empty buffers */
  uint32_t *col = calloc((size_t)chunks * 4, sizeof *col);
  double *val = calloc((size_t)chunks * 4, sizeof *val);
  sessile_status s = SESSILE_OK;
  if (!col || !val) s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory padding the matrix");
  /* Padding repeats the row's last column with value 0: the row reads that x
   * anyway, so an Inf there cannot turn a finite row into NaN (0·Inf).  An
   * empty row pads with its own index (y_r is then NaN only if x_r is not
   * finite; the reference gives 0 — a matrix with an empty row is singular). */
  for (uint32_t rl = 0; s == SESSILE_OK && rl < ch->nrows; rl++) {
    uint32_t r = ch->row0 + rl, sl = rl / 8, j = rl % 8;
    uint64_t wd = (sp[sl + 1] - sp[sl]) / 8;
    uint32_t last = a->rowptr[r + 1] > a->rowptr[r] ? a->col[a->rowptr[r + 1] - 1] : r;
    for (uint64_t q = 0; q < 4 * wd; q++) {
      uint64_t at = ((uint64_t)sp[sl] + 8 * (q / 4) + j) * 4 + q % 4;
      uint64_t e = a->rowptr[r] + q;
      if (e < a->rowptr[r + 1]) {
        col[at] = a->col[e];
        val[at] = a->val[e];
      } else
        col[at] = last;
    }
  }
  if (s == SESSILE_OK)
    s = sessile_buffer_create(la->gpu, ((size_t)nsl + 1) * 4, SESSILE_BUFFER_DEVICE, &ch->rowptr);
  if (s == SESSILE_OK) s = sessile_buffer_upload(ch->rowptr, 0, sp, ((size_t)nsl + 1) * 4);
  if (s == SESSILE_OK)
    s = sessile_buffer_create(la->gpu, (size_t)chunks * 16, SESSILE_BUFFER_DEVICE, &ch->col);
  if (s == SESSILE_OK) s = sessile_buffer_upload(ch->col, 0, col, (size_t)chunks * 16);
  if (s == SESSILE_OK)
    s = sessile_buffer_create(la->gpu, (size_t)chunks * 4 * la->real_bytes, SESSILE_BUFFER_DEVICE,
                              &ch->val);
  if (s == SESSILE_OK) s = sessile_buffer_upload_reals(ch->val, 0, val, (size_t)chunks * 4);
  free(sp);
  free(col);
  free(val);
  return s;
}

/* Splits the SELL-8 slices greedily into row chunks whose row pointers,
 * columns and values each fit m->chunk_limit, then uploads each chunk. */
static sessile_status upload_csr(sessile_la *la, sessile_mat *m) {
  const sessile_csr *a = &m->host;
  const uint64_t lim = m->chunk_limit;
  const uint64_t unit = 32 * (uint64_t)(la->real_bytes > 4 ? la->real_bytes : 4); /* bytes of the
                                      larger array (columns or values) per unit of slice width */
  uint32_t nsl = (a->nrows + 7) / 8;
  uint32_t *w = malloc((size_t)nsl * sizeof *w), *first = malloc(((size_t)nsl + 1) * sizeof *first);
  sessile_status s = w && first ? SESSILE_OK : sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  for (uint32_t sl = 0; s == SESSILE_OK && sl < nsl; sl++) {
    uint64_t wd = 0;
    for (uint32_t r = sl * 8; r < a->nrows && r < sl * 8 + 8; r++) {
      uint64_t cr = (a->rowptr[r + 1] - a->rowptr[r] + 3) / 4;
      if (cr > wd) wd = cr;
    }
    if (wd * unit > lim) { /* (lim < 2^32, so slice pointers fit 32 bits) */
      uint32_t rmax = sl * 8;
      for (uint32_t r = sl * 8; r < a->nrows && r < sl * 8 + 8; r++)
        if (a->rowptr[r + 1] - a->rowptr[r] > a->rowptr[rmax + 1] - a->rowptr[rmax]) rmax = r;
      s = sessile_error_set(SESSILE_ERR_TOO_LARGE,
                            "CSR row %u has %llu entries: its 8-row slice alone needs %llu bytes, "
                            "over " LIMIT_TEXT ", so the matrix cannot be split into row chunks",
                            rmax, (unsigned long long)(a->rowptr[rmax + 1] - a->rowptr[rmax]),
                            (unsigned long long)(wd * unit),
                            (unsigned long long)lim);
    }
    w[sl] = (uint32_t)wd;
  }
  /* first[c]: the first slice of chunk c. */
  uint32_t n = 0;
  for (uint32_t sl = 0; s == SESSILE_OK && sl < nsl;) {
    uint64_t wsum = 0;
    uint32_t s0 = sl;
    for (; sl < nsl; sl++) {
      uint64_t nw = wsum + w[sl];
      if ((nw ? nw : 1) * unit > lim || (uint64_t)(sl - s0 + 2) * 4 > lim) break;
      wsum = nw;
    }
    if (sl == s0) { /* only when the row pointers of one slice exceed the limit */
      s = sessile_error_set(SESSILE_ERR_TOO_LARGE, "matrix chunk: " LIMIT_TEXT " is too small",
                            (unsigned long long)lim);
      break;
    }
    first[n++] = s0;
  }
  if (s == SESSILE_OK) {
    first[n] = nsl;
    s = alloc_chunks(m, n);
  }
  for (uint32_t c = 0; s == SESSILE_OK && c < n; c++)
    s = upload_csr_chunk(la, a, w, first[c], first[c + 1], &m->chunk[c]);
  /* Texel reads need every view within maxTexelBufferElements: chunks
   * RGBA32UI texels of columns, chunks * real_bytes / 4 of values. */
  uint64_t maxt = sessile_gpu_info_of(la->gpu)->max_texel_buffer_elements;
  m->texel = s == SESSILE_OK && la->spmv_texel && a->nrows <= maxt;
  for (uint32_t c = 0; m->texel && c < n; c++)
    if (!la_texel_fits(la, m->chunk[c].val, 16)) m->texel = 0;
  free(w);
  free(first);
  return s;
}

sessile_status sessile_mat_create_csr(sessile_la *la, const sessile_csr *a, sessile_mat **out) {
  *out = NULL;
  SESSILE_CALL(check_csr(a));
  sessile_mat *m = calloc(1, sizeof *m);
  SESSILE_CHECK(m, SESSILE_ERR_NO_MEMORY, "out of host memory");
  m->la = la;
  m->kind = MAT_CSR;
  m->nrows = a->nrows;
  m->nnz = a->nnz;
  m->rows_per = 1; /* SELL-8: one row per invocation */
  m->chunk_limit = la_chunk_limit(la);
  sessile_status s = copy_csr(a, &m->host);
  if (s == SESSILE_OK) s = upload_csr(la, m);
  if (s != SESSILE_OK) {
    sessile_mat_destroy(m);
    return s;
  }
  *out = m;
  return SESSILE_OK;
}

sessile_status la_upload_vals(sessile_la *la, sessile_buffer *b, const double *src, size_t n, uint32_t bytes) {
  if (bytes == la->real_bytes) return sessile_buffer_upload_reals(b, 0, src, n);
  float *f = malloc(n * sizeof *f);
  SESSILE_CHECK(f, SESSILE_ERR_NO_MEMORY, "out of host memory");
  for (size_t i = 0; i < n; i++) f[i] = (float)src[i];
  sessile_status s = sessile_buffer_upload(b, 0, f, n * sizeof *f);
  free(f);
  return s;
}

/* n values into b in the matrix's stored precision. */
static sessile_status upload_vals(const sessile_mat *m, sessile_buffer *b, const double *src, size_t n) {
  return la_upload_vals(m->la, b, src, n, m->val_bytes);
}

/* Block rows r0..r1-1 of `a` into one chunk (row pointers rebased). */
static sessile_status upload_bcsr4_chunk(const sessile_mat *m, const sessile_bcsr4 *a, uint32_t r0,
                                         uint32_t r1, mat_chunk *ch) {
  sessile_la *la = m->la;
  ch->row0 = r0;
  ch->nrows = r1 - r0;
  uint64_t k0 = a->rowptr[r0], nnzb = a->rowptr[r1] - k0;
  size_t nb = nnzb ? (size_t)nnzb : 1;
  uint32_t *rp = malloc(((size_t)ch->nrows + 1) * sizeof *rp);
  SESSILE_CHECK(rp, SESSILE_ERR_NO_MEMORY, "out of host memory");
  for (uint32_t r = r0; r <= r1; r++) rp[r - r0] = (uint32_t)(a->rowptr[r] - k0);
  sessile_status s =
      sessile_buffer_create(la->gpu, ((size_t)ch->nrows + 1) * 4, SESSILE_BUFFER_DEVICE, &ch->rowptr);
  if (s == SESSILE_OK) s = sessile_buffer_upload(ch->rowptr, 0, rp, ((size_t)ch->nrows + 1) * 4);
  if (s == SESSILE_OK) s = sessile_buffer_create(la->gpu, nb * 4, SESSILE_BUFFER_DEVICE, &ch->col);
  if (s == SESSILE_OK && nnzb) s = sessile_buffer_upload(ch->col, 0, a->col + k0, (size_t)nnzb * 4);
  if (s == SESSILE_OK)
    s = sessile_buffer_create(la->gpu, nb * 16 * m->val_bytes, SESSILE_BUFFER_DEVICE, &ch->val);
  if (s == SESSILE_OK && nnzb) s = upload_vals(m, ch->val, a->val + k0 * 16, (size_t)nnzb * 16);
  free(rp);
  return s;
}

/* Greedy split into block-row chunks whose arrays each fit m->chunk_limit
 * (the values, 16 per block of m->val_bytes each, are the largest), then the
 * uploads of a's rows (a: the values; m->hostb may hold the pattern only). */
static sessile_status upload_bcsr4(sessile_mat *m, const sessile_bcsr4 *a) {
  const uint64_t lim = m->chunk_limit, per = 16 * (uint64_t)m->val_bytes;
  uint32_t *first = malloc(((size_t)a->nbrows + 1) * sizeof *first);
  SESSILE_CHECK(first, SESSILE_ERR_NO_MEMORY, "out of host memory");
  sessile_status s = SESSILE_OK;
  uint32_t n = 0;
  for (uint32_t r = 0; r < a->nbrows;) {
    uint32_t r0 = r;
    for (; r < a->nbrows; r++) {
      uint64_t nb = a->rowptr[r + 1] - a->rowptr[r0];
      if ((nb ? nb : 1) * per > lim || (uint64_t)(r - r0 + 2) * 4 > lim) break;
    }
    if (r == r0) {
      uint64_t nb = a->rowptr[r0 + 1] - a->rowptr[r0];
      s = sessile_error_set(SESSILE_ERR_TOO_LARGE,
                            "block row %u has %llu blocks (%llu bytes of values), over " LIMIT_TEXT
                            ", so the matrix cannot be split into row chunks",
                            r0, (unsigned long long)nb, (unsigned long long)(nb * per),
                            (unsigned long long)lim);
      break;
    }
    first[n++] = r0;
  }
  if (s == SESSILE_OK) {
    first[n] = a->nbrows;
    s = alloc_chunks(m, n);
  }
  for (uint32_t c = 0; s == SESSILE_OK && c < n; c++)
    s = upload_bcsr4_chunk(m, a, first[c], first[c + 1], &m->chunk[c]);
  free(first);
  return s;
}

/* A block matrix of values stored in val_bytes; values_on_host: hostb keeps
 * a copy of the values (else the pattern only). */
static sessile_status create_bcsr4(sessile_la *la, const sessile_bcsr4 *a, uint32_t val_bytes,
                                   int values_on_host, sessile_mat **out) {
  *out = NULL;
  SESSILE_CHECK(a->nbrows > 0 && a->nbrows == a->nbcols, SESSILE_ERR_USAGE,
                "block matrix must be square and non-empty (got %u x %u blocks)", a->nbrows,
                a->nbcols);
  SESSILE_CHECK(a->nbrows <= UINT32_MAX / 4, SESSILE_ERR_TOO_LARGE, "block matrix too large");
  for (uint32_t r = 0; r < a->nbrows; r++)
    for (uint64_t k = a->rowptr[r]; k < a->rowptr[r + 1]; k++)
      SESSILE_CHECK(a->col[k] < a->nbcols, SESSILE_ERR_USAGE,
                    "block column %u in block row %u is out of range", a->col[k], r);
  SESSILE_CHECK(a->nnzb <= UINT32_MAX / 4, SESSILE_ERR_TOO_LARGE, "block matrix too large");
  sessile_mat *m = calloc(1, sizeof *m);
  SESSILE_CHECK(m, SESSILE_ERR_NO_MEMORY, "out of host memory");
  m->la = la;
  m->kind = MAT_BCSR4;
  m->val_bytes = val_bytes;
  m->nrows = a->nbrows * 4;
  m->nnz = a->nnzb * 16;
  m->rows_per = 1;
  m->chunk_limit = la_chunk_limit(la);
  sessile_status s = sessile_bcsr4_alloc(a->nbrows, a->nbcols, a->nnzb, &m->hostb);
  if (s == SESSILE_OK) {
    memcpy(m->hostb.rowptr, a->rowptr, ((size_t)a->nbrows + 1) * sizeof *a->rowptr);
    memcpy(m->hostb.col, a->col, (size_t)a->nnzb * sizeof *a->col);
    if (values_on_host) memcpy(m->hostb.val, a->val, (size_t)a->nnzb * 16 * sizeof *a->val);
    else free(m->hostb.val), m->hostb.val = NULL;
    s = upload_bcsr4(m, a);
  }
  if (s != SESSILE_OK) {
    sessile_mat_destroy(m);
    return s;
  }
  *out = m;
  return SESSILE_OK;
}

sessile_status sessile_mat_create_bcsr4(sessile_la *la, const sessile_bcsr4 *a, sessile_mat **out) {
  return create_bcsr4(la, a, la->real_bytes, 1, out);
}

sessile_status la_mat_create_bcsr4_f32(sessile_la *la, const sessile_bcsr4 *a, sessile_mat **out) {
  return create_bcsr4(la, a, 4, 0, out);
}

sessile_status sessile_mat_refill_bcsr4(sessile_mat *m, const sessile_bcsr4 *a) {
  SESSILE_CHECK(m && a && m->kind == MAT_BCSR4 && a->nbrows == m->hostb.nbrows && a->nnzb == m->hostb.nnzb &&
                    memcmp(a->rowptr, m->hostb.rowptr, ((size_t)a->nbrows + 1) * sizeof *a->rowptr) == 0 &&
                    memcmp(a->col, m->hostb.col, (size_t)a->nnzb * sizeof *a->col) == 0,
                SESSILE_ERR_USAGE, "refill: the block matrix's pattern is not the one it was created with");
  SESSILE_CHECK(m->chunk_limit == la_chunk_limit(m->la), SESSILE_ERR_USAGE,
                "refill: the context's chunk limit changed since the matrix was made");
  la_ilu_destroy(m->ilu); /* the factors of the old values */
  m->ilu = NULL;
  if (m->hostb.val) memcpy(m->hostb.val, a->val, (size_t)a->nnzb * 16 * sizeof *a->val);
  for (uint32_t c = 0; c < m->nchunks; c++) {
    const mat_chunk *ch = &m->chunk[c];
    uint64_t k0 = a->rowptr[ch->row0], nnzb = a->rowptr[ch->row0 + ch->nrows] - k0;
    if (nnzb) SESSILE_CALL(upload_vals(m, ch->val, a->val + k0 * 16, (size_t)nnzb * 16));
  }
  return SESSILE_OK;
}

void sessile_mat_destroy(sessile_mat *m) {
  if (!m) return;
  for (uint32_t c = 0; c < m->nchunks; c++) {
    sessile_buffer_destroy(m->chunk[c].rowptr);
    sessile_buffer_destroy(m->chunk[c].col);
    sessile_buffer_destroy(m->chunk[c].val);
  }
  free(m->chunk);
  la_ilu_destroy(m->ilu);
  if (m->kind == MAT_CSR) sessile_csr_free(&m->host);
  else sessile_bcsr4_free(&m->hostb);
  free(m);
}

uint32_t sessile_mat_rows(const sessile_mat *m) { return m->nrows; }
uint64_t sessile_mat_nnz(const sessile_mat *m) { return m->nnz; }
uint32_t sessile_mat_chunks(const sessile_mat *m) { return m->nchunks; }

sessile_status sessile_mat_mult(sessile_la *la, const sessile_mat *a, const sessile_vec *x,
                                sessile_vec *y) {
  SESSILE_CHECK(x->n == a->nrows && y->n == a->nrows, SESSILE_ERR_USAGE,
                "SpMV: matrix has %u rows but x has %u and y %u entries", a->nrows, x->n, y->n);
  SESSILE_CALL(sessile_cmd_begin(la->cmd));
  SESSILE_CALL(rec_spmv(la, la->cmd, a, vref_of(x), vref_of(y), -1));
  SESSILE_CALL(sessile_cmd_end(la->cmd));
  return sessile_cmd_submit_wait(la->cmd);
}

sessile_status sessile_mat_jacobi(sessile_la *la, const sessile_mat *a, sessile_vec *dinv) {
  SESSILE_CHECK(dinv->n == a->nrows, SESSILE_ERR_USAGE, "Jacobi: vector has %u entries, matrix %u rows",
                dinv->n, a->nrows);
  if (a->kind == MAT_STENCIL7) return la_stencil7_jacobi(la, a, dinv);
  if (a->kind == MAT_STENCIL7_CUT) return la_stencil7_cut_jacobi(la, a, dinv);
  double *d = malloc((size_t)a->nrows * sizeof *d);
  SESSILE_CHECK(d, SESSILE_ERR_NO_MEMORY, "out of host memory");
  sessile_status s = a->kind == MAT_CSR ? sessile_ref_jacobi_csr(&a->host, d)
                                        : sessile_ref_jacobi_bcsr4(&a->hostb, d);
  if (s == SESSILE_OK) s = sessile_vec_upload(dinv, d);
  free(d);
  return s;
}
