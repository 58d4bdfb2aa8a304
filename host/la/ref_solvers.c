/* Reference Krylov solvers: Jacobi-preconditioned CG, BiCGSTAB and restarted
 * GMRES(m).  They define what the GPU solvers must reproduce, so they are
 * written for clarity and robustness, built only from the ref_ kernels.
 *
 * Common contract (see la_ref.h):
 *  - converged when the unpreconditioned recursive residual ‖r‖ ≤ rtol‖b‖;
 *  - b = 0: x = 0, converged after 0 iterations, true_relres 0;
 *  - breakdown is reported, never a NaN: x keeps its last finite iterate;
 *  - true_relres is recomputed from x at the end;
 *  - a run that cannot start (non-square matrix, no memory for the work
 *    vectors) returns SESSILE_REF_BREAKDOWN after 0 iterations with x
 *    untouched; the reason is recorded with sessile_error_set() as for every
 *    breakdown, so a caller can print sessile_error_message(). */
#include <inttypes.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "sessile/la/la_ref.h"
#include "la_kernels.h" /* BI_RESTART_EPS64, the device's threshold */

/* n-vectors in one block, with an overflow-checked size. */
static double *alloc_vectors(const char *solver, uint64_t count, uint64_t n) {
  double *w = NULL;
  if (n == 0 || count <= (SIZE_MAX - 1) / sizeof(double) / n)
    w = malloc(count * n * sizeof(double) + 1); /* +1: never malloc(0) */
  if (!w)
    (void)sessile_error_set(SESSILE_ERR_NO_MEMORY,
                            "%s: out of host memory: cannot allocate %" PRIu64 " work vectors of length %" PRIu64
                            " (%.3f GiB): use a smaller problem",
                            solver, count, n,
                            (double)count * (double)n * 8.0 / (1024.0 * 1024.0 * 1024.0));
  return w;
}

/* Recorded reason for a breakdown; the status is informational, the caller
 * sees SESSILE_REF_BREAKDOWN in the result. */
#define BREAKDOWN(...) ((void)sessile_error_set(SESSILE_ERR_NUMERIC, __VA_ARGS__))

static int all_finite(uint64_t n, const double *x) {
  int ok = 1;
#pragma omp parallel for schedule(static) reduction(&& : ok) if (n >= 32768)
  for (uint64_t i = 0; i < n; i++) ok = ok && isfinite(x[i]);
  return ok;
}

/* Shared start: validates, handles b = 0.  Returns 1 when the solve is already
 * finished (result in *res), 0 when the solver should run. */
static int solve_start(const char *solver, const sessile_csr *a, const double *b, double *x,
                       sessile_ref_result *res, double *bnorm) {
  res->iterations = 0;
  res->true_relres = 0.0;
  res->status = SESSILE_REF_BREAKDOWN;
  if (a->nrows != a->ncols) {
    (void)sessile_error_set(SESSILE_ERR_USAGE,
                            "%s: matrix is %" PRIu32 " x %" PRIu32 ", a solver needs it square",
                            solver, a->nrows, a->ncols);
    res->true_relres = INFINITY; /* no residual exists for mismatched sizes */
    return 1;
  }
  *bnorm = sessile_ref_nrm2(a->nrows, b);
  if (*bnorm == 0.0) {
    /* The exact solution is x = 0, whatever the initial guess. */
    sessile_ref_fill(a->nrows, 0.0, x);
    res->status = SESSILE_REF_CONVERGED;
    return 1;
  }
  if (!isfinite(*bnorm)) {
    BREAKDOWN("%s: the right-hand side contains NaN or infinite entries", solver);
    res->true_relres = sessile_ref_true_relres(a, b, x);
    return 1;
  }
  return 0;
}

/* Shared end: true residual, and a last guard that x is finite. */
static sessile_ref_result solve_finish(const char *solver, const sessile_csr *a, const double *b,
                                       const double *x, sessile_ref_result res) {
  if (!all_finite(a->nrows, x)) {
    BREAKDOWN("%s: the iterate became non-finite (overflow) after %d iterations", solver,
              res.iterations);
    res.status = SESSILE_REF_BREAKDOWN;
  }
  res.true_relres = sessile_ref_true_relres(a, b, x);
  return res;
}

/* r = b - A x */
static void residual(const sessile_csr *a, const double *b, const double *x, double *r) {
  sessile_ref_spmv_csr(a, x, r);
  sessile_ref_aypx(a->nrows, -1.0, b, r);
}

/* z = M⁻¹ v with M⁻¹ = diag(dinv); without a preconditioner return v itself
 * (no copy). */
static const double *precondition(uint64_t n, const double *dinv, const double *v, double *z) {
  if (!dinv) return v;
  sessile_ref_pmul(n, dinv, v, z);
  return z;
}

/* Preconditioned CG (Saad, "Iterative Methods for Sparse Linear Systems",
 * 2nd ed., Alg. 9.1), M = diag(A) applied on the left. */
sessile_ref_result sessile_ref_pcg(const sessile_csr *a, const double *dinv, const double *b,
                                   double *x, double rtol, int max_it) {
  static const char *name = "CG";
  sessile_ref_result res;
  double bnorm;
  if (solve_start(name, a, b, x, &res, &bnorm)) return res;
  const uint64_t n = a->nrows;
  double *w = alloc_vectors(name, 4, n);
  if (!w) return solve_finish(name, a, b, x, res);
  double *r = w, *z = w + n, *p = w + 2 * n, *q = w + 3 * n;
  const double tol = rtol * bnorm;

  residual(a, b, x, r);
  double rnorm = sessile_ref_nrm2(n, r);
  res.status = SESSILE_REF_MAX_ITER;
  if (!isfinite(rnorm)) {
    BREAKDOWN("%s: the initial residual is not finite (NaN/inf in A or x0)", name);
    res.status = SESSILE_REF_BREAKDOWN;
  } else if (rnorm <= tol) {
    res.status = SESSILE_REF_CONVERGED;
  } else {
    const double *zr = precondition(n, dinv, r, z);
    sessile_ref_copy(n, zr, p);
    double rz = sessile_ref_dot(n, r, zr);
    while (res.iterations < max_it) {
      sessile_ref_spmv_csr(a, p, q);
      double pq = sessile_ref_dot(n, p, q);
      /* p·Ap ≤ 0 means A is not positive definite along p: CG's minimisation
       * property is gone and α would be meaningless. */
      if (!(pq > 0.0) || !isfinite(pq) || !isfinite(rz / pq)) {
        BREAKDOWN("%s: breakdown at iteration %d: p·Ap = %g (the matrix is indefinite or "
                  "singular; use BiCGSTAB or GMRES)",
                  name, res.iterations, pq);
        res.status = SESSILE_REF_BREAKDOWN;
        break;
      }
      const double alpha = rz / pq;
      sessile_ref_axpy(n, alpha, p, x);
      sessile_ref_axpy(n, -alpha, q, r);
      res.iterations++;
      rnorm = sessile_ref_nrm2(n, r);
      if (!isfinite(rnorm)) {
        sessile_ref_axpy(n, -alpha, p, x); /* back to the last finite iterate */
        BREAKDOWN("%s: residual became non-finite at iteration %d", name, res.iterations);
        res.status = SESSILE_REF_BREAKDOWN;
        break;
      }
      if (rnorm <= tol) {
        res.status = SESSILE_REF_CONVERGED;
        break;
      }
      zr = precondition(n, dinv, r, z);
      const double rz_new = sessile_ref_dot(n, r, zr);
      if (rz_new == 0.0 || !isfinite(rz_new)) {
        BREAKDOWN("%s: breakdown at iteration %d: r·M⁻¹r = %g (the preconditioner is "
                  "singular or indefinite)",
                  name, res.iterations, rz_new);
        res.status = SESSILE_REF_BREAKDOWN;
        break;
      }
      sessile_ref_aypx(n, rz_new / rz, zr, p); /* p = z + β p */
      rz = rz_new;
    }
  }
  free(w);
  return solve_finish(name, a, b, x, res);
}

/* BiCGSTAB (van der Vorst 1992; Saad Alg. 7.7) with right preconditioning:
 * solves A M⁻¹ u = b, x = M⁻¹ u, so its residual is the unpreconditioned one.
 * One iteration = two SpMVs; convergence at the half step counts as one. */
sessile_ref_result sessile_ref_bicgstab(const sessile_csr *a, const double *dinv,
                                        const double *b, double *x, double rtol, int max_it) {
  static const char *name = "BiCGSTAB";
  sessile_ref_result res;
  double bnorm;
  if (solve_start(name, a, b, x, &res, &bnorm)) return res;
  const uint64_t n = a->nrows;
  double *w = alloc_vectors(name, 8, n);
  if (!w) return solve_finish(name, a, b, x, res);
  double *r = w, *r0 = w + n, *p = w + 2 * n, *v = w + 3 * n, *s = w + 4 * n, *t = w + 5 * n,
         *ph = w + 6 * n, *sh = w + 7 * n;
  const double tol = rtol * bnorm;

  residual(a, b, x, r);
  double rnorm = sessile_ref_nrm2(n, r);
  res.status = SESSILE_REF_MAX_ITER;
  if (!isfinite(rnorm)) {
    BREAKDOWN("%s: the initial residual is not finite (NaN/inf in A or x0)", name);
    res.status = SESSILE_REF_BREAKDOWN;
  } else if (rnorm <= tol) {
    res.status = SESSILE_REF_CONVERGED;
  } else {
    sessile_ref_copy(n, r, r0); /* shadow residual r̂0 = r0 */
    double rho = 1.0, alpha = 1.0, omega = 1.0, r0norm = rnorm;
    while (res.iterations < max_it) {
      double rho_new = sessile_ref_dot(n, r0, r);
      int restart = res.iterations == 0;
      if (isfinite(rho_new) && fabs(rho_new) <= BI_RESTART_EPS64 * r0norm * rnorm && rnorm > 0.0) {
        /* r̂0 and r orthogonal to rounding: restart from r (the device's
         * bicgstab_scalar op 1; docs/la.md, "BiCGSTAB restarts") */
        sessile_ref_copy(n, r, r0);
        r0norm = rnorm;
        rho_new = sessile_ref_dot(n, r0, r);
        restart = 1;
      }
      if (rho_new == 0.0 || !isfinite(rho_new)) {
        BREAKDOWN("%s: breakdown at iteration %d: rho = r̂0·r = %g", name, res.iterations,
                  rho_new);
        res.status = SESSILE_REF_BREAKDOWN;
        break;
      }
      if (restart) {
        sessile_ref_copy(n, r, p);
      } else {
        /* p = r + β (p − ω v),  β = (ρ_new/ρ)(α/ω) */
        const double beta = (rho_new / rho) * (alpha / omega);
        sessile_ref_axpy(n, -omega, v, p);
        sessile_ref_aypx(n, beta, r, p);
      }
      const double *pz = precondition(n, dinv, p, ph);
      sessile_ref_spmv_csr(a, pz, v);
      const double r0v = sessile_ref_dot(n, r0, v);
      if (r0v == 0.0 || !isfinite(r0v) || !isfinite(rho_new / r0v)) {
        BREAKDOWN("%s: breakdown at iteration %d: r̂0·v = %g", name, res.iterations, r0v);
        res.status = SESSILE_REF_BREAKDOWN;
        break;
      }
      alpha = rho_new / r0v;
      sessile_ref_waxpy(n, -alpha, v, r, s); /* s = r − α v */
      const double snorm = sessile_ref_nrm2(n, s);
      if (!isfinite(snorm)) {
        BREAKDOWN("%s: residual became non-finite at iteration %d", name, res.iterations);
        res.status = SESSILE_REF_BREAKDOWN;
        break;
      }
      if (snorm <= tol) { /* converged at the half step: x += α M⁻¹p */
        sessile_ref_axpy(n, alpha, pz, x);
        res.iterations++;
        res.status = SESSILE_REF_CONVERGED;
        break;
      }
      const double *sz = precondition(n, dinv, s, sh);
      sessile_ref_spmv_csr(a, sz, t);
      const double tt = sessile_ref_dot(n, t, t);
      const double ts = sessile_ref_dot(n, t, s);
      omega = tt > 0.0 ? ts / tt : 0.0;
      if (omega == 0.0 || !isfinite(omega)) {
        /* The half step is still a valid improvement: keep it. */
        sessile_ref_axpy(n, alpha, pz, x);
        res.iterations++;
        BREAKDOWN("%s: breakdown at iteration %d: omega = t·s/t·t = %g", name, res.iterations,
                  omega);
        res.status = SESSILE_REF_BREAKDOWN;
        break;
      }
      sessile_ref_axpy(n, alpha, pz, x); /* x += α M⁻¹p + ω M⁻¹s */
      sessile_ref_axpy(n, omega, sz, x);
      sessile_ref_waxpy(n, -omega, t, s, r); /* r = s − ω t */
      res.iterations++;
      rho = rho_new;
      rnorm = sessile_ref_nrm2(n, r);
      if (!isfinite(rnorm)) {
        sessile_ref_axpy(n, -omega, sz, x); /* keep the finite half-step iterate */
        BREAKDOWN("%s: residual became non-finite at iteration %d", name, res.iterations);
        res.status = SESSILE_REF_BREAKDOWN;
        break;
      }
      if (rnorm <= tol) {
        res.status = SESSILE_REF_CONVERGED;
        break;
      }
    }
  }
  free(w);
  return solve_finish(name, a, b, x, res);
}

/* Restarted GMRES(m) with right preconditioning (Saad Alg. 9.5): Arnoldi with
 * modified Gram-Schmidt on A M⁻¹, the Hessenberg matrix reduced on the fly by
 * Givens rotations so |g_{j+1}| is the residual norm ‖b − A x_j‖ without
 * forming x_j (right preconditioning keeps it unpreconditioned).  x is updated
 * at the end of each cycle; every cycle starts from the true residual, which
 * is what decides convergence when the estimate says "converged".
 * `iterations` counts Arnoldi steps over all cycles; max_it bounds that. */
sessile_ref_result sessile_ref_gmres(const sessile_csr *a, const double *dinv, const double *b,
                                     double *x, double rtol, int max_it, int restart) {
  static const char *name = "GMRES";
  sessile_ref_result res;
  double bnorm;
  if (solve_start(name, a, b, x, &res, &bnorm)) return res;
  const uint64_t n = a->nrows;
  /* A Krylov space never exceeds n; m < 1 would make no progress. */
  const uint64_t m = restart < 1 ? 1 : (uint64_t)restart < n ? (uint64_t)restart : n;
  /* V: m+1 basis vectors; z: preconditioned vector / update; then the small
   * dense data: H (m+1)×m column-major, cs, sn, g (m+1), y (m). */
  /* H fits in m+1 vectors since m <= n; no product here can overflow. */
  double *w = alloc_vectors(name, (m + 2) + (m + 1) + (4 * (m + 1) + n - 1) / n, n);
  if (!w) return solve_finish(name, a, b, x, res);
  double *V = w, *z = w + (m + 1) * n, *H = w + (m + 2) * n;
  double *cs = H + (m + 1) * m, *sn = cs + (m + 1), *g = sn + (m + 1), *y = g + (m + 1);
#define HH(i, j) H[(uint64_t)(j) * (m + 1) + (i)]
  const double tol = rtol * bnorm;

  res.status = SESSILE_REF_MAX_ITER;
  for (;;) {
    double *v0 = V;
    residual(a, b, x, v0);
    const double beta = sessile_ref_nrm2(n, v0);
    if (!isfinite(beta)) {
      BREAKDOWN("%s: the residual is not finite after %d iterations", name, res.iterations);
      res.status = SESSILE_REF_BREAKDOWN;
      break;
    }
    if (beta <= tol) {
      res.status = SESSILE_REF_CONVERGED;
      break;
    }
    if (res.iterations >= max_it) break;
    sessile_ref_scale(n, 1.0 / beta, v0);
    g[0] = beta;

    uint64_t k = 0; /* finished Arnoldi columns this cycle */
    int broke = 0;
    for (uint64_t j = 0; j < m && res.iterations < max_it; j++) {
      double *vj = V + j * n, *wv = V + (j + 1) * n;
      sessile_ref_spmv_csr(a, precondition(n, dinv, vj, z), wv); /* w = A M⁻¹ v_j */
      for (uint64_t i = 0; i <= j; i++) {                        /* modified Gram-Schmidt */
        HH(i, j) = sessile_ref_dot(n, wv, V + i * n);
        sessile_ref_axpy(n, -HH(i, j), V + i * n, wv);
      }
      const double hn = sessile_ref_nrm2(n, wv);
      HH(j + 1, j) = hn;
      for (uint64_t i = 0; i < j; i++) { /* earlier rotations on the new column */
        const double t = cs[i] * HH(i, j) + sn[i] * HH(i + 1, j);
        HH(i + 1, j) = -sn[i] * HH(i, j) + cs[i] * HH(i + 1, j);
        HH(i, j) = t;
      }
      /* New rotation zeroing h_{j+1,j}; d = 0 means A M⁻¹ is singular on the
       * Krylov space (cs, sn become NaN and are caught below). */
      const double d = hypot(HH(j, j), HH(j + 1, j));
      cs[j] = HH(j, j) / d;
      sn[j] = HH(j + 1, j) / d;
      HH(j, j) = d;
      HH(j + 1, j) = 0.0;
      g[j + 1] = -sn[j] * g[j];
      g[j] = cs[j] * g[j];
      res.iterations++;
      if (!(d > 0.0) || !isfinite(d) || !isfinite(g[j]) || !isfinite(g[j + 1])) {
        BREAKDOWN("%s: breakdown at iteration %d: Arnoldi produced %g (the matrix is singular "
                  "or the data are not finite)",
                  name, res.iterations, d);
        broke = 1; /* column j is dropped; columns 0..j-1 are still valid */
        break;
      }
      k = j + 1;
      /* |g_{j+1}| ≤ tol, or hn = 0 (lucky breakdown: exact in this space). */
      if (fabs(g[j + 1]) <= tol || hn == 0.0) break;
      sessile_ref_scale(n, 1.0 / hn, wv);
    }

    /* y = H_k⁻¹ g (upper triangular), then x += M⁻¹ V_k y. */
    for (uint64_t ii = k; ii-- > 0;) {
      double s = g[ii];
      for (uint64_t l = ii + 1; l < k; l++) s -= HH(ii, l) * y[l];
      y[ii] = s / HH(ii, ii);
    }
    if (k > 0) {
      int finite = all_finite(k, y);
      if (finite) {
        sessile_ref_fill(n, 0.0, z);
        for (uint64_t i = 0; i < k; i++) sessile_ref_axpy(n, y[i], V + i * n, z);
        if (dinv) sessile_ref_pmul(n, dinv, z, z);
        finite = all_finite(n, z);
      }
      if (finite) {
        sessile_ref_axpy(n, 1.0, z, x);
      } else if (!broke) { /* x stays at the start of this cycle */
        BREAKDOWN("%s: the update became non-finite at iteration %d", name, res.iterations);
        broke = 1;
      }
    }
    if (broke) {
      res.status = SESSILE_REF_BREAKDOWN;
      break;
    }
    /* Loop: the true residual of the new x decides convergence / restart. */
  }
#undef HH
  free(w);
  return solve_finish(name, a, b, x, res);
}
