/* Internal to host/run: the run object shared by rundir.c and checkpoint.c. */
#ifndef SESSILE_RUN_INTERNAL_H
#define SESSILE_RUN_INTERNAL_H
#include <stddef.h>
#include <stdint.h>
#include "sessile/run.h"

#define RUN_MANIFEST "manifest.json"
#define RUN_RECORDS "records.jsonl"
#define RUN_CHECKPOINT "checkpoint.bin"
#define RUN_LOCK ".sessile.lock" /* who holds the folder's flock */

typedef struct ckpt_entry {
  char *name;
  const uint8_t *data;
  size_t bytes;
} ckpt_entry;

struct sessile_ckpt {
  int iteration;
  uint64_t records_bytes;
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
  sessile_ckpt *ckpt;     /* on resume: the checkpoint read at open */
};

sessile_status run_read_file(int dfd, const char *name, size_t max, char **text, size_t *len);
/* Reads checkpoint.bin into r->ckpt (none: stays NULL) and r->records_bytes. */
sessile_status run_ckpt_read(sessile_run *r);
void run_ckpt_free(sessile_ckpt *c);
void run_free(sessile_run *r);
#endif
