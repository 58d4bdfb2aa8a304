/* sessile render — reads one of sessile's EXR slices (docs/io.md "Slices"):
 * part "slice", float channels, sessile:plane/origin/spacing/iteration and,
 * for a general plane, sessile:axis_u/axis_v.  Any other EXR is refused with
 * a message saying so, rather than drawn with made-up axes. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/io/io_read.h"
#include "slice_internal.h"

void slice_image_free(slice_image *im) {
  free(im->val);
  free(im->aux);
  im->val = im->aux = NULL;
}

/* The in-plane axes of a box slice "x=..", "y=..", "z=.." (exr_slice.c). */
static int box_axes(const char *plane, int *normal, int *u, int *v) {
  if (!plane || (plane[0] != 'x' && plane[0] != 'y' && plane[0] != 'z') || plane[1] != '=') return 0;
  *normal = plane[0] - 'x';
  *u = *normal == 0 ? 1 : 0;
  *v = *normal == 2 ? 1 : 2;
  return 1;
}

/* The outline channel: asked for, or a known name when present; -1 none. */
static sessile_status pick_outline(const sessile_exr_in *x, const sessile_render2d_opts *o, const char *path,
                                   const char *names, slice_image *im, int *aux) {
  *aux = -1;
  if (o && o->outline_ply && o->outline_ply[0]) return SESSILE_OK;
  if (o && o->outline_channel && o->outline_channel[0]) {
    *aux = sessile_exr_find_channel(x, o->outline_channel);
    SESSILE_CHECK(*aux >= 0, SESSILE_ERR_USAGE, "'%s' has no outline channel '%s' (channels: %s)", path,
                  o->outline_channel, names);
    im->aux_level = o->outline_level;
  } else {
    static const char *known[4] = {"solid", "mask", "phi", "sdf"};
    static const double level[4] = {0.5, 0.5, 0, 0};
    for (int k = 0; k < 4 && *aux < 0; k++)
      if ((*aux = sessile_exr_find_channel(x, known[k])) >= 0) im->aux_level = level[k];
  }
  if (*aux >= 0) snprintf(im->aux_name, sizeof im->aux_name, "%s", sessile_exr_channel_name(x, *aux));
  return SESSILE_OK;
}

/* The plane's geometry from the header into im. */
static sessile_status place(const sessile_slice_header *hd, const char *path, slice_image *im) {
  SESSILE_CHECK(hd->scanline, SESSILE_ERR_USAGE, "'%s' is not a sessile slice (one scanline part named 'slice' expected)",
                path);
  SESSILE_CHECK(hd->has_origin && hd->has_spacing, SESSILE_ERR_USAGE,
                "'%s' is not a sessile slice (no sessile:plane, sessile:origin or sessile:spacing)", path);
  snprintf(im->plane, sizeof im->plane, "%s", hd->plane);
  im->iteration = hd->iteration;
  /* the attributes are float: checked as such */
  float sx = (float)hd->spacing[0], sy = (float)hd->spacing[1];
  SESSILE_CHECK(sx > 0 && sy > 0 && isfinite(sx) && isfinite(sy), SESSILE_ERR_USAGE,
                "'%s': sessile:spacing (%g, %g) is not positive", path, sx, sy);
  im->su = sx, im->sv = sy;
  memcpy(im->origin, hd->origin, sizeof im->origin);
  int nu, u, v;
  if (hd->has_axes) {
    memcpy(im->axis_u, hd->axis_u, sizeof im->axis_u);
    memcpy(im->axis_v, hd->axis_v, sizeof im->axis_v);
    strcpy(im->uname, "u");
    strcpy(im->vname, "v");
    im->u0 = im->v0 = 0; /* distances from the plane's origin along its axes */
  } else if (box_axes(im->plane, &nu, &u, &v)) {
    im->axis_u[u] = 1;
    im->axis_v[v] = 1;
    snprintf(im->uname, sizeof im->uname, "%c", 'x' + u);
    snprintf(im->vname, sizeof im->vname, "%c", 'x' + v);
    im->u0 = im->origin[u], im->v0 = im->origin[v]; /* world coordinates along the two axes */
  } else {
    return sessile_error_set(SESSILE_ERR_USAGE, "'%s' is not a sessile slice (plane '%s' without sessile:axis_u/axis_v)",
                             path, im->plane);
  }
  im->normal[0] = im->axis_u[1] * im->axis_v[2] - im->axis_u[2] * im->axis_v[1];
  im->normal[1] = im->axis_u[2] * im->axis_v[0] - im->axis_u[0] * im->axis_v[2];
  im->normal[2] = im->axis_u[0] * im->axis_v[1] - im->axis_u[1] * im->axis_v[0];
  return SESSILE_OK;
}

static sessile_status read_open(sessile_exr_in *x, const char *path, const char *channel,
                                const sessile_render2d_opts *o, slice_image *im) {
  const sessile_slice_header *hd = sessile_exr_header(x);
  SESSILE_CALL(place(hd, path, im));
  char names[1024];
  sessile_exr_channel_list(x, names, sizeof names);
  int want = sessile_exr_find_channel(x, channel), aux;
  SESSILE_CHECK(want >= 0, SESSILE_ERR_USAGE, "'%s' has no channel '%s' (channels: %s)", path, channel, names);
  SESSILE_CALL(pick_outline(x, o, path, names, im, &aux));
  int64_t w = hd->width, h = hd->height;
  SESSILE_CHECK(!(w < 1 || h < 1 || w > 65536 || h > 65536 || w * h > (1ll << 28)), SESSILE_ERR_USAGE,
                "'%s': a slice of %lld x %lld pixels is outside what sessile renders (65536 a side, 2^28 in all)",
                path, (long long)w, (long long)h);
  im->w = (int)w, im->h = (int)h;
  im->val = malloc((size_t)w * h * sizeof(float));
  if (aux >= 0) im->aux = malloc((size_t)w * h * sizeof(float));
  SESSILE_CHECK(im->val && (aux < 0 || im->aux), SESSILE_ERR_NO_MEMORY, "out of memory reading '%s' (%.0f MB)", path,
                8.0 * w * h / 1e6);
  const char *which[2] = {channel, aux >= 0 ? sessile_exr_channel_name(x, aux) : NULL};
  float *const dst[2] = {im->val, im->aux};
  return sessile_exr_read_channels(x, aux >= 0 ? 2 : 1, which, dst);
}

sessile_status slice_read(const char *path, const char *channel, const sessile_render2d_opts *o, slice_image *im) {
  memset(im, 0, sizeof *im);
  SESSILE_CHECK(path && path[0], SESSILE_ERR_USAGE, "no slice file given");
  SESSILE_CHECK(channel && channel[0], SESSILE_ERR_USAGE, "no channel given for '%s'", path);
  sessile_exr_in *x = NULL;
  SESSILE_CALL(sessile_exr_open(path, &x));
  sessile_status st = read_open(x, path, channel, o, im);
  sessile_exr_close(x);
  if (st != SESSILE_OK) slice_image_free(im);
  return st;
}

sessile_status sessile_render_slice_channels(const char *path, char *names, size_t n) {
  SESSILE_CHECK(names && n > 0, SESSILE_ERR_INTERNAL, "no room for the channel names");
  names[0] = 0;
  sessile_exr_in *x = NULL;
  SESSILE_CALL(sessile_exr_open(path, &x));
  sessile_status st = sessile_exr_header(x)->nchannels >= 1
                          ? SESSILE_OK
                          : sessile_error_set(SESSILE_ERR_USAGE, "'%s' has no channel", path);
  if (st == SESSILE_OK) sessile_exr_channel_list(x, names, n);
  sessile_exr_close(x);
  return st;
}
