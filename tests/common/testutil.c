#include "testutil.h"
#include "cli_gpu_env.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

int t_failed, t_passed;

void t_check(const char *what, double err, double tol) {
  int ok = err <= tol; /* false for NaN */
  printf("%s %-60s error %.3e  tolerance %.1e\n", ok ? "PASS" : "FAIL", what, err, tol);
  if (ok) t_passed++;
  else t_failed++;
}

void t_true(const char *what, int cond) {
  printf("%s %s\n", cond ? "PASS" : "FAIL", what);
  if (cond) t_passed++;
  else t_failed++;
}

void t_ok(const char *what, sessile_status s) {
  if (s == SESSILE_OK) return;
  printf("FAIL %s: %s: %s\n", what, sessile_status_name(s), sessile_error_message());
  t_failed++;
}

sessile_gpu *t_gpu(int precision) {
  sessile_gpu_options o;
  sessile_gpu_options_default(&o);
  o.validation = 1;
  o.precision = precision;
  cli_gpu_env_store st;
  sessile_gpu *g = NULL;
  sessile_status s = cli_gpu_env(&o, &st); /* as the CLI: the library reads no environment */
  if (s == SESSILE_OK) s = sessile_gpu_create(&o, &g);
  if (s != SESSILE_OK) {
    printf("FAIL cannot create the GPU context: %s\n", sessile_error_message());
    exit(1);
  }
  const sessile_gpu_info *i = sessile_gpu_info_of(g);
  printf("device: %s (%s), driver %s, precision fp%d\n", i->name, i->type, i->driver, i->precision);
  /* a test registered at a precision (SESSILE_PRECISION, the _fp32 tests)
   * must run at it, not pass at the default */
  const char *env = getenv("SESSILE_PRECISION");
  int want = precision ? precision : env && *env ? atoi(env) : 0;
  if (want && i->precision != want) {
    printf("FAIL the context runs at fp%d, not the fp%d asked for\n", i->precision, want);
    exit(1);
  }
  /* likewise a test registered at a subgroup size (SESSILE_TEST_SUBGROUP, the
   * _sub4 and _sub16 tests, which ask lavapipe for it through
   * LP_NATIVE_VECTOR_WIDTH) must run at it */
  const char *sub = getenv("SESSILE_TEST_SUBGROUP");
  if (sub && *sub && i->subgroup_size != (uint32_t)atoi(sub)) {
    printf("FAIL the device's subgroups have %u lanes, not the %s asked for\n", i->subgroup_size, sub);
    exit(1);
  }
  if (sub && *sub) printf("subgroup size %u\n", i->subgroup_size);
  return g;
}

sessile_gpu *t_gpu_args(int argc, char **argv, int *fp32) {
  int want32 = 0;
  for (int i = 1; i < argc; i++) {
    if (strcmp(argv[i], "--fp32") == 0) want32 = 1;
    else {
      printf("usage: %s [--fp32]\n", argv[0]);
      exit(2);
    }
  }
  sessile_gpu *g = t_gpu(want32 ? 32 : 0);
  *fp32 = sessile_gpu_info_of(g)->precision == 32;
  if (want32) t_true("--fp32: the context precision is 32", *fp32);
  return g;
}

int t_finish(sessile_gpu *g) {
  uint64_t v = g ? sessile_gpu_validation_count(g) : 0;
  sessile_gpu_destroy(g);
  t_check("validation layer messages", (double)v, 0);
  printf("%d passed, %d failed\n", t_passed, t_failed);
  return t_failed ? 1 : 0;
}

double t_maxdiff(const double *a, const double *b, size_t n) {
  double e = 0;
  for (size_t i = 0; i < n; i++) {
    double d = fabs(a[i] - b[i]);
    if (!(d <= e)) e = d; /* propagates NaN */
  }
  return e;
}

double t_relerr(const double *a, const double *b, size_t n) {
  double num = 0, den = 1e-300;
  for (size_t i = 0; i < n; i++) {
    double d = fabs(a[i] - b[i]);
    if (!(d <= num)) num = d; /* propagates NaN */
    if (fabs(b[i]) > den) den = fabs(b[i]);
  }
  return num / den;
}

void t_must(const char *what, sessile_status s) {
  if (s == SESSILE_OK) return;
  printf("FAIL %s: %s: %s\n", what, sessile_status_name(s), sessile_error_message());
  exit(1);
}

void *t_xalloc(size_t bytes) {
  void *p = calloc(bytes ? bytes : 1, 1);
  if (!p) {
    printf("FAIL out of host memory\n");
    exit(1);
  }
  return p;
}

double *t_dalloc(size_t n) { return t_xalloc(n * sizeof(double)); }
