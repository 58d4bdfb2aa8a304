/* A surface written as a file of the run, with its vertex normals: the
 * write every surface generator's snapshots share (sessile/run/generator.h),
 * and the run's OBJ files in the run's OBJ style with their .mtl. */
#include <ctype.h>
#include <stdlib.h>
#include <string.h>
#include "run_internal.h"
#include "sessile/run/generator.h"
#include "sessile/io/io.h"

void sessile_run_set_obj_style(sessile_run *r, sessile_obj_axes axes, const char *material, const float rgb[3]) {
  if (!r) return;
  r->obj_axes = axes;
  size_t n = 0;
  for (; material && material[n] && n + 1 < sizeof r->obj_material; n++) {
    unsigned char c = (unsigned char)material[n];
    r->obj_material[n] = isalnum(c) || c == '-' || c == '_' ? (char)c : '_'; /* one MTL token */
  }
  r->obj_material[n] = 0;
  for (int k = 0; k < 3; k++) r->obj_rgb[k] = rgb ? rgb[k] : 0.7f;
}

sessile_status sessile_run_write_obj(sessile_run *run, const char *rel, const sessile_surface *s, const double *normals,
                                     const sessile_mesh_info *info, const volatile sig_atomic_t *stop) {
  size_t l = strlen(rel);
  SESSILE_CHECK(l > 4 && l < 250 && !strcmp(rel + l - 4, ".obj"), SESSILE_ERR_INTERNAL, "'%s' is not an OBJ file name",
                rel);
  char mrel[256], path[4096];
  snprintf(mrel, sizeof mrel, "%.*s.mtl", (int)(l - 4), rel);
  const char *base = strrchr(mrel, '/');
  base = base ? base + 1 : mrel; /* mtllib names a file beside the OBJ */
  static const float grey[3] = {0.7f, 0.7f, 0.7f};
  const char *material = run->obj_material[0] ? run->obj_material : "sessile";
  SESSILE_CALL(sessile_run_file(run, mrel, path, sizeof path));
  SESSILE_CALL(sessile_write_mtl(path, material, run->obj_material[0] ? run->obj_rgb : grey));
  SESSILE_CALL(sessile_run_file(run, rel, path, sizeof path));
  sessile_obj_style st = {run->obj_axes, base, material};
  sessile_mesh_info own;
  if (!info) sessile_run_mesh_info(run, &own), info = &own;
  return sessile_write_obj_info(path, s, normals, &st, info, stop);
}

sessile_status sessile_run_write_surface(sessile_run *run, const char *rel, const sessile_surface *s, int nextra,
                                         const char *const *names, const double *const *extra) {
  double *n = malloc(((size_t)s->nv + 1) * 3 * sizeof *n);
  SESSILE_CHECK(n, SESSILE_ERR_NO_MEMORY, "out of host memory for the normals of '%s' (%u vertices)", rel, s->nv);
  sessile_surface_normals(s, n);
  size_t l = strlen(rel);
  sessile_mesh_info info;
  sessile_run_mesh_info(run, &info);
  sessile_status st;
  if (l > 4 && !strcmp(rel + l - 4, ".obj")) {
    st = sessile_run_write_obj(run, rel, s, n, &info, NULL);
  } else {
    sessile_mesh_part part = {"surface", s->pos, s->nv, s->tri, s->nf, n, extra};
    st = sessile_run_write_mesh(run, rel, 1, &part, nextra, names, &info, NULL);
  }
  free(n);
  return st;
}
