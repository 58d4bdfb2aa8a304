/* A seabed from a heightfield image (docs/reef.md, "Seabed"): a 16-bit
 * greyscale PNG or a one-channel EXR, read by io's readers, one sample per
 * pixel over the scene's extent, z = base + height_scale * value.  The
 * image is the seabed seen from above: its top row is y = extent[1], its
 * left column x = 0. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include "reef/reef_internal.h"
#include "reef/reef_json.h"
#include "sessile/io/io_read.h"

enum { MAX_SIDE = 4097 }; /* as seabed.noise.resolution */

static int ends_with(const char *s, const char *tail) {
  size_t n = strlen(s), k = strlen(tail);
  return n > k && !strcasecmp(s + n - k, tail);
}

sessile_status reef_seabed_image(const rj_obj *o, sessile_reef_scene *s) {
  char *path = NULL;
  SESSILE_CALL(rj_known(o, (const char *const[]){"path", "extent", "height_scale", "base", NULL}));
  SESSILE_CALL(rj_nums(o, "extent", 1, 2, 1e-3, 1e6, s->extent));
  s->height_scale = 1, s->base = 0;
  SESSILE_CALL(rj_num(o, "height_scale", 0, -1e6, 1e6, &s->height_scale));
  SESSILE_CALL(rj_num(o, "base", 0, -1e6, 1e6, &s->base));
  SESSILE_CALL(rj_str(o, "path", 1, &path));
  int png = ends_with(path, ".png"), exr = ends_with(path, ".exr");
  if (!png && !exr) {
    free(path);
    return rj_fail(o, "path", "must name a .png (16-bit greyscale) or an .exr (one channel)");
  }
  sessile_image_in im = {0};
  sessile_status st = png ? sessile_read_png_grey16(path, MAX_SIDE, &im) : sessile_read_exr_grey(path, MAX_SIDE, &im);
  free(path);
  if (st != SESSILE_OK) return sessile_error_pass(st, "%s: %s.path", o->where, o->path);
  s->res[0] = im.width, s->res[1] = im.height;
  s->heights = malloc((size_t)im.width * im.height * sizeof *s->heights);
  if (!s->heights) {
    sessile_image_in_free(&im);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for the seabed");
  }
  /* sample (i, j) at (i dx, j dy) is pixel (i, height - 1 - j) */
  for (uint32_t j = 0; j < im.height; j++)
    for (uint32_t i = 0; i < im.width; i++)
      s->heights[(size_t)j * im.width + i] = s->base + s->height_scale * im.v[(size_t)(im.height - 1 - j) * im.width + i];
  sessile_image_in_free(&im);
  return SESSILE_OK;
}
