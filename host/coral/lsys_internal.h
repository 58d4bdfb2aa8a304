/* The compiled L-system grammar shared by lsys_parse.c (text -> productions),
 * lsys_expr.c (muparser handles) and lsys_derive.c (rewriting). */
#ifndef SESSILE_LSYS_INTERNAL_H
#define SESSILE_LSYS_INTERNAL_H

#include <stdint.h>
#include "sessile/expr.h"
#include "sessile/coral/lsystem.h"

enum {
  LSYS_MAX_DEFINES = 128,
  LSYS_MAX_SLOTS = 64,     /* parameters bound by one production (contexts included) */
  LSYS_MAX_CONTEXT = 16,   /* modules in one left or right context */
  LSYS_MAX_EXPRS = 4096,   /* expressions in one grammar (each a muparser handle) */
  LSYS_MAX_PRODS = 1024,
  LSYS_MAX_TEXT = 1 << 20  /* grammar bytes */
};
/* Production sets: the derivation's, and the homomorphism applied once to
 * the derived string before the turtle draws it (L-Py's "homomorphism:"). */
enum { LSYS_DERIVATION = 0, LSYS_HOMOMORPHISM = 1 };

/* An expression: a constant, or a muparser handle whose variables point at
 * the owning production's slots and the grammar's defines. */
typedef sessile_expr lsys_expr; /* a constant, or a compiled muparser handle */

/* A module of a successor or the axiom: symbol and its argument expressions
 * exprs[first .. first + np) of the grammar. */
typedef struct lsys_tpl {
  uint8_t sym, np;
  uint32_t first;
} lsys_tpl;

/* A module of a context pattern: symbol, parameter count, first slot. */
typedef struct lsys_pat {
  uint8_t sym, np, slot;
} lsys_pat;

typedef struct lsys_prod {
  int line;
  int set; /* LSYS_DERIVATION or LSYS_HOMOMORPHISM */
  uint8_t pred, pred_np, pred_slot;
  int nleft, nright;
  lsys_pat left[LSYS_MAX_CONTEXT], right[LSYS_MAX_CONTEXT];
  double *slots; /* LSYS_MAX_SLOTS values: the bound parameters */
  int has_cond, has_weight;
  lsys_expr cond, weight;
  uint32_t succ_first, nsucc; /* modules g->tpl[succ_first ..) */
} lsys_prod;

struct sessile_lsys {
  int iterations;
  double angle, width_factor;
  uint8_t ignore[256];
  uint8_t has_context, has_cut;
  int ndefines;
  char dname[LSYS_MAX_DEFINES][32];
  double *dval; /* LSYS_MAX_DEFINES: stable addresses bound into every parser */
  lsys_prod *prods;
  int nprods;
  /* productions of each set by predecessor symbol, in file order */
  uint32_t by_first[2][256], by_count[2][256];
  uint32_t *by_list;
  int nset[2]; /* productions per set */
  lsys_tpl *tpl;
  uint32_t ntpl, captpl;
  lsys_expr *exprs;
  uint32_t nexprs, capexprs;
  uint32_t axiom_first, naxiom; /* tpl[axiom_first ..) */
  int axiom_line;
  char where[128];              /* the grammar's name in messages ("FILE:LINE: ...") */
  uint64_t *rng;                /* the stream uniform() draws from during a derivation */
};

/* muparser handle for text bound to the production's slot names (NULL prod:
 * defines only); on a syntax error sets *errpos (0-based in text) and the
 * message, returns SESSILE_ERR_USAGE. */
sessile_status lsys_expr_compile(sessile_lsys *g, const char *text, int nnames, char names[][32], double *slots,
                                 lsys_expr *out, int *errpos, char *msg, size_t msgn);

/* Appends one module with np parameters (values not yet written): returns
 * the parameter pointer, or NULL when out of memory. */
double *lsys_string_push(sessile_lsys_string *s, uint8_t sym, uint8_t np);
/* Evaluates tpl[first .. first + n) and appends the modules; a parameter
 * that comes out NaN or infinite is refused (SESSILE_ERR_USAGE) as
 * "WHERE:line: ..." (line: the production's or the axiom's). */
sessile_status lsys_emit(const sessile_lsys *g, uint32_t first, uint32_t n, int line, sessile_lsys_string *out,
                         uint64_t max_modules);
#endif
