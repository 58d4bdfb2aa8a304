/* The configuration every generator with iterations stores for --resume
 * (sessile/run/run.h): seed, iterations, snapshot interval and its parameter
 * table's values, written and read back in one place. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include "sessile/run/run.h"

cJSON *sessile_run_config_make(const sessile_param_table *t, const void *params, uint64_t seed, int iterations,
                               int every) {
  cJSON *c = cJSON_CreateObject();
  if (!c) return NULL;
  char text[32];
  snprintf(text, sizeof text, "%llu", (unsigned long long)seed);
  cJSON *pj = sessile_params_to_config(t, params);
  if (!cJSON_AddStringToObject(c, "seed", text) || !cJSON_AddNumberToObject(c, "iterations", iterations) ||
      !cJSON_AddNumberToObject(c, "every", every) || !pj || !cJSON_AddItemToObject(c, "parameters", pj)) {
    if (pj && !cJSON_GetObjectItemCaseSensitive(c, "parameters")) cJSON_Delete(pj);
    cJSON_Delete(c);
    return NULL;
  }
  return c;
}

sessile_status sessile_run_config_take(const cJSON *cfg, const sessile_param_table *t, void *params, uint64_t *seed,
                                       int *iterations, int *every) {
  const cJSON *sj = cJSON_GetObjectItemCaseSensitive(cfg, "seed");
  const cJSON *its = cJSON_GetObjectItemCaseSensitive(cfg, "iterations");
  const cJSON *ev = cJSON_GetObjectItemCaseSensitive(cfg, "every");
  const cJSON *pj = cJSON_GetObjectItemCaseSensitive(cfg, "parameters");
  SESSILE_CHECK(cJSON_IsString(sj) && cJSON_IsNumber(its) && cJSON_IsNumber(ev) && cJSON_IsObject(pj) &&
                    its->valuedouble >= 0 && its->valuedouble <= 1e9 && ev->valuedouble >= 0 &&
                    ev->valuedouble <= 1e9,
                SESSILE_ERR_USAGE, "the run's stored configuration is damaged");
  char *end = NULL;
  errno = 0;
  unsigned long long v = strtoull(sj->valuestring, &end, 10);
  SESSILE_CHECK(sj->valuestring[0] >= '0' && sj->valuestring[0] <= '9' && !*end && !errno, SESSILE_ERR_USAGE,
                "the run's stored seed is damaged");
  *seed = v;
  *iterations = (int)its->valuedouble;
  *every = (int)ev->valuedouble;
  sessile_params_defaults(t, params);
  for (const sessile_param_before *b = t->before; b && b->name; b++) /* a run made before b existed */
    if (!cJSON_GetObjectItemCaseSensitive(pj, b->name)) SESSILE_CALL(sessile_params_set_text(t, params, b->name, b->value));
  SESSILE_CALL(sessile_params_apply_json(t, params, pj, "the run's stored configuration"));
  return sessile_params_check(t, params);
}
