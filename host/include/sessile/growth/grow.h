/* sessile — the accretive sponge growth loop (O'Hagan et al., Figure 2):
 * per iteration, classify the box nodes inside the sponge, solve the
 * nutrient field, probe it along the vertex normals, translocate, grow, and
 * remesh; snapshots and the manifest go to a run directory.
 *
 * Ownership: the caller owns the GPU context and the parameters. */
#ifndef SESSILE_GROW_H
#define SESSILE_GROW_H

#include <stdint.h>
#include "sessile/run/generator.h"
#include "sessile/gpu/gpu.h"
#include "sessile/growth/grow_params.h"
#include "sessile/run/run.h"
#include "sessile/mesh/surface.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Stages timed per iteration (also the names in the manifest and bench). */
#define SESSILE_GROW_STAGES(X) \
  X(upload) X(classify) X(fluid) X(nutrient) X(growth) X(remesh) X(output)
typedef enum {
#define X(n) SESSILE_STAGE_##n,
  SESSILE_GROW_STAGES(X)
#undef X
  SESSILE_STAGE_COUNT
} sessile_grow_stage;
const char *sessile_grow_stage_name(int stage);


typedef struct sessile_grow_options {
  /* The run directory (sessile/run/run.h), opened by the caller; NULL writes
   * nothing (benchmarks).  When it holds a checkpoint (resume), the loop
   * continues from it. */
  sessile_run *run;
  const char *preset;   /* recorded in the manifest */
  int iterations;       /* growth iterations (default 50) */
  uint64_t seed;        /* every random choice flows from it */
  int every;            /* snapshot interval K: sponge/slices/fields every K iterations and at
                           the last one (0: the last only); each snapshot is a checkpoint */
  const char *slices;   /* planes: "x,y,z" through the sponge centre, or "z=3.5,x=19.2" */
  int fields;           /* write fields/iter_NNNN.vtu at snapshots (default 1) */
  int check_every_iteration; /* run the surface invariant check after every remesh (default 1) */
  /* The starting surface (copied; clamped into the box), or NULL for the
   * icosphere the parameters describe. */
  const sessile_surface *initial;
  /* Progress and warnings, one line each, no newline (NULL: silent).  The
   * library prints nothing itself. */
  void (*monitor)(void *user, sessile_monitor_kind kind, const char *line);
  void *monitor_user;
} sessile_grow_options;
void sessile_grow_options_default(sessile_grow_options *o);

/* Per-run totals (for `sessile bench grow` and callers). */
typedef struct sessile_grow_summary {
  int iterations;
  double stage_seconds[SESSILE_STAGE_COUNT];
  double total_seconds;
  uint32_t box_nodes, final_vertices, final_triangles;
  long solver_iterations;
  double worst_relres;
} sessile_grow_summary;

/* Every check of parameters and options that needs no device (the
 * parameter table's, the --slices spec): a run that passes it starts. */
sessile_status sessile_grow_check_options(const sessile_grow_params *p, const sessile_grow_options *o);

/* Refuses (SESSILE_ERR_USAGE, with the estimate) parameters whose
 * device-memory estimate exceeds the device's largest device-local heap. */
sessile_status sessile_grow_check_device(const sessile_gpu *g, const sessile_grow_params *p);

/* `sessile grow` as a generator (host/growth/grow_gen.c): presets, --slices,
 * --no-fields; the command line is the CLI's generic one. */
extern const sessile_generator sessile_gen_grow;

/* Runs the growth loop (sessile_run_loop over sessile_gen_grow) with the
 * options o: what a library caller (a benchmark, a test) needs beyond the
 * command's.  The final surface is returned in final (may be
 * NULL).  Errors: SESSILE_ERR_USAGE for bad parameters (nothing written
 * then), SESSILE_ERR_TOO_LARGE when the box would not fit the device,
 * SESSILE_ERR_IO, SESSILE_ERR_NUMERIC for a solve that broke down,
 * SESSILE_ERR_INTERRUPTED when the run's stop flag was raised (the state
 * after the last whole iteration is checkpointed); files already written
 * stay whole.  The caller closes the run (sessile_run_close). */
sessile_status sessile_grow_run(sessile_gpu *g, const sessile_grow_params *p,
                                const sessile_grow_options *o, sessile_surface *final,
                                sessile_grow_summary *summary);

#ifdef __cplusplus
}
#endif
#endif
