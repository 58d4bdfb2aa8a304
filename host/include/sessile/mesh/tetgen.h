/* sessile — the conforming water domain: TetGen's quality tetrahedral mesh
 * of the box minus the sponge (the sponge is a hole; docs/conforming.md).
 *
 * The sponge may lie on box faces: its triangles with all three vertices on
 * one box face (the flat base on the substratum that the growth loop makes)
 * are not water boundary; that face's facet is the box face with the
 * footprint cut out.  A sponge vertex on two box faces (a box edge) or
 * outside the box is rejected.  The mesh is graded: the target edge length
 * is the sponge's local edge length at its vertices and size_far at the box
 * corners, interpolated in between (TetGen -m). */
#ifndef SESSILE_TETGEN_H
#define SESSILE_TETGEN_H

#include <stddef.h>
#include <stdint.h>
#include "sessile/mesh/box.h"
#include "sessile/status.h"
#include "sessile/mesh/surface.h"
#include "sessile/mesh/tetmesh.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sessile_tetgen_options {
  /* -q: largest radius-edge ratio of a tet (default 1.5; TetGen's own default
   * is 2.0; smaller is better shaped and needs more nodes; 0 turns quality
   * refinement, and with it the sizing field, off). */
  double radius_edge;
  /* -a: largest tet volume in cm^3 (default 0 = no limit; the sizing field
   * already bounds the size). */
  double max_volume;
  /* Target edge length at the sponge's vertices, cm; 0 (default) = the mean
   * length of each vertex's incident sponge edges. */
  double size_sponge;
  /* Target edge length at the box corners, cm; 0 (default) = 4 box cells
   * (4 box.h: 2.4 cm for the default box). */
  double size_far;
  /* 1: TetGen adds no Steiner points on the boundary (-Y), so the boundary
   * faces are exactly the sponge's triangles and the box faces' CDT (default
   * 0: large box faces then stay coarse). */
  int preserve_surface;
  /* 1: TetGen prints its progress (-V); default 0 (-Q, quiet). */
  int verbose;
} sessile_tetgen_options;

void sessile_tetgen_options_default(sessile_tetgen_options *o);

/* Meshes the box minus the sponge.  out receives nodes (the PLC's points
 * first: the 8 box corners, then the sponge vertices that are water boundary
 * in their surface order; then TetGen's Steiner points), positively oriented
 * tets, boundary faces oriented outward from the water with one tag each
 * (INLET, OUTLET, SUBSTRATUM, SIDE, TOP, SPONGE) and node tags.
 * opt NULL = defaults.  Errors: SESSILE_ERR_USAGE for a sponge vertex outside
 * the box or on a box edge, SESSILE_ERR_NUMERIC with TetGen's reason when it
 * rejects the input geometry (self-intersecting surface, too small features,
 * facets too close, invalid PLC): only these two describe the input;
 * SESSILE_ERR_NO_MEMORY when TetGen or the conversion runs out of memory
 * (std::bad_alloc included), SESSILE_ERR_INTERNAL for TetGen's internal
 * errors and any other failure.  out is empty on failure. */
sessile_status sessile_tetgen_conforming(const sessile_box *box, const sessile_surface *sponge,
                                         const sessile_tetgen_options *opt, sessile_tetmesh *out);

/* TetGen's mesh of the inside of a closed triangulated surface (the SDS
 * import and its topology repairs): points first (zero-based), then any
 * Steiner points TetGen added; tets as TetGen orients them.  The struct owns
 * its malloc'd arrays (sessile_tetgen_mesh_free; a zeroed one is empty). */
typedef struct sessile_tetgen_mesh {
  int npoints, ntets;
  double *xyz; /* 3 npoints */
  int *tet;    /* 4 ntets */
} sessile_tetgen_mesh;

/* Meshes the PLC whose facets are the ntri triangles tri (one polygon each,
 * marker 1, no holes) over the npoints points xyz, with TetGen's switches as
 * given (e.g. "pYzQ": a PLC, no Steiner point on the facets, zero-based,
 * quiet).  msg receives TetGen's reason on failure.  SESSILE_ERR_NO_MEMORY
 * when TetGen or the copy ran out of memory, SESSILE_ERR_NUMERIC for any
 * other failure (the input rejected, TetGen's internal errors, a crash of
 * its process); out is empty then. */
sessile_status sessile_tetgen_surface(const double *xyz, int npoints, const uint32_t *tri, int ntri,
                                      const char *switches, sessile_tetgen_mesh *out, char *msg,
                                      size_t msglen);
void sessile_tetgen_mesh_free(sessile_tetgen_mesh *m);

#ifdef __cplusplus
}
#endif
#endif
