/* `sessile reef` (cli_reef.c) and the organisms of its pool
 * (cli_reef_organisms.c): the CLI is the one layer that knows both the reef
 * and every generator (docs/reef.md, "Organisms"). */
#ifndef SESSILE_CLI_REEF_H
#define SESSILE_CLI_REEF_H
#include "cli.h"
#include "sessile/reef/reef.h"
#include "sessile/run/generator.h"

typedef struct cli_reef_organisms {
  sessile_gpu *gpu;   /* for generators that need a device (NULL: refused) */
  const sessile_run *run; /* the reef's run: a stop request ends the organisms (NULL: never) */
  const char *where;  /* the scene file, in messages */
  uint32_t made;      /* organisms generated so far */
} cli_reef_organisms;

/* Refuses a pool entry whose generator is unknown (or cannot be one), whose
 * arguments or parameters its generator refuses, or that needs a device
 * where the reef has none (device 0), naming the JSON path. */
sessile_status cli_reef_check_entry(const char *where, int k, const sessile_reef_entry *e, int device);
/* sessile_reef_organism_fn over the registered generators (ctx: a
 * cli_reef_organisms). */
sessile_status cli_reef_organism(void *ctx, const sessile_reef_entry *e, uint64_t seed, double exposure,
                                 sessile_surface *out, sessile_reef_scalars *scalars);
/* Writes j (then deleted; NULL: out of memory) as the run's file rel, atomically. */
sessile_status cli_reef_write_json(sessile_run *run, const char *rel, cJSON *j);
/* reef/meshes.ply and reef/scene.json: the preview's instanced scene
 * (cli_reef_preview.c). */
sessile_status cli_reef_preview_scene(sessile_run *run, const sessile_reef_gltf *g);
/* Removes a temporary folder and everything in it (the organisms' runs,
 * bench reef's files). */
void cli_reef_remove_tree(const char *dir);
/* `sessile bench reef` (cmd_bench_reef.c). */
int cmd_bench_reef(int argc, char **argv, const cli_gpu_opts *global);
#endif
