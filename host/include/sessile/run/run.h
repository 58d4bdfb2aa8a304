/* sessile — the run directory every generator writes through: an exclusive
 * lock, a summary manifest (state running / completed / failed /
 * interrupted, pid, host, command line, version, start and end times, the
 * configuration to resume from, every file the run wrote), per-iteration
 * records appended as JSON Lines, checkpoints, and a stop flag for SIGINT /
 * SIGTERM.  docs/run.md describes the directory and the rules.
 *
 * Rules: a run never mixes with an older one (a folder holding a run is
 * refused unless the caller replaces it, which removes the old run's listed
 * files, or resumes it); a second run into a locked folder is refused with
 * the other run's pid and host; temporaries left by a killed run are removed
 * at the next start; files inside the folder are opened without following
 * symlinks.  Library code: nothing here prints or installs signal handlers. */
#ifndef SESSILE_RUN_H
#define SESSILE_RUN_H

#include <signal.h>
#include <stddef.h>
#include <cjson/cJSON.h>
#include <stdint.h>
#include "sessile/io/io.h"
#include "sessile/run/param_table.h"
#include "sessile/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sessile_run sessile_run;
typedef struct sessile_ckpt sessile_ckpt;

typedef enum sessile_run_mode {
  SESSILE_RUN_NEW = 0,     /* the folder must be new, empty, or hold only what a killed start leaves (lock, empty records, temporaries) */
  SESSILE_RUN_REPLACE = 1, /* --force: an older run's files (its manifest's list) are removed first */
  SESSILE_RUN_RESUME = 2   /* --resume: continue the run in the folder from its checkpoint */
} sessile_run_mode;

typedef struct sessile_run_options {
  const char *dir;          /* the run directory (created with its parents) */
  const char *generator;    /* e.g. "grow": a resume must name the same */
  const char *version;      /* sessile's version, recorded */
  const char *commit;       /* the commit it was built from, recorded when not NULL */
  int argc;                 /* the command line, recorded */
  char *const *argv;
  sessile_run_mode mode;
  /* Nonzero asks the run to stop at the next safe point (a signal handler
   * sets it; NULL: never).  Its value is recorded (the signal number). */
  const volatile sig_atomic_t *stop;
} sessile_run_options;

/* Opens (and locks) the run directory.  SESSILE_ERR_USAGE: the folder is in
 * use by another run (its pid and host named), holds an older run (mode
 * NEW), is not a sessile run directory and not empty, or holds nothing to
 * resume; SESSILE_ERR_IO: it cannot be created or written. */
sessile_status sessile_run_open(const sessile_run_options *o, sessile_run **out);
/* sessile_run_open in two steps, so that a command can refuse after seeing
 * the stored configuration and checkpoint without touching the folder:
 * admit locks an existing folder and reads its manifest, configuration and
 * checkpoint (a resume's config and checkpoint are readable at once) but
 * writes nothing and creates no folder; start makes the folder the run's
 * (creates it, sweeps leftovers, removes an older run's files or those a
 * resume goes back past, opens the records, writes the manifest).  Closing
 * an admitted run that never started leaves the folder as it was. */
sessile_status sessile_run_admit(const sessile_run_options *o, sessile_run **out);
sessile_status sessile_run_start(sessile_run *r);

/* The manifest's root: a generator adds its own members (parameters,
 * device, ...); the run's own members (state, pid, files, ...) are set by
 * the framework and must not be touched. */
cJSON *sessile_run_manifest(sessile_run *r);
/* The configuration a resume restarts from (generator-defined JSON: its
 * parameters and options).  Set takes ownership and writes the manifest at
 * once; get returns the stored one (on resume: the older run's). */
sessile_status sessile_run_set_config(sessile_run *r, cJSON *config);
const cJSON *sessile_run_config(const sessile_run *r);
/* The usual configuration of a generator with iterations: {"seed": "N" (as
 * text: 64 bits survive), "iterations": I, "every": K, "parameters": {the
 * table's values}}; the caller may add members.  NULL when out of memory. */
cJSON *sessile_run_config_make(const sessile_param_table *t, const void *params, uint64_t seed, int iterations,
                               int every);
/* Reads it back (a stored config: values bit for bit), checks the values
 * against the table; SESSILE_ERR_USAGE when damaged. */
sessile_status sessile_run_config_take(const cJSON *cfg, const sessile_param_table *t, void *params, uint64_t *seed,
                                       int *iterations, int *every);
/* Writes manifest.json now (atomically). */
sessile_status sessile_run_write_manifest(sessile_run *r);

/* The path of a file of the run, rel relative to the run directory ("final.ply",
 * "sponge/iter_0010.ply"; plain names, no "..", at most one folder deep):
 * creates its folder if needed (refusing a symlink or non-folder there) and
 * lists the file in the manifest, so a later --force removes exactly it. */
sessile_status sessile_run_file(sessile_run *r, const char *rel, char *path, size_t n);
/* Removes a file of the run and its listing (absent: not an error). */
sessile_status sessile_run_remove_file(sessile_run *r, const char *rel);

/* How the run writes OBJ files (sessile_run_write_obj; docs/io.md "OBJ
 * conventions"): the axes and unit, and the one material of the .mtl beside
 * each (its name: characters other than letters, digits, '-' and '_'
 * become '_', at most 63; rgb linear 0..1).  Unset: zup-cm, "sessile", a
 * neutral grey (0.7). */
void sessile_run_set_obj_style(sessile_run *r, sessile_obj_axes axes, const char *material, const float rgb[3]);

/* Appends one record (a line of records.jsonl); takes no ownership. */
sessile_status sessile_run_record(sessile_run *r, const cJSON *rec);
/* Appends n bytes to the run's log `rel` ("sds/steps.csv": a plain name, at
 * most one folder deep; at most 4 logs a run), created and listed at its
 * first append.  For rows too many to rewrite atomically at every frame: a
 * checkpoint keeps each log's length and a resume cuts what was appended
 * after it, so the log of a resumed run holds each row once. */
sessile_status sessile_run_log(sessile_run *r, const char *rel, const void *bytes, size_t n);
/* Nonzero once a stop was asked for (the signal number). */
int sessile_run_stop_requested(const sessile_run *r);
/* The iteration the run continues after (0 for a new run). */
int sessile_run_resumed_at(const sessile_run *r);

/* --- checkpoints ------------------------------------------------------------ */
/* A named block of bytes of the generator's state. */
typedef struct sessile_ckpt_section {
  const char *name;
  const void *data;
  size_t bytes;
} sessile_ckpt_section;
/* Writes checkpoint.bin atomically (sections with CRC-32s, plus the run's
 * own: the iteration, the records written so far, the file list) and the
 * manifest.  Call it with the state after `iteration` complete iterations. */
sessile_status sessile_run_checkpoint(sessile_run *r, int iteration, int nsections,
                                      const sessile_ckpt_section *sections);
/* On resume: the checkpoint read at open (NULL when the run stopped before
 * its first checkpoint: then it restarts from the beginning). */
const sessile_ckpt *sessile_run_checkpoint_loaded(const sessile_run *r);
int sessile_ckpt_iteration(const sessile_ckpt *c);
/* A section's bytes, or NULL when absent (bytes set to its size). */
const void *sessile_ckpt_get(const sessile_ckpt *c, const char *name, size_t *bytes);
/* Copies the section `name` into dst when it holds exactly `bytes` bytes;
 * SESSILE_ERR_IO naming the section otherwise. */
sessile_status sessile_ckpt_take(const sessile_ckpt *c, const char *name, void *dst, size_t bytes);

/* Ends the run: state completed (s == SESSILE_OK), interrupted
 * (SESSILE_ERR_INTERRUPTED) or failed (with sessile_error_message()), end
 * time, final manifest; unlocks and frees.  Returns s, or the manifest's
 * write error when s was SESSILE_OK.  NULL-safe. */
sessile_status sessile_run_close(sessile_run *r, sessile_status s);

/* ISO 8601 UTC time of now into buf ("2026-11-23T18:49:51Z"). */
void sessile_run_utc_now(char *buf, size_t n);

#ifdef __cplusplus
}
#endif
#endif
