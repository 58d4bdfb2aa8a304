/* Parameter tables (sessile/run/param_table.h): defaults, strict text and JSON
 * parsing, checks, printing and the manifest record, for every generator. */
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>
#include "sessile/run/param_table.h"

#define CONFIG_MAX_BYTES (1u << 20)

static double get(const sessile_param_desc *d, const void *values) {
  const char *base = (const char *)values + d->offset;
  if (d->type == SESSILE_PT_REAL) return *(const double *)base;
  return *(const int *)base;
}

static void put(const sessile_param_desc *d, void *values, double v) {
  char *base = (char *)values + d->offset;
  if (d->type == SESSILE_PT_REAL) *(double *)base = v;
  else *(int *)base = (int)v;
}

double sessile_params_value(const sessile_param_table *t, const void *values, int i) {
  return get(&t->params[i], values);
}

void sessile_params_defaults(const sessile_param_table *t, void *values) {
  memset(values, 0, t->struct_size);
  for (int i = 0; i < t->count; i++) put(&t->params[i], values, t->params[i].def);
}

const sessile_param_desc *sessile_params_find(const sessile_param_table *t, const char *name) {
  for (int i = 0; name && i < t->count; i++)
    if (strcmp(t->params[i].name, name) == 0) return &t->params[i];
  for (const sessile_param_alias *a = t->aliases; name && a && a->old_name; a++)
    if (strcmp(a->old_name, name) == 0) return sessile_params_find(t, a->name);
  return NULL;
}

static sessile_status unknown(const sessile_param_table *t, const char *where, const char *key) {
  return sessile_error_set(SESSILE_ERR_USAGE,
                           "%s%sunknown parameter '%.80s' ('sessile %s --print-config' lists them all)",
                           where ? where : "", where ? ": " : "", key, t->generator);
}

/* "[0, 1]", "(0, 1e+06]": the range as the checks apply it. */
static void range_text(const sessile_param_desc *d, char *buf, size_t n) {
  snprintf(buf, n, "%c%g, %g%c", d->flags & SESSILE_PARAM_LO_OPEN ? '(' : '[', d->lo, d->hi,
           d->flags & SESSILE_PARAM_HI_OPEN ? ')' : ']');
}

static sessile_status range_error(const sessile_param_desc *d, const char *where, const char *text) {
  char rg[96];
  range_text(d, rg, sizeof rg);
  if (d->type == SESSILE_PT_INT)
    return sessile_error_set(SESSILE_ERR_USAGE, "%s%sparameter %s: '%.60s' is not an integer in %s",
                             where ? where : "", where ? ": " : "", d->name, text, rg);
  return sessile_error_set(SESSILE_ERR_USAGE, "%s%sparameter %s: '%.60s' is not a number in %s%s%s",
                           where ? where : "", where ? ": " : "", d->name, text, rg,
                           *d->unit ? " " : "", d->unit);
}

static int in_range(const sessile_param_desc *d, double v) {
  if (!isfinite(v)) return 0;
  if (d->flags & SESSILE_PARAM_LO_OPEN ? v <= d->lo : v < d->lo) return 0;
  if (d->flags & SESSILE_PARAM_HI_OPEN ? v >= d->hi : v > d->hi) return 0;
  return d->type != SESSILE_PT_INT || v == floor(v);
}

static sessile_status set_number(const sessile_param_desc *d, void *values, double v,
                                 const char *where, const char *text) {
  if (!in_range(d, v)) return range_error(d, where, text);
  put(d, values, v);
  return SESSILE_OK;
}

/* Decimal numbers only: strtod alone would take "0x1p3", "inf", "nan" and
 * leading blanks. */
static int plain_number(const char *s, int integer) {
  if (*s == '+' || *s == '-') s++;
  if (!*s) return 0;
  for (; *s; s++) {
    if (*s >= '0' && *s <= '9') continue;
    if (integer) return 0;
    if (!strchr(".eE+-", *s)) return 0;
  }
  return 1;
}

static sessile_status set_enum(const sessile_param_desc *d, void *values, const char *where,
                               const char *text) {
  char list[160] = "";
  for (int i = 0; d->names[i]; i++) {
    if (!strcasecmp(text, d->names[i])) {
      put(d, values, i);
      return SESSILE_OK;
    }
    size_t l = strlen(list);
    snprintf(list + l, sizeof list - l, "%s%s", i ? ", " : "", d->names[i]);
  }
  return sessile_error_set(SESSILE_ERR_USAGE, "%s%sparameter %s: '%.60s' is not one of %s",
                           where ? where : "", where ? ": " : "", d->name, text, list);
}

sessile_status sessile_params_set_text(const sessile_param_table *t, void *values, const char *key,
                                       const char *text) {
  const sessile_param_desc *d = sessile_params_find(t, key);
  if (!d) return unknown(t, NULL, key);
  SESSILE_CHECK(text && *text, SESSILE_ERR_USAGE, "parameter %s needs a value", key);
  if (d->type == SESSILE_PT_BOOL) {
    if (!strcasecmp(text, "true") || !strcmp(text, "1") || !strcasecmp(text, "yes")) put(d, values, 1);
    else if (!strcasecmp(text, "false") || !strcmp(text, "0") || !strcasecmp(text, "no")) put(d, values, 0);
    else return sessile_error_set(SESSILE_ERR_USAGE, "parameter %s: '%.60s' is not true or false", key, text);
    return SESSILE_OK;
  }
  if (d->type == SESSILE_PT_ENUM) return set_enum(d, values, NULL, text);
  if (!plain_number(text, d->type == SESSILE_PT_INT)) return range_error(d, NULL, text);
  char *end = NULL;
  errno = 0;
  double v = strtod(text, &end);
  if (end == text || *end || errno == ERANGE) return range_error(d, NULL, text);
  return set_number(d, values, v, NULL, text);
}

sessile_status sessile_params_set_kv(const sessile_param_table *t, void *values, const char *kv) {
  const char *eq = strchr(kv, '=');
  SESSILE_CHECK(eq && eq != kv && eq - kv < 128, SESSILE_ERR_USAGE,
                "--set '%.80s' must be KEY=VALUE", kv);
  char key[128];
  memcpy(key, kv, (size_t)(eq - kv));
  key[eq - kv] = 0;
  return sessile_params_set_text(t, values, key, eq + 1);
}

static sessile_status apply_item(const sessile_param_table *t, void *values, const cJSON *it,
                                 const char *where) {
  const sessile_param_desc *d = sessile_params_find(t, it->string);
  if (!d) return unknown(t, where, it->string ? it->string : "");
  switch (d->type) {
  case SESSILE_PT_BOOL:
    SESSILE_CHECK(cJSON_IsBool(it), SESSILE_ERR_USAGE, "%s: %s must be true or false", where, d->name);
    put(d, values, cJSON_IsTrue(it));
    return SESSILE_OK;
  case SESSILE_PT_ENUM:
    SESSILE_CHECK(cJSON_IsString(it), SESSILE_ERR_USAGE, "%s: %s must be a string (%s, ...)", where,
                  d->name, d->names[0]);
    return set_enum(d, values, where, it->valuestring);
  default: {
    SESSILE_CHECK(cJSON_IsNumber(it), SESSILE_ERR_USAGE, "%s: %s must be a number", where, d->name);
    char txt[64];
    snprintf(txt, sizeof txt, "%.17g", it->valuedouble);
    return set_number(d, values, it->valuedouble, where, txt);
  }
  }
}

sessile_status sessile_params_apply_json_text(const sessile_param_table *t, void *values,
                                              const char *text, size_t len, const char *where) {
  SESSILE_CHECK(len <= CONFIG_MAX_BYTES, SESSILE_ERR_USAGE, "%s: larger than %u bytes", where,
                CONFIG_MAX_BYTES);
  const char *nul = memchr(text, 0, len);
  SESSILE_CHECK(!nul, SESSILE_ERR_USAGE, "%s: holds a NUL byte at offset %zu (not JSON text)", where,
                (size_t)(nul - text));
  /* cJSON reads up to a terminator: parse a terminated copy. */
  char *copy = malloc(len + 1);
  SESSILE_CHECK(copy, SESSILE_ERR_NO_MEMORY, "out of host memory reading %s", where);
  memcpy(copy, text, len);
  copy[len] = 0;
  const char *errp = NULL;
  /* require_null_terminated: anything but blanks after the value is an error */
  cJSON *root = cJSON_ParseWithLengthOpts(copy, len + 1, &errp, 1);
  if (!root) {
    size_t at = errp && errp >= copy ? (size_t)(errp - copy) : 0, line = 1, col = 1;
    for (size_t i = 0; i < at && i < len; i++) {
      if (copy[i] == '\n') line++, col = 1;
      else col++;
    }
    free(copy);
    return sessile_error_set(SESSILE_ERR_USAGE,
                             "%s:%zu:%zu: not valid JSON (one object, nothing after it)", where, line, col);
  }
  free(copy);
  sessile_status s = sessile_params_apply_json(t, values, root, where);
  cJSON_Delete(root);
  return s;
}

sessile_status sessile_params_apply_json(const sessile_param_table *t, void *values, const cJSON *root,
                                         const char *where) {
  sessile_status s = SESSILE_OK;
  if (!cJSON_IsObject(root))
    s = sessile_error_set(SESSILE_ERR_USAGE, "%s: must hold one JSON object {\"key\": value, ...}", where);
  for (const cJSON *it = root ? root->child : NULL; s == SESSILE_OK && it; it = it->next) {
    for (const cJSON *o = it->next; o; o = o->next) {
      if (!it->string || !o->string) continue;
      const sessile_param_desc *d = sessile_params_find(t, it->string);
      if (!strcmp(it->string, o->string)) {
        s = sessile_error_set(SESSILE_ERR_USAGE, "%s: parameter '%.80s' is given twice", where, it->string);
        break;
      }
      if (d && d == sessile_params_find(t, o->string)) { /* a name and its earlier name */
        s = sessile_error_set(SESSILE_ERR_USAGE, "%s: parameter '%.80s' is given twice (also as '%.80s')", where,
                              d->name, strcmp(it->string, d->name) ? it->string : o->string);
        break;
      }
    }
    if (s == SESSILE_OK) s = apply_item(t, values, it, where);
  }
  return s;
}

sessile_status sessile_params_load_json(const sessile_param_table *t, void *values, const char *path) {
  SESSILE_CHECK(path && *path, SESSILE_ERR_USAGE, "--config needs a file name");
  /* O_NONBLOCK: a FIFO must not hang us in open(); we refuse it below. */
  int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  SESSILE_CHECK(fd >= 0, SESSILE_ERR_USAGE, "cannot read config file '%s': %s", path, strerror(errno));
  struct stat st;
  if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    close(fd);
    return sessile_error_set(SESSILE_ERR_USAGE, "config file '%s' is not a regular file", path);
  }
  if (st.st_size > (off_t)CONFIG_MAX_BYTES) {
    close(fd);
    return sessile_error_set(SESSILE_ERR_USAGE, "config file '%s' is larger than %u bytes", path,
                             CONFIG_MAX_BYTES);
  }
  size_t cap = (size_t)st.st_size + 1, len = 0;
  char *text = malloc(cap);
  if (!text) {
    close(fd);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory reading '%s'", path);
  }
  for (;;) {
    ssize_t r = read(fd, text + len, cap - len);
    if (r < 0 && errno == EINTR) continue;
    if (r < 0) {
      int e = errno;
      free(text);
      close(fd);
      return sessile_error_set(SESSILE_ERR_USAGE, "cannot read config file '%s': %s", path, strerror(e));
    }
    if (r == 0) break;
    len += (size_t)r;
    if (len == cap) { /* the file grew while we read it */
      free(text);
      close(fd);
      return sessile_error_set(SESSILE_ERR_USAGE, "config file '%s' changed while it was read", path);
    }
  }
  close(fd);
  char where[600];
  snprintf(where, sizeof where, "config file '%.500s'", path);
  sessile_status s = sessile_params_apply_json_text(t, values, text, len, where);
  free(text);
  return s;
}

sessile_status sessile_params_check(const sessile_param_table *t, const void *values) {
  for (int i = 0; i < t->count; i++) {
    const sessile_param_desc *d = &t->params[i];
    double v = get(d, values);
    char txt[64];
    snprintf(txt, sizeof txt, "%.17g", v);
    if (d->type == SESSILE_PT_BOOL) SESSILE_CHECK(v == 0 || v == 1, SESSILE_ERR_USAGE, "parameter %s: %s is not true or false", d->name, txt);
    else if (d->type == SESSILE_PT_ENUM) {
      int n = 0;
      while (d->names[n]) n++;
      SESSILE_CHECK(v >= 0 && v < n, SESSILE_ERR_USAGE, "parameter %s: %s is not a known value", d->name, txt);
    } else if (!in_range(d, v)) return range_error(d, NULL, txt);
  }
  return t->validate ? t->validate(values) : SESSILE_OK;
}

static void value_text(const sessile_param_desc *d, double v, char *buf, size_t n) {
  if (d->type == SESSILE_PT_ENUM) snprintf(buf, n, "%s", d->names[(int)v]);
  else if (d->type == SESSILE_PT_BOOL) snprintf(buf, n, "%s", v ? "true" : "false");
  else snprintf(buf, n, "%.10g", v);
}

sessile_status sessile_params_print(const sessile_param_table *t, const void *values, FILE *out) {
  fprintf(out, "%-34s %-14s %-6s %-16s %-16s %s\n", "parameter", "value", "unit", "range", "source",
          "meaning");
  for (int i = 0; i < t->count; i++) {
    const sessile_param_desc *d = &t->params[i];
    char val[48], rg[96] = "";
    value_text(d, get(d, values), val, sizeof val);
    if (d->type == SESSILE_PT_ENUM) {
      for (int k = 0; d->names[k]; k++) {
        size_t l = strlen(rg);
        snprintf(rg + l, sizeof rg - l, "%s%s", k ? "|" : "", d->names[k]);
      }
    } else if (d->type == SESSILE_PT_BOOL) snprintf(rg, sizeof rg, "true|false");
    else range_text(d, rg, sizeof rg);
    fprintf(out, "%-34s %-14s %-6s %-16s %-16s %s\n", d->name, val, d->unit, rg, d->source, d->meaning);
  }
  SESSILE_CHECK(fflush(out) == 0 && !ferror(out), SESSILE_ERR_IO,
                "cannot write the parameter list: %s", strerror(errno));
  return SESSILE_OK;
}

/* Reals as raw "%.17g" text: cJSON's own printer keeps 15 digits when they
 * read back within its tolerance, which loses bits (0.1 + 0.2 prints as 0.3)
 * and a resumed run must restart from the very same values. */
static cJSON *value_json(const sessile_param_desc *d, double v) {
  if (d->type == SESSILE_PT_ENUM) return cJSON_CreateString(d->names[(int)v]);
  if (d->type == SESSILE_PT_BOOL) return cJSON_CreateBool(v != 0);
  char txt[40];
  snprintf(txt, sizeof txt, "%.17g", v);
  return cJSON_CreateRaw(txt);
}

cJSON *sessile_params_to_json(const sessile_param_table *t, const void *values) {
  cJSON *o = cJSON_CreateObject();
  for (int i = 0; o && i < t->count; i++) {
    const sessile_param_desc *d = &t->params[i];
    cJSON *pi = cJSON_AddObjectToObject(o, d->name);
    if (!pi) break;
    cJSON_AddItemToObject(pi, "value", value_json(d, get(d, values)));
    cJSON_AddStringToObject(pi, "unit", d->unit);
    cJSON_AddStringToObject(pi, "source", d->source);
  }
  return o;
}

cJSON *sessile_params_to_config(const sessile_param_table *t, const void *values) {
  cJSON *o = cJSON_CreateObject();
  for (int i = 0; o && i < t->count; i++)
    cJSON_AddItemToObject(o, t->params[i].name, value_json(&t->params[i], get(&t->params[i], values)));
  return o;
}
