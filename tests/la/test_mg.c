/* Geometric multigrid (sessile/la/mg.h) on the cut-cell sphere problem
 * (sessile_cut_sphere): a 38.4 x 38.4 x 28.8 box, a solid sphere of radius
 * 8.64 at (17.28, 19.2, 11.52), zero-flux side walls, u = 0 on the sphere and
 * the bottom, u = 1 on the top, every level built the same way at its own
 * spacing; grids 33x33x25 (4 levels), 65x65x49 (5) and, with --large,
 * 129x129x97 (6).
 *
 * Checks: MG-PCG reaches the true relative residual 1e-6 (recomputed on the
 * host with sessile_ref_stencil7_cut) in at most 15 iterations cold (x = 0)
 * and warm (x = the solution plus 1 % noise); the device and the host
 * reference sessile_ref_mg_pcg take the same iterations (+-1) and give the
 * same solution to 1e-8 relative (both solve to rtol 1e-6, but with the same
 * algorithm they agree to rounding: observed ~1e-13); the V-cycle is
 * symmetric (|x·My - y·Mx| <= 1e-10 |x||My|) and positive, and equals the
 * reference V-cycle to 1e-12; a solve with the same b and x re-records
 * nothing; new mask and diag contents are picked up without re-creating;
 * other smoothing settings and a single level (M = omega D^-1: the
 * iterations of Jacobi-PCG); every kind of bad input is SESSILE_ERR_USAGE.
 * --fp32: the 33x33x25 grid through the mixed-precision refinement. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "la/mg_internal.h"
#include "sessile/la/la_ref.h"
#include "testutil.h"

static sessile_la *la;
static int fp64 = 1;

#define MAXL 8

typedef struct {
  int nl;
  sessile_ref_mg_level ref[MAXL];
  sessile_mg_level lv[MAXL];
  uint32_t *mask[MAXL];
  double *diag[MAXL], *b;
  sessile_buffer *mb[MAXL];
  sessile_vec *vd[MAXL];
} problem;

static const double box[3] = {38.4, 38.4, 28.8}, centre[3] = {17.28, 19.2, 11.52};

/* Host arrays of every level for sphere radius `radius`, uploaded into the
 * problem's buffers (created on the first call). */
static void build(problem *p, uint32_t nx, uint32_t ny, uint32_t nz, double radius) {
  uint32_t n[3] = {nx, ny, nz};
  double h = box[0] / (nx - 1);
  int create = p->nl == 0;
  int l = 0;
  for (;; l++) {
    uint32_t nodes = n[0] * n[1] * n[2];
    if (create) {
      p->mask[l] = t_xalloc((size_t)nodes * 4);
      p->diag[l] = t_dalloc(nodes);
      if (l == 0) p->b = t_dalloc(nodes);
      t_must("mask", sessile_buffer_create(sessile_la_gpu(la), (size_t)nodes * 4, SESSILE_BUFFER_DEVICE, &p->mb[l]));
      t_must("diag", sessile_vec_create(la, nodes, &p->vd[l]));
    }
    sessile_cut_sphere(n[0], n[1], n[2], h, centre, radius, p->mask[l], p->diag[l], l ? NULL : p->b);
    if (!fp64)
      for (uint32_t i = 0; i < nodes; i++) p->diag[l][i] = (float)p->diag[l][i];
    t_must("upload", sessile_buffer_upload(p->mb[l], 0, p->mask[l], (size_t)nodes * 4));
    t_must("upload", sessile_vec_upload(p->vd[l], p->diag[l]));
    sessile_ref_mg_level r = {{n[0], n[1], n[2]}, h, p->mask[l], p->diag[l], NULL};
    sessile_mg_level g = {{n[0], n[1], n[2]}, h, p->mb[l], p->vd[l], NULL};
    p->ref[l] = r;
    p->lv[l] = g;
    if ((n[0] - 1) % 2 || (n[1] - 1) % 2 || (n[2] - 1) % 2 || l + 1 == MAXL) break;
    for (int a = 0; a < 3; a++) n[a] = (n[a] - 1) / 2 + 1;
    h *= 2;
  }
  p->nl = l + 1;
}

static void destroy(problem *p) {
  for (int l = 0; l < p->nl; l++) {
    free(p->mask[l]);
    free(p->diag[l]);
    sessile_buffer_destroy(p->mb[l]);
    sessile_vec_destroy(p->vd[l]);
  }
  free(p->b);
}

static double dot(const double *a, const double *b, uint32_t n) {
  double s = 0;
  for (uint32_t i = 0; i < n; i++) s += a[i] * b[i];
  return s;
}

/* ||b - A x|| / ||b|| on the host. */
static double host_relres(const problem *p, const double *x) {
  const sessile_ref_mg_level *v = &p->ref[0];
  uint32_t n = v->n[0] * v->n[1] * v->n[2];
  double *r = t_dalloc(n);
  sessile_ref_stencil7_cut(v->n[0], v->n[1], v->n[2], v->h, v->mask, v->diag, x, r);
  for (uint32_t i = 0; i < n; i++) r[i] = p->b[i] - r[i];
  double rel = sqrt(dot(r, r, n) / dot(p->b, p->b, n));
  free(r);
  return rel;
}

/* MG-PCG from x0 (NULL: zero) on the device; returns the iterations, x in x. */
static int gpu_solve(sessile_mg *mg, const char *name, const problem *p, sessile_vec *vb,
                     sessile_vec *vx, const double *x0, double *x, double *seconds) {
  char what[200];
  uint32_t n = sessile_vec_size(vb);
  if (x0) t_must("upload", sessile_vec_upload(vx, x0));
  else t_must("fill", sessile_vec_fill(la, 0, vx));
  sessile_ksp_options o;
  sessile_ksp_options_default(&o);
  sessile_solve_result res;
  t_must("mg_solve", sessile_mg_solve(mg, &o, vb, vx, &res));
  t_must("download", sessile_vec_download(vx, x));
  double rel = host_relres(p, x);
  snprintf(what, sizeof what, "%s: %s, %d iterations (<= 15), %.2f s; host true relres", name,
           sessile_solve_status_name(res.status), res.iterations, res.seconds);
  t_check(what, res.status == SESSILE_SOLVE_CONVERGED && res.iterations <= 15 ? rel : INFINITY, 1e-6);
  snprintf(what, sizeof what, "%s: reported true relres = the host's", name);
  t_check(what, fabs(res.true_relres - rel) / rel, fp64 ? 1e-6 : 0.1);
  (void)n;
  if (seconds) *seconds = res.seconds;
  return res.iterations;
}

static void check_vcycle(sessile_mg *mg, const problem *p, const char *name) {
  char what[200];
  const sessile_ref_mg_level *v = &p->ref[0];
  uint32_t n = v->n[0] * v->n[1] * v->n[2];
  double *x = t_dalloc(n), *y = t_dalloc(n), *mx = t_dalloc(n), *my = t_dalloc(n), *rx = t_dalloc(n);
  sessile_fill_random(x, n, -1, 1, 21);
  sessile_fill_random(y, n, -1, 1, 22);
  sessile_vec *vx = NULL, *vy = NULL, *vz = NULL;
  t_must("vec", sessile_vec_create(la, n, &vx));
  t_must("vec", sessile_vec_create(la, n, &vy));
  t_must("vec", sessile_vec_create(la, n, &vz));
  t_must("upload", sessile_vec_upload(vx, x));
  t_must("upload", sessile_vec_upload(vy, y));
  t_must("vcycle", sessile_mg_vcycle(mg, vx, vz));
  t_must("download", sessile_vec_download(vz, mx));
  t_must("vcycle", sessile_mg_vcycle(mg, vy, vz));
  t_must("download", sessile_vec_download(vz, my));
  double sym = fabs(dot(x, my, n) - dot(y, mx, n)) / sqrt(dot(x, x, n) * dot(my, my, n));
  snprintf(what, sizeof what, "%s: V-cycle symmetric, |x·My - y·Mx| / |x||My|", name);
  t_check(what, sym, 1e-10);
  snprintf(what, sizeof what, "%s: V-cycle positive, x·Mx = %.3e > 0", name, dot(x, mx, n));
  t_true(what, dot(x, mx, n) > 0 && dot(y, my, n) > 0);
  t_must("ref vcycle", sessile_ref_mg_vcycle(mg->nl, p->ref, &mg->o, x, rx));
  snprintf(what, sizeof what, "%s: V-cycle = sessile_ref_mg_vcycle", name);
  t_check(what, t_relerr(mx, rx, n), 1e-12);
  sessile_vec_destroy(vx);
  sessile_vec_destroy(vy);
  sessile_vec_destroy(vz);
  free(x);
  free(y);
  free(mx);
  free(my);
  free(rx);
}

/* The device against the reference from x = 0 with options o. */
static void check_ref(sessile_mg *mg, const problem *p, sessile_vec *vb, sessile_vec *vx,
                      const char *name, int its, const double *x) {
  char what[200];
  uint32_t n = sessile_vec_size(vb);
  double *xr = t_dalloc(n);
  sessile_ref_result rr = sessile_ref_mg_pcg(mg->nl, p->ref, &mg->o, p->b, xr, 1e-6, 1000);
  snprintf(what, sizeof what, "%s: iterations device %d, reference %d (+-1)", name, its, rr.iterations);
  t_true(what, rr.status == SESSILE_REF_CONVERGED && abs(its - rr.iterations) <= 1);
  snprintf(what, sizeof what, "%s: solution = sessile_ref_mg_pcg's", name);
  t_check(what, t_relerr(x, xr, n), 1e-8);
  (void)vx;
  free(xr);
}

static void check_grid(uint32_t nx, uint32_t ny, uint32_t nz) {
  char name[32], what[200];
  snprintf(name, sizeof name, "%ux%ux%u", nx, ny, nz);
  problem p = {0};
  build(&p, nx, ny, nz, 8.64);
  uint32_t n = nx * ny * nz;
  sessile_mg *mg = NULL;
  t_must("mg_create", sessile_mg_create(la, p.nl, p.lv, NULL, &mg));
  printf("%s: %d levels, coarsest %ux%ux%u\n", name, p.nl, p.lv[p.nl - 1].n[0],
         p.lv[p.nl - 1].n[1], p.lv[p.nl - 1].n[2]);
  sessile_vec *vb = NULL, *vx = NULL;
  t_must("vec", sessile_vec_create(la, n, &vb));
  t_must("vec", sessile_vec_create(la, n, &vx));
  t_must("upload", sessile_vec_upload(vb, p.b));
  double *x = t_dalloc(n), *x0 = t_dalloc(n), t1, t2;
  char sub[128];
  snprintf(sub, sizeof sub, "%s cold", name);
  int cold = gpu_solve(mg, sub, &p, vb, vx, NULL, x, &t1);
  unsigned rec = mg->recordings;
  snprintf(sub, sizeof sub, "%s cold again", name);
  int again = gpu_solve(mg, sub, &p, vb, vx, NULL, x, &t2);
  snprintf(what, sizeof what, "%s: a second solve with the same b, x re-records nothing, same %d its",
           name, cold);
  t_true(what, mg->recordings == rec && again == cold);
  if (fp64) check_ref(mg, &p, vb, vx, name, cold, x);
  /* warm: the solution plus 1 % noise on the free nodes */
  sessile_fill_random(x0, n, -0.01, 0.01, 5);
  for (uint32_t i = 0; i < n; i++) x0[i] = p.mask[0][i] ? 0 : x[i] * (1 + x0[i]);
  snprintf(sub, sizeof sub, "%s warm", name);
  gpu_solve(mg, sub, &p, vb, vx, x0, x, NULL);
  if (fp64) check_vcycle(mg, &p, name);
  if (fp64 && nx == 33) {
    /* New mask and diag contents in the same buffers: a larger sphere. */
    build(&p, nx, ny, nz, 10.0);
    t_must("upload", sessile_vec_upload(vb, p.b));
    snprintf(sub, sizeof sub, "%s, sphere radius 10 in the same buffers", name);
    int its = gpu_solve(mg, sub, &p, vb, vx, NULL, x, NULL);
    check_ref(mg, &p, vb, vx, sub, its, x);
    /* Other smoothing: V(1,1), 3 coarse sweeps, omega 2/3, two levels. */
    sessile_mg_options o;
    sessile_mg_options_default(&o);
    o.pre_smooth = o.post_smooth = 1;
    o.coarse_sweeps = 3;
    o.omega = 2.0 / 3.0;
    sessile_mg *mg2 = NULL;
    t_must("mg_create", sessile_mg_create(la, 2, p.lv, &o, &mg2));
    sessile_ksp_options ko;
    sessile_ksp_options_default(&ko);
    sessile_solve_result r2;
    t_must("fill", sessile_vec_fill(la, 0, vx));
    t_must("mg_solve", sessile_mg_solve(mg2, &ko, vb, vx, &r2));
    t_must("download", sessile_vec_download(vx, x));
    snprintf(sub, sizeof sub, "%s V(1,1) 2 levels", name);
    t_check("V(1,1), 2 levels, 3 coarse sweeps: host true relres", host_relres(&p, x), 1e-6);
    check_ref(mg2, &p, vb, vx, sub, r2.iterations, x);
    check_vcycle(mg2, &p, sub);
    sessile_mg_destroy(mg2);
    /* One level swept once: M = omega D^-1, so CG takes Jacobi-PCG's iterations. */
    o.coarse_sweeps = 1;
    t_must("mg_create", sessile_mg_create(la, 1, p.lv, &o, &mg2));
    t_must("fill", sessile_vec_fill(la, 0, vx));
    t_must("mg_solve", sessile_mg_solve(mg2, &ko, vb, vx, &r2));
    sessile_mat *a = NULL;
    sessile_solve_result rj;
    t_must("stencil7_cut", sessile_mat_create_stencil7_cut(la, nx, ny, nz, p.lv[0].h, p.mb[0], p.vd[0], &a));
    t_must("fill", sessile_vec_fill(la, 0, vx));
    t_must("ksp_solve", sessile_ksp_solve(la, &ko, a, vb, vx, &rj));
    snprintf(what, sizeof what, "one level, one sweep: %d iterations, Jacobi-PCG %d (+-1)",
             r2.iterations, rj.iterations);
    t_true(what, r2.status == SESSILE_SOLVE_CONVERGED && abs(r2.iterations - rj.iterations) <= 1);
    sessile_mat_destroy(a);
    sessile_mg_destroy(mg2);
  }
  sessile_vec_destroy(vb);
  sessile_vec_destroy(vx);
  sessile_mg_destroy(mg);
  destroy(&p);
  free(x);
  free(x0);
}

static void expect_usage(const char *what, sessile_status s, const sessile_mg *mg) {
  char line[400];
  snprintf(line, sizeof line, "%s: SESSILE_ERR_USAGE (%s)", what, sessile_error_message());
  t_true(line, s == SESSILE_ERR_USAGE && mg == NULL);
}

static void check_errors(void) {
  problem p = {0};
  build(&p, 17, 17, 13, 8.64);
  sessile_mg *mg = NULL;
  sessile_mg_level lv[MAXL];
  sessile_mg_options o;
  memcpy(lv, p.lv, sizeof lv);
  lv[1].n[2] = 6;
  expect_usage("level 1 not nested", sessile_mg_create(la, p.nl, lv, NULL, &mg), mg);
  memcpy(lv, p.lv, sizeof lv);
  lv[2].h *= 1.5;
  expect_usage("spacing not doubled", sessile_mg_create(la, p.nl, lv, NULL, &mg), mg);
  memcpy(lv, p.lv, sizeof lv);
  lv[1].mask = NULL;
  expect_usage("no mask", sessile_mg_create(la, p.nl, lv, NULL, &mg), mg);
  memcpy(lv, p.lv, sizeof lv);
  lv[2].diag = NULL;
  expect_usage("no diag", sessile_mg_create(la, p.nl, lv, NULL, &mg), mg);
  memcpy(lv, p.lv, sizeof lv);
  lv[0].mask = p.mb[1];
  expect_usage("mask buffer too small", sessile_mg_create(la, p.nl, lv, NULL, &mg), mg);
  memcpy(lv, p.lv, sizeof lv);
  lv[1].diag = p.vd[2];
  expect_usage("diag of the wrong size", sessile_mg_create(la, p.nl, lv, NULL, &mg), mg);
  expect_usage("no levels", sessile_mg_create(la, 0, p.lv, NULL, &mg), mg);
  expect_usage("levels NULL", sessile_mg_create(la, 2, NULL, NULL, &mg), mg);
  sessile_mg_options_default(&o);
  o.post_smooth = 3;
  expect_usage("pre_smooth != post_smooth", sessile_mg_create(la, p.nl, p.lv, &o, &mg), mg);
  sessile_mg_options_default(&o);
  o.omega = 1.2;
  expect_usage("omega > 1", sessile_mg_create(la, p.nl, p.lv, &o, &mg), mg);
  sessile_mg_options_default(&o);
  o.coarse_sweeps = 0;
  expect_usage("coarse_sweeps 0", sessile_mg_create(la, p.nl, p.lv, &o, &mg), mg);
  t_must("mg_create", sessile_mg_create(la, p.nl, p.lv, NULL, &mg));
  sessile_vec *small = NULL, *big = NULL;
  t_must("vec", sessile_vec_create(la, 100, &small));
  t_must("vec", sessile_vec_create(la, 17 * 17 * 13, &big));
  sessile_solve_result res;
  sessile_status s = sessile_mg_solve(mg, NULL, small, big, &res);
  char line[300];
  snprintf(line, sizeof line, "solve with a b of the wrong size: SESSILE_ERR_USAGE (%s)", sessile_error_message());
  t_true(line, s == SESSILE_ERR_USAGE);
  s = sessile_mg_vcycle(mg, big, big);
  snprintf(line, sizeof line, "V-cycle in place: SESSILE_ERR_USAGE (%s)", sessile_error_message());
  t_true(line, s == SESSILE_ERR_USAGE);
  /* A zero right-hand side: x = 0 whatever it held. */
  t_must("fill", sessile_vec_fill(la, 0, small));
  sessile_vec_destroy(small);
  small = NULL;
  t_must("vec", sessile_vec_create(la, 17 * 17 * 13, &small));
  t_must("fill", sessile_vec_fill(la, 3, big));
  t_must("mg_solve", sessile_mg_solve(mg, NULL, small, big, &res));
  double xn;
  t_must("nrm2", sessile_vec_nrm2(la, big, &xn));
  t_true("zero right-hand side: converged, 0 iterations, x = 0",
         res.status == SESSILE_SOLVE_CONVERGED && res.iterations == 0 && xn == 0);
  sessile_vec_destroy(small);
  sessile_vec_destroy(big);
  sessile_mg_destroy(mg);
  destroy(&p);
}

int main(int argc, char **argv) {
  int large = 0, precision = 0;
  for (int i = 1; i < argc; i++) {
    if (strcmp(argv[i], "--large") == 0) large = 1;
    else if (strcmp(argv[i], "--fp32") == 0) precision = 32;
  }
  sessile_gpu *g = t_gpu(precision);
  fp64 = sessile_gpu_info_of(g)->precision == 64;
  t_must("la_create", sessile_la_create(g, &la));
  if (large) check_grid(129, 129, 97);
  else {
    check_grid(33, 33, 25);
    if (fp64) {
      check_grid(65, 65, 49);
      check_errors();
    }
  }
  sessile_la_destroy(la);
  return t_finish(g);
}
