/* A surface written as a file of the run, with its vertex normals: the
 * write every surface generator's snapshots share (sessile/run/generator.h). */
#include <stdlib.h>
#include <string.h>
#include "sessile/run/generator.h"
#include "sessile/io/io.h"

sessile_status sessile_run_write_surface(sessile_run *run, const char *rel, const sessile_surface *s, int nextra,
                                         const char *const *names, const double *const *extra) {
  char path[4096];
  double *n = malloc(((size_t)s->nv + 1) * 3 * sizeof *n);
  SESSILE_CHECK(n, SESSILE_ERR_NO_MEMORY, "out of host memory for the normals of '%s' (%u vertices)", rel, s->nv);
  sessile_surface_normals(s, n);
  size_t l = strlen(rel);
  sessile_mesh_info info;
  sessile_run_mesh_info(run, &info);
  sessile_status st;
  if (l > 4 && !strcmp(rel + l - 4, ".obj")) {
    st = sessile_run_file(run, rel, path, sizeof path);
    if (st == SESSILE_OK) st = sessile_write_obj_info(path, s, n, &info, NULL);
  } else {
    sessile_mesh_part part = {"surface", s->pos, s->nv, s->tri, s->nf, n, extra};
    st = sessile_run_write_mesh(run, rel, 1, &part, nextra, names, &info, NULL);
  }
  free(n);
  return st;
}
