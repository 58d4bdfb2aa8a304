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
#include "sessile/gpu/gpu.h"
#include "sessile/progress.h"
#include "sessile/run/param_table.h"
#include "sessile/run/run.h"
#include "sessile/mesh/surface.h"
#include "sessile/io/io.h"

#ifdef __cplusplus
extern "C" {
#endif

/* What a line for the user is: a transient status (a terminal may
 * overwrite it), the end of an iteration, or a warning the user should read. */
typedef enum { SESSILE_MONITOR_STATUS = 0, SESSILE_MONITOR_ITERATION = 1, SESSILE_MONITOR_WARNING = 2 } sessile_monitor_kind;
/* Where a generator's lines go (one line each, no newline); library code
 * prints nothing itself. */
typedef void (*sessile_gen_say_fn)(void *user, sessile_monitor_kind kind, const char *line);

#define SESSILE_GEN_MAX_OPTIONS 8

/* The run loop's progress: where its reports go and what it measured for
 * the estimate of time left (run_progress.c; docs/run.md "Progress").  A
 * generator reports within an iteration through sessile_gen_progress. */
typedef struct sessile_gen_meter {
  sessile_progress_fn fn;  /* NULL: nothing is reported */
  void *user;
  const char *unit;        /* the stage of an iteration's end: "iteration", "frame" */
  int it;                  /* the iteration running */
  double t_it;             /* its start (wall clock) */
  double sum[2];           /* seconds of the iterations measured, without [0] and with [1] a snapshot */
  int n[2];
  char detail[160];        /* what the iteration made, for the report of its end */
} sessile_gen_meter;

/* What a generator is given besides its parameters. */
typedef struct sessile_gen_setup {
  sessile_run *run;      /* the run directory (NULL in the checks before it opens; NULL in a
                            library caller's run without files, e.g. a benchmark) */
  sessile_gpu *gpu;      /* the device when needs_device said so, else NULL */
  uint64_t seed;
  int iterations, every; /* snapshots every K iterations (0: none) and at the last */
  unsigned flags;        /* bit k: the generator's flags[k] was given */
  double max_memory;     /* bytes the process may hold after an iteration (0: no budget) */
  void *extra;           /* the generator's own options (extra_size bytes; NULL: none) */
  struct sessile_gen_result *result; /* where end() reports (NULL: nowhere) */
  const char *preset;    /* the preset's name (a generator with presets), else NULL */
  const char *values[SESSILE_GEN_MAX_OPTIONS]; /* options[k]'s value (its fallback when not given) */
  sessile_gen_say_fn say; /* status, iteration and warning lines (NULL: silent) */
  void *say_user;
  const void *caller;    /* a library caller's own options for this generator (NULL from the CLI) */
  sessile_gen_meter *meter; /* the run loop's own (set by it; NULL outside the loop) */
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

/* An option of one generator with a value ("--slices SPEC"; an empty
 * value is a value), kept in the run's configuration under `key` as text. */
typedef struct sessile_gen_option {
  const char *option, *key, *metavar, *fallback, *help;
} sessile_gen_option;

/* Named starting points of the parameters (`--preset NAME`): apply sets
 * params to the preset's values (before every --config and --set);
 * SESSILE_ERR_USAGE names the presets for an unknown name.  The name is
 * kept in the run's configuration ("preset") and given in su->preset. */
typedef struct sessile_gen_presets {
  const char *fallback; /* without --preset */
  const char *help;     /* lines of --help after "--preset NAME", each starting with spaces */
  sessile_status (*apply)(const char *name, void *params);
} sessile_gen_presets;

#define SESSILE_GEN_MAX_SECTIONS 32

typedef struct sessile_generator {
  const char *name;        /* the command ("coral venation") and the manifest's generator */
  const char *summary;     /* one line of `sessile --help` */
  const char *about;       /* what it does and writes: the middle of its --help */
  const char *seed_help;   /* what the seed drives ("the random walk") */
  const char *out_default; /* "runs/sphere"; with presets, one %s: the preset's name */
  const char *snapshot_name; /* "sphere/iter_%04d.ply": the file a snapshot writes */
  const char *preview;     /* "sphere/final.ply": the mesh of preview.png (NULL: none) */
  const sessile_param_table *table;
  int iterations, every;   /* defaults */
  const sessile_gen_flag *flags;
  int nflags;
  /* Whether these parameters need a device (NULL: never). */
  int (*needs_device)(const void *params);
  /* Checks that need the options too (sizes against iterations), before
   * anything is written; NULL: none.  su->run is NULL; called first with
   * su->gpu NULL (also for --print-config), then, when the generator needs
   * a device, again with it (what the device cannot hold). */
  sessile_status (*check)(const void *params, const sessile_gen_setup *su);
  /* The state before iteration 1; su stays valid until destroy.  A create
   * that fails after setting *state is destroyed (destroy: NULL-safe). */
  sessile_status (*create)(const void *params, const sessile_gen_setup *su, void **state);
  /* The state of a checkpoint written after `iteration` iterations. */
  sessile_status (*restore)(void *state, const sessile_ckpt *ck);
  /* Iteration it (1, 2, ...): adds its members to the record, which holds
   * "iteration" already (sessile_gen_snapshot_kind: whether a snapshot
   * follows).  SESSILE_ERR_INTERRUPTED: it saw a stop request
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

  /* Optional members (zero: none), last so that a table may leave them out. */
  const sessile_gen_option *options;
  int noptions;
  const sessile_gen_presets *presets;
  const char *progress_unit; /* what an iteration is called in progress reports (NULL: "iteration") */
  /* On a resume past an old last iteration k off the --every grid: removes
   * that final-only snapshot (every file of it).  NULL: the loop removes
   * the snapshot_name file. */
  sessile_status (*unsnapshot)(void *state, int k);
} sessile_generator;

/* The seven required callbacks of a generator that names its static
 * functions create, restore, step, snapshot, sections, finish and destroy
 * (every generator in this tree but sds, whose names carry a prefix). */
#define SESSILE_GEN_CALLBACKS                                                   \
  .create = create, .restore = restore, .step = step, .snapshot = snapshot,   \
  .sections = sections, .finish = finish, .destroy = destroy

/* Whether iteration it writes a snapshot: 0 no, 1 on the --every grid,
 * 2 only because it is the last (a resume that goes on removes it). */
int sessile_gen_snapshot_kind(const sessile_gen_setup *su, int it);

/* Within iteration it of the loop: the stage running now and the part of
 * the iteration done (0..1); detail (NULL: none) is kept for the report of
 * the iteration's end (stage NULL: only that).  Nothing outside the loop
 * or without a reporter. */
void sessile_gen_progress(const sessile_gen_setup *su, const char *stage, double part, const char *detail);

/* Runs the generator in su->run from its checkpoint (if any) to
 * su->iterations: the manifest's parameters, records, snapshots,
 * checkpoints at each snapshot and when a stop is asked
 * (SESSILE_ERR_INTERRUPTED then), the final outputs.  Over su->max_memory
 * after an iteration it checkpoints and fails with SESSILE_ERR_TOO_LARGE.
 * A failure's message names where it passed ("iteration 12: ...").  *done:
 * iterations complete.  su->run NULL (a library caller): the iterations and
 * finish only, no records, snapshots or checkpoints.  progress (NULL:
 * none) hears of each iteration's end and of the generator's reports within
 * it, with an estimate of the time left. */
sessile_status sessile_run_loop(const sessile_generator *g, const void *params, const sessile_gen_setup *su,
                                sessile_progress_fn progress, void *user, int *done);

/* The process's resident memory and the machine's physical memory, in
 * bytes (0 when unknown). */
double sessile_process_memory(void);
double sessile_physical_memory(void);

/* The configuration a resume restarts from (sessile_run_config_make plus
 * the flags as booleans, the options as text, the preset), and back
 * (SESSILE_ERR_USAGE when damaged; su's strings then point into cfg). */
cJSON *sessile_gen_config(const sessile_generator *g, const void *params, const sessile_gen_setup *su);
sessile_status sessile_gen_config_read(const sessile_generator *g, const cJSON *cfg, void *params,
                                       sessile_gen_setup *su);

/* Writes the run's file rel (".ply", or ".obj" by its suffix through
 * sessile_run_write_obj) from s with its vertex normals and, in a PLY,
 * nextra named per-vertex values: through sessile_run_write_mesh (a PLY
 * gets its .vtp; the main scalar is the first value, or the height z
 * without any). */
sessile_status sessile_run_write_surface(sessile_run *run, const char *rel, const sessile_surface *s, int nextra,
                                         const char *const *names, const double *const *extra);
/* Writes the run's OBJ rel ("sponge/final.obj") from s with normals (NULL:
 * none) in the run's OBJ style (sessile_run_set_obj_style), with info's
 * header lines (NULL: sessile_run_mesh_info's), and first its material
 * library beside it (rel with ".mtl"), both listed in the manifest; stop as
 * for sessile_write_obj_stop (may be NULL). */
sessile_status sessile_run_write_obj(sessile_run *run, const char *rel, const sessile_surface *s, const double *normals,
                                     const sessile_mesh_info *info, const volatile sig_atomic_t *stop);

/* --- mesh files (run_mesh.c; docs/io.md, "Mesh headers") ----------------- */
/* The iteration whose state the files being written hold (-1: none): the
 * loop sets it around each snapshot and the final outputs. */
void sessile_run_set_iteration(sessile_run *run, int iteration);
/* What the run's mesh files say about themselves: generator, version,
 * commit, the configuration's seed, length unit cm, and the iteration set
 * above as the time (time unit "iteration"); no main scalar. */
void sessile_run_mesh_info(const sessile_run *run, sessile_mesh_info *info);
/* The run's surface file rel (".ply") and the VTK PolyData beside it (rel
 * with ".vtp"), both listed in the run: the parts with their nfields fields
 * and info (NULL: sessile_run_mesh_info's).  With no main scalar named, the
 * first field is it; with no field at all, "height" (z, in the length unit)
 * is added as the main scalar, so that every surface carries colours. */
sessile_status sessile_run_write_mesh(sessile_run *run, const char *rel, int nparts, const sessile_mesh_part *parts,
                                      int nfields, const char *const *names, const sessile_mesh_info *info,
                                      const volatile sig_atomic_t *stop);

#ifdef __cplusplus
}
#endif
#endif
