/* sessile — GPU linear algebra: vectors, CSR and 4x4 block-CSR matrices,
 * Jacobi, and Krylov solvers (PCG, BiCGSTAB, restarted GMRES(m)) that run on
 * the device and read convergence from a small mapped buffer every k
 * iterations instead of a submit-and-wait per iteration.
 *
 * Precision: vectors and matrix values are stored in the context's precision
 * (sessile_gpu_info.precision): fp64 where the device has shaderFloat64, else
 * fp32 with compensated reductions, and solves wrapped in mixed-precision
 * iterative refinement (residuals in double on the host).  docs/precision.md.
 *
 * Ownership: sessile_la owns its kernels and work buffers; vectors and
 * matrices are owned by the caller and must be destroyed before the la. */
#ifndef SESSILE_LA_H
#define SESSILE_LA_H

#include <stdarg.h>
#include <stdint.h>
#include "sessile/gpu/gpu.h"
#include "sessile/la/matrix.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sessile_la sessile_la;
typedef struct sessile_vec sessile_vec;
typedef struct sessile_mat sessile_mat;

/* Options of an la context (the defaults suit every normal use). */
typedef struct sessile_la_options {
  /* 1: CSR SpMV, the cut-cell stencil and the block multigrid's smoother
   * and residual read through storage buffers only (default 0: through
   * texel buffers where they fit, docs/design.md; the same bits). */
  int spmv_storage;
  /* Per-buffer limit in bytes of a matrix's arrays: 0 (default), or a value
   * at or above the device's maxStorageBufferRange, means that range; a
   * smaller value makes small matrices split into row chunks (tests). */
  uint64_t max_matrix_chunk_bytes;
  /* 1: GMRES always updates x += M^-1 (V y), the textbook right-preconditioned
   * update (default 0: x += Z y from the kept z_j = M^-1 v_j in a cycle of at
   * most 16 iterations, one preconditioner application fewer; tests). */
  int gmres_textbook_update;
} sessile_la_options;

void sessile_la_options_default(sessile_la_options *o);
/* sessile_la_create_with(g, NULL, out): the defaults. */
sessile_status sessile_la_create(sessile_gpu *g, sessile_la **out);
sessile_status sessile_la_create_with(sessile_gpu *g, const sessile_la_options *opt, sessile_la **out);
/* Replaces the options; they are read when a matrix is created, so they
 * apply to matrices created afterwards (existing ones keep theirs). */
void sessile_la_set_options(sessile_la *la, const sessile_la_options *opt);
void sessile_la_destroy(sessile_la *la);
sessile_gpu *sessile_la_gpu(sessile_la *la);
/* Bytes per stored real: 8 (fp64) or 4 (fp32). */
uint32_t sessile_la_real_bytes(const sessile_la *la);

/* --- vectors (n reals, zero-initialised) -------------------------------- */
sessile_status sessile_vec_create(sessile_la *la, uint32_t n, sessile_vec **out);
void sessile_vec_destroy(sessile_vec *v);
uint32_t sessile_vec_size(const sessile_vec *v);
sessile_status sessile_vec_upload(sessile_vec *v, const double *src);   /* n values */
sessile_status sessile_vec_download(sessile_vec *v, double *dst);       /* n values */
/* The vector's device buffer (n reals of sessile_la_real_bytes each, padded
 * with zeros to a multiple of 4), for kernels of other layers; the vector
 * keeps owning it. */
sessile_buffer *sessile_vec_buffer(const sessile_vec *v);

/* Each runs on the device and waits (tests, benchmarks, simple callers). */
sessile_status sessile_vec_fill(sessile_la *la, double value, sessile_vec *y);
sessile_status sessile_vec_copy(sessile_la *la, const sessile_vec *x, sessile_vec *y);
sessile_status sessile_vec_scale(sessile_la *la, double alpha, sessile_vec *y);
sessile_status sessile_vec_axpy(sessile_la *la, double alpha, const sessile_vec *x, sessile_vec *y);
sessile_status sessile_vec_aypx(sessile_la *la, double alpha, const sessile_vec *x, sessile_vec *y);
sessile_status sessile_vec_waxpy(sessile_la *la, double alpha, const sessile_vec *x,
                                 const sessile_vec *y, sessile_vec *w);
sessile_status sessile_vec_pmul(sessile_la *la, const sessile_vec *x, const sessile_vec *y,
                                sessile_vec *w);
sessile_status sessile_vec_dot(sessile_la *la, const sessile_vec *x, const sessile_vec *y,
                               double *out);
sessile_status sessile_vec_nrm2(sessile_la *la, const sessile_vec *x, double *out);

/* --- matrices ------------------------------------------------------------- */
/* Uploads A (copied; rows padded to multiples of 4 entries for vector loads).
 * Fails with SESSILE_ERR_NUMERIC if a diagonal entry is zero or not finite
 * only when Jacobi is later requested (see sessile_mat_jacobi). */
sessile_status sessile_mat_create_csr(sessile_la *la, const sessile_csr *a, sessile_mat **out);
sessile_status sessile_mat_create_bcsr4(sessile_la *la, const sessile_bcsr4 *a, sessile_mat **out);
/* New values for a block matrix created from the same pattern (rowptr and
 * col equal): written into its buffers, none allocated (a Newton loop's
 * Jacobians: lavapipe's fresh device memory costs page faults).  A pc set
 * up on m must be set up again.  SESSILE_ERR_USAGE for another pattern (or
 * another chunk limit in the context's options since m was made). */
sessile_status sessile_mat_refill_bcsr4(sessile_mat *m, const sessile_bcsr4 *a);
/* The P1 Laplacian of the uniform Kuhn box as a matrix-free operator: the
 * 7-point stencil times h (diagonal 6h, face neighbours -h) on an
 * nx*ny*nz grid (node i + nx (j + ny k)), with every wall node and every
 * node whose mask entry is non-zero a Dirichlet node, eliminated
 * symmetrically (identity row and column), so the operator is SPD.  `mask`
 * is a device buffer of nx*ny*nz uint32, read at every application (update
 * it between solves freely); the caller owns it and keeps it alive while the
 * matrix exists.  Jacobi is computed on the device (1/(6h) free, 1 Dirichlet).
 * docs/fem.md. */
sessile_status sessile_mat_create_stencil7(sessile_la *la, uint32_t nx, uint32_t ny, uint32_t nz,
                                           double h, sessile_buffer *mask, sessile_mat **out);
/* The cut-cell 7-point operator on an nx*ny*nz vertex grid of spacing h
 * (node i + nx (j + ny k)).  Node n is a Dirichlet node when mask[n] != 0:
 * identity row and column.  For a free node
 *   (A x)_n = h (diag[n] x_n - sum over existing face neighbours m that are free of f_nm x_m)
 * where f_nm, the face fraction of the edge n-m along axis a, is the product over the two
 * other axes b of (1/2 if n lies on the grid's boundary in b (index 0 or n_b-1), else 1).
 * A missing neighbour (outside the grid) contributes nothing: the grid's walls are zero-flux
 * unless the caller makes wall nodes Dirichlet in the mask.  diag[n] (dimensionless, > 0 on
 * free nodes) is supplied by the caller: sum over existing neighbours of f_nm w_nm, w = 1 for
 * a free or Dirichlet-node neighbour and 1/theta for an edge cut by a Dirichlet boundary at
 * fraction theta from n (Gibou et al. 2002, symmetric Shortley-Weller).  mask and diag are read
 * at every application (change their contents between solves freely); the caller owns both
 * and keeps them alive while the matrix exists.  mask: nx*ny*nz uint32; diag: nx*ny*nz reals.
 * Jacobi: 1/(h diag) on free nodes, 1 on Dirichlet nodes.  docs/la.md. */
sessile_status sessile_mat_create_stencil7_cut(sessile_la *la, uint32_t nx, uint32_t ny, uint32_t nz,
                                               double h, sessile_buffer *mask, const sessile_vec *diag,
                                               sessile_mat **out);
/* The same operator with off-diagonal weights (the advected nutrient's exponentially fitted
 * fluxes, docs/nutrient.md): for a free node
 *   (A x)_n = h (diag[n] x_n - sum over free existing neighbours m of f_nm coef[6 n + d] x_m),
 * d the direction of m from n (0..5: -x, +x, -y, +y, -z, +z).  Nonsymmetric: not for CG.
 * coef (6 reals per node) is the caller's, read at every application like mask and diag;
 * read through texel buffers (SESSILE_ERR_TOO_LARGE past the device's texel limit).
 * Plain-C reference: sessile_ref_stencil7_cut_adv. */
sessile_status sessile_mat_create_stencil7_cut_adv(sessile_la *la, uint32_t nx, uint32_t ny,
                                                   uint32_t nz, double h, sessile_buffer *mask,
                                                   const sessile_vec *diag, const sessile_vec *coef,
                                                   sessile_mat **out);
void sessile_mat_destroy(sessile_mat *m);
uint32_t sessile_mat_rows(const sessile_mat *m);
uint64_t sessile_mat_nnz(const sessile_mat *m); /* stored scalar entries, before padding */
/* Row chunks the matrix is stored in (1 unless its arrays exceed
 * maxStorageBufferRange, or the la's max_matrix_chunk_bytes when set; 0 for
 * the matrix-free 7-point operators). */
uint32_t sessile_mat_chunks(const sessile_mat *m);
/* y = A x on the device. */
sessile_status sessile_mat_mult(sessile_la *la, const sessile_mat *a, const sessile_vec *x,
                                sessile_vec *y);
/* The Jacobi preconditioner: dinv = 1/diag(A) (fails on a zero diagonal, naming the row). */
sessile_status sessile_mat_jacobi(sessile_la *la, const sessile_mat *a, sessile_vec *dinv);

/* ILU(0) preconditioner of an assembled CSR or BCSR4 matrix (not the
 * matrix-free stencil): factorised once on the host in double (O(nnz) work,
 * sessile_ref_ilu0_*), stored on the device in the context precision with the
 * rows of L and of U grouped by level (level scheduling), and applied as one
 * dispatch per level.  The factors are cached inside the matrix (computed on
 * first use, freed with it): a const matrix is only logically const here.
 * Fails with SESSILE_ERR_NUMERIC naming the row on a zero or singular pivot.
 * docs/design.md ("ILU(0)"). */
typedef struct sessile_ilu0_info {
  uint32_t levels_lower, levels_upper; /* dispatches per application: their sum */
  double seconds;                      /* host factorisation, levels and upload */
} sessile_ilu0_info;
sessile_status sessile_mat_ilu0(sessile_la *la, const sessile_mat *a, sessile_ilu0_info *info);
/* z = (L U)⁻¹ r on the device (factorises first when needed); waits. */
sessile_status sessile_mat_ilu0_apply(sessile_la *la, const sessile_mat *a, const sessile_vec *r,
                                      sessile_vec *z);

/* --- Krylov solvers --------------------------------------------------------- */
typedef enum sessile_ksp_type { SESSILE_KSP_CG = 0, SESSILE_KSP_BICGSTAB = 1, SESSILE_KSP_GMRES = 2 } sessile_ksp_type;
/* The registered preconditioners (sessile/la/pc.h has the objects and the
 * registry by name).  Right preconditioning for BiCGSTAB and GMRES; CG takes
 * the symmetric ones only (not ILU0).  ILU0: CSR and BCSR4 matrices only;
 * MG: only as an object (sessile_pc_mg_set gives it its hierarchy). */
typedef enum sessile_pc_type {
  SESSILE_PC_NONE = 0,
  SESSILE_PC_JACOBI = 1,
  SESSILE_PC_ILU0 = 2,
  SESSILE_PC_BLOCK_JACOBI = 3,
  SESSILE_PC_MG = 4
} sessile_pc_type;

/* A progress monitor: called with one line of text (no trailing newline) at
 * each point the solver reports; user is the options' monitor_user.  NULL
 * (the default) keeps the library silent: it prints nothing itself. */
typedef void (*sessile_monitor_fn)(void *user, const char *line);
/* The one formatter of monitor lines (the solvers', the fluid's, the growth
 * loop's): fmt and ap into a line of at most SESSILE_MONITOR_LINE - 1
 * characters, handed to fn(user, line); nothing when fn is NULL. */
enum { SESSILE_MONITOR_LINE = 1200 };
void sessile_monitor_vprintf(sessile_monitor_fn fn, void *user, const char *fmt, va_list ap)
    __attribute__((format(printf, 3, 0)));

typedef struct sessile_ksp_options {
  sessile_ksp_type type;
  sessile_pc_type pc; /* built and set up by sessile_ksp_solve (default jacobi);
                         sessile_ksp_solve_pc with a pc object ignores it */
  double rtol;      /* on the true relative residual ‖b−Ax‖/‖b‖; default 1e-6 */
  int max_it;       /* default 1000 */
  int restart;      /* GMRES(m): m, default 30 */
  int check_every;  /* iterations recorded per submit (CG/BiCGSTAB); default 16 */
  int x_zero;       /* 1: x is zero on entry, so GMRES starts from r = b without
                       computing A x (PETSc's default; the same bits); default 0:
                       x is any initial guess */
  sessile_monitor_fn monitor; /* iteration and residual at every check, restarts and
                                 the outcome; default NULL (silent) */
  void *monitor_user;
} sessile_ksp_options;

void sessile_ksp_options_default(sessile_ksp_options *o);
const char *sessile_ksp_type_name(sessile_ksp_type t);
/* The registered name: "none", "jacobi", "ilu0", "block_jacobi", "mg" ("?" otherwise). */
const char *sessile_pc_type_name(sessile_pc_type t);

typedef enum sessile_solve_status {
  SESSILE_SOLVE_CONVERGED = 0,
  SESSILE_SOLVE_MAX_ITER = 1,   /* max_it reached before rtol */
  SESSILE_SOLVE_BREAKDOWN = 2   /* indefinite/singular matrix, zero divisor or non-finite value */
} sessile_solve_status;
const char *sessile_solve_status_name(sessile_solve_status s);

typedef struct sessile_solve_result {
  int iterations;            /* Krylov iterations (GMRES: Arnoldi steps), all refinements */
  int refinements;           /* outer mixed-precision refinement steps (fp32 devices), else 0 */
  int restarts;              /* BiCGSTAB: restarts where r̂0·r fell to rounding (docs/la.md), else 0 */
  double true_relres;        /* ‖b − A x‖/‖b‖ recomputed at the end (0 for b = 0) */
  double est_relres;         /* the solver's recursive estimate at the end */
  sessile_solve_status status;
  char reason[128];          /* why it stopped, in words */
  double seconds;            /* wall time of the whole solve */
} sessile_solve_result;

/* Solves A x = b; x holds the initial guess (warm start) on entry.  Returns
 * SESSILE_OK whenever the solve ran, whatever its status; the caller decides
 * whether MAX_ITER or BREAKDOWN is an error.  x never receives NaN: on
 * breakdown it holds the last finite iterate. */
sessile_status sessile_ksp_solve(sessile_la *la, const sessile_ksp_options *opt,
                                 const sessile_mat *a, const sessile_vec *b, sessile_vec *x,
                                 sessile_solve_result *res);

#ifdef __cplusplus
}
#endif
#endif
