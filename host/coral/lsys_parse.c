/* The L-system grammar's text format (docs/lsystem.md) compiled into
 * productions: line by line, every error "where:line:column: what". */
#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "lsys_internal.h"

typedef struct pctx {
  sessile_lsys *g;
  const char *where;
  int line;
  const char *base; /* the current line's first byte (column 1) */
  int noverrides;
  const char *const *onames;
  const double *ovalues;
  char *oused;
  int set; /* where productions go: LSYS_DERIVATION until "homomorphism:" */
} pctx;

static sessile_status perr(const pctx *c, const char *at, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static sessile_status perr(const pctx *c, const char *at, const char *fmt, ...) {
  char m[400];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(m, sizeof m, fmt, ap);
  va_end(ap);
  return sessile_error_set(SESSILE_ERR_USAGE, "%s:%d:%d: %s", c->where, c->line, (int)(at - c->base) + 1, m);
}

/* Module symbols: printable ASCII except what the syntax itself uses. */
static int is_symbol(int ch) { return ch > 32 && ch < 127 && !strchr("(),:<>=;0123456789", ch); }
static const char *skip_blank(const char *p, const char *end) {
  while (p < end && (*p == ' ' || *p == '\t')) p++;
  return p;
}
static const char *trim_end(const char *p, const char *end) {
  while (end > p && (end[-1] == ' ' || end[-1] == '\t')) end--;
  return end;
}
/* The ')' matching the '(' at p, or NULL. */
static const char *match_paren(const char *p, const char *end) {
  int depth = 0;
  for (; p < end; p++) {
    if (*p == '(') depth++;
    else if (*p == ')' && --depth == 0) return p;
  }
  return NULL;
}

static sessile_status push_expr(pctx *c, const char *b, const char *e, int nnames, char names[][32], double *slots,
                                uint32_t *index) {
  sessile_lsys *g = c->g;
  if (g->nexprs >= LSYS_MAX_EXPRS) return perr(c, b, "more than %d expressions in one grammar", LSYS_MAX_EXPRS);
  if (g->nexprs == g->capexprs) {
    uint32_t cap = g->capexprs ? 2 * g->capexprs : 64;
    lsys_expr *x = realloc(g->exprs, cap * sizeof *x);
    SESSILE_CHECK(x, SESSILE_ERR_NO_MEMORY, "out of host memory for the grammar's expressions");
    g->exprs = x, g->capexprs = cap;
  }
  size_t n = (size_t)(e - b);
  char *t = malloc(n + 1);
  SESSILE_CHECK(t, SESSILE_ERR_NO_MEMORY, "out of host memory");
  memcpy(t, b, n);
  t[n] = 0;
  char msg[300];
  int pos = 0;
  sessile_status s = lsys_expr_compile(g, t, nnames, names, slots, &g->exprs[g->nexprs], &pos, msg, sizeof msg);
  free(t);
  if (s == SESSILE_ERR_USAGE) return perr(c, b + pos, "%s", msg);
  if (s != SESSILE_OK) return sessile_error_set(s, "%s", msg);
  *index = g->nexprs++;
  return SESSILE_OK;
}

static sessile_status push_tpl(pctx *c, uint8_t sym, uint8_t np, uint32_t first) {
  sessile_lsys *g = c->g;
  if (g->ntpl == g->captpl) {
    uint32_t cap = g->captpl ? 2 * g->captpl : 64;
    lsys_tpl *x = realloc(g->tpl, cap * sizeof *x);
    SESSILE_CHECK(x, SESSILE_ERR_NO_MEMORY, "out of host memory for the grammar's modules");
    g->tpl = x, g->captpl = cap;
  }
  g->tpl[g->ntpl++] = (lsys_tpl){sym, np, first};
  return SESSILE_OK;
}

/* A successor or the axiom: modules with argument expressions. */
static sessile_status parse_modules(pctx *c, const char *p, const char *end, int nnames, char names[][32],
                                    double *slots, uint32_t *first, uint32_t *count) {
  *first = c->g->ntpl, *count = 0;
  for (p = skip_blank(p, end); p < end; p = skip_blank(p, end)) {
    if (!is_symbol((unsigned char)*p)) return perr(c, p, "'%c' cannot be a module's symbol", *p);
    uint8_t sym = (uint8_t)*p++;
    uint8_t np = 0;
    uint32_t efirst = c->g->nexprs;
    if (p < end && *p == '(') {
      const char *close = match_paren(p, end);
      if (!close) return perr(c, p, "'(' without its ')'");
      const char *a = p + 1;
      int depth = 0;
      for (const char *q = a; q <= close; q++) {
        if (q < close && *q == '(') depth++;
        else if (q < close && *q == ')') depth--;
        else if (q == close || (*q == ',' && depth == 0)) {
          if (np == SESSILE_LSYS_MAX_PARAMS)
            return perr(c, a, "more than %d parameters in one module", SESSILE_LSYS_MAX_PARAMS);
          if (skip_blank(a, q) == q) return perr(c, a, "empty parameter");
          uint32_t idx;
          SESSILE_CALL(push_expr(c, a, q, nnames, names, slots, &idx));
          np++;
          a = q + 1;
        }
      }
      p = close + 1;
    }
    SESSILE_CALL(push_tpl(c, sym, np, efirst));
    if (sym == '%') c->g->has_cut = 1;
    ++*count;
  }
  return SESSILE_OK;
}

/* A pattern (predecessor or context): symbols with parameter names. */
static sessile_status parse_pattern(pctx *c, const char *p, const char *end, lsys_pat *pats, int maxn, int *n,
                                    char names[][32], int *nnames) {
  *n = 0;
  for (p = skip_blank(p, end); p < end; p = skip_blank(p, end)) {
    if (!is_symbol((unsigned char)*p)) return perr(c, p, "'%c' cannot be a module's symbol", *p);
    if (*n == maxn) return perr(c, p, "more than %d modules here", maxn);
    lsys_pat *pt = &pats[(*n)++];
    pt->sym = (uint8_t)*p++, pt->np = 0, pt->slot = (uint8_t)*nnames;
    if (p < end && *p == '(') {
      const char *close = match_paren(p, end);
      if (!close) return perr(c, p, "'(' without its ')'");
      for (const char *q = p + 1;;) {
        q = skip_blank(q, close);
        const char *b = q;
        if (q < close && (isalpha((unsigned char)*q) || *q == '_'))
          while (q < close && (isalnum((unsigned char)*q) || *q == '_')) q++;
        if (q == b) return perr(c, q, "a parameter name (a letter, then letters, digits or _) expected");
        if (q - b > 31) return perr(c, b, "parameter name longer than 31 characters");
        if (*nnames == LSYS_MAX_SLOTS) return perr(c, b, "more than %d parameters in one production", LSYS_MAX_SLOTS);
        if (pt->np == SESSILE_LSYS_MAX_PARAMS)
          return perr(c, b, "more than %d parameters in one module", SESSILE_LSYS_MAX_PARAMS);
        char nm[32];
        memcpy(nm, b, (size_t)(q - b));
        nm[q - b] = 0;
        for (int k = 0; k < *nnames; k++)
          if (!strcmp(names[k], nm)) return perr(c, b, "parameter '%s' named twice in one production", nm);
        for (int k = 0; k < c->g->ndefines; k++)
          if (!strcmp(c->g->dname[k], nm)) return perr(c, b, "parameter '%s' hides the define of that name", nm);
        if (!strcmp(nm, "uniform")) return perr(c, b, "'uniform' is a function, not a parameter name");
        strcpy(names[(*nnames)++], nm);
        pt->np++;
        q = skip_blank(q, close);
        if (q == close) break;
        if (*q != ',') return perr(c, q, "',' or ')' expected after a parameter name");
        q++;
      }
      p = close + 1;
    }
  }
  return SESSILE_OK;
}

/* The arrow: "->" or the weighted "-(w)->", first at depth 0. */
static const char *find_arrow(const char *p, const char *end, const char **wb, const char **we, const char **after) {
  int depth = 0;
  *wb = *we = NULL;
  for (const char *q = p; q < end; q++) {
    if (depth == 0 && q[0] == '-' && q + 1 < end && q[1] == '>') {
      *after = q + 2;
      return q;
    }
    if (depth == 0 && q[0] == '-' && q + 1 < end && q[1] == '(') {
      const char *close = match_paren(q + 1, end);
      if (close && close + 2 < end && close[1] == '-' && close[2] == '>') {
        *wb = q + 2, *we = close, *after = close + 3;
        return q;
      }
    }
    if (*q == '(') depth++;
    else if (*q == ')') depth--;
  }
  return NULL;
}
static const char *find_depth0(const char *p, const char *end, char ch) {
  int depth = 0;
  for (; p < end; p++) {
    if (*p == '(') depth++;
    else if (*p == ')') depth--;
    else if (depth == 0 && *p == ch) return p;
  }
  return NULL;
}

static sessile_status parse_production(pctx *c, const char *p, const char *end, const char *arrow, const char *wb,
                                       const char *we, const char *after) {
  sessile_lsys *g = c->g;
  if (g->nprods == LSYS_MAX_PRODS) return perr(c, p, "more than %d productions", LSYS_MAX_PRODS);
  lsys_prod *x = realloc(g->prods, (size_t)(g->nprods + 1) * sizeof *x);
  SESSILE_CHECK(x, SESSILE_ERR_NO_MEMORY, "out of host memory for the productions");
  g->prods = x;
  lsys_prod *pr = &g->prods[g->nprods];
  memset(pr, 0, sizeof *pr);
  pr->slots = calloc(LSYS_MAX_SLOTS, sizeof *pr->slots);
  SESSILE_CHECK(pr->slots, SESSILE_ERR_NO_MEMORY, "out of host memory");
  g->nprods++; /* owned from here: freed with the grammar */
  pr->line = c->line;
  pr->set = c->set;
  g->nset[c->set]++;
  const char *colon = find_depth0(p, arrow, ':');
  const char *head_end = colon ? colon : arrow;
  const char *lt = find_depth0(p, head_end, '<');
  const char *gt = find_depth0(lt ? lt + 1 : p, head_end, '>');
  char names[LSYS_MAX_SLOTS][32];
  int nnames = 0, n = 0;
  lsys_pat pred[1];
  if (lt) {
    SESSILE_CALL(parse_pattern(c, p, lt, pr->left, LSYS_MAX_CONTEXT, &pr->nleft, names, &nnames));
    if (!pr->nleft) return perr(c, lt, "'<' without a left context before it");
  }
  const char *pb = lt ? lt + 1 : p, *pe = gt ? gt : head_end;
  if (skip_blank(pb, pe) == pe) return perr(c, skip_blank(pb, pe), "a production needs a predecessor module");
  pr->pred_slot = (uint8_t)nnames;
  /* one module: parse with room for two to name the error */
  lsys_pat two[2];
  SESSILE_CALL(parse_pattern(c, pb, pe, two, 2, &n, names, &nnames));
  if (n != 1) return perr(c, skip_blank(pb, pe), "the predecessor must be one module (a context goes before '<' or after '>')");
  pred[0] = two[0];
  pr->pred = pred[0].sym, pr->pred_np = pred[0].np;
  if (gt) {
    SESSILE_CALL(parse_pattern(c, gt + 1, head_end, pr->right, LSYS_MAX_CONTEXT, &pr->nright, names, &nnames));
    if (!pr->nright) return perr(c, gt, "'>' without a right context after it");
  }
  for (int k = 0; k < pr->nleft; k++)
    if (pr->left[k].sym == '[' || pr->left[k].sym == ']')
      return perr(c, p, "brackets are not supported in a left context (it skips branches by itself)");
  for (int k = 0, depth = 0; k < pr->nright; k++) {
    uint8_t b = pr->right[k].sym;
    if ((b == '[' || b == ']') && pr->right[k].np) return perr(c, gt, "a bracket in a context takes no parameters");
    if (b == '[') depth++;
    if (b == ']' && depth-- == 0) return perr(c, gt, "a ']' without its '[' in the right context");
  }
  if (pr->nleft || pr->nright) g->has_context = 1;
  uint32_t idx;
  if (colon) {
    const char *cb = colon + 1, *ce = trim_end(cb, arrow);
    if (skip_blank(cb, ce) == ce) return perr(c, colon, "':' without a condition after it");
    SESSILE_CALL(push_expr(c, cb, ce, nnames, names, pr->slots, &idx));
    pr->cond = g->exprs[idx], pr->has_cond = 1;
    g->exprs[idx].h = NULL; /* owned by the production now */
    g->nexprs--;
  }
  if (wb) {
    if (skip_blank(wb, we) == we) return perr(c, wb, "empty weight in '-()->'");
    SESSILE_CALL(push_expr(c, wb, we, nnames, names, pr->slots, &idx));
    pr->weight = g->exprs[idx], pr->has_weight = 1;
    g->exprs[idx].h = NULL;
    g->nexprs--;
  }
  return parse_modules(c, after, end, nnames, names, pr->slots, &pr->succ_first, &pr->nsucc);
}

static sessile_status const_expr(pctx *c, const char *b, const char *e, double *v) {
  uint32_t idx;
  SESSILE_CALL(push_expr(c, b, e, 0, NULL, NULL, &idx));
  *v = sessile_expr_eval(&c->g->exprs[idx]);
  sessile_expr_free(&c->g->exprs[idx]);
  c->g->nexprs--;
  if (!isfinite(*v)) return perr(c, b, "the value is not finite");
  return SESSILE_OK;
}

static sessile_status parse_define(pctx *c, const char *p, const char *end) {
  sessile_lsys *g = c->g;
  p = skip_blank(p, end);
  const char *b = p;
  if (p < end && (isalpha((unsigned char)*p) || *p == '_'))
    while (p < end && (isalnum((unsigned char)*p) || *p == '_')) p++;
  if (p == b) return perr(c, b, "'define' needs a name (a letter, then letters, digits or _)");
  if (p - b > 31) return perr(c, b, "define name longer than 31 characters");
  char nm[32];
  memcpy(nm, b, (size_t)(p - b));
  nm[p - b] = 0;
  for (int k = 0; k < g->ndefines; k++)
    if (!strcmp(g->dname[k], nm)) return perr(c, b, "'%s' is defined twice", nm);
  if (!strcmp(nm, "uniform")) return perr(c, b, "'uniform' is a function, not a define name");
  if (g->ndefines == LSYS_MAX_DEFINES) return perr(c, b, "more than %d defines", LSYS_MAX_DEFINES);
  const char *eq = skip_blank(p, end);
  if (eq == end || *eq != '=') return perr(c, eq, "'=' expected after the define's name");
  double v;
  SESSILE_CALL(const_expr(c, eq + 1, trim_end(eq + 1, end), &v));
  for (int k = 0; k < c->noverrides; k++)
    if (!strcmp(c->onames[k], nm)) v = c->ovalues[k], c->oused[k] = 1;
  strcpy(g->dname[g->ndefines], nm);
  g->dval[g->ndefines++] = v;
  return SESSILE_OK;
}

static int directive_is(const char *p, const char *end, const char *word, const char **rest) {
  size_t n = strlen(word);
  if ((size_t)(end - p) < n || memcmp(p, word, n)) return 0;
  const char *q = skip_blank(p + n, end);
  if (q == end || *q != ':') return 0;
  *rest = q + 1;
  return 1;
}

static sessile_status parse_line(pctx *c, const char *p, const char *end, int *have_axiom) {
  sessile_lsys *g = c->g;
  p = skip_blank(p, end);
  end = trim_end(p, end);
  if (p == end) return SESSILE_OK;
  const char *wb, *we, *after, *rest;
  const char *arrow = find_arrow(p, end, &wb, &we, &after);
  if (arrow) return parse_production(c, p, end, arrow, wb, we, after);
  if (directive_is(p, end, "axiom", &rest)) {
    if (*have_axiom) return perr(c, p, "a second 'axiom:'");
    *have_axiom = 1;
    g->axiom_line = c->line;
    return parse_modules(c, rest, end, 0, NULL, NULL, &g->axiom_first, &g->naxiom);
  }
  if (directive_is(p, end, "homomorphism", &rest)) {
    if (skip_blank(rest, end) != end) return perr(c, skip_blank(rest, end), "'homomorphism:' stands alone on its line");
    if (c->set == LSYS_HOMOMORPHISM) return perr(c, p, "a second 'homomorphism:'");
    c->set = LSYS_HOMOMORPHISM;
    return SESSILE_OK;
  }
  if (directive_is(p, end, "ignore", &rest)) {
    for (const char *q = skip_blank(rest, end); q < end; q = skip_blank(q + 1, end)) {
      if (!is_symbol((unsigned char)*q)) return perr(c, q, "'%c' cannot be a module's symbol", *q);
      g->ignore[(unsigned char)*q] = 1;
    }
    return SESSILE_OK;
  }
  double v;
  if (directive_is(p, end, "iterations", &rest)) {
    SESSILE_CALL(const_expr(c, rest, end, &v));
    if (!(v >= 0 && v <= 1000 && v == floor(v))) return perr(c, skip_blank(rest, end), "iterations must be an integer in 0..1000");
    g->iterations = (int)v;
    return SESSILE_OK;
  }
  if (directive_is(p, end, "angle", &rest)) {
    SESSILE_CALL(const_expr(c, rest, end, &v));
    if (!(fabs(v) <= 360)) return perr(c, skip_blank(rest, end), "angle must be in -360..360 degrees");
    g->angle = v;
    return SESSILE_OK;
  }
  if (directive_is(p, end, "width_factor", &rest)) {
    SESSILE_CALL(const_expr(c, rest, end, &v));
    if (!(v > 0 && v <= 10)) return perr(c, skip_blank(rest, end), "width_factor must be in (0, 10]");
    g->width_factor = v;
    return SESSILE_OK;
  }
  if ((size_t)(end - p) > 7 && !memcmp(p, "define", 6) && (p[6] == ' ' || p[6] == '\t'))
    return parse_define(c, p + 7, end);
  const char *w = p;
  while (w < end && (isalnum((unsigned char)*w) || *w == '_')) w++;
  if (w > p && skip_blank(w, end) < end && *skip_blank(w, end) == ':')
    return perr(c, p, "unknown directive '%.*s' (axiom, iterations, angle, width_factor, ignore, define, homomorphism)",
                (int)(w - p > 40 ? 40 : w - p), p);
  return perr(c, p, "neither a production (no '->') nor a directive");
}

/* '#' starts a comment as a line's first non-blank, or after a blank and
 * before a blank or the end; otherwise it is the turtle's thickness symbol. */
static const char *comment_start(const char *p, const char *end) {
  const char *q = skip_blank(p, end);
  if (q < end && *q == '#') return q;
  for (q = p + 1; q < end; q++)
    if (*q == '#' && (q[-1] == ' ' || q[-1] == '\t') && (q + 1 == end || q[1] == ' ' || q[1] == '\t'))
      return q;
  return end;
}

static void build_index(sessile_lsys *g) {
  memset(g->by_count, 0, sizeof g->by_count);
  for (int i = 0; i < g->nprods; i++) g->by_count[g->prods[i].set][g->prods[i].pred]++;
  uint32_t acc = 0, fill[2][256];
  for (int k = 0; k < 2; k++)
    for (int s = 0; s < 256; s++) g->by_first[k][s] = acc, acc += g->by_count[k][s];
  memcpy(fill, g->by_first, sizeof fill);
  for (int i = 0; i < g->nprods; i++) g->by_list[fill[g->prods[i].set][g->prods[i].pred]++] = (uint32_t)i;
}

static sessile_status parse_all(pctx *c, const char *text, size_t len) {
  int have_axiom = 0;
  const char *p = text, *end = text + len;
  c->line = 0;
  while (p < end) {
    const char *nl = memchr(p, '\n', (size_t)(end - p));
    const char *le = nl ? nl : end;
    c->line++;
    c->base = p;
    const char *z = memchr(p, 0, (size_t)(le - p));
    if (z) return perr(c, z, "NUL byte in the grammar");
    const char *e = le;
    if (e > p && e[-1] == '\r') e--;
    for (const char *q = p; q < e; q++)
      if ((unsigned char)*q >= 127 || ((unsigned char)*q < 32 && *q != '\t'))
        return perr(c, q, "byte 0x%02x: only printable ASCII is allowed outside comments", (unsigned char)*q);
    e = comment_start(p, e);
    SESSILE_CALL(parse_line(c, p, e, &have_axiom));
    p = nl ? nl + 1 : end;
  }
  if (!have_axiom) {
    c->line = c->line ? c->line : 1;
    c->base = p;
    return perr(c, p, "the grammar has no 'axiom:' line");
  }
  for (int k = 0; k < c->noverrides; k++)
    if (!c->oused[k])
      return sessile_error_set(SESSILE_ERR_USAGE, "%s: no define named '%.40s' to override", c->where, c->onames[k]);
  c->g->by_list = malloc((size_t)(c->g->nprods ? c->g->nprods : 1) * sizeof *c->g->by_list);
  SESSILE_CHECK(c->g->by_list, SESSILE_ERR_NO_MEMORY, "out of host memory");
  build_index(c->g);
  return SESSILE_OK;
}

sessile_status sessile_lsys_parse(const char *text, size_t len, const char *where, int noverrides,
                                  const char *const *override_names, const double *override_values,
                                  sessile_lsys **out) {
  *out = NULL;
  SESSILE_CHECK(len <= LSYS_MAX_TEXT, SESSILE_ERR_USAGE, "%s: the grammar is larger than %d bytes", where,
                LSYS_MAX_TEXT);
  sessile_lsys *g = calloc(1, sizeof *g);
  SESSILE_CHECK(g, SESSILE_ERR_NO_MEMORY, "out of host memory");
  g->dval = calloc(LSYS_MAX_DEFINES, sizeof *g->dval);
  pctx c = {g, where, 0, text, noverrides, override_names, override_values, calloc((size_t)noverrides + 1, 1), 0};
  if (!g->dval || !c.oused) {
    free(c.oused);
    sessile_lsys_destroy(g);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  }
  g->angle = 30, g->width_factor = 0.8, g->iterations = 4;
  snprintf(g->where, sizeof g->where, "%s", where);
  sessile_status s = parse_all(&c, text, len);
  free(c.oused);
  if (s != SESSILE_OK) {
    sessile_lsys_destroy(g);
    return s;
  }
  *out = g;
  return SESSILE_OK;
}

void sessile_lsys_destroy(sessile_lsys *g) {
  if (!g) return;
  for (uint32_t i = 0; i < g->nexprs; i++) sessile_expr_free(&g->exprs[i]);
  for (int i = 0; i < g->nprods; i++) {
    sessile_expr_free(&g->prods[i].cond);
    sessile_expr_free(&g->prods[i].weight);
    free(g->prods[i].slots);
  }
  free(g->prods), free(g->exprs), free(g->tpl), free(g->by_list), free(g->dval);
  free(g);
}

int sessile_lsys_iterations(const sessile_lsys *g) { return g->iterations; }
int sessile_lsys_has_homomorphism(const sessile_lsys *g) { return g->nset[LSYS_HOMOMORPHISM] > 0; }
double sessile_lsys_angle(const sessile_lsys *g) { return g->angle; }
double sessile_lsys_width_factor(const sessile_lsys *g) { return g->width_factor; }
int sessile_lsys_define_count(const sessile_lsys *g) { return g->ndefines; }
const char *sessile_lsys_define_name(const sessile_lsys *g, int i, double *value) {
  if (i < 0 || i >= g->ndefines) return NULL;
  if (value) *value = g->dval[i];
  return g->dname[i];
}
