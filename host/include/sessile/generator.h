/* sessile — the generator framework (layer: run).  A generator is a table of
 * functions over a state of its own; sessile_run_loop drives any of them
 * through the run directory: resume from the checkpoint, one record per
 * iteration, snapshots every K iterations and at the last, checkpoints,
 * stop requests and progress.  The command line around it (options,
 * --print-config, device, preview, exit codes) is the CLI's one generic
 * command, and host/cli/generators.def lists every generator once.
 * docs/run.md, "Writing a generator". */
#ifndef SESSILE_GENERATOR_H
#define SESSILE_GENERATOR_H

#include <stddef.h>
#include <stdint.h>
#include "sessile/gpu.h"
#include "sessile/param_table.h"
#include "sessile/run.h"
#include "sessile/surface.h"

#ifdef __cplusplus
extern "C" {
#endif

/* What a generator is given besides its parameters. */
typedef struct sessile_gen_setup {
  sessile_run *run;      /* the run directory (NULL in the checks before it opens) */
  sessile_gpu *gpu;      /* the device when needs_device said so, else NULL */
  uint64_t seed;
  int iterations, every; /* snapshots every K iterations (0: none) and at the last */
  unsigned flags;        /* bit k: the generator's flags[k] was given */
  double max_memory;     /* bytes the process may hold after an iteration (0: no budget) */
  void *extra;           /* the generator's own options (extra_size bytes; NULL: none) */
  struct sessile_gen_result *result; /* where end() reports (NULL: nowhere) */
} sessile_gen_setup;

/* What a generator's end() reports to the command around it. */
typedef struct sessile_gen_result {
  int exit_code;         /* a generator-specific exit code for this failure (0: the usual one) */
  char summary[512];     /* the summary line of a completed run ("" : "N iterations") */
} sessile_gen_result;

/* A boolean option of one generator ("--check"), kept in the run's
 * configuration under `key` so that a resume runs the same way. */
typedef struct sessile_gen_flag {
  const char *option, *key, *help;
} sessile_gen_flag;

#define SESSILE_GEN_MAX_SECTIONS 32

typedef struct sessile_generator {
  const char *name;        /* the command ("coral venation") and the manifest's generator */
  const char *summary;     /* one line of `sessile --help` */
  const char *about;       /* what it does and writes: the middle of its --help */
  const char *seed_help;   /* what the seed drives ("the random walk") */
  const char *out_default; /* "runs/sphere" */
  const char *snapshot_name; /* "sphere/iter_%04d.ply": the file a snapshot writes */
  const char *preview;     /* "sphere/final.ply": the mesh of preview.png (NULL: none) */
  const sessile_param_table *table;
  int iterations, every;   /* defaults */
  const sessile_gen_flag *flags;
  int nflags;
  /* Whether these parameters need a device (NULL: never). */
  int (*needs_device)(const void *params);
  /* Checks that need the options too (sizes against iterations), before
   * anything is written; NULL: none.  su->run and su->gpu are NULL. */
  sessile_status (*check)(const void *params, const sessile_gen_setup *su);
  /* The state before iteration 1; su stays valid until destroy. */
  sessile_status (*create)(const void *params, const sessile_gen_setup *su, void **state);
  /* The state of a checkpoint written after `iteration` iterations. */
  sessile_status (*restore)(void *state, const sessile_ckpt *ck);
  /* Iteration it (1, 2, ...): adds its members to the record, which holds
   * "iteration" already.  SESSILE_ERR_INTERRUPTED: it saw a stop request
   * part way (sessile_run_stop_requested); the loop checkpoints its
   * sections as iteration it - 1 and a resume reruns iteration it from
   * there (the generator keeps where it stood in its sections). */
  sessile_status (*step)(void *state, int it, cJSON *record);
  /* Writes the snapshot file `rel` (the generator's snapshot pattern). */
  sessile_status (*snapshot)(void *state, const char *rel);
  /* The state to checkpoint as named sections (at most
   * SESSILE_GEN_MAX_SECTIONS); their bytes stay valid until the next call. */
  sessile_status (*sections)(void *state, sessile_ckpt_section *sec, int *n);
  /* The final outputs after the last iteration. */
  sessile_status (*finish)(void *state);
  void (*destroy)(void *state); /* NULL-safe */

  /* --- optional: a generator with arguments of its own (sds run MODEL
   * --t-end T ...); NULL / 0 for one that has none. */
  const char *generator;   /* the manifest's generator (NULL: name) */
  const char *help;        /* the whole --help (NULL: composed from the members above) */
  /* Set: --iterations and --every are refused with this message, and
   * schedule() sets the counts. */
  const char *no_iterations;
  size_t extra_size;       /* bytes of su->extra (zeroed before parsing) */
  /* One argument of its own at argv[*i] (*i advanced over its values):
   * *taken 0 not its own, 1 an option a resume must not change, 2 one a
   * resume may repeat (config_read compares it); SESSILE_ERR_USAGE refuses. */
  sessile_status (*arg)(void *extra, int argc, char **argv, int *i, int *taken);
  /* The parameters before --config and --set (NULL: the table's defaults). */
  sessile_status (*defaults)(void *params, void *extra);
  /* A new run only, after check: further refusals and su->iterations and
   * su->every from the generator's own options. */
  sessile_status (*schedule)(const void *params, sessile_gen_setup *su);
  /* Extra members of the run's configuration, and back on a resume (extra
   * still holds what the command line gave, to compare with the run's). */
  sessile_status (*config_write)(const void *extra, cJSON *cfg);
  sessile_status (*config_read)(void *extra, const cJSON *cfg);
  void (*extra_free)(void *extra); /* what arg, defaults and config_read allocated */
  /* The run directory when --out is not given (NULL: out_default). */
  void (*out_dir)(const void *extra, char *buf, size_t n);
  /* Once after the loop whatever its outcome s, before destroy: the
   * generator's last words (its manifest member, logs flushed); returns the
   * run's status (s, or a later failure) and fills r when not NULL. */
  sessile_status (*end)(void *state, sessile_status s, sessile_gen_result *r);
} sessile_generator;

/* Progress after each iteration (the CLI prints it; NULL: silent). */
typedef void (*sessile_progress_fn)(void *user, int iteration, int iterations, double seconds);

/* Runs the generator in su->run from its checkpoint (if any) to
 * su->iterations: the manifest's parameters, records, snapshots,
 * checkpoints at each snapshot and when a stop is asked
 * (SESSILE_ERR_INTERRUPTED then), the final outputs.  Over su->max_memory
 * after an iteration it checkpoints and fails with SESSILE_ERR_TOO_LARGE.
 * A failure's message names where it passed ("iteration 12: ...").  *done: iterations
 * complete. */
sessile_status sessile_run_loop(const sessile_generator *g, const void *params, const sessile_gen_setup *su,
                                sessile_progress_fn progress, void *user, int *done);

/* The process's resident memory and the machine's physical memory, in
 * bytes (0 when unknown). */
double sessile_process_memory(void);
double sessile_physical_memory(void);

/* The configuration a resume restarts from (sessile_run_config_make plus
 * the flags as booleans), and back (SESSILE_ERR_USAGE when damaged). */
cJSON *sessile_gen_config(const sessile_generator *g, const void *params, const sessile_gen_setup *su);
sessile_status sessile_gen_config_read(const sessile_generator *g, const cJSON *cfg, void *params,
                                       sessile_gen_setup *su);

/* Writes the run's file rel (".ply", or ".obj" by its suffix) from s with
 * its vertex normals and, in a PLY, nextra named per-vertex values. */
sessile_status sessile_run_write_surface(sessile_run *run, const char *rel, const sessile_surface *s, int nextra,
                                         const char *const *names, const double *const *extra);

#ifdef __cplusplus
}
#endif
#endif
