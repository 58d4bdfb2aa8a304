/* GPU vector kernels (sessile_vec_*) against the plain-C references in
 * la_ref.h, for lengths that hit every tail of the REAL4 padding (1, 3, 4, 5),
 * a few groups (1000), 32^3 and a length that is prime-ish and spans many
 * workgroups (100003).  Also: upload/download round trip, the padding
 * invariant, length-mismatch errors and bitwise determinism of dot/nrm2.
 *
 * Tolerances (the context precision decides):
 *  - fp64, element-wise ops: 1e-15 relative to the largest term (max|ref| for
 *    one-operation kernels, max(|a x_i| + |y_i|) for axpy, aypx and waxpy).
 *    Each output is one or two IEEE operations on the same inputs; the only
 *    legal difference is FMA contraction (one rounding instead of two; GPU
 *    compilers do it, lavapipe does not), i.e. <= 1 ulp of the largest term,
 *    ~2.2e-16 relative to it: relative to a result that cancels it can be
 *    larger (seen on an NVIDIA H100: 1.8e-15 of max|ref| for waxpy at n = 1).
 *  - fp64, dot: 1e-12 relative to sum|x_i y_i| (the classical bound on any
 *    summation order is (n eps) sum|x_i y_i|, 100003 * 1.1e-16 = 1.1e-11 in
 *    the worst case, ~sqrt(n) eps in practice; sum|x y| is used instead of
 *    |x.y| because random vectors give dot products with heavy cancellation).
 *    nrm2 (no cancellation): 1e-12 relative.
 *  - fp32 path: 1e-5 relative everywhere (inputs are rounded to float, 6e-8,
 *    reductions are compensated).
 * The expected values always come from sessile_ref_* or from exact facts. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sessile/la/la_ref.h"
#include "testutil.h"

static sessile_la *la;
static int fp64;

static sessile_vec *vec_from(uint32_t n, const double *v) {
  sessile_vec *x = NULL;
  t_must("vec_create", sessile_vec_create(la, n, &x));
  if (v) t_must("vec_upload", sessile_vec_upload(x, v));
  return x;
}

/* max|gpu - ref| / max|ref| after downloading v. */
static double err_vs(sessile_vec *v, const double *ref, double *tmp) {
  uint32_t n = sessile_vec_size(v);
  t_ok("vec_download", sessile_vec_download(v, tmp));
  return t_relerr(tmp, ref, n);
}

/* max|gpu - ref| / max(|a x_i| + |y_i|): the error of a kernel of two terms
 * relative to the terms, not to a result that may cancel them. */
static double err_terms(sessile_vec *v, const double *ref, double a, const double *x, const double *y, double *tmp) {
  uint32_t n = sessile_vec_size(v);
  t_ok("vec_download", sessile_vec_download(v, tmp));
  double e = 0, m = 0;
  for (uint32_t i = 0; i < n; i++) {
    e = fmax(e, fabs(tmp[i] - ref[i]));
    m = fmax(m, fabs(a * x[i]) + fabs(y[i]));
  }
  return m > 0 ? e / m : e;
}

/* The value the device stores for x (fp32 contexts round to float). */
static double stored(double x) { return fp64 ? x : (double)(float)x; }

static void test_length(uint32_t n) {
  char what[128];
  const double tol = fp64 ? 1e-15 : 1e-5, tol_dot = fp64 ? 1e-12 : 1e-5;
  double *x = t_dalloc(n), *y = t_dalloc(n), *w = t_dalloc(n), *r = t_dalloc(n), *t = t_dalloc(n);
  sessile_fill_random(x, n, -1.0, 1.0, 100 + n);
  sessile_fill_random(y, n, -2.0, 3.0, 200 + n);
  /* Compare with what the device can hold, so fp32 contexts test the
   * kernels and not the rounding of the inputs. */
  for (uint32_t i = 0; i < n; i++) x[i] = stored(x[i]), y[i] = stored(y[i]);
  sessile_vec *vx = vec_from(n, x), *vy = vec_from(n, y), *vw = vec_from(n, NULL);
  printf("-- n = %u\n", n);

  /* Upload/download round trip: bitwise in the stored precision. */
  t_ok("download", sessile_vec_download(vx, t));
  snprintf(what, sizeof what, "n=%u upload/download round trip, bitwise", n);
  t_true(what, memcmp(t, x, (size_t)n * sizeof *t) == 0);
  t_true("vec_size", sessile_vec_size(vx) == n);

  /* fill */
  const double fv = -1.25; /* exact in binary */
  t_ok("fill", sessile_vec_fill(la, fv, vw));
  sessile_ref_fill(n, fv, r);
  snprintf(what, sizeof what, "n=%u fill(-1.25) vs ref_fill", n);
  t_check(what, err_vs(vw, r, t), tol);

  /* copy */
  t_ok("copy", sessile_vec_copy(la, vx, vw));
  sessile_ref_copy(n, x, r);
  snprintf(what, sizeof what, "n=%u copy vs ref_copy", n);
  t_check(what, err_vs(vw, r, t), tol);

  /* scale: w (= x) *= alpha */
  const double alpha = 0.7310941, beta = -1.9402;
  t_ok("scale", sessile_vec_scale(la, alpha, vw));
  sessile_ref_scale(n, stored(alpha), r);
  snprintf(what, sizeof what, "n=%u scale(%.7g) vs ref_scale", n, alpha);
  t_check(what, err_vs(vw, r, t), tol);

  /* axpy: w = y; w += alpha x */
  t_ok("copy", sessile_vec_copy(la, vy, vw));
  t_ok("axpy", sessile_vec_axpy(la, alpha, vx, vw));
  sessile_ref_copy(n, y, r);
  sessile_ref_axpy(n, stored(alpha), x, r);
  snprintf(what, sizeof what, "n=%u axpy(%.7g) vs ref_axpy (rel to the terms)", n, alpha);
  t_check(what, err_terms(vw, r, stored(alpha), x, y, t), tol);

  /* aypx: w = y; w = x + beta w */
  t_ok("copy", sessile_vec_copy(la, vy, vw));
  t_ok("aypx", sessile_vec_aypx(la, beta, vx, vw));
  sessile_ref_copy(n, y, r);
  sessile_ref_aypx(n, stored(beta), x, r);
  snprintf(what, sizeof what, "n=%u aypx(%.7g) vs ref_aypx (rel to the terms)", n, beta);
  t_check(what, err_terms(vw, r, stored(beta), y, x, t), tol);

  /* waxpy: w = beta x + y */
  t_ok("waxpy", sessile_vec_waxpy(la, beta, vx, vy, vw));
  sessile_ref_waxpy(n, stored(beta), x, y, r);
  snprintf(what, sizeof what, "n=%u waxpy(%.7g) vs ref_waxpy (rel to the terms)", n, beta);
  t_check(what, err_terms(vw, r, stored(beta), x, y, t), tol);

  /* pmul: w = x .* y */
  t_ok("pmul", sessile_vec_pmul(la, vx, vy, vw));
  sessile_ref_pmul(n, x, y, r);
  snprintf(what, sizeof what, "n=%u pmul vs ref_pmul", n);
  t_check(what, err_vs(vw, r, t), tol);

  /* dot and nrm2 */
  double d = NAN, d2 = NAN, nr = NAN, nr2 = NAN, absdot = 0;
  for (uint32_t i = 0; i < n; i++) absdot += fabs(x[i] * y[i]);
  t_ok("dot", sessile_vec_dot(la, vx, vy, &d));
  double dref = sessile_ref_dot(n, x, y);
  snprintf(what, sizeof what, "n=%u dot vs ref_dot (|diff| / sum|x y|)", n);
  t_check(what, fabs(d - dref) / absdot, tol_dot);
  t_ok("nrm2", sessile_vec_nrm2(la, vy, &nr));
  double nref = sessile_ref_nrm2(n, y);
  snprintf(what, sizeof what, "n=%u nrm2 vs ref_nrm2 (relative)", n);
  t_check(what, fabs(nr - nref) / nref, tol_dot);

  /* Determinism: the same reduction twice gives the same bits. */
  t_ok("dot again", sessile_vec_dot(la, vx, vy, &d2));
  t_ok("nrm2 again", sessile_vec_nrm2(la, vy, &nr2));
  snprintf(what, sizeof what, "n=%u dot and nrm2 bitwise identical when repeated", n);
  t_true(what, memcmp(&d, &d2, sizeof d) == 0 && memcmp(&nr, &nr2, sizeof nr) == 0);

  /* Inputs untouched by the ops that only read them. */
  t_ok("download x", sessile_vec_download(vx, t));
  int same = memcmp(t, x, (size_t)n * sizeof *t) == 0;
  t_ok("download y", sessile_vec_download(vy, t));
  same &= memcmp(t, y, (size_t)n * sizeof *t) == 0;
  snprintf(what, sizeof what, "n=%u read-only operands x, y unchanged by all the ops", n);
  t_true(what, same);

  sessile_vec_destroy(vx);
  sessile_vec_destroy(vy);
  sessile_vec_destroy(vw);
  free(x);
  free(y);
  free(w);
  free(r);
  free(t);
}

/* Length 5 occupies two REAL4 chunks; the 3 padding reals must stay zero
 * through every kernel, or dot (which sums whole chunks) would see them. */
static void test_padding(void) {
  printf("-- padding invariant (n = 5, 3 padding reals)\n");
  sessile_vec *v = vec_from(5, NULL), *ones = vec_from(5, NULL), *w = vec_from(5, NULL);
  double d = NAN;
  t_ok("fill 7", sessile_vec_fill(la, 7.0, v));
  t_ok("fill 1", sessile_vec_fill(la, 1.0, ones));
  t_ok("dot", sessile_vec_dot(la, v, ones, &d));
  printf("   dot(fill(7), fill(1)) = %.17g (padding written would give 56)\n", d);
  t_check("n=5 dot(fill(7), fill(1)) == 35 exactly (|diff|)", fabs(d - 35.0), 0.0);
  t_ok("dot", sessile_vec_dot(la, v, v, &d));
  t_check("n=5 dot(fill(7), fill(7)) == 245 exactly (|diff|)", fabs(d - 245.0), 0.0);
  /* Through the other element-wise kernels: all exact in binary. */
  t_ok("scale", sessile_vec_scale(la, 2.0, v));                /* 14 */
  t_ok("axpy", sessile_vec_axpy(la, 3.0, ones, v));           /* 17 */
  t_ok("aypx", sessile_vec_aypx(la, 0.5, ones, v));           /* 9.5 */
  t_ok("waxpy", sessile_vec_waxpy(la, 2.0, v, ones, w));      /* 20 */
  t_ok("pmul", sessile_vec_pmul(la, w, v, w));                /* 190 */
  t_ok("copy", sessile_vec_copy(la, w, v));                   /* 190 */
  t_ok("dot", sessile_vec_dot(la, v, ones, &d));
  t_check("n=5 after scale/axpy/aypx/waxpy/pmul/copy: dot(v, 1) == 5*190 exactly", fabs(d - 950.0),
          0.0);
  double h[5];
  const double up[5] = {1, 2, 3, 4, 5};
  t_ok("upload", sessile_vec_upload(v, up));
  t_ok("nrm2", sessile_vec_nrm2(la, v, &d));
  t_check("n=5 upload 1..5, nrm2 == sqrt(55) (relative)", fabs(d - sqrt(55.0)) / sqrt(55.0),
          fp64 ? 2.3e-16 : 1.2e-7);
  t_ok("download", sessile_vec_download(v, h));
  t_true("n=5 download after upload returns 1..5", memcmp(h, up, sizeof h) == 0);
  sessile_vec_destroy(v);
  sessile_vec_destroy(ones);
  sessile_vec_destroy(w);
}

static void test_errors(void) {
  printf("-- usage errors\n");
  sessile_vec *a = vec_from(5, NULL), *b = vec_from(6, NULL), *c = vec_from(5, NULL);
  double d = 0;
  struct { const char *name; sessile_status s; } r[] = {
      {"copy 5 -> 6", sessile_vec_copy(la, a, b)},
      {"axpy 5, 6", sessile_vec_axpy(la, 1.0, a, b)},
      {"aypx 5, 6", sessile_vec_aypx(la, 1.0, a, b)},
      {"waxpy x 5, y 6", sessile_vec_waxpy(la, 1.0, a, b, c)},
      {"waxpy w 6", sessile_vec_waxpy(la, 1.0, a, c, b)},
      {"pmul x 5, y 6", sessile_vec_pmul(la, a, b, c)},
      {"pmul w 6", sessile_vec_pmul(la, a, c, b)},
      {"dot 5, 6", sessile_vec_dot(la, a, b, &d)},
  };
  for (size_t i = 0; i < sizeof r / sizeof r[0]; i++) {
    char what[128];
    snprintf(what, sizeof what, "length mismatch %s -> %s", r[i].name, sessile_status_name(r[i].s));
    t_true(what, r[i].s == SESSILE_ERR_USAGE);
  }
  sessile_error_clear();
  (void)sessile_vec_dot(la, a, b, &d);
  printf("   message: \"%s\"\n", sessile_error_message());
  t_true("  ... the message gives both lengths", strstr(sessile_error_message(), "5") &&
                                                     strstr(sessile_error_message(), "6"));
  sessile_vec *z = (sessile_vec *)&z;
  sessile_status s = sessile_vec_create(la, 0, &z);
  t_true("vec_create of length 0 -> SESSILE_ERR_USAGE, *out = NULL",
         s == SESSILE_ERR_USAGE && z == NULL);
  sessile_vec_destroy(a);
  sessile_vec_destroy(b);
  sessile_vec_destroy(c);
}

int main(void) {
  sessile_gpu *g = t_gpu(0);
  fp64 = sessile_gpu_info_of(g)->precision == 64;
  t_must("la_create", sessile_la_create(g, &la));
  t_true("la_real_bytes matches the context precision",
         sessile_la_real_bytes(la) == (fp64 ? 8u : 4u) && sessile_la_gpu(la) == g);
  const uint32_t sizes[] = {1, 3, 4, 5, 1000, 32 * 32 * 32, 100003};
  for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; i++) test_length(sizes[i]);
  test_padding();
  test_errors();
  sessile_la_destroy(la);
  return t_finish(g);
}
