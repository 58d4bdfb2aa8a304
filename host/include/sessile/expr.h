/* sessile — expressions typed by the user (the L-system grammars' and the
 * SDS models' rules) through muparser's C API: one wrapper for every
 * generator.  An expression is a plain number (muparser skipped) or a
 * compiled handle whose variables point at the caller's slots, so an
 * evaluation only reads the slots (bytecode, no re-parse). */
#ifndef SESSILE_EXPR_H
#define SESSILE_EXPR_H
#include <stddef.h>
#include "sessile/status.h"

typedef struct sessile_expr {
  void *h;  /* muParserHandle_t; NULL: the constant c */
  double c;
} sessile_expr;

/* 1 when text is one finite number (blanks around it allowed): *v. */
int sessile_expr_plain_number(const char *text, double *v);
/* Starts compiling into e (e->h a fresh handle); then name its variables,
 * constants and functions, and call sessile_expr_finish.  SESSILE_ERR_NO_MEMORY
 * when muparser cannot make a handle. */
sessile_status sessile_expr_begin(sessile_expr *e);
void sessile_expr_var(sessile_expr *e, const char *name, double *slot);
void sessile_expr_const(sessile_expr *e, const char *name, double value);
/* f(user, a, b) under name (never folded: it may draw random numbers). */
void sessile_expr_fun2(sessile_expr *e, const char *name, double (*f)(void *user, double a, double b), void *user);
/* Sets text and evaluates it once (muparser parses lazily: that finds the
 * syntax errors).  On a fault: SESSILE_ERR_USAGE with nothing recorded, the
 * handle released, *pos muparser's position (not clamped) and msg its
 * message on one line ("bad expression" when it has none). */
sessile_status sessile_expr_finish(sessile_expr *e, const char *text, int *pos, char *msg, size_t n);
double sessile_expr_eval(const sessile_expr *e);
void sessile_expr_free(sessile_expr *e); /* leaves e->h NULL */
#endif
