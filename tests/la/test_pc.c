/* The preconditioner objects (sessile/la/pc.h): the registry, every registered
 * pc applied on the device against its plain-C reference, and the Krylov
 * solvers with each pc.
 *
 * Run twice by ctest: default precision (fp64 on lavapipe) and --fp32.
 * Checks and tolerances:
 *  - registry: every registered name creates a pc of that name and type, the
 *    type's name is the registered one; an unknown name is SESSILE_ERR_USAGE
 *    whose message names it and lists the registered ones;
 *  - apply: z = M⁻¹ r on the device against the reference (none: r; jacobi:
 *    sessile_ref_jacobi_*; block_jacobi: sessile_ref_bjacobi_*, on CSR and
 *    the stencil the jacobi reference; ilu0: sessile_ref_ilu0_*; mg:
 *    sessile_ref_mg_vcycle) on a CSR convection-diffusion matrix, a random
 *    BCSR4 matrix and the cut-cell stencil of the multigrid sphere problem:
 *    max |z − z_ref| / max |z_ref| <= 1e-11 in fp64 (rounding ε times the
 *    growth of the triangular solves and the V-cycle, ~1e2; the same bound as
 *    test_ilu), 1e-4 in fp32 (the operators are stored in float); also a
 *    block_jacobi pc set up again, for a CSR matrix after a BCSR4 one;
 *    a singular diagonal block is SESSILE_ERR_NUMERIC naming its block row;
 *  - misuse: ilu0 on the matrix-free stencil, mg without or with a wrong
 *    hierarchy, apply before setup or in place, CG with ilu0: SESSILE_ERR_USAGE;
 *  - solves: CG (the symmetric pcs, SPD matrices), GMRES and BiCGSTAB (every
 *    pc) converge with the true relative residual recomputed on the host in
 *    double <= rtol = 1e-6; block Jacobi on A ⊗ S (S a coupled SPD 4x4 block)
 *    takes fewer CG iterations than point Jacobi; CG with the mg pc takes the
 *    iterations of the fused sessile_mg_solve (±1); a pc object and the
 *    options' enum give bitwise the same solution (one code path). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sessile/la/la_ref.h"
#include "sessile/la/pc.h"
#include "testutil.h"

static sessile_la *la;
static int fp32;
static const double rtol = 1e-6;
static double apply_tol(void) { return fp32 ? 1e-4 : 1e-11; }

/* A test operator: a device matrix with its host form (one of csr, bcsr, or
 * the stencil's grid, mask and diag). */
typedef struct {
  const char *name;
  sessile_mat *m;
  uint32_t n;
  const sessile_csr *csr;
  const sessile_bcsr4 *bcsr;
  uint32_t grid[3];
  double h;
  const uint32_t *mask;
  const double *diag;
} op;

/* ---- the multigrid sphere problem (as tests/la/test_mg.c), 17x17x13, 3 levels ---- */
#define NL 3
typedef struct {
  sessile_ref_mg_level ref[NL];
  sessile_mg_level lv[NL];
  uint32_t *mask[NL];
  double *diag[NL], *b;
  sessile_buffer *mb[NL];
  sessile_vec *vd[NL];
  sessile_mg *mg;
} sphere;

static void sphere_build(sphere *p) {
  static const double centre[3] = {17.28, 19.2, 11.52};
  uint32_t n[3] = {17, 17, 13};
  double h = 38.4 / 16;
  for (int l = 0; l < NL; l++) {
    uint32_t nodes = n[0] * n[1] * n[2];
    p->mask[l] = t_xalloc((size_t)nodes * 4);
    p->diag[l] = t_dalloc(nodes);
    if (l == 0) p->b = t_dalloc(nodes);
    sessile_cut_sphere(n[0], n[1], n[2], h, centre, 8.64, p->mask[l], p->diag[l], l ? NULL : p->b);
    if (fp32)
      for (uint32_t i = 0; i < nodes; i++) p->diag[l][i] = (float)p->diag[l][i];
    t_must("mask", sessile_buffer_create(sessile_la_gpu(la), (size_t)nodes * 4, SESSILE_BUFFER_DEVICE, &p->mb[l]));
    t_must("diag", sessile_vec_create(la, nodes, &p->vd[l]));
    t_must("upload", sessile_buffer_upload(p->mb[l], 0, p->mask[l], (size_t)nodes * 4));
    t_must("upload", sessile_vec_upload(p->vd[l], p->diag[l]));
    p->ref[l] = (sessile_ref_mg_level){{n[0], n[1], n[2]}, h, p->mask[l], p->diag[l], NULL};
    p->lv[l] = (sessile_mg_level){{n[0], n[1], n[2]}, h, p->mb[l], p->vd[l], NULL};
    for (int a = 0; a < 3; a++) n[a] = (n[a] - 1) / 2 + 1;
    h *= 2;
  }
  t_must("mg_create", sessile_mg_create(la, NL, p->lv, NULL, &p->mg));
}

static void sphere_free(sphere *p) {
  sessile_mg_destroy(p->mg);
  for (int l = 0; l < NL; l++) {
    free(p->mask[l]);
    free(p->diag[l]);
    sessile_buffer_destroy(p->mb[l]);
    sessile_vec_destroy(p->vd[l]);
  }
  free(p->b);
}

/* A device vector of n reals holding v (zeros when v is NULL). */
static sessile_vec *vec_of(uint32_t n, const double *v) {
  sessile_vec *d = NULL;
  t_must("vec", sessile_vec_create(la, n, &d));
  if (v) t_must("upload", sessile_vec_upload(d, v));
  return d;
}

/* ---- host references ---- */
static void ref_jacobi(const op *o, double *dinv) {
  if (o->csr) t_must("ref jacobi", sessile_ref_jacobi_csr(o->csr, dinv));
  else if (o->bcsr) t_must("ref jacobi", sessile_ref_jacobi_bcsr4(o->bcsr, dinv));
  else /* the stencil's documented Jacobi: 1/(h diag) free, 1 Dirichlet */
    for (uint32_t i = 0; i < o->n; i++) dinv[i] = o->mask[i] ? 1.0 : 1.0 / (o->h * o->diag[i]);
}

static void ref_apply(sessile_pc_type t, const op *o, const sphere *sp, const double *r, double *z) {
  uint32_t n = o->n;
  double *w = NULL;
  switch (t) {
  case SESSILE_PC_NONE: sessile_ref_copy(n, r, z); break;
  case SESSILE_PC_BLOCK_JACOBI:
    if (o->bcsr) {
      w = t_dalloc((size_t)o->bcsr->nbrows * 16);
      t_must("ref bjacobi", sessile_ref_bjacobi_bcsr4(o->bcsr, w));
      sessile_ref_bjacobi_apply(o->bcsr->nbrows, w, r, z);
      break;
    } /* 1x1 blocks: point Jacobi */
    /* fall through */
  case SESSILE_PC_JACOBI:
    w = t_dalloc(n);
    ref_jacobi(o, w);
    sessile_ref_pmul(n, w, r, z);
    break;
  case SESSILE_PC_ILU0:
    if (o->csr) {
      w = t_dalloc(o->csr->nnz);
      t_must("ref ilu0", sessile_ref_ilu0_csr(o->csr, w));
      sessile_ref_ilu0_solve_csr(o->csr, w, r, z);
    } else {
      w = t_dalloc(o->bcsr->nnzb * 16);
      t_must("ref ilu0", sessile_ref_ilu0_bcsr4(o->bcsr, w));
      sessile_ref_ilu0_solve_bcsr4(o->bcsr, w, r, z);
    }
    break;
  case SESSILE_PC_MG: {
    sessile_mg_options mo;
    sessile_mg_options_default(&mo);
    t_must("ref vcycle", sessile_ref_mg_vcycle(NL, sp->ref, &mo, r, z));
    break;
  }
  }
  free(w);
}

/* ||b - A x|| / ||b|| on the host in double. */
static double host_relres(const op *o, const double *b, const double *x) {
  double *r = t_dalloc(o->n);
  if (o->csr) sessile_ref_spmv_csr(o->csr, x, r);
  else if (o->bcsr) sessile_ref_spmv_bcsr4(o->bcsr, x, r);
  else sessile_ref_stencil7_cut(o->grid[0], o->grid[1], o->grid[2], o->h, o->mask, o->diag, x, r);
  for (uint32_t i = 0; i < o->n; i++) r[i] = b[i] - r[i];
  double rel = sessile_ref_nrm2(o->n, r) / sessile_ref_nrm2(o->n, b);
  free(r);
  return rel;
}

/* A set-up pc of type t for o (mg: the sphere's hierarchy). */
static sessile_pc *make_pc(sessile_pc_type t, const op *o, const sphere *sp) {
  sessile_pc *pc = NULL;
  t_must("pc create", sessile_pc_create(la, sessile_pc_type_name(t), &pc));
  if (t == SESSILE_PC_MG) t_must("pc mg set", sessile_pc_mg_set(pc, sp->mg));
  t_must("pc setup", sessile_pc_setup(pc, o->m));
  return pc;
}

static int applies(sessile_pc_type t, const op *o) {
  if (t == SESSILE_PC_ILU0) return o->csr || o->bcsr;
  if (t == SESSILE_PC_MG) return !o->csr && !o->bcsr;
  return 1;
}

/* ---- the registry ---- */
static void test_registry(void) {
  printf("-- the registry\n");
  static const char *want[] = {"none", "jacobi", "ilu0", "block_jacobi", "mg"};
  int count = 0;
  for (const char *name; (name = sessile_pc_registered(count)); count++) {
    sessile_pc *pc = NULL;
    sessile_pc_type t = (sessile_pc_type)-1;
    char what[128];
    snprintf(what, sizeof what, "'%s': created by name, named and typed so", name);
    sessile_status s = sessile_pc_create(la, name, &pc);
    t_true(what, s == SESSILE_OK && !strcmp(sessile_pc_name(pc), name) &&
                     sessile_pc_type_from_name(name, &t) == SESSILE_OK && t == sessile_pc_get_type(pc) &&
                     !strcmp(sessile_pc_type_name(t), name));
    snprintf(what, sizeof what, "'%s': symmetric = %d (only ilu0 is not)", name, pc ? sessile_pc_symmetric(pc) : -1);
    t_true(what, pc && sessile_pc_symmetric(pc) == (t != SESSILE_PC_ILU0));
    sessile_pc_destroy(pc);
  }
  int all = count == (int)(sizeof want / sizeof want[0]);
  for (int i = 0; all && i < count; i++) all = !strcmp(want[i], sessile_pc_registered(i));
  t_true("registered: none, jacobi, ilu0, block_jacobi, mg", all);
  sessile_pc *pc = (sessile_pc *)&pc;
  sessile_status s = sessile_pc_create(la, "ilu1", &pc);
  printf("   message: %s\n", sessile_error_message());
  t_true("unknown name 'ilu1': SESSILE_ERR_USAGE, no pc",
         s == SESSILE_ERR_USAGE && pc == NULL);
  t_true("the message names it and lists the registered names",
         strstr(sessile_error_message(), "'ilu1'") && strstr(sessile_error_message(), "block_jacobi") &&
             strstr(sessile_error_message(), "ilu0"));
  sessile_error_clear();
  sessile_pc_type t;
  t_true("type_from_name(NULL): SESSILE_ERR_USAGE", sessile_pc_type_from_name(NULL, &t) == SESSILE_ERR_USAGE);
  t_true("create_type(99): SESSILE_ERR_USAGE", sessile_pc_create_type(la, (sessile_pc_type)99, &pc) == SESSILE_ERR_USAGE);
  t_true("type name of 99 is '?'", !strcmp(sessile_pc_type_name((sessile_pc_type)99), "?"));
  sessile_error_clear();
  sessile_pc_destroy(NULL); /* NULL-safe */
}

/* ---- device apply = reference ---- */
/* pc (set up for o) applied on the device against the reference of its type. */
static void check_apply_pc(sessile_pc *pc, const op *o, const sphere *sp, const char *label) {
  sessile_pc_type t = sessile_pc_get_type(pc);
  uint32_t n = o->n;
  double *r = t_dalloc(n), *z = t_dalloc(n), *zr = t_dalloc(n);
  sessile_fill_random(r, n, -1, 1, 11 + (uint64_t)t);
  if (fp32) /* the reference sees the r the device stores */
    for (uint32_t i = 0; i < n; i++) r[i] = (float)r[i];
  sessile_vec *vr = vec_of(n, r), *vz = vec_of(n, NULL);
  t_must("apply", sessile_pc_apply(pc, vr, vz));
  t_must("download", sessile_vec_download(vz, z));
  ref_apply(t, o, sp, r, zr);
  char what[200];
  snprintf(what, sizeof what, "%s on %s (%u rows)%s: device = reference", sessile_pc_type_name(t), o->name, n, label);
  t_check(what, t_relerr(z, zr, n), apply_tol());
  sessile_vec_destroy(vr);
  sessile_vec_destroy(vz);
  free(r);
  free(z);
  free(zr);
}

static void check_apply(sessile_pc_type t, const op *o, const sphere *sp) {
  sessile_pc *pc = make_pc(t, o, sp);
  check_apply_pc(pc, o, sp, "");
  sessile_pc_destroy(pc);
}

static void test_misuse(const op *csr, const op *st, const sphere *sp) {
  printf("-- misuse\n");
  sessile_pc *pc = NULL;
  sessile_vec *v = vec_of(csr->n, NULL), *w = vec_of(csr->n, NULL);
  t_must("create", sessile_pc_create(la, "jacobi", &pc));
  t_true("apply before setup: SESSILE_ERR_USAGE", sessile_pc_apply(pc, v, w) == SESSILE_ERR_USAGE);
  t_must("setup", sessile_pc_setup(pc, csr->m));
  t_true("apply in place: SESSILE_ERR_USAGE", sessile_pc_apply(pc, v, v) == SESSILE_ERR_USAGE);
  t_true("mg hierarchy on a jacobi pc: SESSILE_ERR_USAGE", sessile_pc_mg_set(pc, sp->mg) == SESSILE_ERR_USAGE);
  sessile_pc_destroy(pc);
  t_must("create", sessile_pc_create(la, "ilu0", &pc));
  sessile_status s = sessile_pc_setup(pc, st->m);
  printf("   message: %s\n", sessile_error_message());
  t_true("ilu0 on the matrix-free stencil: SESSILE_ERR_USAGE, not set up",
         s == SESSILE_ERR_USAGE && sessile_pc_apply(pc, v, w) == SESSILE_ERR_USAGE);
  sessile_pc_destroy(pc);
  t_must("create", sessile_pc_create(la, "mg", &pc));
  s = sessile_pc_setup(pc, st->m);
  printf("   message: %s\n", sessile_error_message());
  t_true("mg without a hierarchy: SESSILE_ERR_USAGE naming sessile_pc_mg_set",
         s == SESSILE_ERR_USAGE && strstr(sessile_error_message(), "sessile_pc_mg_set"));
  t_must("mg set", sessile_pc_mg_set(pc, sp->mg));
  t_true("mg on a matrix of another size: SESSILE_ERR_USAGE", sessile_pc_setup(pc, csr->m) == SESSILE_ERR_USAGE);
  sessile_pc_destroy(pc);
  /* CG refuses the nonsymmetric pc, whichever way it is given. */
  t_must("create", sessile_pc_create(la, "ilu0", &pc));
  t_must("setup", sessile_pc_setup(pc, csr->m));
  sessile_ksp_options o;
  sessile_ksp_options_default(&o);
  sessile_solve_result res;
  t_must("fill", sessile_vec_fill(la, 1.0, v));
  s = sessile_ksp_solve_pc(la, &o, csr->m, pc, v, w, &res);
  printf("   message: %s\n", sessile_error_message());
  t_true("CG with the ilu0 object: SESSILE_ERR_USAGE", s == SESSILE_ERR_USAGE);
  o.pc = SESSILE_PC_ILU0;
  t_true("CG with the ilu0 enum: SESSILE_ERR_USAGE", sessile_ksp_solve(la, &o, csr->m, v, w, &res) == SESSILE_ERR_USAGE);
  sessile_pc_destroy(pc);
  t_must("create", sessile_pc_create(la, "jacobi", &pc));
  o.type = SESSILE_KSP_GMRES;
  t_true("a pc not set up: SESSILE_ERR_USAGE", sessile_ksp_solve_pc(la, &o, csr->m, pc, v, w, &res) == SESSILE_ERR_USAGE);
  sessile_pc_destroy(pc);
  sessile_error_clear();
  sessile_vec_destroy(v);
  sessile_vec_destroy(w);
}

/* ---- solves ---- */
static int solve(sessile_ksp_type k, sessile_pc_type t, const op *o, const sphere *sp, const double *b,
                 double *x) {
  sessile_vec *vb = vec_of(o->n, b), *vx = vec_of(o->n, NULL);
  sessile_pc *pc = make_pc(t, o, sp);
  sessile_ksp_options opt;
  sessile_ksp_options_default(&opt);
  opt.type = k;
  opt.rtol = rtol;
  opt.max_it = 2000;
  sessile_solve_result res;
  t_must("solve", sessile_ksp_solve_pc(la, &opt, o->m, pc, vb, vx, &res));
  t_must("download", sessile_vec_download(vx, x));
  double rel = host_relres(o, b, x);
  char what[200];
  snprintf(what, sizeof what, "%s + %s on %s: %s, %d iterations; host true relres",
           sessile_ksp_type_name(k), sessile_pc_type_name(t), o->name,
           sessile_solve_status_name(res.status), res.iterations);
  t_check(what, res.status == SESSILE_SOLVE_CONVERGED ? rel : INFINITY, rtol);
  sessile_pc_destroy(pc);
  sessile_vec_destroy(vb);
  sessile_vec_destroy(vx);
  return res.iterations;
}

/* A ⊗ S as BCSR4: every block a_ij S, S SPD and coupled (tridiagonal 1.8, 4, 1.8). */
static void kron(const sessile_csr *a, sessile_bcsr4 *out) {
  t_must("alloc", sessile_bcsr4_alloc(a->nrows, a->ncols, a->nnz, out));
  memcpy(out->rowptr, a->rowptr, ((size_t)a->nrows + 1) * sizeof *a->rowptr);
  memcpy(out->col, a->col, a->nnz * sizeof *a->col);
  for (uint64_t e = 0; e < a->nnz; e++)
    for (int q = 0; q < 16; q++) {
      int i = q / 4, j = q % 4;
      out->val[16 * e + q] = a->val[e] * (i == j ? 4.0 : abs(i - j) == 1 ? 1.8 : 0.0);
    }
}

static void test_solves(const op *ops, int nops, const sphere *sp) {
  printf("-- solves\n");
  for (int i = 0; i < nops; i++) {
    const op *o = &ops[i];
    double *b = t_dalloc(o->n), *x = t_dalloc(o->n);
    if (o->csr || o->bcsr) sessile_fill_random(b, o->n, -1, 1, 77);
    else memcpy(b, sp->b, o->n * sizeof *b);
    for (int t = 0; sessile_pc_registered(t); t++) {
      if (!applies((sessile_pc_type)t, o)) continue;
      solve(SESSILE_KSP_GMRES, (sessile_pc_type)t, o, sp, b, x);
      solve(SESSILE_KSP_BICGSTAB, (sessile_pc_type)t, o, sp, b, x);
    }
    free(b);
    free(x);
  }
}

static void test_cg(const sphere *sp, const op *st) {
  printf("-- CG with the symmetric pcs\n");
  sessile_csr a = {0};
  sessile_bcsr4 k = {0};
  t_must("laplacian", sessile_csr_laplacian7(8, 8, 8, &a));
  kron(&a, &k);
  op oa = {.name = "laplacian 8^3", .n = a.nrows, .csr = &a};
  op ok = {.name = "laplacian 8^3 x S", .n = 4 * k.nbrows, .bcsr = &k};
  t_must("mat", sessile_mat_create_csr(la, &a, &oa.m));
  t_must("mat", sessile_mat_create_bcsr4(la, &k, &ok.m));
  double *b = t_dalloc(ok.n), *x = t_dalloc(ok.n);
  sessile_fill_random(b, ok.n, -1, 1, 5);
  for (int t = 0; sessile_pc_registered(t); t++)
    if (t != SESSILE_PC_ILU0 && t != SESSILE_PC_MG) {
      solve(SESSILE_KSP_CG, (sessile_pc_type)t, &oa, sp, b, x);
      solve(SESSILE_KSP_CG, (sessile_pc_type)t, &ok, sp, b, x);
    }
  int ij = solve(SESSILE_KSP_CG, SESSILE_PC_JACOBI, &ok, sp, b, x);
  int ib = solve(SESSILE_KSP_CG, SESSILE_PC_BLOCK_JACOBI, &ok, sp, b, x);
  char what[160];
  snprintf(what, sizeof what, "A x S: block Jacobi couples each block (%d CG iterations < point Jacobi's %d)", ib, ij);
  t_true(what, ib < ij);
  /* The mg pc in the generic CG against the fused MG-PCG. */
  double *bs = t_dalloc(st->n), *xs = t_dalloc(st->n);
  memcpy(bs, sp->b, st->n * sizeof *bs);
  int im = solve(SESSILE_KSP_CG, SESSILE_PC_MG, st, sp, bs, xs);
  solve(SESSILE_KSP_CG, SESSILE_PC_JACOBI, st, sp, bs, xs);
  sessile_vec *vb = vec_of(st->n, bs), *vx = vec_of(st->n, NULL);
  sessile_ksp_options o;
  sessile_ksp_options_default(&o);
  o.rtol = rtol;
  sessile_solve_result res;
  t_must("mg_solve", sessile_mg_solve(sp->mg, &o, vb, vx, &res));
  snprintf(what, sizeof what, "CG + mg pc: %d iterations, the fused sessile_mg_solve %d (+-1)", im, res.iterations);
  t_true(what, abs(im - res.iterations) <= 1);
  sessile_vec_destroy(vb);
  sessile_vec_destroy(vx);
  sessile_mat_destroy(oa.m);
  sessile_mat_destroy(ok.m);
  sessile_csr_free(&a);
  sessile_bcsr4_free(&k);
  free(b);
  free(x);
  free(bs);
  free(xs);
}

/* The options' enum builds the same pc as the object: bitwise the same x. */
static void test_same_path(const op *o, sessile_pc_type t) {
  double *b = t_dalloc(o->n), *x1 = t_dalloc(o->n), *x2 = t_dalloc(o->n);
  sessile_fill_random(b, o->n, -1, 1, 9);
  sessile_vec *vb = vec_of(o->n, b), *vx = vec_of(o->n, NULL);
  sessile_ksp_options opt;
  sessile_ksp_options_default(&opt);
  opt.type = SESSILE_KSP_GMRES;
  opt.pc = t;
  sessile_solve_result r1, r2;
  t_must("solve enum", sessile_ksp_solve(la, &opt, o->m, vb, vx, &r1));
  t_must("download", sessile_vec_download(vx, x1));
  t_must("fill", sessile_vec_fill(la, 0.0, vx));
  sessile_pc *pc = make_pc(t, o, NULL);
  opt.pc = SESSILE_PC_NONE; /* ignored: the object decides */
  t_must("solve object", sessile_ksp_solve_pc(la, &opt, o->m, pc, vb, vx, &r2));
  t_must("download", sessile_vec_download(vx, x2));
  char what[160];
  snprintf(what, sizeof what, "gmres + %s on %s: the enum and the object give bitwise the same x",
           sessile_pc_type_name(t), o->name);
  t_true(what, r1.iterations == r2.iterations && !memcmp(x1, x2, o->n * sizeof *x1));
  sessile_pc_destroy(pc);
  sessile_vec_destroy(vb);
  sessile_vec_destroy(vx);
  free(b);
  free(x1);
  free(x2);
}

/* One pc set up again for another matrix (the release paths). */
static void test_resetup(const op *bc, const op *csr, const sphere *sp) {
  sessile_pc *pc = make_pc(SESSILE_PC_BLOCK_JACOBI, bc, sp);
  t_must("setup again", sessile_pc_setup(pc, csr->m));
  check_apply_pc(pc, csr, sp, ", set up on BCSR4 before");
  sessile_pc_destroy(pc);
}

/* A singular diagonal block: the setup's error names the block row. */
static void test_singular_block(void) {
  sessile_bcsr4 b = {0};
  t_must("alloc", sessile_bcsr4_alloc(3, 3, 3, &b));
  for (uint32_t i = 0; i <= 3; i++) b.rowptr[i] = i;
  for (uint32_t i = 0; i < 3; i++) b.col[i] = i;
  for (int q = 0; q < 48; q++) b.val[q] = (q % 16) / 4 == q % 4 ? 2.0 : 0.25;
  for (int q = 0; q < 4; q++) b.val[16 + 4 + q] = b.val[16 + q]; /* block 1: two equal rows */
  sessile_mat *m = NULL;
  t_must("mat", sessile_mat_create_bcsr4(la, &b, &m));
  sessile_pc *pc = NULL;
  t_must("create", sessile_pc_create(la, "block_jacobi", &pc));
  sessile_status s = sessile_pc_setup(pc, m);
  printf("   message: %s\n", sessile_error_message());
  t_true("singular diagonal block: SESSILE_ERR_NUMERIC naming block row 1",
         s == SESSILE_ERR_NUMERIC && strstr(sessile_error_message(), "block row 1"));
  sessile_error_clear();
  sessile_pc_destroy(pc);
  sessile_mat_destroy(m);
  sessile_bcsr4_free(&b);
}

int main(int argc, char **argv) {
  sessile_gpu *g = t_gpu_args(argc, argv, &fp32);
  t_must("la_create", sessile_la_create(g, &la));
  test_registry();

  sphere sp = {0};
  sphere_build(&sp);
  sessile_csr cd = {0}, pat = {0};
  sessile_bcsr4 rb = {0};
  t_must("convdiff", sessile_csr_convdiff(8, 7, 6, 10.0, &cd));
  t_must("pattern", sessile_csr_convdiff(6, 5, 4, 0.0, &pat));
  t_must("bcsr4", sessile_bcsr4_random_on(&pat, 17, &rb));
  op ops[3] = {
      {.name = "convdiff 8x7x6", .n = cd.nrows, .csr = &cd},
      {.name = "random bcsr4 6x5x4", .n = 4 * rb.nbrows, .bcsr = &rb},
      {.name = "cut sphere 17x17x13", .n = 17 * 17 * 13, .grid = {17, 17, 13}, .h = sp.lv[0].h,
       .mask = sp.mask[0], .diag = sp.diag[0]},
  };
  t_must("mat", sessile_mat_create_csr(la, &cd, &ops[0].m));
  t_must("mat", sessile_mat_create_bcsr4(la, &rb, &ops[1].m));
  t_must("mat", sessile_mat_create_stencil7_cut(la, 17, 17, 13, sp.lv[0].h, sp.mb[0], sp.vd[0], &ops[2].m));

  printf("-- apply = reference\n");
  for (int i = 0; i < 3; i++)
    for (int t = 0; sessile_pc_registered(t); t++)
      if (applies((sessile_pc_type)t, &ops[i])) check_apply((sessile_pc_type)t, &ops[i], &sp);
  test_resetup(&ops[1], &ops[0], &sp);
  test_singular_block();
  test_misuse(&ops[0], &ops[2], &sp);
  test_solves(ops, 3, &sp);
  test_cg(&sp, &ops[2]);
  test_same_path(&ops[1], SESSILE_PC_ILU0);
  test_same_path(&ops[0], SESSILE_PC_JACOBI);

  for (int i = 0; i < 3; i++) sessile_mat_destroy(ops[i].m);
  sessile_csr_free(&cd);
  sessile_csr_free(&pat);
  sessile_bcsr4_free(&rb);
  sphere_free(&sp);
  sessile_la_destroy(la);
  return t_finish(g);
}
