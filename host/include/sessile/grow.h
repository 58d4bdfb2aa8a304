/* sessile — the accretive sponge growth loop (O'Hagan et al., Figure 2):
 * per iteration, classify the box nodes inside the sponge, solve the
 * nutrient field, probe it along the vertex normals, translocate, grow, and
 * remesh; snapshots and the manifest go to a run directory.
 *
 * Ownership: the caller owns the GPU context and the parameters. */
#ifndef SESSILE_GROW_H
#define SESSILE_GROW_H

#include <stdint.h>
#include "sessile/gpu.h"
#include "sessile/params.h"
#include "sessile/surface.h"

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
  const char *out_dir;  /* run directory; NULL writes nothing (benchmarks) */
  const char *preset;   /* recorded in the manifest */
  int iterations;       /* growth iterations (default 50) */
  uint64_t seed;        /* every random choice flows from it */
  int every;            /* snapshot interval K: sponge/slices/fields every K iterations (0: final only) */
  const char *slices;   /* planes: "x,y,z" through the sponge centre, or "z=3.5,x=19.2" */
  int fields;           /* write fields/iter_NNNN.vtu at snapshots (default 1) */
  int quiet;            /* no progress output */
  int check_every_iteration; /* run the surface invariant check after every remesh (default 1) */
  /* The starting surface (copied; clamped into the box), or NULL for the
   * icosphere the parameters describe. */
  const sessile_surface *initial;
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

/* Runs the growth loop.  The final surface is returned in final (may be
 * NULL).  Errors: SESSILE_ERR_USAGE for bad parameters or an unwritable
 * output folder (nothing written then), SESSILE_ERR_IO, SESSILE_ERR_NUMERIC
 * for a solve that broke down; files already written stay whole. */
sessile_status sessile_grow_run(sessile_gpu *g, const sessile_params *p,
                                const sessile_grow_options *o, sessile_surface *final,
                                sessile_grow_summary *summary);

#ifdef __cplusplus
}
#endif
#endif
