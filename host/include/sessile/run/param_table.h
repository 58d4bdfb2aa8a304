/* sessile — parameter tables: every generator describes its parameters once
 * (name, type, default, range, unit, source, meaning; enums with their
 * names) in a table over its own struct, and this one module gives them all
 * the same defaults, JSON and --set parsing, checks, --print-config and
 * manifest record.  The table is the only source of each default.
 *
 * Parsing is strict: unknown keys, duplicate JSON keys, bytes after the JSON
 * value, NUL bytes, a JSON value of the wrong kind, a number outside the
 * parameter's range or not an integer for an integer parameter are all
 * SESSILE_ERR_USAGE with a one-line message naming the parameter. */
#ifndef SESSILE_PARAM_TABLE_H
#define SESSILE_PARAM_TABLE_H

#include <stddef.h>
#include <stdio.h>
#include <cjson/cJSON.h>
#include "sessile/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum sessile_ptype {
  SESSILE_PT_REAL, /* double */
  SESSILE_PT_INT,  /* int */
  SESSILE_PT_BOOL, /* int, 0 or 1 */
  SESSILE_PT_ENUM  /* int: index into names */
} sessile_ptype;

/* Bounds: lo/hi are inclusive unless the matching *_open flag is set (e.g.
 * kinetic_order > 0). */
enum { SESSILE_PARAM_LO_OPEN = 1, SESSILE_PARAM_HI_OPEN = 2 };

typedef struct sessile_param_desc {
  const char *name;
  sessile_ptype type;
  size_t offset; /* into the generator's struct */
  double def, lo, hi;
  unsigned flags; /* SESSILE_PARAM_*_OPEN */
  const char *unit, *source, *meaning;
  const char *const *names; /* enums: value names, NULL-terminated */
} sessile_param_desc;

/* An earlier name of a parameter, still read wherever names are read
 * (--set, --config, a stored run's configuration), so a rename breaks no
 * config file and no resume; printed and recorded under the new name only. */
typedef struct sessile_param_alias {
  const char *old_name, *name;
} sessile_param_alias;

/* A parameter added with a default that behaves otherwise than the code
 * before it: a stored run's configuration that lacks it (a run made before
 * the parameter existed) resumes with this value, the behaviour it started
 * with, so a resume across the upgrade goes on as it began. */
typedef struct sessile_param_before {
  const char *name, *value; /* value as text, as --set takes it */
} sessile_param_before;

typedef struct sessile_param_table {
  const char *generator; /* "grow", "sphere": named in messages */
  size_t struct_size;
  int count;
  const sessile_param_desc *params;
  /* Cross-parameter checks that need no device (NULL: none); called by
   * sessile_params_check after each parameter passed its own range. */
  sessile_status (*validate)(const void *values);
  const sessile_param_alias *aliases; /* ends with a NULL old_name; NULL: none */
  const sessile_param_before *before; /* ends with a NULL name; NULL: none */
} sessile_param_table;

/* Every parameter to its default. */
void sessile_params_defaults(const sessile_param_table *t, void *values);
/* The parameter called name, or whose earlier name it is (t->aliases); NULL. */
const sessile_param_desc *sessile_params_find(const sessile_param_table *t, const char *name);
/* One parameter from text ("0.3", "true", "halichondrid"). */
sessile_status sessile_params_set_text(const sessile_param_table *t, void *values, const char *key,
                                       const char *text);
/* One --set argument "KEY=VALUE". */
sessile_status sessile_params_set_kv(const sessile_param_table *t, void *values, const char *kv);
/* A JSON object of overrides held in text[0..len) ("where" names it in
 * messages: the file).  Booleans as true/false, enums as strings, numbers as
 * numbers. */
sessile_status sessile_params_apply_json_text(const sessile_param_table *t, void *values,
                                              const char *text, size_t len, const char *where);
/* The same from a parsed object (a stored config: values bit for bit). */
sessile_status sessile_params_apply_json(const sessile_param_table *t, void *values, const cJSON *obj,
                                         const char *where);
/* The same from a file: a regular file of at most 1 MiB, opened without
 * following a FIFO or device into a hang. */
sessile_status sessile_params_load_json(const sessile_param_table *t, void *values, const char *path);
/* Each value in its range and the table's cross-parameter checks. */
sessile_status sessile_params_check(const sessile_param_table *t, const void *values);
/* Every parameter: name, value, unit, source, meaning; SESSILE_ERR_IO when
 * the stream fails (a full disk, a closed pipe). */
sessile_status sessile_params_print(const sessile_param_table *t, const void *values, FILE *out);
/* {"name": {"value": v, "unit": u, "source": s}, ...} for the manifest. */
cJSON *sessile_params_to_json(const sessile_param_table *t, const void *values);
/* {"name": v, ...}: what sessile_params_apply_json_text reads back (resume). */
cJSON *sessile_params_to_config(const sessile_param_table *t, const void *values);
/* The value of parameter i as a double (enums and bools as numbers). */
double sessile_params_value(const sessile_param_table *t, const void *values, int i);

#ifdef __cplusplus
}
#endif
#endif
