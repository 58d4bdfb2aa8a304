/* muparser's bytecode rebuilt (rules_rpn.h, docs/sds_rules.md, "Bytecode").
 * muparser 2.3's C API does not expose its bytecode, so this rebuilds it:
 * the same token reader decisions, the same shunting-yard
 * (ParserBase::CreateRPN) and the same optimiser (ParserByteCode::AddOp,
 * AddFun: constant folding, x*c+d as one VARMUL, x^2..4 as products), so
 * that an expression runs the operations muparser runs, in its order, on
 * the same doubles.  It only sees texts muparser has accepted; anything it
 * does not rebuild (assignment, top-level commas, odd numbers) is refused,
 * and the model stays on the host evaluator. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "rules_rpn.h"

int sds_rpn_refuse(cc *c, const char *fmt, ...) {
  char msg[200];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  snprintf(c->why, c->nwhy, "%s:%d: rule %s: %s", c->m->file, c->line, c->rule, msg);
  return -1;
}

const char *const sds_vm_fun_names[VM_F_COUNT] = {
    [VM_F_ABS] = "abs",    [VM_F_SIGN] = "sign",   [VM_F_RINT] = "rint",   [VM_F_SQRT] = "sqrt",
    [VM_F_SIN] = "sin",    [VM_F_COS] = "cos",     [VM_F_TAN] = "tan",     [VM_F_ASIN] = "asin",
    [VM_F_ACOS] = "acos",  [VM_F_ATAN] = "atan",   [VM_F_SINH] = "sinh",   [VM_F_COSH] = "cosh",
    [VM_F_TANH] = "tanh",  [VM_F_ASINH] = "asinh", [VM_F_ACOSH] = "acosh", [VM_F_ATANH] = "atanh",
    [VM_F_LOG2] = "log2",  [VM_F_LOG10] = "log10", [VM_F_LOG] = "log",     [VM_F_EXP] = "exp",
    [VM_F_ATAN2] = "atan2"};

/* A function name: its id and arity (-1: any number of arguments). */
static int fun_of(const char *x, int *argc) {
  static const char *const multi[] = {"sum", "avg", "min", "max"};
  for (int i = 0; i < 4; i++)
    if (!strcmp(x, multi[i])) return *argc = -1, VM_SUM + i;
  if (!strcmp(x, "ln")) return *argc = 1, VM_F_LOG;
  for (int f = 0; f < VM_F_COUNT; f++)
    if (sds_vm_fun_names[f] && !strcmp(x, sds_vm_fun_names[f])) return *argc = f == VM_F_ATAN2 ? 2 : 1, f;
  return -1;
}

static int is_name(char ch) {
  return (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || ch == '_';
}
static int is_digit(char ch) { return ch >= '0' && ch <= '9'; }

/* A number as libstdc++'s `stream >> double` reads one (muparser's IsVal):
 * digits, a point, digits, an exponent with digits; then strtod. */
static int number(const char *s, int *p, double *v) {
  int i = *p, nd = 0;
  while (is_digit(s[i])) i++, nd++;
  if (s[i] == '.') {
    i++;
    while (is_digit(s[i])) i++, nd++;
  }
  if (!nd) return 0;
  if (s[i] == 'e' || s[i] == 'E') {
    int j = i + 1;
    if (s[j] == '+' || s[j] == '-') j++;
    if (!is_digit(s[j])) return 0; /* muparser refuses "1e" */
    while (is_digit(s[j])) j++;
    i = j;
  }
  char buf[64];
  if (i - *p >= (int)sizeof buf) return 0;
  memcpy(buf, s + *p, (size_t)(i - *p));
  buf[i - *p] = 0;
  *v = strtod(buf, NULL);
  *p = i;
  return 1;
}

static int find_name(const char names[][SESSILE_SDS_NAME], int n, const char *x) {
  for (int i = 0; i < n; i++)
    if (!strcmp(names[i], x)) return i;
  return -1;
}

/* The next token (muparser's ReadNextToken order: functions, operators,
 * separators, constants and numbers, variables). */
static int next(cc *c, const char *s, int *p, int prev, tok *t) {
  static const char *const ops[] = {"<=", ">=", "!=", "==", "<", ">", "+", "-", "*", "/", "^", "&&", "||"};
  static const int opc[] = {VM_LE,  VM_GE,  VM_NE,  VM_EQ,  VM_LT,  VM_GT, VM_ADD,
                            VM_SUB, VM_MUL, VM_DIV, VM_POW, VM_AND, VM_OR};
  const sessile_sds_model *m = c->m;
  memset(t, 0, sizeof *t);
  t->slot = -1;
  while (s[*p] == ' ' || s[*p] == '\t' || s[*p] == '\r') (*p)++;
  if (!s[*p]) return t->type = T_END, 0;
  char name[64];
  int a = *p, b = a;
  while (is_name(s[b]) && b - a < 63) b++;
  memcpy(name, s + a, (size_t)(b - a));
  name[b - a] = 0;
  if (b > a && s[b] == '(') {
    int f = fun_of(name, &t->argc);
    if (f >= 0) return t->type = T_FUNC, t->fun = f, *p = b, 0;
  }
  int after_operand = prev == T_VAL || prev == T_VAR || prev == T_BC;
  for (size_t i = 0; i < sizeof ops / sizeof *ops; i++) {
    size_t n = strlen(ops[i]);
    if (strncmp(s + a, ops[i], n)) continue;
    *p = a + (int)n;
    if (!after_operand) { /* muparser's noOPT: a sign, or nothing it accepts */
      if (opc[i] != VM_ADD && opc[i] != VM_SUB)
        return sds_rpn_refuse(c, "operator '%s' without a left operand", ops[i]);
      return t->type = T_INFIX, t->neg = opc[i] == VM_SUB, 0;
    }
    return t->type = T_BIN, t->op = opc[i], 0;
  }
  switch (s[a]) {
    case '(': return *p = a + 1, t->type = T_BO, 0;
    case ')': return *p = a + 1, t->type = T_BC, 0;
    case ',': return *p = a + 1, t->type = T_SEP, 0;
    case '?': return *p = a + 1, t->type = T_IF, 0;
    case ':': return *p = a + 1, t->type = T_ELSE, 0;
    case '=': return sds_rpn_refuse(c, "an assignment ('=') in an expression");
    default: break;
  }
  if (b > a) {
    int k = find_name(m->cname, m->nconst, name);
    if (k >= 0) return t->type = T_VAL, t->val = m->cval[k], *p = b, 0;
    /* muparser's _pi as built by GCC (MathImpl::CONST_PI under __GNUG__): 12 digits */
    if (!strcmp(name, "_pi")) return t->type = T_VAL, t->val = 3.141592653589, *p = b, 0;
    if (!strcmp(name, "_e")) return t->type = T_VAL, t->val = 2.718281828459045235360287, *p = b, 0;
  }
  if (is_digit(s[a]) || s[a] == '.') {
    if (!number(s, p, &t->val)) return sds_rpn_refuse(c, "a number the bytecode does not read");
    return t->type = T_VAL, 0;
  }
  if (b > a) {
    static const char *const fixed[] = {"radius", "volume", "time", "surface"};
    int slot = -1;
    for (int i = 0; i < 4; i++)
      if (!strcmp(name, fixed[i])) slot = i;
    int k = find_name(m->mname, m->nmorph, name);
    if (k >= 0) slot = SDS_SLOT_MORPH + k;
    k = find_name(m->sname, m->nstate, name);
    if (k >= 0) slot = SDS_SLOT_STATE + k;
    if (slot >= 0) return t->type = T_VAR, t->slot = slot, *p = b, 0;
  }
  return sds_rpn_refuse(c, "a token the bytecode does not read at '%.12s'", s + a);
}

/* --- muparser's ParserByteCode ---------------------------------------------- */
int sds_rpn_push(cc *c, rtok r) {
  if (c->n >= MAXT) return sds_rpn_refuse(c, "an expression too long");
  c->rpn[c->n++] = r;
  return 0;
}

static double fold2(int op, double x, double y) {
  switch (op) {
    case VM_AND: return (!(x > -1 && x < 1)) && (!(y > -1 && y < 1)); /* (int)x && (int)y on x86-64 */
    case VM_OR: return (!(x > -1 && x < 1)) || (!(y > -1 && y < 1));
    case VM_LT: return x < y;
    case VM_GT: return x > y;
    case VM_LE: return x <= y;
    case VM_GE: return x >= y;
    case VM_NE: return x != y;
    case VM_EQ: return x == y;
    case VM_ADD: return x + y;
    case VM_SUB: return x - y;
    case VM_MUL: return x * y;
    case VM_DIV: return x / y;
    default: return pow(x, y);
  }
}

static int same_slot(const rtok *a, const rtok *b) { return a->slot == b->slot; }

/* ParserByteCode::AddOp, pattern for pattern. */
static int add_op(cc *c, int op) {
  int sz = c->n;
  if (sz < 2) return sds_rpn_refuse(c, "an operator without operands");
  rtok *x = &c->rpn[sz - 2], *y = &c->rpn[sz - 1];
  if (x->cmd == R_VAL && y->cmd == R_VAL) {
    x->data2 = fold2(op, x->data2, y->data2);
    c->n--;
    return 0;
  }
  int done = 0;
  if (op == VM_POW) {
    if (x->cmd == R_VAR && y->cmd == R_VAL) {
      double e = y->data2;
      done = 1;
      if (e == 0)
        *x = (rtok){R_VAL, 0, 0, 0, -1, 0, 1};
      else if (e == 1)
        x->cmd = R_VAR;
      else if (e == 2)
        x->cmd = R_POW2;
      else if (e == 3)
        x->cmd = R_POW3;
      else if (e == 4)
        x->cmd = R_POW4;
      else
        done = 0;
      if (done) c->n--;
    }
  } else if (op == VM_ADD || op == VM_SUB) {
    if ((y->cmd == R_VAR && x->cmd == R_VAL) || (y->cmd == R_VAL && x->cmd == R_VAR) ||
        (y->cmd == R_VAL && x->cmd == R_VARMUL) || (y->cmd == R_VARMUL && x->cmd == R_VAL) ||
        (y->cmd == R_VAR && x->cmd == R_VAR && same_slot(x, y)) ||
        (y->cmd == R_VAR && x->cmd == R_VARMUL && same_slot(x, y)) ||
        (y->cmd == R_VARMUL && x->cmd == R_VAR && same_slot(x, y)) ||
        (y->cmd == R_VARMUL && x->cmd == R_VARMUL && same_slot(x, y))) {
      double sgn = op == VM_SUB ? -1 : 1;
      x->cmd = R_VARMUL;
      x->slot = x->slot >= 0 ? x->slot : y->slot;
      x->data2 += sgn * y->data2;
      x->data += sgn * y->data;
      c->n--, done = 1;
    }
  } else if (op == VM_MUL) {
    if ((y->cmd == R_VAR && x->cmd == R_VAL) || (y->cmd == R_VAL && x->cmd == R_VAR)) {
      x->cmd = R_VARMUL;
      x->slot = x->slot >= 0 ? x->slot : y->slot;
      x->data = x->data2 + y->data2;
      x->data2 = 0;
      c->n--, done = 1;
    } else if ((y->cmd == R_VAL && x->cmd == R_VARMUL) || (y->cmd == R_VARMUL && x->cmd == R_VAL)) {
      int yval = y->cmd == R_VAL;
      x->cmd = R_VARMUL;
      x->slot = x->slot >= 0 ? x->slot : y->slot;
      if (yval) {
        x->data *= y->data2;
        x->data2 *= y->data2;
      } else {
        x->data = y->data * x->data2;
        x->data2 = y->data2 * x->data2;
      }
      c->n--, done = 1;
    } else if (y->cmd == R_VAR && x->cmd == R_VAR && same_slot(x, y)) {
      x->cmd = R_POW2;
      c->n--, done = 1;
    }
  } else if (op == VM_DIV) {
    if (y->cmd == R_VAL && x->cmd == R_VARMUL && y->data2 != 0) {
      x->data /= y->data2;
      x->data2 /= y->data2;
      c->n--, done = 1;
    }
  }
  if (done) return 0;
  return sds_rpn_push(c, (rtok){R_OP, op, 0, 0, -1, 0, 0});
}

/* ParserByteCode::AddFun: unary plus vanishes; a function of fixed arity
 * whose arguments are all values is folded. */
static int add_fun(cc *c, const tok *f, int argc) {
  if (f->type == T_INFIX && !f->neg) return 0;
  int fun = f->type == T_INFIX ? VM_F_NEG : f->fun;
  if (f->argc == -1) return sds_rpn_push(c, (rtok){R_MULTI, 0, fun, argc, -1, 0, 0});
  if (c->n < argc) return sds_rpn_refuse(c, "a function without its arguments");
  int all = 1;
  for (int i = 0; i < argc; i++) all &= c->rpn[c->n - 1 - i].cmd == R_VAL;
  if (!all) return sds_rpn_push(c, (rtok){R_FUNC, 0, fun, argc, -1, 0, 0});
  double v =
      argc == 2 ? atan2(c->rpn[c->n - 2].data2, c->rpn[c->n - 1].data2) : sds_vm_fun1(fun, c->rpn[c->n - 1].data2);
  c->n -= argc;
  return sds_rpn_push(c, (rtok){R_VAL, 0, 0, 0, -1, 0, v});
}

/* --- muparser's ParserBase::CreateRPN ----------------------------------------- */
static int prec(const tok *t) {
  if (t->type == T_INFIX) return 6;
  if (t->type == T_IF || t->type == T_ELSE) return 0;
  switch (t->op) {
    case VM_OR: return 1;
    case VM_AND: return 2;
    case VM_ADD:
    case VM_SUB: return 5;
    case VM_MUL:
    case VM_DIV: return 6;
    case VM_POW: return 7;
    default: return 4; /* comparisons */
  }
}

static int apply_if_else(cc *c, shunt *s) {
  while (s->nopt && s->opt[s->nopt - 1].type == T_ELSE) {
    s->nopt--;
    if (!s->nopt || s->opt[s->nopt - 1].type != T_IF) return sds_rpn_refuse(c, "a misplaced ':'");
    s->nopt--;
    if (sds_rpn_push(c, (rtok){R_ENDIF, 0, 0, 0, -1, 0, 0})) return -1;
  }
  return 0;
}

static int apply_top(cc *c, shunt *s) {
  tok t = s->opt[--s->nopt];
  if (t.type == T_INFIX) return add_fun(c, &t, 1);
  return add_op(c, t.op);
}

static int apply_remaining(cc *c, shunt *s) {
  while (s->nopt && s->opt[s->nopt - 1].type != T_BO && s->opt[s->nopt - 1].type != T_IF) {
    int ty = s->opt[s->nopt - 1].type;
    if (ty == T_ELSE) {
      if (apply_if_else(c, s)) return -1;
    } else if (ty == T_INFIX || ty == T_BIN) {
      if (apply_top(c, s)) return -1;
    } else {
      return sds_rpn_refuse(c, "an expression the bytecode does not rebuild");
    }
  }
  return 0;
}

int sds_rpn_build(cc *c, const char *text) {
  shunt *s = &c->s;
  int p = 0, prev = T_NONE, ifs = 0;
  c->n = 0, s->nopt = 0, s->nargc = 1, s->argc[0] = 1;
  for (;;) {
    tok t;
    if (next(c, text, &p, prev, &t)) return -1;
    if (s->nopt >= MAXT - 1 || s->nargc >= MAXT - 1) return sds_rpn_refuse(c, "an expression too long");
    switch (t.type) {
      case T_VAR:
        if (sds_rpn_push(c, (rtok){R_VAR, 0, 0, 0, t.slot, 1, 0})) return -1;
        break;
      case T_VAL:
        if (sds_rpn_push(c, (rtok){R_VAL, 0, 0, 0, -1, 0, t.val})) return -1;
        break;
      case T_ELSE:
        if (s->nargc < 2 || s->argc[s->nargc - 1] > 1 || --ifs < 0) return sds_rpn_refuse(c, "a misplaced ':'");
        s->nargc--;
        if (apply_remaining(c, s) || sds_rpn_push(c, (rtok){R_ELSE, 0, 0, 0, -1, 0, 0})) return -1;
        s->opt[s->nopt++] = t;
        break;
      case T_SEP:
        if ((s->nopt && s->opt[s->nopt - 1].type == T_IF) || s->nargc < 1) return sds_rpn_refuse(c, "a misplaced ','");
        s->argc[s->nargc - 1]++;
        if (apply_remaining(c, s)) return -1;
        break;
      case T_END:
        if (apply_remaining(c, s)) return -1;
        break;
      case T_BC: {
        if (prev == T_BO) return sds_rpn_refuse(c, "a function without arguments");
        if (apply_remaining(c, s)) return -1;
        if (!s->nopt || s->opt[s->nopt - 1].type != T_BO) return sds_rpn_refuse(c, "unbalanced parentheses");
        int argc = s->argc[--s->nargc];
        s->nopt--;
        int fun = s->nopt && s->opt[s->nopt - 1].type == T_FUNC;
        if (argc > 1 && !fun) return sds_rpn_refuse(c, "a comma outside a function's arguments");
        if (fun) {
          tok f = s->opt[--s->nopt];
          if (f.argc > 0 && f.argc != argc) return sds_rpn_refuse(c, "a function with the wrong number of arguments");
          if (add_fun(c, &f, argc)) return -1;
        }
        break;
      }
      case T_IF:
        ifs++;
        s->argc[s->nargc++] = 1;
        /* fall through: the condition's operators are applied as before a binary one */
      case T_BIN:
        while (s->nopt) {
          const tok *top = &s->opt[s->nopt - 1];
          if (top->type == T_BO || top->type == T_ELSE || top->type == T_IF) break;
          int p1 = prec(top), p2 = prec(&t);
          if (top->type == t.type && top->op == t.op && t.type == T_BIN) {
            if ((t.op == VM_POW && p1 <= p2) || (t.op != VM_POW && p1 < p2)) break;
          } else if (p1 < p2) {
            break;
          }
          if (apply_top(c, s)) return -1;
        }
        if (t.type == T_IF && sds_rpn_push(c, (rtok){R_IF, 0, 0, 0, -1, 0, 0})) return -1;
        s->opt[s->nopt++] = t;
        break;
      case T_BO:
        s->argc[s->nargc++] = 1;
        s->opt[s->nopt++] = t;
        break;
      default: /* T_INFIX, T_FUNC */ s->opt[s->nopt++] = t; break;
    }
    prev = t.type;
    if (t.type == T_END) break;
  }
  if (ifs > 0) return sds_rpn_refuse(c, "a '?' without its ':'");
  if (s->nopt || s->nargc != 1 || s->argc[0] != 1)
    return sds_rpn_refuse(c, "an expression the bytecode does not rebuild");
  if (!c->n) return sds_rpn_refuse(c, "an empty expression");
  return 0;
}
