/* sessile — `sessile sphere`, the smallest generator: an icosphere whose
 * vertices take a seeded radial random walk, written through the run
 * framework (parameter table, run directory, manifest, records, lock,
 * checkpoint and resume).  It exists to show what a generator needs from
 * the framework and nothing more, and it is the framework's own test. */
#ifndef SESSILE_SPHERE_H
#define SESSILE_SPHERE_H

#include <stdint.h>
#include "sessile/param_table.h"
#include "sessile/run.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sessile_sphere_params {
  int level;        /* icosphere level (1 = icosahedron) */
  double radius;    /* cm */
  double noise;     /* relative radial step per iteration */
} sessile_sphere_params;

extern const sessile_param_table sessile_sphere_param_table;

typedef struct sessile_sphere_options {
  sessile_run *run; /* required */
  uint64_t seed;
  int iterations, every; /* snapshots every K iterations and at the last */
} sessile_sphere_options;

/* The configuration a resume restarts from, and back. */
cJSON *sessile_sphere_config(const sessile_sphere_params *p, const sessile_sphere_options *o);
sessile_status sessile_sphere_config_read(const cJSON *cfg, sessile_sphere_params *p, sessile_sphere_options *o);

/* Runs it: sphere/iter_NNNN.ply at snapshots, sphere/final.ply; SESSILE_ERR_INTERRUPTED
 * when the run's stop flag was raised (state checkpointed).  *done: iterations done. */
sessile_status sessile_sphere_run(const sessile_sphere_params *p, const sessile_sphere_options *o, int *done);

#ifdef __cplusplus
}
#endif
#endif
