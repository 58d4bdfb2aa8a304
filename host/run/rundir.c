/* The run directory (sessile/run/run.h): lock, manifest, file list, records,
 * stop flag.  Everything inside the folder is reached through its file
 * descriptor with O_NOFOLLOW, so a symlink planted in a shared run directory
 * never redirects a write (docs/run.md). */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>
#include <dirent.h>
#include "run_internal.h"
#include "sessile/io/io.h"

void sessile_run_utc_now(char *buf, size_t n) {
  time_t t = time(NULL);
  struct tm tm;
  if (!gmtime_r(&t, &tm) || !strftime(buf, n, "%Y-%m-%dT%H:%M:%SZ", &tm)) snprintf(buf, n, "unknown");
}

/* "name" or "folder/name": plain components, no "..", no hidden names. */
static int plain_rel(const char *rel) {
  if (!rel || !*rel || strlen(rel) > 200) return 0;
  int slashes = 0;
  for (const char *c = rel; *c; c++) slashes += *c == '/';
  if (slashes > 1 || rel[0] == '/' || rel[0] == '.' || rel[strlen(rel) - 1] == '/') return 0;
  const char *s = strchr(rel, '/');
  if (s && (s[1] == '.' || s[1] == 0)) return 0;
  return 1;
}

/* Calls fn for every entry of the folder dfd (but "." and ".."). */
static void each_entry(int dfd, void (*fn)(int dfd, const char *name, void *user), void *user) {
  int fd = dup(dfd);
  if (fd < 0) return;
  DIR *d = fdopendir(fd);
  if (!d) {
    close(fd);
    return;
  }
  rewinddir(d); /* a dup shares its offset with dfd: start from the top */
  struct dirent *e;
  while ((e = readdir(d)) != NULL)
    if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) fn(dfd, e->d_name, user);
  closedir(d);
}

static void unlink_temp(int dfd, const char *name, void *user) {
  (void)user;
  if (sessile_is_temp_name(name)) unlinkat(dfd, name, 0);
}

/* Opens the subfolder `name` of dfd without following a symlink (creating
 * it when asked); -1 with errno on failure. */
static int open_subdir(int dfd, const char *name, int create) {
  if (create && mkdirat(dfd, name, 0777) != 0 && errno != EEXIST) return -1;
  return openat(dfd, name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
}

static void sweep_subdir(int dfd, const char *name, void *user) {
  (void)user;
  if (name[0] == '.') return;
  int sfd = open_subdir(dfd, name, 0);
  if (sfd < 0) return;
  each_entry(sfd, unlink_temp, NULL);
  close(sfd);
}

/* Removes leftover temporaries (sessile_is_temp_name) in the folder and each
 * real subfolder (one level, as runs write). */
static void sweep_all(int dfd) {
  each_entry(dfd, unlink_temp, NULL);
  each_entry(dfd, sweep_subdir, NULL);
}

/* What a run killed while taking a new folder can leave before its manifest
 * exists: the lock's owner file, empty records and temporaries.  Such a
 * folder has nothing to resume and nothing to lose, so a new run may use it. */
static int startup_leftover(int dfd, const char *name) {
  if (!strcmp(name, RUN_LOCK)) return 1;
  struct stat st;
  if (fstatat(dfd, name, &st, AT_SYMLINK_NOFOLLOW) != 0) return 0;
  if (sessile_is_temp_name(name)) return !S_ISDIR(st.st_mode); /* the sweep unlinks it */
  return !strcmp(name, RUN_RECORDS) && S_ISREG(st.st_mode) && st.st_size == 0;
}

static void count_foreign(int dfd, const char *name, void *user) {
  if (!startup_leftover(dfd, name)) ++*(int *)user;
}

/* Whether the folder holds nothing but a killed start's leftovers. */
static int folder_empty(int dfd) {
  int n = 0;
  each_entry(dfd, count_foreign, &n);
  return n == 0;
}

/* Reads a small regular file inside the folder (no symlink, FIFO or device). */
sessile_status run_read_file(int dfd, const char *name, size_t max, char **text, size_t *len) {
  char shown[300];
  snprintf(shown, sizeof shown, "'%.200s' in the run directory", name);
  return sessile_read_small_file_at(dfd, name, shown, max, text, len);
}

/* The lock is an flock on the folder itself: taking it creates nothing, so
 * a refused run leaves the folder exactly as it was.  Who holds it is written
 * to .sessile.lock only once the run is accepted (for the next one's message). */
static sessile_status lock_folder(sessile_run *r) {
  if (flock(r->dfd, LOCK_EX | LOCK_NB) == 0) return SESSILE_OK;
  int e = errno;
  char who[256] = "";
  int fd = openat(r->dfd, RUN_LOCK, O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  struct stat st;
  if (fd >= 0 && fstat(fd, &st) == 0 && S_ISREG(st.st_mode)) {
    ssize_t k = pread(fd, who, sizeof who - 1, 0);
    who[k > 0 ? k : 0] = 0;
    who[strcspn(who, "\n")] = 0;
  }
  if (fd >= 0) close(fd);
  if (e == EWOULDBLOCK)
    return sessile_error_set(SESSILE_ERR_USAGE,
                             "'%s' is in use by another sessile run (%s); wait for it to end or "
                             "choose another --out", r->dir, *who ? who : "pid unknown");
  return sessile_error_set(SESSILE_ERR_IO, "cannot lock '%s': %s", r->dir, strerror(e));
}

/* Records who holds the lock (the folder is ours now). */
static sessile_status write_lock_owner(sessile_run *r) {
  char me[300];
  int n = snprintf(me, sizeof me, "pid %ld on host %s\n", (long)getpid(), r->host);
  unlinkat(r->dfd, RUN_LOCK, 0);
  int fd = openat(r->dfd, RUN_LOCK, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
  int ok = fd >= 0 && write(fd, me, (size_t)n) == n;
  int e = errno;
  if (fd >= 0) close(fd);
  SESSILE_CHECK(ok, SESSILE_ERR_IO, "cannot write '%s/%s': %s", r->dir, RUN_LOCK, strerror(e));
  return SESSILE_OK;
}

/* Removes one listed file of an older run (rel checked; never follows). */
static void remove_rel(int dfd, const char *rel) {
  if (!plain_rel(rel)) return;
  const char *slash = strchr(rel, '/');
  if (!slash) {
    unlinkat(dfd, rel, 0);
    return;
  }
  char sub[256];
  snprintf(sub, sizeof sub, "%.*s", (int)(slash - rel), rel);
  int sfd = open_subdir(dfd, sub, 0);
  if (sfd < 0) return;
  unlinkat(sfd, slash + 1, 0);
  close(sfd);
}

static sessile_status replace_old(sessile_run *r, cJSON *old) {
  const cJSON *files = cJSON_GetObjectItemCaseSensitive(old, "files");
  const cJSON *f;
  cJSON_ArrayForEach(f, files) if (cJSON_IsString(f)) remove_rel(r->dfd, f->valuestring);
  const char *own[] = {RUN_MANIFEST, RUN_RECORDS, RUN_CHECKPOINT};
  for (int i = 0; i < 3; i++) unlinkat(r->dfd, own[i], 0);
  return SESSILE_OK;
}

static int listed(const cJSON *files, const char *rel);

/* What a run writes (sessile_run_file and sessile_run_log refuse other
 * suffixes): a listed file with another suffix is not ours. */
int run_output_name(const char *rel) {
  static const char *const ours[] = {".ply", ".obj", ".mtl", ".vtu", ".vtp", ".pvd", ".exr", ".png",
                                     ".csv", ".json", ".jsonl", ".bin", ".sds", ".lsys", ".glb", ".gltf"};
  const char *dot = strrchr(rel, '.');
  for (size_t i = 0; dot && i < sizeof ours / sizeof *ours; i++)
    if (!strcmp(dot, ours[i])) return 1;
  return 0;
}

/* --force removes an older run's files only when the folder proves to be a
 * sessile run: its manifest is sessile's (program, generator, a file list),
 * its lock's owner file is there, and every listed file is a plain run
 * output.  Anything else is refused whole: nothing is deleted. */
static sessile_status proven_run(const sessile_run *r, const cJSON *old) {
  const cJSON *prog = cJSON_GetObjectItemCaseSensitive(old, "program");
  const cJSON *gen = cJSON_GetObjectItemCaseSensitive(old, "generator");
  const cJSON *files = cJSON_GetObjectItemCaseSensitive(old, "files");
  struct stat st;
  int lock = fstatat(r->dfd, RUN_LOCK, &st, AT_SYMLINK_NOFOLLOW) == 0 && S_ISREG(st.st_mode);
  SESSILE_CHECK(cJSON_IsString(prog) && !strcmp(prog->valuestring, "sessile") && cJSON_IsString(gen) &&
                    cJSON_IsArray(files) && lock,
                SESSILE_ERR_USAGE,
                "'%s' holds a %s that sessile did not write (no sessile signature or lock file): "
                "--force replaces only sessile runs; choose another --out", r->dir, RUN_MANIFEST);
  const cJSON *f;
  cJSON_ArrayForEach(f, files) {
    SESSILE_CHECK(cJSON_IsString(f) && plain_rel(f->valuestring) && run_output_name(f->valuestring),
                  SESSILE_ERR_USAGE,
                  "'%s/%s' lists '%.60s', which is no file a sessile run writes: --force refused, "
                  "nothing deleted; choose another --out", r->dir, RUN_MANIFEST,
                  cJSON_IsString(f) ? f->valuestring : "?");
  }
  return SESSILE_OK;
}

sessile_status run_prune_to_checkpoint(sessile_run *r) {
  cJSON *files = cJSON_GetObjectItemCaseSensitive(r->manifest, "files");
  const cJSON *keep = r->ckpt ? r->ckpt->files : NULL;
  if (r->ckpt && !keep) return SESSILE_OK; /* a checkpoint of an older version: no list to go by */
  for (int i = cJSON_GetArraySize(files) - 1; i >= 0; i--) {
    const cJSON *f = cJSON_GetArrayItem(files, i);
    if (!cJSON_IsString(f) || (keep && listed(keep, f->valuestring))) continue;
    remove_rel(r->dfd, f->valuestring);
    cJSON_DeleteItemFromArray(files, i);
  }
  if (!keep) return SESSILE_OK;
  /* The checkpoint's list is the run's from here on: a run killed between
   * its checkpoint and the manifest's next write has a manifest that lacks
   * files the checkpoint already holds, and the next checkpoint would then
   * lack them too (a resumed run's bytes would differ). */
  cJSON *copy = cJSON_Duplicate(keep, 1);
  SESSILE_CHECK(copy, SESSILE_ERR_NO_MEMORY, "out of host memory for the run's file list");
  if (!cJSON_ReplaceItemInObjectCaseSensitive(r->manifest, "files", copy)) {
    cJSON_Delete(copy);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for the run's file list");
  }
  return SESSILE_OK;
}

static const char *state_of(const cJSON *m) {
  const cJSON *s = cJSON_GetObjectItemCaseSensitive(m, "state");
  return cJSON_IsString(s) ? s->valuestring : "unknown";
}

/* Reads the older run's manifest (NULL: none). */
static sessile_status old_manifest(sessile_run *r, cJSON **out) {
  *out = NULL;
  char *text = NULL;
  size_t len = 0;
  SESSILE_CALL(run_read_file(r->dfd, RUN_MANIFEST, 64u << 20, &text, &len));
  if (!text) return SESSILE_OK;
  cJSON *m = cJSON_ParseWithLength(text, len);
  free(text);
  SESSILE_CHECK(m && cJSON_IsObject(m), SESSILE_ERR_USAGE,
                "'%s/%s' is damaged (not a JSON object); move the folder away or choose another --out",
                r->dir, RUN_MANIFEST);
  *out = m;
  return SESSILE_OK;
}

static sessile_status open_records(sessile_run *r, int truncate_to_ckpt) {
  if (!truncate_to_ckpt) {
    unlinkat(r->dfd, RUN_RECORDS, 0);
    r->recfd = openat(r->dfd, RUN_RECORDS, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_APPEND | O_CLOEXEC, 0666);
  } else { /* what was appended after the checkpoint is redone, so cut it */
    const char *why = NULL;
    r->recfd = run_open_cut(r->dfd, RUN_RECORDS, r->records_bytes, 0, &why);
    SESSILE_CHECK(r->recfd >= 0, SESSILE_ERR_IO, "cannot open '%s/%s': %s", r->dir, RUN_RECORDS, why);
  }
  SESSILE_CHECK(r->recfd >= 0, SESSILE_ERR_IO, "cannot open '%s/%s': %s", r->dir, RUN_RECORDS, strerror(errno));
  return SESSILE_OK;
}

/* Decides whether this run may use the folder (nothing written yet). */
static sessile_status admit(sessile_run *r, const sessile_run_options *o) {
  cJSON *old = NULL;
  SESSILE_CALL(old_manifest(r, &old));
  sessile_status s = SESSILE_OK;
  if (o->mode == SESSILE_RUN_RESUME) {
    if (!old)
      return sessile_error_set(SESSILE_ERR_USAGE,
                               "nothing to resume in '%s': it holds no %s (a run stopped before it wrote one "
                               "has nothing saved: start it again with --out)", o->dir, RUN_MANIFEST);
    const cJSON *g = cJSON_GetObjectItemCaseSensitive(old, "generator");
    if (!cJSON_IsString(g) || strcmp(g->valuestring, r->generator)) {
      s = sessile_error_set(SESSILE_ERR_USAGE, "'%s' holds a run of another generator ('%.40s'), not '%s'",
                            o->dir, cJSON_IsString(g) ? g->valuestring : "?", r->generator);
      cJSON_Delete(old);
      return s;
    }
    cJSON *cfg = cJSON_DetachItemFromObjectCaseSensitive(old, "config");
    if (!cfg) s = sessile_error_set(SESSILE_ERR_USAGE, "'%s/%s' holds no configuration to resume from", o->dir, RUN_MANIFEST);
    r->config = cfg;
    /* files listed so far stay listed (a --force later removes them) */
    cJSON *files = cJSON_DetachItemFromObjectCaseSensitive(old, "files");
    if (files) cJSON_ReplaceItemInObjectCaseSensitive(r->manifest, "files", files);
    const cJSON *starts = cJSON_GetObjectItemCaseSensitive(old, "starts");
    if (cJSON_IsNumber(starts)) r->start_count = (int)starts->valuedouble;
    cJSON_Delete(old);
    if (s == SESSILE_OK) s = run_ckpt_read(r);
    if (s == SESSILE_OK) s = run_ckpt_check_identity(r);
    return s;
  }
  if (old && o->mode != SESSILE_RUN_REPLACE) {
    const cJSON *st = cJSON_GetObjectItemCaseSensitive(old, "start_time");
    s = sessile_error_set(SESSILE_ERR_USAGE,
                          "'%s' holds an earlier run (state %s, started %s); add --force to replace "
                          "it, --resume to continue it, or choose another --out",
                          o->dir, state_of(old), cJSON_IsString(st) ? st->valuestring : "unknown");
  } else if (old) {
    s = proven_run(r, old);
  } else if (!folder_empty(r->dfd)) {
    s = sessile_error_set(SESSILE_ERR_USAGE,
                          "'%s' is not empty and holds no sessile run (no %s); choose an empty "
                          "or new folder for --out", o->dir, RUN_MANIFEST);
  }
  r->replaced = old; /* removed once admitted */
  if (s != SESSILE_OK) {
    cJSON_Delete(old);
    r->replaced = NULL;
  }
  return s;
}

/* Opens the existing folder and takes its lock (nothing written). */
static sessile_status open_locked(sessile_run *r, const char *dir) {
  r->dfd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (r->dfd < 0 && r->mode == SESSILE_RUN_RESUME)
    return sessile_error_set(SESSILE_ERR_USAGE, "nothing to resume in '%s': %s", dir, strerror(errno));
  SESSILE_CHECK(r->dfd >= 0, SESSILE_ERR_USAGE, "cannot open the run directory '%s': %s", dir, strerror(errno));
  SESSILE_CHECK(faccessat(r->dfd, ".", W_OK, 0) == 0, SESSILE_ERR_USAGE,
                "the run directory '%s' is not writable: %s", dir, strerror(errno));
  return lock_folder(r);
}

/* Reads, never writes: whether this run may use the folder.  A folder that
 * does not exist yet is created by sessile_run_start, not here. */
static sessile_status admit_folder(sessile_run *r, const sessile_run_options *o) {
  SESSILE_CHECK(o->dir && *o->dir, SESSILE_ERR_USAGE, "the run directory needs a name");
  SESSILE_CHECK(strlen(o->dir) < 3500, SESSILE_ERR_USAGE, "the run directory's name is too long");
  r->dir = strdup(o->dir);
  r->generator = strdup(o->generator ? o->generator : "");
  r->version = strdup(o->version ? o->version : "dev");
  r->commit = o->commit ? strdup(o->commit) : NULL;
  SESSILE_CHECK(r->dir && r->generator && r->version && (r->commit || !o->commit), SESSILE_ERR_NO_MEMORY,
                "out of host memory");
  r->mode = o->mode;
  if (gethostname(r->host, sizeof r->host) != 0) snprintf(r->host, sizeof r->host, "unknown");
  r->host[sizeof r->host - 1] = 0;
  struct stat st;
  if (o->mode != SESSILE_RUN_RESUME && (stat(o->dir, &st) != 0 || !S_ISDIR(st.st_mode))) { /* start creates it, or says why not */
    r->absent = 1; /* a new folder: nothing to admit */
    return SESSILE_OK;
  }
  SESSILE_CALL(open_locked(r, o->dir));
  return admit(r, o);
}

/* The folder becomes this run's: created when new, the lock's owner
 * written, leftovers swept, an older run's files removed (--force) or cut
 * back to the checkpoint (--resume), records opened. */
static sessile_status take_folder(sessile_run *r) {
  if (r->absent) {
    sessile_status s = sessile_mkdirs(r->dir);
    if (s == SESSILE_ERR_NO_MEMORY) return sessile_error_pass(s, "cannot create the run directory");
    if (s != SESSILE_OK)
      return sessile_error_set(SESSILE_ERR_USAGE, "cannot create the run directory: %s", sessile_error_message());
    sessile_run_options o = {.dir = r->dir, .generator = r->generator, .mode = r->mode};
    SESSILE_CALL(open_locked(r, r->dir));
    SESSILE_CALL(admit(r, &o)); /* created meanwhile by someone else? */
    r->absent = 0;
  }
  SESSILE_CALL(write_lock_owner(r));
  r->wrote_lock = 1;
  sweep_all(r->dfd);
  if (r->mode == SESSILE_RUN_RESUME) {
    SESSILE_CALL(run_prune_to_checkpoint(r));
    return open_records(r, 1);
  }
  if (r->replaced) {
    SESSILE_CALL(replace_old(r, r->replaced));
    cJSON_Delete(r->replaced);
    r->replaced = NULL;
  }
  unlinkat(r->dfd, RUN_CHECKPOINT, 0);
  return open_records(r, 0);
}

sessile_status sessile_run_admit(const sessile_run_options *o, sessile_run **out) {
  *out = NULL;
  sessile_run *r = calloc(1, sizeof *r);
  SESSILE_CHECK(r, SESSILE_ERR_NO_MEMORY, "out of host memory");
  r->dfd = r->recfd = -1;
  r->stop = o->stop;
  r->manifest = cJSON_CreateObject();
  sessile_status s = r->manifest ? SESSILE_OK : sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  if (s == SESSILE_OK) {
    cJSON_AddArrayToObject(r->manifest, "files");
    s = admit_folder(r, o);
  }
  if (s == SESSILE_OK) {
    /* the command line is copied: the caller's argv may not outlive the admit */
    cJSON *cmd = cJSON_CreateArray();
    for (int i = 0; cmd && i < o->argc && o->argv && o->argv[i]; i++)
      cJSON_AddItemToArray(cmd, cJSON_CreateString(o->argv[i]));
    r->command = cmd;
    if (!cmd) s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  }
  if (s != SESSILE_OK) {
    run_free(r);
    return s;
  }
  *out = r;
  return SESSILE_OK;
}

/* Undoes what a failed start created in a folder that was not a run before
 * (the lock's owner file, empty records), so the same --out is accepted
 * again. */
static void undo_start(sessile_run *r) {
  if (r->mode == SESSILE_RUN_RESUME || r->dfd < 0) return;
  if (r->recfd >= 0 && r->records_bytes == 0) {
    close(r->recfd);
    r->recfd = -1;
    unlinkat(r->dfd, RUN_RECORDS, 0);
  }
  if (r->wrote_lock) unlinkat(r->dfd, RUN_LOCK, 0);
}

sessile_status sessile_run_start(sessile_run *r) {
  SESSILE_CHECK(r && !r->started, SESSILE_ERR_INTERNAL, "sessile_run_start: the run is not admitted or already started");
  sessile_status s = take_folder(r);
  if (s == SESSILE_OK) {
    cJSON *m = r->manifest;
    cJSON_AddStringToObject(m, "program", "sessile");
    cJSON_AddStringToObject(m, "generator", r->generator);
    cJSON_AddStringToObject(m, "version", r->version);
    if (r->commit) cJSON_AddStringToObject(m, "commit", r->commit);
    cJSON_AddStringToObject(m, "state", "running");
    cJSON_AddNumberToObject(m, "pid", (double)getpid());
    cJSON_AddStringToObject(m, "host", r->host);
    cJSON_AddItemToObject(m, "command", r->command);
    r->command = NULL;
    char now[64];
    sessile_run_utc_now(now, sizeof now);
    cJSON_AddStringToObject(m, "start_time", now);
    cJSON_AddNullToObject(m, "end_time");
    cJSON_AddNumberToObject(m, "starts", r->start_count + 1);
    cJSON_AddNumberToObject(m, "resumed_from_iteration", r->ckpt ? r->ckpt->iteration : 0);
    cJSON_AddStringToObject(m, "records", RUN_RECORDS);
    if (!cJSON_GetObjectItemCaseSensitive(m, "files")) cJSON_AddArrayToObject(m, "files");
    s = sessile_run_write_manifest(r);
  }
  if (s != SESSILE_OK) {
    undo_start(r);
    return s;
  }
  r->started = 1;
  return SESSILE_OK;
}

sessile_status sessile_run_open(const sessile_run_options *o, sessile_run **out) {
  SESSILE_CALL(sessile_run_admit(o, out));
  sessile_status s = sessile_run_start(*out);
  if (s != SESSILE_OK) {
    run_free(*out);
    *out = NULL;
  }
  return s;
}

cJSON *sessile_run_manifest(sessile_run *r) { return r->manifest; }

sessile_status sessile_run_set_config(sessile_run *r, cJSON *config) {
  cJSON_Delete(r->config);
  r->config = config;
  /* at once: a run killed before its first checkpoint restarts from it */
  return sessile_run_write_manifest(r);
}

const cJSON *sessile_run_config(const sessile_run *r) { return r->config; }

int sessile_run_resumed_at(const sessile_run *r) { return r->ckpt ? r->ckpt->iteration : 0; }

int sessile_run_stop_requested(const sessile_run *r) { return r->stop ? (int)*r->stop : 0; }

sessile_status sessile_run_write_manifest(sessile_run *r) {
  cJSON *m = r->manifest;
  if (r->config) {
    cJSON *c = cJSON_Duplicate(r->config, 1);
    SESSILE_CHECK(c, SESSILE_ERR_NO_MEMORY, "out of host memory for the manifest");
    if (cJSON_GetObjectItemCaseSensitive(m, "config")) cJSON_ReplaceItemInObjectCaseSensitive(m, "config", c);
    else cJSON_AddItemToObject(m, "config", c);
  }
  char *text = cJSON_Print(m);
  SESSILE_CHECK(text, SESSILE_ERR_NO_MEMORY, "out of host memory printing the manifest");
  size_t len = strlen(text);
  char path[4096];
  snprintf(path, sizeof path, "%s/%s", r->dir, RUN_MANIFEST);
  text[len] = '\n'; /* the terminator becomes the file's last newline */
  sessile_status s = sessile_write_file_atomic(path, text, len + 1);
  free(text);
  return s;
}

static int listed(const cJSON *files, const char *rel) {
  const cJSON *f;
  cJSON_ArrayForEach(f, files) if (cJSON_IsString(f) && !strcmp(f->valuestring, rel)) return 1;
  return 0;
}

sessile_status sessile_run_file(sessile_run *r, const char *rel, char *path, size_t n) {
  SESSILE_CHECK(plain_rel(rel), SESSILE_ERR_INTERNAL, "run file name '%s' is not a plain relative name", rel);
  SESSILE_CHECK(run_output_name(rel), SESSILE_ERR_INTERNAL, "run file name '%s' has no run output's suffix", rel);
  const char *slash = strchr(rel, '/');
  if (slash) {
    char sub[256];
    snprintf(sub, sizeof sub, "%.*s", (int)(slash - rel), rel);
    int sfd = open_subdir(r->dfd, sub, 1);
    SESSILE_CHECK(sfd >= 0, SESSILE_ERR_IO, "cannot use the folder '%s/%s': %s%s", r->dir, sub,
                  strerror(errno), errno == ELOOP || errno == ENOTDIR ? " (a symlink or file is there: refused)" : "");
    close(sfd);
  }
  int k = snprintf(path, n, "%s/%s", r->dir, rel);
  SESSILE_CHECK(k > 0 && (size_t)k < n, SESSILE_ERR_USAGE, "the path of '%s' is too long", rel);
  cJSON *files = cJSON_GetObjectItemCaseSensitive(r->manifest, "files");
  if (!listed(files, rel)) cJSON_AddItemToArray(files, cJSON_CreateString(rel));
  return SESSILE_OK;
}

sessile_status sessile_run_remove_file(sessile_run *r, const char *rel) {
  SESSILE_CHECK(plain_rel(rel), SESSILE_ERR_INTERNAL, "run file name '%s' is not a plain relative name", rel);
  remove_rel(r->dfd, rel);
  cJSON *files = cJSON_GetObjectItemCaseSensitive(r->manifest, "files");
  int i = 0;
  const cJSON *f;
  cJSON_ArrayForEach(f, files) {
    if (cJSON_IsString(f) && !strcmp(f->valuestring, rel)) {
      cJSON_DeleteItemFromArray(files, i);
      break;
    }
    i++;
  }
  return SESSILE_OK;
}

sessile_status sessile_run_record(sessile_run *r, const cJSON *rec) {
  char *line = cJSON_PrintUnformatted(rec);
  SESSILE_CHECK(line, SESSILE_ERR_NO_MEMORY, "out of host memory for a record");
  size_t len = strlen(line);
  line[len] = '\n';
  size_t done = 0;
  int e = 0;
  while (done < len + 1) {
    ssize_t k = write(r->recfd, line + done, len + 1 - done);
    if (k < 0 && errno == EINTR) continue;
    if (k < 0) {
      e = errno;
      break;
    }
    done += (size_t)k;
  }
  free(line);
  SESSILE_CHECK(!e, SESSILE_ERR_IO, "cannot append to '%s/%s': %s", r->dir, RUN_RECORDS, strerror(e));
  r->records_bytes += len + 1;
  return SESSILE_OK;
}

void run_free(sessile_run *r) {
  if (!r) return;
  if (r->recfd >= 0) close(r->recfd);
  run_logs_close(r);
  if (r->dfd >= 0) close(r->dfd); /* releases the flock */
  cJSON_Delete(r->replaced);
  cJSON_Delete(r->manifest);
  cJSON_Delete(r->config);
  run_ckpt_free(r->ckpt);
  cJSON_Delete(r->command);
  free(r->dir);
  free(r->generator);
  free(r->version);
  free(r->commit);
  free(r);
}

sessile_status sessile_run_close(sessile_run *r, sessile_status s) {
  if (!r) return s;
  if (!r->started) { /* refused before it began: the folder is left as it was */
    run_free(r);
    return s;
  }
  char msg[1024] = "";
  if (s != SESSILE_OK) snprintf(msg, sizeof msg, "%s", sessile_error_message());
  const char *state = s == SESSILE_OK ? "completed" : s == SESSILE_ERR_INTERRUPTED ? "interrupted" : "failed";
  cJSON *m = r->manifest;
  cJSON_ReplaceItemInObjectCaseSensitive(m, "state", cJSON_CreateString(state));
  char now[64];
  sessile_run_utc_now(now, sizeof now);
  cJSON_ReplaceItemInObjectCaseSensitive(m, "end_time", cJSON_CreateString(now));
  cJSON_DeleteItemFromObjectCaseSensitive(m, "error");
  if (s != SESSILE_OK) cJSON_AddStringToObject(m, "error", msg);
  if (s == SESSILE_ERR_INTERRUPTED && r->stop)
    cJSON_AddNumberToObject(m, "signal", (double)*r->stop);
  if (r->recfd >= 0 && fsync(r->recfd) != 0 && errno != EINVAL && s == SESSILE_OK)
    s = sessile_error_set(SESSILE_ERR_IO, "cannot sync '%s/%s': %s", r->dir, RUN_RECORDS, strerror(errno));
  sessile_status ms = sessile_run_write_manifest(r);
  if (s == SESSILE_OK) s = ms;
  else sessile_error_set(s, "%s", msg); /* the first error is the one to report */
  run_free(r);
  return s;
}
