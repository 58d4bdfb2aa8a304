/* sessile — `sessile sphere`, the smallest generator: an icosphere whose
 * vertices take a seeded radial random walk.  It is a parameter table and a
 * sessile_generator (sessile/run/generator.h): what a generator needs from the
 * framework and nothing more, and the framework's own test. */
#ifndef SESSILE_SPHERE_H
#define SESSILE_SPHERE_H

#include "sessile/run/generator.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sessile_sphere_params {
  int level;        /* icosphere level (1 = icosahedron) */
  double radius;    /* cm */
  double noise;     /* relative radial step per iteration */
} sessile_sphere_params;

extern const sessile_param_table sessile_sphere_param_table;
extern const sessile_generator sessile_gen_sphere;

#ifdef __cplusplus
}
#endif
#endif
