/* The parameter table of `sessile grow` (sessile/params.h): defaults,
 * presets, text and JSON overrides with range checks, printing. */
#include <cjson/cJSON.h>
#include <errno.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include "sessile/params.h"

typedef enum { T_REAL, T_INT, T_BOOL, T_ENUM_SKELETON, T_ENUM_DOMAIN } ptype;

typedef struct {
  const char *name;
  ptype type;
  size_t offset;
  double def, lo, hi;
  const char *unit, *source, *desc;
} pdef;

static const pdef table[] = {
#define X(name, type, def, lo, hi, unit, src, desc)                                                \
  {#name, T_##type, offsetof(sessile_params, name), def, lo, hi, unit, src, desc},
    SESSILE_PARAMS(X)
#undef X
};
enum { NPARAMS = sizeof table / sizeof table[0] };

static const char *skeleton_names[] = {"radiate", "halichondrid", NULL};
static const char *domain_names[] = {"immersed", "conforming", NULL};

/* The names of an enum parameter's values (index = value), NULL-terminated. */
static const char *const *enum_names(ptype t) {
  return t == T_ENUM_SKELETON ? skeleton_names : t == T_ENUM_DOMAIN ? domain_names : NULL;
}

static double get(const sessile_params *p, const pdef *d) {
  const char *base = (const char *)p + d->offset;
  if (d->type == T_REAL) return *(const double *)base;
  return *(const int *)base;
}

static void put(sessile_params *p, const pdef *d, double v) {
  char *base = (char *)p + d->offset;
  if (d->type == T_REAL) *(double *)base = v;
  else *(int *)base = (int)v;
}

static const pdef *find(const char *key) {
  for (int i = 0; i < NPARAMS; i++)
    if (strcmp(table[i].name, key) == 0) return &table[i];
  return NULL;
}

void sessile_params_default(sessile_params *p) {
  memset(p, 0, sizeof *p);
  for (int i = 0; i < NPARAMS; i++) put(p, &table[i], table[i].def);
}

sessile_status sessile_params_preset(sessile_params *p, const char *name) {
  sessile_params_default(p);
  if (strcmp(name, "radiate") == 0) return SESSILE_OK;
  if (strcmp(name, "crella") == 0) {
    /* Halichondrid skeleton (eqs 1-2) + randomised x/y position (§4.7); the
     * normal offset radius and the jitter are ours (docs/model.md says why). */
    p->skeletal_growth = SESSILE_SKELETON_HALICHONDRID;
    p->normal_offset_radius = 0.5;
    p->position_jitter = 4.0;
    return SESSILE_OK;
  }
  return sessile_error_set(SESSILE_ERR_USAGE, "unknown preset '%s' (presets: radiate, crella)", name);
}

static sessile_status range_error(const pdef *d, const char *text) {
  if (d->type == T_INT)
    return sessile_error_set(SESSILE_ERR_USAGE, "parameter %s: '%s' is not an integer in %g..%g",
                             d->name, text, d->lo, d->hi);
  return sessile_error_set(SESSILE_ERR_USAGE, "parameter %s: '%s' is not a number in [%g, %g]%s%s",
                           d->name, text, d->lo, d->hi, *d->unit ? " " : "", d->unit);
}

/* Checks and stores a numeric value (text only for messages). */
static sessile_status set_number(sessile_params *p, const pdef *d, double v, const char *text) {
  if (!isfinite(v) || v < d->lo || v > d->hi) return range_error(d, text);
  if (d->type == T_INT && v != floor(v)) return range_error(d, text);
  put(p, d, v);
  return SESSILE_OK;
}

sessile_status sessile_params_set(sessile_params *p, const char *key, const char *value) {
  const pdef *d = find(key);
  SESSILE_CHECK(d, SESSILE_ERR_USAGE,
                "unknown parameter '%s' ('sessile grow --print-config' lists them all)", key);
  SESSILE_CHECK(value && *value, SESSILE_ERR_USAGE, "parameter %s needs a value", key);
  if (d->type == T_BOOL) {
    if (!strcasecmp(value, "true") || !strcmp(value, "1") || !strcasecmp(value, "yes")) put(p, d, 1);
    else if (!strcasecmp(value, "false") || !strcmp(value, "0") || !strcasecmp(value, "no")) put(p, d, 0);
    else return sessile_error_set(SESSILE_ERR_USAGE, "parameter %s: '%s' is not true or false", key, value);
    return SESSILE_OK;
  }
  const char *const *names = enum_names(d->type);
  if (names) {
    char list[128] = "";
    for (int i = 0; names[i]; i++) {
      if (!strcasecmp(value, names[i])) {
        put(p, d, i);
        return SESSILE_OK;
      }
      snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", i ? ", " : "", names[i]);
    }
    return sessile_error_set(SESSILE_ERR_USAGE, "parameter %s: '%s' is not one of %s", key, value, list);
  }
  char *end = NULL;
  errno = 0;
  double v = strtod(value, &end);
  if (end == value || *end || errno == ERANGE) return range_error(d, value);
  return set_number(p, d, v, value);
}

sessile_status sessile_params_load_json(sessile_params *p, const char *path) {
  FILE *f = fopen(path, "rb");
  SESSILE_CHECK(f, SESSILE_ERR_USAGE, "cannot read config file '%s': %s", path, strerror(errno));
  char *text = NULL;
  size_t len = 0, cap = 0;
  for (;;) {
    if (len + 4096 + 1 > cap) {
      cap = (len + 4096 + 1) * 2;
      char *t = realloc(text, cap);
      if (!t) {
        free(text), fclose(f);
        return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of memory reading '%s'", path);
      }
      text = t;
    }
    size_t r = fread(text + len, 1, 4096, f);
    len += r;
    if (r < 4096) break;
  }
  int rerr = ferror(f);
  fclose(f);
  if (rerr) {
    free(text);
    return sessile_error_set(SESSILE_ERR_USAGE, "cannot read config file '%s'", path);
  }
  text[len] = 0;
  const char *errp = NULL;
  cJSON *root = cJSON_ParseWithOpts(text, &errp, 1);
  if (!root) {
    size_t at = errp ? (size_t)(errp - text) : 0, line = 1;
    for (size_t i = 0; i < at && i < len; i++) line += text[i] == '\n';
    free(text);
    return sessile_error_set(SESSILE_ERR_USAGE, "config file '%s' is not valid JSON (near line %zu)",
                             path, line);
  }
  free(text);
  sessile_status s = SESSILE_OK;
  if (!cJSON_IsObject(root))
    s = sessile_error_set(SESSILE_ERR_USAGE, "config file '%s' must hold one JSON object", path);
  const cJSON *it = NULL;
  if (s == SESSILE_OK) cJSON_ArrayForEach(it, root) {
      const pdef *d = find(it->string);
      if (!d) {
        s = sessile_error_set(SESSILE_ERR_USAGE,
                              "config file '%s': unknown parameter '%s' ('sessile grow "
                              "--print-config' lists them all)", path, it->string);
        break;
      }
      if (d->type == T_BOOL) {
        if (!cJSON_IsBool(it)) {
          s = sessile_error_set(SESSILE_ERR_USAGE, "config file '%s': %s must be true or false",
                                path, d->name);
          break;
        }
        put(p, d, cJSON_IsTrue(it));
      } else if (enum_names(d->type)) {
        if (!cJSON_IsString(it)) {
          s = sessile_error_set(SESSILE_ERR_USAGE, "config file '%s': %s must be a string (%s, ...)",
                                path, d->name, enum_names(d->type)[0]);
          break;
        }
        s = sessile_params_set(p, d->name, it->valuestring);
      } else {
        if (!cJSON_IsNumber(it)) {
          s = sessile_error_set(SESSILE_ERR_USAGE, "config file '%s': %s must be a number", path,
                                d->name);
          break;
        }
        char txt[64];
        snprintf(txt, sizeof txt, "%.17g", it->valuedouble);
        s = set_number(p, d, it->valuedouble, txt);
      }
      if (s != SESSILE_OK) break;
    }
  cJSON_Delete(root);
  return s;
}

sessile_status sessile_params_validate(const sessile_params *p) {
  double top = p->box_base_cell * p->box_cells_z;
  double sx = p->box_base_cell * p->box_cells_x, sy = p->box_base_cell * p->box_cells_y;
  SESSILE_CHECK(p->sponge_z + p->sponge_radius < top && p->sponge_z < p->sponge_radius, SESSILE_ERR_USAGE,
                "the sponge (centre height sponge_z = %g cm, radius %g cm) does not fit under the "
                "box top (%g cm) or does not touch the substratum (sponge_z must be below the radius)",
                p->sponge_z, p->sponge_radius, top);
  SESSILE_CHECK(2 * p->sponge_radius < top && 2 * p->sponge_radius < sx && 2 * p->sponge_radius < sy,
                SESSILE_ERR_USAGE,
                "the sponge (radius %g cm) does not fit the box (%g x %g x %g cm); enlarge the box "
                "(box_cells_*, box_base_cell) or shrink sponge_radius",
                p->sponge_radius, sx, sy, top);
  double cx = p->sponge_x < 0 ? sx / 2 : p->sponge_x, cy = p->sponge_y < 0 ? sy / 2 : p->sponge_y;
  SESSILE_CHECK(cx - p->sponge_radius > 0 && cx + p->sponge_radius < sx && cy - p->sponge_radius > 0 &&
                    cy + p->sponge_radius < sy,
                SESSILE_ERR_USAGE, "the sponge centre (%g, %g) puts the sponge outside the box", cx, cy);
  SESSILE_CHECK(p->vertex_insertion_threshold > p->vertex_fusion_threshold, SESSILE_ERR_USAGE,
                "vertex_insertion_threshold (%g) must exceed vertex_fusion_threshold (%g)",
                p->vertex_insertion_threshold, p->vertex_fusion_threshold);
  SESSILE_CHECK(p->fluid_resolution <= p->box_resolution, SESSILE_ERR_USAGE,
                "fluid_resolution (%d) must not exceed box_resolution (%d)", p->fluid_resolution,
                p->box_resolution);
  return SESSILE_OK;
}

int sessile_params_count(void) { return NPARAMS; }

void sessile_params_get(const sessile_params *p, int i, sessile_param_info *info) {
  const pdef *d = &table[i];
  static const char *tn[] = {"real", "integer", "bool", "enum", "enum"};
  info->name = d->name;
  info->type = tn[d->type];
  info->unit = d->unit;
  info->source = d->source;
  info->description = d->desc;
  info->value = get(p, d);
  info->text = enum_names(d->type) ? enum_names(d->type)[(int)info->value] : NULL;
}

void sessile_params_print(const sessile_params *p, FILE *out) {
  fprintf(out, "%-34s %-14s %-6s %-14s %s\n", "parameter", "value", "unit", "source", "meaning");
  for (int i = 0; i < NPARAMS; i++) {
    sessile_param_info in;
    sessile_params_get(p, i, &in);
    char val[32];
    if (in.text) snprintf(val, sizeof val, "%s", in.text);
    else if (table[i].type == T_BOOL) snprintf(val, sizeof val, "%s", in.value ? "true" : "false");
    else snprintf(val, sizeof val, "%.10g", in.value);
    fprintf(out, "%-34s %-14s %-6s %-14s %s\n", in.name, val, in.unit, in.source, in.description);
  }
}
