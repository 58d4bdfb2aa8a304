/* sessile — point location in an unstructured tet mesh (the conforming
 * water mesh): a uniform grid of bins over the mesh's bounding box, each bin
 * listing the tets whose bounding box overlaps it, built on the host; a host
 * query and a GPU kernel (shaders/mesh/locate.comp) that runs the same scan
 * and interpolates a nodal (P1) field, for the growth probe (eq 6) on the
 * conforming mesh.
 *
 * A point is in tet t when all four barycentric weights are >= -eps
 * (eps = 1e-10 in fp64, 1e-5 in fp32 on the GPU); the bin's tets are tried in
 * ascending index and the first hit is returned, so host and GPU agree.
 * Points in no tet (inside the sponge, outside the box) are "outside". */
#ifndef SESSILE_LOCATE_H
#define SESSILE_LOCATE_H

#include <stdint.h>
#include "sessile/gpu/gpu.h"
#include "sessile/status.h"
#include "sessile/mesh/tetmesh.h"

#ifdef __cplusplus
extern "C" {
#endif

#define SESSILE_LOCATE_OUTSIDE 0xFFFFFFFFu
#define SESSILE_LOCATE_EPS 1e-10

typedef struct sessile_locator sessile_locator;

/* Bins the tets of m.  bins_per_tet: grid cells per tet (0 = default 1; more
 * cells, shorter lists).  The locator keeps a pointer to m: m must outlive
 * it and stay unchanged. */
sessile_status sessile_locator_build(const sessile_tetmesh *m, double bins_per_tet,
                                     sessile_locator **out);
void sessile_locator_destroy(sessile_locator *l);

/* The tet holding p and its barycentric weights w (w[q] belongs to node
 * tet[4t+q]), or SESSILE_LOCATE_OUTSIDE (w untouched). */
uint32_t sessile_locator_find(const sessile_locator *l, const double p[3], double w[4]);

/* The P1 interpolant of the nodal field at p, or outside_value. */
double sessile_locator_interpolate(const sessile_locator *l, const double *field, const double p[3],
                                   double outside_value);

/* The grid, for uploads and statistics. */
typedef struct sessile_locator_grid {
  double lo[3], inv_h[3]; /* bin (i,j,k) covers lo + [i, i+1) / inv_h ... */
  uint32_t dims[3];
  uint32_t nbins, nentries;     /* cell_off has nbins + 1 entries, cell_tet nentries */
  const uint32_t *cell_off, *cell_tet;
  double mean_per_bin;          /* nentries / nbins */
  uint32_t max_per_bin;
} sessile_locator_grid;
void sessile_locator_grid_of(const sessile_locator *l, sessile_locator_grid *g);

/* --- on the GPU ---------------------------------------------------------- */
typedef struct sessile_locate_gpu sessile_locate_gpu;
/* Uploads the mesh (nodes in the context precision, tets) and the grid. */
sessile_status sessile_locate_gpu_create(sessile_gpu *gpu, const sessile_locator *l,
                                         sessile_locate_gpu **out);
void sessile_locate_gpu_destroy(sessile_locate_gpu *lg);
/* Records the kernel into c: for each of the n points (3 n reals in the
 * context precision), the holding tet into tets (n uint32, or
 * SESSILE_LOCATE_OUTSIDE) and the interpolated field (nnodes reals) into
 * values (n reals; outside_value where outside).  outside_value sits in the
 * locator's one parameter slot: the last recorded value applies to every
 * recording of lg. */
sessile_status sessile_locate_gpu_record(sessile_locate_gpu *lg, sessile_cmd *c, sessile_buffer *points,
                                         uint32_t n, sessile_buffer *field, sessile_buffer *values,
                                         sessile_buffer *tets, double outside_value);

#ifdef __cplusplus
}
#endif
#endif
