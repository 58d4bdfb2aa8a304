/* The local engine (`sweep run DIR -j N`) and one point (`sweep task DIR
 * INDEX`): every point is its own `sessile` process (this executable), so a
 * crash of one never takes the others down; completed points are skipped and
 * interrupted ones resumed with the generator's own --resume. */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>
#include "cli_progress.h"
#include "cmd_sweep.h"
#include "sessile/io/io.h"

static volatile sig_atomic_t signals_seen, last_signal;

static void on_signal(int s) { last_signal = s, signals_seen++; }

/* A run killed before its manifest leaves at most its lock owner file and
 * temporaries; the generator refuses a folder that is not empty and holds no
 * manifest, so those (and only those) go before a new start. */
static void clear_leftovers(const char *dir, int index, int width) {
  char path[4096];
  snprintf(path, sizeof path, "%s/runs/%0*d", dir, width, index);
  DIR *d = opendir(path);
  if (!d) return;
  struct dirent *e;
  int others = 0, fd = dirfd(d);
  char names[16][256];
  int n = 0;
  while ((e = readdir(d))) {
    if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..")) continue;
    int ours = !strcmp(e->d_name, ".sessile.lock") || strstr(e->d_name, ".sessile-tmp.");
    if (!ours || n == 16) others = 1;
    else snprintf(names[n++], sizeof names[0], "%s", e->d_name);
  }
  for (int k = 0; !others && k < n; k++) unlinkat(fd, names[k], 0);
  closedir(d);
}

static int exe_path(char *buf, size_t n) {
  ssize_t k = readlink("/proc/self/exe", buf, n - 1);
  if (k <= 0) return fprintf(stderr, "sessile sweep: error: cannot find this executable: %s\n", strerror(errno)), -1;
  buf[k] = 0;
  return 0;
}

/* The point's argv (after "sessile"): a resume when it has a run, else new.
 * A run killed between its first manifest and its configuration cannot be
 * resumed ("holds no configuration"): it starts anew with --force, which
 * removes only what its manifest lists. */
static int point_argv(const char *dir, const cJSON *pt, int width, const char **argv, int max) {
  int index = cJSON_GetObjectItemCaseSensitive(pt, "index")->valueint;
  cJSON *m = sweep_point_manifest(dir, index, width);
  int resume = m && cJSON_IsObject(cJSON_GetObjectItemCaseSensitive(m, "config"));
  const cJSON *a = cJSON_GetObjectItemCaseSensitive(pt, resume ? "resume_args" : "args");
  if (!m) clear_leftovers(dir, index, width);
  int n = 0;
  argv[n++] = "sessile";
  for (const cJSON *v = a ? a->child : NULL; v && n < max - 2; v = v->next)
    if (cJSON_IsString(v)) argv[n++] = v->valuestring;
  if (m && !resume) argv[n++] = "--force";
  argv[n] = NULL;
  cJSON_Delete(m);
  return n;
}

static void exec_point(const char *exe, const char *dir, const char **argv) {
  if (chdir(dir) != 0) {
    fprintf(stderr, "sessile sweep: error: cannot enter '%.200s': %s\n", dir, strerror(errno));
    _exit(EXIT_RUNTIME);
  }
  execv(exe, (char *const *)argv);
  fprintf(stderr, "sessile sweep: error: cannot run '%.200s': %s\n", exe, strerror(errno));
  _exit(EXIT_RUNTIME);
}

static pid_t start(const char *exe, const char *dir, const cJSON *pt, int width) {
  const char *argv[SWEEP_MAX_ARGS * 2 + 210];
  int index = cJSON_GetObjectItemCaseSensitive(pt, "index")->valueint;
  point_argv(dir, pt, width, argv, (int)(sizeof argv / sizeof argv[0]));
  char log[4096];
  snprintf(log, sizeof log, "%s/logs/%0*d.log", dir, width, index);
  fflush(NULL); /* nothing buffered twice */
  pid_t parent = getpid(), pid = fork();
  if (pid != 0) return pid;
  /* its own process group: a terminal's ^C reaches the engine only, which
   * passes one signal on (a second one would end the run at once) */
  setpgid(0, 0);
  prctl(PR_SET_PDEATHSIG, SIGKILL); /* a killed engine leaves no orphan holding a run */
  if (getppid() != parent) _exit(EXIT_RUNTIME);
  signal(SIGINT, SIG_DFL), signal(SIGTERM, SIG_DFL);
  int fd = open(log, O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd >= 0) dup2(fd, STDOUT_FILENO), dup2(fd, STDERR_FILENO);
  exec_point(exe, dir, argv);
  return -1;
}

/* The last line the point's process wrote: its error. */
static void last_line(const char *dir, int index, int width, char *out, size_t n) {
  char path[4096], buf[2048];
  snprintf(path, sizeof path, "%s/logs/%0*d.log", dir, width, index);
  out[0] = 0;
  int fd = open(path, O_RDONLY | O_CLOEXEC);
  if (fd < 0) return;
  off_t size = lseek(fd, 0, SEEK_END);
  off_t from = size > (off_t)sizeof buf - 1 ? size - (off_t)sizeof buf + 1 : 0;
  ssize_t k = pread(fd, buf, sizeof buf - 1, from);
  close(fd);
  if (k <= 0) return;
  buf[k] = 0;
  while (k > 0 && (buf[k - 1] == '\n' || buf[k - 1] == '\r')) buf[--k] = 0;
  char *l = strrchr(buf, '\n');
  snprintf(out, n, "%s", l ? l + 1 : buf);
}

/* The point's last exit: kept for a failure (status reads it where the run
 * failed before its manifest); an interruption (a signal passed on, maybe
 * before the run could catch it) is no failure and leaves none. */
static void record(const char *dir, int index, int width, int rc, int interrupted, const char *error) {
  char path[4096];
  snprintf(path, sizeof path, "%s/state/%0*d.json", dir, width, index);
  if (interrupted || rc == 0) {
    unlink(path);
    return;
  }
  cJSON *r = cJSON_CreateObject();
  cJSON_AddNumberToObject(r, "exit", rc);
  if (rc) cJSON_AddStringToObject(r, "error", error);
  char *t = cJSON_PrintUnformatted(r);
  if (t) sessile_write_file_atomic(path, t, strlen(t)); /* best effort: the manifest says more */
  free(t);
  cJSON_Delete(r);
}

typedef struct running {
  pid_t pid;
  int index;
} running;

/* --quiet: no line of a point that completed, no summary of a sweep that did */
static int quiet;

static int parse_run(int argc, char **argv, const char **dir, int *jobs, int *progress) {
  for (int i = 1; i < argc; i++) {
    const char *v = NULL;
    if (cli_stray_value("sweep run", argv, i)) return EXIT_USAGE;
    int r = cli_progress_option("sweep run", argc, argv, &i, progress);
    if (r < 0) return EXIT_USAGE;
    if (r > 0) continue;
    if (!strcmp(argv[i], "--quiet")) {
      quiet = 1;
      continue;
    }
    if (!strcmp(argv[i], "-j") || !strcmp(argv[i], "--jobs")) {
      if (!(v = cli_value("sweep run", argc, argv, &i))) return EXIT_USAGE;
    } else if (!strncmp(argv[i], "-j", 2)) v = argv[i] + 2;
    else if (argv[i][0] == '-' || *dir) return cli_usage_error("sweep run", "unexpected '%.60s'", argv[i]);
    else *dir = argv[i];
    unsigned u;
    if (v && cli_parse_uint("sweep run", "-j", v, 1, 1024, &u)) return EXIT_USAGE;
    if (v) *jobs = (int)u;
  }
  return *dir ? -1 : cli_usage_error("sweep run", "usage: sessile sweep run DIR [-j N] [--quiet] [--progress MODE]");
}

/* One finished child: its state, one line, the engine's record; 1
 * completed, 0 failed, -1 stopped by a signal passed on. */
static int finished(const char *dir, int width, int index, int status) {
  int rc = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  int stopped = signals_seen && (rc == 130 || rc == 143 || (WIFSIGNALED(status) && WTERMSIG(status) == last_signal));
  char err[1024], line[2048];
  last_line(dir, index, width, line, sizeof line);
  record(dir, index, width, rc, stopped, line);
  sweep_state s = sweep_point_state(dir, index, width, err, sizeof err);
  if (s == PT_COMPLETED && rc == 0) {
    if (!quiet) printf("sweep: %0*d completed\n", width, index);
  }
  else if (stopped) printf("sweep: %0*d interrupted (exit %d); its state is saved\n", width, index, rc);
  else printf("sweep: %0*d failed (exit %d): %s\n", width, index, rc, line[0] ? line : err);
  fflush(stdout);
  return stopped ? -1 : s == PT_COMPLETED && rc == 0;
}

int sweep_cmd_run(int argc, char **argv) {
  const char *dir = NULL;
  int jobs = 1, mode = 0, rc = parse_run(argc, argv, &dir, &jobs, &mode);
  if (rc >= 0) return rc;
  cJSON *plan = sweep_load_plan(dir);
  char exe[4096];
  if (!plan) return EXIT_USAGE;
  if (exe_path(exe, sizeof exe)) return cJSON_Delete(plan), EXIT_RUNTIME;
  int width = cJSON_GetObjectItemCaseSensitive(plan, "width")->valueint;
  const cJSON *pts = cJSON_GetObjectItemCaseSensitive(plan, "points");
  int n = cJSON_GetArraySize(pts), nq = 0, done_before = 0, elsewhere = 0, ok = 0, bad = 0, nrun = 0, forwarded = 0;
  const cJSON **queue = calloc((size_t)n + 1, sizeof *queue);
  running *run = calloc((size_t)jobs, sizeof *run);
  if (!queue || !run) return free(queue), free(run), cJSON_Delete(plan), sweep_oom("sweep run");
  char err[1024];
  for (const cJSON *pt = pts->child; pt; pt = pt->next) {
    sweep_state s = sweep_point_state(dir, cJSON_GetObjectItemCaseSensitive(pt, "index")->valueint, width, err, sizeof err);
    if (s == PT_COMPLETED) done_before++;
    else if (s == PT_RUNNING) elsewhere++;
    else queue[nq++] = pt;
  }
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_signal; /* no SA_RESTART: the loop below polls */
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, NULL), sigaction(SIGTERM, &sa, NULL);
  if (!quiet)
    printf("sweep: %d points: %d completed before, %d to run (%d at once)%s\n", n, done_before, nq, jobs,
           elsewhere ? "; some run elsewhere" : "");
  fflush(stdout);
  /* progress: points finished (completed or failed) of all the sweep's */
  cli_progress pr;
  cli_progress_start(&pr, "sweep run", mode, quiet);
  sessile_progress_count(cli_progress_report, &pr, "point", done_before, n, 0);
  int next = 0;
  while (next < nq || nrun > 0) {
    while (!signals_seen && nrun < jobs && next < nq) {
      const cJSON *pt = queue[next++];
      pid_t pid = start(exe, dir, pt, width);
      int index = cJSON_GetObjectItemCaseSensitive(pt, "index")->valueint;
      if (pid < 0) {
        printf("sweep: %0*d failed: cannot start a process: %s\n", width, index, strerror(errno));
        bad++;
        continue;
      }
      run[nrun++] = (running){pid, index};
    }
    if (signals_seen > forwarded) { /* each signal once to every running point */
      for (int k = 0; k < nrun; k++) kill(run[k].pid, last_signal);
      forwarded = signals_seen;
    }
    int status;
    pid_t pid = waitpid(-1, &status, WNOHANG);
    if (pid > 0) {
      for (int k = 0; k < nrun; k++)
        if (run[k].pid == pid) {
          int f = finished(dir, width, run[k].index, status);
          ok += f > 0, bad += f == 0;
          if (f >= 0) sessile_progress_count(cli_progress_report, &pr, "point", done_before + ok + bad, n, 1);
          run[k] = run[--nrun];
          break;
        }
    } else if (pid == 0 || (pid < 0 && errno == EINTR)) {
      struct timespec ts = {0, 20 * 1000 * 1000};
      nanosleep(&ts, NULL);
    } else break; /* no children left */
    if (signals_seen && next < nq) nq = next; /* start nothing more */
  }
  cli_progress_end(&pr);
  if (signals_seen) {
    fprintf(stderr, "sessile sweep run: interrupted (signal %d); 'sessile sweep run %s' goes on\n", (int)last_signal, dir);
    rc = cli_signal_exit_code((int)last_signal);
  } else {
    rc = bad || elsewhere ? EXIT_RUNTIME : EXIT_OK;
    if (!quiet || rc != EXIT_OK)
      printf("sweep: %d completed now, %d before, %d failed%s\n", ok, done_before, bad,
             elsewhere ? ", some still running elsewhere" : "");
  }
  free(queue), free(run);
  cJSON_Delete(plan);
  return rc;
}

int sweep_cmd_task(int argc, char **argv) {
  if (argc != 3) return cli_usage_error("sweep task", "usage: sessile sweep task DIR INDEX");
  const char *dir = argv[1];
  unsigned index;
  if (cli_parse_uint("sweep task", "INDEX", argv[2], 0, SWEEP_MAX_POINTS, &index)) return EXIT_USAGE;
  cJSON *plan = sweep_load_plan(dir);
  char exe[4096], err[1024];
  if (!plan) return EXIT_USAGE;
  if (exe_path(exe, sizeof exe)) return cJSON_Delete(plan), EXIT_RUNTIME;
  int width = cJSON_GetObjectItemCaseSensitive(plan, "width")->valueint;
  const cJSON *pt = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(plan, "points"), (int)index);
  if (!pt) return cJSON_Delete(plan), cli_usage_error("sweep task", "the sweep has no point %u", index);
  sweep_state s = sweep_point_state(dir, (int)index, width, err, sizeof err);
  if (s == PT_COMPLETED || s == PT_RUNNING) {
    printf("sweep: %0*u %s already\n", width, index, sweep_state_names[s]);
    cJSON_Delete(plan);
    return s == PT_COMPLETED ? EXIT_OK : EXIT_RUNTIME;
  }
  const char *av[SWEEP_MAX_ARGS * 2 + 210];
  point_argv(dir, pt, width, av, (int)(sizeof av / sizeof av[0]));
  fflush(stdout);
  /* the point replaces this process: a scheduler's signals reach the run */
  exec_point(exe, dir, av);
  return EXIT_RUNTIME;
}
