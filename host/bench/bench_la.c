/* `sessile bench la`: every la kernel and solver on the device against its
 * plain-C reference (OpenMP on all cores) measured in the same run.
 * GPU kernel times come from timestamps around `repeat` back-to-back
 * dispatches in one submit (lavapipe's ~11 µs dispatch cost included); C
 * times are wall-clock means.  GB/s counts the minimum traffic: each vector
 * and matrix array once, x of SpMV once (docs/performance.md). */
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>
#include "bench_internal.h"
#include "sessile/bench/bench.h"
#include "sessile/la/la_ref.h"

typedef struct {
  sessile_la *la;
  sessile_cmd *cmd;
  unsigned rep;
  FILE *out;
} bench;

static void row(bench *b, const char *name, double gpu_s, double ref_s, double flops, double bytes) {
  fprintf(b->out, "%-30s %10.3f %10.3f %8.2f %8.2f %8.2f\n", name, gpu_s * 1e3, ref_s * 1e3,
          flops / gpu_s * 1e-9, bytes / gpu_s * 1e-9, ref_s / gpu_s);
}

/* Times `rep` recordings of one operation with GPU timestamps. */
typedef sessile_status (*rec_fn)(bench *b, void *ctx);
static sessile_status time_gpu(bench *b, rec_fn f, void *ctx, double *seconds) {
  SESSILE_CALL(sessile_cmd_begin(b->cmd));
  SESSILE_CALL(f(b, ctx)); /* warm-up dispatch inside the same submit */
  SESSILE_CALL(sessile_cmd_timestamp(b->cmd, 0));
  for (unsigned r = 0; r < b->rep; r++) SESSILE_CALL(f(b, ctx));
  SESSILE_CALL(sessile_cmd_timestamp(b->cmd, 1));
  SESSILE_CALL(sessile_cmd_end(b->cmd));
  double t0 = sessile_wall_seconds();
  SESSILE_CALL(sessile_cmd_submit_wait(b->cmd));
  double wall = sessile_wall_seconds() - t0, ns;
  if (sessile_cmd_elapsed_ns(b->cmd, 0, 1, &ns) == SESSILE_OK) *seconds = ns * 1e-9 / b->rep;
  else *seconds = wall / (b->rep + 1); /* no timestamps on this device */
  sessile_error_clear();
  return SESSILE_OK;
}

typedef struct { la_kernel_id id; uint32_t n; sessile_vec *x, *y, *w; int dot; } vec_ctx;
static sessile_status rec_vec_op(bench *b, void *p) {
  vec_ctx *c = p;
  if (c->dot) {
    uint32_t cnt;
    SESSILE_CALL(rec_dot(b->la, b->cmd, c->n, vref_of(c->x), vref_of(c->y), 0, -1, &cnt));
    return rec_reduce(b->la, b->cmd, cnt, 0, 1, S_IMM + 1, c->dot == 2, -1);
  }
  vref none = {0};
  return rec_vec(b->la, b->cmd, c->id, c->n, vref_of(c->x), c->y ? vref_of(c->y) : none,
                 c->w ? vref_of(c->w) : none, S_IMM, 0, -1);
}

typedef struct { const sessile_mat *a; sessile_vec *x, *y; } spmv_ctx;
static sessile_status rec_spmv_op(bench *b, void *p) {
  spmv_ctx *c = p;
  return rec_spmv(b->la, b->cmd, c->a, vref_of(c->x), vref_of(c->y), -1);
}

static double ref_time(void (*f)(void *), void *ctx, unsigned rep) {
  f(ctx); /* warm caches and threads */
  double t0 = sessile_wall_seconds();
  for (unsigned r = 0; r < rep; r++) f(ctx);
  return (sessile_wall_seconds() - t0) / rep;
}

typedef struct { int op; uint64_t n; double *x, *y, *w; double sink; } ref_vec_ctx;
static void ref_vec_op(void *p) {
  ref_vec_ctx *c = p;
  switch (c->op) {
  case 0: sessile_ref_fill(c->n, 0.5, c->y); break;
  case 1: sessile_ref_copy(c->n, c->x, c->y); break;
  case 2: sessile_ref_scale(c->n, 1.0000001, c->y); break;
  case 3: sessile_ref_axpy(c->n, 1e-7, c->x, c->y); break;
  case 4: sessile_ref_aypx(c->n, 0.5, c->x, c->y); break;
  case 5: sessile_ref_waxpy(c->n, 0.5, c->x, c->y, c->w); break;
  case 6: sessile_ref_pmul(c->n, c->x, c->y, c->w); break;
  case 7: c->sink += sessile_ref_dot(c->n, c->x, c->y); break;
  default: c->sink += sessile_ref_nrm2(c->n, c->x); break;
  }
}

typedef struct { const sessile_csr *a; const sessile_bcsr4 *bb; double *x, *y; } ref_spmv_ctx;
static void ref_spmv_op(void *p) {
  ref_spmv_ctx *c = p;
  if (c->a) sessile_ref_spmv_csr(c->a, c->x, c->y);
  else sessile_ref_spmv_bcsr4(c->bb, c->x, c->y);
}

static sessile_status bench_vectors(bench *b, uint32_t n) {
  static const struct { const char *name; la_kernel_id id; int nvec, dot; double fl, rw; } ops[] = {
      {"fill", K_FILL, 1, 0, 0, 1},   {"copy", K_COPY, 2, 0, 0, 2},
      {"scale", K_SCALE, 1, 0, 1, 2}, {"axpy", K_AXPY, 2, 0, 2, 3},
      {"aypx", K_AYPX, 2, 0, 2, 3},   {"waxpy", K_WAXPY, 3, 0, 2, 3},
      {"pmul", K_PMUL, 3, 0, 1, 3},   {"dot", K_DOT, 2, 1, 2, 2},
      {"nrm2", K_DOT, 1, 2, 2, 1}};
  sessile_vec *v[3] = {0};
  double *h = malloc((size_t)n * 3 * sizeof *h);
  sessile_status s = h ? SESSILE_OK : sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  for (int i = 0; s == SESSILE_OK && i < 3; i++) {
    sessile_fill_random(h + (size_t)i * n, n, 0.5, 1.0, 11 + i);
    s = sessile_vec_create(b->la, n, &v[i]);
    if (s == SESSILE_OK) s = sessile_vec_upload(v[i], h + (size_t)i * n);
  }
  if (s == SESSILE_OK) la_scalar_set(b->la, S_IMM, 1.0);
  double rb = b->la->real_bytes;
  for (size_t k = 0; s == SESSILE_OK && k < sizeof ops / sizeof ops[0]; k++) {
    char name[64];
    snprintf(name, sizeof name, "%s (n=%u)", ops[k].name, n);
    vec_ctx c = {ops[k].id, n, v[0], ops[k].nvec > 1 ? v[1] : ops[k].dot == 2 ? v[0] : NULL,
                 ops[k].nvec > 2 ? v[2] : NULL, ops[k].dot};
    if (ops[k].id == K_FILL || ops[k].id == K_SCALE) c.x = v[1];
    double tg;
    s = time_gpu(b, rec_vec_op, &c, &tg);
    if (s != SESSILE_OK) break; /* the vectors and h are freed below */
    ref_vec_ctx rc = {(int)k, n, h, h + n, h + 2 * (size_t)n, 0};
    double tr = ref_time(ref_vec_op, &rc, b->rep);
    row(b, name, tg, tr, ops[k].fl * n, ops[k].rw * rb * n);
  }
  for (int i = 0; i < 3; i++) sessile_vec_destroy(v[i]);
  free(h);
  return s;
}

static sessile_status bench_spmv(bench *b, const char *name, const sessile_csr *a,
                                 const sessile_bcsr4 *bb) {
  sessile_mat *m = NULL;
  sessile_vec *x = NULL, *y = NULL;
  uint32_t n = a ? a->nrows : bb->nbrows * 4;
  double nnz = a ? (double)a->nnz : 16.0 * (double)bb->nnzb;
  double *hx = malloc((size_t)n * 2 * sizeof *hx);
  SESSILE_CHECK(hx, SESSILE_ERR_NO_MEMORY, "out of host memory");
  sessile_fill_random(hx, n, -1, 1, 5);
  sessile_status s = a ? sessile_mat_create_csr(b->la, a, &m) : sessile_mat_create_bcsr4(b->la, bb, &m);
  if (s == SESSILE_OK) s = sessile_vec_create(b->la, n, &x);
  if (s == SESSILE_OK) s = sessile_vec_create(b->la, n, &y);
  if (s == SESSILE_OK) s = sessile_vec_upload(x, hx);
  double tg = 0;
  spmv_ctx c = {m, x, y};
  if (s == SESSILE_OK) s = time_gpu(b, rec_spmv_op, &c, &tg);
  if (s == SESSILE_OK) {
    ref_spmv_ctx rc = {a, bb, hx, hx + n};
    double tr = ref_time(ref_spmv_op, &rc, b->rep);
    double rb = b->la->real_bytes;
    double idx = a ? 4.0 * nnz : 4.0 * (double)bb->nnzb;
    row(b, name, tg, tr, 2 * nnz, nnz * rb + idx + 2.0 * n * rb + 4.0 * n);
    if (m->kind == MAT_CSR && m->texel) {
      /* The storage-buffer kernel on the same matrix, for comparison. */
      char alt[80];
      snprintf(alt, sizeof alt, "%s (ssbo)", name);
      m->texel = 0;
      s = time_gpu(b, rec_spmv_op, &c, &tg);
      m->texel = 1;
      if (s == SESSILE_OK) row(b, alt, tg, tr, 2 * nnz, nnz * rb + idx + 2.0 * n * rb + 4.0 * n);
    }
  }
  sessile_vec_destroy(x);
  sessile_vec_destroy(y);
  sessile_mat_destroy(m);
  free(hx);
  return s;
}

/* The cut-cell operator on the sphere problem (sessile_cut_sphere) on N^3,
 * through texel and storage buffers.  Traffic: x, diag, mask, y once. */
typedef struct { uint32_t n[3]; double h; const uint32_t *mask; const double *diag; double *x, *y; } ref_cut_ctx;
static void ref_cut_op(void *p) {
  ref_cut_ctx *c = p;
  sessile_ref_stencil7_cut(c->n[0], c->n[1], c->n[2], c->h, c->mask, c->diag, c->x, c->y);
}

static sessile_status bench_cut(bench *b, uint32_t N) {
  uint32_t n = N * N * N;
  double h = 1.0 / (N - 1), centre[3] = {0.45, 0.5, 0.4};
  double *hd = malloc((size_t)n * 3 * sizeof *hd);
  uint32_t *mask = malloc((size_t)n * sizeof *mask);
  sessile_status s = hd && mask ? SESSILE_OK : sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  sessile_buffer *mb = NULL;
  sessile_vec *d = NULL, *x = NULL, *y = NULL;
  sessile_mat *m = NULL;
  if (s == SESSILE_OK) {
    sessile_cut_sphere(N, N, N, h, centre, 0.3, mask, hd, NULL);
    sessile_fill_random(hd + n, n, -1, 1, 5);
    s = sessile_buffer_create(b->la->gpu, (size_t)n * 4, SESSILE_BUFFER_DEVICE, &mb);
  }
  if (s == SESSILE_OK) s = sessile_buffer_upload(mb, 0, mask, (size_t)n * 4);
  if (s == SESSILE_OK) s = sessile_vec_create(b->la, n, &d);
  if (s == SESSILE_OK) s = sessile_vec_create(b->la, n, &x);
  if (s == SESSILE_OK) s = sessile_vec_create(b->la, n, &y);
  if (s == SESSILE_OK) s = sessile_vec_upload(d, hd);
  if (s == SESSILE_OK) s = sessile_vec_upload(x, hd + n);
  if (s == SESSILE_OK) s = sessile_mat_create_stencil7_cut(b->la, N, N, N, h, mb, d, &m);
  double tg = 0, rb = b->la->real_bytes, by = n * (3 * rb + 4), fl = 13.0 * n;
  spmv_ctx c = {m, x, y};
  ref_cut_ctx rc = {{N, N, N}, h, mask, hd, hd + n, hd + 2 * (size_t)n};
  char name[64];
  for (int storage = 0; s == SESSILE_OK && storage < 2; storage++) {
    int tex = m->cut_texel;
    if (storage) m->cut_texel = 0;
    s = time_gpu(b, rec_spmv_op, &c, &tg);
    m->cut_texel = tex;
    snprintf(name, sizeof name, "stencil7 cut %u^3%s", N, storage ? " (ssbo)" : "");
    if (s == SESSILE_OK) row(b, name, tg, ref_time(ref_cut_op, &rc, b->rep), fl, by);
  }
  sessile_mat_destroy(m);
  sessile_vec_destroy(d);
  sessile_vec_destroy(x);
  sessile_vec_destroy(y);
  sessile_buffer_destroy(mb);
  free(hd);
  free(mask);
  return s;
}

static sessile_status bench_solve(bench *b, const char *name, const sessile_csr *a,
                                  sessile_ksp_type type) {
  uint32_t n = a->nrows;
  double *h = malloc((size_t)n * 3 * sizeof *h);
  SESSILE_CHECK(h, SESSILE_ERR_NO_MEMORY, "out of host memory");
  double *hb = h, *hx = h + n, *dinv = h + 2 * (size_t)n;
  sessile_fill_random(hb, n, -1, 1, 3);
  sessile_mat *m = NULL;
  sessile_vec *vb = NULL, *vx = NULL;
  sessile_status s = sessile_mat_create_csr(b->la, a, &m);
  if (s == SESSILE_OK) s = sessile_vec_create(b->la, n, &vb);
  if (s == SESSILE_OK) s = sessile_vec_create(b->la, n, &vx);
  if (s == SESSILE_OK) s = sessile_vec_upload(vb, hb);
  if (s == SESSILE_OK) s = sessile_ref_jacobi_csr(a, dinv);
  sessile_ksp_options o;
  sessile_ksp_options_default(&o);
  o.type = type;
  o.max_it = 5000;
  sessile_solve_result r = {0};
  if (s == SESSILE_OK) s = sessile_ksp_solve(b->la, &o, m, vb, vx, &r);
  if (s == SESSILE_OK) {
    memset(hx, 0, (size_t)n * sizeof *hx);
    double t0 = sessile_wall_seconds();
    sessile_ref_result rr = type == SESSILE_KSP_CG ? sessile_ref_pcg(a, dinv, hb, hx, o.rtol, o.max_it)
                          : type == SESSILE_KSP_BICGSTAB
                              ? sessile_ref_bicgstab(a, dinv, hb, hx, o.rtol, o.max_it)
                              : sessile_ref_gmres(a, dinv, hb, hx, o.rtol, o.max_it, o.restart);
    double tr = sessile_wall_seconds() - t0;
    /* Model: per iteration one SpMV plus ~12 vector passes (CG/BiCGSTAB x2). */
    double rb = b->la->real_bytes, spmvs = type == SESSILE_KSP_BICGSTAB ? 2 : 1;
    double fl = r.iterations * spmvs * (2.0 * (double)a->nnz + 12.0 * n);
    double by = r.iterations * spmvs * ((double)a->nnz * (rb + 4) + 12.0 * n * rb);
    row(b, name, r.seconds, tr, fl, by);
    fprintf(b->out, "    gpu: %s, %d iterations, true relres %.2e; C: %d iterations, true relres %.2e\n",
            sessile_solve_status_name(r.status), r.iterations, r.true_relres, rr.iterations,
            rr.true_relres);
  }
  sessile_vec_destroy(vb);
  sessile_vec_destroy(vx);
  sessile_mat_destroy(m);
  free(h);
  return s;
}

/* ILU(0) against Jacobi, both on the device (the C reference solvers have no
 * ILU): solve times exclude the one-off factorisation, printed beside them. */
static sessile_status bench_ilu(bench *b, const char *name, const sessile_csr *a,
                                sessile_ksp_type type) {
  uint32_t n = a->nrows;
  double *hb = malloc((size_t)n * sizeof *hb);
  SESSILE_CHECK(hb, SESSILE_ERR_NO_MEMORY, "out of host memory");
  sessile_fill_random(hb, n, -1, 1, 3);
  sessile_mat *m = NULL;
  sessile_vec *vb = NULL, *vx = NULL;
  sessile_status s = sessile_mat_create_csr(b->la, a, &m);
  if (s == SESSILE_OK) s = sessile_vec_create(b->la, n, &vb);
  if (s == SESSILE_OK) s = sessile_vec_create(b->la, n, &vx);
  if (s == SESSILE_OK) s = sessile_vec_upload(vb, hb);
  sessile_ilu0_info info = {0};
  if (s == SESSILE_OK) s = sessile_mat_ilu0(b->la, m, &info);
  sessile_ksp_options o;
  sessile_ksp_options_default(&o);
  o.type = type;
  o.max_it = 5000;
  sessile_solve_result rj = {0}, ri = {0};
  o.pc = SESSILE_PC_JACOBI;
  if (s == SESSILE_OK) s = sessile_ksp_solve(b->la, &o, m, vb, vx, &rj);
  o.pc = SESSILE_PC_ILU0;
  if (s == SESSILE_OK) s = sessile_vec_fill(b->la, 0.0, vx);
  if (s == SESSILE_OK) s = sessile_ksp_solve(b->la, &o, m, vb, vx, &ri);
  if (s == SESSILE_OK) {
    fprintf(b->out, "%-30s %10.3f %10.3f %8s %8s %8.2f\n", name, ri.seconds * 1e3, rj.seconds * 1e3,
            "", "", rj.seconds / ri.seconds);
    fprintf(b->out, "    ilu0: %s, %d iterations, true relres %.2e; jacobi: %s, %d iterations, "
            "true relres %.2e; factorisation %.1f ms, %u + %u levels\n",
            sessile_solve_status_name(ri.status), ri.iterations, ri.true_relres,
            sessile_solve_status_name(rj.status), rj.iterations, rj.true_relres,
            info.seconds * 1e3, info.levels_lower, info.levels_upper);
  }
  sessile_vec_destroy(vb);
  sessile_vec_destroy(vx);
  sessile_mat_destroy(m);
  free(hb);
  return s;
}

/* The machine's load averages (1, 5, 15 min) from /proc/loadavg, for the
 * record: the timings here are only comparable at similar load. */
static void print_load(FILE *out, const char *when) {
  double l[3];
  if (sessile_load_average(l))
    fprintf(out, "load average %s: %.2f %.2f %.2f (1, 5, 15 min)\n", when, l[0], l[1], l[2]);
  else fprintf(out, "load average %s: unavailable\n", when);
}

static sessile_status run(bench *b, const sessile_bench_la_options *o) {
  uint32_t N = o->size, n = N * N * N;
  const sessile_gpu_info *gi = sessile_gpu_info_of(b->la->gpu);
  fprintf(b->out, "sessile bench la: device %s (%s), driver %s, fp%d; C reference on %d threads\n",
          gi->name, gi->type, gi->driver, gi->precision, omp_get_max_threads());
  fprintf(b->out, "grid %u^3, %u repetitions per kernel\n", N, o->repeat);
  char cpu[256];
  fprintf(b->out, "machine: %s\n", sessile_cpu_describe(cpu, sizeof cpu));
  print_load(b->out, "at start");
  fprintf(b->out, "\n");
  fprintf(b->out, "%-30s %10s %10s %8s %8s %8s\n", "kernel", "gpu ms", "C ms", "GFLOP/s",
          "GB/s", "C/gpu");
  SESSILE_CALL(bench_vectors(b, n));
  sessile_csr a = {0}, p = {0}, cd = {0};
  sessile_bcsr4 bb = {0};
  char name[64];
  sessile_status s = sessile_csr_laplacian7(N, N, N, &a);
  if (s == SESSILE_OK) s = sessile_csr_p1tet(N, N, N, 1.0, 1.0, 1.0, &p);
  snprintf(name, sizeof name, "spmv csr 7-point %u^3", N);
  if (s == SESSILE_OK) s = bench_spmv(b, name, &a, NULL);
  snprintf(name, sizeof name, "spmv csr P1-tet %u^3", N);
  if (s == SESSILE_OK) s = bench_spmv(b, name, &p, NULL);
  sessile_csr pb = {0};
  uint32_t Nb = N / 2 > 1 ? N / 2 : 2;
  if (s == SESSILE_OK) s = sessile_csr_p1tet(Nb, Nb, Nb, 1.0, 1.0, 1.0, &pb);
  if (s == SESSILE_OK) s = sessile_bcsr4_random_on(&pb, 9, &bb);
  snprintf(name, sizeof name, "spmv bcsr4 P1-tet %u^3", Nb);
  if (s == SESSILE_OK) s = bench_spmv(b, name, NULL, &bb);
  if (s == SESSILE_OK) s = bench_cut(b, N);
  if (s == SESSILE_OK && o->solvers) {
    fprintf(b->out, "\n%-30s %10s %10s %8s %8s %8s   (rtol 1e-6, Jacobi)\n", "solve", "gpu ms",
            "C ms", "GFLOP/s", "GB/s", "C/gpu");
    snprintf(name, sizeof name, "pcg 7-point %u^3", N);
    s = bench_solve(b, name, &a, SESSILE_KSP_CG);
    if (s == SESSILE_OK) s = sessile_csr_convdiff(Nb, Nb, Nb, 2.0, &cd);
    snprintf(name, sizeof name, "bicgstab conv-diff Pe=2 %u^3", Nb);
    if (s == SESSILE_OK) s = bench_solve(b, name, &cd, SESSILE_KSP_BICGSTAB);
    snprintf(name, sizeof name, "gmres(30) conv-diff Pe=2 %u^3", Nb);
    if (s == SESSILE_OK) s = bench_solve(b, name, &cd, SESSILE_KSP_GMRES);
    if (s == SESSILE_OK)
      fprintf(b->out, "\n%-30s %10s %10s %8s %8s %8s   (rtol 1e-6, both on the device)\n",
              "solve", "ilu0 ms", "jacobi ms", "", "", "jac/ilu");
    for (int k = 0; s == SESSILE_OK && k < 2; k++) {
      double pe = k ? 10.0 : 2.0;
      sessile_csr_free(&cd);
      s = sessile_csr_convdiff(Nb, Nb, Nb, pe, &cd);
      snprintf(name, sizeof name, "bicgstab+ilu0 cd Pe=%g %u^3", pe, Nb);
      if (s == SESSILE_OK) s = bench_ilu(b, name, &cd, SESSILE_KSP_BICGSTAB);
      snprintf(name, sizeof name, "gmres(30)+ilu0 cd Pe=%g %u^3", pe, Nb);
      if (s == SESSILE_OK) s = bench_ilu(b, name, &cd, SESSILE_KSP_GMRES);
    }
    if (s == SESSILE_OK && o->mg_sizes) s = la_bench_mg(b->la, o->mg_sizes, b->out);
  }
  fprintf(b->out, "\nC/gpu > 1: the device is faster than the C reference.\n");
  print_load(b->out, "at end");
  sessile_csr_free(&a);
  sessile_csr_free(&p);
  sessile_csr_free(&pb);
  sessile_csr_free(&cd);
  sessile_bcsr4_free(&bb);
  return s;
}

sessile_status sessile_bench_la(sessile_gpu *g, const sessile_bench_la_options *o, FILE *out) {
  SESSILE_CHECK(o->size >= 2 && o->size <= 400, SESSILE_ERR_USAGE, "--size must be in 2..400, got %u", o->size);
  SESSILE_CHECK(o->repeat >= 1 && o->repeat <= 10000, SESSILE_ERR_USAGE,
                "--repeat must be in 1..10000, got %u", o->repeat);
  bench b = {.rep = o->repeat, .out = out};
  sessile_status s = sessile_la_create(g, &b.la);
  if (s == SESSILE_OK) s = sessile_cmd_create(g, &b.cmd);
  if (s == SESSILE_OK) s = run(&b, o);
  sessile_cmd_destroy(b.cmd);
  sessile_la_destroy(b.la);
  return s;
}
