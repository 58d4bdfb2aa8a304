/* Shared by host/render/mesh_*.c (not public API). */
#ifndef SESSILE_RENDER_MESH_INTERNAL_H
#define SESSILE_RENDER_MESH_INTERNAL_H
#include <stddef.h>
#include <stdint.h>
#include "sessile/gpu/graphics.h"
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

/* One vertex as the pipelines read it (28 bytes). */
typedef struct vtx {
  float p[3], n[3];
  unsigned char c[4];
} vtx;
_Static_assert(sizeof(vtx) == 28, "vertex layout");

/* shaders/render/mesh_push.glsl */
typedef struct mesh_push {
  float mvp[16];
  float key[4], fill[4], eye[4], params[4];
} mesh_push;
_Static_assert(sizeof(mesh_push) == 128, "push layout");

/* One instance of a scene as shaders/render/scene.vert reads it (68 bytes):
 * the transform to cm (columns) and the base colour. */
typedef struct render_inst {
  float m[16];
  unsigned char c[4];
} render_inst;
_Static_assert(sizeof(render_inst) == 68, "instance layout");

/* A scene's part drawn with its instances (one instanced draw). */
typedef struct render_group {
  uint32_t first_index, count, first_instance, ninstances;
} render_group;

/* A mesh renderer (mesh_render.c) or a scene's (scene_render.c): a scene
 * has groups and tris is its instanced pipeline. */
struct sessile_mesh_renderer {
  sessile_gpu *gpu;
  sessile_gfx_target *target;
  sessile_gfx_pipeline *tris, *lines;
  sessile_gfx_buffer *vbuf, *ibuf, *gbuf, *instbuf;
  uint32_t nindex, ngrid;
  render_group *groups;
  uint32_t ngroups;
  float *fit;    /* the vertices (cm; a scene's transformed) and then the grid's 4 corners: what the camera frames */
  size_t nfit;
  sessile_render_options o;
  char view[16];
  double lo[3], hi[3];     /* mesh (scene) bounds, cm */
  double glo[3], ghi[3];   /* grid box, cm */
  double spacing;
  double prop_min, prop_max;
  char colormap[16]; /* the map used, "" without colouring */
};

/* The grid below the bounds lo..hi (needs fit's last 4 points free). */
sessile_status render_grid_build_(sessile_mesh_renderer *r);
/* Refuses a render over the device's memory (need bytes), then makes the
 * target and the pipelines: tris (instanced with scene.vert when instanced)
 * and lines. */
sessile_status render_target_make_(sessile_mesh_renderer *r, uint64_t need, uint32_t nv, uint32_t nf,
                                  int instanced);

#endif
