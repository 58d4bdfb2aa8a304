/* muparser's bytecode rebuilt (rules_rpn.c), for the rules' compiler
 * (rules_compile.c): the tokens, muparser's RPN tokens (slot -1 is its null
 * pointer) and the compiler's state. */
#ifndef SESSILE_SDS_RULES_RPN_H
#define SESSILE_SDS_RULES_RPN_H
#include <stddef.h>
#include "rules_internal.h"
#include "rules_vm.h"

enum { T_VAL, T_VAR, T_FUNC, T_INFIX, T_BIN, T_BO, T_BC, T_SEP, T_IF, T_ELSE, T_END, T_NONE };
enum { MAXT = 1100 }; /* a line holds at most 1023 characters */

typedef struct tok {
  int type, op, fun, argc; /* op: VM_ADD..VM_OR; fun: sds_vm_fun, or VM_SUM..VM_MAX with argc -1 */
  int neg;                 /* T_INFIX: 1 minus, 0 plus */
  int slot;
  double val;
} tok;

enum { R_VAL, R_VAR, R_VARMUL, R_POW2, R_POW3, R_POW4, R_OP, R_FUNC, R_MULTI, R_IF, R_ELSE, R_ENDIF };
typedef struct rtok {
  int cmd, op, fun, argc, slot;
  double data, data2;
} rtok;

typedef struct shunt {
  tok opt[MAXT];
  int nopt;
  int argc[MAXT];
  int nargc;
} shunt;

typedef struct cc {
  const sessile_sds_model *m;
  shunt s;
  rtok rpn[MAXT];
  int n;
  char *why;
  size_t nwhy;
  const char *rule;
  int line;
} cc;

/* Writes "file:line: rule NAME: message" into c->why; returns -1. */
int sds_rpn_refuse(cc *c, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
int sds_rpn_push(cc *c, rtok r);
/* The RPN of one expression muparser accepted into c->rpn (c->n tokens); -1 refused. */
int sds_rpn_build(cc *c, const char *text);
extern const char *const sds_vm_fun_names[VM_F_COUNT];
#endif
