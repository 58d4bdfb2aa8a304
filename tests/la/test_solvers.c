/* GPU Krylov solvers (sessile_ksp_solve): PCG, BiCGSTAB and GMRES(30) with
 * Jacobi, on SPD, nonsymmetric, block, indefinite and singular systems, plus
 * the zero and NaN right-hand sides, warm starts, iteration limits and the
 * mapped-buffer contract (check_every must not change the result).
 *
 * Run twice by ctest: default precision (fp64 on lavapipe) and --fp32
 * (context precision 32: fp32 Krylov vectors inside mixed-precision
 * iterative refinement).  The big PCG problem is 48^3 in fp64 and 32^3 in
 * fp32 (to keep the run short).
 *
 * Every convergence claim is checked on the host: x is downloaded and the
 * true relative residual ||b - A x|| / ||b|| is recomputed in double with
 * sessile_ref_true_relres (sessile_ref_spmv_bcsr4 for block matrices).
 * Tolerances:
 *  - converged solves: host residual <= rtol = 1e-6, the solver's own
 *    stopping criterion (it promises the *true* residual, see la.h);
 *  - res.true_relres vs the host value: 1e-3 relative in fp64: the residual
 *    is ~1e-6 ||b|| while each component of b - A x carries rounding
 *    ~eps (|b| + |A||x|) <~ 1e-13 ||b|| here, so the two computations agree
 *    to ~1e-7 relative; fp32 path: 1e-1 relative, because the device keeps x
 *    in float, so the x we download is the refined double iterate rounded to
 *    float (6e-8 relative), which moves a 1e-6 residual by up to
 *    ~6e-8 ||A|| ||x|| / ||b||;
 *  - fp32 path: b is rounded to float on the host first, so both sides
 *    solve the same system. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sessile/la/la_ref.h"
#include "testutil.h"

static sessile_la *la;
static int fp32;
static const double rtol = 1e-6;

static void fill(double *v, size_t n, double a) {
  for (size_t i = 0; i < n; i++) v[i] = a;
}

static int all_finite(const double *v, size_t n) {
  for (size_t i = 0; i < n; i++)
    if (!isfinite(v[i])) return 0;
  return 1;
}

static double max_abs(const double *v, size_t n) {
  double m = 0;
  for (size_t i = 0; i < n; i++)
    if (!(fabs(v[i]) <= m)) m = fabs(v[i]);
  return m;
}

/* Random right-hand side in [-1, 1), representable in the context precision. */
static void rhs(double *b, uint32_t n, uint64_t seed) {
  sessile_fill_random(b, n, -1.0, 1.0, seed);
  if (fp32)
    for (uint32_t i = 0; i < n; i++) b[i] = (double)(float)b[i];
}

/* ||b - A x|| / ||b|| for a block matrix (the CSR one is sessile_ref_true_relres). */
static double relres_bcsr4(const sessile_bcsr4 *a, const double *b, const double *x) {
  uint32_t n = 4 * a->nbrows;
  double *r = t_dalloc(n);
  sessile_ref_spmv_bcsr4(a, x, r);
  for (uint32_t i = 0; i < n; i++) r[i] = b[i] - r[i];
  double q = sessile_ref_nrm2(n, r) / sessile_ref_nrm2(n, b);
  free(r);
  return q;
}

/* Uploads b and the initial guess x, solves, downloads x (also after a
 * breakdown: la.h promises it stays finite). */
static sessile_status solve(const sessile_ksp_options *o, const sessile_mat *m, const double *b,
                            double *x, sessile_solve_result *res) {
  uint32_t n = sessile_mat_rows(m);
  sessile_vec *vb = NULL, *vx = NULL;
  t_must("vec_create", sessile_vec_create(la, n, &vb));
  t_must("vec_create", sessile_vec_create(la, n, &vx));
  t_must("upload b", sessile_vec_upload(vb, b));
  t_must("upload x", sessile_vec_upload(vx, x));
  memset(res, 0, sizeof *res);
  sessile_status s = sessile_ksp_solve(la, o, m, vb, vx, res);
  t_must("download x", sessile_vec_download(vx, x));
  sessile_vec_destroy(vb);
  sessile_vec_destroy(vx);
  return s;
}

static void show(const char *name, const sessile_solve_result *r, double host) {
  printf("   %s: %s after %d iterations (%d refinements), true_relres %.3e (host %.3e), est "
         "%.3e, %.3f s, reason \"%s\"\n",
         name, sessile_solve_status_name(r->status), r->iterations, r->refinements, r->true_relres,
         host, r->est_relres, r->seconds, r->reason);
}

/* The checks every converged solve gets. */
static void check_converged(const char *name, sessile_status s, const sessile_solve_result *r,
                            double host) {
  char what[200];
  show(name, r, host);
  snprintf(what, sizeof what, "%s: ksp_solve returns SESSILE_OK and status converged", name);
  t_true(what, s == SESSILE_OK && r->status == SESSILE_SOLVE_CONVERGED);
  snprintf(what, sizeof what, "%s: host-recomputed ||b-Ax||/||b|| <= rtol", name);
  t_check(what, host, rtol);
  snprintf(what, sizeof what, "%s: res.true_relres vs host value (relative)", name);
  t_check(what, fabs(r->true_relres - host) / host, fp32 ? 1e-1 : 1e-3);
}

static sessile_ksp_options opts(sessile_ksp_type t, sessile_pc_type pc, int max_it) {
  sessile_ksp_options o;
  sessile_ksp_options_default(&o);
  o.type = t;
  o.pc = pc;
  o.rtol = rtol;
  o.max_it = max_it;
  return o;
}

static const char *kname(sessile_ksp_type t) {
  return t == SESSILE_KSP_CG ? "CG" : t == SESSILE_KSP_BICGSTAB ? "BiCGSTAB" : "GMRES(30)";
}

/* ---- PCG on the big Laplacian, then a warm start from its solution ---- */
static void test_pcg_laplacian(void) {
  const uint32_t g = fp32 ? 32 : 48;
  char name[96];
  snprintf(name, sizeof name, "PCG(Jacobi) laplacian7 %u^3", g);
  printf("-- %s%s\n", name, fp32 ? " (32^3 instead of 48^3 in the fp32 run, to save time)" : "");
  sessile_csr a;
  t_must("laplacian7", sessile_csr_laplacian7(g, g, g, &a));
  const uint32_t n = a.nrows;
  double *b = t_dalloc(n), *x = t_dalloc(n);
  rhs(b, n, 64);
  fill(x, n, 0.0);
  sessile_mat *m = NULL;
  t_must("mat_create_csr", sessile_mat_create_csr(la, &a, &m));
  sessile_ksp_options o = opts(SESSILE_KSP_CG, SESSILE_PC_JACOBI, 1000);
  sessile_solve_result r;
  sessile_status s = solve(&o, m, b, x, &r);
  double host = sessile_ref_true_relres(&a, b, x);
  printf("   n = %u: %d iterations in %.2f s\n", n, r.iterations, r.seconds);
  check_converged(name, s, &r, host);
  if (fp32) {
    char what[160];
    snprintf(what, sizeof what, "%s: fp32 path used iterative refinement (refinements = %d >= 1)",
             name, r.refinements);
    t_true(what, r.refinements >= 1);
  } else {
    t_true("fp64: no refinement steps (refinements == 0)", r.refinements == 0);
  }

  /* Warm start from the converged x: nothing left to do. */
  sessile_solve_result w;
  s = solve(&o, m, b, x, &w);
  double host2 = sessile_ref_true_relres(&a, b, x);
  show("warm start", &w, host2);
  t_true("warm start from the converged x: status converged in <= 1 iteration",
         s == SESSILE_OK && w.status == SESSILE_SOLVE_CONVERGED && w.iterations <= 1);
  t_check("warm start: host-recomputed relres <= rtol", host2, rtol);

  /* Iteration limit: exactly max_it iterations, status max-iterations. */
  fill(x, n, 0.0);
  o.max_it = 5;
  s = solve(&o, m, b, x, &r);
  show("PCG max_it 5", &r, sessile_ref_true_relres(&a, b, x));
  t_true("PCG with max_it 5: status max-iterations after exactly 5 iterations, x finite",
         s == SESSILE_OK && r.status == SESSILE_SOLVE_MAX_ITER && r.iterations == 5 &&
             all_finite(x, n));

  sessile_mat_destroy(m);
  sessile_csr_free(&a);
  free(b);
  free(x);
}

/* ---- nonsymmetric convection-diffusion: BiCGSTAB and GMRES(30) ---- */
static void test_convdiff(void) {
  printf("-- convdiff 32^3, cell Peclet 2 (nonsymmetric)\n");
  sessile_csr a;
  t_must("convdiff", sessile_csr_convdiff(32, 32, 32, 2.0, &a));
  const uint32_t n = a.nrows;
  double *b = t_dalloc(n), *x = t_dalloc(n), *d = t_dalloc(n);
  rhs(b, n, 32);
  t_must("ref_jacobi", sessile_ref_jacobi_csr(&a, d));
  sessile_mat *m = NULL;
  t_must("mat_create_csr", sessile_mat_create_csr(la, &a, &m));
  const sessile_ksp_type ts[2] = {SESSILE_KSP_BICGSTAB, SESSILE_KSP_GMRES};
  for (int k = 0; k < 2; k++) {
    char name[96];
    snprintf(name, sizeof name, "%s(Jacobi) convdiff 32^3 Pe=2", kname(ts[k]));
    sessile_ksp_options o = opts(ts[k], SESSILE_PC_JACOBI, 2000);
    sessile_solve_result r;
    fill(x, n, 0.0);
    sessile_status s = solve(&o, m, b, x, &r);
    check_converged(name, s, &r, sessile_ref_true_relres(&a, b, x));
    /* For comparison only (different rounding, so no check): the host reference. */
    fill(x, n, 0.0);
    sessile_ref_result rr = ts[k] == SESSILE_KSP_BICGSTAB
                                ? sessile_ref_bicgstab(&a, d, b, x, rtol, 2000)
                                : sessile_ref_gmres(&a, d, b, x, rtol, 2000, 30);
    printf("   host reference %s: %d iterations, relres %.3e\n", kname(ts[k]), rr.iterations,
           rr.true_relres);
  }
  sessile_mat_destroy(m);
  sessile_csr_free(&a);
  free(b);
  free(x);
  free(d);
}

/* ---- P1 tetrahedra K+M (SPD, 15-point) with PCG ---- */
static void test_p1tet(void) {
  printf("-- PCG(Jacobi) on P1-tet K+M, 32^3 cubes\n");
  sessile_csr a;
  t_must("p1tet", sessile_csr_p1tet(32, 32, 32, 1.0 / 32, 1.0 / 32, 1.0 / 32, &a));
  const uint32_t n = a.nrows;
  double *b = t_dalloc(n), *x = t_dalloc(n), *d = t_dalloc(n);
  rhs(b, n, 33);
  sessile_mat *m = NULL;
  t_must("mat_create_csr", sessile_mat_create_csr(la, &a, &m));
  sessile_ksp_options o = opts(SESSILE_KSP_CG, SESSILE_PC_JACOBI, 2000);
  sessile_solve_result r;
  fill(x, n, 0.0);
  sessile_status s = solve(&o, m, b, x, &r);
  check_converged("PCG(Jacobi) p1tet 32^3 (n = 33^3)", s, &r, sessile_ref_true_relres(&a, b, x));
  /* The same algorithm and stopping rule on the host: PCG's iteration count
   * is insensitive to rounding, so it must agree closely (fp64). */
  t_must("ref_jacobi", sessile_ref_jacobi_csr(&a, d));
  fill(x, n, 0.0);
  sessile_ref_result rr = sessile_ref_pcg(&a, d, b, x, rtol, 2000);
  printf("   host reference PCG: %d iterations, relres %.3e\n", rr.iterations, rr.true_relres);
  if (!fp32) {
    double diff = fabs((double)r.iterations - rr.iterations);
    t_check("PCG p1tet: |GPU iterations - ref_pcg iterations| (fp64, same algorithm)", diff,
            fmax(2.0, 0.02 * rr.iterations));
  }
  sessile_mat_destroy(m);
  sessile_csr_free(&a);
  free(b);
  free(x);
  free(d);
}

/* ---- GMRES on a 4x4 block-CSR system ---- */
static void test_bcsr4(void) {
  printf("-- GMRES(30)(Jacobi) on bcsr4_random_on(laplacian7 16^3)\n");
  sessile_csr pat;
  sessile_bcsr4 a;
  t_must("laplacian7", sessile_csr_laplacian7(16, 16, 16, &pat));
  t_must("bcsr4_random_on", sessile_bcsr4_random_on(&pat, 99, &a));
  if (fp32)
    for (uint64_t i = 0; i < 16 * a.nnzb; i++) a.val[i] = (double)(float)a.val[i];
  const uint32_t n = 4 * a.nbrows;
  double *b = t_dalloc(n), *x = t_dalloc(n);
  rhs(b, n, 16);
  fill(x, n, 0.0);
  sessile_mat *m = NULL;
  t_must("mat_create_bcsr4", sessile_mat_create_bcsr4(la, &a, &m));
  sessile_ksp_options o = opts(SESSILE_KSP_GMRES, SESSILE_PC_JACOBI, 1000);
  sessile_solve_result r;
  sessile_error_clear();
  sessile_status s = solve(&o, m, b, x, &r);
  if (s != SESSILE_OK)
    printf("   ksp_solve: %s: \"%s\"\n", sessile_status_name(s), sessile_error_message());
  check_converged("GMRES(30) bcsr4 16^3 (n = 16384)", s, &r, relres_bcsr4(&a, b, x));
  /* x_zero: the first cycle starts from r = b without A x, later cycles
   * from b - A x: the same x bit for bit (b - A 0 is b); GMRES(3), so that
   * several cycles run */
  double *x0 = t_dalloc(n);
  sessile_solve_result r0;
  o.restart = 3;
  fill(x, n, 0.0);
  t_must("solve (restart 3)", solve(&o, m, b, x, &r));
  fill(x0, n, 0.0);
  o.x_zero = 1;
  t_must("solve (restart 3, x_zero)", solve(&o, m, b, x0, &r0));
  printf("   GMRES(3): %d iterations, %d with x_zero\n", r.iterations, r0.iterations);
  t_true("GMRES(3) x_zero: several cycles, the same iterations and x, bit for bit",
         r.iterations > 3 && r0.iterations == r.iterations && memcmp(x0, x, n * sizeof *x) == 0);
  free(x0);
  sessile_mat_destroy(m);
  sessile_bcsr4_free(&a);
  sessile_csr_free(&pat);
  free(b);
  free(x);
}

/* ---- GMRES with its basis in one buffer a vector ---- */
/* A basis over the per-buffer limit (here the la's max_matrix_chunk_bytes,
 * on lavapipe maxStorageBufferRange at the fluid's level 3) is split into a
 * buffer per vector; the Arnoldi process is the same operations, the update
 * x += V y a sum in another order: the same iterations, x to rounding.
 * Restarted (max_it over the restart length) with the Jacobi pc (the fused
 * update's other path) and with ILU(0). */
static void test_gmres_split(void) {
  printf("-- GMRES with the basis split into one buffer a vector\n");
  sessile_csr a;
  t_must("convdiff", sessile_csr_convdiff(14, 13, 12, 4.0, &a));
  const uint32_t n = a.nrows;
  double *b = t_dalloc(n), *x1 = t_dalloc(n), *x2 = t_dalloc(n);
  rhs(b, n, 21);
  sessile_mat *m = NULL;
  t_must("mat", sessile_mat_create_csr(la, &a, &m));
  const sessile_pc_type pcs[2] = {SESSILE_PC_JACOBI, SESSILE_PC_ILU0};
  for (int q = 0; q < 2; q++) {
    sessile_ksp_options o = opts(SESSILE_KSP_GMRES, pcs[q], 2000);
    o.restart = 12; /* several cycles */
    sessile_solve_result r1, r2;
    fill(x1, n, 0.0), fill(x2, n, 0.0);
    t_must("one buffer", solve(&o, m, b, x1, &r1));
    sessile_la_options lo;
    sessile_la_options_default(&lo);
    lo.max_matrix_chunk_bytes = (uint64_t)n * 8 * 4; /* 13 vectors do not fit; one does */
    sessile_la_set_options(la, &lo);
    t_must("split", solve(&o, m, b, x2, &r2));
    sessile_la_options_default(&lo);
    sessile_la_set_options(la, &lo);
    char what[160];
    snprintf(what, sizeof what, "GMRES(12)+%s, split basis: converged, %d iterations as in one buffer (%d)",
             q ? "ILU(0)" : "Jacobi", r2.iterations, r1.iterations);
    t_true(what, r1.status == SESSILE_SOLVE_CONVERGED && r2.status == SESSILE_SOLVE_CONVERGED &&
                     abs(r2.iterations - r1.iterations) <= 1 && r1.iterations > 12);
    snprintf(what, sizeof what, "GMRES(12)+%s, split basis: x as in one buffer (max rel)", q ? "ILU(0)" : "Jacobi");
    t_check(what, t_relerr(x2, x1, n), fp32 ? 1e-3 : 1e-6);
  }
  sessile_mat_destroy(m);
  sessile_csr_free(&a);
  free(b), free(x1), free(x2);
}

/* ---- b = 0: x = 0 at once, for every solver ---- */
static void test_zero_rhs(void) {
  printf("-- zero right-hand side\n");
  sessile_csr a;
  t_must("laplacian7", sessile_csr_laplacian7(16, 16, 16, &a));
  const uint32_t n = a.nrows;
  double *b = t_dalloc(n), *x = t_dalloc(n);
  fill(b, n, 0.0);
  sessile_mat *m = NULL;
  t_must("mat_create_csr", sessile_mat_create_csr(la, &a, &m));
  for (int t = 0; t < 3; t++) {
    char what[200];
    sessile_ksp_options o = opts((sessile_ksp_type)t, SESSILE_PC_JACOBI, 100);
    sessile_solve_result r;
    fill(x, n, 1.5); /* a nonzero initial guess */
    sessile_status s = solve(&o, m, b, x, &r);
    show(kname((sessile_ksp_type)t), &r, 0);
    snprintf(what, sizeof what,
             "%s b = 0 from x0 = 1.5: converged, 0 iterations, true_relres 0, x == 0 exactly "
             "(max|x| = %g)",
             kname((sessile_ksp_type)t), max_abs(x, n));
    t_true(what, s == SESSILE_OK && r.status == SESSILE_SOLVE_CONVERGED && r.iterations == 0 &&
                     r.true_relres == 0.0 && max_abs(x, n) == 0.0);
  }
  sessile_mat_destroy(m);
  sessile_csr_free(&a);
  free(b);
  free(x);
}

/* ---- indefinite: Laplacian 16^3 - 10 I ---- */
static void test_indefinite(void) {
  printf("-- indefinite: laplacian7 16^3 with the diagonal shifted by -10\n");
  sessile_csr a;
  t_must("laplacian7", sessile_csr_laplacian7(16, 16, 16, &a));
  for (uint32_t i = 0; i < a.nrows; i++)
    for (uint64_t p = a.rowptr[i]; p < a.rowptr[i + 1]; p++)
      if (a.col[p] == i) a.val[p] -= 10.0;
  const uint32_t n = a.nrows;
  double *b = t_dalloc(n), *x = t_dalloc(n);
  rhs(b, n, 10);
  sessile_mat *m = NULL;
  t_must("mat_create_csr", sessile_mat_create_csr(la, &a, &m));
  char what[256];

  sessile_ksp_options o = opts(SESSILE_KSP_CG, SESSILE_PC_JACOBI, 500);
  sessile_solve_result r;
  fill(x, n, 0.0);
  sessile_status s = solve(&o, m, b, x, &r);
  show("CG indefinite", &r, sessile_ref_true_relres(&a, b, x));
  snprintf(what, sizeof what, "CG on an indefinite matrix: status breakdown with a reason (\"%s\")",
           r.reason);
  t_true(what, s == SESSILE_OK && r.status == SESSILE_SOLVE_BREAKDOWN && r.reason[0] != '\0');
  t_true("CG indefinite: downloaded x has no NaN/Inf", all_finite(x, n));

  o = opts(SESSILE_KSP_GMRES, SESSILE_PC_JACOBI, 60);
  fill(x, n, 0.0);
  s = solve(&o, m, b, x, &r);
  double host = sessile_ref_true_relres(&a, b, x);
  show("GMRES indefinite max_it 60", &r, host);
  t_true("GMRES(30) indefinite, max_it 60: status max-iterations (not converged), <= 60 iterations",
         s == SESSILE_OK && r.status == SESSILE_SOLVE_MAX_ITER && r.iterations <= 60);
  t_true("GMRES indefinite: downloaded x has no NaN/Inf", all_finite(x, n));
  /* GMRES minimises the residual over a space that contains x0 = 0. */
  t_check("GMRES indefinite: host relres <= ||b||/||b|| = 1 (residual never grows)", host,
          1.0 + (fp32 ? 1e-5 : 1e-12));
  sessile_mat_destroy(m);
  sessile_csr_free(&a);
  free(b);
  free(x);
}

/* BiCGSTAB's restart: A = [4 1 -1; 1 4 1; 1 -2 4], b = e1, x0 = 0, Jacobi.
 * With r̂0 = r0 = e1, s = r0 − α A M⁻¹ r0 has s_1 = 0 and A's first row
 * gives (A M⁻¹ s)_1 = (s_2 − s_3)/4 = 0, so ρ_1 = r̂0·r_1 = 0 exactly (in
 * fp32 too: every number is a power of two times a small integer) while
 * r_1 ≠ 0 (0.139).  Without the restart BiCGSTAB stops there with a
 * breakdown; with it (r̂0 = r_1) it converges, the device as the host's
 * reference. */
static void test_bicgstab_restart(void) {
  printf("-- BiCGSTAB: r̂0·r = 0 exactly at iteration 1 (a restart, not a breakdown)\n");
  static const double av[3][3] = {{4, 1, -1}, {1, 4, 1}, {1, -2, 4}};
  sessile_csr a;
  t_must("csr_alloc", sessile_csr_alloc(3, 3, 9, &a));
  for (uint32_t i = 0; i < 3; i++) {
    a.rowptr[i + 1] = 3 * (i + 1);
    for (uint32_t j = 0; j < 3; j++) a.col[3 * i + j] = j, a.val[3 * i + j] = av[i][j];
  }
  double b[3] = {1, 0, 0}, x[3] = {0, 0, 0}, dinv[3] = {0.25, 0.25, 0.25};
  sessile_mat *m = NULL;
  t_must("mat_create_csr", sessile_mat_create_csr(la, &a, &m));
  sessile_ksp_options o = opts(SESSILE_KSP_BICGSTAB, SESSILE_PC_JACOBI, 50);
  o.check_every = 1;
  sessile_solve_result r;
  sessile_status s = solve(&o, m, b, x, &r);
  check_converged("BiCGSTAB through rho = 0", s, &r, sessile_ref_true_relres(&a, b, x));
  char what[160];
  snprintf(what, sizeof what, "BiCGSTAB through rho = 0: at least one restart reported (%d)", r.restarts);
  t_true(what, r.restarts >= 1);
  double xr[3] = {0, 0, 0};
  sessile_ref_result rr = sessile_ref_bicgstab(&a, dinv, b, xr, rtol, 50);
  printf("   reference: status %d after %d iterations, true_relres %.3e\n", (int)rr.status, rr.iterations,
         rr.true_relres);
  t_true("the host's reference BiCGSTAB converges through rho = 0 too",
         rr.status == SESSILE_REF_CONVERGED && rr.true_relres <= rtol);
  sessile_mat_destroy(m);
  sessile_csr_free(&a);
}

/* ---- singular: laplacian7 8^3 with row 0 zeroed (structure kept) ---- */
static void test_singular(void) {
  printf("-- singular: laplacian7 8^3 with every value of row 0 set to 0\n");
  sessile_csr a;
  t_must("laplacian7", sessile_csr_laplacian7(8, 8, 8, &a));
  for (uint64_t p = a.rowptr[0]; p < a.rowptr[1]; p++) a.val[p] = 0.0;
  const uint32_t n = a.nrows;
  double *b = t_dalloc(n), *x = t_dalloc(n);
  rhs(b, n, 8); /* b_0 != 0: A x = b has no solution */
  sessile_mat *m = NULL;
  t_must("mat_create_csr", sessile_mat_create_csr(la, &a, &m));
  char what[300];

  sessile_ksp_options o = opts(SESSILE_KSP_CG, SESSILE_PC_JACOBI, 200);
  sessile_solve_result r;
  fill(x, n, 0.0);
  sessile_error_clear();
  sessile_status s = solve(&o, m, b, x, &r);
  snprintf(what, sizeof what, "singular, pc Jacobi: ksp_solve -> %s (\"%s\")",
           sessile_status_name(s), sessile_error_message());
  t_true(what, s == SESSILE_ERR_NUMERIC);
  t_true("  ... the message names row 0", strstr(sessile_error_message(), "row 0 ") != NULL);

  for (int t = 0; t < 3; t++) {
    o = opts((sessile_ksp_type)t, SESSILE_PC_NONE, 200);
    fill(x, n, 0.0);
    double t0 = sessile_wall_seconds();
    s = solve(&o, m, b, x, &r);
    double dt = sessile_wall_seconds() - t0, host = sessile_ref_true_relres(&a, b, x);
    show(kname((sessile_ksp_type)t), &r, host);
    snprintf(what, sizeof what,
             "singular, %s pc none, max_it 200: breakdown or max-iterations within 200 "
             "iterations (%s, %d it, %.2f s)",
             kname((sessile_ksp_type)t), sessile_solve_status_name(r.status), r.iterations, dt);
    t_true(what, s == SESSILE_OK &&
                     (r.status == SESSILE_SOLVE_BREAKDOWN || r.status == SESSILE_SOLVE_MAX_ITER) &&
                     r.iterations <= 200);
    snprintf(what, sizeof what, "singular, %s: never 'converged' with host relres %.3e > rtol",
             kname((sessile_ksp_type)t), host);
    t_true(what, r.status != SESSILE_SOLVE_CONVERGED || host <= rtol);
    snprintf(what, sizeof what, "singular, %s: downloaded x has no NaN/Inf",
             kname((sessile_ksp_type)t));
    t_true(what, all_finite(x, n));
  }
  sessile_mat_destroy(m);
  sessile_csr_free(&a);
  free(b);
  free(x);
}

/* ---- non-finite input: NaN in b, NaN in A ---- */
static void test_nan(void) {
  printf("-- NaN in the right-hand side or the matrix\n");
  sessile_csr a;
  t_must("laplacian7", sessile_csr_laplacian7(16, 16, 16, &a));
  const uint32_t n = a.nrows;
  double *b = t_dalloc(n), *x = t_dalloc(n);
  sessile_mat *m = NULL;
  t_must("mat_create_csr", sessile_mat_create_csr(la, &a, &m));
  char what[300];
  for (int t = 0; t < 3; t++) {
    sessile_ksp_options o = opts((sessile_ksp_type)t, SESSILE_PC_JACOBI, 200);
    sessile_solve_result r;
    rhs(b, n, 77);
    b[77] = NAN;
    fill(x, n, 0.5);
    sessile_status s = solve(&o, m, b, x, &r);
    show(kname((sessile_ksp_type)t), &r, NAN);
    snprintf(what, sizeof what,
             "%s NaN in b: status breakdown (not converged), reason \"%s\", x finite",
             kname((sessile_ksp_type)t), r.reason);
    t_true(what, s == SESSILE_OK && r.status == SESSILE_SOLVE_BREAKDOWN && r.reason[0] != '\0' &&
                     all_finite(x, n));
  }
  sessile_mat_destroy(m);

  /* An off-diagonal NaN (Jacobi does not see it): the solvers must notice
   * and keep x finite (la.h: "x never receives NaN"). */
  uint32_t row = 1000;
  uint64_t p = a.rowptr[row];
  a.val[p] = NAN;
  t_must("mat_create_csr", sessile_mat_create_csr(la, &a, &m));
  for (int t = 0; t < 3; t++) {
    sessile_ksp_options o = opts((sessile_ksp_type)t, SESSILE_PC_JACOBI, 200);
    sessile_solve_result r;
    rhs(b, n, 78);
    fill(x, n, 0.0);
    sessile_status s = solve(&o, m, b, x, &r);
    show(kname((sessile_ksp_type)t), &r, NAN);
    snprintf(what, sizeof what,
             "%s NaN in A (row %u, off-diagonal): status breakdown, reason \"%s\", x finite",
             kname((sessile_ksp_type)t), row, r.reason);
    t_true(what, s == SESSILE_OK && r.status == SESSILE_SOLVE_BREAKDOWN && all_finite(x, n));
  }
  sessile_mat_destroy(m);
  sessile_csr_free(&a);
  free(b);
  free(x);
}

/* ---- check_every: how often the host looks must not change the result ---- */
static void test_check_every(void) {
  printf("-- check_every 1 vs 64: same iterations, same x bits\n");
  struct { sessile_ksp_type t; int grid; int conv; } cases[2] = {
      {SESSILE_KSP_CG, 32, 0}, {SESSILE_KSP_BICGSTAB, 16, 1}};
  for (int c = 0; c < 2; c++) {
    sessile_csr a;
    int g = cases[c].grid;
    if (cases[c].conv) t_must("convdiff", sessile_csr_convdiff(g, g, g, 2.0, &a));
    else t_must("laplacian7", sessile_csr_laplacian7(g, g, g, &a));
    const uint32_t n = a.nrows;
    double *b = t_dalloc(n), *x1 = t_dalloc(n), *x64 = t_dalloc(n);
    rhs(b, n, 1234);
    sessile_mat *m = NULL;
    t_must("mat_create_csr", sessile_mat_create_csr(la, &a, &m));
    sessile_ksp_options o = opts(cases[c].t, SESSILE_PC_JACOBI, 1000);
    sessile_solve_result r1, r64;
    o.check_every = 1;
    fill(x1, n, 0.0);
    sessile_status s1 = solve(&o, m, b, x1, &r1);
    o.check_every = 64;
    fill(x64, n, 0.0);
    sessile_status s64 = solve(&o, m, b, x64, &r64);
    char what[256];
    snprintf(what, sizeof what, "%s %s %d^3: check_every 1", kname(cases[c].t),
             cases[c].conv ? "convdiff" : "laplacian7", g);
    show(what, &r1, sessile_ref_true_relres(&a, b, x1));
    show("check_every 64", &r64, sessile_ref_true_relres(&a, b, x64));
    snprintf(what, sizeof what,
             "%s %s %d^3: check_every 1 and 64 both converge in the same iterations (%d, %d) "
             "with bitwise identical x",
             kname(cases[c].t), cases[c].conv ? "convdiff" : "laplacian7", g, r1.iterations,
             r64.iterations);
    t_true(what, s1 == SESSILE_OK && s64 == SESSILE_OK && r1.status == SESSILE_SOLVE_CONVERGED &&
                     r64.status == SESSILE_SOLVE_CONVERGED && r1.iterations == r64.iterations &&
                     memcmp(x1, x64, (size_t)n * sizeof *x1) == 0);
    sessile_mat_destroy(m);
    sessile_csr_free(&a);
    free(b);
    free(x1);
    free(x64);
  }
}

/* ---- argument checks of ksp_solve ---- */
static void test_usage(void) {
  printf("-- ksp_solve usage errors\n");
  sessile_csr a;
  t_must("laplacian7", sessile_csr_laplacian7(4, 4, 4, &a));
  sessile_mat *m = NULL;
  t_must("mat_create_csr", sessile_mat_create_csr(la, &a, &m));
  sessile_vec *b = NULL, *x = NULL, *short_x = NULL;
  t_must("vec_create", sessile_vec_create(la, a.nrows, &b));
  t_must("vec_create", sessile_vec_create(la, a.nrows, &x));
  t_must("vec_create", sessile_vec_create(la, a.nrows - 1, &short_x));
  t_must("fill", sessile_vec_fill(la, 1.0, b));
  sessile_solve_result r;
  sessile_ksp_options o = opts(SESSILE_KSP_CG, SESSILE_PC_JACOBI, 100);
  t_true("x of the wrong length -> SESSILE_ERR_USAGE",
         sessile_ksp_solve(la, &o, m, b, short_x, &r) == SESSILE_ERR_USAGE);
  o.rtol = 0;
  t_true("rtol 0 -> SESSILE_ERR_USAGE", sessile_ksp_solve(la, &o, m, b, x, &r) == SESSILE_ERR_USAGE);
  o = opts(SESSILE_KSP_CG, SESSILE_PC_JACOBI, 0);
  t_true("max_it 0 -> SESSILE_ERR_USAGE", sessile_ksp_solve(la, &o, m, b, x, &r) == SESSILE_ERR_USAGE);
  o = opts(SESSILE_KSP_GMRES, SESSILE_PC_JACOBI, 100);
  o.restart = 0;
  t_true("GMRES restart 0 -> SESSILE_ERR_USAGE",
         sessile_ksp_solve(la, &o, m, b, x, &r) == SESSILE_ERR_USAGE);
  sessile_vec_destroy(b);
  sessile_vec_destroy(x);
  sessile_vec_destroy(short_x);
  sessile_mat_destroy(m);
  sessile_csr_free(&a);
}

int main(int argc, char **argv) {
  int want32 = 0;
  for (int i = 1; i < argc; i++) {
    if (strcmp(argv[i], "--fp32") == 0) want32 = 1;
    else {
      printf("usage: %s [--fp32]\n", argv[0]);
      return 2;
    }
  }
  sessile_gpu *g = t_gpu(want32 ? 32 : 0);
  fp32 = sessile_gpu_info_of(g)->precision == 32;
  if (want32) t_true("--fp32: the context precision is 32", fp32);
  t_must("la_create", sessile_la_create(g, &la));
  double t0 = sessile_wall_seconds();
  test_pcg_laplacian();
  test_convdiff();
  test_p1tet();
  test_bcsr4();
  test_gmres_split();
  test_zero_rhs();
  test_indefinite();
  test_bicgstab_restart();
  test_singular();
  test_nan();
  test_check_every();
  test_usage();
  printf("solver tests took %.1f s\n", sessile_wall_seconds() - t0);
  sessile_la_destroy(la);
  return t_finish(g);
}
