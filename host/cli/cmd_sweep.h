/* `sessile sweep`: a study of many runs of one generator (docs/sweep.md).
 * cmd_sweep_spec.c reads and expands the sweep file (pure logic: no files
 * written), cmd_sweep.c plans the sweep folder and dispatches,
 * cmd_sweep_run.c runs points as child processes (local engine and Slurm
 * array tasks), cmd_sweep_slurm.c submits and asks Slurm, cmd_sweep_gather.c
 * tabulates the manifests. */
#ifndef SESSILE_CMD_SWEEP_H
#define SESSILE_CMD_SWEEP_H
#include <cjson/cJSON.h>
#include "cli.h"

enum { SWEEP_MAX_AXES = 16, SWEEP_MAX_POINTS = 100000, SWEEP_MAX_ARGS = 128 };

typedef struct sweep_axis {
  const char *param;
  int n;
  char **values; /* as --set spells them */
} sweep_axis;

/* A parsed, validated sweep file. */
typedef struct sweep_spec {
  cJSON *root;             /* the file as given (the strings below point into it) */
  const char *generator;   /* "sphere", "coral venation", "sds run rock" */
  int nwords;              /* the generator's command words (MODEL included) */
  const char *options[SWEEP_MAX_ARGS];
  int noptions;
  int iterations;          /* -1: the generator's default */
  int default_iterations;  /* the generator's (-1 when it has none) */
  const char *base_keys[64];
  char *base_values[64];
  int nbase;
  sweep_axis axes[SWEEP_MAX_AXES];
  int naxes, zip;
  unsigned long long *seeds;
  int nseeds;
  const char *metrics[64];
  int nmetrics;
  long ncombos, npoints;
} sweep_spec;

/* Reads and checks SWEEP.json whole: the generator and every point against
 * its parameter table.  EXIT_OK, or EXIT_USAGE after one line on stderr. */
int sweep_spec_load(const char *path, sweep_spec *s);
void sweep_spec_free(sweep_spec *s);
/* The axis values of combination c: idx[a] indexes axes[a].values. */
void sweep_combo(const sweep_spec *s, long c, int idx[SWEEP_MAX_AXES]);

/* "sessile CMD: error: out of host memory"; EXIT_RUNTIME. */
int sweep_oom(const char *cmd);
/* v as the shortest text that reads back to the same double (buf). */
const char *sweep_number(double v, char buf[40]);

/* DIR/sweep.json, parsed and checked (what the subcommands read of it);
 * NULL after one line on stderr (the caller exits 2). */
cJSON *sweep_load_plan(const char *dir);
/* The points' folder name width (4 digits, more past 10000 points). */
int sweep_width(int npoints);

/* A point's state from its run directory (runs/NNNN under dir) and the
 * engine's record of its last exit (state/NNNN.json). */
typedef enum { PT_PENDING, PT_RUNNING, PT_COMPLETED, PT_FAILED, PT_INTERRUPTED } sweep_state;
extern const char *const sweep_state_names[];
sweep_state sweep_point_state(const char *dir, int index, int width, char *error, size_t n);
/* Its manifest (NULL when none or unreadable). */
cJSON *sweep_point_manifest(const char *dir, int index, int width);
/* A whole small file into a NUL-terminated buffer (free it); NULL if none. */
char *sweep_read_text(const char *path, size_t max);

int sweep_cmd_run(int argc, char **argv);
int sweep_cmd_task(int argc, char **argv);
int sweep_cmd_status(int argc, char **argv);
int sweep_cmd_submit(int argc, char **argv);
int sweep_cmd_gather(int argc, char **argv);
/* Slurm's states of the points (squeue, then sacct) for the last recorded
 * job: out[i] a state word or "" ; 0 when there is no job, -1 when Slurm's
 * tools did not answer. */
int sweep_slurm_states(const char *dir, int npoints, char (*out)[24], char *job, size_t njob);

/* gather's pictures: gather/plots/METRIC-vs-AXIS.png from stat (combinations
 * x metrics x {n, mean, sd, ci95_lo, ci95_hi}) and gather/sheet.png from the
 * completed points' previews (completed[i]: point i completed). */
int sweep_gather_pictures(const char *dir, const cJSON *plan, const double *stat, const unsigned char *completed);

int cmd_sweep(int argc, char **argv, const cli_gpu_opts *global);
#endif
