/* Strict JSON reading for the scene file (reef_json.h). */
#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "reef/reef_json.h"

sessile_status rj_fail(const rj_obj *o, const char *key, const char *fmt, ...) {
  char msg[256];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  const char *dot = key && o->path[0] ? "." : "";
  return sessile_error_set(SESSILE_ERR_USAGE, "%s: %s%s%s: %s", o->where, o->path, dot, key ? key : "", msg);
}

sessile_status rj_open(rj_obj *o, const cJSON *obj, const char *where, const char *path) {
  o->obj = obj, o->where = where;
  snprintf(o->path, sizeof o->path, "%s", path);
  if (!cJSON_IsObject(obj)) return rj_fail(o, NULL, "must be a JSON object");
  for (const cJSON *a = obj->child; a; a = a->next)
    for (const cJSON *b = a->next; b; b = b->next)
      if (!strcmp(a->string, b->string)) return rj_fail(o, a->string, "the key appears twice");
  return SESSILE_OK;
}

sessile_status rj_known(const rj_obj *o, const char *const *keys) {
  for (const cJSON *a = o->obj->child; a; a = a->next) {
    int k = 0;
    while (keys[k] && strcmp(keys[k], a->string)) k++;
    if (!keys[k]) {
      char list[256] = "";
      for (k = 0; keys[k]; k++)
        snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", k ? ", " : "", keys[k]);
      return rj_fail(o, a->string, "unknown key (known: %s)", list);
    }
  }
  return SESSILE_OK;
}

const cJSON *rj_get(const rj_obj *o, const char *key) { return cJSON_GetObjectItemCaseSensitive(o->obj, key); }

static sessile_status number(const rj_obj *o, const char *key, const cJSON *j, double lo, double hi, double *v) {
  if (!cJSON_IsNumber(j) || !isfinite(j->valuedouble)) return rj_fail(o, key, "must be a number");
  if (!(j->valuedouble >= lo && j->valuedouble <= hi))
    return rj_fail(o, key, "%g is outside [%g, %g]", j->valuedouble, lo, hi);
  *v = j->valuedouble;
  return SESSILE_OK;
}

sessile_status rj_num(const rj_obj *o, const char *key, int required, double lo, double hi, double *v) {
  const cJSON *j = rj_get(o, key);
  if (!j) return required ? rj_fail(o, key, "is required") : SESSILE_OK;
  return number(o, key, j, lo, hi, v);
}

sessile_status rj_int(const rj_obj *o, const char *key, int required, double lo, double hi, int *v) {
  double d = *v;
  SESSILE_CALL(rj_num(o, key, required, lo, hi, &d));
  if (d != floor(d)) return rj_fail(o, key, "must be an integer (not %g)", d);
  *v = (int)d;
  return SESSILE_OK;
}

sessile_status rj_bool(const rj_obj *o, const char *key, int *v) {
  const cJSON *j = rj_get(o, key);
  if (!j) return SESSILE_OK;
  if (!cJSON_IsBool(j)) return rj_fail(o, key, "must be true or false");
  *v = cJSON_IsTrue(j);
  return SESSILE_OK;
}

sessile_status rj_str(const rj_obj *o, const char *key, int required, char **v) {
  const cJSON *j = rj_get(o, key);
  if (!j) return required ? rj_fail(o, key, "is required") : SESSILE_OK;
  if (!cJSON_IsString(j) || !j->valuestring[0]) return rj_fail(o, key, "must be a non-empty string");
  char *c = strdup(j->valuestring);
  SESSILE_CHECK(c, SESSILE_ERR_NO_MEMORY, "out of host memory");
  free(*v);
  *v = c;
  return SESSILE_OK;
}

sessile_status rj_nums(const rj_obj *o, const char *key, int required, int n, double lo, double hi, double *v) {
  const cJSON *j = rj_get(o, key);
  if (!j) return required ? rj_fail(o, key, "is required") : SESSILE_OK;
  if (!cJSON_IsArray(j) || cJSON_GetArraySize(j) != n) return rj_fail(o, key, "must be an array of %d numbers", n);
  int k = 0;
  char sub[64];
  for (const cJSON *e = j->child; e; e = e->next, k++) {
    snprintf(sub, sizeof sub, "%s[%d]", key, k);
    SESSILE_CALL(number(o, sub, e, lo, hi, &v[k]));
  }
  return SESSILE_OK;
}

sessile_status rj_seed(const rj_obj *o, const char *key, uint64_t *v) {
  const cJSON *j = rj_get(o, key);
  if (!j) return SESSILE_OK;
  if (cJSON_IsNumber(j) && j->valuedouble >= 0 && j->valuedouble <= 9007199254740992.0 &&
      j->valuedouble == floor(j->valuedouble)) {
    *v = (uint64_t)j->valuedouble;
    return SESSILE_OK;
  }
  if (cJSON_IsString(j) && j->valuestring[0] >= '0' && j->valuestring[0] <= '9') {
    char *end = NULL;
    errno = 0;
    unsigned long long u = strtoull(j->valuestring, &end, 10);
    if (!*end && errno == 0) {
      *v = (uint64_t)u;
      return SESSILE_OK;
    }
  }
  return rj_fail(o, key, "must be an integer 0..2^53 or a decimal string 0..2^64-1");
}
