/* sessile — a coral's skeleton: a list of segments (capsules with a radius at
 * each end) and the two ways to turn it into a surface (docs/coral.md):
 *   - tubes: one closed tube of `sides` sides per segment, oriented by the
 *     segment's rotation-minimising frame (Coralize's way; pieces overlap);
 *   - weld: one watertight surface for the whole coral, the zero level set of
 *     the skeleton's signed distance (capsules, smooth union of radius
 *     `blend`) sampled by a GPU kernel on a grid and polygonised on the GPU.
 * L-systems and venation both produce a skeleton; the geometry is shared
 * (host/mesh/skeleton*.c, host/mesh/weld*.c, shaders/mesh/weld*.comp). */
#ifndef SESSILE_SKELETON_H
#define SESSILE_SKELETON_H

#include <signal.h>
#include <stdint.h>
#include "sessile/gpu/gpu.h"
#include "sessile/status.h"
#include "sessile/mesh/surface.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sessile_skeleton {
  uint32_t n, cap; /* segments, allocated capacity */
  double *a, *b;   /* 3n: the segment's ends, cm */
  double *ra, *rb; /* n: radius at a and at b, cm (> 0) */
  double *up;      /* 3n: a unit vector normal to b - a, the frame's normal at a
                      (rotation-minimising along a branch, so tubes do not twist) */
  double *value;   /* n: a property carried to the mesh's vertices (thickness
                      index, branch order, ...) */
} sessile_skeleton;

void sessile_skeleton_free(sessile_skeleton *s);
/* Appends one segment (grows the arrays); up need not be normalised. */
sessile_status sessile_skeleton_add(sessile_skeleton *s, const double a[3], const double b[3], double ra,
                                    double rb, const double up[3], double value);
/* Axis-aligned bounds of the capsules (radii included). */
void sessile_skeleton_bounds(const sessile_skeleton *s, double lo[3], double hi[3]);

/* Tubes: per segment a ring of `sides` vertices at each end (oriented by up)
 * and a cap at each end, so every tube is a closed 2-manifold on its own;
 * vertex_value (nv doubles, caller frees; may be NULL) carries the segment's
 * value.  Host code: linear in segments. */
sessile_status sessile_skeleton_tubes(const sessile_skeleton *s, int sides, sessile_surface *out,
                                      double **vertex_value);
/* The same, ended with SESSILE_ERR_INTERRUPTED (out left to the caller to
 * free) once *stop (may be NULL) turns nonzero: looked at every 4096 tubes. */
sessile_status sessile_skeleton_tubes_stop(const sessile_skeleton *s, int sides, const volatile sig_atomic_t *stop,
                                           sessile_surface *out, double **vertex_value);

typedef struct sessile_weld_params {
  double cell;         /* grid spacing, cm; 0: from max_cells */
  uint32_t max_cells;  /* with cell == 0: cells along the bounds' longest axis */
  double blend;        /* smooth-union radius, cm (0: the plain union, min of distances) */
} sessile_weld_params;

/* The welded surface (GPU): a closed, consistently oriented 2-manifold
 * without self-intersection (possibly several components); vertex_value
 * (nv doubles, may be NULL) is the value of the nearest capsule.  Refuses a
 * grid that would not fit the device's memory, with the estimate. */
sessile_status sessile_skeleton_weld(sessile_gpu *g, const sessile_skeleton *s, const sessile_weld_params *p,
                                     sessile_surface *out, double **vertex_value);
/* The plain-C reference of the same algorithm (the same mesh to rounding). */
sessile_status sessile_skeleton_weld_ref(const sessile_skeleton *s, const sessile_weld_params *p,
                                         sessile_surface *out, double **vertex_value);

#ifdef __cplusplus
}
#endif
#endif
