/* sessile — pictures of meshes, drawn offscreen through Vulkan (docs/render.md).
 *
 * A mesh (PLY ascii or binary, OBJ, anything sessile writes and the user's
 * own) is read into a sessile_render_mesh; a renderer uploads it once and
 * draws any number of frames (views, turntable angles) into RGBA8 pixels:
 * smooth Lambert shading with a key and a fill light from per-vertex
 * normals (area-weighted when the file has none), optional colouring by a
 * per-vertex property through a colour map, a ground grid in cm, a camera
 * fitted to the bounds, multisampling.  Same input, same device: same pixels.
 *
 * Ownership: a mesh owns its arrays; a renderer keeps no pointer into the
 * mesh after create.  destroy(NULL) is a no-op. */
#ifndef SESSILE_RENDER_MESH_H
#define SESSILE_RENDER_MESH_H
#include <stddef.h>
#include <stdint.h>
#include "sessile/gpu/gpu.h"

#ifdef __cplusplus
extern "C" {
#endif

/* --- meshes -------------------------------------------------------------------- */
typedef struct sessile_render_mesh {
  uint32_t nv, nf;
  float *pos;         /* 3 nv, in the file's unit */
  float *normal;      /* 3 nv unit normals (from the file, or computed) */
  uint32_t *tri;      /* 3 nf (polygons are split into fans) */
  int has_file_normals; /* 1 when nx, ny, nz came from the file */
  int nprops;         /* per-vertex scalar properties other than x y z nx ny nz */
  char **prop_names;
  float **props;      /* props[p][v] */
} sessile_render_mesh;

/* Reads FILE.ply (ascii, binary little- or big-endian; a vertex element
 * with x y z and any scalar properties, a face element with a vertex_indices
 * or vertex_index list) or FILE.obj (v and f lines; f with v, v/t, v//n or
 * v/t/n and negative indices).  Refused as SESSILE_ERR_USAGE with one line
 * naming the file: a missing or unreadable file, an unknown extension, a
 * malformed header or body, a count larger than the file can hold,
 * non-finite coordinates, an index out of range, an empty mesh (no vertex
 * or no face).  Normals: the file's when it has nx ny nz, else the
 * area-weighted mean of the adjacent faces' normals. */
sessile_status sessile_render_mesh_read(const char *path, sessile_render_mesh **out);
/* The same from arrays (copied): pos 3 nv, tri 3 nf; normals computed.
 * The same checks as the reader. */
sessile_status sessile_render_mesh_from_arrays(const double *pos, uint32_t nv, const uint32_t *tri,
                                               uint32_t nf, sessile_render_mesh **out);
void sessile_render_mesh_destroy(sessile_render_mesh *m);
/* The values of property `name`, or NULL. */
const float *sessile_render_mesh_property(const sessile_render_mesh *m, const char *name);

/* --- lights (camera space: x right, y up, z toward the viewer) ------------------ */
/* shade = AMBIENT + KEY_W max(0, n.key) + FILL_W max(0, n.fill), pixel =
 * min(colour shade, 1) written to a UNORM attachment (no sRGB encoding), with
 * n the unit normal turned toward the camera.  The lights move with the
 * camera, so every view and turntable frame is lit alike. */
#define SESSILE_RENDER_AMBIENT 0.15
#define SESSILE_RENDER_KEY_W 0.75
#define SESSILE_RENDER_FILL_W 0.30
/* key: from the upper left, in front; fill: from the right, a little below
 * (unit vectors = these / their length). */
#define SESSILE_RENDER_KEY_DIR {-1.0, 1.0, 1.5}
#define SESSILE_RENDER_FILL_DIR {1.0, -0.3, 1.0}
/* The colour of a mesh not coloured by a property (sRGB bytes). */
#define SESSILE_RENDER_BASE_COLOR {222, 196, 150}

/* --- rendering ----------------------------------------------------------------- */
typedef struct sessile_render_options {
  uint32_t width, height;   /* pixels, 1..16384 (and the device's limit) */
  uint32_t samples;         /* 1, 4 or 8 (as the device allows) */
  const char *view;         /* "oblique" (default), "side", "top", "front" */
  int ortho;                /* 1: orthographic camera (tests); 0: perspective */
  unsigned char background[4]; /* RGBA; default white, opaque */
  int grid;                 /* 1: the ground grid below the mesh (default) */
  const char *color_by;     /* a per-vertex property, or NULL: one colour */
  const char *colormap;     /* NULL: viridis, or coolwarm for a range across 0 */
  double units_cm;          /* cm per mesh unit (> 0; sessile writes cm: 1) */
} sessile_render_options;

/* Fills the defaults above (1280x960, 4 samples, oblique, perspective,
 * white, grid, units 1). */
void sessile_render_options_default(sessile_render_options *o);
/* The names of the views, for messages: "oblique, side, top, front". */
const char *sessile_render_view_names(void);
/* Checks options against the mesh (size range, view, property, colour map,
 * units) without a device: SESSILE_ERR_USAGE with one line. */
sessile_status sessile_render_options_check(const sessile_render_options *o,
                                            const sessile_render_mesh *m);

typedef struct sessile_render_result {
  double grid_spacing_cm;   /* grid line spacing (1, 2 or 5 x 10^k cm); 0 without grid */
  double grid_min[2], grid_max[2]; /* the grid's x, y extent (cm) and its height z */
  double grid_z;
  double px_per_cm;         /* ortho: pixels per cm; perspective: at the bounds' centre */
  double clip_from_world[16]; /* column-major: clip = M (x, y, z, 1) with world in cm;
                               pixel x = (ndc.x + 1) w / 2, y = (ndc.y + 1) h / 2 (row 0 top) */
  double prop_min, prop_max; /* the colour range (when colouring) */
  char colormap[16];        /* the map used when colouring, else "" */
  double t_draw, t_readback; /* seconds of the last frame */
} sessile_render_result;

typedef struct sessile_mesh_renderer sessile_mesh_renderer;

/* Checks the options, refuses what cannot fit in device memory (with the
 * estimate), uploads the mesh and makes the target and pipelines.  upload
 * time goes to *t_upload when not NULL. */
sessile_status sessile_mesh_renderer_create(sessile_gpu *g, const sessile_render_mesh *m,
                                            const sessile_render_options *o,
                                            sessile_mesh_renderer **out, double *t_upload);
void sessile_mesh_renderer_destroy(sessile_mesh_renderer *r);
/* Draws one frame: the options' view turned by azimuth_deg about the
 * vertical (z) axis through the bounds' centre (turntable frames), into
 * rgba (width x height x 4 bytes, row 0 at the top).  res may be NULL. */
sessile_status sessile_mesh_renderer_draw(sessile_mesh_renderer *r, double azimuth_deg,
                                          unsigned char *rgba, sessile_render_result *res);

/* Device bytes a render would take (mesh buffers and images): for the
 * refusal message and the CLI's check. */
uint64_t sessile_render_bytes(const sessile_render_mesh *m, const sessile_render_options *o);

#ifdef __cplusplus
}
#endif
#endif
