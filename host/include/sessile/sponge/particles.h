/* sessile — Coralize's particle-fed sponge (Liapis et al., §3.3;
 * docs/sponge_particles.md): a closed hemisphere on the substratum inside a
 * cube, fed by nutrient particles that fall from the cube's top face; a
 * vertex a particle touches grows along its normal, its neighbours by a
 * Gaussian falloff, then the surface is remeshed under the contact guards.
 *
 * The collision search (every particle against the vertices within its
 * radius) is a GPU kernel over a uniform grid (shaders/sponge/collide.comp),
 * with two host references: brute force and the same grid.  All three return
 * the same hits, bit for bit: the distance test is done in float, operation
 * by operation the same on host and device. */
#ifndef SESSILE_SPONGE_PARTICLES_H
#define SESSILE_SPONGE_PARTICLES_H

#include <stdint.h>
#include "sessile/gpu/gpu.h"
#include "sessile/run/param_table.h"
#include "sessile/run/generator.h"
#include "sessile/run/run.h"
#include "sessile/mesh/surface.h"

#ifdef __cplusplus
extern "C" {
#endif

/* --- collisions ----------------------------------------------------------- */
/* The most vertices one particle may feed ("Particle feed"). */
#define SESSILE_SPONGE_PARTICLES_MAX_FEED 16
#define SESSILE_SPONGE_PARTICLES_NO_HIT 0xFFFFFFFFu
/* A particle's cell range is widened by this fraction of a cell on each side:
 * the device computes cell coordinates in float, and the range must hold
 * every cell a true hit can lie in (the exact test decides). */
#define SESSILE_SPONGE_PARTICLES_CELL_MARGIN 0.05f

/* The vertices binned in a uniform grid: cell (i, j, k) holds
 * cell_vtx[cell_off[c] .. cell_off[c+1]), c = i + d[0] (j + d[1] k), in
 * ascending vertex index.  Positions are kept as float (x, y, z, 0). */
typedef struct sessile_sponge_particles_grid {
  uint32_t nv, d[3];
  float lo[3], inv_h, h;
  float *pos4;       /* 4 nv */
  uint32_t *cell_off; /* d0 d1 d2 + 1 */
  uint32_t *cell_vtx; /* nv */
} sessile_sponge_particles_grid;

/* Bins the nv vertices (3 nv doubles) in cells of side >= 2 radius (a
 * particle's ball meets at most 2 cells per axis); the cell count is capped
 * near 8 nv + 64 by growing the cells. */
sessile_status sessile_sponge_particles_grid_build(const double *pos, uint32_t nv, double radius,
                                          sessile_sponge_particles_grid *g);
void sessile_sponge_particles_grid_free(sessile_sponge_particles_grid *g);

/* The hits of np particles (centres pos4: 4 np floats, x y z and unused):
 * for particle i, hit[feed i .. feed i + feed) the `feed` smallest vertex
 * indices v with |p_i - x_v|^2 <= r^2 (float, in that order:
 * dx*dx + dy*dy, + dz*dz; r2 = (float)r * (float)r), ascending, padded with
 * SESSILE_SPONGE_PARTICLES_NO_HIT; count[i] the number of all such v (not capped). */
sessile_status sessile_sponge_particles_collide_brute(const float *part4, uint32_t np, const float *vtx4,
                                             uint32_t nv, float radius, uint32_t feed,
                                             uint32_t *hit, uint32_t *count);
/* The same through the grid (the host twin of the kernel). */
sessile_status sessile_sponge_particles_collide_grid(const sessile_sponge_particles_grid *g, const float *part4,
                                            uint32_t np, float radius, uint32_t feed,
                                            uint32_t *hit, uint32_t *count);

/* The GPU collider: buffers grow as needed and are kept between calls. */
typedef struct sessile_sponge_particles_gpu sessile_sponge_particles_gpu;
sessile_status sessile_sponge_particles_gpu_create(sessile_gpu *gpu, sessile_sponge_particles_gpu **out);
void sessile_sponge_particles_gpu_destroy(sessile_sponge_particles_gpu *c);
/* Uploads the grid and the particles, runs the kernel, downloads hit and
 * count.  *kernel_ns (NULL: not wanted): the kernel's GPU time. */
sessile_status sessile_sponge_particles_gpu_collide(sessile_sponge_particles_gpu *c, const sessile_sponge_particles_grid *g,
                                           const float *part4, uint32_t np, float radius,
                                           uint32_t feed, uint32_t *hit, uint32_t *count,
                                           double *kernel_ns);

/* --- the generator ----------------------------------------------------------- */
typedef enum sessile_sponge_particles_collider {
  SESSILE_SPONGE_PARTICLES_COLLIDE_GPU = 0,
  SESSILE_SPONGE_PARTICLES_COLLIDE_HOST = 1
} sessile_sponge_particles_collider;

typedef struct sessile_sponge_particles_params {
  int mesh_detail;             /* icosphere level of the starting hemisphere */
  double radius;               /* cm, the hemisphere */
  double cube_size;            /* cm, the cube's edge */
  int nutrients_per_iteration;
  double nutrient_radius;      /* cm */
  int nutrient_lifetime;       /* iterations */
  int particle_feed;           /* vertices one nutrient feeds before it dies */
  double fall_speed;           /* cm per iteration */
  double current_x, current_y, current_z; /* cm per iteration, drift */
  double growth_fraction;      /* of the hit vertex's mean edge length */
  int feeding_iterations;      /* rings of neighbours that grow too */
  double falloff_sigma;        /* cm, the Gaussian's standard deviation */
  double splitting_threshold;  /* cm */
  double collapse_threshold;   /* cm */
  int max_vertices;
  int collider;                /* sessile_sponge_particles_collider */
} sessile_sponge_particles_params;

extern const sessile_param_table sessile_sponge_particles_param_table;

/* One iteration's figures. */
typedef struct sessile_sponge_particles_iter_stats {
  uint32_t spawned, alive, hits, fed_vertices, died_fed, died_age, died_outside;
  uint32_t nv, nf, held_back;
  uint32_t remesh_refused; /* 1: the remesh crossed the surface and was dropped */
  double collide_s, grow_s, remesh_s;
} sessile_sponge_particles_iter_stats;

/* The simulation state (surface, particles, counts, random stream). */
typedef struct sessile_sponge_particles sessile_sponge_particles;
/* gpu: needed when p->collider is GPU (NULL otherwise). */
sessile_status sessile_sponge_particles_create(const sessile_sponge_particles_params *p, uint64_t seed,
                                      sessile_gpu *gpu, sessile_sponge_particles **out);
void sessile_sponge_particles_destroy(sessile_sponge_particles *ps);
sessile_status sessile_sponge_particles_step(sessile_sponge_particles *ps, sessile_sponge_particles_iter_stats *st);
const sessile_surface *sessile_sponge_particles_surface(const sessile_sponge_particles *ps);
/* How many times each vertex was fed (nv entries; inherited through remeshing). */
const uint32_t *sessile_sponge_particles_counts(const sessile_sponge_particles *ps);
uint32_t sessile_sponge_particles_particles(const sessile_sponge_particles *ps);
int sessile_sponge_particles_iteration(const sessile_sponge_particles *ps);

/* The checkpoint's sections back into ps (what the generator wrote). */
sessile_status sessile_sponge_particles_restore(sessile_sponge_particles *ps, const sessile_ckpt *ck);

/* `sessile sponge particles` (sessile/run/generator.h): sponge/iter_NNNN.ply
 * every K iterations and at the last, sponge/final.ply and final.obj. */
extern const sessile_generator sessile_gen_sponge_particles;

#ifdef __cplusplus
}
#endif
#endif
