/* The SDS model text (docs/sds_rules.md): declarations, physics parameters
 * and rules, line by line.  Every error names file:line:column; names must
 * be declared before a rule uses them. */
#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "rules_internal.h"
#include "rules_vm.h"
#include "sessile/io/io.h"

typedef struct cur {
  const sessile_sds_model *m;
  const char *s; /* the line, NUL-terminated, comment removed */
  int p, line;
} cur;

static sessile_status fail(const cur *c, int col0, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static sessile_status fail(const cur *c, int col0, const char *fmt, ...) {
  char msg[400];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  return sessile_error_set(SESSILE_ERR_USAGE, "%s:%d:%d: %s", c->m->file, c->line, col0 + 1, msg);
}

static void ws(cur *c) {
  while (c->s[c->p] == ' ' || c->s[c->p] == '\t' || c->s[c->p] == '\r') c->p++;
}
static int at_end(cur *c) {
  ws(c);
  return c->s[c->p] == 0;
}
/* An identifier into out (0 if none here). */
static int ident(cur *c, char out[SESSILE_SDS_NAME]) {
  ws(c);
  int a = c->p;
  if (!(isalpha((unsigned char)c->s[a]) || c->s[a] == '_')) return 0;
  int b = a;
  while (isalnum((unsigned char)c->s[b]) || c->s[b] == '_') b++;
  if (b - a >= SESSILE_SDS_NAME) return 0;
  memcpy(out, c->s + a, (size_t)(b - a));
  out[b - a] = 0;
  c->p = b;
  return 1;
}
static int lit(cur *c, const char *t) {
  ws(c);
  size_t n = strlen(t);
  if (strncmp(c->s + c->p, t, n)) return 0;
  c->p += (int)n;
  return 1;
}
static int number(cur *c, double *v) {
  ws(c);
  char *end = NULL;
  *v = strtod(c->s + c->p, &end);
  if (end == c->s + c->p || !isfinite(*v)) return 0;
  c->p = (int)(end - c->s);
  return 1;
}

/* Names an expression gives another meaning (keywords are only keywords
 * where a line starts, so a state may be called `tip`). */
static const char *const reserved[] = {"radius", "volume", "time", "surface", "grad", "_pi", "_e"};

static int find(const char names[][SESSILE_SDS_NAME], int n, const char *x) {
  for (int i = 0; i < n; i++)
    if (!strcmp(names[i], x)) return i;
  return -1;
}

/* A name that may be declared: not reserved, not yet used. */
static sessile_status new_name(cur *c, int col, const char *x) {
  for (size_t i = 0; i < sizeof reserved / sizeof *reserved; i++)
    if (!strcmp(reserved[i], x)) return fail(c, col, "'%s' is a reserved word", x);
  const sessile_sds_model *m = c->m;
  if (find(m->mname, m->nmorph, x) >= 0 || find(m->sname, m->nstate, x) >= 0 || find(m->cname, m->nconst, x) >= 0)
    return fail(c, col, "'%s' is declared twice", x);
  return SESSILE_OK;
}

/* Every identifier of an expression (not a function call) must be a known
 * name: muparser's own message for an unknown one is only "unexpected token". */
static sessile_status check_names(cur *c, int col0, const char *text) {
  const sessile_sds_model *m = c->m;
  for (int i = 0; text[i];) {
    if (isdigit((unsigned char)text[i]) || text[i] == '.') { /* a number, exponent included */
      while (isalnum((unsigned char)text[i]) || text[i] == '.' ||
             ((text[i] == '+' || text[i] == '-') && (text[i - 1] == 'e' || text[i - 1] == 'E')))
        i++;
      continue;
    }
    if (!(isalpha((unsigned char)text[i]) || text[i] == '_')) {
      i++;
      continue;
    }
    int a = i;
    while (isalnum((unsigned char)text[i]) || text[i] == '_') i++;
    char x[64];
    int len = i - a < 63 ? i - a : 63;
    memcpy(x, text + a, (size_t)len);
    x[len] = 0;
    int j = i;
    while (text[j] == ' ' || text[j] == '\t') j++;
    if (text[j] == '(') continue; /* a function: muparser knows its own */
    if (!strcmp(x, "radius") || !strcmp(x, "volume") || !strcmp(x, "time") || !strcmp(x, "surface") ||
        !strcmp(x, "_pi") ||
        !strcmp(x, "_e"))
      continue;
    if (find(m->mname, m->nmorph, x) >= 0 || find(m->sname, m->nstate, x) >= 0 || find(m->cname, m->nconst, x) >= 0)
      continue;
    return fail(c, col0 + a, "unknown name '%s' (not a declared morphogen, timer, state variable or constant, "
                "nor radius, volume, time, surface)", x);
  }
  return SESSILE_OK;
}

/* Compiles text (columns from col0) into e, its variables bound to the
 * model's slots; the text is kept in *keep for the bytecode compiler. */
static sessile_status compile(cur *c, int col0, const char *text, sds_expr *e, char **keep) {
  sessile_sds_model *m = (sessile_sds_model *)c->m;
  e->h = NULL, e->c = 0;
  int lead = 0;
  while (text[lead] == ' ' || text[lead] == '\t') lead++;
  if (!text[lead]) return fail(c, col0, "empty expression");
  if (sessile_expr_plain_number(text, &e->c)) return SESSILE_OK;
  SESSILE_CALL(check_names(c, col0, text));
  SESSILE_CALL(sessile_expr_begin(e));
  sessile_expr_var(e, "radius", &m->slot[SDS_SLOT_RADIUS]);
  sessile_expr_var(e, "volume", &m->slot[SDS_SLOT_VOLUME]);
  sessile_expr_var(e, "time", &m->slot[SDS_SLOT_TIME]);
  sessile_expr_var(e, "surface", &m->slot[SDS_SLOT_SURFACE]);
  for (int i = 0; i < m->nmorph; i++) sessile_expr_var(e, m->mname[i], &m->slot[SDS_SLOT_MORPH + i]);
  for (int i = 0; i < m->nstate; i++) sessile_expr_var(e, m->sname[i], &m->slot[SDS_SLOT_STATE + i]);
  for (int i = 0; i < m->nconst; i++) sessile_expr_const(e, m->cname[i], m->cval[i]);
  char one[256];
  int pos = 0, len = (int)strlen(text);
  if (sessile_expr_finish(e, text, &pos, one, sizeof one) != SESSILE_OK) {
    if (pos < 0 || pos > len) pos = len;
    return fail(c, col0 + pos, "bad expression: %s", one);
  }
  *keep = strdup(text);
  SESSILE_CHECK(*keep, SESSILE_ERR_NO_MEMORY, "out of host memory for an expression");
  return SESSILE_OK;
}

/* key=value pairs after a morphogen / timer declaration. */
static sessile_status morph_line(cur *c, int timer) {
  sessile_sds_model *m = (sessile_sds_model *)c->m;
  char name[SESSILE_SDS_NAME], key[SESSILE_SDS_NAME];
  ws(c);
  int col = c->p;
  if (!ident(c, name)) return fail(c, col, "expected a %s name", timer ? "timer" : "morphogen");
  SESSILE_CALL(new_name(c, col, name));
  if (m->nmorph >= SDS_MAX_MORPH) return fail(c, col, "more than %d morphogens and timers", SDS_MAX_MORPH);
  int k = m->nmorph;
  snprintf(m->mname[k], SESSILE_SDS_NAME, "%s", name);
  m->diffusion[k] = 0, m->decay[k] = 0, m->mstart[k] = 0, m->capped[k] = !timer, m->timer[k] = timer;
  int seen_d = 0, seen_c = 0;
  while (!at_end(c)) {
    int kc = c->p;
    if (!ident(c, key)) return fail(c, kc, "expected key=value (diffusion, decay, start%s)", timer ? "" : ", capped, axis");
    if (!lit(c, "=")) return fail(c, c->p, "expected '=' after '%s'", key);
    double v;
    int vc = (ws(c), c->p);
    if (!number(c, &v)) return fail(c, vc, "expected a number for '%s'", key);
    if (!strcmp(key, "diffusion") && !timer) {
      if (v < 0) return fail(c, vc, "diffusion must be >= 0 (got %g)", v);
      m->diffusion[k] = v, seen_d = 1;
    } else if (!strcmp(key, "decay")) {
      if (v < 0) return fail(c, vc, "decay must be >= 0 (got %g)", v);
      m->decay[k] = v, seen_c = 1;
    } else if (!strcmp(key, "start")) {
      if (v < 0) return fail(c, vc, "start must be >= 0 (got %g)", v);
      m->mstart[k] = v;
    } else if (!strcmp(key, "capped") && !timer) {
      if (v != 0 && v != 1) return fail(c, vc, "capped is 0 or 1 (got %g)", v);
      m->capped[k] = (int)v;
    } else if (!strcmp(key, "axis") && !timer) {
      if (v != 0 && v != 1) return fail(c, vc, "axis is 0 or 1 (got %g)", v);
      if (v == 1 && m->axis && m->axis != k + 1)
        return fail(c, kc, "morphogen '%s' is the axis already: one morphogen may be", m->mname[m->axis - 1]);
      if (v == 1) m->axis = k + 1;
    } else {
      return fail(c, kc, "unknown key '%s' for a %s (%s)", key, timer ? "timer" : "morphogen",
                  timer ? "decay, start" : "diffusion, decay, start, capped, axis");
    }
  }
  if (!timer && !seen_d) return fail(c, col, "morphogen '%s' needs diffusion=", name);
  if (!seen_c) return fail(c, col, "%s '%s' needs decay=", timer ? "timer" : "morphogen", name);
  m->nmorph++;
  return SESSILE_OK;
}

static sessile_status action(cur *c, const char *text, int col0, sds_action *a) {
  cur t = *c;
  t.s = text, t.p = 0;
  char word[SESSILE_SDS_NAME], name[SESSILE_SDS_NAME];
  const sessile_sds_model *m = c->m;
  ws(&t);
  int wc = t.p;
  a->sign = 1, a->value.h = NULL, a->value.c = 0, a->target = -1, a->text = NULL;
  if (!ident(&t, word)) return fail(c, col0 + wc, "expected an action (set, produce, grow, divide, reset)");
  if (!strcmp(word, "set") || !strcmp(word, "produce")) {
    int nc = (ws(&t), t.p);
    if (!ident(&t, name)) return fail(c, col0 + nc, "expected a morphogen or state name after '%s'", word);
    int k = find(m->mname, m->nmorph, name), s = find(m->sname, m->nstate, name);
    if (word[0] == 'p') {
      if (k < 0) return fail(c, col0 + nc, "unknown morphogen '%s'", name);
      a->kind = SESSILE_SDS_PRODUCE, a->target = k;
    } else {
      if (k < 0 && s < 0) return fail(c, col0 + nc, "unknown morphogen or state variable '%s'", name);
      a->kind = k >= 0 ? SESSILE_SDS_SET_MORPH : SESSILE_SDS_SET_STATE, a->target = k >= 0 ? k : s;
      if (!lit(&t, "=")) return fail(c, col0 + t.p, "expected '=' after 'set %s'", name);
    }
    return compile(c, col0 + t.p, text + t.p, &a->value, &a->text);
  }
  if (!strcmp(word, "grow")) {
    a->kind = SESSILE_SDS_GROW;
    return compile(c, col0 + t.p, text + t.p, &a->value, &a->text);
  }
  if (!strcmp(word, "reset")) {
    int nc = (ws(&t), t.p);
    if (!ident(&t, name)) return fail(c, col0 + nc, "expected a timer name after 'reset'");
    int k = find(m->mname, m->nmorph, name);
    if (k < 0 || !m->timer[k]) return fail(c, col0 + nc, "unknown timer '%s'", name);
    a->kind = SESSILE_SDS_RESET, a->target = k;
    if (!at_end(&t)) return fail(c, col0 + t.p, "unexpected text after 'reset %s'", name);
    return SESSILE_OK;
  }
  if (!strcmp(word, "divide")) {
    a->kind = SESSILE_SDS_DIVIDE;
    char w2[SESSILE_SDS_NAME];
    int save = t.p;
    if (ident(&t, w2)) {
      if (!strcmp(w2, "away")) a->sign = -1;
      else if (strcmp(w2, "toward")) t.p = save;
    }
    ws(&t);
    if (t.s[t.p] == '-') a->sign = -a->sign, t.p++;
    int gc = (ws(&t), t.p);
    if (!lit(&t, "grad") || !lit(&t, "(")) return fail(c, col0 + gc, "expected grad(MORPHOGEN) after 'divide'");
    int nc = (ws(&t), t.p);
    if (!ident(&t, name)) return fail(c, col0 + nc, "expected a morphogen name in grad()");
    int k = find(m->mname, m->nmorph, name);
    if (k < 0) return fail(c, col0 + nc, "unknown morphogen '%s'", name);
    if (!lit(&t, ")")) return fail(c, col0 + t.p, "expected ')'");
    if (!at_end(&t)) return fail(c, col0 + t.p, "unexpected text after grad(%s)", name);
    a->target = k;
    return SESSILE_OK;
  }
  return fail(c, col0 + wc, "unknown action '%s' (set, produce, grow, divide, reset)", word);
}

static sessile_status rule_line(cur *c) {
  sessile_sds_model *m = (sessile_sds_model *)c->m;
  char name[SESSILE_SDS_NAME];
  int col = (ws(c), c->p);
  if (!ident(c, name)) return fail(c, col, "expected a rule name");
  for (int i = 0; i < m->nrules; i++)
    if (!strcmp(m->rules[i].name, name)) return fail(c, col, "rule '%s' is declared twice", name);
  if (m->nrules >= SDS_MAX_RULES) return fail(c, col, "more than %d rules", SDS_MAX_RULES);
  if (!lit(c, ":")) return fail(c, c->p, "expected ':' after the rule name");
  const char *arrow = strstr(c->s + c->p, "->");
  if (!arrow) return fail(c, (int)strlen(c->s), "expected '->' between the condition and the actions");
  sds_rule *r = &m->rules[m->nrules];
  memset(r, 0, sizeof *r);
  snprintf(r->name, sizeof r->name, "%s", name);
  r->line = c->line;
  char buf[1024];
  int a = c->p, b = (int)(arrow - c->s);
  snprintf(buf, sizeof buf, "%.*s", b - a, c->s + a);
  m->nrules++; /* counted now so destroy frees what compiles below */
  SESSILE_CALL(compile(c, a, buf, &r->cond, &r->text));
  int p = b + 2;
  for (;;) {
    const char *semi = strchr(c->s + p, ';');
    int e = semi ? (int)(semi - c->s) : (int)strlen(c->s);
    if (r->nact >= SDS_MAX_ACTIONS) return fail(c, p, "more than %d actions in one rule", SDS_MAX_ACTIONS);
    snprintf(buf, sizeof buf, "%.*s", e - p, c->s + p);
    r->nact++;
    SESSILE_CALL(action(c, buf, p, &r->act[r->nact - 1]));
    if (!semi) break;
    p = e + 1;
  }
  return SESSILE_OK;
}

static sessile_status param_line(cur *c, const char *name, int col) {
  sessile_sds_model *m = (sessile_sds_model *)c->m;
  for (int i = 0; i < m->nparams; i++)
    if (!strcmp(m->params[i].name, name)) return fail(c, col, "parameter '%s' is set twice", name);
  if (m->nparams >= SDS_MAX_PARAMS) return fail(c, col, "more than %d parameters", SDS_MAX_PARAMS);
  sessile_sds_param *q = &m->params[m->nparams];
  memset(q, 0, sizeof *q);
  snprintf(q->name, sizeof q->name, "%s", name);
  q->line = c->line;
  ws(c);
  if (c->s[c->p] == '"') {
    const char *e = strchr(c->s + c->p + 1, '"');
    if (!e) return fail(c, c->p, "unterminated string");
    int len = (int)(e - (c->s + c->p + 1));
    if (len >= (int)sizeof q->text) return fail(c, c->p, "string longer than %zu", sizeof q->text - 1);
    memcpy(q->text, c->s + c->p + 1, (size_t)len);
    c->p = (int)(e - c->s) + 1;
  } else {
    while (!at_end(c)) {
      int vc = c->p;
      if (q->nvalues >= SESSILE_SDS_MAX_VALUES)
        return fail(c, vc, "more than %d values for '%s'", SESSILE_SDS_MAX_VALUES, name);
      if (!number(c, &q->values[q->nvalues])) return fail(c, vc, "expected a number for '%s'", name);
      q->nvalues++;
    }
    if (!q->nvalues) return fail(c, c->p, "expected a value for '%s'", name);
  }
  if (!at_end(c)) return fail(c, c->p, "unexpected text after the value of '%s'", name);
  m->nparams++;
  return SESSILE_OK;
}

static sessile_status line(cur *c) {
  sessile_sds_model *m = (sessile_sds_model *)c->m;
  char word[SESSILE_SDS_NAME], name[SESSILE_SDS_NAME];
  if (at_end(c)) return SESSILE_OK;
  int col = c->p;
  if (!ident(c, word)) return fail(c, col, "expected a declaration, a rule or NAME = VALUE");
  if (!strcmp(word, "morphogen")) return morph_line(c, 0);
  if (!strcmp(word, "timer")) return morph_line(c, 1);
  if (!strcmp(word, "rule")) return rule_line(c);
  if (!strcmp(word, "model")) return SESSILE_OK; /* a title: the rest of the line */
  if (!strcmp(word, "state") || !strcmp(word, "const")) {
    int nc = (ws(c), c->p);
    if (!ident(c, name)) return fail(c, nc, "expected a name after '%s'", word);
    SESSILE_CALL(new_name(c, nc, name));
    double v = 0;
    int has = lit(c, "=");
    int vc = (ws(c), c->p);
    if (has && !number(c, &v)) return fail(c, vc, "expected a number");
    if (!has && word[0] == 'c') return fail(c, vc, "expected '=' and a value after 'const %s'", name);
    if (!at_end(c)) return fail(c, c->p, "unexpected text after '%s %s'", word, name);
    if (word[0] == 's') {
      if (m->nstate >= SDS_MAX_STATE) return fail(c, nc, "more than %d state variables", SDS_MAX_STATE);
      snprintf(m->sname[m->nstate], SESSILE_SDS_NAME, "%s", name);
      m->sstart[m->nstate++] = v;
    } else {
      if (m->nconst >= SDS_MAX_CONST) return fail(c, nc, "more than %d constants", SDS_MAX_CONST);
      snprintf(m->cname[m->nconst], SESSILE_SDS_NAME, "%s", name);
      m->cval[m->nconst++] = v;
    }
    return SESSILE_OK;
  }
  if (!strcmp(word, "tip")) {
    if (m->ntips >= SDS_MAX_TIPS) return fail(c, col, "more than %d tips", SDS_MAX_TIPS);
    double d[3];
    for (int a = 0; a < 3; a++) {
      int vc = (ws(c), c->p);
      if (!number(c, &d[a])) return fail(c, vc, "expected a direction: tip X Y Z");
    }
    if (!at_end(c)) return fail(c, c->p, "unexpected text after the tip direction");
    double l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (!(l > 0)) return fail(c, col, "the tip direction is zero");
    for (int a = 0; a < 3; a++) m->tips[m->ntips][a] = d[a] / l;
    m->ntips++;
    return SESSILE_OK;
  }
  if (lit(c, "=")) return param_line(c, word, col);
  return fail(c, col, "unknown keyword '%s' (morphogen, timer, state, const, tip, rule, model, or NAME = VALUE)",
              word);
}

static void free_texts(sessile_sds_model *m) {
  for (int i = 0; i < m->nrules; i++) {
    free(m->rules[i].text), m->rules[i].text = NULL;
    for (int a = 0; a < m->rules[i].nact; a++) free(m->rules[i].act[a].text), m->rules[i].act[a].text = NULL;
  }
}

sessile_status sessile_sds_model_parse(const char *text, const char *file, sessile_sds_model **out) {
  *out = NULL;
  SESSILE_CHECK(text, SESSILE_ERR_USAGE, "no model text");
  sessile_sds_model *m = calloc(1, sizeof *m);
  SESSILE_CHECK(m, SESSILE_ERR_NO_MEMORY, "out of host memory for a model");
  snprintf(m->file, sizeof m->file, "%s", file ? file : "<model>");
  cur c = {m, NULL, 0, 0};
  char buf[1024];
  sessile_status st = SESSILE_OK;
  for (const char *p = text; *p && st == SESSILE_OK;) {
    const char *e = strchr(p, '\n');
    size_t n = e ? (size_t)(e - p) : strlen(p);
    c.line++;
    if (n >= sizeof buf) {
      c.s = "";
      st = fail(&c, 0, "line longer than %zu characters", sizeof buf - 1);
      break;
    }
    memcpy(buf, p, n);
    buf[n] = 0;
    for (size_t i = 0; i < n; i++)
      if (buf[i] == '#' || buf[i] == 0) { /* a comment, or a NUL inside the line */
        buf[i] = 0;
        break;
      }
    c.s = buf, c.p = 0;
    st = line(&c);
    p = e ? e + 1 : p + n;
  }
  if (st == SESSILE_OK && m->nrules == 0) {
    c.s = "", c.p = 0;
    if (c.line == 0) c.line = 1; /* an empty text */
    st = fail(&c, 0, "the model has no rules");
  }
  if (st != SESSILE_OK) {
    sessile_sds_model_destroy(m);
    return st;
  }
  /* the bytecode, from the texts muparser accepted; then the texts go */
  m->prog = sds_prog_compile(m, m->prog_why, sizeof m->prog_why);
  free_texts(m);
  *out = m;
  return SESSILE_OK;
}

sessile_status sessile_sds_model_load(const char *path, sessile_sds_model **out) {
  *out = NULL;
  char *text = NULL;
  size_t len = 0;
  SESSILE_CALL(sessile_read_small_file(path, (size_t)1 << 20, "model file", &text, &len));
  sessile_status st = sessile_sds_model_parse(text, path, out);
  free(text);
  return st;
}

void sessile_sds_model_destroy(sessile_sds_model *m) {
  if (!m) return;
  for (int i = 0; i < m->nrules; i++) {
    sessile_expr_free(&m->rules[i].cond);
    for (int a = 0; a < m->rules[i].nact; a++) sessile_expr_free(&m->rules[i].act[a].value);
  }
  free_texts(m);
  sds_prog_free(m->prog);
  free(m);
}

int sessile_sds_model_nmorph(const sessile_sds_model *m) { return m->nmorph; }
int sessile_sds_model_axis(const sessile_sds_model *m) { return m->axis - 1; }
int sessile_sds_model_nstate(const sessile_sds_model *m) { return m->nstate; }
int sessile_sds_model_nrules(const sessile_sds_model *m) { return m->nrules; }
const char *sessile_sds_model_morph_name(const sessile_sds_model *m, int k) { return m->mname[k]; }
const char *sessile_sds_model_state_name(const sessile_sds_model *m, int k) { return m->sname[k]; }
int sessile_sds_model_morph_index(const sessile_sds_model *m, const char *name) {
  return find(m->mname, m->nmorph, name);
}
int sessile_sds_model_state_index(const sessile_sds_model *m, const char *name) {
  return find(m->sname, m->nstate, name);
}
sessile_morph_coef sessile_sds_model_coef(const sessile_sds_model *m) {
  return (sessile_morph_coef){m->nmorph, m->diffusion, m->decay, m->capped};
}
double sessile_sds_model_morph_start(const sessile_sds_model *m, int k) { return m->mstart[k]; }
double sessile_sds_model_state_start(const sessile_sds_model *m, int k) { return m->sstart[k]; }
int sessile_sds_model_nparams(const sessile_sds_model *m) { return m->nparams; }
const sessile_sds_param *sessile_sds_model_param(const sessile_sds_model *m, int i) { return &m->params[i]; }
const sessile_sds_param *sessile_sds_model_param_find(const sessile_sds_model *m, const char *name) {
  for (int i = 0; i < m->nparams; i++)
    if (!strcmp(m->params[i].name, name)) return &m->params[i];
  return NULL;
}
int sessile_sds_model_ntips(const sessile_sds_model *m) { return m->ntips; }
const double *sessile_sds_model_tip(const sessile_sds_model *m, int i) { return m->tips[i]; }
