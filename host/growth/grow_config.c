/* The configuration of a growth run as JSON: stored in the manifest so that
 * `sessile grow --resume DIR` restarts with exactly the same parameters,
 * preset, seed and snapshot settings. */
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include "grow_internal.h"

cJSON *sessile_grow_config(const sessile_params *p, const sessile_grow_options *o) {
  cJSON *c = cJSON_CreateObject();
  if (!c) return NULL;
  char seed[32];
  snprintf(seed, sizeof seed, "%llu", (unsigned long long)o->seed);
  cJSON_AddStringToObject(c, "preset", o->preset ? o->preset : "");
  cJSON_AddStringToObject(c, "seed", seed);
  cJSON_AddNumberToObject(c, "iterations", o->iterations);
  cJSON_AddNumberToObject(c, "every", o->every);
  cJSON_AddStringToObject(c, "slices", o->slices ? o->slices : "");
  cJSON_AddBoolToObject(c, "fields", o->fields != 0);
  cJSON *params = sessile_params_to_config(&sessile_grow_param_table, p);
  if (!params || !cJSON_AddItemToObject(c, "parameters", params)) {
    cJSON_Delete(params);
    cJSON_Delete(c);
    return NULL;
  }
  return c;
}

static sessile_status bad(const char *what) {
  return sessile_error_set(SESSILE_ERR_USAGE, "the run's stored configuration is damaged (%s)", what);
}

sessile_status sessile_grow_config_read(const cJSON *cfg, sessile_params *p, sessile_grow_options *o) {
  const cJSON *preset = cJSON_GetObjectItemCaseSensitive(cfg, "preset");
  const cJSON *seed = cJSON_GetObjectItemCaseSensitive(cfg, "seed");
  const cJSON *its = cJSON_GetObjectItemCaseSensitive(cfg, "iterations");
  const cJSON *every = cJSON_GetObjectItemCaseSensitive(cfg, "every");
  const cJSON *slices = cJSON_GetObjectItemCaseSensitive(cfg, "slices");
  const cJSON *fields = cJSON_GetObjectItemCaseSensitive(cfg, "fields");
  const cJSON *params = cJSON_GetObjectItemCaseSensitive(cfg, "parameters");
  if (!cJSON_IsString(preset) || !cJSON_IsString(seed) || !cJSON_IsNumber(its) ||
      !cJSON_IsNumber(every) || !cJSON_IsString(slices) || !cJSON_IsBool(fields) || !cJSON_IsObject(params))
    return bad("a member is missing or of the wrong kind");
  char *end = NULL;
  errno = 0;
  unsigned long long sv = strtoull(seed->valuestring, &end, 10);
  if (!seed->valuestring[0] || *end || errno || seed->valuestring[0] == '-') return bad("seed");
  if (its->valuedouble < 0 || its->valuedouble > 1e7 || every->valuedouble < 0 || every->valuedouble > 1e7)
    return bad("iterations");
  o->preset = preset->valuestring;
  o->seed = sv;
  o->iterations = (int)its->valuedouble;
  o->every = (int)every->valuedouble;
  o->slices = slices->valuestring;
  o->fields = cJSON_IsTrue(fields);
  sessile_params_default(p);
  sessile_status s = sessile_params_apply_json(&sessile_grow_param_table, p, params, "the run's stored configuration");
  SESSILE_CALL(s);
  return sessile_params_validate(p);
}
