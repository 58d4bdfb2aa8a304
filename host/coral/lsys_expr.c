/* L-system expressions through the shared muparser wrapper (sessile/expr.h):
 * each expression compiled once, its variables pointing at fixed slots (the
 * production's parameters and the grammar's defines), so a derivation only
 * writes slots and evaluates.  Plain numbers skip muparser altogether. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "lsys_internal.h"
#include "sessile/expr.h"
#include "sessile/rng.h"

/* uniform(a, b): a draw from the derivation's stream; a while compiling
 * (the syntax check evaluates once, outside any derivation). */
static double fn_uniform(void *ud, double a, double b) {
  sessile_lsys *g = ud;
  return g->rng ? sessile_rng_range(g->rng, a, b) : a;
}

sessile_status lsys_expr_compile(sessile_lsys *g, const char *text, int nnames, char names[][32], double *slots,
                                 lsys_expr *out, int *errpos, char *msg, size_t msgn) {
  out->h = NULL, out->c = 0;
  *errpos = 0;
  const char *t = text;
  while (*t == ' ' || *t == '\t') t++;
  if (!*t) {
    snprintf(msg, msgn, "empty expression");
    return SESSILE_ERR_USAGE;
  }
  if (sessile_expr_plain_number(text, &out->c)) return SESSILE_OK;
  if (sessile_expr_begin(out) != SESSILE_OK) {
    snprintf(msg, msgn, "out of host memory for an expression");
    return SESSILE_ERR_NO_MEMORY;
  }
  for (int i = 0; i < nnames; i++) sessile_expr_var(out, names[i], &slots[i]);
  for (int i = 0; i < g->ndefines; i++) sessile_expr_var(out, g->dname[i], &g->dval[i]);
  sessile_expr_fun2(out, "uniform", fn_uniform, g);
  int pos = 0;
  if (sessile_expr_finish(out, text, &pos, msg, msgn) != SESSILE_OK) {
    *errpos = pos < 0 ? 0 : (size_t)pos > strlen(text) ? (int)strlen(text) : pos;
    return SESSILE_ERR_USAGE;
  }
  return SESSILE_OK;
}
