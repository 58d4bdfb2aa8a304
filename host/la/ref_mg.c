/* Plain-C reference of the geometric multigrid (mg_record.c has the
 * algorithm): the same V-cycle and the same CG, in double, written for
 * clarity from sessile_ref_stencil7_cut and the ref_ vector kernels.
 * Threaded with OpenMP per node; every reduction is sessile_ref_dot. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/la/la_ref.h"
#include "sessile/la/mg.h"

typedef sessile_ref_mg_level level;

static uint32_t nodes(const level *v) { return v->n[0] * v->n[1] * v->n[2]; }

/* y = S(x, b): one damped-Jacobi sweep (x NULL: from zero); ax is scratch. */
static void sweep(const level *v, double omega, const double *x, const double *b, double *y,
                  double *ax) {
  int64_t n = nodes(v);
  if (x) sessile_ref_stencil7_cut_adv(v->n[0], v->n[1], v->n[2], v->h, v->mask, v->diag, v->coef, x, ax);
#pragma omp parallel for schedule(static)
  for (int64_t i = 0; i < n; i++) {
    if (v->mask[i]) y[i] = b[i];
    else if (!x) y[i] = omega * b[i] / (v->h * v->diag[i]);
    else y[i] = x[i] + omega * (b[i] - ax[i]) / (v->h * v->diag[i]);
  }
}

/* Coarse b = R r (0 on coarse Dirichlet nodes), R = P^T. */
static void restrict_to(const level *f, const level *c, const double *r, double *b) {
  const int64_t cn0 = c->n[0], cn1 = c->n[1], fn0 = f->n[0], fn1 = f->n[1];
#pragma omp parallel for schedule(static)
  for (int64_t K = 0; K < (int64_t)c->n[2]; K++)
    for (int64_t J = 0; J < cn1; J++)
      for (int64_t I = 0; I < cn0; I++) {
        int64_t node = I + cn0 * (J + cn1 * K);
        double sum = 0;
        if (!c->mask[node])
          for (int dk = -1; dk <= 1; dk++)
            for (int dj = -1; dj <= 1; dj++)
              for (int di = -1; di <= 1; di++) {
                int64_t i = 2 * I + di, j = 2 * J + dj, k = 2 * K + dk;
                if (i < 0 || j < 0 || k < 0 || i >= fn0 || j >= fn1 || k >= (int64_t)f->n[2]) continue;
                double w = (di ? 0.5 : 1) * (dj ? 0.5 : 1) * (dk ? 0.5 : 1);
                sum += w * r[i + fn0 * (j + fn1 * k)];
              }
        b[node] = sum;
      }
}

/* x += P xc on free fine nodes (trilinear). */
static void prolong_add(const level *f, const level *c, const double *xc, double *x) {
  const int64_t cn0 = c->n[0], cn1 = c->n[1], fn0 = f->n[0], fn1 = f->n[1];
#pragma omp parallel for schedule(static)
  for (int64_t k = 0; k < (int64_t)f->n[2]; k++)
    for (int64_t j = 0; j < fn1; j++)
      for (int64_t i = 0; i < fn0; i++) {
        int64_t node = i + fn0 * (j + fn1 * k);
        if (f->mask[node]) continue;
        double v = 0;
        for (int64_t K = k / 2; K <= (k + 1) / 2; K++)
          for (int64_t J = j / 2; J <= (j + 1) / 2; J++)
            for (int64_t I = i / 2; I <= (i + 1) / 2; I++) {
              double w = (i % 2 ? 0.5 : 1) * (j % 2 ? 0.5 : 1) * (k % 2 ? 0.5 : 1);
              if (!c->mask[I + cn0 * (J + cn1 * K)]) v += w * xc[I + cn0 * (J + cn1 * K)];
            }
        x[node] += v;
      }
}

/* x = V-cycle on level l for right-hand side b; work holds 4 vectors of level
 * l's size for this level and those below it (b_c, x_c, and two scratch). */
static void vcycle(int nl, const level *lv, const sessile_mg_options *o, int l, const double *b,
                   double *x, double *work) {
  const level *v = &lv[l];
  int64_t n = nodes(v);
  double *t = work, *ax = work + n, *next = work + 2 * n;
  int sweeps = l == nl - 1 ? o->coarse_sweeps : o->pre_smooth;
  sweep(v, o->omega, NULL, b, x, ax);
  for (int s = 1; s < sweeps; s++) {
    sweep(v, o->omega, x, b, t, ax);
    memcpy(x, t, n * sizeof *x);
  }
  if (l == nl - 1) return;
  /* residual, 0 on Dirichlet nodes */
  sessile_ref_stencil7_cut_adv(v->n[0], v->n[1], v->n[2], v->h, v->mask, v->diag, v->coef, x, ax);
  for (int64_t i = 0; i < n; i++) t[i] = v->mask[i] ? 0 : b[i] - ax[i];
  const level *c = &lv[l + 1];
  int64_t nc = nodes(c);
  double *bc = next, *xc = next + nc;
  restrict_to(v, c, t, bc);
  vcycle(nl, lv, o, l + 1, bc, xc, next + 2 * nc);
  prolong_add(v, c, xc, x);
  for (int s = 0; s < o->post_smooth; s++) {
    sweep(v, o->omega, x, b, t, ax);
    memcpy(x, t, n * sizeof *x);
  }
}

static double *alloc_work(int nl, const level *lv, size_t extra) {
  size_t total = extra;
  for (int l = 0; l < nl; l++) total += 4 * (size_t)nodes(&lv[l]);
  double *w = malloc(total * sizeof *w);
  if (!w) (void)sessile_error_set(SESSILE_ERR_NO_MEMORY, "reference multigrid: out of host memory");
  return w;
}

sessile_status sessile_ref_mg_vcycle(int nlevels, const sessile_ref_mg_level *lv,
                                     const struct sessile_mg_options *o, const double *r, double *z) {
  double *w = alloc_work(nlevels, lv, 0);
  if (!w) return SESSILE_ERR_NO_MEMORY;
  vcycle(nlevels, lv, o, 0, r, z, w);
  free(w);
  return SESSILE_OK;
}

sessile_ref_result sessile_ref_mg_pcg(int nlevels, const sessile_ref_mg_level *lv,
                                      const struct sessile_mg_options *o, const double *b,
                                      double *x, double rtol, int max_it) {
  sessile_ref_result res = {0, 0, SESSILE_REF_BREAKDOWN};
  const level *v = &lv[0];
  uint64_t n = nodes(v);
  double *w = alloc_work(nlevels, lv, 4 * n);
  if (!w) return res;
  double *r = w, *z = r + n, *p = z + n, *q = p + n, *work = q + n;
#define APPLY(in, out) sessile_ref_stencil7_cut_adv(v->n[0], v->n[1], v->n[2], v->h, v->mask, v->diag, v->coef, in, out)
  double bb = sessile_ref_dot(n, b, b);
  if (bb == 0) {
    sessile_ref_fill(n, 0, x);
    res.status = SESSILE_REF_CONVERGED;
    free(w);
    return res;
  }
  APPLY(x, q);
  sessile_ref_waxpy(n, -1, q, b, r);
  double rr = sessile_ref_dot(n, r, r), tol2 = rtol * rtol * bb;
  vcycle(nlevels, lv, o, 0, r, p, work);
  double rz = sessile_ref_dot(n, r, p);
  res.status = rr <= tol2 ? SESSILE_REF_CONVERGED : SESSILE_REF_MAX_ITER;
  while (res.status == SESSILE_REF_MAX_ITER && res.iterations < max_it) {
    APPLY(p, q);
    double pq = sessile_ref_dot(n, p, q);
    if (!(pq > 0) || !isfinite(pq)) {
      res.status = SESSILE_REF_BREAKDOWN;
      break;
    }
    double alpha = rz / pq;
    sessile_ref_axpy(n, alpha, p, x);
    sessile_ref_axpy(n, -alpha, q, r);
    res.iterations++;
    rr = sessile_ref_dot(n, r, r);
    if (rr <= tol2) {
      res.status = SESSILE_REF_CONVERGED;
      break;
    }
    vcycle(nlevels, lv, o, 0, r, z, work);
    double rzn = sessile_ref_dot(n, r, z);
    if (!(rzn > 0)) {
      res.status = SESSILE_REF_BREAKDOWN;
      break;
    }
    sessile_ref_aypx(n, rzn / rz, z, p);
    rz = rzn;
  }
  APPLY(x, q);
  sessile_ref_waxpy(n, -1, q, b, r);
  res.true_relres = sqrt(sessile_ref_dot(n, r, r) / bb);
#undef APPLY
  free(w);
  return res;
}
