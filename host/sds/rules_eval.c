/* Rule evaluation on the host, one cell after another in ascending index,
 * rules in file order, every condition and value reading the state at the
 * start of the step (docs/sds_rules.md).  Host evaluation is a choice: a
 * few compiled muparser expressions per cell cost far less than the physics
 * step on the GPU, and keep the language open (any muparser function). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "rules_internal.h"
#include "rules_vm.h"

void sessile_sds_actions_free(sessile_sds_actions *a) {
  if (!a) return;
  free(a->grow), free(a->produce), free(a->sets), free(a->divides);
  memset(a, 0, sizeof *a);
}

static sessile_status reset(sessile_sds_actions *a, int ncells, int nmorph) {
  if (a->ncells != ncells || a->nmorph != nmorph || !a->grow) {
    free(a->grow), free(a->produce);
    a->grow = calloc((size_t)ncells + 1, sizeof *a->grow);
    a->produce = calloc((size_t)ncells * (nmorph > 0 ? nmorph : 1) + 1, sizeof *a->produce);
    a->ncells = ncells, a->nmorph = nmorph;
    SESSILE_CHECK(a->grow && a->produce, SESSILE_ERR_NO_MEMORY, "out of host memory for %d cells' actions", ncells);
  } else {
    memset(a->grow, 0, sizeof *a->grow * (size_t)ncells);
    memset(a->produce, 0, sizeof *a->produce * (size_t)ncells * nmorph);
  }
  a->nsets = a->ndivides = a->fired = 0;
  return SESSILE_OK;
}

static sessile_status push_set(sessile_sds_actions *a, sessile_sds_set s) {
  if (a->nsets == a->cap_sets) {
    size_t cap = a->cap_sets ? 2 * a->cap_sets : 64;
    sessile_sds_set *p = realloc(a->sets, cap * sizeof *p);
    SESSILE_CHECK(p, SESSILE_ERR_NO_MEMORY, "out of host memory for %zu set actions", cap);
    a->sets = p, a->cap_sets = cap;
  }
  a->sets[a->nsets++] = s;
  return SESSILE_OK;
}

static sessile_status push_divide(sessile_sds_actions *a, sessile_sds_divide d) {
  if (a->ndivides == a->cap_divides) {
    size_t cap = a->cap_divides ? 2 * a->cap_divides : 16;
    sessile_sds_divide *p = realloc(a->divides, cap * sizeof *p);
    SESSILE_CHECK(p, SESSILE_ERR_NO_MEMORY, "out of host memory for %zu divisions", cap);
    a->divides = p, a->cap_divides = cap;
  }
  a->divides[a->ndivides++] = d;
  return SESSILE_OK;
}

/* An expression by muparser, or (vm) by the bytecode at pc. */
static double expr(const sessile_sds_model *m, int vm, const sds_expr *e, uint32_t pc) {
  return vm ? sds_vm_run(m->prog, pc, m->slot) : sessile_expr_eval(e);
}

static sessile_status eval(const sessile_sds_model *cm, const sessile_morph_cells *cl, const double *phi,
                           const double *state, double time, sessile_sds_actions *out, int vm) {
  sessile_sds_model *m = (sessile_sds_model *)cm; /* the slots are scratch */
  const uint32_t *w = vm ? m->prog->w : NULL;
  SESSILE_CHECK(cl->ncells >= 0 && (m->nmorph == 0 || phi) && (m->nstate == 0 || state), SESSILE_ERR_USAGE,
                "rules: missing morphogen or state arrays");
  SESSILE_CALL(reset(out, cl->ncells, m->nmorph));
  int nm = m->nmorph, ns = m->nstate;
  m->slot[SDS_SLOT_TIME] = time;
  for (int c = 0; c < cl->ncells; c++) {
    m->slot[SDS_SLOT_RADIUS] = cl->radius[c];
    m->slot[SDS_SLOT_VOLUME] = sessile_morph_vol(cl->radius[c]);
    m->slot[SDS_SLOT_SURFACE] = cl->surface ? cl->surface[c] != 0 : 0;
    for (int k = 0; k < nm; k++) m->slot[SDS_SLOT_MORPH + k] = phi[(size_t)c * nm + k];
    for (int k = 0; k < ns; k++) m->slot[SDS_SLOT_STATE + k] = state[(size_t)c * ns + k];
    int divided = 0;
    for (int r = 0; r < m->nrules; r++) {
      const sds_rule *R = &m->rules[r];
      uint32_t rec = vm ? w[1 + r] : 0;
      double v = expr(m, vm, &R->cond, vm ? w[rec] : 0);
      SESSILE_CHECK(!isnan(v), SESSILE_ERR_NUMERIC, "%s:%d: rule %s: the condition is NaN at cell %d", m->file,
                    R->line, R->name, c);
      if (v == 0) continue;
      out->fired++;
      for (int i = 0; i < R->nact; i++) {
        const sds_action *A = &R->act[i];
        double x = 0;
        if (A->kind != SESSILE_SDS_DIVIDE && A->kind != SESSILE_SDS_RESET) {
          x = expr(m, vm, &A->value, vm ? w[rec + 3 + 2 * i] : 0);
          SESSILE_CHECK(isfinite(x), SESSILE_ERR_NUMERIC, "%s:%d: rule %s: action %d gives %g at cell %d", m->file,
                        R->line, R->name, i + 1, x, c);
        }
        switch (A->kind) {
          case SESSILE_SDS_SET_MORPH:
          case SESSILE_SDS_SET_STATE:
            SESSILE_CALL(push_set(out, (sessile_sds_set){c, A->kind, A->target, x}));
            break;
          case SESSILE_SDS_RESET:
            SESSILE_CALL(push_set(out, (sessile_sds_set){c, A->kind, A->target, m->mstart[A->target]}));
            break;
          case SESSILE_SDS_PRODUCE: out->produce[(size_t)c * nm + A->target] += x; break;
          case SESSILE_SDS_GROW: out->grow[c] += x; break;
          case SESSILE_SDS_DIVIDE:
            if (!divided) {
              sessile_sds_divide d = {c, r, {0, 0, 0}};
              double g[3];
              if (sessile_morph_gradient(cl, nm, phi, c, A->target, g)) {
                double l = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
                for (int a = 0; a < 3; a++) d.dir[a] = A->sign * g[a] / l;
              }
              SESSILE_CALL(push_divide(out, d));
              divided = 1;
            }
            break;
          default: break;
        }
      }
    }
  }
  return SESSILE_OK;
}

sessile_status sessile_sds_rules_eval(const sessile_sds_model *m, const sessile_morph_cells *cl, const double *phi,
                                      const double *state, double time, sessile_sds_actions *out) {
  return eval(m, cl, phi, state, time, out, 0);
}

sessile_status sessile_sds_rules_eval_vm(const sessile_sds_model *m, const sessile_morph_cells *cl,
                                         const double *phi, const double *state, double time,
                                         sessile_sds_actions *out) {
  SESSILE_CHECK(m->prog, SESSILE_ERR_USAGE, "%s", m->prog_why);
  return eval(m, cl, phi, state, time, out, 1);
}

const char *sessile_sds_model_bytecode_refusal(const sessile_sds_model *m, int device) {
  if (!m->prog) return m->prog_why;
  return device && !m->prog->device ? m->prog->why : NULL;
}

void sessile_sds_actions_apply(const sessile_sds_model *m, const sessile_sds_actions *a, double dt, double *radius,
                               double *phi, double *state) {
  int nm = m->nmorph, ns = m->nstate;
  for (int c = 0; c < a->ncells; c++) radius[c] += dt * a->grow[c];
  for (size_t i = 0; i < a->nsets; i++) {
    const sessile_sds_set *s = &a->sets[i];
    if (s->kind == SESSILE_SDS_SET_STATE) {
      state[(size_t)s->cell * ns + s->target] = s->value;
    } else {
      double v = fmax(s->value, 0.0);
      if (m->capped[s->target]) v = fmin(v, sessile_morph_vol(radius[s->cell]));
      phi[(size_t)s->cell * nm + s->target] = v;
    }
  }
}
