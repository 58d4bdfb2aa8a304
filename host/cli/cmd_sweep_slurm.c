/* The Slurm engine through Slurm's own tools (docs/sweep.md): `sweep submit`
 * writes a batch script and hands the unfinished points to `sbatch --array`
 * (each task: `sessile sweep task DIR $SLURM_ARRAY_TASK_ID`), records the job
 * in DIR/slurm.json; `sweep status` reads the manifests and asks
 * squeue/sacct about the recorded jobs. */
#define _DEFAULT_SOURCE /* realpath */
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>
#include "cmd_sweep.h"
#include "sessile/io/io.h"

/* Runs argv (a program on PATH) with its stdout into out; its stderr is
 * kept or dropped.  The exit code, or -1 when it could not run. */
static int capture(const char *const *argv, char *out, size_t n, int keep_stderr) {
  int fd[2];
  if (pipe(fd) != 0) return -1;
  fflush(NULL);
  pid_t pid = fork();
  if (pid < 0) return close(fd[0]), close(fd[1]), -1;
  if (pid == 0) {
    dup2(fd[1], STDOUT_FILENO);
    if (!keep_stderr) {
      int nul = open("/dev/null", O_WRONLY);
      if (nul >= 0) dup2(nul, STDERR_FILENO);
    }
    close(fd[0]), close(fd[1]);
    execvp(argv[0], (char *const *)argv);
    _exit(127);
  }
  close(fd[1]);
  size_t got = 0;
  ssize_t k;
  while ((k = read(fd[0], out + got, got + 1 < n ? n - 1 - got : 0)) > 0 || (k < 0 && errno == EINTR))
    if (k > 0) got += (size_t)k;
  out[got] = 0;
  char sink[4096];
  while (read(fd[0], sink, sizeof sink) > 0) {} /* the rest, so that it never blocks */
  close(fd[0]);
  int st;
  while (waitpid(pid, &st, 0) < 0)
    if (errno != EINTR) return -1;
  return WIFEXITED(st) && WEXITSTATUS(st) != 127 ? WEXITSTATUS(st) : -1;
}

static cJSON *load_jobs(const char *dir) {
  char path[PATH_MAX + 16];
  snprintf(path, sizeof path, "%s/slurm.json", dir);
  char *t = sweep_read_text(path, 1 << 20);
  cJSON *j = t ? cJSON_Parse(t) : NULL;
  free(t);
  return j;
}

/* Lines "JOB_INDEX|STATE" into out[INDEX] (squeue -r and sacct -P both). */
static void take_states(const char *job, const char *text, int npoints, char (*out)[24]) {
  size_t lj = strlen(job);
  for (const char *l = text; l && *l; l = strchr(l, '\n') ? strchr(l, '\n') + 1 : NULL) {
    if (strncmp(l, job, lj) || l[lj] != '_') continue;
    char *end;
    long i = strtol(l + lj + 1, &end, 10);
    if (end == l + lj + 1 || *end != '|' || i < 0 || i >= npoints) continue; /* "_[2-5%2]": not started */
    size_t k = strcspn(end + 1, " \n|");
    snprintf(out[i], 24, "%.*s", (int)(k < 23 ? k : 23), end + 1);
  }
}

int sweep_slurm_states(const char *dir, int npoints, char (*out)[24], char *job, size_t njob) {
  for (int i = 0; i < npoints; i++) out[i][0] = 0;
  cJSON *j = load_jobs(dir);
  const cJSON *jobs = cJSON_GetObjectItemCaseSensitive(j, "jobs");
  int any = 0, answered = 0;
  static char text[1 << 20];
  for (const cJSON *e = jobs ? jobs->child : NULL; e; e = e->next) { /* later submissions win */
    const cJSON *id = cJSON_GetObjectItemCaseSensitive(e, "id");
    if (!cJSON_IsString(id)) continue;
    any = 1;
    snprintf(job, njob, "%s", id->valuestring);
    const char *sacct[] = {"sacct", "-n", "-P", "-X", "-j", id->valuestring, "-o", "JobID,State", NULL};
    if (capture(sacct, text, sizeof text, 0) == 0) answered = 1, take_states(id->valuestring, text, npoints, out);
    /* squeue last: it knows the live tasks even where accounting is off */
    const char *squeue[] = {"squeue", "-h", "-r", "-j", id->valuestring, "-o", "%i|%T", NULL};
    if (capture(squeue, text, sizeof text, 0) == 0) answered = 1, take_states(id->valuestring, text, npoints, out);
  }
  cJSON_Delete(j);
  return !any ? 0 : answered ? 1 : -1;
}

int sweep_cmd_status(int argc, char **argv) {
  if (argc != 2 || argv[1][0] == '-') return cli_usage_error("sweep status", "usage: sessile sweep status DIR");
  const char *dir = argv[1];
  cJSON *plan = sweep_load_plan(dir);
  if (!plan) return EXIT_USAGE;
  int width = cJSON_GetObjectItemCaseSensitive(plan, "width")->valueint;
  int n = cJSON_GetArraySize(cJSON_GetObjectItemCaseSensitive(plan, "points")), count[5] = {0};
  char (*sl)[24] = calloc((size_t)n + 1, sizeof *sl), job[64] = "", err[1024];
  if (!sl) return cJSON_Delete(plan), sweep_oom("sweep status");
  int asked = sweep_slurm_states(dir, n, sl, job, sizeof job);
  for (int i = 0; i < n; i++) {
    sweep_state s = sweep_point_state(dir, i, width, err, sizeof err);
    /* a task Slurm holds that has not written its manifest yet */
    if (s == PT_PENDING && (!strcmp(sl[i], "RUNNING") || !strcmp(sl[i], "COMPLETING"))) s = PT_RUNNING;
    count[s]++;
    printf("%0*d %s", width, i, sweep_state_names[s]);
    if (sl[i][0]) printf(" (slurm %s: %s)", job, sl[i]);
    if (err[0]) printf(": %s", err);
    putchar('\n');
  }
  printf("sweep: %d points: %d completed, %d running, %d pending, %d interrupted, %d failed\n", n, count[PT_COMPLETED],
         count[PT_RUNNING], count[PT_PENDING], count[PT_INTERRUPTED], count[PT_FAILED]);
  if (asked < 0) printf("sweep: Slurm job %s recorded, but squeue and sacct did not answer\n", job);
  free(sl);
  cJSON_Delete(plan);
  return EXIT_OK;
}

/* 'text' for sh, whatever it holds. */
static void sh_quote(FILE *f, const char *s) {
  fputc('\'', f);
  for (; *s; s++) *s == '\'' ? fputs("'\\''", f) : fputc(*s, f);
  fputc('\'', f);
}

static int write_script(const char *path, const char *exe, const char *absdir) {
  char *buf = NULL;
  size_t len = 0;
  FILE *f = open_memstream(&buf, &len);
  if (!f) return -1;
  fputs("#!/bin/sh\n# sessile sweep: one array task per point (docs/sweep.md)\n#SBATCH --job-name=sessile-sweep\n", f);
  fprintf(f, "#SBATCH --output=%s/logs/slurm-%%A_%%a.log\nexec ", absdir);
  sh_quote(f, exe);
  fputs(" sweep task ", f);
  sh_quote(f, absdir);
  fputs(" \"$SLURM_ARRAY_TASK_ID\"\n", f);
  fclose(f);
  sessile_status s = buf ? sessile_write_file_atomic(path, buf, len) : SESSILE_ERR_NO_MEMORY;
  free(buf);
  return s == SESSILE_OK && chmod(path, 0755) == 0 ? 0 : -1;
}

/* The unfinished points as an --array list: "0-3,5,7-9". */
static int array_spec(const char *dir, int n, int width, char *out, size_t cap) {
  size_t l = 0;
  int count = 0;
  char err[16];
  out[0] = 0;
  for (int i = 0; i < n; i++) {
    if (sweep_point_state(dir, i, width, err, sizeof err) == PT_COMPLETED) continue;
    int j = i;
    while (j + 1 < n && sweep_point_state(dir, j + 1, width, err, sizeof err) != PT_COMPLETED) j++;
    int w = j > i ? snprintf(out + l, cap - l, "%s%d-%d", l ? "," : "", i, j) : snprintf(out + l, cap - l, "%s%d", l ? "," : "", i);
    if (w < 0 || (size_t)w >= cap - l) return -1;
    l += (size_t)w, count += j - i + 1, i = j;
  }
  return count;
}

static int record_job(const char *dir, const char *id, const char *array) {
  cJSON *j = load_jobs(dir);
  if (!j) j = cJSON_CreateObject();
  cJSON *jobs = cJSON_GetObjectItemCaseSensitive(j, "jobs");
  if (!jobs) jobs = cJSON_AddArrayToObject(j, "jobs");
  cJSON *e = cJSON_CreateObject();
  char when[32];
  time_t now = time(NULL);
  strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", gmtime(&now));
  cJSON_AddStringToObject(e, "id", id);
  cJSON_AddStringToObject(e, "array", array);
  cJSON_AddStringToObject(e, "submitted", when);
  cJSON_AddItemToArray(jobs, e);
  char path[PATH_MAX + 16], *t = cJSON_Print(j);
  snprintf(path, sizeof path, "%s/slurm.json", dir);
  sessile_status s = t ? sessile_write_file_atomic(path, t, strlen(t)) : SESSILE_ERR_NO_MEMORY;
  free(t);
  cJSON_Delete(j);
  return s == SESSILE_OK ? 0 : -1;
}

int sweep_cmd_submit(int argc, char **argv) {
  const char *dir = NULL, *part = NULL, *tm = NULL, *gpus = NULL, *extra[64];
  unsigned maxpar = 0, g = 0;
  int nextra = 0;
  for (int i = 1; i < argc; i++) {
    const char *o = argv[i], *v = NULL;
    int valued = !strcmp(o, "--partition") || !strcmp(o, "--time") || !strcmp(o, "--gpus-per-task") ||
                 !strcmp(o, "--max-parallel") || !strcmp(o, "--sbatch-arg");
    if (valued && i + 1 >= argc) return cli_usage_error("sweep submit", "%s needs a value", o);
    if (valued) v = argv[++i]; /* --sbatch-arg takes "--x=y" */
    if (!strcmp(o, "--partition")) part = v;
    else if (!strcmp(o, "--time")) tm = v;
    else if (!strcmp(o, "--gpus-per-task")) {
      if (cli_parse_uint("sweep submit", o, v, 0, 1024, &g)) return EXIT_USAGE;
      gpus = v;
    } else if (!strcmp(o, "--max-parallel")) {
      if (cli_parse_uint("sweep submit", o, v, 1, 1000000, &maxpar)) return EXIT_USAGE;
    } else if (!strcmp(o, "--sbatch-arg")) {
      if (nextra == 64) return cli_usage_error("sweep submit", "more than 64 --sbatch-arg");
      extra[nextra++] = v;
    } else if (o[0] == '-' || dir) return cli_usage_error("sweep submit", "unexpected '%.60s'", o);
    else dir = o;
  }
  if (!dir) return cli_usage_error("sweep submit", "usage: sessile sweep submit DIR [options] (sessile sweep --help)");
  cJSON *plan = sweep_load_plan(dir);
  if (!plan) return EXIT_USAGE;
  char absdir[PATH_MAX], exe[PATH_MAX], script[PATH_MAX + 64];
  ssize_t k = readlink("/proc/self/exe", exe, sizeof exe - 1);
  if (!realpath(dir, absdir) || k <= 0) {
    cJSON_Delete(plan);
    return fprintf(stderr, "sessile sweep submit: error: cannot resolve '%.200s' or this executable\n", dir), EXIT_RUNTIME;
  }
  exe[k] = 0;
  int width = cJSON_GetObjectItemCaseSensitive(plan, "width")->valueint;
  int n = cJSON_GetArraySize(cJSON_GetObjectItemCaseSensitive(plan, "points"));
  cJSON_Delete(plan);
  static char array[1 << 16], arrayopt[sizeof array + 32];
  int todo = array_spec(absdir, n, width, array, sizeof array - 16);
  if (todo < 0) return cli_usage_error("sweep submit", "the unfinished points make too long an --array list");
  if (todo == 0) return printf("sweep: every point completed; nothing to submit\n"), EXIT_OK;
  if (maxpar) snprintf(array + strlen(array), 16, "%%%u", maxpar);
  snprintf(arrayopt, sizeof arrayopt, "--array=%s", array);
  snprintf(script, sizeof script, "%s/logs/sweep.sbatch", absdir);
  if (write_script(script, exe, absdir)) return fprintf(stderr, "sessile sweep submit: error: cannot write '%.200s'\n", script), EXIT_RUNTIME;
  char opt[3][600];
  const char *av[80];
  int na = 0;
  av[na++] = "sbatch", av[na++] = "--parsable", av[na++] = arrayopt;
  if (part) snprintf(opt[0], sizeof opt[0], "--partition=%s", part), av[na++] = opt[0];
  if (tm) snprintf(opt[1], sizeof opt[1], "--time=%s", tm), av[na++] = opt[1];
  if (gpus) snprintf(opt[2], sizeof opt[2], "--gpus-per-task=%s", gpus), av[na++] = opt[2];
  for (int e = 0; e < nextra; e++) av[na++] = extra[e];
  av[na++] = script, av[na] = NULL;
  char out[4096];
  int rc = capture(av, out, sizeof out, 1);
  out[strcspn(out, ";\n")] = 0; /* --parsable: "ID" or "ID;CLUSTER" */
  int digits = out[0] != 0;
  for (const char *c = out; *c; c++) digits &= *c >= '0' && *c <= '9';
  if (rc != 0 || !digits) {
    fprintf(stderr, "sessile sweep submit: error: sbatch %s (%s)\n", rc < 0 ? "could not run (is Slurm installed?)" : "refused the job",
            out[0] ? out : "no job id");
    return EXIT_RUNTIME;
  }
  if (record_job(absdir, out, array)) fprintf(stderr, "sessile sweep submit: warning: job %s not recorded in %s/slurm.json\n", out, dir);
  printf("sweep: submitted Slurm job array %s (%d points: %s); 'sessile sweep status %s'\n", out, todo, array, dir);
  return EXIT_OK;
}
