/* Fuzz target of the parameter parser (sessile/run/param_table.h): the input is
 * fed to sessile_params_apply_json_text for both generators' tables (grow,
 * sphere), and its first line to sessile_params_set_kv.  Whatever the input,
 * a call that returns SESSILE_OK must leave every parameter inside its
 * table's range (finite, within [lo, hi] or the open bound, an integer for
 * integer parameters, a known enum value, 0/1 for booleans), and the values
 * must survive the manifest's round trip (to_config -> JSON text -> apply)
 * unchanged; anything else is a bug and aborts.  Built with libFuzzer by
 * tools/fuzz/run.sh, or with driver.c (plain main) by CMake's
 * fuzz_params_short. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/run/param_table.h"
#include "sessile/growth/grow_params.h"
#include "sessile/sphere/sphere.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void fail(const sessile_param_table *t, const char *what, int i, double v) {
  fprintf(stderr, "fuzz_params: %s table: %s (parameter %s, value %.17g; last message: %s)\n",
          t->generator, what, i >= 0 ? t->params[i].name : "-", v, sessile_error_message());
  abort();
}

/* Every parameter within its own range: what sessile_params_check's first
 * half checks, restated here independently of param_table.c. */
static void check_ranges(const sessile_param_table *t, const void *values) {
  for (int i = 0; i < t->count; i++) {
    const sessile_param_desc *d = &t->params[i];
    double v = sessile_params_value(t, values, i);
    if (d->type == SESSILE_PT_BOOL) {
      if (v != 0 && v != 1) fail(t, "boolean outside {0, 1}", i, v);
      continue;
    }
    if (d->type == SESSILE_PT_ENUM) {
      int n = 0;
      while (d->names[n]) n++;
      if (!(v >= 0 && v < n) || v != floor(v)) fail(t, "enum index outside its names", i, v);
      continue;
    }
    if (!isfinite(v)) fail(t, "value not finite", i, v);
    if (d->flags & SESSILE_PARAM_LO_OPEN ? !(v > d->lo) : !(v >= d->lo)) fail(t, "value below its range", i, v);
    if (d->flags & SESSILE_PARAM_HI_OPEN ? !(v < d->hi) : !(v <= d->hi)) fail(t, "value above its range", i, v);
    if (d->type == SESSILE_PT_INT && v != floor(v)) fail(t, "integer parameter not integral", i, v);
  }
}

/* The manifest's record read back gives the same values (a resume relies on it). */
static void check_round_trip(const sessile_param_table *t, const void *values) {
  cJSON *cfg = sessile_params_to_config(t, values);
  char *text = cfg ? cJSON_PrintUnformatted(cfg) : NULL;
  cJSON_Delete(cfg);
  if (!text) return; /* out of memory: not the parser's contract */
  _Alignas(16) unsigned char back[4096];
  if (t->struct_size > sizeof back) fail(t, "struct larger than the scratch buffer", -1, 0);
  sessile_params_defaults(t, back);
  sessile_status s = sessile_params_apply_json_text(t, back, text, strlen(text), "round trip");
  if (s != SESSILE_OK) {
    fprintf(stderr, "fuzz_params: round trip text: %s\n", text);
    fail(t, "the manifest's config was refused when read back", -1, 0);
  }
  free(text);
  for (int i = 0; i < t->count; i++) {
    double a = sessile_params_value(t, values, i), b = sessile_params_value(t, back, i);
    if (a != b) fail(t, "value changed through the manifest's round trip", i, a);
  }
}

/* The accepted values also go through the whole check (cross-parameter
 * rules may refuse them, but must not crash) and, with print, through
 * --print-config. */
static void check_accepted(const sessile_param_table *t, const void *values, int print) {
  check_ranges(t, values);
  (void)sessile_params_check(t, values);
  check_round_trip(t, values);
  if (!print) return;
  static FILE *devnull;
  if (!devnull) devnull = fopen("/dev/null", "w");
  if (devnull && sessile_params_print(t, values, devnull) != SESSILE_OK)
    fail(t, "printing accepted values failed", -1, 0);
}

static void one_table(const sessile_param_table *t, const uint8_t *data, size_t size, const char *line) {
  _Alignas(16) unsigned char values[4096];
  if (t->struct_size > sizeof values) fail(t, "struct larger than the scratch buffer", -1, 0);
  sessile_params_defaults(t, values);
  check_ranges(t, values); /* the defaults themselves */
  if (sessile_params_apply_json_text(t, values, (const char *)data, size, "fuzz") == SESSILE_OK)
    check_accepted(t, values, 1);
  /* --set with the first line, on defaults and on whatever the JSON left */
  sessile_params_defaults(t, values);
  if (sessile_params_set_kv(t, values, line) == SESSILE_OK) check_accepted(t, values, 1);
  if (strchr(line, '=')) {
    /* the same text as KEY=VALUE for each parameter name: reaches every
     * parameter's value parser even without the name in the input */
    const char *val = strchr(line, '=') + 1;
    for (int i = 0; i < t->count; i++) {
      sessile_params_defaults(t, values);
      if (sessile_params_set_text(t, values, t->params[i].name, val) == SESSILE_OK) check_accepted(t, values, 0);
    }
  }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  /* the first line as a C string (a NUL byte ends it early, as argv would) */
  size_t n = 0;
  while (n < size && data[n] != '\n') n++;
  char *line = malloc(n + 1);
  if (!line) return 0;
  memcpy(line, data, n);
  line[n] = 0;
  one_table(&sessile_grow_param_table, data, size, line);
  one_table(&sessile_sphere_param_table, data, size, line);
  free(line);
  return 0;
}
