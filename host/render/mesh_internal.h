/* Shared by host/render/mesh_*.c (not public API). */
#ifndef SESSILE_RENDER_MESH_INTERNAL_H
#define SESSILE_RENDER_MESH_INTERNAL_H
#include <stddef.h>
#include <stdint.h>
#include "sessile/render/render_mesh.h"

/* Finite coordinates, indices in range, not empty; then normals (the
 * file's normalised, else area-weighted). */
sessile_status mesh_finish_(const char *what, sessile_render_mesh *m);
void mesh_bounds_(const sessile_render_mesh *m, double lo[3], double hi[3]);

/* --- camera (mesh_camera.c) ---------------------------------------------------- */
typedef struct render_camera {
  double eye[3], right[3], up[3], toward[3]; /* toward: unit vector from target to eye */
  double clip_from_world[16];                /* column-major */
  double px_per_cm;
  int ortho;
} render_camera;
/* 1 for a known view name.  Its azimuth and elevation in degrees. */
int render_view_angles_(const char *view, double *azimuth, double *elevation);
/* Fits a camera to the points pts (3 npts floats, cm: the mesh's vertices
 * and the grid's corners), seen from the view turned by extra_azimuth;
 * near and far planes enclose the box lo..hi of everything drawn. */
void render_camera_fit_(const char *view, double extra_azimuth, int ortho, uint32_t width,
                        uint32_t height, const float *pts, size_t npts, const double lo[3],
                        const double hi[3], render_camera *c);
/* Grid spacing for an extent of `span` cm: 1, 2 or 5 x 10^k, about 10 lines. */
double render_grid_spacing_(double span);

#endif
