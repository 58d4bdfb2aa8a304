/* The cut-cell 7-point operator (sessile_mat_create_stencil7_cut) on the
 * device against sessile_ref_stencil7_cut: random masks with ~20 % Dirichlet
 * nodes, random diagonals in [f-sum, 10 f-sum] (f-sum: the node's face
 * fractions over its existing neighbours), no Dirichlet walls so the half and
 * quarter faces of the zero-flux walls are exercised, grid sizes that are not
 * multiples of the local size; through the texel and the storage-buffer
 * kernels.  Symmetry x·Ay = y·Ax, Jacobi, CG + Jacobi through
 * sessile_ksp_solve, and the creation errors.
 *
 * Error measure: max_n |y_n - ref_n| / (h (diag_n |x_n| + sum f |x_m|)), the
 * row-wise bound of any summation order (7 terms: ~7 eps); fp64 tolerance
 * 1e-14, fp32 path 1e-5 (x and diag stored in float).  Symmetry: |x·Ay -
 * y·Ax| / (|x| |Ay|), fp64 1e-14 (sums of 10^4..10^5 products, each side
 * rounded differently), fp32 1e-5.  Run with --fp32 for the fp32 path. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sessile/la/la_ref.h"
#include "testutil.h"

static sessile_la *la;
static int fp64;

static double stored(double v) { return fp64 ? v : (double)(float)v; }

typedef struct {
  uint32_t n[3], nodes;
  double h;
  uint32_t *mask;
  double *diag, *bound; /* bound: f-sum per node */
} grid;

static double half(uint32_t i, uint32_t n) { return i == 0 || i == n - 1 ? 0.5 : 1; }

/* Random mask (~20 % Dirichlet), diag in [f-sum, 10 f-sum] on free nodes. */
static grid make_grid(uint32_t nx, uint32_t ny, uint32_t nz, double h, uint64_t seed) {
  grid g = {{nx, ny, nz}, nx * ny * nz, h, NULL, NULL, NULL};
  g.mask = t_xalloc((size_t)g.nodes * 4);
  g.diag = t_dalloc(g.nodes);
  g.bound = t_dalloc(g.nodes);
  double *u = t_dalloc(2 * (size_t)g.nodes);
  sessile_fill_random(u, 2 * (uint64_t)g.nodes, 0, 1, seed);
  for (uint32_t k = 0; k < nz; k++)
    for (uint32_t j = 0; j < ny; j++)
      for (uint32_t i = 0; i < nx; i++) {
        uint32_t n = i + nx * (j + ny * k);
        double bx = half(i, nx), by = half(j, ny), bz = half(k, nz);
        double fs = by * bz * ((i > 0) + (i + 1 < nx)) + bx * bz * ((j > 0) + (j + 1 < ny)) +
                    bx * by * ((k > 0) + (k + 1 < nz));
        g.mask[n] = u[n] < 0.2;
        g.diag[n] = stored(fs * (1 + 9 * u[g.nodes + n]));
        g.bound[n] = fs;
      }
  free(u);
  return g;
}

static void free_grid(grid *g) {
  free(g->mask);
  free(g->diag);
  free(g->bound);
}

/* Row-wise scale h (diag |x_n| + sum f |x_m|) of node n (|x_n| on Dirichlet
 * nodes), bounded above by h (diag + f-sum) max|x|. */
static double row_scale(const grid *g, uint32_t n, double xmax) {
  return g->mask[n] ? xmax : g->h * (g->diag[n] + g->bound[n]) * xmax;
}

static double rowwise(const grid *g, const double *x, const double *y, const double *r) {
  double xmax = 0, e = 0;
  for (uint32_t n = 0; n < g->nodes; n++) xmax = fmax(xmax, fabs(x[n]));
  for (uint32_t n = 0; n < g->nodes; n++) {
    double d = fabs(y[n] - r[n]) / row_scale(g, n, xmax);
    if (!(d <= e)) e = d;
  }
  return e;
}

static double dot(const double *a, const double *b, uint32_t n) {
  double s = 0;
  for (uint32_t i = 0; i < n; i++) s += a[i] * b[i];
  return s;
}

static void check_grid(uint32_t nx, uint32_t ny, uint32_t nz, uint64_t seed) {
  char what[160];
  grid g = make_grid(nx, ny, nz, 0.37, seed);
  uint32_t n = g.nodes;
  double *x = t_dalloc(n), *x2 = t_dalloc(n), *y = t_dalloc(n), *y2 = t_dalloc(n),
         *r = t_dalloc(n), *r2 = t_dalloc(n);
  sessile_fill_random(x, n, -1, 1, seed + 1);
  sessile_fill_random(x2, n, -1, 1, seed + 2);
  for (uint32_t i = 0; i < n; i++) {
    x[i] = stored(x[i]);
    x2[i] = stored(x2[i]);
  }
  sessile_buffer *mb = NULL;
  sessile_vec *vd = NULL, *vx = NULL, *vx2 = NULL, *vy = NULL, *vy2 = NULL;
  t_must("mask buffer", sessile_buffer_create(sessile_la_gpu(la), (size_t)n * 4, SESSILE_BUFFER_DEVICE, &mb));
  t_must("mask upload", sessile_buffer_upload(mb, 0, g.mask, (size_t)n * 4));
  t_must("vec", sessile_vec_create(la, n, &vd));
  t_must("vec", sessile_vec_create(la, n, &vx));
  t_must("vec", sessile_vec_create(la, n, &vx2));
  t_must("vec", sessile_vec_create(la, n, &vy));
  t_must("vec", sessile_vec_create(la, n, &vy2));
  t_must("upload", sessile_vec_upload(vd, g.diag));
  t_must("upload", sessile_vec_upload(vx, x));
  t_must("upload", sessile_vec_upload(vx2, x2));
  sessile_ref_stencil7_cut(nx, ny, nz, g.h, g.mask, g.diag, x, r);
  sessile_ref_stencil7_cut(nx, ny, nz, g.h, g.mask, g.diag, x2, r2);
  double tol = fp64 ? 1e-14 : 1e-5;
  for (int storage = 0; storage < 2; storage++) {
    sessile_la_options lo;
    sessile_la_options_default(&lo);
    lo.spmv_storage = storage;
    sessile_la_set_options(la, &lo);
    const char *path = storage ? "storage" : "texel";
    sessile_mat *a = NULL;
    t_must("create_stencil7_cut", sessile_mat_create_stencil7_cut(la, nx, ny, nz, g.h, mb, vd, &a));
    t_must("mat_mult", sessile_mat_mult(la, a, vx, vy));
    t_must("mat_mult", sessile_mat_mult(la, a, vx2, vy2));
    t_must("download", sessile_vec_download(vy, y));
    t_must("download", sessile_vec_download(vy2, y2));
    snprintf(what, sizeof what, "%ux%ux%u %s: A x vs sessile_ref_stencil7_cut (row-wise)", nx, ny, nz, path);
    t_check(what, fmax(rowwise(&g, x, y, r), rowwise(&g, x2, y2, r2)), tol);
    double sym = fabs(dot(x2, y, n) - dot(x, y2, n)) / sqrt(dot(x, x, n) * dot(y2, y2, n));
    snprintf(what, sizeof what, "%ux%ux%u %s: symmetric, |x2·Ax - x·Ax2| / |x||Ax2|", nx, ny, nz, path);
    t_check(what, sym, fp64 ? 1e-14 : 1e-5);
    sessile_mat_destroy(a);
  }
  sessile_la_options lo;
  sessile_la_options_default(&lo);
  sessile_la_set_options(la, &lo);

  /* Jacobi: 1/(h diag) free, 1 Dirichlet. */
  sessile_mat *a = NULL;
  t_must("create_stencil7_cut", sessile_mat_create_stencil7_cut(la, nx, ny, nz, g.h, mb, vd, &a));
  t_must("jacobi", sessile_mat_jacobi(la, a, vy));
  t_must("download", sessile_vec_download(vy, y));
  double je = 0;
  for (uint32_t i = 0; i < n; i++) {
    double want = g.mask[i] ? 1 : 1 / (g.h * g.diag[i]);
    je = fmax(je, fabs(y[i] - want) / want);
  }
  snprintf(what, sizeof what, "%ux%ux%u: Jacobi vs 1/(h diag)", nx, ny, nz);
  t_check(what, je, fp64 ? 2.3e-16 : 1e-6);

  /* CG + Jacobi: random b, the residual recomputed on the host. */
  if (n >= 64) {
    sessile_fill_random(r, n, -1, 1, seed + 3);
    for (uint32_t i = 0; i < n; i++) r[i] = stored(r[i]);
    t_must("upload", sessile_vec_upload(vy, r));
    t_must("fill", sessile_vec_fill(la, 0, vx));
    sessile_ksp_options o;
    sessile_ksp_options_default(&o);
    sessile_solve_result res;
    t_must("ksp_solve", sessile_ksp_solve(la, &o, a, vy, vx, &res));
    t_must("download", sessile_vec_download(vx, x));
    sessile_ref_stencil7_cut(nx, ny, nz, g.h, g.mask, g.diag, x, y);
    for (uint32_t i = 0; i < n; i++) y[i] = r[i] - y[i];
    double rel = sqrt(dot(y, y, n) / dot(r, r, n));
    snprintf(what, sizeof what, "%ux%ux%u: CG + Jacobi converged (%d its), host true relres",
             nx, ny, nz, res.iterations);
    t_check(what, res.status == SESSILE_SOLVE_CONVERGED ? rel : INFINITY, 1e-6);
  }
  sessile_mat_destroy(a);
  sessile_vec_destroy(vd);
  sessile_vec_destroy(vx);
  sessile_vec_destroy(vx2);
  sessile_vec_destroy(vy);
  sessile_vec_destroy(vy2);
  sessile_buffer_destroy(mb);
  free(x);
  free(x2);
  free(y);
  free(y2);
  free(r);
  free(r2);
  free_grid(&g);
}

static void expect_usage(const char *what, sessile_status s, sessile_mat *m) {
  char line[200];
  snprintf(line, sizeof line, "%s: SESSILE_ERR_USAGE (%s)", what, sessile_error_message());
  t_true(line, s == SESSILE_ERR_USAGE && m == NULL);
  sessile_mat_destroy(m);
}

static void check_errors(void) {
  sessile_buffer *mb = NULL, *small = NULL;
  sessile_vec *d = NULL, *d2 = NULL;
  sessile_mat *m = NULL;
  t_must("buffer", sessile_buffer_create(sessile_la_gpu(la), 60 * 4, SESSILE_BUFFER_DEVICE, &mb));
  t_must("buffer", sessile_buffer_create(sessile_la_gpu(la), 59 * 4, SESSILE_BUFFER_DEVICE, &small));
  t_must("vec", sessile_vec_create(la, 60, &d));
  t_must("vec", sessile_vec_create(la, 59, &d2));
  expect_usage("one node along x", sessile_mat_create_stencil7_cut(la, 1, 6, 10, 1, mb, d, &m), m);
  expect_usage("h = 0", sessile_mat_create_stencil7_cut(la, 3, 4, 5, 0, mb, d, &m), m);
  expect_usage("no mask", sessile_mat_create_stencil7_cut(la, 3, 4, 5, 1, NULL, d, &m), m);
  expect_usage("mask too small", sessile_mat_create_stencil7_cut(la, 3, 4, 5, 1, small, d, &m), m);
  expect_usage("no diag", sessile_mat_create_stencil7_cut(la, 3, 4, 5, 1, mb, NULL, &m), m);
  expect_usage("diag of the wrong size", sessile_mat_create_stencil7_cut(la, 3, 4, 5, 1, mb, d2, &m), m);
  t_ok("3x4x5 with the right sizes", sessile_mat_create_stencil7_cut(la, 3, 4, 5, 1, mb, d, &m));
  sessile_mat_destroy(m);
  sessile_vec_destroy(d);
  sessile_vec_destroy(d2);
  sessile_buffer_destroy(mb);
  sessile_buffer_destroy(small);
}

int main(int argc, char **argv) {
  int precision = argc > 1 && strcmp(argv[1], "--fp32") == 0 ? 32 : 0;
  sessile_gpu *g = t_gpu(precision);
  fp64 = sessile_gpu_info_of(g)->precision == 64;
  t_must("la_create", sessile_la_create(g, &la));
  check_grid(2, 2, 2, 11);
  check_grid(13, 7, 5, 12);
  check_grid(31, 17, 9, 13);
  check_grid(33, 33, 25, 14);
  check_grid(65, 65, 49, 15);
  check_errors();
  sessile_la_destroy(la);
  return t_finish(g);
}
