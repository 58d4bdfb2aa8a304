/* Error paths and diagnostics of the solvers (each check fails without its fix):
 *  - a failure inside an OpenMP worker of the Navier-Stokes solver (a
 *    singular diagonal block in the block-Jacobi scaling, at a node that no
 *    tet uses, placed last so a second thread owns it) reaches the caller
 *    with its message: the message is thread-local, so it must be set on the
 *    calling thread, not in the worker;
 *  - the library prints nothing: a fluid solve and a Krylov solve without a
 *    monitor write no byte to stderr; with a monitor, their progress lines go
 *    to the callback;
 *  - a refused sessile_advdiff_set_source (a non-finite value) leaves the
 *    source in force before the call: none on a fresh object (the heap is
 *    dirtied first, so a source left uninitialised would show), the old one
 *    otherwise; solves then assemble exactly the right-hand side of an
 *    object given that source directly. */
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "sessile/fem/advdiff.h"
#include "sessile/fem/fluid.h"
#include "testutil.h"

static sessile_gpu *gpu;
static sessile_la *la;

/* Lines received by a monitor. */
typedef struct { int n; char last[256]; } lines;
static void collect(void *user, const char *line) {
  lines *l = user;
  l->n++;
  snprintf(l->last, sizeof l->last, "%s", line);
}

/* stderr into a temporary file while `run` runs; returns the bytes written. */
static long stderr_bytes_during(void (*run)(void *), void *ctx) {
  fflush(stderr);
  char path[] = "/tmp/sessile-stderr-XXXXXX";
  int fd = mkstemp(path);
  if (fd < 0) return -1;
  int saved = dup(2);
  dup2(fd, 2);
  run(ctx);
  fflush(stderr);
  dup2(saved, 2);
  close(saved);
  long n = (long)lseek(fd, 0, SEEK_END);
  close(fd);
  unlink(path);
  return n;
}

static sessile_box small_box(uint32_t cells, double h) {
  sessile_box b = {{0, 0, 0}, h, {cells + 1, cells + 1, cells + 1}};
  return b;
}

/* ---- the fluid ------------------------------------------------------------- */
typedef struct {
  sessile_fluid *fl;
  sessile_fluid_params p;
  double *up;
  sessile_fluid_result res;
  sessile_status st;
} fluid_run;
static void run_fluid(void *c) {
  fluid_run *r = c;
  r->st = sessile_fluid_solve(r->fl, NULL, &r->p, r->up, &r->res);
}

static void test_fluid(void) {
  sessile_box b = small_box(4, 0.5);
  sessile_tetmesh m = {0};
  t_must("tetmesh", sessile_tetmesh_from_box(&b, &m));
  uint32_t n = m.nnodes;

  /* The same mesh with one more node that no tet uses: its block row is
   * empty, so block-Jacobi finds no diagonal block there. */
  sessile_tetmesh mo = m;
  mo.nnodes = n + 1;
  mo.xyz = t_dalloc(3 * (size_t)(n + 1));
  mo.node_tags = t_xalloc((size_t)(n + 1) * sizeof *mo.node_tags);
  memcpy(mo.xyz, m.xyz, 3 * (size_t)n * sizeof *mo.xyz);
  memcpy(mo.node_tags, m.node_tags, (size_t)n * sizeof *mo.node_tags);
  for (int k = 0; k < 3; k++) mo.xyz[3 * (size_t)n + k] = 0.25;
  sessile_fluid *fl = NULL;
  t_must("fluid create (orphan node)", sessile_fluid_create(la, &mo, &fl));
  fluid_run r = {.fl = fl};
  sessile_fluid_params_default(&r.p);
  r.p.pc = SESSILE_PC_BLOCK_JACOBI;
  r.p.newton_max = 3;
  r.up = t_dalloc(4 * (size_t)(n + 1));
  omp_set_dynamic(0);
  omp_set_num_threads(2); /* node n lies in the second thread's static share */
  sessile_error_clear();
  run_fluid(&r);
  char want[96];
  snprintf(want, sizeof want, "singular diagonal block at block row %u", n);
  printf("  orphan node, 2 threads: %s: %s\n", sessile_status_name(r.st), sessile_error_message());
  t_true("worker failure: SESSILE_ERR_NUMERIC", r.st == SESSILE_ERR_NUMERIC);
  t_true("worker failure: its message reaches the calling thread", strstr(sessile_error_message(), want) != NULL);
  free(r.up);
  sessile_fluid_destroy(fl);
  free(mo.xyz);
  free(mo.node_tags);

  /* Silence without a monitor, lines with one. */
  t_must("fluid create", sessile_fluid_create(la, &m, &fl));
  fluid_run q = {.fl = fl};
  sessile_fluid_params_default(&q.p);
  q.p.newton_max = 2;
  q.up = t_dalloc(4 * (size_t)n);
  long bytes = stderr_bytes_during(run_fluid, &q);
  t_ok("fluid solve without a monitor", q.st);
  t_check("fluid solve without a monitor: bytes written to stderr", (double)bytes, 0);
  lines got = {0};
  q.p.monitor = collect;
  q.p.monitor_user = &got;
  q.p.check_linear = 1;
  memset(q.up, 0, 4 * (size_t)n * sizeof *q.up);
  bytes = stderr_bytes_during(run_fluid, &q);
  t_ok("fluid solve with a monitor", q.st);
  printf("  fluid monitor: %d lines, last \"%s\"\n", got.n, got.last);
  t_check("fluid solve with a monitor: bytes written to stderr", (double)bytes, 0);
  t_true("fluid monitor: a line per step and the outcome",
         got.n >= 2 && strncmp(got.last, "fluid: ", 7) == 0);
  /* The time bound: a solve past max_seconds fails with a message that
   * names the bound (a hopeless setting must not run for hours). */
  sessile_fluid_params_default(&q.p);
  q.p.max_seconds = 1e-9;
  memset(q.up, 0, 4 * (size_t)n * sizeof *q.up);
  sessile_error_clear();
  run_fluid(&q);
  printf("  time bound: %s: %s\n", sessile_status_name(q.st), sessile_error_message());
  t_true("a solve past max_seconds fails (SESSILE_ERR_NUMERIC, names the bound)",
         q.st == SESSILE_ERR_NUMERIC && strstr(sessile_error_message(), "time bound") != NULL);
  free(q.up);
  sessile_fluid_destroy(fl);
  sessile_tetmesh_free(&m);
}

/* ---- a Krylov solve --------------------------------------------------------- */
typedef struct {
  sessile_ksp_options o;
  sessile_mat *a;
  sessile_vec *b, *x;
  sessile_solve_result res;
  sessile_status st;
} ksp_run;
static void run_ksp(void *c) {
  ksp_run *r = c;
  r->st = sessile_vec_fill(la, 0.0, r->x);
  if (r->st == SESSILE_OK) r->st = sessile_ksp_solve(la, &r->o, r->a, r->b, r->x, &r->res);
}

static void test_ksp(void) {
  sessile_csr a = {0};
  t_must("laplacian", sessile_csr_laplacian7(6, 6, 6, &a));
  ksp_run r = {0};
  t_must("matrix", sessile_mat_create_csr(la, &a, &r.a));
  t_must("b", sessile_vec_create(la, a.nrows, &r.b));
  t_must("x", sessile_vec_create(la, a.nrows, &r.x));
  t_must("b = 1", sessile_vec_fill(la, 1.0, r.b));
  for (int k = 0; k < 3; k++) {
    static const sessile_ksp_type types[3] = {SESSILE_KSP_CG, SESSILE_KSP_BICGSTAB, SESSILE_KSP_GMRES};
    sessile_ksp_options_default(&r.o);
    r.o.type = types[k];
    r.o.check_every = 1;
    long bytes = stderr_bytes_during(run_ksp, &r);
    char what[128];
    snprintf(what, sizeof what, "%s without a monitor: bytes written to stderr", sessile_ksp_type_name(types[k]));
    t_ok(what, r.st);
    t_check(what, (double)bytes, 0);
    lines got = {0};
    r.o.monitor = collect;
    r.o.monitor_user = &got;
    bytes = stderr_bytes_during(run_ksp, &r);
    snprintf(what, sizeof what, "%s with a monitor: iteration lines and the outcome, nothing on stderr",
             sessile_ksp_type_name(types[k]));
    printf("  %s monitor: %d lines, last \"%s\"\n", sessile_ksp_type_name(types[k]), got.n, got.last);
    t_true(what, r.st == SESSILE_OK && bytes == 0 && got.n >= 2 && strstr(got.last, "true relative residual"));
  }
  sessile_vec_destroy(r.b);
  sessile_vec_destroy(r.x);
  sessile_mat_destroy(r.a);
  sessile_csr_free(&a);
}

/* ---- advection-diffusion source -------------------------------------------- */
/* Solves the Laplace problem with the nutrient's walls on ad; returns a copy
 * of the assembled right-hand side. */
static double *solve_rhs(sessile_advdiff *ad, const sessile_tetmesh *m) {
  uint32_t n = m->nnodes;
  uint8_t *mask = t_xalloc(n);
  double *g = t_dalloc(n), *c = t_dalloc(n), *rhs = t_dalloc(n);
  sessile_advdiff_nutrient_bc(m, NULL, mask, g);
  sessile_solve_result res;
  t_ok("advdiff solve", sessile_advdiff_solve(ad, NULL, 1e-3, mask, g, NULL, c, &res));
  memcpy(rhs, sessile_advdiff_rhs(ad), (size_t)n * sizeof *rhs);
  free(mask), free(g), free(c);
  return rhs;
}

static double max_diff(const double *a, const double *b, uint32_t n) {
  double d = 0;
  for (uint32_t i = 0; i < n; i++) d = fmax(d, fabs(a[i] - b[i]));
  if (!(d == d)) d = INFINITY;
  return d;
}

static void test_advdiff_source(void) {
  sessile_box b = small_box(4, 0.5);
  sessile_tetmesh m = {0};
  t_must("tetmesh", sessile_tetmesh_from_box(&b, &m));
  uint32_t n = m.nnodes;
  double *bad = t_dalloc(n), *f1 = t_dalloc(n);
  for (uint32_t i = 0; i < n; i++) bad[i] = 1.0, f1[i] = 0.5 + 0.01 * i;
  bad[n / 2] = NAN;

  /* The references: no source, and f1 set directly. */
  sessile_advdiff *ref = NULL, *ad = NULL;
  t_must("advdiff create", sessile_advdiff_create(la, &m, &ref));
  double *rhs_none = solve_rhs(ref, &m);
  t_ok("set_source f1", sessile_advdiff_set_source(ref, f1));
  double *rhs_f1 = solve_rhs(ref, &m);
  t_true("the source changes the right-hand side", max_diff(rhs_none, rhs_f1, n) > 0);

  /* A fresh object refuses a non-finite source: it must keep "no source".
   * A heap block of the source's size, filled with 1.0 and freed just
   * before, is what malloc would hand back to an uninitialised copy. */
  t_must("advdiff create", sessile_advdiff_create(la, &m, &ad));
  double *junk = malloc((size_t)n * sizeof *junk);
  if (junk) {
    for (uint32_t i = 0; i < n; i++) junk[i] = 1.0;
    free(junk);
  }
  sessile_status st = sessile_advdiff_set_source(ad, bad);
  printf("  non-finite source: %s: %s\n", sessile_status_name(st), sessile_error_message());
  t_true("non-finite source refused with SESSILE_ERR_NUMERIC", st == SESSILE_ERR_NUMERIC);
  double *rhs = solve_rhs(ad, &m);
  t_check("refused first source: right-hand side as with no source (max |diff|)", max_diff(rhs, rhs_none, n), 0);
  free(rhs);
  /* A refused source after a good one keeps the good one. */
  t_ok("set_source f1", sessile_advdiff_set_source(ad, f1));
  st = sessile_advdiff_set_source(ad, bad);
  t_true("non-finite source refused again", st == SESSILE_ERR_NUMERIC);
  rhs = solve_rhs(ad, &m);
  t_check("refused later source: right-hand side as with f1 (max |diff|)", max_diff(rhs, rhs_f1, n), 0);
  free(rhs);
  t_ok("set_source NULL", sessile_advdiff_set_source(ad, NULL));
  rhs = solve_rhs(ad, &m);
  t_check("source removed: right-hand side as with no source (max |diff|)", max_diff(rhs, rhs_none, n), 0);
  free(rhs);

  sessile_advdiff_destroy(ad);
  sessile_advdiff_destroy(ref);
  free(rhs_none), free(rhs_f1), free(bad), free(f1);
  sessile_tetmesh_free(&m);
}

int main(void) {
  setvbuf(stdout, NULL, _IOLBF, 0);
  gpu = t_gpu(0);
  t_must("la", sessile_la_create(gpu, &la));
  printf("== Navier-Stokes: worker failure, monitor\n");
  test_fluid();
  printf("== Krylov monitor\n");
  test_ksp();
  printf("== advection-diffusion source after a refused set_source\n");
  test_advdiff_source();
  sessile_la_destroy(la);
  return t_finish(gpu);
}
