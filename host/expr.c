/* The muparser wrapper (sessile/expr.h). */
#include <math.h>
#include <muParserDLL.h>
#include <stdio.h>
#include <stdlib.h>
#include "sessile/expr.h"

int sessile_expr_plain_number(const char *t, double *v) {
  char *end = NULL;
  while (*t == ' ' || *t == '\t') t++;
  if (!((*t >= '0' && *t <= '9') || *t == '.' || *t == '-' || *t == '+')) return 0;
  *v = strtod(t, &end);
  if (end == t) return 0;
  while (*end == ' ' || *end == '\t') end++;
  return *end == 0 && isfinite(*v);
}

sessile_status sessile_expr_begin(sessile_expr *e) {
  e->c = 0;
  e->h = mupCreate(muBASETYPE_FLOAT);
  SESSILE_CHECK(e->h, SESSILE_ERR_NO_MEMORY, "out of host memory for an expression");
  return SESSILE_OK;
}

void sessile_expr_var(sessile_expr *e, const char *name, double *slot) { mupDefineVar(e->h, name, slot); }
void sessile_expr_const(sessile_expr *e, const char *name, double value) { mupDefineConst(e->h, name, value); }
void sessile_expr_fun2(sessile_expr *e, const char *name, double (*f)(void *, double, double), void *user) {
  mupDefineFunUserData2(e->h, name, f, user, 0);
}

sessile_status sessile_expr_finish(sessile_expr *e, const char *text, int *pos, char *msg, size_t n) {
  muParserHandle_t h = e->h;
  int bad = mupError(h);
  if (!bad) {
    mupSetExpr(h, text);
    bad = mupError(h);
  }
  if (!bad) {
    (void)mupEval(h);
    bad = mupError(h);
  }
  if (!bad) return SESSILE_OK;
  const char *m = mupGetErrorMsg(h);
  *pos = mupGetErrorPos(h);
  snprintf(msg, n, "%s", m && *m ? m : "bad expression");
  for (char *c = msg; *c; c++) /* muparser's messages may hold line breaks: keep one line */
    if (*c == '\n' || *c == '\r') *c = ' ';
  mupRelease(h);
  e->h = NULL;
  return SESSILE_ERR_USAGE;
}

double sessile_expr_eval(const sessile_expr *e) { return e->h ? mupEval(e->h) : e->c; }

void sessile_expr_free(sessile_expr *e) {
  if (e->h) mupRelease(e->h);
  e->h = NULL;
}
