/* The particle sponge's parameter table (docs/sponge_particles.md): the
 * paper's name for each as its source (Liapis et al., Coralize §3.3), or
 * "ours" where Coralize leaves the choice open. */
#include <math.h>
#include "sessile/sponge/particles.h"

#define F(x) offsetof(sessile_sponge_particles_params, x)
static const char *const collider_names[] = {"gpu", "host", NULL};

static const sessile_param_desc descs[] = {
    {"mesh_detail", SESSILE_PT_INT, F(mesh_detail), 4, 2, 6, 0, "", "Mesh detail",
     "the starting hemisphere's detail: an icosphere level whose lower half is flattened into the base (3: 162 vertices, 4: 642, 5: 2562)", NULL},
    {"radius", SESSILE_PT_REAL, F(radius), 1, 0, 100, SESSILE_PARAM_LO_OPEN, "cm", "ours",
     "radius of the starting hemisphere, centred on the cube's floor", NULL},
    {"cube_size", SESSILE_PT_REAL, F(cube_size), 4, 0, 1000, SESSILE_PARAM_LO_OPEN, "cm",
     "ours (the paper's bounding cube)", "edge of the cube [-L/2, L/2]^2 x [0, L] that bounds the sponge and the particles", NULL},
    {"nutrients_per_iteration", SESSILE_PT_INT, F(nutrients_per_iteration), 200, 1, 1000000, 0, "",
     "Nutrients per iteration", "particles spawned uniformly on the cube's top face each iteration", NULL},
    {"nutrient_radius", SESSILE_PT_REAL, F(nutrient_radius), 0.08, 0, 100, SESSILE_PARAM_LO_OPEN, "cm",
     "Nutrient radius", "radius of each particle (a sphere; it touches a vertex within this distance)", NULL},
    {"nutrient_lifetime", SESSILE_PT_INT, F(nutrient_lifetime), 26, 1, 100000, 0, "iterations",
     "Nutrient lifetime", "iterations a particle lives (it dies sooner when it feeds or leaves the cube)", NULL},
    {"particle_feed", SESSILE_PT_INT, F(particle_feed), 2, 1, SESSILE_SPONGE_PARTICLES_MAX_FEED, 0, "",
     "Particle feed", "most vertices one particle feeds (those it touches, lowest indices first) before it dies", NULL},
    {"fall_speed", SESSILE_PT_REAL, F(fall_speed), 0.12, 0, 100, SESSILE_PARAM_LO_OPEN, "cm/iteration",
     "ours (the paper: particles move downwards)", "distance a particle falls per iteration", NULL},
    {"current_x", SESSILE_PT_REAL, F(current_x), 0, -100, 100, 0, "cm/iteration", "ours",
     "drift added to every particle's step (a current), x", NULL},
    {"current_y", SESSILE_PT_REAL, F(current_y), 0, -100, 100, 0, "cm/iteration", "ours",
     "drift, y", NULL},
    {"current_z", SESSILE_PT_REAL, F(current_z), 0, -100, 100, 0, "cm/iteration", "ours",
     "drift, z (added to -fall_speed)", NULL},
    {"growth_fraction", SESSILE_PT_REAL, F(growth_fraction), 0.15, 0, 2, 0, "",
     "ours (the paper: a fraction of its edge length)",
     "a fed vertex moves along its normal by this times its mean edge length", NULL},
    {"feeding_iterations", SESSILE_PT_INT, F(feeding_iterations), 3, 0, 8, 0, "rings", "Feeding iterations",
     "rings of neighbours of a fed vertex that grow too (by the Gaussian falloff)", NULL},
    {"falloff_sigma", SESSILE_PT_REAL, F(falloff_sigma), 0.25, 0, 100, SESSILE_PARAM_LO_OPEN, "cm",
     "ours (the paper: a normal function of the distance)",
     "standard deviation of the Gaussian falloff over the Euclidean distance to the fed vertex", NULL},
    {"splitting_threshold", SESSILE_PT_REAL, F(splitting_threshold), 0.2, 0, 100, SESSILE_PARAM_LO_OPEN,
     "cm", "Splitting threshold", "edges longer than this are split", NULL},
    {"collapse_threshold", SESSILE_PT_REAL, F(collapse_threshold), 0.08, 0, 100, SESSILE_PARAM_LO_OPEN,
     "cm", "Collapse threshold", "edges shorter than this are collapsed (guarded: docs/remesh.md)", NULL},
    {"max_vertices", SESSILE_PT_INT, F(max_vertices), 200000, 100, 20000000, 0, "", "ours",
     "the run stops with an error when the surface grows past this many vertices", NULL},
    {"collider", SESSILE_PT_ENUM, F(collider), 0, 0, 1, 0, "", "ours",
     "collision search: gpu (the kernel) or host (its plain-C twin); same hits", collider_names},
};

/* Bytes a storage buffer may hold on the smallest devices we run on
 * (lavapipe's maxStorageBufferRange). */
#define BUFFER_RANGE (128.0 * 1024 * 1024)

static sessile_status validate(const void *values) {
  const sessile_sponge_particles_params *p = values;
  SESSILE_CHECK(p->cube_size > 2 * p->radius, SESSILE_ERR_USAGE,
                "cube_size %g cm must exceed the hemisphere's diameter 2 radius = %g cm",
                p->cube_size, 2 * p->radius);
  SESSILE_CHECK(p->collapse_threshold < p->splitting_threshold, SESSILE_ERR_USAGE,
                "collapse_threshold %g cm must be below splitting_threshold %g cm",
                p->collapse_threshold, p->splitting_threshold);
  SESSILE_CHECK(p->nutrient_radius < p->cube_size / 2, SESSILE_ERR_USAGE,
                "nutrient_radius %g cm must be below half the cube (%g cm)", p->nutrient_radius,
                p->cube_size / 2);
  /* a step longer than the particle's diameter could pass a vertex untouched */
  double vz = p->current_z - p->fall_speed;
  double step = sqrt(p->current_x * p->current_x + p->current_y * p->current_y + vz * vz);
  SESSILE_CHECK(step <= 2 * p->nutrient_radius, SESSILE_ERR_USAGE,
                "a particle's step (fall_speed and current) is %g cm, more than its diameter "
                "2 nutrient_radius = %g cm: it could pass vertices untouched; lower the speeds or "
                "raise nutrient_radius", step, 2 * p->nutrient_radius);
  SESSILE_CHECK(vz < 0, SESSILE_ERR_USAGE,
                "current_z %g must be below fall_speed %g: the particles must fall", p->current_z,
                p->fall_speed);
  /* the most particles alive at once, and what they need */
  double np = (double)p->nutrients_per_iteration * (p->nutrient_lifetime + 1.0);
  double hit_bytes = np * p->particle_feed * 4, part_bytes = np * 16;
  SESSILE_CHECK(hit_bytes <= BUFFER_RANGE && part_bytes <= BUFFER_RANGE, SESSILE_ERR_USAGE,
                "up to %.0f particles alive (nutrients_per_iteration x (nutrient_lifetime + 1)) "
                "need %.0f MiB of hits and %.0f MiB of positions on the device, more than a storage "
                "buffer's 128 MiB; lower nutrients_per_iteration, nutrient_lifetime or particle_feed",
                np, hit_bytes / 1048576, part_bytes / 1048576);
  return SESSILE_OK;
}

const sessile_param_table sessile_sponge_particles_param_table = {
    "sponge particles", sizeof(sessile_sponge_particles_params), (int)(sizeof descs / sizeof descs[0]), descs,
    validate, NULL, NULL};
