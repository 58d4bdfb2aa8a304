/* The plain-C interpreter of the rules' bytecode (rules_vm.h), the
 * reference of shaders/sds/rules_vm.glsl.  Every operation is muparser's
 * (ParserBase::ParseCmdCodeBulk and MathImpl, muparser 2.3), so a rule gives
 * the host evaluator's doubles bit for bit (tests/sds/test_rules_vm.c). */
#include <math.h>
#include "rules_vm.h"

double sds_vm_fun1(int f, double v) {
  switch (f) {
    case VM_F_NEG: return -v;
    case VM_F_ABS: return (v >= 0) ? v : -v;
    case VM_F_SIGN: return (v < 0) ? -1 : (v > 0) ? 1 : 0;
    case VM_F_RINT: return floor(v + 0.5);
    case VM_F_SQRT: return sqrt(v);
    case VM_F_SIN: return sin(v);
    case VM_F_COS: return cos(v);
    case VM_F_TAN: return tan(v);
    case VM_F_ASIN: return asin(v);
    case VM_F_ACOS: return acos(v);
    case VM_F_ATAN: return atan(v);
    case VM_F_SINH: return sinh(v);
    case VM_F_COSH: return cosh(v);
    case VM_F_TANH: return tanh(v);
    case VM_F_ASINH: return log(v + sqrt(v * v + 1));
    case VM_F_ACOSH: return log(v + sqrt(v * v - 1));
    case VM_F_ATANH: return 0.5 * log((1 + v) / (1 - v));
    case VM_F_LOG2: return log(v) / log(2.0);
    case VM_F_LOG10: return log10(v);
    case VM_F_LOG: return log(v);
    case VM_F_EXP: return exp(v);
    default: return NAN;
  }
}

/* sum, avg, min, max over n values (MathImpl::Sum ...: min and max start
 * from the first value and compare it with itself, as std::min does). */
static double multi(int op, const double *a, int n) {
  double r = op == VM_MIN || op == VM_MAX ? a[0] : 0;
  for (int i = 0; i < n; i++) {
    if (op == VM_MIN) r = (a[i] < r) ? a[i] : r;
    else if (op == VM_MAX) r = (r < a[i]) ? a[i] : r;
    else r += a[i];
  }
  return op == VM_AVG ? r / (double)n : r;
}

double sds_vm_run(const sds_prog *p, uint32_t pc, const double *slots) {
  double st[SDS_VM_STACK + 1];
  int sp = -1;
  const uint32_t *w = p->w;
  const double *k = p->k;
  for (;;) {
    uint32_t op = w[pc] & 255u, a = w[pc] >> 8, b = w[pc + 1];
    pc += 2;
    double x = 0, y = 0;
    if (op >= VM_ADD && op <= VM_OR) y = st[sp--], x = st[sp];
    switch (op) {
      case VM_END: return st[sp];
      case VM_VAL: st[++sp] = k[b]; break;
      case VM_VAR: st[++sp] = slots[a]; break;
      case VM_VARMUL: st[++sp] = slots[a] * k[b] + k[b + 1]; break;
      case VM_POW2: x = slots[a], st[++sp] = x * x; break;
      case VM_POW3: x = slots[a], st[++sp] = x * x * x; break;
      case VM_POW4: x = slots[a], st[++sp] = x * x * x * x; break;
      case VM_ADD: st[sp] = x + y; break;
      case VM_SUB: st[sp] = x - y; break;
      case VM_MUL: st[sp] = x * y; break;
      case VM_DIV: st[sp] = x / y; break;
      case VM_POW: st[sp] = pow(x, y); break;
      case VM_LT: st[sp] = x < y; break;
      case VM_GT: st[sp] = x > y; break;
      case VM_LE: st[sp] = x <= y; break;
      case VM_GE: st[sp] = x >= y; break;
      case VM_NE: st[sp] = x != y; break;
      case VM_EQ: st[sp] = x == y; break;
      case VM_AND: st[sp] = x != 0 && y != 0; break;
      case VM_OR: st[sp] = x != 0 || y != 0; break;
      case VM_IF:
        if (st[sp--] == 0) pc = b;
        break;
      case VM_JMP: pc = b; break;
      case VM_FUN:
        if (a == VM_F_ATAN2) sp--, st[sp] = atan2(st[sp], st[sp + 1]);
        else st[sp] = sds_vm_fun1((int)a, st[sp]);
        break;
      default: /* VM_SUM .. VM_MAX */
        sp -= (int)a - 1;
        st[sp] = multi((int)op, &st[sp], (int)a);
        break;
    }
  }
}
