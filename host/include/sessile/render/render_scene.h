/* sessile — scenes for the mesh renderer (docs/render.md, "Scenes"): parts
 * of one mesh, each drawn any number of times (instanced), every instance
 * with its own transform and flat base colour, lit as a single mesh.  The
 * reef's preview is one (docs/reef.md, "Output").
 *
 * On disk a scene is a JSON file beside a PLY of its parts (written by
 * sessile_render_scene_json's caller, read by sessile_render_scene_read):
 *
 *   {"format": "sessile render scene", "version": 1, "mesh": "meshes.ply",
 *    "parts": [[first_vertex, nv, first_face, nf], ...],
 *    "instances": [{"part": 0, "rgb": [r, g, b], "matrix": [16 numbers]}, ...]}
 *
 * "mesh" is relative to the JSON file's folder; "rgb" are sRGB bytes; the
 * matrix is column-major, from the part's units to the scene's (cm). */
#ifndef SESSILE_RENDER_SCENE_H
#define SESSILE_RENDER_SCENE_H
#include <stdint.h>
#include <cjson/cJSON.h>
#include "sessile/render/render_mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sessile_render_part {
  uint32_t first_vertex, nv; /* its vertices in the scene's mesh */
  uint32_t first_face, nf;   /* its triangles, which use only those vertices */
} sessile_render_part;

typedef struct sessile_render_instance {
  uint32_t part;
  unsigned char rgba[4]; /* base colour, sRGB bytes; drawn opaque */
  double matrix[16];     /* column-major affine transform, part units -> scene units */
} sessile_render_instance;

typedef struct sessile_render_scene {
  sessile_render_mesh *mesh; /* every part's vertices and triangles, one after the other */
  sessile_render_part *parts;
  uint32_t nparts;
  sessile_render_instance *inst;
  uint32_t ninst;
} sessile_render_scene;

/* Parts cover the mesh's ranges, a part's faces use only its vertices, an
 * instance names a part and its matrix is finite, affine and invertible;
 * at least one instance.  SESSILE_ERR_USAGE with one line naming `what`. */
sessile_status sessile_render_scene_check(const char *what, const sessile_render_scene *s);

/* Reads a scene file and its mesh (by sessile_render_mesh_read) and checks
 * it; SESSILE_ERR_USAGE with one line naming the file otherwise. */
sessile_status sessile_render_scene_read(const char *path, sessile_render_scene **out);
/* 1 when path names a scene file (it ends in .json), not a mesh. */
int sessile_render_is_scene(const char *path);
/* Frees everything, mesh included; NULL is a no-op. */
void sessile_render_scene_destroy(sessile_render_scene *s);

/* The scene file's JSON for a mesh file named mesh_file (relative to the
 * JSON's folder); NULL when out of memory. */
cJSON *sessile_render_scene_json(const char *mesh_file, const sessile_render_part *parts, uint32_t nparts,
                                 const sessile_render_instance *inst, uint32_t ninst);

/* A renderer of the scene (draw and destroy as a mesh's: render_mesh.h).
 * The options' color_by must be NULL (colours are the instances'); the
 * camera and the grid fit every instance's transformed vertices. */
sessile_status sessile_scene_renderer_create(sessile_gpu *g, const sessile_render_scene *s,
                                             const sessile_render_options *o, sessile_mesh_renderer **out,
                                             double *t_upload);

/* Linear-light [0, 1] to an sRGB byte (the sRGB transfer function), for
 * linear base colours such as glTF's. */
unsigned char sessile_render_srgb_byte(double linear);

#ifdef __cplusplus
}
#endif
#endif
