/* The options every generator's command shares (--config, --set,
 * --print-config, --seed, --iterations, --every, --out, --force, --resume,
 * --quiet, --progress) and the run directory's life around the generator: open (lock,
 * replace or resume), close, and the exit code (130/143 when interrupted). */
#ifndef SESSILE_CLI_RUN_H
#define SESSILE_CLI_RUN_H
#include "cli.h"
#include "sessile/run/run.h"

typedef struct cli_run_args {
  const char *out, *resume;
  const char **configs, **sets; /* argc entries each */
  int nconfigs, nsets;
  int print_config, force, quiet;
  int no_preview;               /* --no-preview: no preview.png at the end */
  int glb;                      /* --glb: the final mesh as .glb too (cli_glb.c) */
  sessile_obj_axes obj_axes;    /* --obj-axes zup-cm|yup-m: how OBJ files are written */
  int progress;                 /* --progress MODE (cli_progress.h; 0: not given) */
  int have_iterations;          /* --iterations given */
  int have_run_option;          /* an option a resume must not change */
  unsigned long long seed;
  int iterations, every;
} cli_run_args;

/* Allocates the lists for argc arguments; defaults for seed etc. */
int cli_run_args_init(cli_run_args *a, int argc, unsigned long long seed, int iterations, int every);
void cli_run_args_free(cli_run_args *a);
/* Consumes a shared option at argv[*i]: 1 consumed, 0 not one, -1 usage error. */
int cli_run_option(const char *cmd, int argc, char **argv, int *i, cli_run_args *a);
/* After parsing: --resume excludes every run option; -1 to go on, else an exit code. */
int cli_run_args_check(const char *cmd, const cli_run_args *a);
/* The configs in order, then the --sets, into values (after defaults/preset). */
sessile_status cli_run_apply_params(const sessile_param_table *t, void *values, const cli_run_args *a);
/* Admits the run directory (new, --force or --resume) with the stop flag:
 * reads, writes nothing (sessile_run_admit); sessile_run_start takes it. */
sessile_status cli_run_admit(const char *generator, int argc, char **argv, const cli_run_args *a,
                             const char *dir, volatile sig_atomic_t *stop, sessile_run **run);
/* Opens the run directory (new, --force or --resume) with the stop flag. */
sessile_status cli_run_open(const char *generator, int argc, char **argv, const cli_run_args *a,
                            const char *dir, volatile sig_atomic_t *stop, sessile_run **run);
/* The manifest's "device": name, type, driver and the precision of its
 * kernels (precision_bits, 64 or 32: the same seed gives the same bytes only
 * on the same device and precision).  Nothing when g is NULL. */
void cli_run_note_device(sessile_run *run, sessile_gpu *g);
/* At the end of a completed run (before sessile_run_close), unless
 * --no-preview: preview.png in the run directory, the mesh mesh_rel (e.g.
 * "sponge/final.ply") from the oblique view (docs/render.md "Preview"), on
 * g, or on a device made from go (NULL: the default) when g is NULL.  A
 * device that cannot draw, or any failure of the picture, is one warning
 * on stderr: the run still succeeds, without preview.png. */
void cli_run_preview(const char *cmd, const cli_run_args *a, sessile_run *run, const char *mesh_rel,
                     sessile_gpu *g, const cli_gpu_opts *go);
/* At the end of a completed run, with --glb: the mesh mesh_rel (a PLY,
 * "sponge/final.ply") as glTF 2.0 binary beside it ("sponge/final.glb"),
 * with the command's material colour (docs/io.md "glTF").  A failure fails
 * the run: the user asked for the file. */
sessile_status cli_run_glb(const char *cmd, const cli_run_args *a, sessile_run *run, const char *mesh_rel);
/* The run's OBJ style: --obj-axes and the command's material colour (the
 * --glb one), for the .mtl beside each OBJ (docs/io.md "OBJ conventions"). */
void cli_run_obj_style(const char *cmd, const cli_run_args *a, sessile_run *run);
/* The exit code after sessile_run_close returned s. */
int cli_run_exit(const char *cmd, sessile_status s, const char *dir, const volatile sig_atomic_t *stop,
                 int iterations_done);
#endif
