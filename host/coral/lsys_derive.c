/* Parallel rewriting of a module string (docs/lsystem.md "Derivation"):
 * each module is replaced by the successor of the first production whose
 * predecessor, contexts and condition hold, or, when that production carries
 * a weight, by one of all the matching weighted productions chosen with
 * probability w / sum(w) from the one stream; no match copies the module.
 * Contexts skip the `ignore:` symbols and branches the ABOP way (right:
 * over bracketed sub-branches; left: over completed branches and up to the
 * parent).  '%' then cuts the rest of its branch. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "lsys_internal.h"
#include "sessile/rng.h"

void sessile_lsys_string_free(sessile_lsys_string *s) {
  if (!s) return;
  free(s->sym), free(s->np), free(s->off), free(s->par);
  memset(s, 0, sizeof *s);
}

double *lsys_string_push(sessile_lsys_string *s, uint8_t sym, uint8_t np) {
  if (s->n == s->cap) {
    if (s->cap >= UINT32_MAX / 2) return NULL;
    uint32_t cap = s->cap ? 2 * s->cap : 256;
    uint8_t *a = realloc(s->sym, cap);
    if (!a) return NULL;
    s->sym = a;
    uint8_t *b = realloc(s->np, cap);
    if (!b) return NULL;
    s->np = b;
    uint32_t *o = realloc(s->off, (size_t)cap * sizeof *o);
    if (!o) return NULL;
    s->off = o;
    s->cap = cap;
  }
  if (!s->par || s->npar + np > s->parcap) {
    size_t cap = s->parcap ? 2 * s->parcap : 256;
    while (cap < s->npar + np) cap *= 2;
    if (cap > UINT32_MAX) return NULL;
    double *p = realloc(s->par, cap * sizeof *p);
    if (!p) return NULL;
    s->par = p, s->parcap = cap;
  }
  uint32_t i = s->n++;
  s->sym[i] = sym, s->np[i] = np, s->off[i] = (uint32_t)s->npar;
  double *p = s->par + s->npar;
  s->npar += np;
  return p;
}

/* The refusal, with the step's estimated size: modules and bytes (6 per
 * module plus 8 per parameter, at the string's mean parameter count). */
static sessile_status too_long(const sessile_lsys_string *out, uint64_t max_modules, double estimate) {
  double per = 6 + 8.0 * (out->n ? (double)out->npar / out->n : 0);
  return sessile_error_set(SESSILE_ERR_TOO_LARGE,
                           "the derivation would exceed max_modules = %llu (reached %u modules, estimate %.3g "
                           "modules, about %.3g MB): use fewer iterations or raise max_modules",
                           (unsigned long long)max_modules, out->n, estimate, estimate * per * 1e-6);
}

sessile_status lsys_emit(const sessile_lsys *g, uint32_t first, uint32_t n, int line, sessile_lsys_string *out,
                         uint64_t max_modules) {
  for (uint32_t k = 0; k < n; k++) {
    const lsys_tpl *t = &g->tpl[first + k];
    if ((uint64_t)out->n + 1 > max_modules) return too_long(out, max_modules, (double)out->n + 1);
    double *p = lsys_string_push(out, t->sym, t->np);
    SESSILE_CHECK(p, SESSILE_ERR_NO_MEMORY, "out of host memory for a string of %u modules", out->n);
    for (uint8_t a = 0; a < t->np; a++) {
      p[a] = sessile_expr_eval(&g->exprs[t->first + a]);
      SESSILE_CHECK(isfinite(p[a]), SESSILE_ERR_USAGE, "%s:%d: module '%c' got a non-finite parameter (%g)", g->where,
                    line, t->sym, p[a]);
    }
  }
  return SESSILE_OK;
}

static void bind(double *slots, const lsys_pat *pt, const sessile_lsys_string *s, uint32_t i) {
  memcpy(slots + pt->slot, s->par + s->off[i], pt->np * sizeof *slots);
}

/* Right context: from i + 1, skipping ignored symbols and whole [ ... ]
 * sub-branches; a ']' ends the branch and fails the match.  A '[' in the
 * pattern enters the next sub-branch (the first one: no backtracking over
 * siblings), a ']' in the pattern skips the rest of the entered branch. */
static int match_right(const lsys_prod *p, const sessile_lsys_string *s, const int32_t *mate, const uint8_t *ign,
                       uint32_t i) {
  uint32_t j = i + 1;
  for (int k = 0; k < p->nright; k++) {
    uint8_t want = p->right[k].sym;
    if (want == '[') {
      while (j < s->n && s->sym[j] != '[' && ign[s->sym[j]]) j++;
      if (j >= s->n || s->sym[j] != '[' || mate[j] < 0) return 0;
      j++;
      continue;
    }
    if (want == ']') {
      int depth = 0; /* to the ']' closing the entered branch */
      for (; j < s->n; j++) {
        if (s->sym[j] == '[') depth++;
        else if (s->sym[j] == ']' && depth-- == 0) break;
      }
      if (j >= s->n) return 0;
      j++;
      continue;
    }
    while (j < s->n) {
      uint8_t c = s->sym[j];
      if (c == '[' && mate[j] >= 0) j = (uint32_t)mate[j] + 1;
      else if (ign[c]) j++;
      else break;
    }
    if (j >= s->n || s->sym[j] == ']') return 0;
    if (s->sym[j] != want || s->np[j] != p->right[k].np) return 0;
    bind(p->slots, &p->right[k], s, j);
    j++;
  }
  return 1;
}

/* Left context: back from i - 1, skipping ignored symbols and completed
 * branches ([ ... ] before i), and climbing out of the current branch
 * through its '[' to the parent module. */
static int match_left(const lsys_prod *p, const sessile_lsys_string *s, const int32_t *mate, const uint8_t *ign,
                      uint32_t i) {
  int64_t j = (int64_t)i - 1;
  for (int k = p->nleft - 1; k >= 0; k--) {
    while (j >= 0) {
      uint8_t c = s->sym[j];
      if (c == ']' && mate[j] >= 0) j = mate[j] - 1;
      else if (c == '[' || ign[c]) j--;
      else break;
    }
    if (j < 0 || s->sym[j] == ']') return 0;
    if (s->sym[j] != p->left[k].sym || s->np[j] != p->left[k].np) return 0;
    bind(p->slots, &p->left[k], s, (uint32_t)j);
    j--;
  }
  return 1;
}

/* mate[j]: the matching bracket of a '[' or ']', -1 when unmatched. */
static sessile_status brackets(const sessile_lsys_string *s, int32_t **mate_out) {
  int32_t *mate = malloc((size_t)(s->n ? s->n : 1) * sizeof *mate);
  int32_t *stack = malloc((size_t)(s->n ? s->n : 1) * sizeof *stack);
  if (!mate || !stack) {
    free(mate), free(stack);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for %u modules' brackets", s->n);
  }
  uint32_t top = 0;
  for (uint32_t j = 0; j < s->n; j++) {
    mate[j] = -1;
    if (s->sym[j] == '[') stack[top++] = (int32_t)j;
    else if (s->sym[j] == ']' && top) {
      int32_t o = stack[--top];
      mate[j] = o, mate[o] = (int32_t)j;
    }
  }
  free(stack);
  *mate_out = mate;
  return SESSILE_OK;
}

/* '%': removes itself and the rest of its branch, keeping the closing ']'. */
static void cut(sessile_lsys_string *s) {
  uint32_t w = 0;
  size_t pw = 0;
  for (uint32_t r = 0; r < s->n; r++) {
    if (s->sym[r] == '%') {
      int depth = 0;
      for (r++; r < s->n; r++) {
        if (s->sym[r] == '[') depth++;
        else if (s->sym[r] == ']' && depth-- == 0) break;
      }
      if (r == s->n) break;
    }
    uint8_t np = s->np[r];
    memmove(s->par + pw, s->par + s->off[r], np * sizeof *s->par);
    s->sym[w] = s->sym[r], s->np[w] = np, s->off[w] = (uint32_t)pw;
    w++, pw += np;
  }
  s->n = w, s->npar = pw;
}

static sessile_status step(const sessile_lsys *g, int set, const sessile_lsys_string *in, uint64_t max_modules,
                           sessile_lsys_string *out) {
  int32_t *mate = NULL;
  if (g->has_context) SESSILE_CALL(brackets(in, &mate));
  out->n = 0, out->npar = 0;
  sessile_status st = SESSILE_OK;
  uint32_t cand[LSYS_MAX_PRODS];
  double w[LSYS_MAX_PRODS];
  for (uint32_t i = 0; i < in->n && st == SESSILE_OK; i++) {
    uint8_t c = in->sym[i];
    uint32_t nb = g->by_count[set][c], nc = 0;
    int chosen = -1;
    double total = 0;
    for (uint32_t k = 0; k < nb; k++) {
      const lsys_prod *p = &g->prods[g->by_list[g->by_first[set][c] + k]];
      if (p->pred_np != in->np[i]) continue;
      memcpy(p->slots + p->pred_slot, in->par + in->off[i], p->pred_np * sizeof *p->slots);
      if (p->nleft && !match_left(p, in, mate, g->ignore, i)) continue;
      if (p->nright && !match_right(p, in, mate, g->ignore, i)) continue;
      if (p->has_cond) {
        double cv = sessile_expr_eval(&p->cond);
        if (isnan(cv)) { /* neither true nor false: refused, not taken as true */
          st = sessile_error_set(SESSILE_ERR_USAGE, "%s:%d: the condition came out NaN", g->where, p->line);
          break;
        }
        if (cv == 0) continue;
      }
      if (!p->has_weight) {
        if (nc == 0) chosen = (int)(p - g->prods);
        if (nc == 0) break;
        continue; /* after a weighted first match only weighted ones compete */
      }
      double wt = sessile_expr_eval(&p->weight);
      if (!isfinite(wt)) {
        st = sessile_error_set(SESSILE_ERR_USAGE, "%s:%d: the weight came out %g", g->where, p->line, wt);
        break;
      }
      if (!(wt > 0)) continue;
      cand[nc] = (uint32_t)(p - g->prods), w[nc++] = wt, total += wt;
    }
    if (st != SESSILE_OK) break;
    if (chosen < 0 && nc == 1) chosen = (int)cand[0];
    else if (chosen < 0 && nc > 1) {
      double u = sessile_rng_uniform(g->rng) * total, acc = 0;
      chosen = (int)cand[nc - 1];
      for (uint32_t k = 0; k < nc; k++)
        if (u < (acc += w[k])) {
          chosen = (int)cand[k];
          break;
        }
    }
    if (chosen < 0) { /* identity */
      if ((uint64_t)out->n + 1 > max_modules) {
        st = too_long(out, max_modules, (double)out->n * in->n / (i + 1));
        break;
      }
      double *p = lsys_string_push(out, c, in->np[i]);
      if (!p) {
        st = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for a string of %u modules", out->n);
        break;
      }
      memcpy(p, in->par + in->off[i], in->np[i] * sizeof *p);
      continue;
    }
    const lsys_prod *p = &g->prods[chosen];
    /* the chosen production's slots may have been overwritten by no later
     * candidate: each production owns its slots */
    st = lsys_emit(g, p->succ_first, p->nsucc, p->line, out, max_modules);
    if (st == SESSILE_ERR_TOO_LARGE)
      st = too_long(out, max_modules, (double)out->n * in->n / (i + 1));
  }
  free(mate);
  if (st == SESSILE_OK && g->has_cut) cut(out);
  return st;
}

sessile_status sessile_lsys_step(const sessile_lsys *g, const sessile_lsys_string *in, uint64_t *rng,
                                 uint64_t max_modules, sessile_lsys_string *out) {
  sessile_lsys *gm = (sessile_lsys *)g; /* the stream uniform() reads: set for this call only */
  gm->rng = rng;
  sessile_status s = step(g, LSYS_DERIVATION, in, max_modules, out);
  gm->rng = NULL;
  return s;
}

sessile_status sessile_lsys_homomorphism(const sessile_lsys *g, const sessile_lsys_string *in, uint64_t *rng,
                                         uint64_t max_modules, sessile_lsys_string *out) {
  sessile_lsys *gm = (sessile_lsys *)g;
  gm->rng = rng;
  sessile_status s = step(g, LSYS_HOMOMORPHISM, in, max_modules, out);
  gm->rng = NULL;
  return s;
}

sessile_status sessile_lsys_derive(const sessile_lsys *g, int iterations, uint64_t *rng, uint64_t max_modules,
                                   sessile_lsys_string *out) {
  sessile_lsys *gm = (sessile_lsys *)g;
  sessile_lsys_string a = {0}, b = {0};
  gm->rng = rng;
  sessile_status s = lsys_emit(g, g->axiom_first, g->naxiom, g->axiom_line, &a, max_modules);
  if (s == SESSILE_OK && g->has_cut) cut(&a);
  for (int it = 0; it < iterations && s == SESSILE_OK; it++) {
    s = step(g, LSYS_DERIVATION, &a, max_modules, &b);
    sessile_lsys_string t = a;
    a = b, b = t;
  }
  gm->rng = NULL;
  sessile_lsys_string_free(&b);
  if (s != SESSILE_OK) {
    sessile_lsys_string_free(&a);
    return s;
  }
  sessile_lsys_string_free(out);
  *out = a;
  return SESSILE_OK;
}

sessile_status sessile_lsys_string_format(const sessile_lsys_string *s, char **text) {
  size_t cap = 64 + (size_t)s->n * 2 + s->npar * 26, n = 0;
  char *t = malloc(cap);
  SESSILE_CHECK(t, SESSILE_ERR_NO_MEMORY, "out of host memory");
  for (uint32_t i = 0; i < s->n; i++) {
    t[n++] = (char)s->sym[i];
    for (uint8_t a = 0; a < s->np[i]; a++)
      n += (size_t)snprintf(t + n, cap - n, "%c%.12g", a ? ',' : '(', s->par[s->off[i] + a]);
    if (s->np[i]) t[n++] = ')';
  }
  t[n] = 0;
  *text = t;
  return SESSILE_OK;
}
