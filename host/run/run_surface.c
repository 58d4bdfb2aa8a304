/* A surface written as a file of the run, with its vertex normals: the
 * write every surface generator's snapshots share (sessile/run/generator.h). */
#include <stdlib.h>
#include <string.h>
#include "sessile/run/generator.h"
#include "sessile/io/io.h"

sessile_status sessile_run_write_surface(sessile_run *run, const char *rel, const sessile_surface *s, int nextra,
                                         const char *const *names, const double *const *extra) {
  char path[4096];
  SESSILE_CALL(sessile_run_file(run, rel, path, sizeof path));
  double *n = malloc(((size_t)s->nv + 1) * 3 * sizeof *n);
  SESSILE_CHECK(n, SESSILE_ERR_NO_MEMORY, "out of host memory for the normals of '%s' (%u vertices)", rel, s->nv);
  sessile_surface_normals(s, n);
  size_t l = strlen(rel);
  sessile_status st = l > 4 && !strcmp(rel + l - 4, ".obj") ? sessile_write_obj(path, s, n)
                                                            : sessile_write_ply(path, s, n, nextra, names, extra);
  free(n);
  return st;
}
