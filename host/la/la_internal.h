/* Internal definitions of host/la (not public API). */
#ifndef SESSILE_LA_INTERNAL_H
#define SESSILE_LA_INTERNAL_H

#include "sessile/la/la.h"
#include "sessile/la/pc.h"

/* The kernels (la_kernel_id, sessile_la_kernels[]), their push structs
 * (vec_push, spmv_push, ...) and the scalar slots (S_*, CG_*, BI_*, GM_*),
 * MAXG, NSETS, COEF_*: generated from shaders/la/kernels.def. */
#include "la_kernels.h"

/* Vectors kept one after another in one buffer, or one buffer each when
 * that would exceed the per-buffer limit. */
typedef struct {
  sessile_buffer *one;
  sessile_buffer **each;
  uint32_t neach;
} la_vstore;

struct sessile_la {
  sessile_gpu *gpu;
  uint32_t real_bytes;
  sessile_kernel *k[K_COUNT]; /* created on first use */
  sessile_buffer *scalars;    /* NSLOTS reals, mapped */
  sessile_buffer *partials;   /* NSETS * MAXG (hi, lo) pairs */
  sessile_cmd *cmd;           /* immediate operations */
  int spmv_texel;             /* CSR SpMV may read through texel buffers (default
                                 on; sessile_la_options.spmv_storage forces storage buffers) */
  uint64_t max_chunk_bytes;   /* sessile_la_options.max_matrix_chunk_bytes (0: none) */
  int gm_textbook;            /* sessile_la_options.gmres_textbook_update */
  uint64_t vec_serial;        /* the last vector's serial (sessile_vec.serial) */
  /* GMRES's scratch, kept between solves (la_gmres): fresh device memory on
   * lavapipe is host memory page-faulted in on first touch, ~45 MB a solve
   * of the fluid's level-1 system */
  la_vstore gm_v;             /* the Krylov basis */
  la_vstore gm_zs;            /* the preconditioned basis vectors z_j = M^-1 v_j (gmres.c) */
  sessile_vec *gm_z, *gm_ones;
  uint32_t fused_groups;      /* at most this many groups for the grid-stride kernels with
                                 a reduction of the cut-cell operator and the multigrid:
                                 128 on CPU devices (lavapipe runs a group's barriers as
                                 coroutine switches: 1024 groups cost ~1.5x the work), else MAXG */
};

struct sessile_vec {
  sessile_la *la;
  uint32_t n, n4;
  sessile_buffer *buf;
  uint64_t serial;            /* unique within its la: a recording made for this vector
                                 is recognised even if a later vector reuses its address */
};

typedef enum { MAT_CSR = 0, MAT_BCSR4 = 1, MAT_STENCIL7 = 2, MAT_STENCIL7_CUT = 3 } mat_kind;

/* A row range of an assembled matrix with its own buffers: row pointers
 * rebased to the chunk, columns global (x is read whole), values of the
 * chunk's rows.  A matrix whose arrays exceed the per-buffer limit
 * (maxStorageBufferRange, or the la's max_matrix_chunk_bytes for tests) is
 * stored as several chunks and every SpMV dispatches once per chunk. */
typedef struct {
  uint32_t row0, nrows;    /* CSR: scalar rows (row0 a multiple of 8); BCSR4: block rows */
  sessile_buffer *rowptr, *col, *val;
} mat_chunk;

struct sessile_mat {
  sessile_la *la;
  mat_kind kind;
  uint32_t nrows;          /* scalar rows */
  uint64_t nnz;            /* scalar entries before padding */
  uint32_t nchunks;        /* CSR, BCSR4: >= 1; STENCIL7: 0 */
  mat_chunk *chunk;
  uint64_t chunk_limit;    /* bytes per matrix buffer (also bounds the ILU(0) factors) */
  uint32_t val_bytes;      /* BCSR4: bytes of a stored value: the context's real_bytes, or 4
                              for an fp32 copy in an fp64 context (la_mat_create_bcsr4_f32) */
  sessile_csr host;        /* CSR: kept for fp32 refinement residuals and Jacobi */
  sessile_bcsr4 hostb;     /* BCSR4: likewise (an fp32 copy: the pattern only, val NULL) */
  uint32_t rows_per;       /* rows per invocation in the SpMV kernel */
  int texel;               /* CSR: read through texel buffers (sizes within the
                              device's maxTexelBufferElements and la->spmv_texel) */
  uint32_t grid[3];        /* STENCIL7(_CUT): nodes per axis */
  double h;                /* STENCIL7(_CUT): grid spacing */
  sessile_buffer *mask;    /* STENCIL7(_CUT): Dirichlet mask (uint32 per node), not owned */
  const sessile_vec *diag; /* STENCIL7_CUT: the cut-cell diagonal, not owned */
  int cut_texel;           /* STENCIL7_CUT: read mask, diag and x through texel buffers */
  const sessile_vec *coef; /* STENCIL7_CUT with advection: 6 off-diagonal weights per node
                              (stencil_cut_adv.c), not owned; NULL: all 1 */
  struct la_ilu *ilu;      /* ILU(0) factors, computed on first use (ilu.c) */
};

/* A device-only copy of the block matrix a with its values as floats, in any
 * context, chunked for 4-byte values: the block multigrid's fp32 cycle
 * (bmg_setup.c) reads it with its f32 kernels.  Its hostb holds the pattern
 * but no values, so nothing else (SpMV, Jacobi, ILU, references) may take
 * it; sessile_mat_refill_bcsr4 refreshes its values. */
sessile_status la_mat_create_bcsr4_f32(sessile_la *la, const sessile_bcsr4 *a, sessile_mat **out);
/* n values from the host's doubles into b at offset 0, stored in `bytes`
 * each: the context's real_bytes (sessile_buffer_upload_reals) or 4 (floats). */
sessile_status la_upload_vals(sessile_la *la, sessile_buffer *b, const double *src, size_t n, uint32_t bytes);

/* A vector inside a buffer: `off4` REAL4 chunks from its start. */
typedef struct { sessile_buffer *buf; uint32_t off4; } vref;
static inline vref vref_of(const sessile_vec *v) { vref r = {v->buf, 0}; return r; }

sessile_status la_kernel(sessile_la *la, la_kernel_id id, sessile_kernel **out);
/* Host view of the scalar slots (mapped). */
void la_scalar_set(sessile_la *la, int slot, double v);
double la_scalar_read(sessile_la *la, int slot);

/* Recording helpers (la_record.c): each records into `c`. */
sessile_status rec_vec(sessile_la *la, sessile_cmd *c, la_kernel_id id, uint32_t n, vref a,
                       vref b, vref w, int a_slot, uint32_t flags, int guard);
/* Partial sums of x·y into `set`; returns the number of partials written. */
sessile_status rec_dot(sessile_la *la, sessile_cmd *c, uint32_t n, vref x, vref y, uint32_t set,
                       int guard, uint32_t *count);
sessile_status rec_reduce(sessile_la *la, sessile_cmd *c, uint32_t count, uint32_t first_set,
                          uint32_t nsets, int dst_slot, int sqrt_flag, int guard);
sessile_status rec_spmv(sessile_la *la, sessile_cmd *c, const sessile_mat *a, vref x, vref y,
                        int guard);
/* Buffer b as a texel view of texel_bytes-byte texels fits the device's
 * maxTexelBufferElements. */
int la_texel_fits(const sessile_la *la, const sessile_buffer *b, uint32_t texel_bytes);
/* A block chunk (rowptr, col, val as raw 32-bit texels) and x's buffer may
 * be read through texel views: the context allows it and every view fits
 * maxTexelBufferElements (the block SpMV and pc mg's _tex kernels). */
int la_block_texel_ok(const sessile_la *la, const mat_chunk *ch, sessile_buffer *x);
/* y = A x with the partial sums of x·y in set 0 (CG's p·Ap). */
sessile_status rec_spmv_dot(sessile_la *la, sessile_cmd *c, const sessile_mat *a, vref x, vref y,
                            int guard, uint32_t *count);
/* A matrix-free stencil matrix of `kind` (stencil.c): the grid, spacing and
 * mask checked (`what` names the operator in messages), nothing else set. */
sessile_status la_stencil_mat(sessile_la *la, mat_kind kind, const char *what, uint32_t nx,
                              uint32_t ny, uint32_t nz, double h, sessile_buffer *mask,
                              sessile_mat **out);
/* The masked 7-point operator (stencil.c): y = A x, with x·y partials in set 0. */
sessile_status rec_stencil7(sessile_la *la, sessile_cmd *c, const sessile_mat *a, vref x, vref y,
                            int guard, uint32_t *count);
sessile_status la_stencil7_jacobi(sessile_la *la, const sessile_mat *a, sessile_vec *dinv);
/* Host copy of the mask for host residuals (fp32 refinement); free() it. */
sessile_status la_stencil7_host_mask(const sessile_mat *a, uint32_t **mask);
/* The cut-cell operator (stencil_cut.c): y = A x (x·y partials in set 0 when count is
 * not NULL), its Jacobi, and a host copy of its diagonal (free() it). */
sessile_status rec_stencil7_cut(sessile_la *la, sessile_cmd *c, const sessile_mat *a, vref x,
                                vref y, int guard, uint32_t *count);
sessile_status la_stencil7_cut_jacobi(sessile_la *la, const sessile_mat *a, sessile_vec *dinv);
sessile_status la_stencil7_cut_host_diag(const sessile_mat *a, double **diag);
/* The push constants of the cut-cell kernels for y = A x. */
cut_push la_cut_push_of(sessile_la *la, const sessile_mat *a, vref x, vref y, int guard);
/* The advective variant (a->coef set; stencil_cut_adv.c): texel reads only. */
sessile_status rec_stencil7_cut_adv(sessile_la *la, sessile_cmd *c, const sessile_mat *a, vref x,
                                    vref y, int guard, uint32_t *count);
/* Host copy of a->coef, or NULL when it has none (free() it). */
sessile_status la_stencil7_cut_host_coef(const sessile_mat *a, double **coef);
/* Multiply-high divisor of grid extent n (kernels: node -> (i, j, k) without division). */
static inline uint32_t la_div_magic(uint32_t n) { return 0xffffffffu / n; }
/* Groups for an element-wise kernel over n reals, and for a reduction. */
uint32_t la_groups(sessile_la *la, la_kernel_id id, uint32_t n4);
uint32_t la_reduce_groups(sessile_la *la, uint32_t n4);
/* la_groups capped at la->fused_groups (and at least 1). */
uint32_t la_fused_groups(sessile_la *la, la_kernel_id id, uint32_t items);

/* Host <-> device transfers in the stored precision (vec.c). */

/* ILU(0) on the device (ilu.c): the factors of `a`, computed once and cached
 * in the matrix; z = (LU)⁻¹ r as one dispatch per level of L and of U. */
typedef struct la_ilu la_ilu;
sessile_status la_ilu_get(sessile_la *la, const sessile_mat *a, const la_ilu **out);
void la_ilu_destroy(la_ilu *f);
sessile_status rec_ilu(sessile_la *la, sessile_cmd *c, const la_ilu *f, vref r, vref z, int guard);
/* Inverse of a bs x bs row-major block (bs <= 4) by Gauss-Jordan with partial
 * pivoting; 0 when singular to working precision or not finite (ref_ilu.c). */
int la_block_inverse(int bs, const double *a, double *inv);

/* Solvers (one file each); run on the device in the context precision with
 * a set-up preconditioner object (pc_internal.h). */
sessile_status la_cg(sessile_la *la, const sessile_ksp_options *o, const sessile_mat *a,
                     const sessile_vec *b, sessile_vec *x, const sessile_pc *pc,
                     sessile_solve_result *res);
sessile_status la_bicgstab(sessile_la *la, const sessile_ksp_options *o, const sessile_mat *a,
                           const sessile_vec *b, sessile_vec *x, const sessile_pc *pc,
                           sessile_solve_result *res);
sessile_status la_gmres(sessile_la *la, const sessile_ksp_options *o, const sessile_mat *a,
                        const sessile_vec *b, sessile_vec *x, const sessile_pc *pc,
                        sessile_solve_result *res);
/* A vector of n ones (the fused solver kernels' D⁻¹ when the pc is not diagonal). */
sessile_status la_ones(sessile_la *la, uint32_t n, sessile_vec **out);
/* The per-buffer limit of a matrix's arrays and GMRES's basis: the device's
 * maxStorageBufferRange, lowered by the la's max_matrix_chunk_bytes when set
 * (a testing knob: small problems then split). mat.c. */
uint64_t la_chunk_limit(const sessile_la *la);
/* GMRES's kept vectors (gmres.c): `count` vectors of `per` bytes, in one
 * buffer unless `split`; what is there is kept when it is large enough. */
sessile_status la_vstore_ensure(sessile_la *la, la_vstore *v, uint32_t count, uint64_t per, int split);
void la_vstore_free(la_vstore *v);
/* solver_loop.c: submit `iter` until the device sets S_STOP; reset the slots. */
sessile_status la_solver_loop(sessile_la *la, sessile_cmd *iter, int per_submit, int max_it,
                              const sessile_ksp_options *o, const char *name, int est_slot,
                              int est_is_sq);
/* Formats one line and hands it to o->monitor (nothing when it is NULL). */
void la_monitorf(const sessile_ksp_options *o, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
void la_solver_reset(sessile_la *la, const sessile_ksp_options *o);

/* fp32 contexts (ksp.c): iterative refinement with the residual b - A x in
 * double on the host; `inner` solves A d = q on the device in fp32. */
typedef sessile_status (*la_inner_fn)(void *ctx, const sessile_ksp_options *o, const sessile_vec *q,
                                      sessile_vec *d, sessile_solve_result *res);
sessile_status la_solve_refined(sessile_la *la, const sessile_ksp_options *o, const sessile_mat *a,
                                const sessile_vec *b, sessile_vec *x, sessile_vec *q, sessile_vec *d,
                                la_inner_fn inner, void *ctx, sessile_solve_result *res);

/* Shared by the solvers: reads STOP/ITER, fills status and reason. */
void la_solver_outcome(sessile_la *la, sessile_solve_result *res, double est_relres);

#endif
