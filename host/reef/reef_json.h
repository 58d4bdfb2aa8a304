/* Strict reading of the scene's JSON (reef_json.c): every object is read
 * through a reader that refuses unknown and duplicate keys, each message
 * naming the JSON path ("pool[1].size"). */
#ifndef SESSILE_REEF_JSON_H
#define SESSILE_REEF_JSON_H
#include <cjson/cJSON.h>
#include <stdint.h>
#include "sessile/status.h"

typedef struct rj_obj {
  const cJSON *obj;
  char path[160];
  const char *where; /* the file */
} rj_obj;

/* The object at path (SESSILE_ERR_USAGE when not an object or a key repeats). */
sessile_status rj_open(rj_obj *o, const cJSON *obj, const char *where, const char *path);
/* Refuses any key not in the NULL-terminated list. */
sessile_status rj_known(const rj_obj *o, const char *const *keys);
/* A member (NULL: absent). */
const cJSON *rj_get(const rj_obj *o, const char *key);
/* A number in [lo, hi] (*v kept when absent and !required). */
sessile_status rj_num(const rj_obj *o, const char *key, int required, double lo, double hi, double *v);
sessile_status rj_int(const rj_obj *o, const char *key, int required, double lo, double hi, int *v);
sessile_status rj_bool(const rj_obj *o, const char *key, int *v);
/* A string, copied (*v kept when absent and !required). */
sessile_status rj_str(const rj_obj *o, const char *key, int required, char **v);
/* An array of exactly n numbers in [lo, hi] (n 0: any length up to max, *got set). */
sessile_status rj_nums(const rj_obj *o, const char *key, int required, int n, double lo, double hi, double *v);
/* A seed: a non-negative integer number or a decimal string (64 bits). */
sessile_status rj_seed(const rj_obj *o, const char *key, uint64_t *v);
/* A usage error naming "where: path.key". */
sessile_status rj_fail(const rj_obj *o, const char *key, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
#endif
