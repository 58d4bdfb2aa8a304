/* The rules' expressions to bytecode (rules_vm.h, docs/sds_rules.md,
 * "Bytecode"): each RPN that rules_rpn.c rebuilt from muparser's is written
 * as two-word instructions, its stack depth followed and bounded, and
 * marked host-only when an operation has no fp64 version on the device. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "rules_rpn.h"

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
      case R_VAR:
      case R_POW2:
      case R_POW3:
      case R_POW4:
        if (emit(o, r->cmd == R_VAR ? VM_VAR : VM_POW2 + (r->cmd - R_POW2), (uint32_t)r->slot, 0)) return -2;
        d++;
        break;
      case R_VARMUL:
        if ((ka = add_k(o, r->data)) < 0 || (kb = add_k(o, r->data2)) < 0) return -2;
        if (emit(o, VM_VARMUL, (uint32_t)r->slot, (uint32_t)ka)) return -2;
        d++;
        break;
      case R_OP:
        if (r->op == VM_POW && dev)
          dev = 0, sds_rpn_refuse(c, "'^' with a non-constant exponent has no fp64 version on the device");
        if (emit(o, r->op, 0, 0)) return -2;
        d--;
        break;
      case R_FUNC:
        if (r->fun >= VM_F_DEVICE && dev)
          dev = 0, sds_rpn_refuse(c, "'%s' has no fp64 version on the device", sds_vm_fun_names[r->fun]);
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
        if (!nif) return sds_rpn_refuse(c, "a misplaced ':'");
        elses[nelse++] = o->nw;
        if (emit(o, VM_JMP, 0, 0)) return -2;
        o->w[ifs[--nif] + 1] = o->nw;
        d--; /* the else branch starts where the then branch did */
        break;
      case R_ENDIF:
        if (!nelse) return sds_rpn_refuse(c, "a misplaced ':'");
        o->w[elses[--nelse] + 1] = o->nw;
        break;
      default: return sds_rpn_refuse(c, "an expression the bytecode does not rebuild");
    }
    if (d < 1 && r->cmd != R_IF && r->cmd != R_ELSE)
      return sds_rpn_refuse(c, "an expression the bytecode does not rebuild");
    if (d > dmax) dmax = d;
  }
  if (d != 1 || nif || nelse) return sds_rpn_refuse(c, "an expression the bytecode does not rebuild");
  if (dmax > SDS_VM_STACK)
    return sds_rpn_refuse(c, "an expression that needs %d stack values (at most %d)", dmax, SDS_VM_STACK);
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
    if (sds_rpn_push(c, (rtok){R_VAL, 0, 0, 0, -1, 0, e->c})) return -1;
  } else if (!text || sds_rpn_build(c, text)) {
    if (!text) sds_rpn_refuse(c, "no text kept");
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
