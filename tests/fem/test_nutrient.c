/* The nutrient field (host/fem/nutrient.c) and the masked 7-point operator
 * it runs on (host/la/stencil.c).
 *
 * Checks and tolerances:
 *  - P1 assembly element by element on a small Kuhn box: every tet has
 *    positive volume, the 6 tets of a cube sum to h^3 (1e-14 relative), every
 *    row of K sums to 0 (constants are in the kernel, 1e-14 h), and every
 *    interior row is the 7-point stencil times h (diagonal 6h, face
 *    neighbours -h, all other entries 0) to 1e-12 h;
 *  - stencil operator on the GPU = the CSR SpMV of the assembled, eliminated
 *    P1 matrix on the GPU = sessile_ref_stencil7, with a random Dirichlet
 *    mask, row-wise relative error 1e-13 (a handful of fp64 roundings of
 *    entries that are themselves assembled sums); device Jacobi = 1/diag(A)
 *    of the CSR matrix to 1e-14 relative (the assembled diagonal is a sum of
 *    24 element terms, a few ulps from 6h: see the stencil check);
 *  - patch test: linear Dirichlet data on the walls and on an interior ball
 *    of nodes: the solve (rtol 1e-10) reproduces the linear field to 1e-8
 *    (the 7-point stencil is exact for linear functions; what is left is the
 *    solver tolerance times the condition number, ~1e-10 * 100);
 *  - manufactured harmonic u = exp(sqrt2 a x) sin(a y) sin(a z) on the unit
 *    cube at h = 1/8, 1/16, 1/32 (rtol 1e-10): observed orders of the L2
 *    error (tet quadrature of (u - u_h)^2, exact degree 2) and the nodal max
 *    error > 1.8 between successive grids;
 *  - the nutrient BCs with a solid ball on the substratum: c = 0 exactly on
 *    solid and substratum nodes, c = 1 exactly on the other walls,
 *    -1e-6 <= c <= 1 + 1e-6 everywhere (discrete maximum principle of the
 *    M-matrix, up to the solver tolerance), reported and host-recomputed
 *    relative residual of the free rows <= 1e-6, warm start from a smaller
 *    ball's field takes fewer iterations than a cold start;
 *  - the GPU solve agrees with la's plain-C PCG on the assembled CSR system
 *    (both at rtol 1e-10) to 1e-7 (max norm; c is O(1));
 *  - the fp32 path (mixed-precision refinement with the stencil's host
 *    residual) converges on the same problem, agreeing to 1e-5.
 * `test_nutrient --bench` (not run by ctest) times the ~65x65x49 box with a
 * 6 cm ball: cold and warm solves, stencil vs CSR application and solve. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sessile/la/la_ref.h"
#include "sessile/fem/nutrient.h"
#include "testutil.h"

static sessile_gpu *gpu;
static sessile_la *la;

static sessile_box box_of(uint32_t nx, uint32_t ny, uint32_t nz, double h, const double o[3]) {
  sessile_box b = {{o[0], o[1], o[2]}, h, {nx, ny, nz}};
  return b;
}

static int is_wall(const sessile_box *b, uint32_t node) {
  uint32_t i = node % b->n[0], j = (node / b->n[0]) % b->n[1], k = node / (b->n[0] * b->n[1]);
  return sessile_box_node_tags(b, i, j, k) != 0;
}

/* Solid ball of nodes: |p - centre| <= r. */
static void ball_mask(const sessile_box *b, const double c[3], double r, uint32_t *mask) {
  for (uint32_t n = 0; n < sessile_box_nodes(b); n++) {
    double p[3];
    sessile_box_node_pos(b, n, p);
    double d2 = 0;
    for (int a = 0; a < 3; a++) d2 += (p[a] - c[a]) * (p[a] - c[a]);
    mask[n] = d2 <= r * r;
  }
}

static sessile_buffer *mask_buffer(const sessile_box *b, const uint32_t *mask) {
  sessile_buffer *m;
  size_t bytes = (size_t)sessile_box_nodes(b) * 4;
  t_must("mask buffer", sessile_buffer_create(gpu, bytes, SESSILE_BUFFER_DEVICE, &m));
  t_must("mask upload", sessile_buffer_upload(m, 0, mask, bytes));
  return m;
}

/* ---------------------------------------------------------------------- */
static void test_assembly(void) {
  const double o[3] = {-0.4, 1.1, 0.25}, h = 0.3;
  sessile_box b = box_of(5, 4, 6, h, o);
  double vol_err = 0, min_vol = INFINITY;
  for (uint32_t k = 0; k + 1 < b.n[2]; k++)
    for (uint32_t j = 0; j + 1 < b.n[1]; j++)
      for (uint32_t i = 0; i + 1 < b.n[0]; i++) {
        double sum = 0;
        for (int t = 0; t < 6; t++) {
          uint32_t nd[4];
          double p[4][3], e[3][3];
          sessile_box_tet(&b, i, j, k, t, nd);
          for (int q = 0; q < 4; q++) sessile_box_node_pos(&b, nd[q], p[q]);
          for (int q = 0; q < 3; q++)
            for (int a = 0; a < 3; a++) e[q][a] = p[q + 1][a] - p[0][a];
          double v = (e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
                      e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                      e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0])) / 6.0;
          if (v < min_vol) min_vol = v;
          sum += v;
        }
        vol_err = fmax(vol_err, fabs(sum - h * h * h) / (h * h * h));
      }
  t_true("every Kuhn tet has positive volume", min_vol > 0);
  t_check("6 tets of a cube fill it: |sum vol - h^3| / h^3", vol_err, 1e-14);

  sessile_csr K;
  t_must("assemble", sessile_p1_laplace_assemble(&b, &K));
  double rowsum = 0, stencil = 0;
  uint32_t s1 = b.n[0], s2 = b.n[0] * b.n[1];
  for (uint32_t r = 0; r < K.nrows; r++) {
    double sum = 0;
    for (uint64_t e = K.rowptr[r]; e < K.rowptr[r + 1]; e++) sum += K.val[e];
    rowsum = fmax(rowsum, fabs(sum) / h);
    if (is_wall(&b, r)) continue;
    for (uint64_t e = K.rowptr[r]; e < K.rowptr[r + 1]; e++) {
      uint32_t c = K.col[e];
      double want = c == r ? 6 * h
                    : (c == r - 1 || c == r + 1 || c == r - s1 || c == r + s1 || c == r - s2 ||
                       c == r + s2)
                        ? -h
                        : 0.0;
      stencil = fmax(stencil, fabs(K.val[e] - want) / h);
    }
  }
  t_true("K has the 15-point Kuhn graph (nnz/row <= 15)", K.nnz <= 15ull * K.nrows);
  t_check("P1 K row sums (/h)", rowsum, 1e-14);
  t_check("P1 K interior rows = 7-point stencil * h (/h)", stencil, 1e-12);
  sessile_csr_free(&K);
}

/* ---------------------------------------------------------------------- */
static double rowwise(const sessile_csr *a, const double *x, const double *y, const double *r) {
  double e = 0;
  for (uint32_t i = 0; i < a->nrows; i++) {
    double s = 0;
    for (uint64_t k = a->rowptr[i]; k < a->rowptr[i + 1]; k++) s += fabs(a->val[k] * x[a->col[k]]);
    double d = fabs(y[i] - r[i]) / (s > 0 ? s : 1.0);
    if (!(d <= e)) e = d;
  }
  return e;
}

static void test_spmv(void) {
  const double o[3] = {0, 0, 0}, h = 0.6;
  sessile_box b = box_of(13, 11, 9, h, o);
  uint32_t n = sessile_box_nodes(&b);
  uint32_t *mask = t_xalloc(n * 4);
  uint8_t *dir = t_xalloc(n);
  double *x = t_xalloc(n * 8), *g = t_xalloc(n * 8), *bb = t_xalloc(n * 8);
  double *y1 = t_xalloc(n * 8), *y2 = t_xalloc(n * 8), *yr = t_xalloc(n * 8), *d = t_xalloc(n * 8);
  sessile_fill_random(x, n, -1, 1, 11);
  sessile_fill_random(g, n, 0, 1, 12);
  for (uint32_t i = 0; i < n; i++) {
    mask[i] = g[i] < 0.2 ? 1 + (i % 3) : 0; /* any non-zero value counts */
    dir[i] = mask[i] || is_wall(&b, i);
  }
  sessile_csr K, A;
  t_must("assemble", sessile_p1_laplace_assemble(&b, &K));
  t_must("eliminate", sessile_p1_dirichlet(&K, dir, g, &A, bb));
  sessile_buffer *mb = mask_buffer(&b, mask);
  sessile_mat *st, *csr;
  sessile_vec *vx, *vy, *vd;
  t_must("stencil", sessile_mat_create_stencil7(la, b.n[0], b.n[1], b.n[2], h, mb, &st));
  t_must("csr", sessile_mat_create_csr(la, &A, &csr));
  t_must("vec", sessile_vec_create(la, n, &vx));
  t_must("vec", sessile_vec_create(la, n, &vy));
  t_must("vec", sessile_vec_create(la, n, &vd));
  t_must("upload", sessile_vec_upload(vx, x));
  t_must("stencil mult", sessile_mat_mult(la, st, vx, vy));
  t_must("download", sessile_vec_download(vy, y1));
  t_must("csr mult", sessile_mat_mult(la, csr, vx, vy));
  t_must("download", sessile_vec_download(vy, y2));
  sessile_ref_stencil7(b.n[0], b.n[1], b.n[2], h, mask, x, yr);
  t_check("GPU stencil7 vs GPU CSR SpMV of the eliminated P1 matrix", rowwise(&A, x, y1, y2), 1e-13);
  t_check("GPU stencil7 vs sessile_ref_stencil7", rowwise(&A, x, y1, yr), 1e-13);
  t_must("jacobi", sessile_mat_jacobi(la, st, vd));
  t_must("download", sessile_vec_download(vd, d));
  double jerr = 0;
  for (uint32_t i = 0; i < n; i++)
    for (uint64_t k = A.rowptr[i]; k < A.rowptr[i + 1]; k++)
      if (A.col[k] == i) jerr = fmax(jerr, fabs(d[i] * A.val[k] - 1.0));
  t_check("GPU stencil7 Jacobi vs 1/diag of the CSR matrix", jerr, 1e-14);
  sessile_vec_destroy(vx);
  sessile_vec_destroy(vy);
  sessile_vec_destroy(vd);
  sessile_mat_destroy(st);
  sessile_mat_destroy(csr);
  sessile_buffer_destroy(mb);
  sessile_csr_free(&K);
  sessile_csr_free(&A);
  free(mask), free(dir), free(x), free(g), free(bb), free(y1), free(y2), free(yr), free(d);
}

/* ---------------------------------------------------------------------- */
typedef double (*field_fn)(const double p[3]);

/* Solves with Dirichlet data u on the walls and the masked nodes; c holds
 * the nodal solution on return. */
static sessile_solve_result solve_with(const sessile_box *b, const uint32_t *mask, field_fn u,
                                       double rtol, double *c) {
  uint32_t n = sessile_box_nodes(b);
  uint32_t *m0 = NULL;
  if (!mask) mask = m0 = t_xalloc(n * 4);
  double *gv = t_xalloc(n * 8);
  for (uint32_t i = 0; i < n; i++) {
    double p[3];
    sessile_box_node_pos(b, i, p);
    gv[i] = u(p);
  }
  sessile_nutrient *nt;
  sessile_vec *vg, *vc;
  sessile_buffer *mb = mask_buffer(b, mask);
  t_must("nutrient", sessile_nutrient_create(la, b, &nt));
  t_must("vec", sessile_vec_create(la, n, &vg));
  t_must("vec", sessile_vec_create(la, n, &vc));
  t_must("upload", sessile_vec_upload(vg, gv));
  sessile_ksp_options opt;
  sessile_ksp_options_default(&opt);
  opt.rtol = rtol;
  opt.max_it = 5000;
  sessile_solve_result res;
  t_must("solve", sessile_nutrient_solve_dirichlet(nt, mb, vg, vc, &opt, &res));
  t_must("download", sessile_vec_download(vc, c));
  sessile_vec_destroy(vg);
  sessile_vec_destroy(vc);
  sessile_nutrient_destroy(nt);
  sessile_buffer_destroy(mb);
  free(gv);
  free(m0);
  return res;
}

static double linear(const double p[3]) { return 1.0 + 2.0 * p[0] - 3.0 * p[1] + 0.5 * p[2]; }

static void test_patch(void) {
  const double o[3] = {0.1, -0.2, 0.0}, h = 0.25, ctr[3] = {1.35, 0.8, 0.9};
  sessile_box b = box_of(11, 9, 8, h, o);
  uint32_t n = sessile_box_nodes(&b);
  uint32_t *mask = t_xalloc(n * 4);
  ball_mask(&b, ctr, 0.6, mask);
  double *c = t_xalloc(n * 8), e = 0, umax = 0;
  sessile_solve_result res = solve_with(&b, mask, linear, 1e-10, c);
  for (uint32_t i = 0; i < n; i++) {
    double p[3];
    sessile_box_node_pos(&b, i, p);
    e = fmax(e, fabs(c[i] - linear(p)));
    umax = fmax(umax, fabs(linear(p)));
  }
  printf("  patch test: %d iterations, true relres %.2e\n", res.iterations, res.true_relres);
  t_true("patch test solve converged", res.status == SESSILE_SOLVE_CONVERGED);
  t_check("patch test: max |c - linear| / max |linear|", e / umax, 1e-8);
  free(mask);
  free(c);
}

/* ---------------------------------------------------------------------- */
static const double A_MS = 1.5;
static double harmonic(const double p[3]) {
  return exp(sqrt(2.0) * A_MS * p[0]) * sin(A_MS * p[1]) * sin(A_MS * p[2]);
}

/* L2 norm of u - u_h over the box (degree-2 4-point rule per tet) and the
 * nodal max error. */
static void errors(const sessile_box *b, const double *c, double *l2, double *linf) {
  static const double qa = 0.5854101966249685, qb = 0.1381966011250105;
  double s = 0, m = 0;
  for (uint32_t n = 0; n < sessile_box_nodes(b); n++) {
    double p[3];
    sessile_box_node_pos(b, n, p);
    m = fmax(m, fabs(c[n] - harmonic(p)));
  }
  for (uint32_t k = 0; k + 1 < b->n[2]; k++)
    for (uint32_t j = 0; j + 1 < b->n[1]; j++)
      for (uint32_t i = 0; i + 1 < b->n[0]; i++)
        for (int t = 0; t < 6; t++) {
          uint32_t nd[4];
          double p[4][3];
          sessile_box_tet(b, i, j, k, t, nd);
          for (int q = 0; q < 4; q++) sessile_box_node_pos(b, nd[q], p[q]);
          for (int q = 0; q < 4; q++) { /* point q: weight qa on node q, qb on the others */
            double x[3], uh = 0;
            for (int a = 0; a < 3; a++) x[a] = 0;
            for (int r = 0; r < 4; r++) {
              double w = r == q ? qa : qb;
              for (int a = 0; a < 3; a++) x[a] += w * p[r][a];
              uh += w * c[nd[r]];
            }
            double d = harmonic(x) - uh;
            s += d * d * (b->h * b->h * b->h / 6.0) / 4.0;
          }
        }
  *l2 = sqrt(s);
  *linf = m;
}

static void test_convergence(void) {
  const double o[3] = {0, 0, 0};
  double l2[3], li[3];
  for (int r = 0; r < 3; r++) {
    uint32_t cells = 8u << r;
    sessile_box b = box_of(cells + 1, cells + 1, cells + 1, 1.0 / cells, o);
    double *c = t_xalloc((size_t)sessile_box_nodes(&b) * 8);
    sessile_solve_result res = solve_with(&b, NULL, harmonic, 1e-10, c);
    errors(&b, c, &l2[r], &li[r]);
    printf("  h = 1/%u: %d iterations, L2 error %.4e, max nodal error %.4e\n", cells,
           res.iterations, l2[r], li[r]);
    t_true("manufactured solve converged", res.status == SESSILE_SOLVE_CONVERGED);
    free(c);
  }
  for (int r = 1; r < 3; r++) {
    double p2 = log2(l2[r - 1] / l2[r]), pi = log2(li[r - 1] / li[r]);
    printf("  order h = 1/%u -> 1/%u: L2 %.3f, max %.3f\n", 8u << (r - 1), 8u << r, p2, pi);
    t_check("L2 order >= 1.8 (shortfall 1.8 - order)", fmax(0, 1.8 - p2), 0);
    t_check("max-norm order >= 1.8 (shortfall 1.8 - order)", fmax(0, 1.8 - pi), 0);
  }
}

/* ---------------------------------------------------------------------- */
/* The real nutrient BCs.  Host system: the eliminated P1 CSR with b = g on
 * Dirichlet rows; the residual compared is that of the free rows. */
typedef struct {
  sessile_box b;
  uint32_t n, *mask;
  uint8_t *dir;
  double *g;
} nutrient_case;

static void nutrient_case_make(nutrient_case *nc, const sessile_box *b, const double ctr[3], double r) {
  nc->b = *b;
  nc->n = sessile_box_nodes(b);
  nc->mask = t_xalloc(nc->n * 4);
  nc->dir = t_xalloc(nc->n);
  nc->g = t_xalloc(nc->n * 8);
  ball_mask(b, ctr, r, nc->mask);
  for (uint32_t i = 0; i < nc->n; i++) {
    uint32_t x = i % b->n[0], y = (i / b->n[0]) % b->n[1], z = i / (b->n[0] * b->n[1]);
    nc->dir[i] = nc->mask[i] || is_wall(b, i);
    nc->g[i] = nc->mask[i] ? 0.0 : sessile_nutrient_wall_value(b, x, y, z);
  }
}

static void nutrient_case_free(nutrient_case *nc) {
  free(nc->mask), free(nc->dir), free(nc->g);
}

/* ||(b - A c)_free|| / ||b_free|| on the host. */
static double free_relres(const sessile_csr *A, const double *bb, const uint8_t *dir, const double *c) {
  double *r = t_xalloc((size_t)A->nrows * 8), rn = 0, bn = 0;
  sessile_ref_spmv_csr(A, c, r);
  for (uint32_t i = 0; i < A->nrows; i++)
    if (!dir[i]) {
      rn += (bb[i] - r[i]) * (bb[i] - r[i]);
      bn += bb[i] * bb[i];
    }
  free(r);
  return sqrt(rn / bn);
}

static void test_nutrient_bcs(void) {
  const double o[3] = {0, 0, 0}, h = 0.6, ctr[3] = {7.2, 6.6, 2.4};
  sessile_box b = box_of(25, 23, 17, h, o);
  nutrient_case small, big;
  nutrient_case_make(&small, &b, ctr, 2.7);
  nutrient_case_make(&big, &b, ctr, 3.0);
  uint32_t n = big.n;
  sessile_nutrient *nt;
  sessile_vec *vc;
  t_must("nutrient", sessile_nutrient_create(la, &b, &nt));
  t_must("vec", sessile_vec_create(la, n, &vc));
  sessile_buffer *ms = mask_buffer(&b, small.mask), *mb = mask_buffer(&b, big.mask);
  sessile_solve_result rs, warm, cold;
  t_must("solve small", sessile_nutrient_solve(nt, ms, vc, NULL, &rs));
  t_must("solve warm", sessile_nutrient_solve(nt, mb, vc, NULL, &warm));
  double *c = t_xalloc(n * 8), *c0 = t_xalloc(n * 8), *cr = t_xalloc(n * 8), *bb = t_xalloc(n * 8);
  t_must("download", sessile_vec_download(vc, c));
  t_must("zero", sessile_vec_fill(la, 0.0, vc));
  t_must("solve cold", sessile_nutrient_solve(nt, mb, vc, NULL, &cold));
  printf("  small ball: %d it; bigger ball: warm start %d it (relres %.2e), cold start %d it "
         "(relres %.2e)\n", rs.iterations, warm.iterations, warm.true_relres, cold.iterations,
         cold.true_relres);
  t_true("warm start takes fewer iterations than a cold start", warm.iterations < cold.iterations);
  t_true("nutrient solves converged", rs.status == SESSILE_SOLVE_CONVERGED &&
                                          warm.status == SESSILE_SOLVE_CONVERGED &&
                                          cold.status == SESSILE_SOLVE_CONVERGED);
  t_check("reported true relative residual (warm)", warm.true_relres, 1e-6);

  double bc = 0, lo = 0, hi = 0;
  uint32_t nsolid = 0;
  for (uint32_t i = 0; i < n; i++) {
    if (big.dir[i]) bc = fmax(bc, fabs(c[i] - big.g[i]));
    nsolid += big.mask[i] != 0;
    lo = fmin(lo, c[i]);
    hi = fmax(hi, c[i] - 1.0);
  }
  printf("  %u solid nodes; min c %.3e, max c - 1 %.3e\n", nsolid, lo, hi);
  t_check("c = 0 on solid and substratum, 1 on other walls (exact)", bc, 0);
  t_check("maximum principle: -min c", -lo, 1e-6);
  t_check("maximum principle: max c - 1", hi, 1e-6);

  sessile_csr K, A;
  t_must("assemble", sessile_p1_laplace_assemble(&b, &K));
  t_must("eliminate", sessile_p1_dirichlet(&K, big.dir, big.g, &A, bb));
  t_check("host-recomputed free-row relative residual (warm)", free_relres(&A, bb, big.dir, c), 1e-6);

  /* Reference: la's plain-C PCG on the assembled CSR, both at rtol 1e-10. */
  double *dinv = t_xalloc(n * 8);
  t_must("ref jacobi", sessile_ref_jacobi_csr(&A, dinv));
  sessile_ref_result rr = sessile_ref_pcg(&A, dinv, bb, cr, 1e-10, 5000);
  sessile_ksp_options opt;
  sessile_ksp_options_default(&opt);
  opt.rtol = 1e-10;
  sessile_solve_result tight;
  t_must("solve tight", sessile_nutrient_solve(nt, mb, vc, &opt, &tight));
  t_must("download", sessile_vec_download(vc, c0));
  printf("  reference PCG %d it, GPU %d it (warm from rtol 1e-6 field)\n", rr.iterations, tight.iterations);
  t_true("reference PCG converged", rr.status == SESSILE_REF_CONVERGED);
  t_check("GPU nutrient (rtol 1e-10) vs reference PCG on the P1 CSR (max)", t_relerr(c0, cr, n), 1e-7);
  printf("  (default rtol 1e-6 field vs reference: max difference %.2e)\n", t_relerr(c, cr, n));

  /* fp32 path: refinement with the stencil's host residual. */
  {
    sessile_gpu *g32 = t_gpu(32);
    sessile_la *la32;
    sessile_nutrient *nt32;
    sessile_vec *v32;
    sessile_buffer *m32;
    t_must("la32", sessile_la_create(g32, &la32));
    t_must("nutrient32", sessile_nutrient_create(la32, &b, &nt32));
    t_must("vec32", sessile_vec_create(la32, n, &v32));
    t_must("mask32", sessile_buffer_create(g32, (size_t)n * 4, SESSILE_BUFFER_DEVICE, &m32));
    t_must("mask32", sessile_buffer_upload(m32, 0, big.mask, (size_t)n * 4));
    sessile_solve_result r32;
    t_must("solve fp32", sessile_nutrient_solve(nt32, m32, v32, NULL, &r32));
    t_must("download", sessile_vec_download(v32, c0));
    printf("  fp32: %s, %d iterations in %d refinements, true relres %.2e\n",
           sessile_solve_status_name(r32.status), r32.iterations, r32.refinements, r32.true_relres);
    t_true("fp32 nutrient solve converged", r32.status == SESSILE_SOLVE_CONVERGED);
    t_check("fp32 nutrient vs reference PCG (max)", t_relerr(c0, cr, n), 1e-5);
    sessile_buffer_destroy(m32);
    sessile_vec_destroy(v32);
    sessile_nutrient_destroy(nt32);
    sessile_la_destroy(la32);
    uint64_t v = sessile_gpu_validation_count(g32);
    sessile_gpu_destroy(g32);
    t_check("fp32 context validation messages", (double)v, 0);
  }

  free(dinv);
  sessile_csr_free(&K);
  sessile_csr_free(&A);
  free(c), free(c0), free(cr), free(bb);
  sessile_buffer_destroy(ms);
  sessile_buffer_destroy(mb);
  sessile_vec_destroy(vc);
  sessile_nutrient_destroy(nt);
  nutrient_case_free(&small);
  nutrient_case_free(&big);
}

/* ---------------------------------------------------------------------- */
/* --bench: the default pipeline box (65 x 65 x 49 nodes, h = 0.6 cm) with a
 * 6 cm ball on the substratum. */
static void bench(void) {
  const double o[3] = {0, 0, 0}, h = 0.6, ctr[3] = {19.2, 19.2, 6.0};
  sessile_box b = box_of(65, 65, 49, h, o);
  nutrient_case prev, cur;
  nutrient_case_make(&prev, &b, ctr, 5.7);
  nutrient_case_make(&cur, &b, ctr, 6.0);
  uint32_t n = cur.n;
  sessile_nutrient *nt;
  sessile_vec *vc, *vb, *vx;
  t_must("nutrient", sessile_nutrient_create(la, &b, &nt));
  t_must("vec", sessile_vec_create(la, n, &vc));
  t_must("vec", sessile_vec_create(la, n, &vb));
  t_must("vec", sessile_vec_create(la, n, &vx));
  sessile_buffer *mp = mask_buffer(&b, prev.mask), *mc = mask_buffer(&b, cur.mask);
  sessile_solve_result r;
  t_must("warm-up", sessile_nutrient_solve(nt, mc, vc, NULL, &r)); /* pipelines compiled */
  t_must("zero", sessile_vec_fill(la, 0.0, vc));
  t_must("cold", sessile_nutrient_solve(nt, mc, vc, NULL, &r));
  printf("bench %ux%ux%u: cold solve %d it, %.3f s, relres %.2e\n", b.n[0], b.n[1], b.n[2],
         r.iterations, r.seconds, r.true_relres);
  t_must("zero", sessile_vec_fill(la, 0.0, vc));
  t_must("prev", sessile_nutrient_solve(nt, mp, vc, NULL, &r));
  t_must("warm", sessile_nutrient_solve(nt, mc, vc, NULL, &r));
  printf("bench: warm solve (from the 5.7 cm ball's field) %d it, %.3f s, relres %.2e\n",
         r.iterations, r.seconds, r.true_relres);

  /* Operator application: stencil vs the CSR of the eliminated P1 matrix. */
  sessile_csr K, A;
  double *bb = t_xalloc(n * 8);
  t_must("assemble", sessile_p1_laplace_assemble(&b, &K));
  t_must("eliminate", sessile_p1_dirichlet(&K, cur.dir, cur.g, &A, bb));
  sessile_mat *st, *csr;
  t_must("stencil", sessile_mat_create_stencil7(la, b.n[0], b.n[1], b.n[2], h, mc, &st));
  t_must("csr", sessile_mat_create_csr(la, &A, &csr));
  const int reps = 20;
  for (int m = 0; m < 2; m++) {
    sessile_mat *a = m ? csr : st;
    t_must("mult", sessile_mat_mult(la, a, vc, vx));
    double t0 = sessile_wall_seconds();
    for (int i = 0; i < reps; i++) t_must("mult", sessile_mat_mult(la, a, vc, vx));
    printf("bench: %s application %.2f ms (incl. one submit-and-wait each)\n",
           m ? "CSR SpMV (P1, eliminated)" : "stencil7", 1e3 * (sessile_wall_seconds() - t0) / reps);
  }
  for (uint32_t i = 0; i < n; i++) /* the homogenised system, as the stencil solve */
    if (cur.dir[i]) bb[i] = 0;
  t_must("b", sessile_vec_upload(vb, bb));
  t_must("zero", sessile_vec_fill(la, 0.0, vx));
  t_must("csr solve", sessile_ksp_solve(la, NULL, csr, vb, vx, &r));
  printf("bench: CSR PCG cold solve (homogenised, as the stencil solve) %d it, %.3f s, relres %.2e\n",
         r.iterations, r.seconds, r.true_relres);
  sessile_mat_destroy(st);
  sessile_mat_destroy(csr);
  sessile_csr_free(&K);
  sessile_csr_free(&A);
  free(bb);
  sessile_buffer_destroy(mp);
  sessile_buffer_destroy(mc);
  sessile_vec_destroy(vc);
  sessile_vec_destroy(vb);
  sessile_vec_destroy(vx);
  sessile_nutrient_destroy(nt);
  nutrient_case_free(&prev);
  nutrient_case_free(&cur);
}

int main(int argc, char **argv) {
  int do_bench = argc > 1 && strcmp(argv[1], "--bench") == 0;
  if (do_bench) { /* timings without the validation layer */
    sessile_gpu_options go;
    sessile_gpu_options_default(&go);
    go.validation = 0;
    t_must("gpu", sessile_gpu_create(&go, &gpu));
    printf("device: %s, driver %s\n", sessile_gpu_info_of(gpu)->name, sessile_gpu_info_of(gpu)->driver);
  } else {
    gpu = t_gpu(0);
  }
  t_must("la", sessile_la_create(gpu, &la));
  if (do_bench) {
    bench();
  } else {
    test_assembly();
    test_spmv();
    test_patch();
    test_convergence();
    test_nutrient_bcs();
  }
  sessile_la_destroy(la);
  return t_finish(gpu);
}
