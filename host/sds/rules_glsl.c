/* The rules' bytecode written out as GLSL (rules_glsl.h; docs/sds_rules.md,
 * "Generated kernel"): each expression becomes a function of straight-line
 * code, its stack a chain of temporaries and each ?: an if/else, the
 * operations those of the interpreter (shaders/sds/rules_vm.glsl's vm_run)
 * one for one, `precise` where it has them; the rules and actions are
 * unrolled around rules_vm.glsl's act().  The interpreter's loop branches on
 * each instruction's opcode, which a SIMD device (lavapipe runs a workgroup's
 * lanes in vectors) cannot tell is the same on every lane: it pays for every
 * case of the switch at every instruction.  Here the opcodes are gone. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "rules_glsl.h"
#include "rules_internal.h"
#include "sessile/gpu/gpu.h"

typedef struct gen {
  char *s;
  size_t n, cap;
  const sds_prog *p;
  int tmp;     /* the next temporary's number */
  int bad;     /* 1: out of memory; 2: code the writer does not know */
  char why[160];
} gen;

static void out(gen *g, const char *fmt, ...) {
  if (g->bad) return;
  va_list ap;
  for (;;) {
    size_t room = g->cap - g->n;
    va_start(ap, fmt);
    int k = vsnprintf(g->s ? g->s + g->n : NULL, g->s ? room : 0, fmt, ap);
    va_end(ap);
    if (k < 0) {
      g->bad = 1;
      return;
    }
    if (g->s && (size_t)k < room) {
      g->n += (size_t)k;
      return;
    }
    size_t cap = g->cap ? 2 * g->cap : 8192;
    while (cap < g->n + (size_t)k + 1) cap *= 2;
    char *q = realloc(g->s, cap);
    if (!q) {
      g->bad = 1;
      return;
    }
    g->s = q, g->cap = cap;
  }
}

static int refuse(gen *g, uint32_t at, const char *what) {
  if (!g->bad) g->bad = 2, snprintf(g->why, sizeof g->why, "%s at word %u of the bytecode", what, at);
  return -1;
}

/* Writes the instructions from p up to `stop` (a branch's end) or VM_END,
 * with the stack st[0 .. *sp] of temporaries; *end: where it stopped. */
static int block(gen *g, uint32_t p, uint32_t stop, int *st, int *sp, uint32_t *end) {
  const uint32_t *w = g->p->w;
  uint32_t nw = g->p->nw;
  while (p != stop) {
    if (p + 1 >= nw) return refuse(g, p, "code past the end");
    uint32_t op = w[p] & 255u, a = w[p] >> 8, b = w[p + 1];
    int t = g->tmp++;
    if (op == VM_END) {
      if (stop != UINT32_MAX) return refuse(g, p, "an end inside a branch");
      *end = p;
      return 0;
    }
    int need = op >= VM_ADD && op <= VM_OR ? 2 : op == VM_IF || op == VM_FUN ? 1 : op >= VM_SUM ? (int)a : 0;
    if (*sp + 1 < need || (op >= VM_SUM && a == 0)) return refuse(g, p, "a stack too shallow");
    if (*sp + 2 > SDS_VM_STACK + 1) return refuse(g, p, "a stack too deep");
    if ((op == VM_VAL && b >= g->p->nk) || (op == VM_VARMUL && b + 1 >= g->p->nk))
      return refuse(g, p, "a constant past the table");
    if ((op == VM_VAR || op == VM_VARMUL || (op >= VM_POW2 && op <= VM_POW4)) && a >= SDS_VM_SLOTS)
      return refuse(g, p, "a slot past the table");
    p += 2;
    switch (op) {
      case VM_VAL: out(g, "  REAL t%d = konst[%uu];\n", t, b); break;
      case VM_VAR: out(g, "  REAL t%d = slot_of(c, %uu);\n", t, a); break;
      case VM_VARMUL:
        out(g, "  precise REAL t%da = slot_of(c, %uu) * konst[%uu];\n  precise REAL t%d = t%da + konst[%uu];\n", t, a,
            b, t, t, b + 1);
        break;
      case VM_POW2:
      case VM_POW3:
      case VM_POW4:
        out(g, "  REAL t%da = slot_of(c, %uu);\n  precise REAL t%d = t%da * t%da;\n", t, a, t, t, t);
        for (uint32_t k = VM_POW2; k < op; k++) out(g, "  t%d = t%d * t%da;\n", t, t, t);
        break;
      case VM_ADD: case VM_SUB: case VM_MUL: case VM_DIV: case VM_LT: case VM_GT: case VM_LE: case VM_GE:
      case VM_NE: case VM_EQ: case VM_AND: case VM_OR: {
        int x = st[*sp - 1], y = st[*sp];
        *sp -= 2;
        static const char *const arith[] = {"+", "-", "*", "/"}, *const cmp[] = {"<", ">", "<=", ">="};
        if (op <= VM_DIV) out(g, "  precise REAL t%d = t%d %s t%d;\n", t, x, arith[op - VM_ADD], y);
        else if (op <= VM_GE) out(g, "  REAL t%d = b2r(t%d %s t%d);\n", t, x, cmp[op - VM_LT], y);
        else if (op == VM_NE) out(g, "  REAL t%d = b2r(!(t%d == t%d));\n", t, x, y);
        else if (op == VM_EQ) out(g, "  REAL t%d = b2r(t%d == t%d);\n", t, x, y);
        else
          out(g, "  REAL t%d = b2r(!(t%d == REAL(0)) %s !(t%d == REAL(0)));\n", t, x, op == VM_AND ? "&&" : "||", y);
        break;
      }
      case VM_FUN: {
        int x = st[(*sp)--];
        if (a == VM_F_NEG) out(g, "  REAL t%d = -t%d;\n", t, x);
        else if (a == VM_F_ABS) out(g, "  REAL t%d = (t%d >= REAL(0)) ? t%d : -t%d;\n", t, x, x, x);
        else if (a == VM_F_SIGN)
          out(g, "  REAL t%d = (t%d < REAL(0)) ? REAL(-1) : (t%d > REAL(0)) ? REAL(1) : REAL(0);\n", t, x, x);
        else if (a == VM_F_RINT) out(g, "  precise REAL t%da = t%d + REAL(0.5);\n  REAL t%d = floor(t%da);\n", t, x, t, t);
        else if (a == VM_F_SQRT) out(g, "  REAL t%d = sqrt(t%d);\n", t, x);
        else return refuse(g, p - 2, "a function without a device version");
        break;
      }
      case VM_SUM: case VM_AVG: case VM_MIN: case VM_MAX: {
        int lo = *sp - (int)a + 1;
        if (op == VM_MIN || op == VM_MAX) out(g, "  precise REAL t%d = t%d;\n", t, st[lo]);
        else out(g, "  precise REAL t%d = REAL(0);\n", t);
        for (int i = 0; i < (int)a; i++) {
          int v = st[lo + i];
          if (op == VM_MIN) out(g, "  t%d = (t%d < t%d) ? t%d : t%d;\n", t, v, t, v, t);
          else if (op == VM_MAX) out(g, "  t%d = (t%d < t%d) ? t%d : t%d;\n", t, t, v, v, t);
          else out(g, "  t%d = t%d + t%d;\n", t, t, v);
        }
        if (op == VM_AVG) out(g, "  t%d = t%d / REAL(%u);\n", t, t, a);
        *sp = lo - 1;
        break;
      }
      case VM_IF: { /* cond IF(else) then.. JMP(end) else.. end: if (cond != 0) then else */
        int x = st[(*sp)--];
        if (b < p + 2 || b > nw || (w[b - 2] & 255u) != VM_JMP || w[b - 1] < b || w[b - 1] > nw)
          return refuse(g, p - 2, "a ?: the writer does not know");
        uint32_t stop_else = w[b - 1], e;
        int d0 = *sp;
        out(g, "  REAL t%d;\n  if (!(t%d == REAL(0))) {\n", t, x);
        if (block(g, p, b - 2, st, sp, &e) || *sp != d0 + 1) return refuse(g, p - 2, "a ?: branch not one value");
        out(g, "  t%d = t%d;\n  } else {\n", t, st[(*sp)--]);
        if (block(g, b, stop_else, st, sp, &e) || *sp != d0 + 1) return refuse(g, p - 2, "a ?: branch not one value");
        out(g, "  t%d = t%d;\n  }\n", t, st[(*sp)--]);
        p = stop_else;
        break;
      }
      default: return refuse(g, p - 2, "an operation without a device version");
    }
    st[++*sp] = t;
    if (p > nw) return refuse(g, p, "code past the end");
  }
  *end = p;
  return 0;
}

/* REAL e<pc>(uint c): the expression at pc. */
static void expr(gen *g, uint32_t pc) {
  int st[SDS_VM_STACK + 2], sp = -1;
  uint32_t end;
  out(g, "REAL e%u(uint c) {\n", pc);
  if (block(g, pc, UINT32_MAX, st, &sp, &end) == 0 && sp != 0) refuse(g, pc, "an expression not one value");
  if (!g->bad) out(g, "  return t%d;\n}\n", st[0]);
}

char *sds_rules_glsl(const sds_prog *p, const char *shell, char *why, size_t nwhy) {
  gen g = {.p = p};
  why[0] = 0;
  if (!p->device) {
    snprintf(why, nwhy, "%s", p->why);
    return NULL;
  }
  const uint32_t *w = p->w;
  uint32_t nrules = p->nw ? w[0] : 0;
  out(&g, "// Generated from the model's rules by host/sds/rules_glsl.c.\n#define SDS_RULES_GEN 1\n"
          "#include \"%s\"\n\n", shell);
  for (uint32_t r = 0; r < nrules && !g.bad; r++) {
    uint32_t rec = w[1 + r];
    if (rec + 1 >= p->nw || rec + 2 + 2 * w[rec + 1] > p->nw) {
      refuse(&g, 1 + r, "a rule record past the end");
      break;
    }
    expr(&g, w[rec]);
    for (uint32_t i = 0; i < w[rec + 1] && !g.bad; i++) {
      uint32_t kind = w[rec + 2 + 2 * i] & 255u;
      if (kind != SESSILE_SDS_DIVIDE && kind != SESSILE_SDS_RESET) expr(&g, w[rec + 3 + 2 * i]);
    }
  }
  out(&g, "\nvoid evaluate_gen(uint c) {\n  cell_acc e = acc_begin(c);\n  REAL v;\n");
  for (uint32_t r = 0; r < nrules && !g.bad; r++) {
    uint32_t rec = w[1 + r];
    out(&g, "  v = e%u(c); // rule %u\n  if (isnan(v)) {\n    numeric(c, e.base);\n    return;\n  }\n"
            "  if (!(v == REAL(0))) {\n", w[rec], r);
    for (uint32_t i = 0; i < w[rec + 1]; i++) {
      uint32_t kw = w[rec + 2 + 2 * i], kind = kw & 255u;
      if (kind != SESSILE_SDS_DIVIDE && kind != SESSILE_SDS_RESET)
        out(&g, "    v = e%u(c);\n    if (!is_finite(v)) {\n      numeric(c, e.base);\n      return;\n    }\n"
                "    act(c, %uu, %uu, v, e);\n", w[rec + 3 + 2 * i], r, kw);
      else
        out(&g, "    act(c, %uu, %uu, REAL(0), e);\n", r, kw);
    }
    out(&g, "  }\n");
  }
  out(&g, "  acc_end(c, e);\n}\n");
  if (g.bad) {
    snprintf(why, nwhy, "%s", g.bad == 1 ? "out of host memory for the rules' GLSL" : g.why);
    free(g.s);
    return NULL;
  }
  return g.s;
}

/* The kernel of declaration id around the shader file `shell`, compiled. */
static sessile_status spirv_of(const sessile_sds_model *m, int id, const char *shell, uint32_t **words, size_t *n) {
  char w[320];
  char *body = sds_rules_glsl(m->prog, shell, w, sizeof w);
  SESSILE_CHECK(body, SESSILE_ERR_INTERNAL, "the rules' generated kernel: %s", w);
  char log[1024];
  sessile_status st = sessile_glsl_to_spirv(sessile_sds_kernels[id].name, 1, body, words, n, log, sizeof log);
  free(body);
  if (st != SESSILE_OK) return sessile_error_set(SESSILE_ERR_INTERNAL, "the rules' generated kernel (%s): %s", shell, log);
  return SESSILE_OK;
}

sessile_status sessile_sds_model_rules_spirv(const sessile_sds_model *m, uint32_t **words, size_t *n) {
  *words = NULL, *n = 0;
  const char *why = sessile_sds_model_bytecode_refusal(m, 1);
  SESSILE_CHECK(!why, SESSILE_ERR_USAGE, "the rules on the device: %s", why);
  if (m->nmorph) { /* the batch's rules with their first sub-step (rules_morph.glsl) must compile too */
    uint32_t *fw = NULL;
    size_t fn = 0;
    SESSILE_CALL(spirv_of(m, SDS_RULES_MORPH, "rules_morph.glsl", &fw, &fn));
    free(fw);
  }
  return spirv_of(m, SDS_RULES_VM, "rules_vm.glsl", words, n);
}
