/* Internal to host/run: the run object shared by rundir.c and checkpoint.c. */
#ifndef SESSILE_RUN_INTERNAL_H
#define SESSILE_RUN_INTERNAL_H
#include <stddef.h>
#include <stdint.h>
#include "sessile/run/run.h"

#define RUN_MANIFEST "manifest.json"
#define RUN_RECORDS "records.jsonl"
#define RUN_CHECKPOINT "checkpoint.bin"
#define RUN_LOCK ".sessile.lock" /* who holds the folder's flock */

#define RUN_MAX_LOGS 4 /* append-only logs per run (sessile_run_log) */
#define RUN_LOG_NAME 208

/* A log's name and its length: what a checkpoint keeps of it. */
typedef struct run_log_len {
  char rel[RUN_LOG_NAME];
  uint64_t bytes;
} run_log_len;

typedef struct ckpt_entry {
  char *name;
  const uint8_t *data;
  size_t bytes;
} ckpt_entry;

struct sessile_ckpt {
  int iteration;
  uint64_t records_bytes;
  int nlogs;
  run_log_len logs[RUN_MAX_LOGS]; /* the logs' lengths at the checkpoint */
  char config_id[16]; /* run_config_identity of the run that wrote it ("": older checkpoint) */
  cJSON *files;        /* the run's files at the checkpoint (NULL: older checkpoint) */
  uint8_t *blob; /* the file's bytes; entries point into it */
  int n;
  ckpt_entry *e;
};

struct sessile_run {
  char *dir, *generator;
  char host[256];
  int dfd, recfd;         /* the folder (flock'ed while the run lives), records.jsonl */
  cJSON *replaced;        /* --force: the older run's manifest, until its files are removed */
  const volatile sig_atomic_t *stop;
  cJSON *manifest, *config;
  uint64_t records_bytes; /* records.jsonl's length: a checkpoint keeps it */
  int start_count;        /* starts of this run before this one (resumes) */
  int nlogs;              /* logs opened by this start: fds and lengths */
  int log_fd[RUN_MAX_LOGS];
  run_log_len logs[RUN_MAX_LOGS];
  sessile_ckpt *ckpt;     /* on resume: the checkpoint read at open */
  char *version;
  char *commit;           /* NULL: not recorded */
  cJSON *command;         /* argv, until the start puts it in the manifest */
  sessile_run_mode mode;
  int absent;             /* admitted a folder that does not exist yet */
  int started;            /* sessile_run_start succeeded: the folder is this run's */
  int wrote_lock;         /* this start wrote the lock's owner file */
  int state_iteration;    /* the iteration whose state is being written, plus 1 (0: none; run_mesh.c) */
  char seed_text[24];     /* a numeric configuration seed as text (run_mesh.c) */
  sessile_obj_axes obj_axes; /* how OBJ files are written (sessile_run_set_obj_style) */
  char obj_material[64];  /* "": the default material */
  float obj_rgb[3];
};

/* Whether rel ends in a suffix of what runs write (.ply, .csv, ...). */
int run_output_name(const char *rel);
sessile_status run_read_file(int dfd, const char *name, size_t max, char **text, size_t *len);
/* Reads checkpoint.bin into r->ckpt (none: stays NULL) and r->records_bytes. */
sessile_status run_ckpt_read(sessile_run *r);
void run_ckpt_free(sessile_ckpt *c);
/* A short hash of a run's configuration without "iterations" (which a
 * resume may raise): what ties a checkpoint to its run. */
void run_config_identity(const cJSON *config, char out[16]);
/* SESSILE_ERR_USAGE when the loaded checkpoint belongs to another configuration. */
sessile_status run_ckpt_check_identity(const sessile_run *r);
void run_free(sessile_run *r);
/* On resume, before the records open: the files the manifest lists but the
 * checkpoint does not (written after it, or every file when there is no
 * checkpoint) are removed, so the resumed run never mixes in later
 * snapshots of the stopped one. */
sessile_status run_prune_to_checkpoint(sessile_run *r);
/* The logs' lengths to keep in a checkpoint: this start's, and the loaded
 * checkpoint's for logs not appended to since (n set to their count). */
void run_logs_to_keep(const sessile_run *r, run_log_len *out, int *n);
/* Opens dfd/name to append after its first `keep` bytes (the rest cut):
 * created if absent, no symlink followed, a regular file only (O_NONBLOCK
 * while checking: a planted FIFO does not hang); refuse_short: a file shorter
 * than keep is refused rather than extended.  The fd, or -1 with *why. */
int run_open_cut(int dfd, const char *name, uint64_t keep, int refuse_short, const char **why);
void run_logs_sync(const sessile_run *r);
void run_logs_close(sessile_run *r);

/* The run loop's progress (run_progress.c): iteration it begins, and ends
 * (measured by its kind, reported when su->meter has a reporter). */
#include "sessile/run/generator.h"
void run_progress_begin(const sessile_gen_setup *su, int it);
void run_progress_end(const sessile_gen_setup *su, int it);
/* The final outputs begin (ended 0) or are written (1): a stage of its own
 * (a reef's organisms are grown there). */
void run_progress_finish(const sessile_gen_setup *su, int ended);
#endif
