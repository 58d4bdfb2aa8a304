/* `sessile sweep plan|run|task|status|submit|gather` (docs/sweep.md): the
 * dispatch, `plan` (the sweep folder from a sweep file) and what the other
 * subcommands share (the plan back, a point's state). */
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include <dirent.h>
#include "cmd_sweep.h"
#include "sessile/io/io.h"

const char *const sweep_state_names[] = {"pending", "running", "completed", "failed", "interrupted"};

char *sweep_read_text(const char *path, size_t max) {
  char *text = NULL;
  size_t len = 0;
  if (sessile_read_small_file(path, max, "file", &text, &len) != SESSILE_OK) return sessile_error_clear(), NULL;
  return text;
}

int sweep_oom(const char *cmd) {
  fprintf(stderr, "sessile %s: error: out of host memory\n", cmd);
  return EXIT_RUNTIME;
}

int sweep_width(int npoints) {
  int w = 1;
  for (int n = npoints > 1 ? npoints - 1 : 1; n >= 10; n /= 10) w++;
  return w < 4 ? 4 : w;
}

static int string_list(const cJSON *a) {
  if (!cJSON_IsArray(a)) return 0;
  for (const cJSON *v = a->child; v; v = v->next)
    if (!cJSON_IsString(v)) return 0;
  return 1;
}

/* What the subcommands read of a plan, checked once: an edited or damaged
 * sweep.json is refused, never followed into a crash. */
static int plan_ok(const cJSON *p) {
  const cJSON *w = cJSON_GetObjectItemCaseSensitive(p, "width"), *c = cJSON_GetObjectItemCaseSensitive(p, "combinations");
  const cJSON *pts = cJSON_GetObjectItemCaseSensitive(p, "points");
  if (!cJSON_IsNumber(w) || w->valueint < 4 || w->valueint > 6 || !cJSON_IsNumber(c) || c->valueint < 1 ||
      !string_list(cJSON_GetObjectItemCaseSensitive(p, "metrics")) || !cJSON_IsArray(pts))
    return 0;
  int n = cJSON_GetArraySize(pts), i = 0;
  if (n < 1 || n > SWEEP_MAX_POINTS || n % c->valueint) return 0;
  for (const cJSON *pt = pts->child; pt; pt = pt->next, i++) {
    const cJSON *ix = cJSON_GetObjectItemCaseSensitive(pt, "index"), *cb = cJSON_GetObjectItemCaseSensitive(pt, "combination");
    const cJSON *par = cJSON_GetObjectItemCaseSensitive(pt, "parameters");
    if (!cJSON_IsNumber(ix) || ix->valueint != i || !cJSON_IsNumber(cb) || cb->valueint != i / (n / c->valueint) ||
        !cJSON_IsNumber(cJSON_GetObjectItemCaseSensitive(pt, "seed")) || !cJSON_IsObject(par) ||
        !string_list(cJSON_GetObjectItemCaseSensitive(pt, "args")) ||
        !string_list(cJSON_GetObjectItemCaseSensitive(pt, "resume_args")))
      return 0;
    for (const cJSON *v = par->child; v; v = v->next)
      if (!cJSON_IsString(v)) return 0;
  }
  return 1;
}

cJSON *sweep_load_plan(const char *dir) {
  char path[4096];
  snprintf(path, sizeof path, "%s/sweep.json", dir);
  char *text = sweep_read_text(path, (size_t)1 << 30);
  cJSON *p = text ? cJSON_Parse(text) : NULL;
  free(text);
  if (!p || !plan_ok(p)) {
    cJSON_Delete(p);
    fprintf(stderr, "sessile sweep: error: '%.200s' holds no sweep plan (sweep.json; 'sessile sweep plan')\n", dir);
    return NULL;
  }
  return p;
}

cJSON *sweep_point_manifest(const char *dir, int index, int width) {
  char path[4096];
  snprintf(path, sizeof path, "%s/runs/%0*d/manifest.json", dir, width, index);
  char *text = sweep_read_text(path, (size_t)1 << 26);
  cJSON *m = text ? cJSON_Parse(text) : NULL;
  free(text);
  return m;
}

/* Whether the run's lock holder ("pid N on host H") is alive on this host;
 * on another host we cannot tell and believe the manifest. */
static int holder_alive(const char *dir, int index, int width) {
  char path[4096], host[256] = "", me[256] = "";
  snprintf(path, sizeof path, "%s/runs/%0*d/.sessile.lock", dir, width, index);
  char *t = sweep_read_text(path, 4096);
  long pid = 0;
  int ok = t && sscanf(t, "pid %ld on host %255s", &pid, host) == 2;
  free(t);
  if (!ok) return 0;
  gethostname(me, sizeof me - 1);
  if (strcmp(me, host)) return 1;
  if (pid <= 0 || (kill((pid_t)pid, 0) != 0 && errno != EPERM)) return 0;
  /* a killed run's zombie (never reaped where pid 1 does not reap) is dead */
  char st[512] = "";
  snprintf(path, sizeof path, "/proc/%ld/stat", pid);
  int fd = open(path, O_RDONLY | O_CLOEXEC);
  ssize_t k = fd >= 0 ? read(fd, st, sizeof st - 1) : 0;
  if (fd >= 0) close(fd);
  st[k > 0 ? k : 0] = 0;
  const char *p = strrchr(st, ')');
  return !p || (p[1] && p[2] != 'Z' && p[2] != 'X');
}

sweep_state sweep_point_state(const char *dir, int index, int width, char *error, size_t n) {
  if (n) error[0] = 0;
  cJSON *m = sweep_point_manifest(dir, index, width);
  const cJSON *st = cJSON_GetObjectItemCaseSensitive(m, "state");
  const cJSON *err = cJSON_GetObjectItemCaseSensitive(m, "error");
  sweep_state s = PT_PENDING;
  if (cJSON_IsString(st)) {
    const char *v = st->valuestring;
    s = !strcmp(v, "completed") ? PT_COMPLETED : !strcmp(v, "failed") ? PT_FAILED
        : !strcmp(v, "running") && holder_alive(dir, index, width) ? PT_RUNNING : PT_INTERRUPTED;
    if (s == PT_FAILED && cJSON_IsString(err) && n) snprintf(error, n, "%s", err->valuestring);
  } else {
    /* no run yet: the engine's record of a start that failed before one */
    char path[4096];
    snprintf(path, sizeof path, "%s/state/%0*d.json", dir, width, index);
    char *t = sweep_read_text(path, 65536);
    cJSON *r = t ? cJSON_Parse(t) : NULL;
    const cJSON *e = cJSON_GetObjectItemCaseSensitive(r, "error");
    if (cJSON_IsNumber(cJSON_GetObjectItemCaseSensitive(r, "exit")) &&
        cJSON_GetObjectItemCaseSensitive(r, "exit")->valueint != 0) {
      s = PT_FAILED;
      if (cJSON_IsString(e) && n) snprintf(error, n, "%s", e->valuestring);
    }
    cJSON_Delete(r);
    free(t);
  }
  cJSON_Delete(m);
  return s;
}

/* ---- plan ------------------------------------------------------------------ */

static cJSON *strings(const char *const *v, int n) {
  cJSON *a = cJSON_CreateArray();
  for (int k = 0; a && k < n; k++) cJSON_AddItemToArray(a, cJSON_CreateString(v[k]));
  return a;
}

/* The point's two command lines (after "sessile"), relative to the sweep
 * folder: a new run, and the resume of an interrupted one (which takes only
 * the generator's words, --iterations and the options that do not change
 * the run: device, --no-preview, --max-memory). */
static void point_args(const sweep_spec *s, cJSON *pt, const char *rel, unsigned long long seed, const cJSON *params) {
  const char *v[SWEEP_MAX_ARGS * 2 + 200];
  char words[256], seedtxt[32], iters[16], sets[64 + SWEEP_MAX_AXES][600];
  int n = 0, r = 0;
  snprintf(words, sizeof words, "%s", s->generator);
  const char *w[8];
  int nw = 0;
  for (char *t = strtok(words, " "); t && nw < 8; t = strtok(NULL, " ")) w[nw++] = t;
  for (int k = 0; k < nw; k++) v[n++] = w[k];
  for (int k = 0; k < s->noptions; k++) v[n++] = s->options[k];
  snprintf(seedtxt, sizeof seedtxt, "%llu", seed);
  snprintf(iters, sizeof iters, "%d", s->iterations);
  v[n++] = "--out", v[n++] = rel, v[n++] = "--seed", v[n++] = seedtxt;
  if (s->iterations >= 0) v[n++] = "--iterations", v[n++] = iters;
  int ns = 0;
  for (const cJSON *p = params->child; p; p = p->next, ns++) {
    snprintf(sets[ns], sizeof sets[ns], "%s=%s", p->string, p->valuestring);
    v[n++] = "--set", v[n++] = sets[ns];
  }
  v[n++] = "--quiet";
  cJSON_AddItemToObject(pt, "args", strings(v, n));
  const char *u[SWEEP_MAX_ARGS + 16];
  for (int k = 0; k < nw; k++) u[r++] = w[k];
  for (int k = 0; k < s->noptions; k++) { /* the options a resume takes (docs/run.md) go with it */
    const char *o = s->options[k];
    if (!strcmp(o, "--validation") || !strcmp(o, "--no-preview")) u[r++] = o;
    if ((!strcmp(o, "--device") || !strcmp(o, "--precision") || !strcmp(o, "--max-memory")) && k + 1 < s->noptions)
      u[r++] = o, u[r++] = s->options[++k];
  }
  u[r++] = "--resume", u[r++] = rel;
  if (s->iterations >= 0) u[r++] = "--iterations", u[r++] = iters;
  u[r++] = "--quiet";
  cJSON_AddItemToObject(pt, "resume_args", strings(u, r));
}

static cJSON *plan_json(const sweep_spec *s, int width) {
  cJSON *p = cJSON_CreateObject(), *axes = cJSON_CreateArray(), *pts = cJSON_CreateArray();
  if (!p || !axes || !pts) return cJSON_Delete(p), cJSON_Delete(axes), cJSON_Delete(pts), NULL;
  cJSON_AddStringToObject(p, "format", "sessile-sweep/1");
  cJSON_AddStringToObject(p, "generator", s->generator);
  cJSON_AddNumberToObject(p, "width", width);
  int iters = s->iterations >= 0 ? s->iterations : s->default_iterations;
  if (iters >= 0) cJSON_AddNumberToObject(p, "iterations", iters);
  cJSON_AddNumberToObject(p, "combinations", (double)s->ncombos);
  for (int a = 0; a < s->naxes; a++) cJSON_AddItemToArray(axes, cJSON_CreateString(s->axes[a].param));
  cJSON_AddItemToObject(p, "axes", axes);
  cJSON_AddItemToObject(p, "metrics", strings(s->metrics, s->nmetrics));
  cJSON_AddItemToObject(p, "sweep", cJSON_Duplicate(s->root, 1));
  cJSON_AddItemToObject(p, "points", pts);
  int idx[SWEEP_MAX_AXES];
  for (long i = 0; i < s->npoints; i++) {
    long c = i / s->nseeds;
    char rel[32], seed[32];
    sweep_combo(s, c, idx);
    snprintf(rel, sizeof rel, "runs/%0*ld", width & 15, i); /* width <= 6: at most 100000 points */
    cJSON *pt = cJSON_CreateObject(), *par = cJSON_CreateObject();
    if (!pt || !par) return cJSON_Delete(pt), cJSON_Delete(par), cJSON_Delete(p), NULL;
    cJSON_AddItemToArray(pts, pt);
    cJSON_AddNumberToObject(pt, "index", (double)i);
    cJSON_AddNumberToObject(pt, "combination", (double)c);
    snprintf(seed, sizeof seed, "%llu", s->seeds[i % s->nseeds]);
    cJSON_AddRawToObject(pt, "seed", seed);
    for (int b = 0; b < s->nbase; b++) cJSON_AddStringToObject(par, s->base_keys[b], s->base_values[b]);
    for (int a = 0; a < s->naxes; a++) cJSON_AddStringToObject(par, s->axes[a].param, s->axes[a].values[idx[a]]);
    cJSON_AddItemToObject(pt, "parameters", par);
    point_args(s, pt, rel, s->seeds[i % s->nseeds], par);
  }
  return p;
}

static int write_json(const char *path, const cJSON *j) {
  char *t = cJSON_Print(j);
  size_t n = t ? strlen(t) : 0;
  if (t) t[n] = '\n'; /* replaces the NUL: written by length */
  sessile_status s = t ? sessile_write_file_atomic(path, t, n + 1) : SESSILE_ERR_NO_MEMORY;
  if (!t) sessile_error_set(s, "out of host memory");
  free(t);
  return s == SESSILE_OK ? EXIT_OK : cli_fail_in("sweep", s);
}

/* A folder that does not exist (made) or is empty. */
static int fresh_dir(const char *dir) {
  if (mkdir(dir, 0777) == 0) return 0;
  if (errno != EEXIST) return -1;
  DIR *d = opendir(dir);
  struct dirent *e;
  int n = 0;
  while (d && (e = readdir(d)))
    if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) n++;
  if (d) closedir(d);
  return d && n == 0 ? 0 : 1;
}

static int cmd_plan(int argc, char **argv) {
  const char *file = NULL, *out = NULL;
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--out")) {
      if (!(out = cli_value("sweep plan", argc, argv, &i))) return EXIT_USAGE;
    } else if (argv[i][0] == '-' || file) return cli_usage_error("sweep plan", "unexpected '%.60s'", argv[i]);
    else file = argv[i];
  }
  if (!file || !out) return cli_usage_error("sweep plan", "usage: sessile sweep plan SWEEP.json --out DIR");
  sweep_spec s;
  int rc = sweep_spec_load(file, &s);
  if (rc) return sweep_spec_free(&s), rc;
  int width = sweep_width((int)s.npoints);
  cJSON *plan = plan_json(&s, width);
  int fr = plan ? fresh_dir(out) : -1;
  if (!plan) rc = sweep_oom("sweep plan");
  else if (fr > 0) rc = cli_usage_error("sweep plan", "'%.200s' is not empty: a sweep folder starts new", out);
  else if (fr < 0) fprintf(stderr, "sessile sweep plan: error: cannot make '%.200s': %s\n", out, strerror(errno)), rc = EXIT_RUNTIME;
  char path[4096];
  const char *sub[] = {"runs", "points", "state", "logs"};
  for (int k = 0; !rc && k < 4; k++) {
    snprintf(path, sizeof path, "%s/%s", out, sub[k]);
    if (mkdir(path, 0777) != 0) fprintf(stderr, "sessile sweep plan: error: cannot make '%.200s': %s\n", path, strerror(errno)), rc = EXIT_RUNTIME;
  }
  const cJSON *pts = cJSON_GetObjectItemCaseSensitive(plan, "points");
  for (const cJSON *pt = pts ? pts->child : NULL; !rc && pt; pt = pt->next) {
    snprintf(path, sizeof path, "%s/points/%0*d.json", out, width, cJSON_GetObjectItemCaseSensitive(pt, "index")->valueint);
    rc = write_json(path, pt);
  }
  snprintf(path, sizeof path, "%s/sweep.json", out);
  if (!rc) rc = write_json(path, plan); /* last: a sweep folder with sweep.json is whole */
  if (!rc) {
    int it = s.iterations >= 0 ? s.iterations : s.default_iterations;
    printf("sweep: %ld points (%ld combinations x %d seeds) of %s in %s\n", s.npoints, s.ncombos, s.nseeds, s.generator, out);
    if (it >= 0) printf("estimated cost: %ld points x %d iterations = %.0f iterations\n", s.npoints, it, (double)s.npoints * it);
    else printf("estimated cost: %ld runs (the generator sets its own iterations)\n", s.npoints);
  }
  cJSON_Delete(plan);
  sweep_spec_free(&s);
  return rc;
}

static const char usage[] =
    "usage: sessile sweep plan SWEEP.json --out DIR   expand a sweep file into a sweep folder\n"
    "       sessile sweep run DIR [-j N]               run its points here, N at once (default 1);\n"
    "                 [--quiet] [--progress MODE]     points done on stderr (auto, tty, lines, json,\n"
    "                                                 none; docs/run.md \"Progress\")\n"
    "       sessile sweep task DIR INDEX               run one point (what a Slurm array task calls)\n"
    "       sessile sweep submit DIR [--partition P] [--time T] [--gpus-per-task G]\n"
    "                            [--max-parallel M] [--sbatch-arg A]...   one Slurm job array\n"
    "       sessile sweep status DIR                   each point's state (and Slurm's)\n"
    "       sessile sweep gather DIR                   DIR/gather/: points and summary, CSV and JSON lines\n"
    "\nA study of many runs of one generator: docs/sweep.md.  Every point is its own\n"
    "sessile process writing DIR/runs/NNNN; completed points are skipped, interrupted\n"
    "ones resumed (--resume), so running or submitting again finishes the sweep.\n"
    "Exit codes: 0 success, 1 a point failed or a runtime failure, 2 bad usage or input,\n"
    "130/143 interrupted.\n";

int cmd_sweep(int argc, char **argv, const cli_gpu_opts *global) {
  (void)global; /* device options go to the points through the sweep file's "options" */
  if (argc < 2) return cli_usage_error("sweep", "name a subcommand: plan, run, task, submit, status or gather");
  const char *c = argv[1];
  for (int i = 1; i < argc; i++)
    if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) return fputs(usage, stdout), EXIT_OK;
  if (!strcmp(c, "plan")) return cmd_plan(argc - 1, argv + 1);
  if (!strcmp(c, "run")) return sweep_cmd_run(argc - 1, argv + 1);
  if (!strcmp(c, "task")) return sweep_cmd_task(argc - 1, argv + 1);
  if (!strcmp(c, "status")) return sweep_cmd_status(argc - 1, argv + 1);
  if (!strcmp(c, "submit")) return sweep_cmd_submit(argc - 1, argv + 1);
  if (!strcmp(c, "gather")) return sweep_cmd_gather(argc - 1, argv + 1);
  return cli_usage_error("sweep", "unknown subcommand '%.60s' (plan, run, task, submit, status, gather)", c);
}
