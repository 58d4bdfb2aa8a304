/* sessile io — what a mesh file says about itself (sessile_mesh_info): the
 * header lines shared by the PLY and OBJ writers, and a PLY's vertex colours
 * from its main scalar (docs/io.md, "Mesh headers"). */
#include <math.h>
#include <stdlib.h>
#include "io_internal.h"
#include "sessile/io/colormap.h"
#include "sessile/io/mesh_colors.h"

static int one_line(const char *s) { return !s || !strpbrk(s, "\r\n"); }

sessile_status io_mesh_info_check(const char *path, const sessile_mesh_info *info, int nfields,
                                  const char *const *names, int *main_field) {
  *main_field = -1;
  if (!info) return SESSILE_OK;
  const char *s[] = {info->generator, info->version, info->commit, info->seed, info->length_unit,
                     info->time_unit, info->state, info->color_by, info->colormap};
  for (size_t k = 0; k < sizeof s / sizeof s[0]; k++)
    SESSILE_CHECK(one_line(s[k]), SESSILE_ERR_USAGE, "cannot write '%s': a header text holds a line break", path);
  SESSILE_CHECK(!info->time_unit || isfinite(info->time), SESSILE_ERR_USAGE,
                "cannot write '%s': the time is not finite (%g)", path, info->time);
  SESSILE_CHECK(!info->colormap || sessile_colormap_known(info->colormap), SESSILE_ERR_USAGE,
                "cannot write '%s': unknown colour map '%s' (maps: %s)", path, info->colormap,
                sessile_colormap_names());
  if (!info->color_by) return SESSILE_OK;
  for (int p = 0; p < nfields; p++)
    if (!strcmp(names[p], info->color_by)) *main_field = p;
  SESSILE_CHECK(*main_field >= 0, SESSILE_ERR_USAGE, "cannot write '%s': the main scalar '%s' is none of its fields",
                path, info->color_by);
  return SESSILE_OK;
}

sessile_status io_mesh_info_lines(sessile_atomic_file *af, const char *lead, const sessile_mesh_info *info) {
  if (!info) return SESSILE_OK;
  sessile_status st = SESSILE_OK;
  if (info->generator) st = io_printf(af, "%s generator %s\n", lead, info->generator);
  if (st == SESSILE_OK && info->version)
    st = io_printf(af, "%s version %s commit %s\n", lead, info->version, info->commit ? info->commit : "unknown");
  if (st == SESSILE_OK && info->seed) st = io_printf(af, "%s seed %s\n", lead, info->seed);
  if (st == SESSILE_OK && (info->length_unit || info->time_unit))
    st = io_printf(af, "%s units length %s time %s\n", lead, info->length_unit ? info->length_unit : "unknown",
                   info->time_unit ? info->time_unit : "none");
  if (st == SESSILE_OK && info->time_unit) st = io_printf(af, "%s time %.17g\n", lead, info->time);
  if (st == SESSILE_OK && info->iteration >= 0) st = io_printf(af, "%s iteration %d\n", lead, info->iteration);
  if (st == SESSILE_OK && info->state) st = io_printf(af, "%s state %s\n", lead, info->state);
  return st;
}

sessile_status io_mesh_rgb(const char *path, int nparts, const sessile_mesh_part *parts, uint32_t tv, int field,
                           const char *map, uint8_t **rgb, io_mesh_rgb_used *used) {
  /* the values as the file holds them (float), so that a reader of the PLY
   * finds the same range and colours */
  float *v = malloc(((size_t)tv + 1) * sizeof *v);
  *rgb = malloc((size_t)tv * 3 + 1);
  if (!v || !*rgb) {
    free(v), free(*rgb), *rgb = NULL;
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of memory colouring '%s' (%u vertices)", path, tv);
  }
  size_t k = 0;
  for (int p = 0; p < nparts; p++)
    for (uint32_t i = 0; i < parts[p].nv; i++) v[k++] = (float)parts[p].fields[field][i];
  used->map = sessile_mesh_colors_range(v, tv, map, &used->lo, &used->hi);
  for (size_t i = 0; i < tv; i++) sessile_mesh_color(used->map, used->lo, used->hi, v[i], *rgb + 3 * i);
  free(v);
  return SESSILE_OK;
}
