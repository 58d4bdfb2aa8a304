/* sessile — soft corals by open and closed venation in 3-D (Coralize §3.2,
 * after Runions et al. 2005, docs/venation.md): auxins placed per iteration in
 * a leaf blade bounded by two Bézier curves (or in a 3-D box) attract vein
 * nodes, which grow toward them; the thickness index of each node maps
 * through a thickness curve to radii, and the vein graph becomes a skeleton
 * (sessile/mesh/skeleton.h) meshed as tubes or welded.
 *
 * The O(auxins x nodes) step, the nearest vein node of every auxin, is a GPU
 * kernel over a uniform grid (shaders/coral/nearest.comp) with two plain-C
 * references: brute force and the same grid search on the host. */
#ifndef SESSILE_VENATION_H
#define SESSILE_VENATION_H

#include <stdint.h>
#include "sessile/gpu/gpu.h"
#include "sessile/run/generator.h"
#include "sessile/run/param_table.h"
#include "sessile/run/run.h"

/* Only the struct tag: sessile/growth/grow_params.h names an enum sessile_skeleton too,
 * and the CLI includes both (include sessile/mesh/skeleton.h to use it). */
struct sessile_skeleton;

#ifdef __cplusplus
extern "C" {
#endif

#define SESSILE_VENATION_NONE 0xFFFFFFFFu /* no nearest node */

typedef enum { SESSILE_VENATION_TUBES = 0, SESSILE_VENATION_WELD = 1 } sessile_venation_geometry;
typedef enum { SESSILE_VENATION_GPU = 0, SESSILE_VENATION_HOST = 1 } sessile_venation_search;

typedef struct sessile_venation_params {
  int open;                 /* "Open Ended": 1 open venation, 0 closed */
  int planar;               /* "2D": 1 leaf blade in the x-z plane, 0 a 3-D box */
  int auxins_per_iteration; /* "Auxins per iteration": candidates per iteration */
  double initial_width;     /* "Initial width", cm */
  double width_increment;   /* "Width increment", cm per iteration */
  double aspect;            /* blade (box) height / width */
  double depth_ratio;       /* 3-D box: depth / width */
  double left_1x, left_1z, left_2x, left_2z;     /* "Shape": left curve's inner control points */
  double right_1x, right_1z, right_2x, right_2z; /* ... right curve's (x in widths, z in heights) */
  double kill_radius;       /* "Auxin Kill Radius", cm */
  double birth_distance;    /* Runions' birth distance: dart-throwing radius, cm */
  double vein_step;         /* "Vein Radius": growth in length per iteration, cm */
  double influence_radius;  /* closed: relative-neighbourhood candidates within it, cm */
  double merge_distance;    /* closed: a new node this close to a node joins it (cycle), cm */
  double thickness[4];      /* "Thickness": radius at normalised TI 0, 1/3, 2/3, 1, cm */
  int mesh_detail;          /* "Mesh detail": tube sides */
  int geometry;             /* sessile_venation_geometry */
  double weld_cell;         /* weld grid spacing, cm */
  double weld_blend;        /* weld smooth-union radius, cm */
  int search;               /* sessile_venation_search: who finds nearest nodes */
} sessile_venation_params;

extern const sessile_param_table sessile_venation_param_table;

/* --- the nearest-node search ---------------------------------------------- */
/* A uniform grid of cubic cells over the nodes' bounds; cell_node lists each
 * cell's nodes in ascending index (CSR). */
typedef struct sessile_venation_grid {
  double lo[3], h;
  uint32_t dims[3], ncells, n;
  uint32_t *cell_off; /* ncells + 1 */
  uint32_t *cell_node; /* n */
} sessile_venation_grid;

sessile_status sessile_venation_grid_build(const double *nodes, uint32_t n, sessile_venation_grid *g);
void sessile_venation_grid_free(sessile_venation_grid *g);
/* Brute force: for each of m points the node with the least squared distance
 * (dx*dx + dy*dy + dz*dz, in this order), ties to the lowest index. */
void sessile_venation_nearest_ref(const double *nodes, uint32_t n, const double *pts, uint32_t m,
                                  uint32_t *idx, double *d2);
/* The same answer by the grid: rings of cells outward from the point's cell
 * until no unvisited node can be as close (what the kernel does). */
void sessile_venation_nearest_grid(const sessile_venation_grid *g, const double *nodes, const double *pts,
                                   uint32_t m, uint32_t *idx, double *d2);

/* The GPU search: buffers grow as needed and are kept between calls. */
typedef struct sessile_venation_gpu sessile_venation_gpu;
sessile_status sessile_venation_gpu_create(sessile_gpu *g, sessile_venation_gpu **out);
void sessile_venation_gpu_destroy(sessile_venation_gpu *vg);
/* Uploads nodes, grid and points, runs the kernel, downloads idx/d2 (either
 * may be NULL); *kernel_ns (may be NULL): the dispatch's device time. */
sessile_status sessile_venation_gpu_nearest(sessile_venation_gpu *vg, const sessile_venation_grid *g,
                                            const double *nodes, const double *pts, uint32_t m,
                                            uint32_t *idx, double *d2, double *kernel_ns);
/* Closed venation's relative-neighbourhood test (shaders/coral/rn.comp):
 * total entries, each a candidate node j[k] of an auxin with its squared
 * distance d2[k], the auxin's entries contiguous and sorted by (d2, j),
 * start[k] its auxin's first entry (SESSILE_VENATION_NONE: skipped, for
 * lists longer than SESSILE_VENATION_RN_MAX_CAND); blocked[k] = 1 when an
 * entry before it has a smaller d2 and lies closer to j[k] than d2[k]. */
#define SESSILE_VENATION_RN_MAX_CAND 8000
sessile_status sessile_venation_gpu_rn(sessile_venation_gpu *vg, const double *nodes, uint32_t n,
                                       const uint32_t *j, const double *d2, const uint32_t *start,
                                       uint32_t total, uint32_t *blocked);
/* Passes the last search took (each pass is bounded: docs/venation.md). */
uint64_t sessile_venation_gpu_passes(const sessile_venation_gpu *vg);

/* --- the model --------------------------------------------------------------- */
typedef struct sessile_venation {
  uint32_t n, cap;       /* vein nodes */
  double *pos;           /* 3n, cm; node 0 is the root (seed) at the origin */
  uint32_t *parent;      /* n; the root's is SESSILE_VENATION_NONE */
  uint32_t *ti;          /* n: thickness index (1 + descendants) */
  uint32_t ne, ecap;     /* closed venation's extra edges (cycles) */
  uint32_t *edge;        /* 2 ne: (from, to) */
  uint32_t na, acap;     /* auxins */
  double *aux;           /* 3 na */
  uint64_t rng;          /* the one random stream */
  int iteration;         /* iterations done */
  /* last iteration's figures (records) */
  uint32_t placed, removed, grown, merged;
} sessile_venation;

sessile_status sessile_venation_init(sessile_venation *v, uint64_t seed);
void sessile_venation_free(sessile_venation *v);
/* The blade's width at iteration it (marginal growth). */
double sessile_venation_width(const sessile_venation_params *p, int it);
/* Whether (x, z) lies in the blade of width w (the box when !planar tests x, z only). */
int sessile_venation_in_blade(const sessile_venation_params *p, double w, double x, double z);
/* One iteration: place auxins, find nearest nodes (vg, or the host when
 * NULL), grow, remove auxins. */
sessile_status sessile_venation_step(sessile_venation *v, const sessile_venation_params *p,
                                     sessile_venation_gpu *vg);
/* Radius of a node from its normalised thickness index t in [0, 1]. */
double sessile_venation_radius(const sessile_venation_params *p, double t);
/* The vein graph as a skeleton: one segment per edge, rotation-minimising
 * frames, radii from the thickness curve, value = the TI of the segment's
 * base (its parent end: the root's segments carry the node count). */
sessile_status sessile_venation_skeleton(const sessile_venation *v, const sessile_venation_params *p,
                                         struct sessile_skeleton *sk);

/* --- the generator on the run framework ------------------------------------ */
/* `sessile coral venation` (sessile/run/generator.h): coral/iter_NNNN.ply every
 * K iterations and at the last, coral/final.ply and .obj. */
extern const sessile_generator sessile_gen_coral_venation;

#ifdef __cplusplus
}
#endif
#endif
