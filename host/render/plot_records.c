/* sessile render — plots of a run's records.jsonl (one JSON object per line,
 * docs/run.md): presets for `sessile grow` (solver iterations, seconds per
 * iteration by stage) and `sessile sds run` (ms per step against cells, as
 * in Fig. 12 of Porter & McCormack's SDS paper), or any keys. */
#include <cjson/cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/render/render2d.h"

typedef struct preset {
  const char *name, *title, *xlabel, *ylabel, *x;
  const char *y[SESSILE_PLOT_MAX_SERIES], *label[SESSILE_PLOT_MAX_SERIES];
  const char *skip_zero; /* records with 0 at this key have no y (NULL: none) */
} preset;

static const preset presets[] = {
    {"solver", "Solver iterations per growth iteration", "growth iteration", "solver iterations", "iteration",
     {"nutrient_solve.iterations", "fluid.linear_iterations"},
     {"nutrient (PCG + multigrid)", "flow (linear, all Newton steps)"}, NULL},
    {"time", "Time per growth iteration", "growth iteration", "time per iteration (s)", "iteration",
     {"seconds.total", "seconds.nutrient", "seconds.fluid", "seconds.remesh", "seconds.classify", "seconds.growth",
      "seconds.output", "seconds.upload"},
     {"total", "nutrient", "fluid", "remesh", "classify", "growth", "output", "upload"}, NULL},
    /* frame 0 is written before any step: its ms_per_step 0 is no measurement */
    {"steps", "Time per step against cells", "cells", "time per step (ms)", "cells", {"ms_per_step"},
     {"ms per step"}, "steps"},
};

/* The number at a dotted key ("seconds.total"), or NaN. */
static double get_number(const cJSON *rec, const char *key) {
  char part[128];
  const cJSON *node = rec;
  while (node && *key) {
    size_t n = strcspn(key, ".");
    if (n >= sizeof part) return NAN;
    memcpy(part, key, n);
    part[n] = 0;
    node = cJSON_GetObjectItemCaseSensitive(node, part);
    key += n + (key[n] == '.');
  }
  return node && cJSON_IsNumber(node) ? node->valuedouble : NAN;
}

typedef struct columns {
  double *v[1 + SESSILE_PLOT_MAX_SERIES];
  size_t n, cap;
} columns;

static void columns_free(columns *c) {
  for (int k = 0; k <= SESSILE_PLOT_MAX_SERIES; k++) free(c->v[k]);
}

/* Every record's x and y values (NaN where a record lacks a key). */
static sessile_status read_records(const char *path, const char *x, const char *const *y, int ny,
                                   const char *skip_zero, columns *c) {
  FILE *f = fopen(path, "r");
  SESSILE_CHECK(f, SESSILE_ERR_USAGE, "cannot read '%s': %s", path, strerror(errno));
  sessile_status st = SESSILE_OK;
  char *line = NULL;
  size_t lcap = 0;
  long lineno = 0;
  while (st == SESSILE_OK && getline(&line, &lcap, f) >= 0) {
    lineno++;
    if (strspn(line, " \t\r\n") == strlen(line)) continue;
    cJSON *rec = cJSON_Parse(line);
    if (!rec || !cJSON_IsObject(rec)) {
      cJSON_Delete(rec);
      st = sessile_error_set(SESSILE_ERR_USAGE, "'%s' line %ld is not a JSON object (not a records.jsonl?)", path, lineno);
      break;
    }
    if (c->n == c->cap) {
      size_t cap = c->cap ? 2 * c->cap : 64;
      for (int k = 0; k <= ny && st == SESSILE_OK; k++) {
        double *v = realloc(c->v[k], cap * sizeof *v);
        if (!v) st = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of memory reading '%s'", path);
        else c->v[k] = v;
      }
      c->cap = cap;
    }
    if (st == SESSILE_OK) {
      c->v[0][c->n] = get_number(rec, x);
      int skip = skip_zero && get_number(rec, skip_zero) == 0;
      for (int k = 0; k < ny; k++) c->v[1 + k][c->n] = skip ? NAN : get_number(rec, y[k]);
      c->n++;
    }
    cJSON_Delete(rec);
  }
  /* getline's -1 is the end only at the end of the file: else a read error
   * or no memory, which must not pass as a shorter file */
  if (st == SESSILE_OK && !feof(f))
    st = sessile_error_set(errno == ENOMEM ? SESSILE_ERR_NO_MEMORY : SESSILE_ERR_IO, "cannot read '%s': %s", path,
                           strerror(errno));
  free(line);
  fclose(f);
  return st;
}

sessile_status sessile_render_plot_records(const char *records_jsonl, const char *what,
                                           const sessile_render2d_opts *o, const char *png_out) {
  SESSILE_CHECK(records_jsonl && records_jsonl[0], SESSILE_ERR_USAGE, "no records file given");
  SESSILE_CHECK(what && what[0], SESSILE_ERR_USAGE, "no plot given (solver, time, steps, or XKEY:YKEY[,YKEY...])");
  SESSILE_CHECK(png_out && png_out[0], SESSILE_ERR_USAGE, "no output picture given");
  preset custom = {0};
  const preset *pr = NULL;
  char spec[512];
  for (size_t k = 0; k < sizeof presets / sizeof presets[0]; k++)
    if (!strcmp(presets[k].name, what)) pr = &presets[k];
  if (!pr) {
    SESSILE_CHECK(strlen(what) < sizeof spec && strchr(what, ':'), SESSILE_ERR_USAGE,
                  "unknown plot '%s' (solver, time, steps, or XKEY:YKEY[,YKEY...])", what);
    snprintf(spec, sizeof spec, "%s", what);
    char *colon = strchr(spec, ':');
    *colon = 0;
    custom.x = custom.xlabel = spec;
    int ny = 0;
    for (char *save = NULL, *tok = strtok_r(colon + 1, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
      SESSILE_CHECK(ny < SESSILE_PLOT_MAX_SERIES, SESSILE_ERR_USAGE, "plot '%s': at most %d y keys", what,
                    SESSILE_PLOT_MAX_SERIES);
      custom.y[ny] = custom.label[ny] = tok;
      ny++;
    }
    SESSILE_CHECK(ny > 0 && spec[0], SESSILE_ERR_USAGE, "plot '%s': give XKEY:YKEY[,YKEY...]", what);
    custom.ylabel = ny == 1 ? custom.y[0] : "value";
    pr = &custom;
  }
  int ny = 0;
  while (ny < SESSILE_PLOT_MAX_SERIES && pr->y[ny]) ny++;
  columns c = {0};
  sessile_status st = read_records(records_jsonl, pr->x, pr->y, ny, pr->skip_zero, &c);
  sessile_plot p = {.title = pr->title, .xlabel = pr->xlabel, .ylabel = pr->ylabel};
  for (int k = 0; st == SESSILE_OK && k < ny; k++) { /* series absent from every record are left out */
    int any = 0;
    for (size_t i = 0; i < c.n && !any; i++) any = isfinite(c.v[0][i]) && isfinite(c.v[1 + k][i]);
    if (any) p.series[p.nseries++] = (sessile_plot_series){pr->label[k], c.v[0], c.v[1 + k], c.n, 0, NULL, NULL};
  }
  if (st == SESSILE_OK && p.nseries == 0) {
    char keys[400] = "";
    for (int k = 0; k < ny; k++) {
      size_t len = strlen(keys);
      snprintf(keys + len, sizeof keys - len, "%s%s", k ? ", " : "", pr->y[k]);
    }
    st = sessile_error_set(SESSILE_ERR_USAGE, "no record in '%s' has %s with any of: %s (%zu records)", records_jsonl,
                           pr->x, keys, c.n);
  }
  if (st == SESSILE_OK) st = sessile_render_plot(&p, o, png_out);
  columns_free(&c);
  return st;
}
