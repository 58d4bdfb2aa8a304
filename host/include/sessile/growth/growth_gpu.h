/* sessile — the growth kernels on the GPU (O'Hagan et al. §4.4-4.5): solid
 * node classification, vertex normals, nutrient probing, translocation and
 * growth.  Each kernel has a plain-C reference (sessile/growth/growth_ref.h) that the
 * tests compare it with.
 *
 * Data flow per growth iteration: the host uploads the surface (positions,
 * triangles, adjacency) once; classify writes the solid mask the nutrient
 * solve reads; probe reads the nutrient field; translocate and grow work on
 * per-vertex arrays; the host downloads the new positions for remeshing.
 *
 * Ownership: sessile_growth_gpu owns its kernels and per-surface buffers; the
 * caller owns the box, surface, field vector and mask buffer. */
#ifndef SESSILE_GROWTH_GPU_H
#define SESSILE_GROWTH_GPU_H

#include <stdint.h>
#include "sessile/mesh/box.h"
#include "sessile/la/la.h"
#include "sessile/mesh/surface.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sessile_growth_gpu sessile_growth_gpu;

/* The growth parameters the kernels need (docs/model.md has every source). */
typedef struct sessile_growth_params {
  int probe_flux;          /* 1: the absorbed flux (default), 0: the paper's eq 6 */
  double probe_distance;   /* flux probe: samples at d and 2d along the normal, cm */
  double flux_ref;         /* flux probe: the bare substratum's flux (1/cm), C = flux / this */
  double probe_offset;     /* concentration offset distance, cm (Table 1: 0.1) */
  uint32_t probe_samples;  /* samples along the normal, >= 2 (ours) */
  double t_give;           /* translocation coefficient, [0,1] (ours) */
  int translocate_passes;  /* 0 disables translocation */
  int translocate_sequential; /* 0: each sweep in the parallel form (GPU); 1: the paper's
                               * vertex-by-vertex sweep (host, between probe and grow) */
  double nutrient_threshold; /* Iroquois: grow only where C > this (ours) */
  double growth_threshold; /* grow only where g(C) > this, cm (Table 1: 0) */
  double growth_rate;      /* Gr (Table 1: 5) */
  double l_max;            /* Lmax, cm (ours) */
  double kinetic_order;    /* n (Table 1: 1.4) */
  double growth_constant;  /* K (Table 1: 1) */
  double max_growth;       /* maxgrowth, cm (ours) */
  int halichondrid;        /* 0: radiate accretive (N), 1: Halichondrid (normalize(N + r)) */
  double normal_offset_radius; /* R: r uniform in [-R, R]^3 (Table 1: 0.02) */
  double ceiling;          /* grown vertices stay at or below this z (cm; the far-field plane), 0: the box top */
} sessile_growth_params;

sessile_status sessile_growth_gpu_create(sessile_la *la, sessile_growth_gpu **out);
void sessile_growth_gpu_destroy(sessile_growth_gpu *g);

/* Uploads the surface (positions, triangles, vertex->face and vertex
 * adjacency); call after every remesh. */
sessile_status sessile_growth_gpu_set_surface(sessile_growth_gpu *g, const sessile_surface *s);

/* Marks box nodes inside the closed surface: solid[i] = 1 inside, 0 outside
 * (robust ray parity along +z, see docs/growth.md). solid: device buffer of
 * sessile_box_nodes(box) uint32. */
sessile_status sessile_growth_gpu_classify(sessile_growth_gpu *g, const sessile_box *box,
                                           sessile_buffer *solid);

/* The same mask, and the cut fractions of the surface on the box's grid
 * lines along x, y and z (theta: 6 reals per node, laid out as in
 * sessile_growth_ref_cut, whose values it reproduces exactly).  The
 * nutrient's cut-cell boundary (docs/nutrient.md) reads both. */
sessile_status sessile_growth_gpu_cut(sessile_growth_gpu *g, const sessile_box *box,
                                      sessile_buffer *solid, sessile_buffer *theta);

/* Area-weighted vertex normals of the uploaded surface (3 nv doubles out). */
sessile_status sessile_growth_gpu_normals(sessile_growth_gpu *g, double *normals);

/* One growth step on the uploaded surface: normals, probe c along them (eq
 * 6), translocation (eqs 7-8, order-independent form; the paper's sequential
 * one on the host where p->translocate_sequential), Iroquois and growth
 * thresholds, growth (eqs 9-10) with radiate or Halichondrid normals (eqs 1-2,
 * random vectors from `seed` and `iteration`), displacement clamped into the
 * box.  Writes the new positions (3 nv) and, when not NULL, the per-vertex
 * probed nutrient, translocated nutrient and growth length (nv each). */
sessile_status sessile_growth_gpu_step(sessile_growth_gpu *g, const sessile_box *box,
                                       const sessile_vec *c, const sessile_growth_params *p,
                                       uint64_t seed, uint32_t iteration, double *new_pos,
                                       double *probed, double *translocated, double *length);

/* The growth directions of the last step (3 nv: N, or normalize(N + r) for
 * Halichondrid), e.g. to check the random vectors against the reference. */
sessile_status sessile_growth_gpu_directions(sessile_growth_gpu *g, double *dir);

/* Seconds of host work plus GPU run of the last classify call (binning
 * included), for benchmarks. */
double sessile_growth_gpu_classify_seconds(const sessile_growth_gpu *g);

#ifdef __cplusplus
}
#endif
#endif
