/* `sessile bench la`, the multigrid part: MG-PCG (sessile/la/mg.h, default
 * options) beside Jacobi-PCG (sessile_ksp_solve, CG + Jacobi) on the same
 * cut-cell operator: the sphere problem of tests/la/test_mg.c
 * (sessile_cut_sphere) on the nested box sizes 33x33x25, 65x65x49 and
 * 129x129x97, every level built the same way.  Whole solves, wall clock,
 * median of 3, cold (x = 0); "fixed" is a solve that starts at the solution
 * (0 iterations: everything but the iterations); "warm" starts from the
 * solution with 1 % noise on the free nodes.  docs/performance.md. */
#include <stdlib.h>
#include <string.h>
#include "bench_internal.h"

typedef struct {
  int nl;
  sessile_mg_level lv[MG_MAX_LEVELS];
  double *b;
  uint32_t *mask0;
} problem;

static const double box[3] = {38.4, 38.4, 28.8}, centre[3] = {17.28, 19.2, 11.52}, radius = 8.64;

static void problem_free(problem *p) {
  for (int l = 0; l < p->nl; l++) {
    sessile_buffer_destroy(p->lv[l].mask);
    sessile_vec_destroy((sessile_vec *)p->lv[l].diag);
  }
  free(p->b);
  free(p->mask0);
}

/* Every level down to the coarsest the nesting allows. */
static sessile_status problem_make(sessile_la *la, uint32_t nx, uint32_t ny, uint32_t nz, problem *p) {
  uint32_t n[3] = {nx, ny, nz};
  double h = box[0] / (nx - 1);
  sessile_status s = SESSILE_OK;
  for (int l = 0; s == SESSILE_OK && l < MG_MAX_LEVELS; l++) {
    uint32_t nodes = n[0] * n[1] * n[2];
    uint32_t *mask = malloc((size_t)nodes * sizeof *mask);
    double *diag = malloc((size_t)nodes * sizeof *diag), *b = l ? NULL : malloc((size_t)nodes * sizeof *b);
    sessile_buffer *mb = NULL;
    sessile_vec *vd = NULL;
    if (!mask || !diag || (!l && !b)) s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
    if (s == SESSILE_OK) {
      sessile_cut_sphere(n[0], n[1], n[2], h, centre, radius, mask, diag, b);
      s = sessile_buffer_create(la->gpu, (size_t)nodes * 4, SESSILE_BUFFER_DEVICE, &mb);
    }
    if (s == SESSILE_OK) s = sessile_buffer_upload(mb, 0, mask, (size_t)nodes * 4);
    if (s == SESSILE_OK) s = sessile_vec_create(la, nodes, &vd);
    if (s == SESSILE_OK) s = sessile_vec_upload(vd, diag);
    sessile_mg_level v = {{n[0], n[1], n[2]}, h, mb, vd, NULL};
    p->lv[l] = v;
    p->nl = l + 1;
    if (l == 0) {
      p->b = b;
      p->mask0 = mask;
    } else free(mask);
    free(diag);
    if ((n[0] - 1) % 2 || (n[1] - 1) % 2 || (n[2] - 1) % 2) break;
    for (int a = 0; a < 3; a++) n[a] = (n[a] - 1) / 2 + 1;
    h *= 2;
  }
  return s;
}

static double median3(const double t[3]) {
  double a = t[0], b = t[1], c = t[2];
  return a > b ? (b > c ? b : a > c ? c : a) : (a > c ? a : b > c ? c : b);
}

/* Three solves from x0 (NULL: zero): median seconds, iterations of the last. */
typedef struct { sessile_la *la; sessile_mg *mg; const sessile_mat *a; sessile_vec *b, *x; } solver;
static sessile_status solve3(const solver *sv, const double *x0, double *seconds, int *its) {
  sessile_ksp_options o;
  sessile_ksp_options_default(&o);
  o.max_it = 5000;
  double t[3];
  for (int k = 0; k < 3; k++) {
    sessile_solve_result r;
    SESSILE_CALL(x0 ? sessile_vec_upload(sv->x, x0) : sessile_vec_fill(sv->la, 0, sv->x));
    SESSILE_CALL(sv->mg ? sessile_mg_solve(sv->mg, &o, sv->b, sv->x, &r)
                        : sessile_ksp_solve(sv->la, &o, sv->a, sv->b, sv->x, &r));
    SESSILE_CHECK(r.status == SESSILE_SOLVE_CONVERGED, SESSILE_ERR_NUMERIC,
                  "bench: %s did not converge (%s)", sv->mg ? "mg-pcg" : "jacobi-pcg", r.reason);
    t[k] = r.seconds;
    *its = r.iterations;
  }
  *seconds = median3(t);
  return SESSILE_OK;
}

static sessile_status bench_size(sessile_la *la, uint32_t nx, uint32_t ny, uint32_t nz, FILE *out) {
  problem p = {0};
  uint32_t n = nx * ny * nz;
  sessile_mat *a = NULL;
  sessile_mg *mg = NULL;
  sessile_vec *b = NULL, *x = NULL;
  double *xs = malloc(2 * (size_t)n * sizeof *xs), tj, tm, fj, fm, tw;
  int ij, im, i0, iw;
  sessile_status s = xs ? problem_make(la, nx, ny, nz, &p)
                        : sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  if (s == SESSILE_OK) s = sessile_vec_create(la, n, &b);
  if (s == SESSILE_OK) s = sessile_vec_create(la, n, &x);
  if (s == SESSILE_OK) s = sessile_vec_upload(b, p.b);
  if (s == SESSILE_OK)
    s = sessile_mat_create_stencil7_cut(la, nx, ny, nz, p.lv[0].h, p.lv[0].mask, p.lv[0].diag, &a);
  if (s == SESSILE_OK) s = sessile_mg_create(la, p.nl, p.lv, NULL, &mg);
  solver jac = {la, NULL, a, b, x}, mgs = {la, mg, a, b, x};
  if (s == SESSILE_OK) s = solve3(&mgs, NULL, &tm, &im);
  if (s == SESSILE_OK) s = sessile_vec_download(x, xs);
  if (s == SESSILE_OK) s = solve3(&mgs, xs, &fm, &i0);
  if (s == SESSILE_OK) {
    sessile_fill_random(xs + n, n, -0.01, 0.01, 5);
    for (uint32_t i = 0; i < n; i++) xs[n + i] = p.mask0[i] ? 0 : xs[i] * (1 + xs[n + i]);
    s = solve3(&mgs, xs + n, &tw, &iw);
  }
  if (s == SESSILE_OK) s = solve3(&jac, NULL, &tj, &ij);
  if (s == SESSILE_OK) s = solve3(&jac, xs, &fj, &i0);
  if (s == SESSILE_OK) {
    char grid[32];
    snprintf(grid, sizeof grid, "%ux%ux%u", nx, ny, nz);
    fprintf(out, "%-11s %8u %2d %6d %8.3f %7.2f %7.1f %6d %7.3f %7.2f %7.1f %8.3f\n", grid, n, p.nl,
            ij, tj, tj / ij * 1e3, tj / ij / n * 1e9, im, tm, tm / im * 1e3, tm / im / n * 1e9,
            tm / tj);
    fprintf(out, "    fixed cost per solve (starting at the solution, 0 iterations): jacobi-pcg "
                 "%.3f s, mg-pcg %.3f s; mg-pcg warm (1 %% noise): %d iterations, %.3f s\n",
            fj, fm, iw, tw);
  }
  sessile_mg_destroy(mg);
  sessile_mat_destroy(a);
  sessile_vec_destroy(b);
  sessile_vec_destroy(x);
  problem_free(&p);
  free(xs);
  return s;
}

sessile_status la_bench_mg(sessile_la *la, unsigned sizes, FILE *out) {
  fprintf(out, "\nmultigrid PCG (V(2,2), damped Jacobi 6/7, 8 coarse sweeps) vs Jacobi-PCG, cut-cell "
               "sphere problem,\nrtol 1e-6, x = 0, whole solves, median of 3 (ns/n/it: per node "
               "and iteration)\n");
  fprintf(out, "%-11s %8s %2s %6s %8s %7s %7s %6s %7s %7s %7s %8s\n", "grid", "nodes", "lv", "jac it",
          "jac s", "ms/it", "ns/n/it", "mg it", "mg s", "ms/it", "ns/n/it", "mg/jacobi");
  sessile_status s = SESSILE_OK;
  for (unsigned k = 0; s == SESSILE_OK && k < sizes && k < 3; k++) {
    uint32_t r = 1u << k;
    s = bench_size(la, 32 * r + 1, 32 * r + 1, 24 * r + 1, out);
  }
  return s;
}
