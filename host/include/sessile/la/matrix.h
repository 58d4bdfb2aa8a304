/* sessile — host-side sparse matrices (plain C, double precision) and the
 * generators the tests and benchmarks use.
 *
 * Ownership: a matrix owns its arrays; free it with sessile_csr_free /
 * sessile_bcsr4_free (NULL is a no-op).  Column indices are sorted within each
 * row and unique. */
#ifndef SESSILE_MATRIX_H
#define SESSILE_MATRIX_H

#include <stdint.h>
#include "sessile/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Compressed sparse row, scalar entries. */
typedef struct sessile_csr {
  uint32_t nrows, ncols;
  uint64_t nnz;
  uint64_t *rowptr; /* nrows + 1 */
  uint32_t *col;    /* nnz */
  double *val;      /* nnz */
} sessile_csr;

/* Block CSR with dense 4x4 blocks (4 unknowns per node, e.g. u,v,w,p).
 * Block k's entries are val[16k + 4*i + j] (row-major). */
typedef struct sessile_bcsr4 {
  uint32_t nbrows, nbcols; /* in blocks; scalar size is 4x that */
  uint64_t nnzb;
  uint64_t *rowptr; /* nbrows + 1 */
  uint32_t *col;    /* nnzb, block columns */
  double *val;      /* 16 * nnzb */
} sessile_bcsr4;

sessile_status sessile_csr_alloc(uint32_t nrows, uint32_t ncols, uint64_t nnz, sessile_csr *out);
void sessile_csr_free(sessile_csr *a);
sessile_status sessile_bcsr4_alloc(uint32_t nbrows, uint32_t nbcols, uint64_t nnzb, sessile_bcsr4 *out);
void sessile_bcsr4_free(sessile_bcsr4 *a);

#ifdef __cplusplus
}
#endif
#endif
