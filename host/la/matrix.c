/* Allocation and release of host CSR / BCSR4 matrices.  Sizes are checked in
 * 64-bit/size_t arithmetic before malloc so a huge request fails with a
 * message instead of wrapping around to a small allocation. */
#include <inttypes.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "sessile/la/matrix.h"

/* count*elem bytes, or SIZE_MAX when that does not fit in size_t. */
static size_t array_bytes(uint64_t count, size_t elem) {
  if (count > SIZE_MAX / elem) return SIZE_MAX;
  return (size_t)count * elem;
}

/* malloc that never asks for 0 bytes (malloc(0) may return NULL) and refuses
 * sizes that overflowed. */
static void *alloc_array(uint64_t count, size_t elem) {
  size_t bytes = array_bytes(count, elem);
  if (bytes == SIZE_MAX) return NULL;
  return malloc(bytes ? bytes : 1);
}

/* Human-readable size for messages; double is exact enough and never overflows. */
static double gib(uint64_t count, size_t elem) {
  return (double)count * (double)elem / (1024.0 * 1024.0 * 1024.0);
}

sessile_status sessile_csr_alloc(uint32_t nrows, uint32_t ncols, uint64_t nnz, sessile_csr *out) {
  SESSILE_CHECK(out != NULL, SESSILE_ERR_INTERNAL, "sessile_csr_alloc: out is NULL");
  memset(out, 0, sizeof *out);
  /* An impossible size fails before anything is allocated. */
  const int fits = array_bytes(nnz, sizeof(double)) != SIZE_MAX;
  uint64_t *rowptr = fits ? alloc_array((uint64_t)nrows + 1, sizeof *rowptr) : NULL;
  uint32_t *col = rowptr ? alloc_array(nnz, sizeof *col) : NULL;
  double *val = col ? alloc_array(nnz, sizeof *val) : NULL;
  if (!rowptr || !col || !val) {
    free(rowptr);
    free(col);
    free(val);
    return sessile_error_set(
        SESSILE_ERR_NO_MEMORY,
        "out of host memory: cannot allocate a %" PRIu32 " x %" PRIu32 " CSR matrix with %" PRIu64
        " nonzeros (%.3f GiB row pointers + %.3f GiB columns + %.3f GiB values): "
        "use a smaller problem",
        nrows, ncols, nnz, gib((uint64_t)nrows + 1, sizeof *rowptr), gib(nnz, sizeof *col),
        gib(nnz, sizeof *val));
  }
  rowptr[0] = 0; /* so an empty matrix is valid as soon as it exists */
  out->nrows = nrows;
  out->ncols = ncols;
  out->nnz = nnz;
  out->rowptr = rowptr;
  out->col = col;
  out->val = val;
  return SESSILE_OK;
}

void sessile_csr_free(sessile_csr *a) {
  if (!a) return;
  free(a->rowptr);
  free(a->col);
  free(a->val);
  memset(a, 0, sizeof *a); /* a second free is then a no-op, not a double free */
}

sessile_status sessile_bcsr4_alloc(uint32_t nbrows, uint32_t nbcols, uint64_t nnzb,
                                   sessile_bcsr4 *out) {
  SESSILE_CHECK(out != NULL, SESSILE_ERR_INTERNAL, "sessile_bcsr4_alloc: out is NULL");
  memset(out, 0, sizeof *out);
  /* 16 doubles per block: check that product, and every size, before the
   * first malloc. */
  const int fits = nnzb <= UINT64_MAX / 16 && array_bytes(16 * nnzb, sizeof(double)) != SIZE_MAX;
  uint64_t *rowptr = fits ? alloc_array((uint64_t)nbrows + 1, sizeof *rowptr) : NULL;
  uint32_t *col = rowptr ? alloc_array(nnzb, sizeof *col) : NULL;
  double *val = col ? alloc_array(16 * nnzb, sizeof *val) : NULL;
  if (!rowptr || !col || !val) {
    free(rowptr);
    free(col);
    free(val);
    return sessile_error_set(
        SESSILE_ERR_NO_MEMORY,
        "out of host memory: cannot allocate a %" PRIu32 " x %" PRIu32 " block (4x4) matrix with %" PRIu64
        " blocks (%.3f GiB row pointers + %.3f GiB columns + %.3f GiB values): "
        "use a smaller problem",
        nbrows, nbcols, nnzb, gib((uint64_t)nbrows + 1, sizeof *rowptr), gib(nnzb, sizeof *col),
        16.0 * gib(nnzb, sizeof *val));
  }
  rowptr[0] = 0;
  out->nbrows = nbrows;
  out->nbcols = nbcols;
  out->nnzb = nnzb;
  out->rowptr = rowptr;
  out->col = col;
  out->val = val;
  return SESSILE_OK;
}

void sessile_bcsr4_free(sessile_bcsr4 *a) {
  if (!a) return;
  free(a->rowptr);
  free(a->col);
  free(a->val);
  memset(a, 0, sizeof *a);
}
