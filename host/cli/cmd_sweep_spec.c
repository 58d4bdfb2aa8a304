/* The sweep file (docs/sweep.md): strict JSON, the generator from the
 * registry, values spelled as --set spells them, every combination checked
 * against the generator's parameter table before anything is written. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "cli_generator.h"
#include "cmd_sweep.h"
#include "sessile/sds/sds_run.h"

#define SWEEP_ERR(...) (cli_usage_error("sweep plan", __VA_ARGS__))

/* cJSON keeps duplicate keys; a sweep file must not have them (the last one
 * winning would hide a mistake). */
static const char *duplicate_key(const cJSON *o) {
  for (const cJSON *a = o ? o->child : NULL; a; a = a->next) {
    if (cJSON_IsObject(o))
      for (const cJSON *b = a->next; b; b = b->next)
        if (!strcmp(a->string, b->string)) return a->string;
    const char *d = duplicate_key(a);
    if (d) return d;
  }
  return NULL;
}

static int only_keys(const cJSON *o, const char *where, const char *const *keys) {
  for (const cJSON *it = o->child; it; it = it->next) {
    int k = 0;
    while (keys[k] && strcmp(keys[k], it->string)) k++;
    if (!keys[k]) return SWEEP_ERR("%s: unknown key '%.60s'", where, it->string);
  }
  return EXIT_OK;
}

const char *sweep_number(double v, char buf[40]) {
  for (int p = 15; p <= 17; p++) {
    snprintf(buf, 40, "%.*g", p, v);
    if (strtod(buf, NULL) == v) break;
  }
  return buf;
}

static char *number_text(double v) {
  char buf[40];
  return strdup(sweep_number(v, buf));
}

/* A JSON value as --set spells it: numbers, true/false, strings as given. */
static char *value_text(const cJSON *v) {
  if (cJSON_IsNumber(v)) return number_text(v->valuedouble);
  if (cJSON_IsBool(v)) return strdup(cJSON_IsTrue(v) ? "true" : "false");
  if (cJSON_IsString(v) && v->valuestring[0]) return strdup(v->valuestring);
  return NULL;
}

static const sessile_generator *find_generator(sweep_spec *s, const char *name) {
  char *words[8], buf[256];
  int n = 0;
  snprintf(buf, sizeof buf, "%s", name);
  for (char *t = strtok(buf, " "); t && n < 8; t = strtok(NULL, " ")) words[n++] = t;
  int used = 0;
  const sessile_generator *g = n ? cli_generator_find(n, words, &used) : NULL;
  if (!g && n >= 2 && !strcmp(words[0], "sds") && !strcmp(words[1], "run")) g = &sessile_gen_sds, used = 2;
  s->nwords = n;
  return g;
}

static int read_axis(sweep_spec *s, const cJSON *ax, int a) {
  static const char *const keys[] = {"parameter", "values", "range", NULL};
  char where[96];
  snprintf(where, sizeof where, "axes[%d]", a);
  if (!cJSON_IsObject(ax)) return SWEEP_ERR("%s must be an object", where);
  if (only_keys(ax, where, keys)) return EXIT_USAGE;
  const cJSON *p = cJSON_GetObjectItemCaseSensitive(ax, "parameter");
  const cJSON *vals = cJSON_GetObjectItemCaseSensitive(ax, "values");
  const cJSON *range = cJSON_GetObjectItemCaseSensitive(ax, "range");
  if (!cJSON_IsString(p)) return SWEEP_ERR("%s: \"parameter\" must be a parameter's name", where);
  sweep_axis *x = &s->axes[a];
  x->param = p->valuestring;
  if (!vals == !range) return SWEEP_ERR("axis %.60s: give \"values\" or \"range\", one of them", x->param);
  if (vals) {
    if (!cJSON_IsArray(vals)) return SWEEP_ERR("axis %.60s: \"values\" must be a list", x->param);
    x->n = cJSON_GetArraySize(vals);
    if (x->n > SWEEP_MAX_POINTS) return SWEEP_ERR("axis %.60s: more than %d values", x->param, SWEEP_MAX_POINTS);
    if (x->n && !(x->values = calloc((size_t)x->n, sizeof *x->values))) return sweep_oom("sweep plan");
    int k = 0;
    for (const cJSON *v = vals->child; v; v = v->next, k++)
      if (!(x->values[k] = value_text(v)))
        return SWEEP_ERR("axis %.60s: value %d must be a number, true/false or a name", x->param, k);
  } else {
    static const char *const rk[] = {"from", "to", "step", "count", NULL};
    if (!cJSON_IsObject(range) || only_keys(range, "range", rk)) return SWEEP_ERR("axis %.60s: \"range\" is {from, to, step or count}", x->param);
    const cJSON *f = cJSON_GetObjectItemCaseSensitive(range, "from"), *t = cJSON_GetObjectItemCaseSensitive(range, "to");
    const cJSON *st = cJSON_GetObjectItemCaseSensitive(range, "step"), *c = cJSON_GetObjectItemCaseSensitive(range, "count");
    if (!cJSON_IsNumber(f) || !cJSON_IsNumber(t) || !st == !c || (st && !cJSON_IsNumber(st)) || (c && !cJSON_IsNumber(c)))
      return SWEEP_ERR("axis %.60s: \"range\" needs numbers from, to and one of step or count", x->param);
    double from = f->valuedouble, to = t->valuedouble, n;
    if (st) {
      if (!(st->valuedouble > 0) || to < from) return SWEEP_ERR("axis %.60s: a range's step must be above 0 and to >= from", x->param);
      n = floor((to - from) / st->valuedouble * (1 + 1e-12)) + 1;
    } else {
      n = c->valuedouble;
      if (n != floor(n) || n < 0) return SWEEP_ERR("axis %.60s: a range's count must be a whole number", x->param);
    }
    if (n > SWEEP_MAX_POINTS) return SWEEP_ERR("axis %.60s: more than %d values", x->param, SWEEP_MAX_POINTS);
    x->n = (int)n;
    if (x->n && !(x->values = calloc((size_t)x->n, sizeof *x->values))) return sweep_oom("sweep plan");
    for (int k = 0; k < x->n; k++) {
      /* from + k*step (not a running sum): the same values on every machine */
      double v = st ? from + k * st->valuedouble : x->n == 1 ? from : from + (to - from) * k / (x->n - 1);
      char buf[40]; /* 15 digits: a step of 0.1 gives 0.3, not 0.30000000000000004 */
      snprintf(buf, sizeof buf, "%.15g", v);
      if (!(x->values[k] = strdup(buf))) return sweep_oom("sweep plan");
    }
  }
  if (x->n == 0) return SWEEP_ERR("axis %.60s has no values", x->param);
  return EXIT_OK;
}

static int read_seeds(sweep_spec *s, const cJSON *sd) {
  if (!sd) {
    s->seeds = calloc(1, sizeof *s->seeds);
    if (!s->seeds) return sweep_oom("sweep plan");
    s->seeds[0] = 1, s->nseeds = 1; /* the generators' default seed */
    return EXIT_OK;
  }
  const cJSON *cnt = cJSON_IsObject(sd) ? cJSON_GetObjectItemCaseSensitive(sd, "count") : NULL;
  const cJSON *first = cJSON_IsObject(sd) ? cJSON_GetObjectItemCaseSensitive(sd, "first") : NULL;
  static const char *const sk[] = {"count", "first", NULL};
  if (cJSON_IsObject(sd) && only_keys(sd, "seeds", sk)) return EXIT_USAGE;
  if (cJSON_IsArray(sd)) s->nseeds = cJSON_GetArraySize(sd);
  else if (cJSON_IsNumber(cnt) && cnt->valuedouble == floor(cnt->valuedouble) && cnt->valuedouble >= 0 &&
           cnt->valuedouble <= SWEEP_MAX_POINTS && (!first || cJSON_IsNumber(first)))
    s->nseeds = (int)cnt->valuedouble;
  else return SWEEP_ERR("\"seeds\" is a list of seeds or {\"count\": N, \"first\": S}");
  if (s->nseeds == 0) return SWEEP_ERR("\"seeds\" has none");
  if (s->nseeds > SWEEP_MAX_POINTS) return SWEEP_ERR("more than %d seeds", SWEEP_MAX_POINTS);
  if (!(s->seeds = calloc((size_t)s->nseeds, sizeof *s->seeds))) return sweep_oom("sweep plan");
  double f = first ? first->valuedouble : 1;
  for (int k = 0; k < s->nseeds; k++) {
    const cJSON *v = cJSON_IsArray(sd) ? cJSON_GetArrayItem(sd, k) : NULL;
    double d = v ? (cJSON_IsNumber(v) ? v->valuedouble : -1) : f + k;
    /* JSON numbers are doubles: seeds up to 2^53 are exact */
    if (!(d >= 0 && d <= 9007199254740992.0 && d == floor(d))) return SWEEP_ERR("seed %d is not an integer in 0..2^53", k);
    s->seeds[k] = (unsigned long long)d;
  }
  return EXIT_OK;
}

static int read_strings(const cJSON *a, const char *what, const char **out, int max, int *n) {
  if (!a) return EXIT_OK;
  if (!cJSON_IsArray(a)) return SWEEP_ERR("\"%s\" must be a list of strings", what);
  for (const cJSON *v = a->child; v; v = v->next) {
    if (!cJSON_IsString(v) || !v->valuestring[0]) return SWEEP_ERR("\"%s\" must be a list of strings", what);
    if (*n >= max) return SWEEP_ERR("\"%s\": more than %d", what, max);
    out[(*n)++] = v->valuestring;
  }
  return EXIT_OK;
}

/* Options the sweep itself gives every point; a sweep file must not. */
static int check_options(const sweep_spec *s) {
  static const char *const owned[] = {"--out", "--seed", "--set", "--config", "--resume", "--force",
                                      "--iterations", "--print-config", "--help", "-h", NULL};
  for (int k = 0; k < s->noptions; k++)
    for (int j = 0; owned[j]; j++)
      if (!strcmp(s->options[k], owned[j]))
        return SWEEP_ERR("\"options\": %s is the sweep's to give (docs/sweep.md)", owned[j]);
  return EXIT_OK;
}

void sweep_combo(const sweep_spec *s, long c, int idx[SWEEP_MAX_AXES]) {
  for (int a = s->naxes - 1; a >= 0; a--) {
    if (s->zip) idx[a] = (int)c;
    else idx[a] = (int)(c % s->axes[a].n), c /= s->axes[a].n; /* the last axis varies fastest */
  }
}

/* Every combination through the table: base, then the axes' values, then
 * the table's ranges and cross checks.  The first failure names the point. */
static int validate(const sweep_spec *s, const sessile_generator *g) {
  const sessile_param_table *t = g->table;
  static char params[1 << 14] __attribute__((aligned(16)));
  if (t->struct_size > sizeof params) return SWEEP_ERR("%s: parameters too large", g->name);
  for (int a = 0; a < s->naxes; a++) {
    if (!sessile_params_find(t, s->axes[a].param))
      return SWEEP_ERR("axes: %s has no parameter '%.60s' (sessile %s --print-config)", g->name, s->axes[a].param, s->generator);
    for (int b = 0; b < a; b++)
      if (!strcmp(s->axes[a].param, s->axes[b].param)) return SWEEP_ERR("axes: %.60s twice", s->axes[a].param);
    for (int b = 0; b < s->nbase; b++)
      if (!strcmp(s->axes[a].param, s->base_keys[b])) return SWEEP_ERR("%.60s is in both \"base\" and \"axes\"", s->axes[a].param);
  }
  for (int b = 0; b < s->nbase; b++)
    if (!sessile_params_find(t, s->base_keys[b]))
      return SWEEP_ERR("base: %s has no parameter '%.60s' (sessile %s --print-config)", g->name, s->base_keys[b], s->generator);
  int idx[SWEEP_MAX_AXES];
  for (long c = 0; c < s->ncombos; c++) {
    sweep_combo(s, c, idx);
    sessile_params_defaults(t, params);
    sessile_status st = SESSILE_OK;
    for (int b = 0; b < s->nbase && st == SESSILE_OK; b++)
      st = sessile_params_set_text(t, params, s->base_keys[b], s->base_values[b]);
    for (int a = 0; a < s->naxes && st == SESSILE_OK; a++)
      st = sessile_params_set_text(t, params, s->axes[a].param, s->axes[a].values[idx[a]]);
    if (st == SESSILE_OK) st = sessile_params_check(t, params);
    if (st != SESSILE_OK) {
      char m[600];
      snprintf(m, sizeof m, "%s", sessile_error_message());
      return SWEEP_ERR("point %ld (combination %ld of %ld): %s", c * s->nseeds, c, s->ncombos, m);
    }
  }
  return EXIT_OK;
}

static int parse(sweep_spec *s, const char *path) {
  char *text = sweep_read_text(path, 1 << 22);
  if (!text) return SWEEP_ERR("cannot read '%.200s' (a JSON file of at most 4 MiB)", path);
  const char *end = NULL;
  s->root = cJSON_ParseWithOpts(text, &end, 1);
  long at = end ? (long)(end - text) : 0L;
  free(text);
  if (!s->root) return SWEEP_ERR("%.200s: not JSON (near byte %ld)", path, at);
  if (!cJSON_IsObject(s->root)) return SWEEP_ERR("%.200s: a sweep is a JSON object", path);
  const char *dup = duplicate_key(s->root);
  if (dup) return SWEEP_ERR("%.200s: key '%.60s' given twice", path, dup);
  static const char *const keys[] = {"generator", "options", "iterations", "base", "axes", "combine", "seeds", "metrics", NULL};
  return only_keys(s->root, path, keys);
}

int sweep_spec_load(const char *path, sweep_spec *s) {
  memset(s, 0, sizeof *s);
  if (parse(s, path)) return EXIT_USAGE;
  const cJSON *r = s->root;
  const cJSON *gen = cJSON_GetObjectItemCaseSensitive(r, "generator");
  if (!cJSON_IsString(gen)) return SWEEP_ERR("\"generator\" must name a generator (sessile --help)");
  s->generator = gen->valuestring;
  const sessile_generator *g = find_generator(s, s->generator);
  if (!g) return SWEEP_ERR("unknown generator '%.60s' (sessile --help lists them; SDS: \"sds run MODEL\")", s->generator);
  if (g == &sessile_gen_sds && s->nwords != 3) return SWEEP_ERR("\"sds run MODEL\": name one model");
  if (g != &sessile_gen_sds && (s->nwords != 1 + (strchr(g->name, ' ') != NULL)))
    return SWEEP_ERR("\"generator\": '%.60s' takes no further words", g->name);
  s->default_iterations = g->no_iterations ? -1 : g->iterations;
  s->iterations = -1;
  const cJSON *it = cJSON_GetObjectItemCaseSensitive(r, "iterations");
  if (it && g->no_iterations) return SWEEP_ERR("\"iterations\": %s", g->no_iterations);
  if (it && !(cJSON_IsNumber(it) && it->valuedouble == floor(it->valuedouble) && it->valuedouble >= 0 && it->valuedouble <= 1e7))
    return SWEEP_ERR("\"iterations\" must be a whole number in 0..10000000");
  if (it) s->iterations = (int)it->valuedouble;
  if (read_strings(cJSON_GetObjectItemCaseSensitive(r, "options"), "options", s->options, SWEEP_MAX_ARGS, &s->noptions) ||
      check_options(s) ||
      read_strings(cJSON_GetObjectItemCaseSensitive(r, "metrics"), "metrics", s->metrics, 64, &s->nmetrics))
    return EXIT_USAGE;
  const cJSON *base = cJSON_GetObjectItemCaseSensitive(r, "base");
  if (base && !cJSON_IsObject(base)) return SWEEP_ERR("\"base\" must be an object of parameter: value");
  for (const cJSON *b = base ? base->child : NULL; b; b = b->next) {
    if (s->nbase >= 64) return SWEEP_ERR("\"base\": more than 64 parameters");
    s->base_keys[s->nbase] = b->string;
    if (!(s->base_values[s->nbase++] = value_text(b))) return SWEEP_ERR("base: %.60s must be a number, true/false or a name", b->string);
  }
  const cJSON *comb = cJSON_GetObjectItemCaseSensitive(r, "combine");
  if (comb && !(cJSON_IsString(comb) && (!strcmp(comb->valuestring, "grid") || !strcmp(comb->valuestring, "zip"))))
    return SWEEP_ERR("\"combine\" is \"grid\" or \"zip\"");
  s->zip = comb && !strcmp(comb->valuestring, "zip");
  const cJSON *axes = cJSON_GetObjectItemCaseSensitive(r, "axes");
  if (axes && !cJSON_IsArray(axes)) return SWEEP_ERR("\"axes\" must be a list");
  if (cJSON_GetArraySize(axes) > SWEEP_MAX_AXES) return SWEEP_ERR("more than %d axes", SWEEP_MAX_AXES);
  for (const cJSON *a = axes ? axes->child : NULL; a; a = a->next, s->naxes++)
    if (read_axis(s, a, s->naxes)) return s->naxes++, EXIT_USAGE;
  if (read_seeds(s, cJSON_GetObjectItemCaseSensitive(r, "seeds"))) return EXIT_USAGE;
  double combos = 1;
  for (int a = 0; a < s->naxes; a++) {
    if (s->zip && s->axes[a].n != s->axes[0].n)
      return SWEEP_ERR("\"zip\": axes %.60s and %.60s differ in length (%d, %d)", s->axes[0].param, s->axes[a].param,
                       s->axes[0].n, s->axes[a].n);
    combos = s->zip ? s->axes[a].n : combos * s->axes[a].n;
  }
  if (combos * s->nseeds > SWEEP_MAX_POINTS)
    return SWEEP_ERR("%.0f points: a sweep holds at most %d (split it)", combos * s->nseeds, SWEEP_MAX_POINTS);
  s->ncombos = (long)combos, s->npoints = s->ncombos * s->nseeds;
  return validate(s, g);
}

void sweep_spec_free(sweep_spec *s) {
  for (int a = 0; a < s->naxes; a++) {
    for (int k = 0; k < s->axes[a].n; k++) free(s->axes[a].values[k]);
    free(s->axes[a].values);
  }
  for (int b = 0; b < s->nbase; b++) free(s->base_values[b]);
  free(s->seeds);
  cJSON_Delete(s->root);
  memset(s, 0, sizeof *s);
}
