/* L-system expressions through muparser's C API: each expression compiled
 * once into its own handle whose variables point at fixed slots (the
 * production's parameters and the grammar's defines), so a derivation only
 * writes slots and calls mupEval (bytecode, no re-parse).  Plain numbers
 * skip muparser altogether. */
#include <math.h>
#include <muParserDLL.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "lsys_internal.h"
#include "sessile/rng.h"

/* uniform(a, b): a draw from the derivation's stream; a while compiling
 * (the syntax check evaluates once, outside any derivation). */
static muFloat_t fn_uniform(void *ud, muFloat_t a, muFloat_t b) {
  sessile_lsys *g = ud;
  return g->rng ? sessile_rng_range(g->rng, a, b) : a;
}

static int is_plain_number(const char *t, double *v) {
  char *end = NULL;
  while (*t == ' ' || *t == '\t') t++;
  if (!((*t >= '0' && *t <= '9') || *t == '.' || *t == '-' || *t == '+')) return 0;
  *v = strtod(t, &end);
  if (end == t) return 0;
  while (*end == ' ' || *end == '\t') end++;
  return *end == 0 && isfinite(*v);
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
  if (is_plain_number(text, &out->c)) return SESSILE_OK;
  muParserHandle_t h = mupCreate(muBASETYPE_FLOAT);
  if (!h) {
    snprintf(msg, msgn, "out of host memory for an expression");
    return SESSILE_ERR_NO_MEMORY;
  }
  for (int i = 0; i < nnames; i++) mupDefineVar(h, names[i], &slots[i]);
  for (int i = 0; i < g->ndefines; i++) mupDefineVar(h, g->dname[i], &g->dval[i]);
  mupDefineFunUserData2(h, "uniform", fn_uniform, g, 0);
  int bad = mupError(h);
  if (!bad) {
    mupSetExpr(h, text);
    bad = mupError(h);
  }
  if (!bad) {
    double v = mupEval(h);
    (void)v;
    bad = mupError(h);
  }
  if (bad) {
    const char *m = mupGetErrorMsg(h);
    int pos = mupGetErrorPos(h);
    *errpos = pos < 0 ? 0 : (size_t)pos > strlen(text) ? (int)strlen(text) : pos;
    snprintf(msg, msgn, "%s", m && *m ? m : "bad expression");
    /* muparser's messages end with a full stop or position note: keep one line */
    for (char *c = msg; *c; c++)
      if (*c == '\n' || *c == '\r') *c = ' ';
    mupRelease(h);
    return SESSILE_ERR_USAGE;
  }
  out->h = h;
  return SESSILE_OK;
}

double lsys_expr_eval(const lsys_expr *e) { return e->h ? mupEval(e->h) : e->c; }

void lsys_expr_free(lsys_expr *e) {
  if (e->h) mupRelease(e->h);
  e->h = NULL;
}
