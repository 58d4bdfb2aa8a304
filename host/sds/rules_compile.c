/* The rules' expressions to bytecode (rules_vm.h, docs/sds_rules.md,
 * "Bytecode").  muparser 2.3's C API does not expose its bytecode, so this
 * rebuilds it: the same token reader decisions, the same shunting-yard
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

/* muparser's RPN token: slot -1 is its null pointer. */
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

static int refuse(cc *c, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static int refuse(cc *c, const char *fmt, ...) {
  char msg[200];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  snprintf(c->why, c->nwhy, "%s:%d: rule %s: %s", c->m->file, c->line, c->rule, msg);
  return -1;
}

static const char *const fun_names[VM_F_COUNT] = {
    [VM_F_ABS] = "abs",   [VM_F_SIGN] = "sign",   [VM_F_RINT] = "rint",   [VM_F_SQRT] = "sqrt", [VM_F_SIN] = "sin",
    [VM_F_COS] = "cos",   [VM_F_TAN] = "tan",     [VM_F_ASIN] = "asin",   [VM_F_ACOS] = "acos", [VM_F_ATAN] = "atan",
    [VM_F_SINH] = "sinh", [VM_F_COSH] = "cosh",   [VM_F_TANH] = "tanh",   [VM_F_ASINH] = "asinh",
    [VM_F_ACOSH] = "acosh", [VM_F_ATANH] = "atanh", [VM_F_LOG2] = "log2", [VM_F_LOG10] = "log10",
    [VM_F_LOG] = "log",   [VM_F_EXP] = "exp",     [VM_F_ATAN2] = "atan2"};

/* A function name: its id and arity (-1: any number of arguments). */
static int fun_of(const char *x, int *argc) {
  static const char *const multi[] = {"sum", "avg", "min", "max"};
  for (int i = 0; i < 4; i++)
    if (!strcmp(x, multi[i])) return *argc = -1, VM_SUM + i;
  if (!strcmp(x, "ln")) return *argc = 1, VM_F_LOG;
  for (int f = 0; f < VM_F_COUNT; f++)
    if (fun_names[f] && !strcmp(x, fun_names[f])) return *argc = f == VM_F_ATAN2 ? 2 : 1, f;
  return -1;
}

static int is_name(char ch) { return (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || ch == '_'; }
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
  static const int opc[] = {VM_LE, VM_GE, VM_NE, VM_EQ, VM_LT, VM_GT, VM_ADD, VM_SUB, VM_MUL, VM_DIV, VM_POW, VM_AND, VM_OR};
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
      if (opc[i] != VM_ADD && opc[i] != VM_SUB) return refuse(c, "operator '%s' without a left operand", ops[i]);
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
    case '=': return refuse(c, "an assignment ('=') in an expression");
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
    if (!number(s, p, &t->val)) return refuse(c, "a number the bytecode does not read");
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
  return refuse(c, "a token the bytecode does not read at '%.12s'", s + a);
}

/* --- muparser's ParserByteCode ---------------------------------------------- */
static int push_rpn(cc *c, rtok r) {
  if (c->n >= MAXT) return refuse(c, "an expression too long");
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
  if (sz < 2) return refuse(c, "an operator without operands");
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
      if (e == 0) *x = (rtok){R_VAL, 0, 0, 0, -1, 0, 1};
      else if (e == 1) x->cmd = R_VAR;
      else if (e == 2) x->cmd = R_POW2;
      else if (e == 3) x->cmd = R_POW3;
      else if (e == 4) x->cmd = R_POW4;
      else done = 0;
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
  return push_rpn(c, (rtok){R_OP, op, 0, 0, -1, 0, 0});
}

/* ParserByteCode::AddFun: unary plus vanishes; a function of fixed arity
 * whose arguments are all values is folded. */
static int add_fun(cc *c, const tok *f, int argc) {
  if (f->type == T_INFIX && !f->neg) return 0;
  int fun = f->type == T_INFIX ? VM_F_NEG : f->fun;
  if (f->argc == -1) return push_rpn(c, (rtok){R_MULTI, 0, fun, argc, -1, 0, 0});
  if (c->n < argc) return refuse(c, "a function without its arguments");
  int all = 1;
  for (int i = 0; i < argc; i++) all &= c->rpn[c->n - 1 - i].cmd == R_VAL;
  if (!all) return push_rpn(c, (rtok){R_FUNC, 0, fun, argc, -1, 0, 0});
  double v = argc == 2 ? atan2(c->rpn[c->n - 2].data2, c->rpn[c->n - 1].data2) : sds_vm_fun1(fun, c->rpn[c->n - 1].data2);
  c->n -= argc;
  return push_rpn(c, (rtok){R_VAL, 0, 0, 0, -1, 0, v});
}

/* --- muparser's ParserBase::CreateRPN ----------------------------------------- */
static int prec(const tok *t) {
  if (t->type == T_INFIX) return 6;
  if (t->type == T_IF || t->type == T_ELSE) return 0;
  switch (t->op) {
    case VM_OR: return 1;
    case VM_AND: return 2;
    case VM_ADD: case VM_SUB: return 5;
    case VM_MUL: case VM_DIV: return 6;
    case VM_POW: return 7;
    default: return 4; /* comparisons */
  }
}

static int apply_if_else(cc *c, shunt *s) {
  while (s->nopt && s->opt[s->nopt - 1].type == T_ELSE) {
    s->nopt--;
    if (!s->nopt || s->opt[s->nopt - 1].type != T_IF) return refuse(c, "a misplaced ':'");
    s->nopt--;
    if (push_rpn(c, (rtok){R_ENDIF, 0, 0, 0, -1, 0, 0})) return -1;
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
      return refuse(c, "an expression the bytecode does not rebuild");
    }
  }
  return 0;
}

static int build_rpn(cc *c, const char *text, shunt *s) {
  int p = 0, prev = T_NONE, ifs = 0;
  c->n = 0, s->nopt = 0, s->nargc = 1, s->argc[0] = 1;
  for (;;) {
    tok t;
    if (next(c, text, &p, prev, &t)) return -1;
    if (s->nopt >= MAXT - 1 || s->nargc >= MAXT - 1) return refuse(c, "an expression too long");
    switch (t.type) {
      case T_VAR:
        if (push_rpn(c, (rtok){R_VAR, 0, 0, 0, t.slot, 1, 0})) return -1;
        break;
      case T_VAL:
        if (push_rpn(c, (rtok){R_VAL, 0, 0, 0, -1, 0, t.val})) return -1;
        break;
      case T_ELSE:
        if (s->nargc < 2 || s->argc[s->nargc - 1] > 1 || --ifs < 0) return refuse(c, "a misplaced ':'");
        s->nargc--;
        if (apply_remaining(c, s) || push_rpn(c, (rtok){R_ELSE, 0, 0, 0, -1, 0, 0})) return -1;
        s->opt[s->nopt++] = t;
        break;
      case T_SEP:
        if ((s->nopt && s->opt[s->nopt - 1].type == T_IF) || s->nargc < 1) return refuse(c, "a misplaced ','");
        s->argc[s->nargc - 1]++;
        if (apply_remaining(c, s)) return -1;
        break;
      case T_END:
        if (apply_remaining(c, s)) return -1;
        break;
      case T_BC: {
        if (prev == T_BO) return refuse(c, "a function without arguments");
        if (apply_remaining(c, s)) return -1;
        if (!s->nopt || s->opt[s->nopt - 1].type != T_BO) return refuse(c, "unbalanced parentheses");
        int argc = s->argc[--s->nargc];
        s->nopt--;
        int fun = s->nopt && s->opt[s->nopt - 1].type == T_FUNC;
        if (argc > 1 && !fun) return refuse(c, "a comma outside a function's arguments");
        if (fun) {
          tok f = s->opt[--s->nopt];
          if (f.argc > 0 && f.argc != argc) return refuse(c, "a function with the wrong number of arguments");
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
        if (t.type == T_IF && push_rpn(c, (rtok){R_IF, 0, 0, 0, -1, 0, 0})) return -1;
        s->opt[s->nopt++] = t;
        break;
      case T_BO:
        s->argc[s->nargc++] = 1;
        s->opt[s->nopt++] = t;
        break;
      default: /* T_INFIX, T_FUNC */
        s->opt[s->nopt++] = t;
        break;
    }
    prev = t.type;
    if (t.type == T_END) break;
  }
  if (ifs > 0) return refuse(c, "a '?' without its ':'");
  if (s->nopt || s->nargc != 1 || s->argc[0] != 1) return refuse(c, "an expression the bytecode does not rebuild");
  if (!c->n) return refuse(c, "an empty expression");
  return 0;
}

/* --- emission ------------------------------------------------------------------ */
typedef struct out {
  uint32_t *w;
  uint32_t nw, cw;
  double *k;
  uint32_t nk, ck;
} out;

static int grow_w(out *o, uint32_t n) {
  if (o->nw + n <= o->cw) return 0;
  uint32_t cap = o->cw ? 2 * o->cw : 256;
  while (cap < o->nw + n) cap *= 2;
  uint32_t *p = realloc(o->w, cap * sizeof *p);
  if (!p) return -1;
  o->w = p, o->cw = cap;
  return 0;
}

static int add_k(out *o, double v) {
  if (o->nk == o->ck) {
    uint32_t cap = o->ck ? 2 * o->ck : 64;
    double *p = realloc(o->k, cap * sizeof *p);
    if (!p) return -1;
    o->k = p, o->ck = cap;
  }
  o->k[o->nk++] = v;
  return (int)(o->nk - 1);
}

static int emit(out *o, int op, uint32_t a, uint32_t b) {
  if (grow_w(o, 2)) return -1;
  o->w[o->nw++] = (uint32_t)op | a << 8;
  o->w[o->nw++] = b;
  return 0;
}

/* Writes the RPN as instructions; the stack's depth is followed through,
 * each branch of a ?: starting from the depth after its condition. */
static int emit_rpn(cc *c, out *o, sds_prog *p, uint32_t *pc) {
  uint32_t ifs[MAXT], elses[MAXT];
  int nif = 0, nelse = 0, d = 0, dmax = 0, dev = 1;
  *pc = o->nw;
  for (int i = 0; i < c->n; i++) {
    const rtok *r = &c->rpn[i];
    int ka = -1, kb = -1;
    switch (r->cmd) {
      case R_VAL:
        if ((ka = add_k(o, r->data2)) < 0 || emit(o, VM_VAL, 0, (uint32_t)ka)) return -2;
        d++;
        break;
      case R_VAR: case R_POW2: case R_POW3: case R_POW4:
        if (emit(o, r->cmd == R_VAR ? VM_VAR : VM_POW2 + (r->cmd - R_POW2), (uint32_t)r->slot, 0)) return -2;
        d++;
        break;
      case R_VARMUL:
        if ((ka = add_k(o, r->data)) < 0 || (kb = add_k(o, r->data2)) < 0) return -2;
        if (emit(o, VM_VARMUL, (uint32_t)r->slot, (uint32_t)ka)) return -2;
        d++;
        break;
      case R_OP:
        if (r->op == VM_POW && dev) dev = 0, refuse(c, "'^' with a non-constant exponent has no fp64 version on the device");
        if (emit(o, r->op, 0, 0)) return -2;
        d--;
        break;
      case R_FUNC:
        if (r->fun >= VM_F_DEVICE && dev)
          dev = 0, refuse(c, "'%s' has no fp64 version on the device", fun_names[r->fun]);
        if (emit(o, VM_FUN, (uint32_t)r->fun, 0)) return -2;
        d -= r->argc - 1;
        break;
      case R_MULTI:
        if (emit(o, r->fun, (uint32_t)r->argc, 0)) return -2;
        d -= r->argc - 1;
        break;
      case R_IF:
        ifs[nif++] = o->nw;
        if (emit(o, VM_IF, 0, 0)) return -2;
        d--;
        break;
      case R_ELSE:
        if (!nif) return refuse(c, "a misplaced ':'");
        elses[nelse++] = o->nw;
        if (emit(o, VM_JMP, 0, 0)) return -2;
        o->w[ifs[--nif] + 1] = o->nw;
        d--; /* the else branch starts where the then branch did */
        break;
      case R_ENDIF:
        if (!nelse) return refuse(c, "a misplaced ':'");
        o->w[elses[--nelse] + 1] = o->nw;
        break;
      default: return refuse(c, "an expression the bytecode does not rebuild");
    }
    if (d < 1 && r->cmd != R_IF && r->cmd != R_ELSE) return refuse(c, "an expression the bytecode does not rebuild");
    if (d > dmax) dmax = d;
  }
  if (d != 1 || nif || nelse) return refuse(c, "an expression the bytecode does not rebuild");
  if (dmax > SDS_VM_STACK) return refuse(c, "an expression that needs %d stack values (at most %d)", dmax, SDS_VM_STACK);
  if (emit(o, VM_END, 0, 0)) return -2;
  if (dmax > p->depth) p->depth = dmax;
  if (!dev && p->device) {
    p->device = 0;
    snprintf(p->why, sizeof p->why, "%s", c->why);
    c->why[0] = 0;
  }
  return 0;
}

static int compile_expr(cc *c, out *o, sds_prog *p, const char *text, const sds_expr *e, uint32_t *pc) {
  if (!e->h) { /* a plain number: the host never calls muparser for it */
    c->n = 0;
    if (push_rpn(c, (rtok){R_VAL, 0, 0, 0, -1, 0, e->c})) return -1;
  } else if (!text || build_rpn(c, text, &c->s)) {
    if (!text) refuse(c, "no text kept");
    return -1;
  }
  return emit_rpn(c, o, p, pc);
}

sds_prog *sds_prog_compile(const sessile_sds_model *m, char *why, size_t nwhy) {
  why[0] = 0;
  cc *c = calloc(1, sizeof *c); /* the RPN and the shunting-yard's stacks: large */
  sds_prog *p = calloc(1, sizeof *p);
  out o = {0};
  if (!c) {
    free(p);
    snprintf(why, nwhy, "%s: out of host memory for the rules' bytecode", m->file);
    return NULL;
  }
  c->m = m, c->why = why, c->nwhy = nwhy;
  int nrec = 0;
  for (int r = 0; r < m->nrules; r++) nrec += 2 + 2 * m->rules[r].nact;
  int bad = !p || grow_w(&o, (uint32_t)(1 + m->nrules + nrec));
  if (!bad) {
    p->device = 1;
    o.w[0] = (uint32_t)m->nrules;
    o.nw = (uint32_t)(1 + m->nrules + nrec);
  }
  uint32_t at = 1 + (uint32_t)m->nrules;
  for (int r = 0; r < m->nrules && !bad; r++) {
    const sds_rule *R = &m->rules[r];
    c->rule = R->name, c->line = R->line;
    uint32_t rec = at, pc = 0;
    o.w[1 + r] = rec;
    at += 2 + 2 * (uint32_t)R->nact;
    bad = compile_expr(c, &o, p, R->text, &R->cond, &pc) != 0;
    if (bad) break;
    o.w[rec] = pc, o.w[rec + 1] = (uint32_t)R->nact;
    for (int i = 0; i < R->nact && !bad; i++) {
      const sds_action *A = &R->act[i];
      pc = 0;
      if (A->kind != SESSILE_SDS_DIVIDE && A->kind != SESSILE_SDS_RESET)
        bad = compile_expr(c, &o, p, A->text, &A->value, &pc) != 0;
      o.w[rec + 2 + 2 * i] = (uint32_t)A->kind | (uint32_t)A->target << 8 | (uint32_t)(A->sign < 0) << 16;
      o.w[rec + 3 + 2 * i] = pc;
    }
  }
  if (bad) {
    if (!why[0]) snprintf(why, nwhy, "%s: out of host memory for the rules' bytecode", m->file);
    free(o.w), free(o.k), free(p), free(c);
    return NULL;
  }
  free(c);
  p->w = o.w, p->nw = o.nw, p->k = o.k, p->nk = o.nk;
  return p;
}

void sds_prog_free(sds_prog *p) {
  if (!p) return;
  free(p->w), free(p->k), free(p);
}
