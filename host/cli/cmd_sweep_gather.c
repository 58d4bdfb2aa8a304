/* `sweep gather DIR`: every point's parameters, seed, state and metrics (JSON
 * paths into its manifest) as DIR/gather/points.csv and points.jsonl, and per
 * combination of parameters over its seeds: n, mean, standard deviation and
 * the 95 % confidence interval of the mean (Student's t), as summary.csv and
 * summary.jsonl; then the plots and the contact sheet (cmd_sweep_pictures.c). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "cmd_sweep.h"
#include "sessile/io/io.h"

/* "totals.vertices", "a.b.0.c": object members and array indices. */
static const cJSON *json_path(const cJSON *j, const char *path) {
  char buf[512];
  snprintf(buf, sizeof buf, "%s", path);
  for (char *save = NULL, *t = strtok_r(buf, ".", &save); j && t; t = strtok_r(NULL, ".", &save)) {
    char *end;
    long i = strtol(t, &end, 10);
    j = cJSON_IsArray(j) && !*end && end != t ? cJSON_GetArrayItem(j, (int)i) : cJSON_GetObjectItemCaseSensitive(j, t);
  }
  return j;
}

/* The two-sided 95 % quantile of Student's t with df degrees of freedom. */
static double t95(int df) {
  static const double t[] = {12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228,
                             2.201,  2.179, 2.160, 2.145, 2.131, 2.120, 2.110, 2.101, 2.093, 2.086,
                             2.080,  2.074, 2.069, 2.064, 2.060, 2.056, 2.052, 2.048, 2.045, 2.042};
  return df <= 30 ? t[df - 1] : 1.95996 + 2.4 / df; /* within 0.002 past 30 */
}

static void csv_field(FILE *f, const char *s) {
  if (!strpbrk(s, ",\"\n\r")) {
    fputs(s, f);
    return;
  }
  fputc('"', f);
  for (; *s; s++) *s == '"' ? fputs("\"\"", f) : fputc(*s, f);
  fputc('"', f);
}

static void csv_number(FILE *f, double v) {
  char buf[40];
  if (isfinite(v)) fputs(sweep_number(v, buf), f);
}

/* The run's last record (records.jsonl), for "last_record.KEY" metrics. */
static cJSON *last_record(const char *dir, int index, int width) {
  char path[4096];
  snprintf(path, sizeof path, "%s/runs/%0*d/records.jsonl", dir, width, index);
  char *t = sweep_read_text(path, (size_t)1 << 28);
  size_t n = t ? strlen(t) : 0;
  while (n && (t[n - 1] == '\n' || t[n - 1] == '\r')) t[--n] = 0;
  char *l = t ? strrchr(t, '\n') : NULL;
  cJSON *r = t ? cJSON_Parse(l ? l + 1 : t) : NULL;
  free(t);
  return r;
}

/* A metric: a JSON path into the manifest, or into the last record. */
static const cJSON *metric(const cJSON *man, const cJSON *rec, const char *path) {
  static const char pre[] = "last_record.";
  return strncmp(path, pre, sizeof pre - 1) ? json_path(man, path) : json_path(rec, path + sizeof pre - 1);
}

static int save(const char *dir, const char *name, char *buf, size_t len) {
  char path[4096];
  snprintf(path, sizeof path, "%s/gather/%s", dir, name);
  sessile_status s = buf ? sessile_write_file_atomic(path, buf, len) : SESSILE_ERR_NO_MEMORY;
  free(buf);
  return s == SESSILE_OK ? EXIT_OK : cli_fail_in("sweep gather", s);
}

/* Out of host memory opening the two tables: whichever opened, closed. */
static int drop(FILE *a, FILE *b, char **ab, char **bb) {
  if (a) fclose(a);
  if (b) fclose(b);
  free(*ab), free(*bb);
  return sweep_oom("sweep gather");
}

typedef struct table {
  int n, nm;
  double *v;           /* n x nm, NAN where missing or not completed */
  unsigned char *done; /* n: 1 for a completed point */
  double *stat;        /* combinations x nm x 5: n, mean, sd, ci95_lo, ci95_hi (NAN where undefined) */
} table;

/* One row per point: points.csv and points.jsonl; fills t. */
static int points(const char *dir, const cJSON *plan, table *t) {
  int width = cJSON_GetObjectItemCaseSensitive(plan, "width")->valueint;
  const cJSON *pts = cJSON_GetObjectItemCaseSensitive(plan, "points");
  const cJSON *metrics = cJSON_GetObjectItemCaseSensitive(plan, "metrics");
  const cJSON *par0 = cJSON_GetObjectItemCaseSensitive(pts->child, "parameters");
  char *cb = NULL, *jb = NULL, err[1024];
  size_t cl = 0, jl = 0;
  FILE *c = open_memstream(&cb, &cl), *jf = open_memstream(&jb, &jl);
  if (!c || !jf) return drop(c, jf, &cb, &jb);
  fputs("index,combination,seed,state", c);
  for (const cJSON *p = par0 ? par0->child : NULL; p; p = p->next) fputc(',', c), csv_field(c, p->string);
  for (const cJSON *m = metrics->child; m; m = m->next) fputc(',', c), csv_field(c, m->valuestring);
  fputc('\n', c);
  int i = 0, done = 0;
  for (const cJSON *pt = pts->child; pt; pt = pt->next, i++) {
    sweep_state s = sweep_point_state(dir, i, width, err, sizeof err);
    cJSON *man = sweep_point_manifest(dir, i, width), *rec = s == PT_COMPLETED ? last_record(dir, i, width) : NULL, *row = cJSON_CreateObject(), *mo = cJSON_CreateObject();
    char seed[32];
    snprintf(seed, sizeof seed, "%.0f", cJSON_GetObjectItemCaseSensitive(pt, "seed")->valuedouble);
    fprintf(c, "%d,%d,%s,%s", i, cJSON_GetObjectItemCaseSensitive(pt, "combination")->valueint, seed, sweep_state_names[s]);
    cJSON_AddNumberToObject(row, "index", i);
    cJSON_AddNumberToObject(row, "combination", cJSON_GetObjectItemCaseSensitive(pt, "combination")->valueint);
    cJSON_AddRawToObject(row, "seed", seed);
    cJSON_AddStringToObject(row, "state", sweep_state_names[s]);
    if (err[0]) cJSON_AddStringToObject(row, "error", err);
    const cJSON *par = cJSON_GetObjectItemCaseSensitive(pt, "parameters");
    for (const cJSON *p = par ? par->child : NULL; p; p = p->next) fputc(',', c), csv_field(c, p->valuestring);
    cJSON_AddItemToObject(row, "parameters", cJSON_Duplicate(par, 1));
    int k = 0;
    for (const cJSON *m = metrics->child; m; m = m->next, k++) {
      const cJSON *v = s == PT_COMPLETED ? metric(man, rec, m->valuestring) : NULL;
      double d = cJSON_IsNumber(v) ? v->valuedouble : cJSON_IsBool(v) ? cJSON_IsTrue(v) : NAN;
      t->v[(size_t)i * t->nm + k] = d;
      fputc(',', c);
      if (cJSON_IsString(v)) csv_field(c, v->valuestring);
      else csv_number(c, d);
      cJSON_AddItemToObject(mo, m->valuestring, v ? cJSON_Duplicate(v, 1) : cJSON_CreateNull());
    }
    cJSON_AddItemToObject(row, "metrics", mo);
    fputc('\n', c);
    char *line = cJSON_PrintUnformatted(row);
    if (line) fprintf(jf, "%s\n", line);
    free(line);
    cJSON_Delete(row);
    cJSON_Delete(man);
    cJSON_Delete(rec);
    done += t->done[i] = s == PT_COMPLETED;
  }
  fclose(c), fclose(jf);
  int rc = save(dir, "points.csv", cb, cl);
  int rj = save(dir, "points.jsonl", jb, jl);
  if (!rc && !rj) printf("sweep: %d points (%d completed) in %s/gather/points.csv and points.jsonl\n", i, done, dir);
  return rc ? rc : rj;
}

/* Over the completed seeds of each combination: n, mean, sd, 95 % interval. */
static int summary(const char *dir, const cJSON *plan, table *t) {
  const cJSON *pts = cJSON_GetObjectItemCaseSensitive(plan, "points");
  const cJSON *metrics = cJSON_GetObjectItemCaseSensitive(plan, "metrics");
  int ncomb = cJSON_GetObjectItemCaseSensitive(plan, "combinations")->valueint;
  const cJSON *par0 = cJSON_GetObjectItemCaseSensitive(pts->child, "parameters");
  char *cb = NULL, *jb = NULL;
  size_t cl = 0, jl = 0;
  FILE *c = open_memstream(&cb, &cl), *jf = open_memstream(&jb, &jl);
  if (!c || !jf) return drop(c, jf, &cb, &jb);
  fputs("combination", c);
  for (const cJSON *p = par0 ? par0->child : NULL; p; p = p->next) fputc(',', c), csv_field(c, p->string);
  static const char *const stat[] = {"n", "mean", "sd", "ci95_lo", "ci95_hi"};
  for (const cJSON *m = metrics->child; m; m = m->next)
    for (int s = 0; s < 5; s++) fputc(',', c), csv_field(c, m->valuestring), fprintf(c, "_%s", stat[s]);
  fputc('\n', c);
  /* the plan's points are combination-major: combination c is the points
   * [c * nseeds, (c + 1) * nseeds) */
  int nseeds = ncomb ? t->n / ncomb : 0;
  const cJSON *first = pts->child;
  for (int cmb = 0; cmb < ncomb; cmb++) {
    const cJSON *par = cJSON_GetObjectItemCaseSensitive(first, "parameters");
    cJSON *row = cJSON_CreateObject(), *mo = cJSON_CreateObject();
    cJSON_AddNumberToObject(row, "combination", cmb);
    cJSON_AddItemToObject(row, "parameters", cJSON_Duplicate(par, 1));
    fprintf(c, "%d", cmb);
    for (const cJSON *p = par ? par->child : NULL; p; p = p->next) fputc(',', c), csv_field(c, p->valuestring);
    int k = 0;
    for (const cJSON *m = metrics->child; m; m = m->next, k++) {
      const double *v = t->v + (size_t)cmb * nseeds * t->nm + k;
      double sum = 0, ss = 0;
      int n = 0;
      for (int r = 0; r < nseeds; r++)
        if (isfinite(v[(size_t)r * t->nm])) sum += v[(size_t)r * t->nm], n++;
      double mean = n ? sum / n : NAN;
      for (int r = 0; r < nseeds; r++)
        if (isfinite(v[(size_t)r * t->nm])) ss += (v[(size_t)r * t->nm] - mean) * (v[(size_t)r * t->nm] - mean);
      double sd = n > 1 ? sqrt(ss / (n - 1)) : NAN, h = n > 1 ? t95(n - 1) * sd / sqrt(n) : NAN;
      double st[5] = {n, mean, sd, mean - h, mean + h};
      memcpy(t->stat + ((size_t)cmb * t->nm + k) * 5, st, sizeof st);
      cJSON *o = cJSON_CreateObject();
      for (int s = 0; s < 5; s++) {
        fputc(',', c), csv_number(c, st[s]);
        cJSON_AddItemToObject(o, stat[s], isfinite(st[s]) ? cJSON_CreateNumber(st[s]) : cJSON_CreateNull());
      }
      cJSON_AddItemToObject(mo, m->valuestring, o);
    }
    fputc('\n', c);
    cJSON_AddItemToObject(row, "metrics", mo);
    char *line = cJSON_PrintUnformatted(row);
    if (line) fprintf(jf, "%s\n", line);
    free(line);
    cJSON_Delete(row);
    for (int r = 0; r < nseeds && first; r++) first = first->next;
  }
  fclose(c), fclose(jf);
  int rc = save(dir, "summary.csv", cb, cl);
  int rj = save(dir, "summary.jsonl", jb, jl);
  if (!rc && !rj) printf("sweep: %d combinations in %s/gather/summary.csv and summary.jsonl\n", ncomb, dir);
  return rc ? rc : rj;
}

int sweep_cmd_gather(int argc, char **argv) {
  if (argc != 2 || argv[1][0] == '-') return cli_usage_error("sweep gather", "usage: sessile sweep gather DIR");
  const char *dir = argv[1];
  cJSON *plan = sweep_load_plan(dir);
  if (!plan) return EXIT_USAGE;
  char path[4096];
  snprintf(path, sizeof path, "%s/gather", dir);
  table t = {cJSON_GetArraySize(cJSON_GetObjectItemCaseSensitive(plan, "points")),
             cJSON_GetArraySize(cJSON_GetObjectItemCaseSensitive(plan, "metrics")), NULL, NULL, NULL};
  size_t nm = t.nm ? (size_t)t.nm : 1;
  t.v = calloc((size_t)t.n * nm, sizeof *t.v);
  t.done = calloc((size_t)t.n, 1);
  t.stat = calloc((size_t)cJSON_GetObjectItemCaseSensitive(plan, "combinations")->valueint * nm * 5, sizeof *t.stat);
  int rc = t.v && t.done && t.stat ? EXIT_OK : sweep_oom("sweep gather");
  sessile_status ms = rc ? SESSILE_OK : sessile_mkdirs(path);
  if (ms != SESSILE_OK) rc = cli_fail_in("sweep gather", ms);
  if (!rc) rc = points(dir, plan, &t);
  if (!rc) rc = summary(dir, plan, &t);
  if (!rc) rc = sweep_gather_pictures(dir, plan, t.stat, t.done);
  free(t.v), free(t.done), free(t.stat);
  cJSON_Delete(plan);
  return rc;
}
