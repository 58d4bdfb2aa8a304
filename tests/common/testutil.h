/* Small harness for sessile's test programs: each check prints what it
 * compared, the tolerance and the error found; the program exits non-zero if
 * any check failed or the validation layer said anything. */
#ifndef SESSILE_TESTUTIL_H
#define SESSILE_TESTUTIL_H
#include <stdio.h>
#include "sessile/gpu/gpu.h"
#include "sessile/la/la.h"
#include "sessile/bench/matrix_gen.h" /* the test matrices (host/bench) */

extern int t_failed, t_passed;

/* Records a check: ok when err <= tol (and err is not NaN). */
void t_check(const char *what, double err, double tol);
/* Records a boolean check. */
void t_true(const char *what, int cond);
/* Fails the test (with the library's message) when s != SESSILE_OK. */
void t_ok(const char *what, sessile_status s);
/* Creates the context with validation on; exits 1 (after printing why) on failure. */
sessile_gpu *t_gpu(int precision);
/* t_gpu for a test whose only argument is an optional --fp32 (any other
 * prints the usage and exits 2); *fp32: the context runs in fp32. */
sessile_gpu *t_gpu_args(int argc, char **argv, int *fp32);
/* Destroys g, adds a failed check if validation reported anything, prints the
 * summary line and returns the exit code. */
int t_finish(sessile_gpu *g);
/* Stops the test (exit 1, with the library's message) when s != SESSILE_OK:
 * for set-up steps whose failure makes the rest meaningless. */
void t_must(const char *what, sessile_status s);
/* Zero-filled allocations that stop the test when the host is out of memory. */
void *t_xalloc(size_t bytes);
double *t_dalloc(size_t n);
/* max_i |a_i - b_i| (NaN when any difference is) */
double t_maxdiff(const double *a, const double *b, size_t n);
/* max_i |a_i - b_i| / max(max_i |b_i|, tiny) */
double t_relerr(const double *a, const double *b, size_t n);
#endif
