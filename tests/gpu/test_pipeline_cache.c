/* The on-disk pipeline cache (host/gpu/pipeline_cache.c) against a hostile
 * or odd cache folder.  A cache is only speed, so every case must end with a
 * working context and nothing written outside the cache folder:
 *   - the default folder $XDG_CACHE_HOME/sessile is created 0700, the file
 *     0600, and no temporary remains;
 *   - a FIFO planted as the cache file does not hang the run (alarm: 60 s);
 *   - a symlink planted as the cache file is not followed: the file it points
 *     to is unchanged, and the link is replaced by a regular file; nor is one
 *     planted at the old predictable temporary name "<cache>.tmp.<pid>";
 *   - a folder, or a sparse 300 MiB file, at the cache path is ignored;
 *   - a default folder that is a symlink to elsewhere is not used;
 *   - an explicit cache_dir is created, and one whose path is too long for
 *     the cache path is turned off instead of being cut. */
#define _DEFAULT_SOURCE /* mkdtemp, symlink, lstat */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>
#include "cli/cli_gpu_env.h"
#include "testutil.h"

static char T[512];
static uint64_t validation_total;

static char *P(const char *name) { /* T/name, from a small ring of buffers */
  static char buf[8][2048];
  static int k;
  k = (k + 1) % 8;
  snprintf(buf[k], sizeof buf[k], "%s/%s", T, name);
  return buf[k];
}

static void on_alarm(int sig) {
  (void)sig;
  static const char msg[] = "FAIL the pipeline cache hung for 60 s (alarm)\n";
  if (write(1, msg, sizeof msg - 1) < 0) _exit(2);
  _exit(1);
}

/* Creates and destroys a context (cache_dir NULL: the default folder);
 * returns the seconds taken, or -1 when creation failed. */
static double cycle(const char *cache_dir) {
  struct timespec a, b;
  clock_gettime(CLOCK_MONOTONIC, &a);
  sessile_gpu_options o;
  sessile_gpu_options_default(&o);
  o.cache_dir = cache_dir;
  cli_gpu_env_store st; /* the default folder from $XDG_CACHE_HOME, as the CLI finds it */
  sessile_gpu *g = NULL;
  alarm(60);
  sessile_status s = cli_gpu_env(&o, &st);
  if (s == SESSILE_OK) s = sessile_gpu_create(&o, &g);
  if (s != SESSILE_OK) {
    alarm(0);
    printf("     sessile_gpu_create: %s\n", sessile_error_message());
    return -1;
  }
  validation_total += sessile_gpu_validation_count(g);
  sessile_gpu_destroy(g);
  alarm(0);
  clock_gettime(CLOCK_MONOTONIC, &b);
  return (double)(b.tv_sec - a.tv_sec) + 1e-9 * (double)(b.tv_nsec - a.tv_nsec);
}

/* The one pipelines-*.bin in folder d (into out); counts entries matching
 * it, temporaries (".*.sessile-tmp.*") and other entries. */
static int scan(const char *d, char *out, size_t n, int *tmps, int *others) {
  DIR *dir = opendir(d);
  int found = 0;
  *tmps = *others = 0;
  if (out) out[0] = 0;
  if (!dir) return -1;
  struct dirent *e;
  while ((e = readdir(dir))) {
    const char *s = e->d_name;
    if (!strcmp(s, ".") || !strcmp(s, "..")) continue;
    size_t len = strlen(s);
    if (strstr(s, ".sessile-tmp.")) (*tmps)++;
    else if (!strncmp(s, "pipelines-", 10) && len > 14 && !strcmp(s + len - 4, ".bin")) {
      found++;
      if (out) snprintf(out, n, "%s/%s", d, s);
    } else (*others)++;
  }
  closedir(dir);
  return found;
}

static int is_regular(const char *p) {
  struct stat st;
  return lstat(p, &st) == 0 && S_ISREG(st.st_mode);
}

static void rm_rf(const char *d) {
  DIR *dir = opendir(d);
  if (!dir) {
    unlink(d);
    return;
  }
  struct dirent *e;
  char p[4096];
  while ((e = readdir(dir))) {
    if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..")) continue;
    snprintf(p, sizeof p, "%s/%s", d, e->d_name);
    struct stat st;
    if (lstat(p, &st) == 0 && S_ISDIR(st.st_mode)) rm_rf(p);
    else unlink(p);
  }
  closedir(dir);
  rmdir(d);
}

int main(void) {
  snprintf(T, sizeof T, "%s/sessile_test_pcache.XXXXXX", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
  if (!mkdtemp(T)) {
    printf("FAIL cannot create a scratch folder: %s\n", strerror(errno));
    return 1;
  }
  signal(SIGALRM, on_alarm);
  setenv("XDG_CACHE_HOME", P("xdg"), 1);
  char cache[2048], folder[2048];
  snprintf(folder, sizeof folder, "%s", P("xdg/sessile"));
  int tmps, others;

  /* 1. the default folder, created fresh */
  double t_cold = cycle(NULL);
  t_true("context with a fresh default cache folder", t_cold >= 0);
  int found = scan(folder, cache, sizeof cache, &tmps, &others);
  struct stat st;
  printf("     cache file: %s\n", cache);
  t_true("$XDG_CACHE_HOME/sessile holds one pipelines-*.bin, no temporary, nothing else",
         found == 1 && tmps == 0 && others == 0);
  t_true("the cache folder was created with mode 0700",
         lstat(folder, &st) == 0 && S_ISDIR(st.st_mode) && (st.st_mode & 0777) == 0700);
  t_true("the cache file is a regular file with mode 0600",
         lstat(cache, &st) == 0 && S_ISREG(st.st_mode) && (st.st_mode & 0777) == 0600 && st.st_size > 0);
  double t_warm = cycle(NULL);
  printf("     create + destroy: %.2f s cold, %.2f s warm\n", t_cold, t_warm);

  if (found == 1) {
    /* 2. a FIFO at the cache path */
    unlink(cache);
    t_true("plant a FIFO at the cache path", mkfifo(cache, 0600) == 0);
    double t = cycle(NULL);
    printf("     with a FIFO: %.2f s\n", t);
    t_true("a FIFO as the cache file does not hang: the context comes up and goes down", t >= 0);
    t_true("... and is replaced by a regular cache file, no temporary left",
           is_regular(cache) && scan(folder, NULL, 0, &tmps, &others) == 1 && tmps == 0 && others == 0);

    /* 3. a symlink at the cache path pointing outside */
    static const char outside_text[] = "not a pipeline cache: must stay as it is\n";
    FILE *f = fopen(P("outside.bin"), "wb");
    if (f) fputs(outside_text, f), fclose(f);
    chmod(P("outside.bin"), 0644);
    unlink(cache);
    t_true("plant a symlink at the cache path to a file outside", symlink(P("outside.bin"), cache) == 0);
    t = cycle(NULL);
    t_true("a symlinked cache file: the context comes up and goes down", t >= 0);
    char buf[256] = {0};
    f = fopen(P("outside.bin"), "rb");
    size_t n = f ? fread(buf, 1, sizeof buf - 1, f) : 0;
    if (f) fclose(f);
    t_true("the file outside is unchanged (content and mode)",
           n == strlen(outside_text) && !strcmp(buf, outside_text) && lstat(P("outside.bin"), &st) == 0 &&
               (st.st_mode & 0777) == 0644);
    t_true("... and the link was replaced by a regular file, no temporary left",
           is_regular(cache) && scan(folder, NULL, 0, &tmps, &others) == 1 && tmps == 0 && others == 0);

    /* 3b. a symlink at the old predictable temporary name "<cache>.tmp.<pid>" */
    char pidtmp[2100];
    snprintf(pidtmp, sizeof pidtmp, "%s.tmp.%ld", cache, (long)getpid());
    f = fopen(P("outside2.bin"), "wb");
    if (f) fputs(outside_text, f), fclose(f);
    t_true("plant a symlink at <cache>.tmp.<pid> to a file outside", symlink(P("outside2.bin"), pidtmp) == 0);
    t = cycle(NULL);
    memset(buf, 0, sizeof buf);
    f = fopen(P("outside2.bin"), "rb");
    n = f ? fread(buf, 1, sizeof buf - 1, f) : 0;
    if (f) fclose(f);
    t_true("a link at the old temporary name is not written through: the file outside is unchanged",
           t >= 0 && n == strlen(outside_text) && !strcmp(buf, outside_text) && is_regular(cache));
    unlink(pidtmp);

    /* 4. a folder at the cache path */
    unlink(cache);
    mkdir(cache, 0700);
    t = cycle(NULL);
    t_true("a folder as the cache file is ignored: the context works, the folder stays, no temporary",
           t >= 0 && lstat(cache, &st) == 0 && S_ISDIR(st.st_mode) &&
               scan(folder, NULL, 0, &tmps, &others) == 1 && tmps == 0);
    rmdir(cache);

    /* 5. a sparse file over the size limit */
    int fd = open(cache, O_WRONLY | O_CREAT | O_TRUNC, 0600);
    int sparse = fd >= 0 && ftruncate(fd, 300 << 20) == 0;
    if (fd >= 0) close(fd);
    t_true("plant a sparse 300 MiB cache file", sparse);
    t = cycle(NULL);
    t_true("a 300 MiB cache file is ignored and replaced by a small one",
           t >= 0 && lstat(cache, &st) == 0 && S_ISREG(st.st_mode) && st.st_size < (1 << 20));
  }

  /* 6. the default folder is a symlink to elsewhere */
  mkdir(P("xdg2"), 0700);
  mkdir(P("elsewhere"), 0700);
  t_true("plant xdg2/sessile -> elsewhere", symlink(P("elsewhere"), P("xdg2/sessile")) == 0);
  setenv("XDG_CACHE_HOME", P("xdg2"), 1);
  double t = cycle(NULL);
  t_true("a symlinked default cache folder is not used: the context works, the target stays empty",
         t >= 0 && scan(P("elsewhere"), NULL, 0, &tmps, &others) == 0 && tmps == 0 && others == 0);

  /* 7. an explicit folder, created 0700 */
  t = cycle(P("explicit/a/b"));
  t_true("an explicit cache_dir is created (mode 0700) and holds the cache file",
         t >= 0 && lstat(P("explicit/a/b"), &st) == 0 && (st.st_mode & 0777) == 0700 &&
             scan(P("explicit/a/b"), NULL, 0, &tmps, &others) == 1 && tmps == 0 && others == 0);

  /* 8. a cache path longer than the context's buffer (1024): off, not cut */
  char longdir[2048];
  int len = snprintf(longdir, sizeof longdir, "%s", P("long"));
  for (int k = 0; k < 6; k++) {
    longdir[len++] = '/';
    memset(longdir + len, 'a' + k, 200);
    len += 200;
  }
  longdir[len] = 0;
  t = cycle(longdir);
  t_true("a cache_dir of 1200+ characters: the context works, no cache file, nothing cut short",
         t >= 0 && scan(longdir, NULL, 0, &tmps, &others) == 0 && tmps == 0 && others == 0);
  found = 0;
  for (int cut = (int)strlen(T) + 1; cut < len; cut++) { /* a cut path would be a prefix */
    char c = longdir[cut];
    longdir[cut] = 0;
    int tt, oo;
    found += scan(longdir, NULL, 0, &tt, &oo) > 0;
    longdir[cut] = c;
  }
  t_true("... and no file was written under a truncated path", found == 0);

  /* 9. the cache off */
  t = cycle("");
  t_true("cache_dir \"\" turns the cache off: the context works", t >= 0);

  t_check("validation layer messages (every context above)", (double)validation_total, 0);
  rm_rf(T);
  return t_finish(NULL);
}
