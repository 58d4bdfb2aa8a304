/* sessile render — slices: the EXR reader and the outline, shared by slice.c. */
#ifndef SESSILE_SLICE_INTERNAL_H
#define SESSILE_SLICE_INTERNAL_H
#include <stddef.h>
#include "sessile/render/render2d.h"

/* One sessile EXR slice, read.  Pixel (i, j) is at world
 * origin + i su axis_u + j sv axis_v, and at in-plane (u0 + i su, v0 + j sv). */
typedef struct slice_image {
  int w, h;
  float *val;      /* the asked channel, val[i + w j] */
  float *aux;      /* the outline channel when one is used (else NULL) */
  double aux_level;
  char aux_name[64];
  double origin[3], axis_u[3], axis_v[3], normal[3];
  double su, sv, u0, v0;
  char uname[8], vname[8]; /* "x", "z", or "u", "v" for a general plane */
  char plane[128];
  int iteration;
} slice_image;

/* Reads `channel` (and the outline channel the options ask for, or a
 * solid/mask/phi/sdf channel when present).  Frees with slice_image_free. */
sessile_status slice_read(const char *path, const char *channel, const sessile_render2d_opts *o, slice_image *im);
void slice_image_free(slice_image *im);

/* Line segments (u, v pairs: 4 doubles each) in the plane's coordinates. */
typedef struct seg_list {
  double *p;
  size_t n, cap;
} seg_list;
void seg_list_free(seg_list *s);

/* Marching squares on the node grid at `level` (saddles resolved by the
 * cell's mean); NaN cells are skipped. */
sessile_status slice_contour(const slice_image *im, const float *f, double level, seg_list *out);
/* The intersection of a sessile PLY surface with the slice's plane. */
sessile_status slice_cut_ply(const slice_image *im, const char *ply_path, seg_list *out);
#endif
