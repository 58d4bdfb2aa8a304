/* sessile render — what a run directory holds and what to draw of it
 * (render_run.h).  The generator comes from the manifest; its meshes,
 * snapshots and slices from listings of its folders, read through the run
 * folder's descriptor without following symlinks (a planted link is
 * refused, as the run framework refuses it when writing).  Nothing is
 * written and no device is needed, so bad input writes nothing. */
#define _DEFAULT_SOURCE /* realpath */
#include <cjson/cJSON.h>
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/io/io.h"
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>
#include "run_internal.h"

static const rp_layout layouts[] = {
    {"grow", "sponge", "iter_", "iteration", 1, {"solver", "time"}, NULL, NULL},
    {"sponge particles", "sponge", "iter_", "iteration", 0, {NULL, NULL}, NULL, NULL},
    {"sphere", "sphere", "iter_", "iteration", 0, {NULL, NULL}, NULL, NULL},
    {"coral lsystem", "coral", NULL, NULL, 0, {NULL, NULL}, NULL, NULL},
    {"coral venation", "coral", "iter_", "iteration", 0, {NULL, NULL}, NULL, NULL},
    {"sds", "sds", "frame_", "frame", 0, {"steps", NULL}, "steps.csv", NULL},
    {"reef", "reef", NULL, NULL, 0, {NULL, NULL}, NULL, "scene.json"}, /* an instanced scene (render_scene.h) */
};

sessile_status rp_read_at(int dfd, const char *dir, const char *name, size_t max, char **text, size_t *len) {
  char shown[600];
  snprintf(shown, sizeof shown, "'%.400s/%.150s'", dir, name);
  return sessile_read_small_file_at(dfd, name, shown, max, text, len);
}

/* A directory stream on a copy of fd (fd stays open); NULL on failure. */
static DIR *list_open(int fd) {
  int c = dup(fd);
  DIR *d = c >= 0 ? fdopendir(c) : NULL;
  if (!d && c >= 0) close(c);
  return d;
}

static char *path_join(const char *a, const char *b, const char *c) {
  size_t n = strlen(a) + strlen(b) + (c ? strlen(c) : 0) + 3;
  char *p = malloc(n);
  if (p) snprintf(p, n, c ? "%s/%s/%s" : "%s/%s", a, b, c ? c : "");
  return p;
}

/* "PREFIX" + digits + SUFFIX (SUFFIX may be followed by more when rest): the number, else -1. */
static int numbered(const char *name, const char *prefix, const char *suffix, const char **rest) {
  size_t p = strlen(prefix);
  if (strncmp(name, prefix, p)) return -1;
  const char *d = name + p, *e = d;
  long v = 0;
  while (*e >= '0' && *e <= '9' && e - d < 9) v = v * 10 + (*e++ - '0');
  if (e == d) return -1;
  if (rest) {
    if (*e != '_' || !e[1]) return -1;
    *rest = e + 1;
    size_t n = strlen(e + 1), s = strlen(suffix);
    return n > s && !strcmp(e + 1 + n - s, suffix) ? (int)v : -1;
  }
  return !strcmp(e, suffix) ? (int)v : -1;
}

/* Opens folder `name` of the run without following a symlink: -1 and
 * SESSILE_OK when absent; a link or non-folder is refused. */
static sessile_status open_folder(sessile_render_plan *p, const char *name, int *fd) {
  *fd = openat(p->dfd, name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (*fd >= 0 || errno == ENOENT) return SESSILE_OK;
  return sessile_error_set(SESSILE_ERR_USAGE, "'%s/%s' is not a folder of the run (%s)%s", p->run_dir, name,
                           strerror(errno), errno == ELOOP || errno == ENOTDIR ? ": a symlink or file: refused" : "");
}

/* Whether name in folder fd is a regular file (a symlink is refused). */
static sessile_status regular(const sessile_render_plan *p, int fd, const char *folder, const char *name, int *yes) {
  struct stat st;
  *yes = 0;
  if (fstatat(fd, name, &st, AT_SYMLINK_NOFOLLOW) != 0) return SESSILE_OK;
  SESSILE_CHECK(S_ISREG(st.st_mode), SESSILE_ERR_USAGE, "'%s/%s%s%s' is not a regular file (%s): refused", p->run_dir,
                folder ? folder : "", folder ? "/" : "", name, S_ISLNK(st.st_mode) ? "a symlink" : "not a file");
  *yes = 1;
  return SESSILE_OK;
}

static int by_index(const void *a, const void *b) {
  int x = ((const rp_snap *)a)->index, y = ((const rp_snap *)b)->index;
  return (x > y) - (x < y);
}

static int slice_order(const void *a, const void *b) {
  const rp_slice *x = a, *y = b;
  if (x->index != y->index) return (x->index > y->index) - (x->index < y->index);
  return strcmp(x->base, y->base);
}

/* The snapshots FOLDER/PREFIXNNNN.ply, sorted by NNNN. */
static sessile_status list_snapshots(sessile_render_plan *p, int fd) {
  DIR *d = list_open(fd);
  SESSILE_CHECK(d, SESSILE_ERR_IO, "cannot list '%s/%s': %s", p->run_dir, p->lay->folder, strerror(errno));
  sessile_status s = SESSILE_OK;
  int cap = 0;
  struct dirent *e;
  while (s == SESSILE_OK && (e = readdir(d)) != NULL) {
    int k = numbered(e->d_name, p->lay->snap_prefix, ".ply", NULL), yes = 0;
    if (k < 0) continue;
    s = regular(p, fd, p->lay->folder, e->d_name, &yes);
    if (s != SESSILE_OK || !yes) continue;
    if (p->nsnaps == cap) {
      rp_snap *q = realloc(p->snaps, (size_t)(cap = 2 * cap + 16) * sizeof *q);
      if (!q) {
        s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
        break;
      }
      p->snaps = q;
    }
    rp_snap *sn = &p->snaps[p->nsnaps];
    memset(sn, 0, sizeof *sn);
    sn->index = k;
    sn->mesh = path_join(p->run_dir, p->lay->folder, e->d_name);
    if (!sn->mesh) s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
    else p->nsnaps++;
  }
  closedir(d);
  if (p->nsnaps > 1) qsort(p->snaps, (size_t)p->nsnaps, sizeof *p->snaps, by_index);
  return s;
}

/* slices/iter_NNNN_PLANE.exr with the snapshot's mesh as the outline. */
static sessile_status list_slices(sessile_render_plan *p, int mfd) {
  int fd = -1;
  SESSILE_CALL(open_folder(p, "slices", &fd));
  if (fd < 0) return SESSILE_OK;
  DIR *d = list_open(fd);
  if (!d) {
    close(fd);
    return sessile_error_set(SESSILE_ERR_IO, "cannot list '%s/slices': %s", p->run_dir, strerror(errno));
  }
  sessile_status s = SESSILE_OK;
  int cap = 0, last = -1;
  struct dirent *e;
  while (s == SESSILE_OK && (e = readdir(d)) != NULL) {
    const char *plane = NULL;
    int k = numbered(e->d_name, "iter_", ".exr", &plane), yes = 0;
    if (k < 0 || strlen(e->d_name) >= 150) continue;
    s = regular(p, fd, "slices", e->d_name, &yes);
    if (s != SESSILE_OK || !yes) continue;
    if (p->nslices == cap) {
      rp_slice *q = realloc(p->slices, (size_t)(cap = 2 * cap + 16) * sizeof *q);
      if (!q) {
        s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
        break;
      }
      p->slices = q;
    }
    rp_slice *sl = &p->slices[p->nslices];
    memset(sl, 0, sizeof *sl);
    sl->index = k;
    snprintf(sl->base, sizeof sl->base, "%.*s", (int)(strlen(e->d_name) - 4), e->d_name);
    sl->exr = path_join(p->run_dir, "slices", e->d_name);
    char mesh[64];
    snprintf(mesh, sizeof mesh, "iter_%04d.ply", k);
    int have = 0;
    if (mfd >= 0) s = regular(p, mfd, p->lay->folder, mesh, &have);
    if (have) sl->outline = path_join(p->run_dir, p->lay->folder, mesh);
    if (!sl->exr || (have && !sl->outline)) {
      free(sl->exr), free(sl->outline);
      s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
    } else {
      p->nslices++;
      if (k > last) last = k;
    }
  }
  closedir(d);
  close(fd);
  for (int i = 0; i < p->nslices; i++) p->slices[i].all_channels = p->slices[i].index == last;
  if (p->nslices > 1) qsort(p->slices, (size_t)p->nslices, sizeof *p->slices, slice_order);
  return s;
}

/* Captions: "iteration 10"; for frames, "frame 3, t = 1.5" with the time
 * from records.jsonl's record of that frame when there is one. */
static void captions(sessile_render_plan *p) {
  char *text = NULL;
  size_t len = 0;
  if (p->records && !strcmp(p->lay->snap_word, "frame")) {
    if (rp_read_at(p->dfd, p->run_dir, "records.jsonl", (size_t)256 << 20, &text, &len) != SESSILE_OK) text = NULL;
  }
  for (int i = 0; i < p->nsnaps; i++)
    snprintf(p->snaps[i].caption, sizeof p->snaps[i].caption, "%s %d", p->lay->snap_word, p->snaps[i].index);
  for (char *line = text, *next; line && *line; line = next) {
    next = strchr(line, '\n');
    if (next) *next++ = 0;
    cJSON *r = cJSON_Parse(line);
    const cJSON *f = cJSON_GetObjectItemCaseSensitive(r, "frame"), *t = cJSON_GetObjectItemCaseSensitive(r, "time");
    if (cJSON_IsNumber(f) && cJSON_IsNumber(t))
      for (int i = 0; i < p->nsnaps; i++)
        if (p->snaps[i].index == (int)f->valuedouble)
          snprintf(p->snaps[i].caption, sizeof p->snaps[i].caption, "frame %d, t = %.4g", p->snaps[i].index,
                   t->valuedouble);
    cJSON_Delete(r);
  }
  free(text);
}

/* Who holds the run's lock ("pid N on host H"), for the message. */
static void lock_owner(int dfd, char *who, size_t n) {
  who[0] = 0;
  int fd = openat(dfd, ".sessile.lock", O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  struct stat st;
  if (fd >= 0 && fstat(fd, &st) == 0 && S_ISREG(st.st_mode)) {
    ssize_t k = pread(fd, who, n - 1, 0);
    who[k > 0 ? k : 0] = 0;
    who[strcspn(who, "\n")] = 0;
  }
  if (fd >= 0) close(fd);
}

/* Decides where the pictures go: RUN/renders (listed) or another folder. */
static sessile_status place_output(sessile_render_plan *p, const char *out_dir) {
  if (out_dir) {
    struct stat st;
    if (stat(out_dir, &st) == 0)
      SESSILE_CHECK(S_ISDIR(st.st_mode), SESSILE_ERR_USAGE, "-o '%s' is not a folder", out_dir);
    char a[PATH_MAX], b[PATH_MAX];
    if (realpath(out_dir, a) && realpath(p->run_dir, b) && strlen(b) + 9 < sizeof b) {
      strcat(b, "/renders");
      if (!strcmp(a, b)) out_dir = NULL; /* the default place, named */
    }
  }
  p->listed = out_dir == NULL;
  p->out_dir = p->listed ? path_join(p->run_dir, "renders", NULL) : strdup(out_dir);
  SESSILE_CHECK(p->out_dir, SESSILE_ERR_NO_MEMORY, "out of host memory");
  if (p->listed) {
    struct stat st;
    if (fstatat(p->dfd, "renders", &st, AT_SYMLINK_NOFOLLOW) == 0)
      SESSILE_CHECK(S_ISDIR(st.st_mode), SESSILE_ERR_USAGE, "'%s' is %s, not a folder: refused", p->out_dir,
                    S_ISLNK(st.st_mode) ? "a symlink" : "a file");
    SESSILE_CHECK(faccessat(p->dfd, ".", W_OK, 0) == 0, SESSILE_ERR_USAGE, "'%s' is not writable: %s (use -o DIR)",
                  p->run_dir, strerror(errno));
    /* writing into the run: only when no run holds it, and none starts meanwhile */
    if (flock(p->dfd, LOCK_EX | LOCK_NB) != 0) {
      char who[256];
      lock_owner(p->dfd, who, sizeof who);
      return sessile_error_set(SESSILE_ERR_USAGE,
                               "'%s' is in use by a running sessile run (%s): render it when the run ends, "
                               "or now into another folder with -o DIR",
                               p->run_dir, who[0] ? who : "pid unknown");
    }
  } else if (flock(p->dfd, LOCK_SH | LOCK_NB) != 0) {
    p->running = 1; /* read what is there: every file of a run is written atomically */
  } else {
    flock(p->dfd, LOCK_UN);
  }
  return SESSILE_OK;
}

sessile_status sessile_render_plan_make(const char *run_dir, const sessile_render_run_opts *o,
                                        sessile_render_plan **out) {
  *out = NULL;
  SESSILE_CHECK(run_dir && run_dir[0], SESSILE_ERR_USAGE, "no run directory given");
  sessile_render_plan *p = calloc(1, sizeof *p);
  SESSILE_CHECK(p, SESSILE_ERR_NO_MEMORY, "out of host memory");
  p->dfd = -1;
  p->width = o && o->width ? o->width : 1280;
  p->height = o && o->height ? o->height : 960;
  p->quiet = o ? o->quiet : 0;
  if (o) p->progress = o->progress, p->progress_user = o->progress_user;
  sessile_status s = SESSILE_OK;
  char *text = NULL;
  size_t len = 0;
  cJSON *m = NULL;
  int mfd = -1;
  p->run_dir = strdup(run_dir);
  if (!p->run_dir) s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  if (s == SESSILE_OK) {
    p->dfd = open(run_dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (p->dfd < 0) s = sessile_error_set(SESSILE_ERR_USAGE, "cannot open the run directory '%s': %s", run_dir, strerror(errno));
  }
  if (s == SESSILE_OK) s = rp_read_at(p->dfd, run_dir, "manifest.json", (size_t)64 << 20, &text, &len);
  if (s == SESSILE_OK && !text)
    s = sessile_error_set(SESSILE_ERR_USAGE, "'%s' is not a sessile run directory (no manifest.json)", run_dir);
  if (s == SESSILE_OK && !(m = cJSON_ParseWithLength(text, len)))
    s = sessile_error_set(SESSILE_ERR_USAGE, "'%s/manifest.json' is not JSON", run_dir);
  if (s == SESSILE_OK) {
    const cJSON *g = cJSON_GetObjectItemCaseSensitive(m, "generator");
    for (size_t k = 0; cJSON_IsString(g) && k < sizeof layouts / sizeof layouts[0]; k++)
      if (!strcmp(g->valuestring, layouts[k].generator)) p->lay = &layouts[k];
    if (!p->lay)
      s = sessile_error_set(SESSILE_ERR_USAGE,
                            "'%s': a run of generator '%.40s', whose layout sessile render does not know (grow, "
                            "sponge particles, sphere, coral lsystem, coral venation, sds, reef)",
                            run_dir, cJSON_IsString(g) ? g->valuestring : "?");
  }
  if (s == SESSILE_OK) s = open_folder(p, p->lay->folder, &mfd);
  int have_final = 0;
  const char *final_name = p->lay && p->lay->final_name ? p->lay->final_name : "final.ply";
  if (s == SESSILE_OK && mfd >= 0) s = regular(p, mfd, p->lay->folder, final_name, &have_final);
  if (s == SESSILE_OK && mfd >= 0 && p->lay->snap_prefix) s = list_snapshots(p, mfd);
  if (s == SESSILE_OK && p->lay->slices) s = list_slices(p, mfd);
  if (s == SESSILE_OK && !have_final && p->nsnaps == 0)
    s = sessile_error_set(SESSILE_ERR_USAGE, "'%s' holds nothing to draw yet (no %s/%s and no snapshots)",
                          run_dir, p->lay->folder, final_name);
  if (s == SESSILE_OK) {
    p->final_is_snapshot = !have_final;
    p->final_mesh = have_final ? path_join(run_dir, p->lay->folder, final_name) : strdup(p->snaps[p->nsnaps - 1].mesh);
    if (!p->final_mesh) s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  }
  int have_records = 0;
  if (s == SESSILE_OK && p->lay->plots[0]) s = regular(p, p->dfd, NULL, "records.jsonl", &have_records);
  if (s == SESSILE_OK && have_records && !(p->records = path_join(run_dir, "records.jsonl", NULL)))
    s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  /* the per-step log: refused when planted as a link, as records.jsonl is */
  if (s == SESSILE_OK && p->lay->steps_log && mfd >= 0)
    s = regular(p, mfd, p->lay->folder, p->lay->steps_log, &p->has_steps_log);
  if (s == SESSILE_OK && p->lay->snap_prefix) captions(p);
  if (s == SESSILE_OK) s = place_output(p, o ? o->out_dir : NULL);
  if (mfd >= 0) close(mfd);
  cJSON_Delete(m);
  free(text);
  if (s != SESSILE_OK) {
    sessile_render_plan_destroy(p);
    return s;
  }
  *out = p;
  return SESSILE_OK;
}

void sessile_render_plan_destroy(sessile_render_plan *p) {
  if (!p) return;
  if (p->dfd >= 0) close(p->dfd); /* releases the lock */
  for (int i = 0; i < p->nsnaps; i++) free(p->snaps[i].mesh);
  for (int i = 0; i < p->nslices; i++) free(p->slices[i].exr), free(p->slices[i].outline);
  for (int i = 0; i < p->nwritten; i++) free(p->written[i]);
  free(p->snaps), free(p->slices), free(p->written);
  free(p->final_mesh), free(p->records), free(p->run_dir), free(p->out_dir);
  free(p);
}
